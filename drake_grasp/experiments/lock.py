"""Deprecated: moved to :mod:`drake_grasp.sweeps.lock` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.sweeps import lock as _moved

warnings.warn("drake_grasp.experiments.lock is deprecated: use drake_grasp.sweeps.lock", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
