"""Deprecated: moved to :mod:`drake_grasp.studies.epsilon_physics` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import epsilon_physics as _moved

warnings.warn("drake_grasp.experiments.epsilon_physics is deprecated: use drake_grasp.studies.epsilon_physics", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
