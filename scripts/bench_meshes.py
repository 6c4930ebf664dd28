"""Benchmark: speed on meshes against the catalogue objects (the planner and the camera-driven trial).

It makes three non-convex test meshes itself (seeded, about 10-17 cm): a *blob*, an icosphere with
smooth random radial bumps, a *tube*, an 18 mm capsule bent into a 230° arc, and *ring_0_012*, object
12 of the novel-object generator's seed 0 (drake_grasp/geometry/novel.py, a torus of 17 cm), the
one that splits into the full 10 pieces; each is split into at most 10 convex pieces
(``object_from_mesh(path, max_pieces=10)``, CoACD, cached). Then, for each object:

* the Eigengrasp planner (``contact`` energy): one plan of ``--steps`` annealing steps, its annealing
  rate in steps per second of wall time and of this process's CPU time (other processes on a shared
  machine inflate the first, much less the second), and the plan's wall time;
* one compliant trial (``trial.run``, method compliant, seed 0: wrist-camera exploration, decision, grasp,
  lift, hold), its wall and CPU time and its outcome.

Each measurement is repeated ``--repeats`` times (trials: ``--trial-repeats``, default the same) and
the median reported. ``--before FILE`` adds a
previous run's JSON (e.g. of the code before a change, run with this script and ``PYTHONPATH``
pointing at that code) as a "before" column; repeat it for several. Writes ``--out`` (Markdown) and the
same stem ``.json``. With ``--no-trials`` the trial cells of this run stay empty (the previous runs' show).

Run: .venv/bin/python scripts/bench_meshes.py [--steps N] [--repeats R] [--trial-repeats R]
     [--before FILE ...] [--out docs/results/mesh_speed.md] [--label after]
Not a test: the numbers depend on the machine and its load.
"""

import argparse
import json
import pathlib
import statistics
import sys
import tempfile
import time
import warnings

import numpy as np
import trimesh

try:
    from drake_grasp.objects import object_from_mesh, paper_object
except ModuleNotFoundError:  # Run from a checkout without installing the package.
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
    from drake_grasp.objects import object_from_mesh, paper_object
from baselines.eigengrasp.planner import EigengraspPlanner
from drake_grasp.objects import _convex_vertices
from drake_grasp.objects.novel import novel_object, obj_text
from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario
from drake_grasp import trial

PLANNER_CATALOGUE = ("sponge", "spectacle_case", "bottle_case")
TRIAL_CATALOGUE = ("bottle_case",)
MAX_PIECES = 10
NOVEL = (0, 12)  # (seed, index) of the generated mesh: a ring that CoACD splits into 10 pieces


def blob_mesh(seed: int = 0, radius: float = 0.05, bumps: int = 20, amplitude: float = 0.6,
              width: float = 0.12) -> trimesh.Trimesh:
    """An icosphere (subdivision 3, `radius` m) with `bumps` smooth radial bumps of random centre and
    relative height in ±`amplitude` (Gaussian in the cosine of the angle from their centre, `width`)."""
    rng = np.random.default_rng(seed)
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    directions = sphere.vertices
    scale = np.ones(len(directions))
    for _ in range(bumps):
        centre = rng.normal(size=3)
        centre /= np.linalg.norm(centre)
        scale += rng.uniform(-amplitude, amplitude) * np.exp(-((directions @ centre - 1.0) ** 2) / width)
    return trimesh.Trimesh(directions * (radius * np.maximum(scale, 0.4))[:, None], sphere.faces)


def tube_mesh(radius: float = 0.018, length: float = 0.22, bend: float = 4.0) -> trimesh.Trimesh:
    """A capsule (`radius`, straight part `length`, m) bent about y into an arc of `bend` rad."""
    capsule = trimesh.creation.capsule(height=length, radius=radius, count=[32, 32])
    vertices, faces = trimesh.remesh.subdivide_to_size(capsule.vertices, capsule.faces, max_edge=0.006)
    arc_radius = length / bend
    theta = vertices[:, 2] / arc_radius
    rho = arc_radius + vertices[:, 0]
    bent = np.column_stack([rho * np.cos(theta) - arc_radius, vertices[:, 1], rho * np.sin(theta)])
    return trimesh.Trimesh(bent, faces)


def mesh_objects(directory: pathlib.Path) -> dict:
    """The test meshes as ObjectSpecs, by name."""
    specs = {}
    novel = novel_object(*NOVEL)
    for name, mesh in (("blob", blob_mesh()), ("tube", tube_mesh()), (novel.name, novel.mesh)):
        path = directory / f"{name}.obj"
        if name == novel.name:
            path.write_text(obj_text(mesh))  # the generator's own file, as `objects generate` writes it
        else:
            mesh.export(path)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # They are laid on a stable face; that is fine here.
            specs[name] = object_from_mesh(path, max_pieces=MAX_PIECES)
    return specs


def time_plan(spec, steps: int) -> dict:
    planner = EigengraspPlanner(spec, "contact")
    start = time.perf_counter()
    plan = planner.plan(steps, seed=0)
    return {"steps_per_second": plan.steps_per_second,
            "steps_per_cpu_second": plan.iterations / plan.annealing_cpu_time,
            "plan_wall_time": time.perf_counter() - start}


def time_trial(scenario, spec) -> dict:
    wall, cpu = time.perf_counter(), time.process_time()
    record = trial.run(trial.TrialSpec(spec.name, "compliant", "", 0), scenario=scenario, obj=spec)
    return {"trial_wall_time": time.perf_counter() - wall, "trial_cpu_time": time.process_time() - cpu,
            "success": record.success, "failure": record.failure, "grasp": record.chosen_grasp}


def median_of(runs: list[dict]) -> dict:
    """Medians of the numeric fields, the last run's other fields."""
    out = dict(runs[-1])
    for key, value in runs[-1].items():
        if isinstance(value, float):
            out[key] = statistics.median(r[key] for r in runs)
    return out


def markdown(rows: dict, befores: list[dict], label: str, steps: int, repeats: int,
             trial_repeats: int | None = None) -> str:
    def cell(name, key, fmt, source):
        value = (source or {}).get(name, {}).get(key)
        return "" if value is None else format(value, fmt)

    cols = [b["label"] for b in befores] + [label]
    sources = [b["rows"] for b in befores] + [rows]
    runs = f"medians of {repeats} runs" + "".join(f"; {b['repeats']} in {b['label']}" for b in befores)
    if trial_repeats is not None and trial_repeats != repeats:
        runs += f"; trials: {trial_repeats} in {label}"
    lines = [f"# Speed on meshes ({steps} planner steps; {runs})", "",
             "Made by `scripts/bench_meshes.py` on a shared 2-core machine: wall times are inflated by other "
             "processes, CPU times much less. Meshes: the script's seeded blob and tube, and the novel-object "
             f"generator's object {NOVEL[1]} of seed {NOVEL[0]} (a ring), at most {MAX_PIECES} convex pieces. "
             "Where the time goes, and what changed: "
             "[mesh_speed_profile.md](mesh_speed_profile.md).", "",
             "## Eigengrasp planner (`contact` energy): annealing steps per CPU second (per wall second)", "",
             f"| object | pieces (vertices, {label}) | " + " | ".join(cols) + " |",
             "|---|---|" + "---|" * len(cols)]
    for name, row in rows.items():
        if "steps_per_cpu_second" not in row:
            continue
        cells = [f"{cell(name, 'steps_per_cpu_second', '.0f', s)} ({cell(name, 'steps_per_second', '.0f', s)})"
                 if cell(name, 'steps_per_cpu_second', '.0f', s) else "" for s in sources]
        lines.append(f"| {name} | {row['pieces']} | " + " | ".join(cells) + " |")
    lines += ["", "## Compliant trial (camera-driven, seed 0): CPU s (wall s), outcome", "",
              "| object | " + " | ".join(cols) + " |", "|---|" + "---|" * len(cols)]
    for name in rows:
        if not any("trial_cpu_time" in s.get(name, {}) for s in sources):
            continue
        cells = []
        for s in sources:
            r = (s or {}).get(name, {})
            if "trial_cpu_time" not in r:
                cells.append("")
                continue
            outcome = "held" if r.get("success") else (r.get("failure") or "")
            cells.append(f"{cell(name, 'trial_cpu_time', '.1f', s)} ({cell(name, 'trial_wall_time', '.1f', s)}), "
                         f"{r.get('grasp', '')} {outcome}")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    lines += ["", "## Meshes against the catalogue (CPU time)", "",
              "| | " + " | ".join(cols) + " |", "|---|" + "---|" * len(cols)]
    for name in rows:
        if name in PLANNER_CATALOGUE or name in TRIAL_CATALOGUE:
            continue
        planner, trial = [], []
        for source in sources:
            if "steps_per_cpu_second" not in source.get(name, {}):  # not measured in that run
                planner.append("")
                trial.append("")
                continue
            catalogue = [source[c]["steps_per_cpu_second"] for c in PLANNER_CATALOGUE if c in source]
            planner.append(f"{source[name]['steps_per_cpu_second'] / statistics.mean(catalogue):.2f}")
            if source[name].get("failure") in ("simulation error", "perception failed"):  # ended early
                trial.append(f"n/a ({source[name]['failure']})")
            elif "trial_cpu_time" in source[name] and "trial_cpu_time" in source.get("bottle_case", {}):
                trial.append(f"{source[name]['trial_cpu_time'] / source['bottle_case']['trial_cpu_time']:.2f}")
            else:
                trial.append("")
        lines.append(f"| {name}: planner steps/s ÷ the catalogue objects' mean | " + " | ".join(planner) + " |")
        if any(trial):
            lines.append(f"| {name}: trial time ÷ the bottle case's | " + " | ".join(trial) + " |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=40_000)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--trial-repeats", type=int, default=None, help="repeats of each trial (default: --repeats)")
    parser.add_argument("--no-trials", action="store_true", help="time the planner only")
    parser.add_argument("--before", metavar="FILE", action="append", default=[],
                        help="a previous run's JSON, shown as a column before this run's (repeatable)")
    parser.add_argument("--label", default="after")
    parser.add_argument("--out", default="docs/results/mesh_speed.md")
    args = parser.parse_args(argv)

    scenario = load_scenario(DEFAULT_SCENARIO_FILE, "default")
    with tempfile.TemporaryDirectory() as tmp:
        meshes = mesh_objects(pathlib.Path(tmp))
    objects = {name: paper_object(name) for name in PLANNER_CATALOGUE + TRIAL_CATALOGUE} | meshes
    rows = {}
    for name, spec in objects.items():
        vertices = [len(_convex_vertices(p.mesh_path)) for p in spec.pieces if p.kind == "convex"]
        row = {"pieces": f"{len(spec.pieces)} ({sum(vertices)})" if vertices else str(len(spec.pieces))}
        if name in PLANNER_CATALOGUE or name in meshes:
            row |= median_of([time_plan(spec, args.steps) for _ in range(args.repeats)])
            print(f"{name:15s} planner {row['steps_per_cpu_second']:6.0f} steps/cpu-s "
                  f"({row['steps_per_second']:6.0f} steps/s)", flush=True)
        if not args.no_trials and (name in TRIAL_CATALOGUE or name in meshes):
            trial_repeats = args.repeats if args.trial_repeats is None else args.trial_repeats
            row |= median_of([time_trial(scenario, spec) for _ in range(trial_repeats)])
            print(f"{name:15s} trial {row['trial_cpu_time']:6.1f} cpu-s ({row['trial_wall_time']:6.1f} s) "
                  f"{row['grasp']} {'held' if row['success'] else row['failure']}", flush=True)
        rows[name] = row
    befores = [json.loads(pathlib.Path(b).read_text()) for b in args.before]
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    result = {"label": args.label, "steps": args.steps, "repeats": args.repeats, "rows": rows}
    if not args.no_trials:
        result["trial_repeats"] = args.repeats if args.trial_repeats is None else args.trial_repeats
    out.with_suffix(".json").write_text(json.dumps(result, indent=2) + "\n")
    out.write_text(markdown(rows, befores, args.label, args.steps, args.repeats, result.get("trial_repeats")))
    print(f"wrote {out} and {out.with_suffix('.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
