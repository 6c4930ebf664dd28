"""A seeded generator of the paper's "flower" region: thin, flat and small objects.

The paper's Fig. 4 maps where its three grasps from above succeed; its future work names the region
where they cannot: small and flat objects that need a precision grasp. The classes, with the sizes
the acceptance target names (issue 24):

* ``plate``: a rectangular plate 6-12 mm thick, 6-12 cm long, 4-10 cm wide, corners rounded
  0-8 mm (a coaster, a phone, a book lying flat);
* ``T`` and ``L``: two bars 2 cm thick (1.5-2.5 cm), 1.5-3 cm wide, the stem 7-12 cm long;
* ``stick``: a box or cylinder 1-2 cm across and 6-14 cm long, lying (a marker, a chopstick bundle);
* ``ball``: a sphere 4-8 cm across;
* ``fruit``: a lumpy ellipsoid 4-8 cm across (a plum, an egg, a small orange).

Object `index` of seed `seed` is drawn from default_rng([seed, index]); its class cycles through
CLASSES, so any six consecutive indices cover them all. Files are closed 2-manifolds in metres,
written like the novel objects' (`novel.obj_text`).
"""

from __future__ import annotations

import csv
import dataclasses
import json
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.novel import CIRCULAR_SEGMENTS, obj_text

CLASSES = ("plate", "T", "L", "stick", "ball", "fruit")


@dataclasses.dataclass(frozen=True)
class FlowerObject:
    name: str
    shape_class: str
    seed: int
    index: int
    mesh: trimesh.Trimesh


def _from_manifold(solid) -> trimesh.Trimesh:
    out = solid.to_mesh()
    return trimesh.Trimesh(np.asarray(out.vert_properties)[:, :3], np.asarray(out.tri_verts), process=True)


def _rounded_plate(rng: np.random.Generator) -> trimesh.Trimesh:
    import manifold3d as m

    length, width = rng.uniform(0.06, 0.12), rng.uniform(0.04, 0.10)
    width = min(width, length)
    thickness = rng.uniform(0.006, 0.012)
    fillet = rng.uniform(0.0, 0.008)
    if fillet < 1e-3:
        return trimesh.creation.box([length, width, thickness])
    core = m.CrossSection.square((length - 2 * fillet, width - 2 * fillet), center=True)
    rounded = core.offset(fillet, m.JoinType.Round, circular_segments=CIRCULAR_SEGMENTS)
    return _from_manifold(m.Manifold.extrude(rounded, thickness).translate((0.0, 0.0, -thickness / 2)))


def _letter(rng: np.random.Generator, letter: str) -> trimesh.Trimesh:
    import manifold3d as m

    thickness, width = rng.uniform(0.015, 0.025), rng.uniform(0.015, 0.03)
    stem, arm = rng.uniform(0.07, 0.12), rng.uniform(0.05, 0.10)
    first = m.Manifold.cube((stem, width, thickness), center=True)
    if letter == "L":
        second = m.Manifold.cube((width, arm, thickness), center=True).translate(
            ((stem - width) / 2.0, (arm - width) / 2.0, 0.0))
    else:
        second = m.Manifold.cube((width, arm, thickness), center=True).translate(
            ((stem - width) / 2.0, 0.0, 0.0))
    return _from_manifold(first + second)


def _stick(rng: np.random.Generator) -> trimesh.Trimesh:
    across, length = rng.uniform(0.01, 0.02), rng.uniform(0.06, 0.14)
    if rng.uniform() < 0.5:
        return trimesh.creation.box([length, across, across])
    mesh = trimesh.creation.cylinder(radius=across / 2, height=length, sections=CIRCULAR_SEGMENTS)
    mesh.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0.0, 1.0, 0.0]))
    return mesh


def _ball(rng: np.random.Generator) -> trimesh.Trimesh:
    return trimesh.creation.icosphere(subdivisions=3, radius=rng.uniform(0.02, 0.04))


def _fruit(rng: np.random.Generator) -> trimesh.Trimesh:
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    directions = sphere.vertices
    radius = np.ones(len(directions))
    for _ in range(int(rng.integers(2, 5))):  # gentle lumps
        centre = rng.normal(size=3)
        centre /= np.linalg.norm(centre)
        radius += rng.uniform(-0.08, 0.08) * np.exp(-(1.0 - directions @ centre) / 0.3)
    axes = rng.uniform(0.8, 1.0, size=3)
    mesh = trimesh.Trimesh(directions * radius[:, None] * axes, sphere.faces, process=True)
    mesh.apply_scale(rng.uniform(0.04, 0.08) / float(np.max(mesh.extents)))
    return mesh


def flower_object(seed: int, index: int) -> FlowerObject:
    """Object `index` of seed `seed` (module docstring)."""
    rng = np.random.default_rng([seed, index])
    shape_class = CLASSES[index % len(CLASSES)]
    if shape_class == "plate":
        mesh = _rounded_plate(rng)
    elif shape_class in ("T", "L"):
        mesh = _letter(rng, shape_class)
    elif shape_class == "stick":
        mesh = _stick(rng)
    elif shape_class == "ball":
        mesh = _ball(rng)
    else:
        mesh = _fruit(rng)
    mesh.apply_translation(-mesh.bounds.mean(axis=0))
    mesh.vertices = np.round(mesh.vertices, 6)
    if mesh.volume < 0:
        mesh.invert()
    return FlowerObject(f"{shape_class}_{seed}_{index:03d}", shape_class, seed, index, mesh)


def generate(count: int, seed: int, out_dir: str | Path) -> list[dict]:
    """Writes objects 0..count-1 of `seed` as OBJ files into `out_dir` with ``manifest.json`` and
    ``manifest.csv``, as the other generators do; returns the manifest rows ({"file", "class", "seed",
    "index", "extents_m"})."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for index in range(count):
        obj = flower_object(seed, index)
        file = f"{obj.name}.obj"
        (out_dir / file).write_text(obj_text(obj.mesh))
        rows.append({"file": file, "class": obj.shape_class, "seed": seed, "index": index,
                     "extents_m": [round(float(e), 6) for e in obj.mesh.extents]})
    (out_dir / "manifest.json").write_text(json.dumps(rows, indent=1) + "\n")
    with open(out_dir / "manifest.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["file", "class", "seed", "index", "extents_m"], lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({**row, "extents_m": " ".join(f"{e:.6f}" for e in row["extents_m"])})
    return rows
