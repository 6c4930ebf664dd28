"""Deprecated: moved to :mod:`drake_grasp.objects.novel` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.objects import novel as _moved

warnings.warn("drake_grasp.geometry.novel is deprecated: use drake_grasp.objects.novel", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
