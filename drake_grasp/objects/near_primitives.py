"""A seeded generator of near-primitives: objects that are almost a sphere, a box or a cylinder.

The shape-resemblance primitives (`drake_grasp.primitives.scores`) are meant to name an object's
closest primitive; household objects are never perfect primitives. This generator makes the small
departures a real sphere, box or cylinder has, each a closed, convex 2-manifold in metres resting
stably on the table with its z up (the file's pose is its resting pose), at a random yaw:

=================== ========= ==============================================================
class               primitive  parameters (uniform draws)
=================== ========= ==============================================================
``ellipsoid``       sphere     radius r: diameter 2r in ``SPHERE_DIAMETER`` (6-12 cm); semi-axes
                               r·(1 + uᵢ), uᵢ in ±``ELLIPSOID_DEVIATION`` (±10 %), sorted so that
                               the vertical one is the smallest (the pose it rests in)
``rounded_box``     box        sides in ``BOX_SIDE`` (5-12 cm); every edge and corner rounded
                               with radius ρ = f · the smallest side, f in ``BOX_FILLET`` (5-20 %)
``tapered_cylinder`` cylinder  mean diameter D in ``CYLINDER_DIAMETER`` (5-8 cm), length
                               k·D, k in ``CYLINDER_ASPECT`` (2-3.5); end radii r(1 ± t/2), t in
                               ``CYLINDER_TAPER`` (5-15 %: the ends' radii differ by t of the mean);
                               lying on its side, on one of its side facets
``rounded_cylinder`` cylinder  D and k as above; the side bulges by b in ``CYLINDER_BULGE``
                               (0-8 % of the radius, a parabola peaking mid-length); the end
                               edges rounded with radius ρ = g · r, g in ``CYLINDER_END_FILLET``
                               (10-30 %); lying on its side
=================== ========= ==============================================================

``perfect`` meshes (`perfect_mesh`) are the same constructions with no departure (u = 0, f = 0,
t = 0, b = g = 0): the generator's own controls, tessellated and loaded exactly like the others, so
that a study can tell the shape's departure from what tessellation and the object pipeline do to any
mesh (a convex mesh is rendered as its hull of at most 64 vertices: `drake_grasp.objects.piece_budget`).

Every shape is the convex hull of points on its surface (trimesh), so it is watertight by
construction; the cylinders' side is a prism of ``CYLINDER_SEGMENTS`` facets with one facet facing
straight down, tilted for the tapered one so that facet is horizontal: each rests on a face and
passes the object loader's stability check without being turned over.

Determinism: object ``i`` of seed ``s`` is drawn from ``numpy.random.default_rng([s, i, 15])`` (15:
this generator, so its draws differ from `geometry.novel`'s for the same seed), classes cycle
through `CLASSES` with the index, and vertices are written with a fixed format (µm): the same (seed,
index) gives a byte-identical file whatever `count` is.
"""

from __future__ import annotations

import csv
import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.generated import obj_text

CLASSES = ("ellipsoid", "rounded_box", "tapered_cylinder", "rounded_cylinder")
PRIMITIVE_OF_CLASS = {"ellipsoid": "sphere", "rounded_box": "box", "tapered_cylinder": "cylinder",
                      "rounded_cylinder": "cylinder"}
GENERATOR_TAG = 15  # the third word of every draw's seed (issue 15): see the module docstring

SPHERE_DIAMETER = (0.06, 0.12)  # m, 2r of the ellipsoid's common radius
ELLIPSOID_DEVIATION = 0.10  # each semi-axis within ±10 % of the common radius
BOX_SIDE = (0.05, 0.12)  # m, each side
BOX_FILLET = (0.05, 0.20)  # fillet radius over the smallest side
CYLINDER_DIAMETER = (0.05, 0.08)  # m, mean diameter
CYLINDER_ASPECT = (2.0, 3.5)  # length over mean diameter
CYLINDER_TAPER = (0.05, 0.15)  # (r_big - r_small) / r_mean
CYLINDER_BULGE = (0.0, 0.08)  # extra radius at mid-length over the end radius
CYLINDER_END_FILLET = (0.10, 0.30)  # end-edge fillet radius over the radius

CYLINDER_SEGMENTS = 32  # side facets of a cylinder (two rings of 32: within the 64-vertex piece budget)
SPHERE_SUBDIVISIONS = 3  # icosphere subdivisions of an ellipsoid (642 points) and of a box corner (2: 162)


@dataclasses.dataclass(frozen=True)
class NearPrimitive:
    """One generated object: its mesh (metres), its class and primitive, and the drawn parameters."""

    name: str
    shape_class: str
    seed: int
    index: int
    params: dict
    mesh: trimesh.Trimesh

    @property
    def primitive(self) -> str:
        return PRIMITIVE_OF_CLASS[self.shape_class]

    def manifest_row(self, file: str) -> dict:
        return {
            "file": file,
            "class": self.shape_class,
            "primitive": self.primitive,
            "seed": self.seed,
            "index": self.index,
            "params": self.params,
            "extents_m": [round(float(e), 6) for e in self.mesh.extents],
            "volume_m3": float(f"{self.mesh.volume:.6e}"),
            "faces": int(len(self.mesh.faces)),
        }


# --- Shapes (pure: parameters -> a convex, watertight mesh centred at the origin) --------------------


def _hull(points: np.ndarray) -> trimesh.Trimesh:
    hull = trimesh.convex.convex_hull(np.asarray(points, float))
    hull.fix_normals()
    return hull


def ellipsoid_mesh(semi_axes) -> trimesh.Trimesh:
    """An ellipsoid with semi-axes (a, b, c) along x, y, z (m)."""
    unit = trimesh.creation.icosphere(subdivisions=SPHERE_SUBDIVISIONS, radius=1.0).vertices
    return _hull(unit * np.asarray(semi_axes, float))


def rounded_box_mesh(sides, fillet: float) -> trimesh.Trimesh:
    """A box of outer sides (x, y, z) (m) whose edges and corners are rounded with radius `fillet`
    (the Minkowski sum of a smaller box and a ball: the hull of a ball at each inner corner). A
    fillet of 0 gives the sharp box."""
    sides = np.asarray(sides, float)
    if not 0.0 <= fillet < 0.5 * float(sides.min()):
        raise ValueError(f"fillet {fillet} must be in [0, half the smallest side {0.5 * sides.min()})")
    half = sides / 2.0 - fillet
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float) * half
    if fillet == 0.0:
        return _hull(corners)
    ball = trimesh.creation.icosphere(subdivisions=SPHERE_SUBDIVISIONS - 1, radius=fillet).vertices
    return _hull((corners[:, None, :] + ball[None, :, :]).reshape(-1, 3))


def _ring_angles(segments: int) -> np.ndarray:
    """Angles (about the axis, from +z) of a ring's vertices, one facet centred on −z (facing down)."""
    return -math.pi / 2.0 + math.pi / segments + 2.0 * math.pi * np.arange(segments) / segments


def revolved_mesh(profile, segments: int = CYLINDER_SEGMENTS) -> trimesh.Trimesh:
    """The convex solid whose radius about the x axis at x is given by `profile` [(x, r), ...] (r ≥ 0,
    a concave profile), with `segments` facets around, one of them facing straight down (−z)."""
    theta = _ring_angles(segments)
    points = []
    for x, r in profile:
        if r <= 0.0:
            points.append([[x, 0.0, 0.0]])
        else:
            points.append(np.column_stack([np.full(segments, x), r * np.sin(theta), r * np.cos(theta)]))
    return _hull(np.vstack(points))


def tapered_cylinder_mesh(length: float, radius_big: float, radius_small: float,
                          segments: int = CYLINDER_SEGMENTS) -> trimesh.Trimesh:
    """A frustum along x (the big end at −x) lying on its side: tilted about y so that its
    downward side facet is horizontal (it rests on that facet, not on an end's rim)."""
    mesh = revolved_mesh([(-length / 2.0, radius_big), (length / 2.0, radius_small)], segments)
    drop = (radius_big - radius_small) * math.cos(math.pi / segments)  # the bottom facet's rise along x
    tilt = math.atan2(drop, length)
    mesh.apply_transform(trimesh.transformations.rotation_matrix(tilt, [0.0, 1.0, 0.0]))
    return mesh


def rounded_cylinder_mesh(length: float, radius: float, bulge: float, end_fillet: float,
                          segments: int = CYLINDER_SEGMENTS, rings: int = 7) -> trimesh.Trimesh:
    """A cylinder along x of end radius `radius` whose side bulges by `bulge`·radius at mid-length (a
    parabola over the straight part) and whose end edges are rounded with radius
    `end_fillet`·radius (a quarter circle in the profile; the ends are flat discs of radius
    (1 − end_fillet)·radius). The solid is the convex hull of these rings."""
    half = length / 2.0
    rho = end_fillet * radius
    straight = half - rho
    profile = [(x, radius * (1.0 + bulge * (1.0 - (x / straight) ** 2)))
               for x in np.linspace(-straight, straight, rings)]
    if rho > 0.0:
        quarter = [(rho * math.sin(a), radius - rho + rho * math.cos(a))
                   for a in np.linspace(0.0, math.pi / 2.0, 5)[1:]]
        profile = ([(-straight - dx, r) for dx, r in reversed(quarter)] + profile
                   + [(straight + dx, r) for dx, r in quarter])
    return revolved_mesh(profile, segments)


# --- The draws ---------------------------------------------------------------------------------------


def draw_parameters(shape_class: str, rng: np.random.Generator) -> dict:
    """The parameters of one object of `shape_class` (see the module docstring), as plain floats."""
    u = lambda low_high: float(rng.uniform(*low_high))  # noqa: E731
    if shape_class == "ellipsoid":
        radius = u(SPHERE_DIAMETER) / 2.0
        deviations = rng.uniform(-ELLIPSOID_DEVIATION, ELLIPSOID_DEVIATION, size=3)
        semi = sorted((radius * (1.0 + deviations)).tolist(), reverse=True)  # z: the smallest
        return {"radius": radius, "semi_axes": semi, "yaw_deg": u((0.0, 180.0))}
    if shape_class == "rounded_box":
        sides = [u(BOX_SIDE) for _ in range(3)]
        fraction = u(BOX_FILLET)
        return {"sides": sides, "fillet_fraction": fraction, "fillet": fraction * min(sides),
                "yaw_deg": u((0.0, 180.0))}
    diameter, aspect = u(CYLINDER_DIAMETER), u(CYLINDER_ASPECT)
    params = {"diameter": diameter, "length": aspect * diameter, "aspect": aspect}
    if shape_class == "tapered_cylinder":
        taper = u(CYLINDER_TAPER)
        params.update(taper=taper, radius_big=diameter / 2.0 * (1.0 + taper / 2.0),
                      radius_small=diameter / 2.0 * (1.0 - taper / 2.0))
    elif shape_class == "rounded_cylinder":
        params.update(bulge=u(CYLINDER_BULGE), end_fillet=u(CYLINDER_END_FILLET))
    else:
        raise ValueError(f"unknown near-primitive class {shape_class!r}; expected one of {CLASSES}")
    params["yaw_deg"] = u((0.0, 180.0))
    return params


def shape_mesh(shape_class: str, params: dict) -> trimesh.Trimesh:
    """The mesh of `shape_class` with `params` (before yaw and placement)."""
    if shape_class == "ellipsoid":
        return ellipsoid_mesh(params["semi_axes"])
    if shape_class == "rounded_box":
        return rounded_box_mesh(params["sides"], params["fillet"])
    if shape_class == "tapered_cylinder":
        return tapered_cylinder_mesh(params["length"], params["radius_big"], params["radius_small"])
    if shape_class == "rounded_cylinder":
        return rounded_cylinder_mesh(params["length"], params["diameter"] / 2.0, params["bulge"],
                                     params["end_fillet"])
    raise ValueError(f"unknown near-primitive class {shape_class!r}; expected one of {CLASSES}")


def _finish(mesh: trimesh.Trimesh, yaw_deg: float) -> trimesh.Trimesh:
    """Yawed about z, centred over the origin with its lowest point at z = 0 − half its height (the
    bounding box centred at the origin), vertices rounded to µm as the file holds them."""
    mesh = mesh.copy()
    mesh.apply_transform(trimesh.transformations.rotation_matrix(math.radians(yaw_deg), [0.0, 0.0, 1.0]))
    mesh.apply_translation(-mesh.bounds.mean(axis=0))
    mesh.vertices = np.round(mesh.vertices, 6)
    if mesh.volume < 0:
        mesh.invert()
    return mesh


def near_primitive(seed: int, index: int) -> NearPrimitive:
    """Object `index` of seed `seed`: class CLASSES[index % 4], parameters from
    default_rng([seed, index, GENERATOR_TAG])."""
    if seed < 0 or index < 0:
        raise ValueError(f"seed and index must be >= 0, got {seed}, {index}")
    rng = np.random.default_rng([seed, index, GENERATOR_TAG])
    shape_class = CLASSES[index % len(CLASSES)]
    params = draw_parameters(shape_class, rng)
    mesh = _finish(shape_mesh(shape_class, params), params["yaw_deg"])
    return NearPrimitive(f"{shape_class}_{seed}_{index:03d}", shape_class, seed, index, params, mesh)


PERFECT = {
    # The controls (no departure), of sizes in the middle of the ranges above.
    "ellipsoid": {"radius": 0.045, "semi_axes": [0.045, 0.045, 0.045], "yaw_deg": 0.0},
    "rounded_box": {"sides": [0.10, 0.07, 0.06], "fillet_fraction": 0.0, "fillet": 0.0, "yaw_deg": 0.0},
    "tapered_cylinder": {"diameter": 0.065, "length": 0.18, "aspect": 0.18 / 0.065, "taper": 0.0,
                         "radius_big": 0.0325, "radius_small": 0.0325, "yaw_deg": 0.0},
}


def perfect_mesh(shape_class: str) -> NearPrimitive:
    """The perfect member of a class (`PERFECT`): a tessellated sphere, sharp box or straight cylinder."""
    params = PERFECT[shape_class]
    mesh = _finish(shape_mesh(shape_class, params), params["yaw_deg"])
    name = {"ellipsoid": "perfect_sphere", "rounded_box": "perfect_box", "tapered_cylinder": "perfect_cylinder"}
    return NearPrimitive(name[shape_class], shape_class, -1, -1, params, mesh)


def write(obj: NearPrimitive, out_dir: str | Path) -> dict:
    """Writes obj as ``out_dir/<name>.obj`` (fixed format); returns its manifest row."""
    file = f"{obj.name}.obj"
    Path(out_dir, file).write_text(obj_text(obj.mesh))
    return obj.manifest_row(file)


def generate(count: int, seed: int, out_dir: str | Path, perfect: bool = False) -> list[dict]:
    """Writes `count` near-primitives (indices 0..count-1 of `seed`; classes in turn) as OBJ files
    into `out_dir` with ``manifest.json`` and ``manifest.csv``; with `perfect`, the three perfect
    meshes too. Returns the manifest rows."""
    if count < 0:
        raise ValueError(f"count must be >= 0, got {count}")
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = [write(near_primitive(seed, i), out_dir) for i in range(count)]
    if perfect:
        rows += [write(perfect_mesh(c), out_dir) for c in PERFECT]
    (out_dir / "manifest.json").write_text(json.dumps(rows, indent=1) + "\n")
    with open(out_dir / "manifest.csv", "w", newline="") as f:
        fields = ["file", "class", "primitive", "seed", "index", "extents_m", "volume_m3", "faces", "params"]
        writer = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({**row, "extents_m": " ".join(f"{e:.6f}" for e in row["extents_m"]),
                             "params": json.dumps(row["params"], sort_keys=True)})
    return rows
