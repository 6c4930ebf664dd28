#!/usr/bin/env python3
"""Benchmark: the wall time of a small Fig. 6 study, before and after, with every record compared.

    .venv/bin/python scripts/bench_study.py --ref GITREV [--objects apple,sponge,bottle_case] \\
        [--trials 2] [--workers 2] [--rounds 1] [--out docs/results/bench_study]

A study is what users wait for: Fig. 6 runs, for each object, each of the three compliant grasps
after the wrist camera's exploration, for N seeds. This runs the same small Fig. 6 (default: 3
objects x 3 grasps x 2 seeds = 18 camera-driven trials) with the code of revision GITREV ("before",
exported with `git archive`) and with the working tree ("after"), each as the command a user types
(`python -m drake_grasp.cli fig6 --objects ... --trials N --workers W`, from an empty output
folder, object cache shared and warm), one after the other, alternating which goes first from
round to round so that a drift of the machine's load falls on both alike. The time is the command's
whole wall time (process start, imports, workers, every trial, the figure).

Every record of the two runs is compared field by field (`compare_records.compare_rows`: all but
wall time, fingerprint and line check): a speed-up that changes a record is not one. Writes
`--out`.md (the table) and `--out`.json (every measurement); exits 1 if any record differs.
"""

import argparse
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
DEFAULT_OBJECTS = "apple,sponge,bottle_case"


def run_study(tree: pathlib.Path, out: pathlib.Path, args) -> float:
    """Runs the small Fig. 6 with the code in `tree` into `out`; returns its wall time, s."""
    env = dict(os.environ, PYTHONPATH=str(tree))
    command = [sys.executable, "-m", "drake_grasp.cli", "fig6", "--objects", args.objects, "--trials",
               str(args.trials), "--workers", str(args.workers), "--seed", str(args.seed), "--out", str(out)]
    start = time.perf_counter()
    result = subprocess.run(command, cwd=tree, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        sys.exit(f"bench_study: fig6 failed in {tree}: {result.stderr.strip().splitlines()[-1:]}")
    return wall


def compare(before_csv: pathlib.Path, after_csv: pathlib.Path) -> tuple[int, list[str]]:
    """(records compared, a line per record that differs)."""
    sys.path.insert(0, str(REPO / "scripts"))
    from compare_records import compare_rows, load

    before, after = load(str(before_csv)), load(str(after_csv))
    lines = []
    if set(before) != set(after):
        lines.append(f"records only before: {sorted(set(before) - set(after))}; "
                     f"only after: {sorted(set(after) - set(before))}")
    for key in sorted(set(before) & set(after)):
        differing, _ = compare_rows(before[key], after[key])
        if differing:
            lines.append(f"{key}: {', '.join(sorted(differing))}")
    return len(set(before) & set(after)), lines


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ref", required=True, metavar="GITREV", help="the revision to measure against (before)")
    parser.add_argument("--objects", default=DEFAULT_OBJECTS, help="comma-separated objects")
    parser.add_argument("--trials", type=int, default=2, help="seeds per object and grasp")
    parser.add_argument("--seed", type=int, default=0, help="the first seed")
    parser.add_argument("--workers", type=int, default=2, help="worker processes of each study")
    parser.add_argument("--rounds", type=int, default=1, help="before/after pairs (alternating the order)")
    parser.add_argument("--out", help="write OUT.md (the table) and OUT.json (the measurements)")
    args = parser.parse_args(argv)
    if args.trials < 1 or args.workers < 1 or args.rounds < 1:
        print("bench_study: --trials, --workers and --rounds must be >= 1", file=sys.stderr)
        return 2
    git = ["git", "-C", str(REPO)]
    try:
        revision = subprocess.run(git + ["rev-parse", "--short", args.ref], check=True, capture_output=True,
                                  text=True).stdout.strip()
    except subprocess.CalledProcessError:
        print(f"bench_study: unknown revision '{args.ref}'", file=sys.stderr)
        return 2
    head = subprocess.run(git + ["rev-parse", "--short", "HEAD"], check=True, capture_output=True, text=True).stdout
    dirty = subprocess.run(git + ["status", "--porcelain", "--untracked-files=no"], check=True, capture_output=True,
                           text=True).stdout.strip()
    measurements, problems, compared = [], [], 0
    with tempfile.TemporaryDirectory(prefix="bench_study_") as temp:
        temp = pathlib.Path(temp)
        before_tree = temp / "before"
        before_tree.mkdir()
        archive = subprocess.run(git + ["archive", args.ref], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(before_tree)], input=archive, check=True)
        trees = {"before": before_tree, "after": REPO}
        # Warm the object cache (both versions read the same one) so that neither pays for it.
        run_study(REPO, temp / "warm", argparse.Namespace(**{**vars(args), "trials": 1, "objects": args.objects}))
        for round_number in range(args.rounds):
            order = ("before", "after") if round_number % 2 == 0 else ("after", "before")
            walls = {}
            for version in order:
                out = temp / f"{version}_{round_number}"
                walls[version] = run_study(trees[version], out, args)
                print(f"round {round_number + 1}: {version} {walls[version]:.1f} s", flush=True)
            n, lines = compare(temp / f"before_{round_number}" / "fig6.csv", temp / f"after_{round_number}" / "fig6.csv")
            compared += n
            problems += lines
            print(f"round {round_number + 1}: {n} records compared, {len(lines)} differ", flush=True)
            measurements.append({"round": round_number + 1, "first": order[0], **walls,
                                 "ratio": walls["after"] / walls["before"], "records": n, "differing": len(lines)})
    objects = args.objects.split(",")
    trials = len(objects) * 3 * args.trials
    ratio = statistics.median(m["ratio"] for m in measurements)
    meta = {"ref": f"{args.ref} ({revision})", "after": f"working tree at {head.strip()}" + (" with changes" if dirty else ""),
            "objects": objects, "trials_per_study": trials, "workers": args.workers, "seed": args.seed,
            "machine": f"{platform.node()}, {os.cpu_count()} CPUs, {platform.processor() or platform.machine()}",
            "date": time.strftime("%Y-%m-%d %H:%M")}
    for line in problems:
        print(f"  differs: {line}")
    print(f"after/before wall time (median of {len(measurements)} rounds): {ratio:.2f}; "
          f"{compared} records compared, {len(problems)} differ")
    if args.out:
        out = pathlib.Path(args.out)
        out.parent.mkdir(parents=True, exist_ok=True)
        out.with_suffix(".json").write_text(json.dumps({"meta": meta, "rounds": measurements,
                                                        "differing": problems}, indent=1) + "\n")
        table = ["# A small Fig. 6 study, before and after", "",
                 f"Before: {meta['ref']}; after: {meta['after']}. {trials} camera-driven trials per study "
                 f"({', '.join(objects)} x 3 grasps x {args.trials} seeds from {args.seed}), "
                 f"`--workers {args.workers}`; {meta['machine']}; {meta['date']}. "
                 "Produced by `scripts/bench_study.py --ref`.", "",
                 "| round | first | before (s) | after (s) | after / before | records identical |",
                 "|---:|---|---:|---:|---:|---:|"]
        for m in measurements:
            table.append(f"| {m['round']} | {m['first']} | {m['before']:.1f} | {m['after']:.1f} | {m['ratio']:.2f} | "
                         f"{m['records'] - m['differing']}/{m['records']} |")
        table += ["", f"Median after / before: **{ratio:.2f}**."]
        out.with_suffix(".md").write_text("\n".join(table) + "\n")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
