"""Deprecated: moved to :mod:`drake_grasp.studies.reproduce` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import reproduce as _moved

warnings.warn("drake_grasp.experiments.reproduce is deprecated: use drake_grasp.studies.reproduce", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
