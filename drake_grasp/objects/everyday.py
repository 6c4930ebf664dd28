"""A generator of everyday objects as users bring them: polycubes, scans, mugs, bottles and boxes,
written as a mesh or as a URDF model with a placeholder inertia.

Why: the novel classes (`objects.novel`) are abstract shapes: blobs, unions, letters, rings. The
files users bring to a grasping project are mostly other things: toy polycubes, scans of household
objects, mugs, bottles and cartons, often wrapped in a URDF whose inertia nobody filled in. This
generator draws such objects from a seed, so that the plain command can be measured on them without
tuning on any one file (`scripts/holding_study.py --objects everyday`).

The five classes (``CLASSES``), each a closed 2-manifold in metres:

* ``polycube``: 2-8 cubic cells of 2-5 cm joined face to face (a connected set grown cell by cell,
  mostly sideways, so most rest flat), 3-15 cm overall;
* ``scan``: a lumpy solid 5-14 cm across, cut flat where it stood on the scanner's table, its surface
  roughened by about a millimetre, as a scan's is;
* ``mug``: a hollow cylinder 6-10 cm across and 7-12 cm tall with a handle on its side;
* ``bottle``: a revolved profile 5-9 cm across and 12-24 cm tall: body, shoulder, neck and cap;
* ``box``: a carton 3-20 cm on each side, its narrower horizontal side at most 11 cm (what the
  BarrettHand spans), from a flat box to a cereal box standing up.

Every second object of a class (odd ``index // len(CLASSES)``) is written as a URDF naming its OBJ
mesh, with the placeholder inertial block exporters write (1 kg, a unit inertia matrix), which the
loader replaces by the geometry's (`objects.model_files`). Object ``i`` of seed ``s`` is drawn from
``numpy.random.default_rng([s, i])``: the same (seed, index) gives byte-identical files whatever the
count.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.generated import (CIRCULAR_SEGMENTS, manifold, one_link_urdf, placed_on_table,
                                          to_trimesh, write_generated, write_manifest)

CLASSES = ("polycube", "scan", "mug", "bottle", "box")
FORMATS = ("mesh", "urdf")
HAND_SPAN = 0.11  # m: the largest narrower horizontal side of a generated box (the hand's opening)

# The inertial block of a URDF whose author left the exporter's defaults (a placeholder).
PLACEHOLDER_INERTIAL = ('<inertial><origin xyz="0 0 0"/><mass value="1.0"/>'
                        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>')

# Growth directions of a polycube: sideways four times as often as up (a pile of cells that rests).
_STEPS = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]])
_STEP_WEIGHTS = np.array([4.0, 4.0, 4.0, 4.0, 2.0]) / 18.0


def _polycube(rng: np.random.Generator) -> trimesh.Trimesh:
    m = manifold()
    count = int(rng.integers(2, 9))
    cells = [(0, 0, 0)]
    while len(cells) < count:
        base = np.array(cells[int(rng.integers(len(cells)))])
        cell = tuple(int(v) for v in base + _STEPS[rng.choice(len(_STEPS), p=_STEP_WEIGHTS)])
        if cell not in cells:
            cells.append(cell)
    span = 1 + np.ptp(np.array(cells), axis=0).max()
    edge = float(np.clip(rng.uniform(0.02, 0.05), 0.03 / span, 0.15 / span))
    # Each cell overlaps its neighbours by 0.2 mm so that the union is one solid, not shells touching
    # along faces (a toy's cells are never exactly flush either).
    size = edge + 2e-4
    solid = m.Manifold.batch_boolean([m.Manifold.cube((size,) * 3, center=True).translate(tuple(edge * np.array(c)))
                                      for c in cells], m.OpType.Add)
    return to_trimesh(solid)


def _scan(rng: np.random.Generator) -> trimesh.Trimesh:
    sphere = trimesh.creation.icosphere(subdivisions=4, radius=1.0)
    directions = sphere.vertices
    radius = np.ones(len(directions))
    for _ in range(int(rng.integers(3, 7))):  # a few broad bumps and dents: the object's own shape
        centre = rng.normal(size=3)
        centre /= np.linalg.norm(centre)
        radius += rng.uniform(-0.25, 0.35) * np.exp(-(1.0 - directions @ centre) / rng.uniform(0.1, 0.4))
    size = rng.uniform(0.05, 0.14)
    axes = rng.uniform(0.55, 1.0, size=3) * size / 2.0
    lump = trimesh.Trimesh(directions * np.maximum(radius, 0.4)[:, None] * axes, sphere.faces, process=True)
    m = manifold()
    solid = m.Manifold(m.Mesh(vert_properties=np.asarray(lump.vertices, np.float32),
                              tri_verts=np.asarray(lump.faces, np.uint32)))
    cut = lump.bounds[0, 2] + rng.uniform(0.15, 0.3) * lump.extents[2]  # where it stood when scanned
    mesh = to_trimesh(solid.trim_by_plane((0.0, 0.0, 1.0), float(cut)))
    noise = rng.normal(scale=min(0.001, 0.01 * size), size=(len(mesh.vertices), 3))  # the scanner's noise
    return trimesh.Trimesh(mesh.vertices + noise, mesh.faces, process=True)


def _mug(rng: np.random.Generator) -> trimesh.Trimesh:
    m = manifold()
    radius, height, wall = rng.uniform(0.03, 0.05), rng.uniform(0.07, 0.12), rng.uniform(0.003, 0.006)
    outer = m.Manifold.cylinder(height, radius, circular_segments=CIRCULAR_SEGMENTS)
    inner = m.Manifold.cylinder(height, radius - wall, circular_segments=CIRCULAR_SEGMENTS).translate((0, 0, wall))
    tube, loop = rng.uniform(0.004, 0.007), rng.uniform(0.018, 0.03)
    section = m.CrossSection.circle(tube, CIRCULAR_SEGMENTS // 2).translate((loop, 0.0))
    handle = m.Manifold.revolve(section, CIRCULAR_SEGMENTS).rotate((90.0, 0.0, 0.0))
    handle = handle.translate((radius - 0.3 * loop, 0.0, height * rng.uniform(0.45, 0.6)))
    return to_trimesh((outer - inner) + handle)


def _bottle(rng: np.random.Generator) -> trimesh.Trimesh:
    radius, height = rng.uniform(0.025, 0.045), rng.uniform(0.12, 0.24)
    neck, shoulder = rng.uniform(0.009, 0.016), rng.uniform(0.6, 0.78) * height
    taper = height * rng.uniform(0.08, 0.15)
    profile = np.array([[0.0, 0.0], [radius * 0.95, 0.0], [radius, 0.004], [radius, shoulder],
                        [neck, shoulder + taper], [neck, height - 0.02], [neck * 1.15, height - 0.02],
                        [neck * 1.15, height], [0.0, height]])
    return trimesh.creation.revolve(profile, sections=CIRCULAR_SEGMENTS)


def _box(rng: np.random.Generator) -> trimesh.Trimesh:
    sides = np.sort(rng.uniform(0.03, 0.20, size=2))
    sides[0] = min(sides[0], HAND_SPAN)
    height = rng.uniform(0.03, 0.20)
    return trimesh.creation.box(extents=[sides[1], sides[0], height])


_GENERATORS = {"polycube": _polycube, "scan": _scan, "mug": _mug, "bottle": _bottle, "box": _box}


def everyday_object(seed: int, index: int) -> tuple[str, str, trimesh.Trimesh]:
    """(name, class, mesh resting on z = 0 and centred in x and y) of object `index` of seed `seed`:
    its class cycles through CLASSES (so any 5 consecutive indices cover them all)."""
    rng = np.random.default_rng([seed, index])
    shape_class = CLASSES[index % len(CLASSES)]
    mesh = _GENERATORS[shape_class](rng)
    placed_on_table(mesh, rng)
    return f"{shape_class}_{seed}_{index:03d}", shape_class, mesh


def format_of(index: int) -> str:
    """"mesh" or "urdf": every second object of a class is a URDF (module docstring)."""
    return FORMATS[(index // len(CLASSES)) % len(FORMATS)]


def urdf_text(name: str, mesh_file: str) -> str:
    """A one-link URDF naming `mesh_file` for its visual and collision, with a placeholder inertia."""
    return one_link_urdf(name, mesh_file, PLACEHOLDER_INERTIAL)


def generate(count: int, seed: int, out_dir: str | Path) -> list[dict]:
    """Writes `count` objects (indices 0..count-1 of `seed`) into `out_dir`, a URDF's mesh beside it,
    with ``manifest.json`` and ``manifest.csv``. Returns the manifest rows: "file" is what a user
    passes as ``--object``, "assets" the other files it needs."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for index in range(count):
        name, shape_class, mesh = everyday_object(seed, index)
        urdf = urdf_text(name, f"{name}.obj") if format_of(index) == "urdf" else None
        rows.append(write_generated(out_dir, name, mesh, shape_class, seed, index, urdf))
    write_manifest(out_dir, rows, ["file", "class", "format", "seed", "index", "size_m", "extents_m", "volume_m3"])
    return rows
