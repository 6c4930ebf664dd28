"""Deprecated: moved to :mod:`drake_grasp.studies.fig6` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import fig6 as _moved

warnings.warn("drake_grasp.experiments.fig6 is deprecated: use drake_grasp.studies.fig6", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
