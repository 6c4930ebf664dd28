#!/usr/bin/env python3
"""The sensitivity sweep: `drake-grasp sensitivity` under its earlier script name.

    .venv/bin/python scripts/sensitivity.py --quick     # the same as: drake-grasp sensitivity --quick

Every option, output and exit code is the command's (`drake_grasp/cli/studies.py`).
"""

import sys


def main(argv=None) -> int:
    from drake_grasp.cli import main as drake_grasp

    return drake_grasp(["sensitivity", *(sys.argv[1:] if argv is None else argv)])


if __name__ == "__main__":
    raise SystemExit(main())
