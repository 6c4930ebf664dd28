"""Deprecated: moved to :mod:`drake_grasp.studies.sensitivity` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import sensitivity as _moved

warnings.warn("drake_grasp.experiments.sensitivity is deprecated: use drake_grasp.studies.sensitivity", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
