"""Deprecated: moved to :mod:`drake_grasp.sweeps.stats` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.sweeps import stats as _moved

warnings.warn("drake_grasp.experiments.stats is deprecated: use drake_grasp.sweeps.stats", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
