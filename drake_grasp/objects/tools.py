"""A generator of hand tools as users bring them: hammers, screwdrivers, spring clamps, markers and
wrenches, lying on the table as meshes or as URDFs with real, uneven masses.

Why: tools are a large part of the object sets users take from (YCB's hammer, clamps, screwdriver,
markers and wrench; OCRTOC's claw hammer, clamps, marker and stapler), and they are where the plain
command held least among the real files tried (docs/results/holding/real_files.md: thin or small,
1 of 8 first attempts on a fresh set). They are long and low, made of a thick part and a thin one
(a head and a handle, a handle and a shaft), and their mass sits where the steel is. None of the other
generators has such a shape: the novel L and T are slabs, the flower's sticks and pens are uniform
(`objects.flower`). This generator draws them from a seed, so that the plain command can be measured on
them without tuning on any one file (`scripts/holding_study.py --objects tools`).

The five classes (``CLASSES``), each a closed 2-manifold in metres, built with Manifold's booleans:

* ``hammer``: a handle 18-30 cm long, 2-3 cm wide and 1.8-2.6 cm thick, and across its end a steel
  head 8-13 cm long, 2.2-3.2 cm square, lying on its side;
* ``screwdriver``: a round or hexagonal handle 2.2-4 cm across and 7-12 cm long, and a steel shaft
  0.5-0.9 cm across and 5-15 cm long;
* ``clamp``: a spring clamp, two bars 8-15 cm long and 1.4-2.4 cm square crossing at 15-35° about a
  pivot 2.4-3.6 cm across;
* ``marker``: a round or hexagonal barrel 1.2-2.2 cm across and 10-15 cm long, a cap 0.5-3 mm wider
  over 3-6 cm of one end, and a conical or blunt point at the other;
* ``wrench``: an open-end spanner, a steel bar 12-25 cm long, 1.6-2.8 cm wide and 0.5-1 cm thick,
  with a slotted jaw 2.6-4.4 cm across at each end.

Each rests as it would when put down: on the stable face of its hull that puts its real centre of
mass lowest (`resting_transform`), then turned about the vertical by an angle from the seed. Every
second object of a class (odd ``index // len(CLASSES)``) is written as a URDF naming its OBJ, with
the real inertial block of its parts (steel 7850 kg/m³; wood or plastic handles 500-1300 kg/m³; a
marker's and a clamp's plastic, hollow, 300-700 kg/m³), so the centre of mass lies towards a hammer's
head and a screwdriver's shaft; the others are bare meshes, which the loader gives its default density. Object ``i`` of seed ``s`` is drawn from ``numpy.random.default_rng([s, i])``: the
same (seed, index) gives byte-identical files whatever the count.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.generated import (CIRCULAR_SEGMENTS, inertial_element, manifold, one_link_urdf,
                                          placed_on_table, to_trimesh, write_generated, write_manifest)

CLASSES = ("hammer", "screwdriver", "clamp", "marker", "wrench")
FORMATS = ("mesh", "urdf")
STEEL = 7850.0  # kg/m³
HANDLE_DENSITY = (500.0, 1300.0)  # kg/m³: wood to solid plastic
HOLLOW_PLASTIC = (300.0, 700.0)  # kg/m³: a marker's or a clamp's moulded shell, averaged over its solid


def _bar(length: float, width: float, thickness: float):
    """A Manifold box `length` along x from x = 0, centred in y and z (m)."""
    m = manifold()
    return m.Manifold.cube((length, width, thickness), center=True).translate((length / 2.0, 0.0, 0.0))


def _rod(length: float, radius: float, segments: int):
    """A Manifold prism of `segments` sides (a cylinder when many) of `radius`, along x from x = 0 (m)."""
    m = manifold()
    return m.Manifold.cylinder(length, radius, circular_segments=segments).rotate((0.0, 90.0, 0.0))


def _hammer(rng: np.random.Generator) -> list[tuple[object, float]]:
    length, width, thickness = rng.uniform(0.18, 0.30), rng.uniform(0.02, 0.03), rng.uniform(0.018, 0.026)
    head_length, head_side = rng.uniform(0.08, 0.13), rng.uniform(0.022, 0.032)
    m = manifold()
    head = m.Manifold.cube((head_side, head_length, max(head_side, thickness)), center=True)
    head = head.translate((length - head_side / 2.0, 0.0, 0.0))
    handle = _bar(length - head_side / 2.0, width, thickness) - head
    return [(handle, rng.uniform(*HANDLE_DENSITY)), (head, STEEL)]


def _screwdriver(rng: np.random.Generator) -> list[tuple[object, float]]:
    segments = CIRCULAR_SEGMENTS if rng.random() < 0.6 else 6
    handle_radius, handle_length = rng.uniform(0.011, 0.02), rng.uniform(0.07, 0.12)
    shaft_radius, shaft_length = rng.uniform(0.0025, 0.0045), rng.uniform(0.05, 0.15)
    handle = _rod(handle_length, handle_radius, segments)
    shaft = _rod(shaft_length + 0.01, shaft_radius, CIRCULAR_SEGMENTS // 2).translate((handle_length - 0.01, 0, 0))
    return [(handle, rng.uniform(*HANDLE_DENSITY)), (shaft - handle, STEEL)]


def _clamp(rng: np.random.Generator) -> list[tuple[object, float]]:
    length, side = rng.uniform(0.08, 0.15), rng.uniform(0.014, 0.024)
    angle, pivot = rng.uniform(15.0, 35.0), rng.uniform(0.012, 0.018)
    m = manifold()
    front = rng.uniform(0.2, 0.35) * length  # the jaws' length in front of the pivot
    bars = [_bar(length, side, side).translate((-front, 0.0, 0.0)).rotate((0.0, 0.0, sign * angle / 2.0))
            for sign in (1.0, -1.0)]
    hub = m.Manifold.cylinder(side * 1.2, pivot, circular_segments=CIRCULAR_SEGMENTS, center=True)
    return [(bars[0] + bars[1] + hub, rng.uniform(*HOLLOW_PLASTIC))]


def _marker(rng: np.random.Generator) -> list[tuple[object, float]]:
    m = manifold()
    segments = CIRCULAR_SEGMENTS if rng.random() < 0.7 else 6
    radius, length = rng.uniform(0.006, 0.011), rng.uniform(0.10, 0.15)
    cap_radius, cap_length = radius + rng.uniform(0.0005, 0.003), rng.uniform(0.03, 0.06)
    point = rng.uniform(0.008, 0.02)
    barrel = _rod(length, radius, segments)
    cap = _rod(cap_length, cap_radius, CIRCULAR_SEGMENTS).translate((length - cap_length, 0.0, 0.0))
    tip_radius = radius * (0.25 if rng.random() < 0.6 else 0.8)  # a pen's cone, or a chisel marker's stub
    tip = m.Manifold.cylinder(point, radius, tip_radius, circular_segments=CIRCULAR_SEGMENTS)
    tip = tip.rotate((0.0, -90.0, 0.0))  # from x = 0 towards -x, narrowing
    return [(barrel + cap + tip, rng.uniform(*HOLLOW_PLASTIC))]


def _wrench(rng: np.random.Generator) -> list[tuple[object, float]]:
    m = manifold()
    length, width, thickness = rng.uniform(0.12, 0.25), rng.uniform(0.016, 0.028), rng.uniform(0.005, 0.01)
    solid = _bar(length, width, thickness)
    for end, sign in ((0.0, -1.0), (length, 1.0)):
        jaw_radius = rng.uniform(0.013, 0.022)
        slot = rng.uniform(0.45, 0.7) * jaw_radius * 2.0 * 0.6
        disc = m.Manifold.cylinder(thickness, jaw_radius, circular_segments=CIRCULAR_SEGMENTS, center=True)
        cut = m.Manifold.cube((jaw_radius * 2.0, slot, thickness * 2.0), center=True)
        cut = cut.translate((sign * jaw_radius * 0.9, 0.0, 0.0))
        solid = solid + (disc - cut).translate((end + sign * jaw_radius * 0.6, 0.0, 0.0))
    return [(solid, STEEL)]


_GENERATORS = {"hammer": _hammer, "screwdriver": _screwdriver, "clamp": _clamp, "marker": _marker,
               "wrench": _wrench}


def _mass_properties(parts: list[tuple[trimesh.Trimesh, float]]) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass kg, centre of mass m, inertia kg·m² about it) of disjoint `parts` (mesh, density kg/m³)."""
    masses = [mesh.volume * density for mesh, density in parts]
    total = float(sum(masses))
    com = sum(mass * mesh.center_mass for (mesh, _), mass in zip(parts, masses)) / total
    inertia = np.zeros((3, 3))
    for (mesh, density), mass in zip(parts, masses):
        d = mesh.center_mass - com
        inertia += mesh.moment_inertia * density / mesh.density + mass * (d @ d * np.eye(3) - np.outer(d, d))
    return total, com, inertia


def tool_object(seed: int, index: int) -> tuple[str, str, trimesh.Trimesh, tuple[float, np.ndarray, np.ndarray]]:
    """(name, class, mesh resting on z = 0 and centred in x and y, (mass kg, centre of mass m, inertia
    kg·m² about it) in the mesh's frame) of object `index` of seed `seed`: its class cycles through
    CLASSES (so any 5 consecutive indices cover them all)."""
    rng = np.random.default_rng([seed, index])
    shape_class = CLASSES[index % len(CLASSES)]
    parts = [(to_trimesh(solid), density) for solid, density in _GENERATORS[shape_class](rng)]
    m = manifold()
    # The union of the parts as meshes (float32 vertices), not of the solids they came from: the two
    # differ in the last digits, and the studies' objects are these bytes.
    whole = to_trimesh(m.Manifold.batch_boolean([
        m.Manifold(m.Mesh(vert_properties=np.asarray(p.vertices, np.float32), tri_verts=np.asarray(p.faces, np.uint32)))
        for p, _ in parts], m.OpType.Add))
    mass, com, _ = _mass_properties(parts)
    before = whole.vertices.copy()
    whole.apply_transform(resting_transform(whole, com))
    placed_on_table(whole, rng)
    # The same rigid motion for the parts: solve it from the whole's vertices (rotation and shift).
    motion = _rigid_motion(before, whole.vertices)
    for part, _ in parts:
        part.apply_transform(motion)
    return f"{shape_class}_{seed}_{index:03d}", shape_class, whole, _mass_properties(parts)


def resting_transform(mesh: trimesh.Trimesh, com: np.ndarray) -> np.ndarray:
    """The 4 × 4 rotation that sets `mesh` down on its stable face with the lowest centre of mass.

    A face of the convex hull is stable when `com` (m), dropped onto its plane, falls inside it; of
    those, the one nearest the centre of mass is where a tool put down on a table comes to rest (a
    hammer on its side, not on its head's end)."""
    hull = mesh.convex_hull
    grouped = {int(f) for facet in hull.facets for f in facet}
    groups = [list(facet) for facet in hull.facets] + [[f] for f in range(len(hull.faces)) if f not in grouped]
    best, best_height = None, math.inf
    for faces in groups:
        normal = hull.face_normals[faces[0]]
        height = float(normal @ (hull.vertices[hull.faces[faces[0], 0]] - com))
        foot = com + height * normal
        triangles = hull.triangles[faces]
        inside = trimesh.triangles.points_to_barycentric(triangles, np.repeat(foot[None], len(faces), axis=0))
        if height < best_height and np.any(np.all(inside >= -1e-9, axis=1)):
            best, best_height = normal, height
    return trimesh.geometry.align_vectors(best, [0.0, 0.0, -1.0])


def _rigid_motion(before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """The 4 × 4 rigid transform taking points `before` to `after` (least squares; exact up to the µm
    rounding of `placed_on_table`)."""
    a0, b0 = before.mean(axis=0), after.mean(axis=0)
    u, _, vt = np.linalg.svd((before - a0).T @ (after - b0))
    d = np.sign(np.linalg.det(vt.T @ u.T))
    rotation = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
    motion = np.eye(4)
    motion[:3, :3], motion[:3, 3] = rotation, b0 - rotation @ a0
    return motion


def format_of(index: int) -> str:
    """"mesh" or "urdf": every second object of a class is a URDF (module docstring)."""
    return FORMATS[(index // len(CLASSES)) % len(FORMATS)]


def urdf_text(name: str, mesh_file: str, mass: float, com: np.ndarray, inertia: np.ndarray) -> str:
    """A one-link URDF naming `mesh_file`, with the tool's real `mass` (kg), centre of mass `com` (m) and
    `inertia` about it (kg·m²)."""
    return one_link_urdf(name, mesh_file, inertial_element(mass, com, inertia))


def generate(count: int, seed: int, out_dir: str | Path) -> list[dict]:
    """Objects 0..count-1 of `seed` written into `out_dir` (`generated.write_generated`: a URDF beside
    its mesh) with their manifest; returns its rows, each with the URDF's mass ("mass_kg", None for a
    bare mesh)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for index in range(count):
        name, shape_class, mesh, (mass, com, inertia) = tool_object(seed, index)
        urdf = urdf_text(name, f"{name}.obj", mass, com, inertia) if format_of(index) == "urdf" else None
        rows.append(write_generated(out_dir, name, mesh, shape_class, seed, index, urdf,
                                    mass_kg=None if urdf is None else round(mass, 6)))
    write_manifest(out_dir, rows, ["file", "class", "format", "seed", "index", "size_m", "extents_m", "volume_m3",
                                   "mass_kg"])
    return rows
