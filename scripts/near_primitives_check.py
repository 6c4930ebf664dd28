"""Shape resemblance on near-primitives: are almost-spheres, -boxes and -cylinders named right?

Issue 15, item 4. Generates near-primitives (`drake_grasp.objects.near_primitives`: ellipsoids
within 10 % of a sphere, rounded boxes, tapered and rounded cylinders; COUNT per class) for a
development seed and an evaluation seed, and runs the wrist camera's exploration on each exactly as
`drake-grasp resemble --object FILE --seed K` does (default scenario and perception), beside the
perfect primitives (Drake's sphere, cube and cylinder, and the generator's perfect meshes) and the
paper's nine objects. Records go to OUT/explorations.csv as they finish (rerun to resume); the
summary (per-class accuracy with 95 % Wilson intervals, confusion tables, the perfect and catalogue
objects' resemblances) is written to OUT/summary.md with its figure OUT/near_primitives.png (the
functions: `drake_grasp.studies.near_primitives.run_study`), printed, and with --report copied
there (the figure beside it).

Run: .venv/bin/python scripts/near_primitives_check.py [--count 10] [--seed 0] [--eval-seed 1]
     [--workers 2] [--out out/near-primitives] [--report docs/results/near_primitives.md]
"""

import argparse
import os
import pathlib
import shutil
import sys

PROG = "near_primitives_check"


class UsageError(ValueError):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit code 2 (argparse prints the usage too)
        raise UsageError(message)


def _parse(argv):
    parser = _Parser(prog=PROG, description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=10, help="near-primitives per class and seed (default 10)")
    parser.add_argument("--seed", type=int, default=0, help="the development set's generator seed (default 0)")
    parser.add_argument("--eval-seed", type=int, default=1, help="the evaluation set's generator seed (default 1)")
    parser.add_argument("--reference-seeds", type=int, default=3, metavar="N",
                        help="trial seeds 0..N-1 for the perfect primitives and the paper's objects (default 3)")
    parser.add_argument("--skip-catalogue", action="store_true", help="leave out the paper's nine objects")
    parser.add_argument("--development-only", action="store_true",
                        help="leave out the evaluation set (while a scorer is being developed on the other)")
    parser.add_argument("--workers", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--out", default="out/near-primitives",
                        help="results folder (default out/near-primitives): explorations.csv, summary.md, the figure")
    parser.add_argument("--report", help="also write the summary as Markdown here, the figure beside it (a "
                        "'## Discussion' section already in that file is kept)")
    args = parser.parse_args(argv)
    from drake_grasp.studies.near_primitives import StudyConfig

    config = StudyConfig(count=args.count, seed=args.seed, eval_seed=args.eval_seed,
                         reference_seeds=args.reference_seeds, catalogue=not args.skip_catalogue,
                         development_only=args.development_only)
    try:
        config.validate()
    except ValueError as e:
        raise UsageError(str(e)) from None
    if args.workers < 1:
        raise UsageError(f"--workers must be >= 1, got {args.workers}")
    out = pathlib.Path(args.out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out {out}: not a directory")
    parent = out if out.exists() else out.absolute().parent
    while not parent.exists():
        parent = parent.parent
    if not os.access(parent, os.W_OK):
        raise UsageError(f"--out {out}: not writable")
    if args.report:
        report = pathlib.Path(args.report)
        if report.suffix.lower() != ".md":
            raise UsageError(f"--report {report}: expected a .md file name")
        if not report.absolute().parent.is_dir():
            raise UsageError(f"--report {report}: folder {report.absolute().parent} does not exist")
    return args, config


def main(argv=None) -> int:
    try:
        args, config = _parse(argv)
    except UsageError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 2
    from drake_grasp.studies import near_primitives as study
    from drake_grasp.sweeps.executors import LocalExecutor
    from drake_grasp.sweeps.lock import LockHeld
    from drake_grasp.sweeps.results import ResultsFileError, write_atomically

    out = pathlib.Path(args.out)
    workers = min(args.workers, os.cpu_count() or 1)
    if workers < args.workers:
        print(f"{PROG}: note: --workers {args.workers} capped at {workers} (cores)", file=sys.stderr)
    try:
        with LocalExecutor(workers) as executor:
            text = study.run_study(config, out, executor, label=PROG)
    except (LockHeld, ResultsFileError, ValueError) as e:
        print(f"{PROG}: error: {str(e).splitlines()[0]}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    print(text)
    if args.report:
        report = pathlib.Path(args.report)
        old = report.read_text() if report.is_file() else ""
        kept = old[old.index("\n## Discussion"):] if "\n## Discussion" in old else ""
        write_atomically(report, text.rstrip("\n") + "\n" + kept.rstrip("\n") + ("\n" if kept else ""))
        shutil.copyfile(out / study.FIGURE, report.parent / study.FIGURE)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
