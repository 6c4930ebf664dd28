"""Deprecated: moved to :mod:`drake_grasp.objects.cleaning` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.objects import cleaning as _moved

warnings.warn("drake_grasp.geometry.cleaning is deprecated: use drake_grasp.objects.cleaning", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
