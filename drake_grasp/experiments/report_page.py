"""Deprecated: moved to :mod:`drake_grasp.studies.report_page` (this path works for one release, with a DeprecationWarning)."""

import sys
import warnings

from drake_grasp.studies import report_page as _moved

warnings.warn("drake_grasp.experiments.report_page is deprecated: use drake_grasp.studies.report_page", DeprecationWarning, stacklevel=2)
sys.modules[__name__] = _moved
