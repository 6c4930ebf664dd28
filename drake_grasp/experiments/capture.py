"""Deprecated: moved to :mod:`drake_grasp.studies.capture` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import capture as _moved

warnings.warn("drake_grasp.experiments.capture is deprecated: use drake_grasp.studies.capture", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
