"""Benchmark and accuracy survey of the visual primitives (drake_grasp.perception).

Two modes:

* default (speed): one full exploration (build the Diagram, approach, depth + principal axis, the
  three resemblance primitives) of one object, pinned to one CPU core; prints build, simulation and
  wall-clock times and the frames rendered, best and median of --repeat runs. The issue asks for at
  most 10 s of wall time per exploration.
* --accuracy: explores every test object (the primitive shapes in several sizes, as catalogue shapes
  and as user meshes written here; the paper's nine objects), each placed with trial SEED's
  variation (±1 cm, ±10° yaw: docs/design.md §4.7), and prints per object the errors of centre, depth,
  principal axis and size against the truth at the end of the exploration, the three resemblances
  and whether the highest names the true class. Writes accuracy.json and accuracy.csv to --out.

Run: /work/venv/bin/python scripts/bench_resemble.py [--object NAME] [--repeat N]
     /work/venv/bin/python scripts/bench_resemble.py --accuracy [--workers N] [--seeds N] [--out DIR]
Not a test: the numbers depend on the machine (the simulation is deterministic).
"""

import argparse
import csv
import json
import multiprocessing
import os
import pathlib
import statistics
import sys
import time

import numpy as np

try:
    import drake_grasp  # noqa: F401
except ModuleNotFoundError:  # Run from a checkout without installing the package.
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))

# The survey: catalogue primitives (drake_grasp.objects), user meshes (written below), paper objects.
CATALOGUE = [f"sphere:{d}" for d in (0.05, 0.1, 0.2, 0.3)] + [f"cube:{e}" for e in (0.05, 0.1, 0.2, 0.3)] + \
    [f"cylinder:{d}x0.3" for d in (0.05, 0.1, 0.2, 0.3)]
MESHES = [("sphere", (0.06,)), ("sphere", (0.15,)), ("sphere", (0.25,)),
          ("box", (0.06, 0.05, 0.04)), ("box", (0.15, 0.10, 0.08)), ("box", (0.25, 0.20, 0.12)),
          ("cylinder", (0.06, 0.20)), ("cylinder", (0.12, 0.30)), ("cylinder", (0.25, 0.35))]
PAPER = ["banana", "apple", "bell_pepper", "sponge", "spectacle_case", "toy_bridge", "soccer_ball", "game_box",
         "bottle_case"]


def write_mesh(kind: str, size: tuple, directory: pathlib.Path) -> pathlib.Path:
    """A watertight mesh file (metres, z up, resting on its lowest point): a sphere (diameter), a box
    (x, y, z edges) or a cylinder (diameter, length) lying along x."""
    import trimesh

    if kind == "sphere":
        mesh = trimesh.creation.icosphere(subdivisions=3, radius=size[0] / 2)
    elif kind == "box":
        mesh = trimesh.creation.box(extents=size)
    else:
        mesh = trimesh.creation.cylinder(radius=size[0] / 2, height=size[1], sections=48)
        mesh.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    name = f"mesh_{kind}_" + "x".join(f"{int(round(s * 1000))}" for s in size)
    path = directory / f"{name}.{'stl' if kind == 'box' else 'obj'}"
    mesh.export(path)
    return path


def explore_one(job: dict) -> dict:
    """One exploration of a job {name, mesh (optional: kind, size, directory), seed}: plain data out."""
    from drake_grasp.objects import object_from_mesh, resolve_object
    from drake_grasp.perception import comparison_record, explore, load_perception_config
    from drake_grasp.protocol import TrialVariation
    from drake_grasp.station import load_scenario
    from drake_grasp.trial import apply_variation

    scenario = load_scenario()
    if "mesh" in job:
        kind, size, directory = job["mesh"]
        path = write_mesh(kind, tuple(size), pathlib.Path(directory))
        spec = object_from_mesh(path, closest_primitive=kind)
    else:
        spec = resolve_object(job["name"])
    look_at = np.array([scenario.object.x, scenario.object.y, 0.0])
    scenario, spec = apply_variation(scenario, spec, TrialVariation.draw(job["seed"], scenario.protocol))
    result = explore(scenario, load_perception_config(), spec, look_at=look_at)
    return dict(comparison_record(result, spec), label=job["name"], seed=job["seed"])


def speed(args) -> None:
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})  # one core
    from drake_grasp.objects import resolve_object
    from drake_grasp.perception import explore, load_perception_config
    from drake_grasp.station import load_scenario

    scenario = load_scenario()
    spec = resolve_object(args.object)
    config = load_perception_config()
    runs = []
    for k in range(args.repeat):
        start = time.perf_counter()
        estimate = explore(scenario, config, spec).estimate
        wall = time.perf_counter() - start
        t = estimate.timings
        runs.append(wall)
        print(f"run {k + 1}: {wall:.2f} s wall (build {t['build_time']:.2f} s, simulate {t['sim_wall_time']:.2f} s "
              f"for {t['sim_time']:.1f} s simulated = {t['sim_time'] / t['sim_wall_time']:.1f}x real time, "
              f"{t['frames']} frames at {config.rate_hz:.0f} Hz); {estimate.best_shape} "
              f"{estimate.resemblances[estimate.best_shape]:.2f}", flush=True)
    print(f"{args.object}: one exploration takes {min(runs):.2f} s (best) / {statistics.median(runs):.2f} s "
          f"(median of {len(runs)}) of wall time on one core; budget 10 s: "
          f"{'within' if statistics.median(runs) <= 10.0 else 'OVER'}")


def accuracy(args) -> None:
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    mesh_dir = out / "meshes"
    mesh_dir.mkdir(exist_ok=True)
    jobs = []
    for seed in range(args.first_seed, args.first_seed + args.seeds):
        jobs += [{"name": name, "seed": seed} for name in CATALOGUE]
        jobs += [{"name": f"mesh {kind} " + "x".join(str(s) for s in size), "mesh": (kind, size, str(mesh_dir)),
                  "seed": seed} for kind, size in MESHES]
        jobs += [{"name": name, "seed": seed} for name in PAPER]
    if args.only:
        jobs = [j for j in jobs if any(o in j["name"] for o in args.only)]
    start = time.perf_counter()
    with multiprocessing.get_context("spawn").Pool(args.workers) as pool:
        records = []
        for record in pool.imap(explore_one, jobs):
            records.append(record)
            print(_line(record), flush=True)
    (out / "accuracy.json").write_text(json.dumps(records, indent=1, default=float) + "\n")
    with open(out / "accuracy.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["object", "seed", "found", "centre_error_m", "depth_error_rel", "axis_error_deg",
                         "length_error_rel", "width_error_rel", "height_error_rel", "sphere", "cylinder", "box",
                         "best", "true_shape", "shape_correct", "object_moved_m", "wall_s"])
        for r in records:
            e, est = r.get("errors"), r["estimate"]
            writer.writerow([r["label"], r["seed"], est["status"] == "ok"] + (
                [e["centre"], e["depth"], e["axis_deg"], *e["extents"]] if e else [""] * 6) +
                [est["resemblances"].get(s, "") for s in ("sphere", "cylinder", "box")] +
                [r["best_shape"], r["truth"]["shape"], e and e["shape_correct"], r["truth"]["object_moved"],
                 est["timings"].get("wall_time")])
    _summary(records, time.perf_counter() - start)
    print(f"wrote {out / 'accuracy.json'} and {out / 'accuracy.csv'}")


def _line(r: dict) -> str:
    est = r["estimate"]
    if est["status"] != "ok":
        return f"{r['label']:28s} seed {r['seed']}: {est['status']}"
    e = r["errors"]
    res = est["resemblances"]
    axis = "   -  " if e["axis_deg"] is None else f"{e['axis_deg']:5.1f}°"
    verdict = {True: "right", False: "WRONG", None: "?"}[e["shape_correct"]]
    return (f"{r['label']:28s} seed {r['seed']}: centre {e['centre'] * 1000:4.1f} mm  depth {e['depth'] * 100:+5.1f} %  "
            f"axis {axis}  size " + " ".join(f"{x * 100:+5.1f}" for x in e["extents"]) + " %  "
            f"S {res['sphere']:.2f} C {res['cylinder']:.2f} B {res['box']:.2f} -> {r['best_shape']:8s} {verdict:5s} "
            f"moved {r['truth']['object_moved'] * 1000:.0f} mm  {est['timings']['wall_time']:.1f} s")


def _summary(records: list, wall: float) -> None:
    found = [r for r in records if r["estimate"]["status"] == "ok"]
    errors = [r["errors"] for r in found]
    within = lambda key, tol: sum(1 for e in errors if e[key] is not None and abs(e[key]) <= tol)  # noqa: E731
    axes = [e for e in errors if e["axis_deg"] is not None]
    known = [e for e in errors if e["shape_correct"] is not None]
    print(f"\n{len(found)}/{len(records)} found; centre within 1 cm: {within('centre', 0.01)}/{len(errors)}; "
          f"depth within 5 %: {within('depth', 0.05)}/{len(errors)}; axis within 10 deg: "
          f"{within('axis_deg', 10.0)}/{len(axes)}; size within 15 %: "
          f"{sum(1 for e in errors if max(abs(x) for x in e['extents']) <= 0.15)}/{len(errors)}; "
          f"class right: {sum(1 for e in known if e['shape_correct'])}/{len(known)} "
          f"(survey took {wall:.0f} s)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--object", default="bottle_case", help="object of the speed run (default bottle_case)")
    parser.add_argument("--repeat", type=int, default=3, help="speed runs (default 3)")
    parser.add_argument("--accuracy", action="store_true", help="survey accuracy over the test objects")
    parser.add_argument("--seeds", type=int, default=1, help="placement variations per object (survey)")
    parser.add_argument("--first-seed", type=int, default=0, help="the first variation's seed (survey)")
    parser.add_argument("--workers", type=int, default=max(1, (os.cpu_count() or 1)), help="survey processes")
    parser.add_argument("--only", nargs="*", help="survey only objects whose label contains one of these")
    parser.add_argument("--out", default="out/bench_resemble", help="survey output directory")
    args = parser.parse_args()
    accuracy(args) if args.accuracy else speed(args)


if __name__ == "__main__":
    main()
