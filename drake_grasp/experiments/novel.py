"""Deprecated: moved to :mod:`drake_grasp.studies.novel` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import novel as _moved

warnings.warn("drake_grasp.experiments.novel is deprecated: use drake_grasp.studies.novel", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
