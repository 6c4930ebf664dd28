"""Deprecated: moved to :mod:`drake_grasp.objects.near_primitives` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.objects import near_primitives as _moved

warnings.warn("drake_grasp.geometry.near_primitives is deprecated: use drake_grasp.objects.near_primitives", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
