"""The box grasp against the flower grasp on objects just taller than the flat rule's thin step.

The flat resemblance's thin step is 1/2 at 2.5 cm (`primitives.flat.THIN_HEIGHT`): thinner objects
take the flower grasp, taller ones the paper's argmax (mostly the box grasp). This probe asks whether
the step sits where it should: objects 2.7-4.0 cm tall of five footprint shapes (a square and a long
box, an oval puck, a lumpy pebble, an L and a rounded bar, 6-14 cm), each grasped camera-driven (the
`funnel` scenario) with the grasp forced, box and flower, at trial seeds 1 and 2. One attempt each.

Run: .venv/bin/python scripts/thin_band_probe.py --out out/thin_band --workers 2
Results: docs/results/holding/thin_band.md.
"""

import argparse
import collections
import pathlib
import sys

import numpy as np
import trimesh

from drake_grasp.sweeps.executors import LocalExecutor
from drake_grasp.sweeps.runner import TrialSpec, run_trials

HEIGHTS = (0.027, 0.031, 0.035, 0.040)  # m


def _box(a, b, h, rng):
    return trimesh.creation.box((a, b, h))


def _oval(a, b, h, rng):
    mesh = trimesh.creation.cylinder(radius=0.5, height=h, sections=48)
    mesh.apply_scale((a, b, 1.0))
    return mesh


def _pebble(a, b, h, rng):
    """A lumpy ellipsoid: a sphere with a smooth ripple and a little noise, scaled to a × b × h."""
    mesh = trimesh.creation.icosphere(subdivisions=3)
    v = mesh.vertices
    radial = 1.0 + 0.12 * np.sin(3.0 * v[:, [0]] + 2.0 * v[:, [1]]) + 0.024 * rng.standard_normal((len(v), 1))
    mesh = trimesh.Trimesh(v * radial, mesh.faces)
    mesh.apply_scale((a, b, h) / mesh.extents)
    return mesh


def _ell(a, b, h, rng):
    arm_a = trimesh.creation.box((a, 0.45 * b, h))
    arm_b = trimesh.creation.box((0.45 * a, b, h)).apply_translation((-0.275 * a, 0.0, 0.0))
    return trimesh.boolean.union([arm_a, arm_b], engine="manifold")


def _bar(a, b, h, rng):
    """A bar with round ends and round sides (a flattened capsule)."""
    mesh = trimesh.creation.capsule(height=max(a - b, 0.001), radius=b / 2, count=[24, 24])
    mesh.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, (0, 1, 0)))
    mesh.apply_scale((a, b, h) / mesh.extents)
    return mesh


SHAPES = {"box": (_box, ((0.09, 0.09), (0.14, 0.08))), "oval": (_oval, ((0.10, 0.07),)),
          "pebble": (_pebble, ((0.11, 0.09),)), "L": (_ell, ((0.10, 0.09),)), "bar": (_bar, ((0.13, 0.06),))}


def make_objects(folder: pathlib.Path, seed: int = 24) -> list[pathlib.Path]:
    """The probe's OBJ files in `folder` (made once; the same seed gives the same files)."""
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    files = []
    for name, (make, sizes) in SHAPES.items():
        for a, b in sizes:
            for h in HEIGHTS:
                mesh = make(a, b, h, rng)  # drawn whether or not the file exists: the same files either way
                file = folder / f"{name}_{round(a * 100)}x{round(b * 100)}_{round(h * 1000)}.obj"
                if not file.exists():
                    mesh.apply_translation(-mesh.bounds.mean(axis=0))
                    mesh.export(file)
                files.append(file)
    return files


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/thin_band")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--seeds", default="1,2", help="trial seeds, comma-separated")
    args = parser.parse_args(argv)
    try:
        seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError:
        seeds = []
    if not seeds or args.workers < 1:  # checked before any work starts
        print("thin_band_probe: error: --seeds takes integers, comma-separated, and --workers at least 1",
              file=sys.stderr)
        return 2
    out = pathlib.Path(args.out)
    files = make_objects(out / "objects")
    specs = [TrialSpec(str(f), "compliant", g, s, scenario_name="funnel")
             for f in files for g in ("box", "precision") for s in seeds]
    rows = run_trials(specs, out / "trials.csv", executor=LocalExecutor(args.workers), label="thin band")
    held, total = collections.Counter(), collections.Counter()
    for r in rows:
        height = int(pathlib.Path(r["object"]).stem.rsplit("_", 1)[1])
        key = (r["grasp"], height)
        total[key] += 1
        held[key] += str(r["success"]) in ("1", "True")
    print("| height (mm) | box grasp | flower grasp |\n|---|---|---|")
    for h in sorted({k[1] for k in total}):
        print(f"| {h} | {held[('box', h)]}/{total[('box', h)]} | {held[('precision', h)]}/{total[('precision', h)]} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
