"""Deprecated: moved to :mod:`drake_grasp.studies.capture_region` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import capture_region as _moved

warnings.warn("drake_grasp.experiments.capture_region is deprecated: use drake_grasp.studies.capture_region", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
