"""How often the plain command holds what users bring: per class, at the first attempt and within N.

Generated objects of a generator seed, or your own object files (`--files LIST.tsv`). The generators:
the novel classes (`--objects novel`, `drake-grasp objects generate`: blobs, unions, plates, L and T
shapes, rings and handles) or everyday ones (`--objects everyday`, `objects.everyday`: polycubes,
scans, mugs, bottles and boxes, every second one a URDF with a placeholder inertia) or low round ones
(`--objects round`, `objects.round`: fruit and balls 4-11 cm) or hand tools (`--objects tools`,
`objects.tools`: hammers, screwdrivers, spring clamps, markers and wrenches, lying down) or slender objects
standing on their end (`--objects standing`, `objects.standing`: pegs, pencils, markers, vials, sticks). Each
object goes through the
compliance-centric algorithm's own choice (camera only) with `--attempts N`, under each scenario named
(the "before" and "after" columns: e.g. the table-top estimate alone, and the funnel search), over
trial seeds. The first attempt's outcome is the paper's protocol; within N counts a hold at any
attempt (`trial.attempts`). Resumable (the sweeps' runner: rerun the same command to go on).

A files list has one object a line: its class, its path (relative to the list) and optionally its
--scale, tab-separated; lines starting with # are skipped.

Run: .venv/bin/python scripts/holding_study.py [--objects everyday | --files LIST.tsv] --count 14 --seed 9001
     --seeds 1,2 --attempts 3 --scenarios table_top,funnel --workers 2 --out out/holding
     [--report docs/results/holding.md] [--classes blob,union,ring,handle] [--grasps box,precision]
"""

import argparse
import collections
import json
import pathlib
import sys
import time

from drake_grasp.studies.novel import ensure_objects
from drake_grasp.sweeps.executors import LocalExecutor
from drake_grasp.sweeps.results import write_atomically
from drake_grasp.sweeps.runner import TrialSpec, run_trials
from drake_grasp.sweeps.stats import short_rate


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--objects", choices=("novel", "everyday", "round", "tools", "standing"), default="novel",
                        help="which generator")
    parser.add_argument("--files", help="a list of object files (class, path, optional scale; tab-separated) "
                        "instead of a generator's objects")
    parser.add_argument("--count", type=int, default=14, help="generated objects (the classes in turn)")
    parser.add_argument("--seed", type=int, default=9001, help="the generator's seed")
    parser.add_argument("--seeds", default="1,2", help="trial seeds, comma-separated")
    parser.add_argument("--attempts", type=int, default=3)
    parser.add_argument("--scenarios", default="table_top,funnel")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="out/holding")
    parser.add_argument("--report", help="write the summary as Markdown here")
    parser.add_argument("--classes", help="run only these classes of the COUNT objects (comma-separated)")
    parser.add_argument("--grasps", default="", help="also force each of these grasps (comma-separated: spherical, "
                        "cylindrical, box, precision), camera-driven, one attempt: a column each beside the "
                        "algorithm's own choice")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    seeds = [int(s) for s in args.seeds.split(",")]
    scenarios = args.scenarios.split(",")
    forced = [g.strip() for g in args.grasps.split(",") if g.strip()]
    if set(forced) - {"spherical", "cylindrical", "box", "precision"}:  # checked before any work starts
        print("holding_study: error: --grasps: choose from spherical, cylindrical, box, precision", file=sys.stderr)
        return 2
    # A column: (scenario, grasp forced or "" for the algorithm's own choice with --attempts).
    columns = [(n, g) for n in scenarios for g in [""] + forced]
    if args.classes and not args.files:  # checked before any work starts
        known = _generator(args.objects).CLASSES
        keep = {c.strip() for c in args.classes.split(",") if c.strip()}
        if not keep or keep - set(known):
            print(f"holding_study: error: --classes: choose from {', '.join(known)}", file=sys.stderr)
            return 2
    start = time.perf_counter()
    if args.files:
        try:
            objects = read_files_list(pathlib.Path(args.files))
        except (OSError, ValueError) as error:
            print(f"holding_study: error: --files: {error}", file=sys.stderr)
            return 2
    elif args.objects == "novel":
        objects = ensure_objects(out / "objects", args.count, args.seed)
    else:
        from drake_grasp.sweeps.results import ensure_generated

        generator = _generator(args.objects)
        objects = ensure_generated(out / "objects", lambda staging: generator.generate(args.count, args.seed, staging),
                                   args.count, (args.seed,))
    if args.classes:
        keep = {c.strip() for c in args.classes.split(",") if c.strip()}
        objects = [o for o in objects if o["class"] in keep]
    from drake_grasp.objects.names import load_error

    # Every object loads before any trial starts (one line and exit 2 if not), checked on the workers:
    # a new mesh's convex decomposition takes up to minutes, and the trials find it cached.
    checked = {}
    for index, error in LocalExecutor(args.workers).imap_unordered(
            load_error, [(str(o["file"]), o.get("scale", 1.0)) for o in objects]):
        checked[index] = error
        print(f"holding: checked {len(checked)}/{len(objects)} object files", flush=True)
    first_error = next((checked[i] for i in range(len(objects)) if checked[i]), None)
    if first_error:
        print(f"holding_study: error: {first_error}", file=sys.stderr)
        return 2
    specs = [TrialSpec(str(o["file"]), "compliant", g, s, scenario_name=n, attempts=1 if g else args.attempts,
                       scale=o.get("scale", 1.0))
             for n, g in columns for o in objects for s in seeds]
    rows = run_trials(specs, out / "trials.csv", executor=LocalExecutor(args.workers), label="holding")
    wall = time.perf_counter() - start
    shape_class = {str(o["file"]): o["class"] for o in objects}
    # (scenario, class) -> [first-attempt holds, within-N holds, trials]
    counts = collections.defaultdict(lambda: [0, 0, 0])
    failures = collections.defaultdict(collections.Counter)
    chose = collections.defaultdict(collections.Counter)
    tries = collections.defaultdict(list)
    by_key = {(r["object"], int(r["seed"]), json.loads(r["extra"]).get("scenario"), r["grasp"]): r for r in rows}
    for spec in specs:
        r = by_key[(spec.object, spec.seed, spec.scenario_name, spec.grasp)]
        column = _label(spec.scenario_name, spec.grasp)
        extra = json.loads(r["extra"])
        attempts = extra.get("attempts") or []
        within = str(r["success"]) in ("1", "True")
        first = bool(attempts[0]["success"]) if attempts else within
        for key in ((column, shape_class[spec.object]), (column, "all")):
            c = counts[key]
            c[0] += first
            c[1] += within
            c[2] += 1
        failures[column][("held" if first else (attempts[0]["failure"] if attempts else r["failure"]))] += 1
        chose[column][(attempts[0]["grasp"] if attempts else r["grasp"] or extra.get("chosen")) or "-"] += 1
        tries[column].append(len(attempts) or 1)
    classes = sorted({c for _, c in counts} - {"all"}) + ["all"]
    source = (f"--files {args.files}" if args.files
              else f"--objects {args.objects} --count {args.count} --seed {args.seed}")
    what = (f"{len(objects)} object files of {args.files}" if args.files
            else f"{len(objects)} objects of generator seed {args.seed}")
    title = "object files" if args.files else f"generated {args.objects} objects"
    lines = [f"# Holding what users bring: {title}, first attempt and within {args.attempts}",
             "", f"`scripts/holding_study.py {source} --seeds {args.seeds} "
             f"--attempts {args.attempts} --scenarios {args.scenarios}"
             + (f" --classes {args.classes}" if args.classes else "")
             + (f" --grasps {args.grasps}" if forced else "") + f"`: {what}, trial seeds {args.seeds}, "
             "the algorithm's own choice (camera only), "
             f"{len(rows)} trials in {wall / 60:.0f} min on {args.workers} workers.", "",
             "| class | " + " | ".join(f"{_label(n, g)}: first attempt | {_label(n, g)}: within {1 if g else args.attempts}"
                                      for n, g in columns) + " |",
             "|---|" + "---|---|" * len(columns)]
    for c in classes:
        cells = []
        for n, g in columns:
            first, within, total = counts[(_label(n, g), c)]
            cells += [short_rate(first, total), short_rate(within, total)]
        lines.append(f"| {c} | " + " | ".join(cells) + " |")
    lines.append("")
    for n in (_label(n, g) for n, g in columns):
        lines.append(f"- {n}: first attempts {dict(failures[n])}; first grasp chosen {dict(chose[n])}; "
                     f"attempts made {dict(collections.Counter(tries[n]))}")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.report:
        write_atomically(pathlib.Path(args.report), text)
    return 0


def _label(scenario: str, grasp: str) -> str:
    """A column's name: the scenario, and the grasp when one was forced."""
    return f"{scenario}, {grasp} forced" if grasp else scenario


def _generator(name: str):
    """The generator module of `--objects NAME`."""
    from drake_grasp.objects import everyday, novel, round as round_objects, standing, tools

    return {"novel": novel, "everyday": everyday, "round": round_objects, "tools": tools, "standing": standing}[name]


def read_files_list(path: pathlib.Path) -> list[dict]:
    """Objects of a files list: [{"class", "file", "scale"}], paths resolved against the list's folder.

    ValueError naming the line when a line has no class and path, a scale that is not a positive number,
    or a file that does not exist."""
    objects = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        fields = [f.strip() for f in line.split("\t")]
        if len(fields) < 2 or not fields[0] or not fields[1]:
            raise ValueError(f"{path}:{number}: expected a class and a path, tab-separated")
        file = (path.parent / fields[1]).resolve()
        if not file.is_file():
            raise ValueError(f"{path}:{number}: no such file {fields[1]}")
        scale = 1.0
        if len(fields) > 2 and fields[2]:
            try:
                scale = float(fields[2])
            except ValueError:
                scale = -1.0
            if not scale > 0.0:
                raise ValueError(f"{path}:{number}: the scale must be a positive number, got {fields[2]!r}")
        objects.append({"class": fields[0], "file": file, "scale": scale})
    if not objects:
        raise ValueError(f"{path}: no object listed")
    return objects


if __name__ == "__main__":
    raise SystemExit(main())
