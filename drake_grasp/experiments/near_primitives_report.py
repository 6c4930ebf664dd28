"""Deprecated: moved to :mod:`drake_grasp.studies.near_primitives_report` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import near_primitives_report as _moved

warnings.warn("drake_grasp.experiments.near_primitives_report is deprecated: use drake_grasp.studies.near_primitives_report", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
