"""Deprecated: moved to :mod:`drake_grasp.sweeps.runner` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.sweeps import runner as _moved

warnings.warn("drake_grasp.experiments.runner is deprecated: use drake_grasp.sweeps.runner", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
