"""Shape resemblance on near-primitives: are almost-spheres, -boxes and -cylinders named right?

Issue 15, item 4. Generates near-primitives (`drake_grasp.geometry.near_primitives`: ellipsoids
within 10 % of a sphere, rounded boxes, tapered and rounded cylinders; COUNT per class) for a
development seed and an evaluation seed, and runs the wrist camera's exploration on each exactly as
`drake-grasp resemble --object FILE --seed K` does (default scenario and perception), beside the
perfect primitives (Drake's sphere, cube and cylinder, and the generator's perfect meshes) and the
paper's nine objects. Records go to OUT/explorations.csv as they finish (rerun to resume); the
summary (per-class accuracy with 95 % Wilson intervals, confusion tables, the perfect and catalogue
objects' resemblances) is printed and, with --report, written as Markdown with a figure beside it.

Run: .venv/bin/python scripts/near_primitives_check.py [--count 10] [--seed 0] [--eval-seed 1]
     [--workers 2] [--out out/near-primitives] [--report docs/results/near_primitives.md]
"""

import argparse
import os
import pathlib
import sys
import time

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
    parser.add_argument("--workers", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--out", default="out/near-primitives", help="results folder (default out/near-primitives)")
    parser.add_argument("--report", help="write the summary as Markdown here (and the figure beside it)")
    parser.add_argument("--reference-seeds", type=int, default=3, metavar="N",
                        help="trial seeds 0..N-1 for the perfect primitives and the paper's objects (default 3)")
    parser.add_argument("--skip-catalogue", action="store_true", help="leave out the paper's nine objects")
    parser.add_argument("--development-only", action="store_true",
                        help="leave out the evaluation set (while a scorer is being developed on the other)")
    args = parser.parse_args(argv)
    if args.count < 1:
        raise UsageError(f"--count must be >= 1, got {args.count}")
    if args.seed < 0 or args.eval_seed < 0:
        raise UsageError("--seed and --eval-seed must be >= 0")
    if args.seed == args.eval_seed:
        raise UsageError(f"--eval-seed must differ from --seed ({args.seed}): the evaluation set must be new objects")
    if args.reference_seeds < 1:
        raise UsageError(f"--reference-seeds must be >= 1, got {args.reference_seeds}")
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
    return args


def main(argv=None) -> int:
    try:
        args = _parse(argv)
    except UsageError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 2
    from drake_grasp.experiments import near_primitives as study
    from drake_grasp.experiments.executors import LocalExecutor
    from drake_grasp.experiments.lock import LockHeld, results_lock
    from drake_grasp.experiments.results import ResultsFileError, check_results_file

    out = pathlib.Path(args.out)
    workers = min(args.workers, os.cpu_count() or 1)
    if workers < args.workers:
        print(f"{PROG}: note: --workers {args.workers} capped at {workers} (cores)", file=sys.stderr)
    csv_path = out / "explorations.csv"
    start, cpu_start = time.perf_counter(), _cpu_seconds()
    try:
        check_results_file(csv_path, study.FIELDS)
        out.mkdir(parents=True, exist_ok=True)
        with results_lock(out):
            dev = study.ensure_objects(out / f"objects-seed{args.seed}", 4 * args.count, args.seed)
            ev = [] if args.development_only else study.ensure_objects(
                out / f"objects-seed{args.eval_seed}", 4 * args.count, args.eval_seed)
            perfect = study.ensure_objects(out / "objects-perfect", 0, 0, perfect=True)
            groups = {
                "perfect": study.perfect_tasks(perfect, args.reference_seeds),
                "catalogue": [] if args.skip_catalogue else study.catalogue_tasks(args.reference_seeds),
                "development": study.near_tasks(dev),
                "evaluation": study.near_tasks(ev),
            }
            records = {}
            with LocalExecutor(workers) as executor:
                for name, tasks in groups.items():
                    if tasks:
                        records[name] = study.run(tasks, csv_path, executor=executor, label=f"{PROG} {name}")
            wall, cpu = time.perf_counter() - start, _cpu_seconds() - cpu_start
            command = (f"scripts/near_primitives_check.py --count {args.count} --seed {args.seed} "
                       f"--eval-seed {args.eval_seed} --reference-seeds {args.reference_seeds}"
                       + (" --skip-catalogue" if args.skip_catalogue else "")
                       + (" --development-only" if args.development_only else ""))
            figure = pathlib.Path(args.report).with_suffix(".png") if args.report else out / "near_primitives.png"
            text = study.report(records, command=command, seeds=(args.seed, args.eval_seed), count=args.count,
                                figure=figure, wall=wall, cpu=cpu, workers=workers, baseline=study.main_scorer,
                                scorer_note=study.SCORER_NOTE)
    except (LockHeld, ResultsFileError) as e:
        print(f"{PROG}: error: {str(e).splitlines()[0]}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    print(text)
    if args.report:
        from drake_grasp.experiments.results import write_atomically

        write_atomically(pathlib.Path(args.report), text)
    return 0


def _cpu_seconds() -> float:
    """CPU time of this process and its finished children (the workers), s."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


if __name__ == "__main__":
    raise SystemExit(main())
