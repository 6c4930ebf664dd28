#!/usr/bin/env python3
"""The paper's nine objects x three compliant grasps x N seeds, with ground-truth estimates.

    .venv/bin/python scripts/oracle_trials.py [--seeds 3] [--workers 2] [--out out/oracle]

Resumable (out/oracle/trials.csv); prints a success table per object and grasp.
"""

import argparse
import pathlib

from drake_grasp.sweeps.runner import TrialSpec, run_trials
from drake_grasp.objects import PAPER_OBJECTS

GRASPS = ("spherical", "cylindrical", "box")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--workers", type=int)
    parser.add_argument("--out", default="out/oracle")
    parser.add_argument("--scenario-name", default="default")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    specs = [TrialSpec(o, "oracle", g, s, scenario_name=args.scenario_name)
             for o in PAPER_OBJECTS for g in GRASPS for s in range(args.seeds)]
    rows = run_trials(specs, out / "trials.csv", workers=args.workers, label="oracle")
    print(f"\n{'object':16s}" + "".join(f"{g:>24s}" for g in GRASPS))
    for o in PAPER_OBJECTS:
        cells = []
        for g in GRASPS:
            mine = [r for r in rows if r["object"] == o and r["grasp"] == g]
            ok = sum(r["success"] == "1" for r in mine)
            reasons = sorted({r["failure"] for r in mine if r["success"] != "1"})
            cells.append(f"{ok}/{len(mine)} " + ("(" + ", ".join(reasons) + ")" if reasons else ""))
        print(f"{o:16s}" + "".join(f"{c:>24s}" for c in cells))
    wall = [float(r["wall_time"]) for r in rows]
    print(f"\n{len(rows)} trials; mean wall time per trial {sum(wall) / len(wall):.1f} s")


if __name__ == "__main__":
    main()
