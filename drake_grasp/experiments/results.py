"""Deprecated: moved to :mod:`drake_grasp.sweeps.results` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.sweeps import results as _moved

warnings.warn("drake_grasp.experiments.results is deprecated: use drake_grasp.sweeps.results", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
