"""How right is the camera's estimate? The silhouettes' against the table-top estimate, per shape class.

Explores generated novel objects (every class), near-primitives and the paper's nine objects once each
with the `table_top` scenario, and compares both estimates of that one exploration with the truth
(`drake_grasp.studies.estimates`). Records go to OUT/estimates.csv as they finish (rerun to resume);
the summary to OUT/summary.md, printed, and with --report copied there.

Run: .venv/bin/python scripts/estimate_check.py [--count 42] [--near 10] [--seed 7] [--workers 2]
     [--out out/estimates] [--report docs/results/estimates.md] [--skip-catalogue]
"""

import pathlib
import shutil
import sys

PROG = "estimate_check"


def main(argv=None) -> int:
    from drake_grasp.cli.common import OneLineParser, UsageError

    parser = OneLineParser(prog=PROG, description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=42, help="novel objects (classes cycle; default 42)")
    parser.add_argument("--near", type=int, default=10, help="near-primitives per class (default 10)")
    parser.add_argument("--seed", type=int, default=7, help="the generators' seed (default 7)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="out/estimates")
    parser.add_argument("--report", help="copy the summary here")
    parser.add_argument("--skip-catalogue", action="store_true", help="leave out the paper's nine objects")
    try:
        args = parser.parse_args(argv)
        if args.count < 0 or args.near < 0 or args.seed < 0 or args.workers < 1:
            raise UsageError("--count, --near and --seed must be >= 0, --workers >= 1")
    except UsageError as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 2
    from drake_grasp.studies import estimates
    from drake_grasp.sweeps.executors import LocalExecutor
    from drake_grasp.sweeps.results import write_atomically

    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    tasks = estimates.tasks(out, args.count, args.near, args.seed, not args.skip_catalogue)
    rows = estimates.run(tasks, out / "estimates.csv", LocalExecutor(args.workers))
    command = (f"scripts/estimate_check.py --count {args.count} --near {args.near} --seed {args.seed}"
               + (" --skip-catalogue" if args.skip_catalogue else ""))
    text = "\n".join(estimates.summary_lines(rows, command)) + "\n"
    write_atomically(out / "summary.md", text)
    print(text)
    if args.report:
        shutil.copyfile(out / "summary.md", args.report)
    return 0


if __name__ == "__main__":
    sys.exit(main())
