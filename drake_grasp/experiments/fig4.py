"""Deprecated: moved to :mod:`drake_grasp.studies.fig4` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import fig4 as _moved

warnings.warn("drake_grasp.experiments.fig4 is deprecated: use drake_grasp.studies.fig4", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
