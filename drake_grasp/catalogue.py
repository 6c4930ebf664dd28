"""Deprecated: moved to :mod:`drake_grasp.objects.catalogue` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.objects import catalogue as _moved

warnings.warn("drake_grasp.catalogue is deprecated: use drake_grasp.objects.catalogue", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
