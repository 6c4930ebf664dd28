"""Deprecated: moved to :mod:`drake_grasp.objects.solid` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.objects import solid as _moved

warnings.warn("drake_grasp.geometry.solid is deprecated: use drake_grasp.objects.solid", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
