"""Deprecated: moved to :mod:`drake_grasp.studies.near_primitives` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import near_primitives as _moved

warnings.warn("drake_grasp.experiments.near_primitives is deprecated: use drake_grasp.studies.near_primitives", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
