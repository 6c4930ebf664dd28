"""The flower: thin, flat and small objects through every compliant grasp and the camera's own choice.

Generates the flower's classes (`drake_grasp.objects.flower`: plates and tiles 6-12 mm thick, T and
L shapes 2 cm thick, sticks from 1 cm and pens from 0.9 cm across, dominoes lying and standing, cubes
of 2-3 cm, balls and fruit of 4-8 cm; with --six-classes, the cycle of the first six alone, which the
results stored up to behaviour 0.7.0 used), and runs, per object, each of the
four compliant grasps from the true pose (oracle) and the camera-driven algorithm with the
`table_top` scenario (depth views: the table-top estimate and the flat resemblance, so that it may
choose the precision grasp itself), for trial seeds 0..SEEDS-1. Records go to OUT/trials.csv as they
finish (rerun to resume); the table (success per class and grasp, 95 % Wilson intervals, and what the
camera chose) to OUT/summary.md, printed, and with --report copied there.

Run: .venv/bin/python scripts/flower_check.py [--count 12] [--seed 0] [--seeds 1] [--workers 2]
     [--out out/flower] [--report docs/results/flower.md] [--grasps precision,box] [--no-camera]
     [--classes ball,fruit] [--six-classes]
"""

import collections
import json
import pathlib
import shutil
import sys

PROG = "flower_check"
GRASPS = ("spherical", "cylindrical", "box", "precision")


def main(argv=None) -> int:
    from drake_grasp.cli.common import OneLineParser, UsageError

    parser = OneLineParser(prog=PROG, description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=12, help="objects (the classes cycle; default 12)")
    parser.add_argument("--seed", type=int, default=0, help="the generator's seed (default 0)")
    parser.add_argument("--seeds", type=int, default=1, help="trial seeds per object and grasp (default 1)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="out/flower")
    parser.add_argument("--report", help="copy the summary here")
    parser.add_argument("--grasps", default=",".join(GRASPS), help="the oracle grasps (comma-separated)")
    parser.add_argument("--no-camera", action="store_true", help="oracle trials only")
    parser.add_argument("--classes", help="keep only these classes of the COUNT objects (comma-separated)")
    parser.add_argument("--six-classes", action="store_true",
                        help="cycle through the first six classes alone (the generator up to behaviour 0.7.0)")
    try:
        args = parser.parse_args(argv)
        grasps = [g.strip() for g in args.grasps.split(",") if g.strip()]
        if any(g not in GRASPS for g in grasps):
            raise UsageError(f"--grasps: choose from {', '.join(GRASPS)}")
        if args.count < 1 or args.seeds < 1 or args.seed < 0 or args.workers < 1:
            raise UsageError("--count, --seeds and --workers must be >= 1, --seed >= 0")
        from drake_grasp.objects.flower import CLASSES, CLASSES_0_7

        cycle = CLASSES_0_7 if args.six_classes else CLASSES
        classes = cycle if not args.classes else tuple(c.strip() for c in args.classes.split(",") if c.strip())
        if not classes or any(c not in cycle for c in classes):
            raise UsageError(f"--classes: choose from {', '.join(cycle)}")
    except UsageError as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 2
    from drake_grasp.objects import flower
    from drake_grasp.sweeps.executors import LocalExecutor
    from drake_grasp.sweeps.results import write_atomically
    from drake_grasp.sweeps.runner import TrialSpec, run_trials

    out = pathlib.Path(args.out)
    objects_dir = out / "objects"
    manifest = objects_dir / "manifest.json"
    rows = json.loads(manifest.read_text()) if manifest.is_file() else []
    if (len(rows) != args.count or any(r["seed"] != args.seed for r in rows)
            or [r["class"] for r in rows] != [cycle[i % len(cycle)] for i in range(args.count)]):
        rows = flower.generate(args.count, args.seed, objects_dir, cycle)
    objects = [(str(objects_dir / r["file"]), r["class"]) for r in rows if r["class"] in classes]
    specs = [TrialSpec(path, "oracle", g, s) for path, _ in objects for g in grasps for s in range(args.seeds)]
    if not args.no_camera:
        specs += [TrialSpec(path, "compliant", "", s, scenario_name="table_top")
                  for path, _ in objects for s in range(args.seeds)]
    records = run_trials(specs, out / "trials.csv", executor=LocalExecutor(args.workers), label="flower")
    shape_class = dict(objects)
    text = "\n".join(summary_lines(records, shape_class, grasps, args)) + "\n"
    write_atomically(out / "summary.md", text)
    print(text)
    if args.report:
        shutil.copyfile(out / "summary.md", args.report)
    return 0


def summary_lines(records, shape_class, grasps, args) -> list[str]:
    from drake_grasp.sweeps.stats import wilson_interval

    held = collections.defaultdict(lambda: [0, 0])
    chosen = collections.defaultdict(collections.Counter)
    failures = collections.defaultdict(collections.Counter)
    for r in records:
        c = shape_class[r["object"]]
        column = r["grasp"] if r["method"] == "oracle" else "camera"
        ok = str(r["success"]) in ("1", "True")
        held[(c, column)][0] += ok
        held[(c, column)][1] += 1
        if not ok:
            failures[(c, column)][r["failure"]] += 1
        if r["method"] == "compliant":
            extra = json.loads(r["extra"]) if isinstance(r.get("extra"), str) and r["extra"] else (r.get("extra") or {})
            chosen[c][r.get("chosen_grasp") or extra.get("chosen") or "-"] += 1
    columns = list(grasps) + ([] if args.no_camera else ["camera"])
    classes = sorted({shape_class[r["object"]] for r in records})

    def cell(key):
        k, n = held[key]
        if not n:
            return "-"
        lo, hi = wilson_interval(k, n)
        return f"{k}/{n} ({100 * lo:.0f}-{100 * hi:.0f} %)"

    lines = [f"# The flower: thin, flat and small objects ({args.count} objects, generator seed {args.seed})", "",
             f"Made by `scripts/flower_check.py --count {args.count} --seed {args.seed} --seeds {args.seeds}"
             f"{' --classes ' + args.classes if args.classes else ''}`: "
             "each oracle grasp from the true pose, and the camera-driven algorithm with the `table_top` "
             "scenario (its own choice among four), trial seeds 0.."
             f"{args.seeds - 1}. Held / trials, 95 % Wilson intervals.", "",
             "| class | " + " | ".join(columns) + " | camera chose |",
             "|---|" + "---:|" * len(columns) + "---|"]
    for col in columns:
        held[("all", col)] = [sum(held[(c, col)][i] for c in classes) for i in (0, 1)]
    chosen["all"] = sum((chosen[c] for c in classes), collections.Counter())
    for c in classes + ["all"]:
        lines.append(f"| {c} | " + " | ".join(cell((c, col)) for col in columns) + " | "
                     + ", ".join(f"{g} {n}" for g, n in sorted(chosen[c].items())) + " |")
    lines += ["", "Failures: " + "; ".join(f"{c} {col}: " + ", ".join(f"{f} {n}" for f, n in counts.items())
                                          for (c, col), counts in sorted(failures.items())) or "none"]
    return lines


if __name__ == "__main__":
    sys.exit(main())
