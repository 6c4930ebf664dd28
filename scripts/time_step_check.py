#!/usr/bin/env python3
"""Does a grasp held in one scenario stay held in another? The oracle set, paired trial by trial.

    .venv/bin/python scripts/time_step_check.py [--scenarios default step_10ms] [--seeds 3] \\
        [--workers 2] [--out docs/results/time_step]

The success test judges a grasp by what happens over a 10 s hold (docs/design.md §4.7), so a
cheaper physics setting (a longer plant time step, another contact approximation) is only a speed-up
if held objects stay held and slip as little as before. This runs the oracle set (the paper's nine
objects x three compliant grasps x `--seeds` seeds, ground-truth estimates, the same seeds' pose and
friction variations) in each of two named scenarios of the repository's scenario file, and compares
the two trial by trial: which grasps hold in one and not in the other, and the slip (distance and
angle of the object in the palm frame over the hold) of the grasps held in both. Resumable: the
trials of scenario S are kept in OUT/trials_S.csv. Writes OUT/README.md (the table) and
OUT/summary.json. About 6 s (5 ms) and 4 s (10 ms) of one core per trial.
"""

import argparse
import json
import math
import pathlib
import statistics
import sys

GRASPS = ("spherical", "cylindrical", "box")


def run_scenario(name: str, seeds: int, workers: int | None, out: pathlib.Path) -> dict:
    """The oracle set's rows in scenario `name`, by (object, grasp, seed)."""
    from drake_grasp.sweeps.runner import TrialSpec, run_trials
    from drake_grasp.objects import PAPER_OBJECTS

    specs = [TrialSpec(o, "oracle", g, s, scenario_name=name)
             for o in PAPER_OBJECTS for g in GRASPS for s in range(seeds)]
    rows = run_trials(specs, out / f"trials_{name}.csv", workers=workers, label=f"oracle ({name})")
    return {(r["object"], r["grasp"], int(r["seed"])): r for r in rows}


def held(row: dict) -> bool:
    return row["success"] == "1"


def slip_mm(row: dict) -> float:
    return 1e3 * float(row["slip_distance"])


def slip_deg(row: dict) -> float:
    return math.degrees(float(row["slip_angle"]))


def outcome(row: dict) -> str:
    """'held, 0.7 mm, 0.3 deg' or the failure with its slip (nan when there was no hold)."""
    what = "held" if held(row) else row["failure"]
    return f"{what}, {slip_mm(row):.2f} mm, {slip_deg(row):.2f}°"


def quantiles(values: list[float]) -> dict:
    """Median, 90th percentile (nearest rank: the smallest value with at least 90 % of the values at
    or below it) and maximum; nan for no values."""
    if not values:
        return {"median": float("nan"), "p90": float("nan"), "max": float("nan")}
    ordered = sorted(values)
    return {"median": statistics.median(ordered), "p90": ordered[math.ceil(0.9 * len(ordered)) - 1],
            "max": ordered[-1]}


def compare(a: dict, b: dict) -> dict:
    """Paired summary of two scenarios' rows (same keys)."""
    from drake_grasp.sweeps.stats import wilson_interval

    keys = sorted(set(a) & set(b))
    both = [k for k in keys if held(a[k]) and held(b[k])]
    summary = {"trials": len(keys)}
    for label, rows in (("a", a), ("b", b)):
        count = sum(held(rows[k]) for k in keys)
        low, high = wilson_interval(count, len(keys))
        summary[label] = {
            "held": count, "held_ci95": [low, high],
            "slip_mm_held_in_both": quantiles([slip_mm(rows[k]) for k in both]),
            "slip_deg_held_in_both": quantiles([slip_deg(rows[k]) for k in both]),
            "held_under_1mm": sum(held(rows[k]) and slip_mm(rows[k]) < 1.0 for k in keys),
            "mean_wall_time_s": statistics.fmean(float(rows[k]["wall_time"]) for k in keys),
        }
    summary["held_only_in_a"] = [list(k) for k in keys if held(a[k]) and not held(b[k])]
    summary["held_only_in_b"] = [list(k) for k in keys if held(b[k]) and not held(a[k])]
    summary["held_in_both"] = len(both)
    return summary


def report(name_a: str, name_b: str, a: dict, b: dict, summary: dict) -> str:
    from drake_grasp.sweeps.stats import format_rate

    n = summary["trials"]
    sa, sb = summary["a"], summary["b"]
    lines = [
        f"# Held grasps: `{name_a}` against `{name_b}`", "",
        f"The oracle set (nine objects x three compliant grasps x {len({k[2] for k in a})} seed(s), ground-truth "
        f"estimates), "
        f"each trial run in both scenarios with the same seed. Produced by `scripts/time_step_check.py "
        f"--scenarios {name_a} {name_b}`. Where an object's cylindrical and box grasps are the same hand pose "
        f"their trials are the same trial, and their rows repeat; the 95 % intervals count every row as "
        f"independent, so they are narrower than the data warrant.", "",
        f"| | `{name_a}` | `{name_b}` |", "|---|---:|---:|",
        f"| held | {format_rate(sa['held'], n)} | {format_rate(sb['held'], n)} |",
        f"| held with under 1 mm of slip | {sa['held_under_1mm']}/{n} | {sb['held_under_1mm']}/{n} |",
    ]
    for what, unit in (("slip_mm_held_in_both", "mm"), ("slip_deg_held_in_both", "°")):
        for q in ("median", "p90", "max"):
            lines.append(f"| slip ({unit}) of the {summary['held_in_both']} grasps held in both, {q} | "
                         f"{sa[what][q]:.2f} | {sb[what][q]:.2f} |")
    lines += [f"| mean wall time per trial (s) | {sa['mean_wall_time_s']:.1f} | {sb['mean_wall_time_s']:.1f} |", ""]
    lines += [f"Held in `{name_a}` only: " + (", ".join(f"{o} {g} seed {s}" for o, g, s in summary["held_only_in_a"])
                                              or "none") + ".",
              f"Held in `{name_b}` only: " + (", ".join(f"{o} {g} seed {s}" for o, g, s in summary["held_only_in_b"])
                                              or "none") + ".", "",
              "Every trial (outcome, slip distance and angle over the hold):", "",
              f"| object | grasp | seed | `{name_a}` | `{name_b}` |", "|---|---|---:|---|---|"]
    for key in sorted(set(a) & set(b)):
        o, g, s = key
        mark = " **(differs)**" if held(a[key]) != held(b[key]) else ""
        lines.append(f"| {o} | {g} | {s} | {outcome(a[key])} | {outcome(b[key])}{mark} |")
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenarios", nargs=2, default=["default", "step_10ms"], metavar=("A", "B"))
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--workers", type=int)
    parser.add_argument("--out", default="out/time_step")
    args = parser.parse_args()
    for flag, value in (("--seeds", args.seeds), ("--workers", args.workers)):
        if value is not None and value < 1:
            print(f"time_step_check: {flag} must be at least 1, got {value}", file=sys.stderr)
            return 2
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario
    for name in args.scenarios:
        try:
            load_scenario(DEFAULT_SCENARIO_FILE, name)
        except ValueError as e:
            print(f"time_step_check: {e}", file=sys.stderr)
            return 2
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    name_a, name_b = args.scenarios
    a = run_scenario(name_a, args.seeds, args.workers, out)
    b = run_scenario(name_b, args.seeds, args.workers, out)
    summary = compare(a, b)
    (out / "summary.json").write_text(json.dumps({"scenarios": args.scenarios, **summary}, indent=1) + "\n")
    text = report(name_a, name_b, a, b, summary)
    (out / "README.md").write_text(text)
    print(text.split("Every trial")[0])
    return 0


if __name__ == "__main__":
    sys.exit(main())
