"""Deprecated: moved to :mod:`drake_grasp.studies.calibration` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import calibration as _moved

warnings.warn("drake_grasp.experiments.calibration is deprecated: use drake_grasp.studies.calibration", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
