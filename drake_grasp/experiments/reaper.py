"""Deprecated: moved to :mod:`drake_grasp.sweeps.reaper` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.sweeps import reaper as _moved

warnings.warn("drake_grasp.experiments.reaper is deprecated: use drake_grasp.sweeps.reaper", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
