"""Compares two trial-record files (Fig. 6, Fig. 7, any sweep's CSV) record by record.

Records are matched by (object, method, grasp, seed); every field is compared except those that
describe the run rather than the trial (wall time, fingerprint, line check). Keys that one version
added to the JSON `extra` column are reported and ignored, so files written before and after a new
field appeared can still be compared. Used to check that a refactor changed no behaviour, and that a
speed change moved no outcome:

    python scripts/compare_records.py before/fig6.csv after/fig6.csv
    python scripts/compare_records.py before/fig6.csv after/fig6.csv --outcomes-only

Prints one line per differing record (the fields that differ, and the largest relative difference of
the numbers in them) and a summary; exits 1 when any compared field differs, 0 otherwise.
"""

import argparse
import csv
import json
import math
import re
import sys

KEY = ("object", "method", "grasp", "seed")
RUN_FIELDS = {"wall_time", "fingerprint", "check"}  # describe the run, not the trial
OUTCOME_FIELDS = ("success", "failure")
_NUMBER = re.compile(r"-?\d+\.?\d*(?:[eE][-+]?\d+)?")


def load(path: str) -> dict[tuple, dict]:
    """{key: row} of a record file; a key that appears twice is an error (a doubled record)."""
    rows = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            key = tuple(row[k] for k in KEY)
            if key in rows:
                raise ValueError(f"{path}: record {key} appears twice")
            rows[key] = row
    return rows


def relative_difference(a: str, b: str) -> float:
    """The largest relative difference between the numbers of two field texts of the same shape
    (inf when their shapes differ, e.g. a different failure text)."""
    xs, ys = _NUMBER.findall(a), _NUMBER.findall(b)
    if len(xs) != len(ys) or _NUMBER.sub("#", a) != _NUMBER.sub("#", b):
        return math.inf
    worst = 0.0
    for x, y in zip(map(float, xs), map(float, ys)):
        if x != y:
            worst = max(worst, abs(x - y) / max(abs(x), abs(y)))
    return worst


def compare_rows(before: dict, after: dict, fields=None) -> tuple[dict[str, float], set[str]]:
    """({field: largest relative difference} of the fields that differ, keys added to `extra`)."""
    differing, added = {}, set()
    for field in fields or before:
        if field in RUN_FIELDS or field not in after:
            continue
        a, b = before[field], after[field]
        if field == "extra" and a and b:
            ja, jb = json.loads(a), json.loads(b)
            added |= set(jb) - set(ja)
            a, b = json.dumps(ja, sort_keys=True), json.dumps({k: v for k, v in jb.items() if k in ja}, sort_keys=True)
        if a != b:
            differing[field] = relative_difference(a, b)
    return differing, added


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--outcomes-only", action="store_true", help="compare success and failure alone")
    args = parser.parse_args(argv)
    try:
        before, after = load(args.before), load(args.after)
    except (OSError, ValueError, KeyError) as error:
        print(f"compare_records: {error}", file=sys.stderr)
        return 2
    only_before, only_after = sorted(set(before) - set(after)), sorted(set(after) - set(before))
    fields = OUTCOME_FIELDS if args.outcomes_only else None
    differing, added = 0, set()
    for key in sorted(set(before) & set(after)):
        diff, new = compare_rows(before[key], after[key], fields)
        added |= new
        if diff:
            differing += 1
            print(" ".join(key), ", ".join(f"{f} ({d:.1e})" for f, d in diff.items()))
    print(f"{len(before)} records before, {len(after)} after; {len(set(before) & set(after))} compared, "
          f"{differing} differ; only before: {len(only_before)}, only after: {len(only_after)}"
          + (f"; keys added to extra (ignored): {', '.join(sorted(added))}" if added else ""))
    return 1 if differing or only_before or only_after else 0


if __name__ == "__main__":
    sys.exit(main())
