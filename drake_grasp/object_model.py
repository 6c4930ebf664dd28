"""Deprecated: moved to :mod:`drake_grasp.objects.drake_model` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.objects import drake_model as _moved

warnings.warn("drake_grasp.object_model is deprecated: use drake_grasp.objects.drake_model", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
