"""Deprecated: moved to :mod:`drake_grasp.objects.piece_budget` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.objects import piece_budget as _moved

warnings.warn("drake_grasp.piece_budget is deprecated: use drake_grasp.objects.piece_budget", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
