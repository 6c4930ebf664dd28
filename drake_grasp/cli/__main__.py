"""`python -m drake_grasp.cli`: the `drake-grasp` command."""

import sys

from drake_grasp.cli import main

sys.exit(main())
