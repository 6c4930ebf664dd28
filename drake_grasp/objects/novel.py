"""A generator of novel, watertight test objects: the kind of shapes users bring.

Seven classes, each a closed 2-manifold in metres with its largest extent between
`SIZE_RANGE` (3-25 cm):

- ``blob``: a noise-displaced sphere (a star-shaped, non-convex lump: a radial displacement of a
  sphere never self-intersects);
- ``union``: the boolean union of 2-4 random boxes, cylinders and ellipsoids that overlap;
- ``plate``: a thin plate (a box 6-12 mm thick);
- ``L`` and ``T``: two bars joined as the letter;
- ``ring``: a torus;
- ``handle``: a cylinder with a torus on its side, half sunk in it (a mug without its hollow).

Booleans use Manifold (the ``manifold3d`` package; https://github.com/elalish/manifold), whose
Boolean operations are guaranteed to return a closed 2-manifold.

Determinism: object ``i`` of seed ``s`` is drawn from ``numpy.random.default_rng([s, i])``, and
vertices are written with a fixed format, so the same (seed, index) gives a byte-identical file
whatever `count` is.
"""

from __future__ import annotations

import csv
import dataclasses
import json
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.generated import CIRCULAR_SEGMENTS, manifold, obj_text, to_trimesh

CLASSES = ("blob", "union", "plate", "L", "T", "ring", "handle")
SIZE_RANGE = (0.03, 0.25)  # m: largest extent of a generated object


@dataclasses.dataclass(frozen=True)
class NovelObject:
    """One generated object: its mesh (metres) and what the manifest says of it."""

    name: str
    shape_class: str
    seed: int
    index: int
    mesh: trimesh.Trimesh

    def manifest_row(self, file: str) -> dict:
        extents = self.mesh.extents
        return {
            "file": file,
            "class": self.shape_class,
            "seed": self.seed,
            "index": self.index,
            "size_m": round(float(np.max(extents)), 6),
            "extents_m": [round(float(e), 6) for e in extents],
            "volume_m3": float(f"{self.mesh.volume:.6e}"),
            "faces": int(len(self.mesh.faces)),
            "convex": bool(self.mesh.volume >= 0.99 * self.mesh.convex_hull.volume),
        }


def _random_rotation_deg(rng: np.random.Generator) -> tuple[float, float, float]:
    return tuple(float(v) for v in rng.uniform(0.0, 360.0, size=3))


def _primitive(rng: np.random.Generator, scale: float):
    """A random box, cylinder or ellipsoid (Manifold) of dimensions 0.25-0.6 × `scale`, randomly
    rotated, centred near the origin."""
    m = manifold()
    kind = rng.choice(["box", "cylinder", "ellipsoid"])
    dims = rng.uniform(0.25, 0.6, size=3) * scale
    if kind == "box":
        solid = m.Manifold.cube(tuple(dims), center=True)
    elif kind == "cylinder":
        solid = m.Manifold.cylinder(dims[2], dims[0] / 2.0, circular_segments=CIRCULAR_SEGMENTS, center=True)
    else:
        solid = m.Manifold.sphere(1.0, CIRCULAR_SEGMENTS).scale(tuple(dims / 2.0))
    offset = rng.uniform(-0.2, 0.2, size=3) * scale
    return solid.rotate(_random_rotation_deg(rng)).translate(tuple(offset))


def _blob(rng: np.random.Generator) -> trimesh.Trimesh:
    sphere = trimesh.creation.icosphere(subdivisions=4, radius=1.0)
    directions = sphere.vertices
    radius = np.ones(len(directions))
    for _ in range(int(rng.integers(4, 9))):  # Gaussian bumps and dents on the unit sphere.
        centre = rng.normal(size=3)
        centre /= np.linalg.norm(centre)
        width = rng.uniform(0.05, 0.3)
        radius += rng.uniform(-0.5, 0.6) * np.exp(-(1.0 - directions @ centre) / width)
    radius = np.maximum(radius, 0.3)
    axes = rng.uniform(0.6, 1.0, size=3)
    return trimesh.Trimesh(directions * radius[:, None] * axes, sphere.faces, process=True)


def _union(rng: np.random.Generator) -> trimesh.Trimesh:
    m = manifold()
    solids = [_primitive(rng, 1.0) for _ in range(int(rng.integers(2, 5)))]
    solid = m.Manifold.batch_boolean(solids, m.OpType.Add)
    parts = solid.decompose()
    if len(parts) > 1:  # Keep the shapes touching: the largest part (random pieces may miss it).
        solid = max(parts, key=lambda p: p.volume())
    return to_trimesh(solid)


def _bar(m, length: float, width: float, height: float, x: float, y: float):
    return m.Manifold.cube((length, width, height), center=True).translate((x, y, 0.0))


def _letter(rng: np.random.Generator, letter: str) -> trimesh.Trimesh:
    m = manifold()
    width, height = rng.uniform(0.15, 0.35), rng.uniform(0.12, 0.35)
    stem, arm = 1.0, rng.uniform(0.5, 1.0)
    first = _bar(m, stem, width, height, 0.0, 0.0)
    if letter == "L":
        second = _bar(m, width, arm, height, (stem - width) / 2.0, (arm - width) / 2.0)
    else:
        second = _bar(m, width, arm, height, 0.0, (arm + width) / 2.0 - 1e-3)
    return to_trimesh(first + second)


def _plate(rng: np.random.Generator) -> trimesh.Trimesh:
    m = manifold()
    return to_trimesh(m.Manifold.cube((1.0, rng.uniform(0.4, 1.0), 1.0), center=True))


def _ring(rng: np.random.Generator) -> trimesh.Trimesh:
    m = manifold()
    tube = rng.uniform(0.1, 0.22)
    section = m.CrossSection.circle(tube, CIRCULAR_SEGMENTS // 2).translate((0.5 - tube, 0.0))
    return to_trimesh(m.Manifold.revolve(section, CIRCULAR_SEGMENTS))


def _handle(rng: np.random.Generator) -> trimesh.Trimesh:
    m = manifold()
    radius, height = rng.uniform(0.25, 0.4), 1.0
    body = m.Manifold.cylinder(height, radius, circular_segments=CIRCULAR_SEGMENTS, center=True)
    tube, loop = rng.uniform(0.05, 0.09), rng.uniform(0.2, 0.3)
    section = m.CrossSection.circle(tube, CIRCULAR_SEGMENTS // 2).translate((loop, 0.0))
    torus = m.Manifold.revolve(section, CIRCULAR_SEGMENTS).rotate((90.0, 0.0, 0.0))
    return to_trimesh(body + torus.translate((radius, 0.0, 0.0)))


def novel_object(seed: int, index: int) -> NovelObject:
    """Object `index` of the generator with seed `seed`: its class cycles through CLASSES (so any 7
    consecutive indices cover them all); its shape and size are drawn from default_rng([seed, index])."""
    rng = np.random.default_rng([seed, index])
    shape_class = CLASSES[index % len(CLASSES)]
    if shape_class == "blob":
        mesh = _blob(rng)
    elif shape_class == "union":
        mesh = _union(rng)
    elif shape_class == "plate":
        mesh = _plate(rng)
    elif shape_class in ("L", "T"):
        mesh = _letter(rng, shape_class)
    elif shape_class == "ring":
        mesh = _ring(rng)
    else:
        mesh = _handle(rng)
    size = rng.uniform(*SIZE_RANGE)
    if shape_class == "plate":
        size = max(size, 0.08)  # a 6-12 mm plate smaller than 8 cm is a coin
    mesh.apply_translation(-mesh.bounds.mean(axis=0))
    mesh.apply_scale(size / float(np.max(mesh.extents)))
    if shape_class == "plate":
        thickness = rng.uniform(0.006, 0.012)
        mesh.apply_scale([1.0, 1.0, thickness / mesh.extents[2]])
    mesh.vertices = np.round(mesh.vertices, 6)  # What the file holds (µm), so volume/manifest agree.
    if mesh.volume < 0:
        mesh.invert()
    return NovelObject(f"{shape_class}_{seed}_{index:03d}", shape_class, seed, index, mesh)


def generate(count: int, seed: int, out_dir: str | Path) -> list[dict]:
    """Writes `count` objects (indices 0..count-1 of `seed`) as OBJ files into `out_dir`, with
    ``manifest.json`` and ``manifest.csv`` (one row per file). Returns the manifest rows."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for index in range(count):
        obj = novel_object(seed, index)
        file = f"{obj.name}.obj"
        (out_dir / file).write_text(obj_text(obj.mesh))
        rows.append(obj.manifest_row(file))
    (out_dir / "manifest.json").write_text(json.dumps(rows, indent=1) + "\n")
    with open(out_dir / "manifest.csv", "w", newline="") as f:
        fields = ["file", "class", "seed", "index", "size_m", "extents_m", "volume_m3", "faces", "convex"]
        writer = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({**row, "extents_m": " ".join(f"{e:.6f}" for e in row["extents_m"])})
    return rows
