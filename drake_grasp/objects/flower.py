"""A seeded generator of the paper's "flower" region: thin, flat and small objects.

The paper's Fig. 4 maps where its three grasps from above succeed; its future work names the region
where they cannot: small and flat objects that need a precision grasp. The classes, with the sizes
the acceptance target names (issue 24):

* ``plate``: a rectangular plate 6-12 mm thick, 6-12 cm long, 4-10 cm wide, corners rounded
  0-8 mm (a coaster, a phone, a book lying flat);
* ``T`` and ``L``: two bars 2 cm thick (1.5-2.5 cm), 1.5-3 cm wide, the stem 7-12 cm long;
* ``stick``: a box or cylinder 1-2 cm across and 6-14 cm long, lying (a marker, a chopstick bundle);
* ``ball``: a sphere 4-8 cm across;
* ``fruit``: a lumpy ellipsoid 4-8 cm across (a plum, an egg, a small orange);
* ``tile``: a nearly square tile 4-10 cm on a side, 6-12 mm thick, its edges bevelled 0-2 mm (a
  coaster, a bathroom tile, a mahjong tile lying);
* ``pen``: a round or hexagonal barrel 0.9-1.3 cm across and 11-15 cm long with a conical tip,
  lying (a pen, a pencil, a marker);
* ``domino``: a 4.4-5.6 × 2.2-2.8 × 0.8-1.2 cm block lying on its face;
* ``standing_domino``: the same block standing on its short end, as dominoes stand in a row;
* ``cube``: a cube 2-3 cm on a side, its edges rounded 0-3 mm (a die, a sugar cube, a toy block).

Object `index` of seed `seed` is drawn from default_rng([seed, index]); its class cycles through
CLASSES, so any eleven consecutive indices cover them all. Up to behaviour version 0.7.0 the cycle
was the first six classes alone (`CLASSES_0_7`, which the stored results in docs/results/flower.md
used; pass it as `classes` to regenerate them). Files are closed 2-manifolds in metres, written like
the novel objects' (`novel.obj_text`).
"""

from __future__ import annotations

import csv
import dataclasses
import json
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.generated import CIRCULAR_SEGMENTS, obj_text, to_trimesh

CLASSES_0_7 = ("plate", "T", "L", "stick", "ball", "fruit")
CLASSES = ("plate", "tile", "T", "L", "stick", "pen", "domino", "standing_domino", "cube", "ball", "fruit")


@dataclasses.dataclass(frozen=True)
class FlowerObject:
    name: str
    shape_class: str
    seed: int
    index: int
    mesh: trimesh.Trimesh


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
    return to_trimesh(m.Manifold.extrude(rounded, thickness).translate((0.0, 0.0, -thickness / 2)))


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
    return to_trimesh(first + second)


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


def _tile(rng: np.random.Generator) -> trimesh.Trimesh:
    import manifold3d as m

    side = rng.uniform(0.04, 0.10)
    other = side * rng.uniform(0.85, 1.0)
    thickness = rng.uniform(0.006, 0.012)
    bevel = rng.uniform(0.0, min(0.002, thickness / 4))
    if bevel < 2e-4:
        return trimesh.creation.box([side, other, thickness])
    # A bevelled slab: the hull of a full-size core and a face inset by the bevel on each side.
    core = m.Manifold.cube((side, other, thickness - 2 * bevel), center=True)
    face = m.Manifold.cube((side - 2 * bevel, other - 2 * bevel, thickness), center=True)
    return to_trimesh(m.Manifold.batch_hull([core, face]))


def _pen(rng: np.random.Generator) -> trimesh.Trimesh:
    import manifold3d as m

    across, length = rng.uniform(0.009, 0.013), rng.uniform(0.11, 0.15)
    sides = 6 if rng.uniform() < 0.5 else CIRCULAR_SEGMENTS
    tip = rng.uniform(0.012, 0.02)
    barrel = m.Manifold.cylinder(length - tip, across / 2, circular_segments=sides)
    cone = m.Manifold.cylinder(tip, across / 2, across / 8, circular_segments=sides).translate((0.0, 0.0, length - tip))
    pen = (barrel + cone).rotate((0.0, 90.0, 0.0))  # lying along x
    return to_trimesh(pen)


def _domino_block(rng: np.random.Generator) -> tuple[float, float, float]:
    return rng.uniform(0.044, 0.056), rng.uniform(0.022, 0.028), rng.uniform(0.008, 0.012)


def _cube(rng: np.random.Generator) -> trimesh.Trimesh:
    import manifold3d as m

    side = rng.uniform(0.02, 0.03)
    radius = rng.uniform(0.0, 0.003)
    if radius < 3e-4:
        return trimesh.creation.box([side, side, side])
    inner = side - 2 * radius
    corners = [m.Manifold.sphere(radius, CIRCULAR_SEGMENTS // 2).translate((x, y, z))
               for x in (-inner / 2, inner / 2) for y in (-inner / 2, inner / 2) for z in (-inner / 2, inner / 2)]
    return to_trimesh(m.Manifold.batch_hull(corners))


def flower_object(seed: int, index: int, classes: tuple[str, ...] = CLASSES) -> FlowerObject:
    """Object `index` of seed `seed`, its class cycling through `classes` (module docstring)."""
    rng = np.random.default_rng([seed, index])
    shape_class = classes[index % len(classes)]
    if shape_class == "plate":
        mesh = _rounded_plate(rng)
    elif shape_class == "tile":
        mesh = _tile(rng)
    elif shape_class == "pen":
        mesh = _pen(rng)
    elif shape_class == "domino":
        mesh = trimesh.creation.box(_domino_block(rng))
    elif shape_class == "standing_domino":
        length, width, thickness = _domino_block(rng)
        mesh = trimesh.creation.box([thickness, width, length])
    elif shape_class == "cube":
        mesh = _cube(rng)
    elif shape_class in ("T", "L"):
        mesh = _letter(rng, shape_class)
    elif shape_class == "stick":
        mesh = _stick(rng)
    elif shape_class == "ball":
        mesh = _ball(rng)
    elif shape_class == "fruit":
        mesh = _fruit(rng)
    else:
        raise ValueError(f"unknown flower class {shape_class!r}: choose from {', '.join(classes)}")
    mesh.apply_translation(-mesh.bounds.mean(axis=0))
    mesh.vertices = np.round(mesh.vertices, 6)
    if mesh.volume < 0:
        mesh.invert()
    return FlowerObject(f"{shape_class}_{seed}_{index:03d}", shape_class, seed, index, mesh)


def generate(count: int, seed: int, out_dir: str | Path, classes: tuple[str, ...] = CLASSES) -> list[dict]:
    """Writes objects 0..count-1 of `seed` (their classes cycling through `classes`) as OBJ files into
    `out_dir` with ``manifest.json`` and ``manifest.csv``, as the other generators do; returns the
    manifest rows ({"file", "class", "seed", "index", "extents_m"})."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for index in range(count):
        obj = flower_object(seed, index, classes)
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
