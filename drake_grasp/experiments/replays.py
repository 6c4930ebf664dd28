"""Deprecated: moved to :mod:`drake_grasp.studies.replays` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import replays as _moved

warnings.warn("drake_grasp.experiments.replays is deprecated: use drake_grasp.studies.replays", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
