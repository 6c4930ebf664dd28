#!/usr/bin/env python3
"""Do trials still give the same records? Runs a few trials and compares them field by field.

    # the records of today's code, kept as the reference:
    PYTHONPATH=. .venv/bin/python scripts/record_check.py --out /tmp/before.json
    # after a change (or with PYTHONPATH pointing at another checkout): compare with the reference
    PYTHONPATH=. .venv/bin/python scripts/record_check.py --out /tmp/after.json --against /tmp/before.json

A speed change must not change what a trial measures. Every field of every record is compared
exactly (floats bit for bit, NaN equal to NaN), except `wall_time`, which measures the machine.
The trials: the oracle and the camera-driven (compliant) method on the soccer ball and the bottle
case, seed 0, in the default scenario (about a minute on one core). Exits 1 when a record differs,
printing each differing field with its largest absolute difference.
"""

import argparse
import json
import math
import sys

IGNORED = ("wall_time",)
TRIALS = [("soccer_ball", "oracle", "spherical"), ("bottle_case", "oracle", "cylindrical"),
          ("soccer_ball", "compliant", ""), ("bottle_case", "compliant", "")]


def run_records(trials=TRIALS, seed: int = 0) -> list[dict]:
    """The records (plain data) of `trials`, each (object, method, grasp), with `seed`."""
    from drake_grasp import trial

    records = []
    for name, method, grasp in trials:
        record = trial.run(trial.TrialSpec(name, method, grasp, seed)).to_dict()
        print(f"  {name:12s} {method:9s} {'held' if record['success'] else record['failure']:20s} "
              f"{record['wall_time']:6.2f} s wall", flush=True)
        records.append(record)
    return records


def differences(a, b, path: str = "") -> list[tuple[str, str]]:
    """(field path, what differs) for every leaf where `a` and `b` differ (floats exactly; NaN == NaN)."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for key in sorted(set(a) | set(b)):
            if key in IGNORED and not path:
                continue
            if key not in a or key not in b:
                out.append((f"{path}{key}", "present in one record only"))
            else:
                out += differences(a[key], b[key], f"{path}{key}.")
        return out
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [(path.rstrip("."), f"lengths {len(a)} and {len(b)}")]
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, f"{path}{i}.")]
    if isinstance(a, float) and isinstance(b, float):
        if a == b or (math.isnan(a) and math.isnan(b)):
            return []
        return [(path.rstrip("."), f"{a!r} vs {b!r} (difference {abs(a - b):.3g})")]
    return [] if a == b else [(path.rstrip("."), f"{a!r} vs {b!r}")]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", required=True, help="write the records here (JSON)")
    parser.add_argument("--against", help="compare with the records in this file")
    args = parser.parse_args()
    records = run_records()
    with open(args.out, "w") as f:
        json.dump(records, f, indent=1)
    if not args.against:
        return
    with open(args.against) as f:
        reference = json.load(f)
    records = json.loads(json.dumps(records))  # the same JSON round trip as the reference's
    found = 0
    for before, after in zip(reference, records):
        for field, what in differences(before, after):
            found += 1
            print(f"DIFFERS {after['object']} {after['method']}: {field}: {what}")
    print("records identical (every field but wall_time)" if not found else f"{found} fields differ")
    sys.exit(1 if found else 0)


if __name__ == "__main__":
    main()
