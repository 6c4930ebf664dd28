#!/usr/bin/env python3
"""How heavy an object each compliant grasp holds: the same shapes at masses from 0.1 to 1.5 kg.

    .venv/bin/python scripts/payload_check.py [--masses 0.1,0.25,0.5,0.75,1,1.5] [--seeds 1,2]
        [--workers 2] [--out out/payload]

Why: a model file's mass is what the trial simulates, and files as projects ship them often carry an
exporter's placeholder of 1 kg (`objects.everyday`). Whether a grasp fails on such a file because of
its shape or because of its mass is read here: each shape is written as a URDF at each mass (its
inertia the mesh's at uniform density, so the loader keeps the file's mass), and grasped by its own
compliant grasp from its true pose (`--oracle`: the camera's errors do not enter). Success is the
trial's test (lifted 10 cm, moved under 1 cm and 10° in the hand over a 10 s hold).

Resumable: records go to OUT/trials.csv as they finish; a table (held / trials per shape and mass)
goes to OUT/summary.md.
"""

from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np
import trimesh

from drake_grasp.sweeps.stats import wilson_interval
from drake_grasp.objects.round import urdf_text
from drake_grasp.sweeps.runner import TrialSpec, run_trials

# (name, what it is, its compliant grasp, mesh maker). Sizes in metres; each stands on the table as made.
SHAPES = (
    ("bottle", "a standing cylinder 6.4 cm across, 18 cm tall", "cylindrical",
     lambda: trimesh.creation.cylinder(radius=0.032, height=0.18, sections=48)),
    ("can_lying", "a cylinder 7 cm across, 12 cm long, lying", "cylindrical",
     lambda: trimesh.creation.cylinder(radius=0.035, height=0.12, sections=48).apply_transform(
         trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]))),
    ("box", "a box 9 x 6.5 x 10 cm", "box", lambda: trimesh.creation.box(extents=(0.09, 0.065, 0.10))),
    ("melon", "an ellipsoid 12 x 12 x 11 cm", "spherical",
     lambda: trimesh.creation.icosphere(subdivisions=3, radius=1.0).apply_scale((0.06, 0.06, 0.055))),
    ("low_blob", "an ellipsoid 11 x 10 x 6 cm", "precision",
     lambda: trimesh.creation.icosphere(subdivisions=3, radius=1.0).apply_scale((0.055, 0.05, 0.03))),
)


def write_objects(folder: pathlib.Path, masses: list[float]) -> list[tuple[str, float, str, pathlib.Path]]:
    """(shape, mass kg, grasp, URDF path) for each shape at each mass; the mesh centred on its centre of
    mass, the inertia the mesh's at the density that gives `mass`."""
    folder.mkdir(parents=True, exist_ok=True)
    made = []
    for name, _, grasp, make in SHAPES:
        mesh = make()
        mesh.apply_translation(-mesh.center_mass)
        mesh_file = folder / f"{name}.obj"
        mesh.export(mesh_file)
        for mass in masses:
            label = f"{name}_{round(mass * 1000):04d}g"
            path = folder / f"{label}.urdf"
            path.write_text(urdf_text(label, mesh_file.name, mesh, mass))  # the mesh's inertia at `mass`
            made.append((name, mass, grasp, path))
    return made


def _floats(text: str) -> list[float]:
    return [float(v) for v in text.split(",") if v.strip()]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--masses", default="0.1,0.25,0.5,0.75,1,1.5", help="kg, comma-separated")
    parser.add_argument("--seeds", default="1,2", help="trial seeds, comma-separated")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="out/payload")
    args = parser.parse_args(argv)
    try:
        masses, seeds = _floats(args.masses), [int(s) for s in args.seeds.split(",") if s.strip()]
    except ValueError as error:
        print(f"payload_check: --masses and --seeds take comma-separated numbers ({error})", file=sys.stderr)
        return 2
    if not masses or not seeds or min(masses) <= 0.0:
        print("payload_check: give at least one positive mass and one seed", file=sys.stderr)
        return 2
    out = pathlib.Path(args.out)
    objects = write_objects(out / "objects", masses)
    specs = [TrialSpec(str(path), "oracle", grasp, seed) for _, _, grasp, path in objects for seed in seeds]
    rows = run_trials(specs, out / "trials.csv", workers=args.workers, label="payload")
    by_object = {}
    for row in rows:
        by_object.setdefault(pathlib.Path(row["object"]).stem, []).append(row)
    lines = [f"Each shape's own compliant grasp from its true pose, trial seeds {args.seeds}: held / trials "
             "(failures).", "", "| shape | grasp | " + " | ".join(f"{m:g} kg" for m in masses) + " |",
             "|---|---|" + "---|" * len(masses)]
    for name, what, grasp, _ in SHAPES:
        cells = []
        for mass in masses:
            mine = by_object.get(f"{name}_{round(mass * 1000):04d}g", [])
            held = sum(r["success"] == "1" for r in mine)
            why = sorted({r["failure"] for r in mine if r["success"] != "1"})
            cells.append(f"{held}/{len(mine)}" + (f" ({', '.join(why)})" if why else ""))
        lines.append(f"| {name}: {what} | {grasp} | " + " | ".join(cells) + " |")
    held = sum(r["success"] == "1" for r in rows)
    low, high = wilson_interval(held, len(rows))
    lines += ["", f"All: {held}/{len(rows)} ({100 * low:.0f}-{100 * high:.0f} %)."]
    (out / "summary.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
