"""Deprecated: moved to :mod:`drake_grasp.sweeps.executors` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.sweeps import executors as _moved

warnings.warn("drake_grasp.experiments.executors is deprecated: use drake_grasp.sweeps.executors", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
