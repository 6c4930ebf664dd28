"""Deprecated: moved to :mod:`drake_grasp.sweeps.fingerprint` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.sweeps import fingerprint as _moved

warnings.warn("drake_grasp.experiments.fingerprint is deprecated: use drake_grasp.sweeps.fingerprint", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
