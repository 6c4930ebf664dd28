"""The funnel search's cost per decision, on one core: how many poses it closes the hand on, and how long.

Each object (the novel-object generator's classes, and a box, a ball and a lying cylinder) rests on the
table; its height map is what an ideal camera above would raise (the highest of dense surface samples
per 3 mm cell, as `table_top.HeightMap.add` does with depth pixels), and the search runs on its column
solid exactly as the supervisor runs it at the decision (`funnel.search.search`, the scenario
`funnel`'s parameters). Wall time of the whole search (building the quasi-static hand included), one
process, one thread.

With `--carve` the column solid is carved as the depth views carve it (docs/design.md §5.4r), by an
ideal carving: every level of a column whose centre lies outside the object is free (the mesh filled
into 2 mm voxels), the most a camera could carve, and so the most pieces the shape can have.

Run: .venv/bin/python scripts/bench_funnel.py [--count 14] [--seed 77] [--carve] [--out docs/results/funnel_search]
"""

import argparse
import json
import pathlib
import statistics
import tempfile

import numpy as np
import trimesh

from drake_grasp.funnel.observed_shape import observed_shape
from drake_grasp.funnel.search import search
from drake_grasp.grasps import GRASP_OF_SHAPE, GraspType, ObjectEstimate
from drake_grasp.primitives import free_space, table_top
from drake_grasp.primitives.scores import SHAPES
from drake_grasp.station import load_scenario

CENTRE = np.array([0.55, 0.0])


def height_map_of(mesh: trimesh.Trimesh, seed: int, carve: bool = False) -> table_top.HeightMap:
    """An ideal camera's height map of `mesh` resting on the table (z = 0) at CENTRE (with `carve`, its
    ideal carving: `ideal_carving`)."""
    mesh = mesh.copy()
    mesh.apply_translation([*(CENTRE - mesh.bounds.mean(axis=0)[:2]), -mesh.bounds[0, 2]])
    points, _ = trimesh.sample.sample_surface(mesh, 400_000, seed=seed)
    m = table_top.HeightMap.around(CENTRE, 0.003, 128)
    m.add(points)
    if carve:
        m.carved = ideal_carving(mesh, m)
    return m


def ideal_carving(mesh: trimesh.Trimesh, m: table_top.HeightMap) -> np.ndarray:
    """The carved levels (`free_space.carve`'s bits) of every seen column whose level centre lies outside
    `mesh` (filled into 2 mm voxels): what views from everywhere would carve."""
    filled = mesh.voxelized(pitch=0.002).fill()
    i, j = np.nonzero(np.isfinite(m.heights))
    levels = np.arange(free_space.LEVELS)
    xy = m.origin + (np.column_stack([i, j]) + 0.5) * m.cell
    centres = np.column_stack([np.repeat(xy, len(levels), axis=0),
                               np.tile((levels + 0.5) * free_space.LEVEL, len(i))])
    free = ~filled.is_filled(centres).reshape(len(i), len(levels))
    bits = np.zeros(m.heights.shape)
    bits[i, j] = free.astype(np.int64) @ np.left_shift(np.int64(1), levels.astype(np.int64))
    return bits


def grasp_estimate(m: table_top.HeightMap) -> tuple[ObjectEstimate, float]:
    """The table-top estimate's centre, axes and extents as a grasp estimate; its centre uncertainty."""
    e = table_top.estimate(m)
    sides = np.asarray(e.sides, float)
    R = np.column_stack([sides, np.cross([0.0, 0.0, 1.0], sides), [0.0, 0.0, 1.0]])
    axis = e.principal_axis if e.extents_axis[0] > 1.1 * e.extents_axis[1] else None
    return ObjectEstimate(center=e.centre, R_WB=R, size=np.maximum(e.extents_sides, 1e-3), principal_axis=axis,
                          table_z=0.0), 0.002


def objects(count: int, seed: int, directory: pathlib.Path) -> list[tuple[str, trimesh.Trimesh]]:
    from drake_grasp.objects.novel import generate

    out = [("box 12x6x5 cm", trimesh.creation.box([0.12, 0.06, 0.05])),
           ("ball 9 cm", trimesh.creation.icosphere(4, 0.045)),
           ("lying cylinder 6x20 cm", trimesh.creation.cylinder(0.03, 0.2).apply_transform(
               trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0])))]
    for entry in generate(count, seed, directory):
        out.append((f"{entry['class']} {pathlib.Path(entry['file']).stem}", trimesh.load(directory / entry["file"], force="mesh")))
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=14, help="generated objects (2 of each class by default)")
    parser.add_argument("--seed", type=int, default=77, help="the generator's seed")
    parser.add_argument("--carve", action="store_true", help="carve each column solid ideally (module docstring)")
    parser.add_argument("--out", default="out/bench_funnel", help="writes OUT.json and OUT.md")
    args = parser.parse_args()
    params = load_scenario(scenario_name="funnel").perception.grasp_search
    grasps = tuple(GraspType(GRASP_OF_SHAPE[s]) for s in SHAPES)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, mesh in objects(args.count, args.seed, pathlib.Path(tmp)):
            m = height_map_of(mesh, args.seed, args.carve)
            shape = observed_shape(m)
            estimate, uncertainty = grasp_estimate(m)
            found = search(shape, estimate, grasps, params, uncertainty)
            rows.append({"object": name, "pieces": len(shape.pieces), "grasps_closed": found.grasps,
                         "wall_time": found.wall_time,
                         "per_grasp_ms": 1000 * found.wall_time / found.grasps,
                         "funnels": {g.value: [f.primitive, f.best.epsilon_mean] for g, f in found.funnels.items()}})
            print(f"{name}: {len(shape.pieces)} pieces, {found.grasps} grasps, {found.wall_time:.2f} s", flush=True)
    walls = [r["wall_time"] for r in rows]
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.with_suffix(".json").write_text(json.dumps({"seed": args.seed, "carve": args.carve, "params": vars(params),
                                                    "rows": rows}, indent=1))
    shape = "the ideally carved column solid (`--carve`)" if args.carve else "the column solid"
    lines = [f"# The funnel search's cost per decision (scripts/bench_funnel.py, generator seed {args.seed})", "",
             f"The shape closed on: {shape}.", "",
             f"One process, one core; the scenario `funnel`'s parameters. {len(rows)} objects: median "
             f"{statistics.median(walls):.2f} s, largest {max(walls):.2f} s per decision (target: at most 5 s).", "",
             "| object | pieces | grasps closed | wall time (s) | ms per grasp | ε_mean spherical, cylindrical, box: primitive → best |",
             "|---|---:|---:|---:|---:|---|"]
    for r in rows:
        eps = "; ".join(f"{a:.3f} → {b:.3f}" for a, b in r["funnels"].values())
        lines.append(f"| {r['object']} | {r['pieces']} | {r['grasps_closed']} | {r['wall_time']:.2f} | "
                     f"{r['per_grasp_ms']:.1f} | {eps} |")
    out.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print(f"median {statistics.median(walls):.2f} s, largest {max(walls):.2f} s; {out.with_suffix('.md')}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
