"""Object files as users bring them, through loading and whole trials: accepted or refused, and does
any trial end in a simulation error?

The acceptance check of "real objects as users bring them": each file (mesh or model) is loaded as
a trial would (`drake_grasp.objects.check.check_object`: accepted or refused and why, the notes, the
load time first and cached), then every accepted file runs, resumable like every sweep, the oracle
grasps named by --grasps (from the true pose) and one camera-driven trial of the algorithm (its own
choice), default scenario, trial seed --seed. A failed grasp is an honest result; a simulation error
is not. Prints (and with --report writes) a table per file and the counts of outcomes.

Run: .venv/bin/python scripts/object_files_check.py FILE_OR_DIR... [--zoo] [--grasps box,cylindrical]
     [--seed 1] [--workers 2] [--out out/files-check] [--report docs/results/object_files_check.md]
     --zoo adds the defect zoo (drake_grasp.objects.mesh_zoo, seed 0) to the files. Run it with a fresh
     DRAKE_GRASP_CACHE to measure first loads (a file loaded before is read from the cache).
"""

import argparse
import collections
import json
import pathlib
import time
import warnings

from drake_grasp.sweeps.executors import LocalExecutor
from drake_grasp.sweeps.results import write_atomically
from drake_grasp.sweeps.runner import TrialSpec, run_trials
from drake_grasp.objects.check import check_object
from drake_grasp.objects import ObjectError
from drake_grasp.trial import SIMULATION_ERROR

SUFFIXES = (".obj", ".stl", ".ply", ".off", ".glb", ".gltf", ".sdf", ".urdf", ".xml")


def _files(arguments: list[str], zoo_dir: pathlib.Path | None) -> list[pathlib.Path]:
    files = []
    for argument in arguments:
        path = pathlib.Path(argument)
        if path.is_dir():
            files += sorted(p for p in path.rglob("*") if p.suffix.lower() in SUFFIXES and "meshes" not in p.parts)
        else:
            files.append(path)
    if zoo_dir is not None:
        from drake_grasp.objects import mesh_zoo

        files += [case.path for case in mesh_zoo.generate(zoo_dir, seeds=(0,)) if case.scale == 1.0]
    return files


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="*", help="object files or folders of them")
    parser.add_argument("--zoo", action="store_true", help="add the defect zoo (seed 0)")
    parser.add_argument("--grasps", default="box", help="oracle grasps to run, comma-separated ('' for none)")
    parser.add_argument("--no-camera", action="store_true", help="skip the camera-driven trial")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="out/files-check")
    parser.add_argument("--report", help="write the summary as Markdown here")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    files = _files(args.paths, out / "zoo" if args.zoo else None)
    start = time.perf_counter()
    loaded, rows_by_file = {}, collections.defaultdict(list)
    for path in files:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                _, report = check_object(str(path))
                loaded[path] = ("accepted", report)
            except ObjectError as error:
                loaded[path] = ("refused", str(error).split(": ", 1)[-1])
        print(f"{path}: {loaded[path][0]}", flush=True)
    accepted = [p for p, (verdict, _) in loaded.items() if verdict == "accepted"]
    grasps = [g for g in args.grasps.split(",") if g]
    specs = [TrialSpec(str(p), "oracle", g, args.seed) for p in accepted for g in grasps]
    if not args.no_camera:
        specs += [TrialSpec(str(p), "compliant", "", args.seed) for p in accepted]
    rows = run_trials(specs, out / "trials.csv", executor=LocalExecutor(args.workers), label="files") if specs else []
    wall = time.perf_counter() - start
    outcomes = collections.Counter()
    for r in rows:
        outcome = "held" if str(r["success"]) in ("1", "True") else r["failure"]
        method = "oracle" if r["method"] == "oracle" else "camera"
        outcomes[(method, outcome)] += 1
        grasp = r["grasp"] or json.loads(r.get("extra") or "{}").get("chosen", "")
        rows_by_file[r["object"]].append(f"{method} {grasp}: {outcome}"
                                         + (f" ({r['detail']})" if r["failure"] == SIMULATION_ERROR else ""))
    errors = sum(n for (_, outcome), n in outcomes.items() if outcome == SIMULATION_ERROR)
    refused = sum(1 for verdict, _ in loaded.values() if verdict == "refused")
    lines = [f"# Object files through loading and whole trials ({len(files)} files)", "",
             f"Made by `scripts/object_files_check.py` (seed {args.seed}, oracle grasps: {', '.join(grasps) or 'none'}"
             f"{'' if args.no_camera else ', and one camera-driven trial'}); {wall:.0f} s wall on {args.workers} workers.",
             "", f"**Accepted {len(accepted)}, refused {refused}; simulation errors: {errors} of {len(rows)} trials.**",
             "", "| file | load | notes | first / cached load (s) | trials |", "|---|---|---|---|---|"]
    for path, (verdict, detail) in loaded.items():
        if verdict == "accepted":
            notes = "; ".join(n.split(": ", 1)[-1] for n in detail.notes) or "none"
            times = f"{detail.load_time:.2f} / {detail.cached_load_time:.2f}"
        else:
            notes, times = f"refused: {detail}", ""
        lines.append(f"| {path.name} | {verdict} | {notes} | {times} | {'; '.join(rows_by_file.get(str(path), []))} |")
    lines += ["", "| method | outcome | trials |", "|---|---|---|"]
    lines += [f"| {m} | {o} | {n} |" for (m, o), n in sorted(outcomes.items())]
    text = "\n".join(lines) + "\n"
    print(text)
    if args.report:
        write_atomically(pathlib.Path(args.report), text)
    return 1 if errors else 0


if __name__ == "__main__":
    raise SystemExit(main())
