"""A zoo of defective object files, one generator per kind of defect a real mesh or model file has.

Why: object files from scans, CAD exports, convex-decomposition tools and robot-learning benchmarks
are rarely the clean closed 2-manifold a textbook assumes. Each generator here produces, from a seed,
a file with one class of defect on a random base shape, and says what a loader should do with it:
accept it as it is, accept it after a repair (and say so), or refuse it for a stated reason. The
tests load every case; scripts/bench_repair.py measures repair libraries on the same cases.

The classes (``CLASSES``):

* cells sharing faces (a solid stored as closed convex cells, as fracture and voxel tools write it);
* a hollow object (an inner wall wound inward);
* hull sets with 0.5-2 mm gaps (a convex decomposition written as one file);
* overlapping shells (CAD exports: a handle's shell running into a body's);
* a polycube of flush cells that meet along edges only (edges of four faces);
* open caps, holes, non-manifold edges, flipped faces, duplicated faces, internal faces, degenerate
  triangles (scans, visual meshes, hand-edited files), and all of these at once in a triangle soup;
* seams left open at T-junctions (CAD exports that refined one part and not the part it meets);
* a millimetre file; truly separate parts, an open sheet and a point cloud (refused);
* URDF and MJCF models with placeholder inertias, an MJCF naming an STL mesh, a glTF binary.

Every mesh is in metres unless the case says otherwise; the same seed gives the same files.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import trimesh


@dataclasses.dataclass(frozen=True)
class ZooCase:
    """One generated file and what loading it should do.

    Attributes:
        name: the case's name (its class and seed).
        defect: the class of defect (one of ``CLASSES``).
        path: the file a user would pass as ``--object``.
        verdict: "accepted" (loads as it is), "repaired" (loads after a repair, with a note) or
            "refused" (an input error naming `reason`).
        reason: for a refused case, a phrase the error must contain; for an accepted one, a phrase
            the notes must contain ("" for none).
        volume: the volume (m³) of the solid the file describes, or None when it is not known
            in closed form (the loader's volume is compared with it).
        scale: the --scale the case is loaded with.
        volume_tolerance: how far (a fraction) the loaded volume may honestly be from `volume`.
    """

    name: str
    defect: str
    path: Path
    verdict: str
    reason: str = ""
    volume: float | None = None
    scale: float = 1.0
    volume_tolerance: float = 0.02


def _rng(seed: int, salt: str) -> np.random.Generator:
    return np.random.default_rng([seed, sum(map(ord, salt))])


def _base_convex(rng: np.random.Generator) -> trimesh.Trimesh:
    """A random convex solid 4-12 cm across: a box, a cylinder, an ellipsoid or a random hull."""
    kind = rng.integers(4)
    size = rng.uniform(0.04, 0.12, size=3)
    if kind == 0:
        return trimesh.creation.box(size)
    if kind == 1:
        return trimesh.creation.cylinder(radius=size[0] / 2, height=size[2], sections=32)
    if kind == 2:
        sphere = trimesh.creation.icosphere(subdivisions=3)
        sphere.apply_scale(size / 2)
        return sphere
    points = rng.normal(size=(40, 3)) * size / 4
    return trimesh.convex.convex_hull(points)


def _half(cell: trimesh.Trimesh, origin: np.ndarray, normal: np.ndarray) -> trimesh.Trimesh | None:
    """The part of a convex cell on the positive side of a plane: the hull of its vertices there
    and of its edges' crossings (both halves share those crossings, so they touch exactly)."""
    d = (cell.vertices - origin) @ normal
    edges = cell.edges_unique
    da, db = d[edges[:, 0]], d[edges[:, 1]]
    crossing = (da * db) < 0
    t = da[crossing] / (da[crossing] - db[crossing])
    a, b = cell.vertices[edges[crossing, 0]], cell.vertices[edges[crossing, 1]]
    points = np.vstack([cell.vertices[d > 0], a + t[:, None] * (b - a)])
    if len(points) < 4:
        return None
    try:
        half = trimesh.convex.convex_hull(points)
    except Exception:  # qhull: the points span no volume
        return None
    return half if half.volume > 1e-3 * cell.volume else None


def _cells(mesh: trimesh.Trimesh, rng: np.random.Generator, count: int) -> list[trimesh.Trimesh]:
    """A convex mesh cut by random planes through its interior into closed convex cells."""
    cells = [mesh]
    for _ in range(20 * count):
        if len(cells) >= count:
            break
        index = int(np.argmax([cell.volume for cell in cells]))
        cell = cells.pop(index)
        normal = rng.normal(size=3)
        normal /= np.linalg.norm(normal)
        origin = cell.center_mass + rng.uniform(-0.2, 0.2) * (cell.extents @ np.abs(normal)) * normal
        halves = [_half(cell, origin, sign * normal) for sign in (1.0, -1.0)]
        if any(half is None for half in halves):
            cells.append(cell)
            continue
        cells.extend(halves)
    return cells


def _concatenate(meshes) -> trimesh.Trimesh:
    return trimesh.util.concatenate([trimesh.Trimesh(m.vertices, m.faces, process=False) for m in meshes])


def _write(mesh: trimesh.Trimesh, path: Path) -> Path:
    mesh.export(path)
    return path


def _remove_faces(mesh: trimesh.Trimesh, drop: np.ndarray) -> trimesh.Trimesh:
    keep = np.ones(len(mesh.faces), dtype=bool)
    keep[drop] = False
    return trimesh.Trimesh(mesh.vertices, mesh.faces[keep], process=False)


def shared_faces(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "shared_faces")
    base = _base_convex(rng)
    cells = _cells(base, rng, int(rng.integers(2, 7)))
    path = _write(_concatenate(cells), out / f"shared_faces_{seed}.obj")
    return ZooCase(path.stem, "shared_faces", path, "accepted", "", float(base.volume))


def hull_gaps(out: Path, seed: int) -> ZooCase:
    """Convex cells moved apart so that neighbours are 0.5-2 mm apart (a decomposition's output)."""
    rng = _rng(seed, "hull_gaps")
    base = _base_convex(rng)
    cells = _cells(base, rng, int(rng.integers(3, 8)))
    gap = rng.uniform(0.0005, 0.002)
    centre = base.center_mass
    moved = []
    for cell in cells:
        direction = cell.center_mass - centre
        norm = np.linalg.norm(direction)
        cell = cell.copy()
        if norm > 1e-9:
            cell.apply_translation(0.5 * gap * direction / norm)
        moved.append(cell)
    path = _write(_concatenate(moved), out / f"hull_gaps_{seed}.obj")
    return ZooCase(path.stem, "hull_gaps", path, "accepted", "", float(base.volume))


def overlapping(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "overlapping")
    body = trimesh.creation.box(rng.uniform(0.04, 0.09, size=3))
    handle = trimesh.creation.cylinder(radius=rng.uniform(0.008, 0.015), height=rng.uniform(0.08, 0.14),
                                       sections=24)
    handle.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    handle.apply_translation([body.extents[0] / 2, 0.0, rng.uniform(-0.01, 0.01)])
    volume = float(body.union(handle, engine="manifold").volume)
    path = _write(_concatenate([body, handle]), out / f"overlapping_{seed}.stl")
    return ZooCase(path.stem, "overlapping", path, "accepted", "", volume)


def open_caps(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "open_caps")
    radius, height = rng.uniform(0.02, 0.05), rng.uniform(0.05, 0.15)
    cylinder = trimesh.creation.cylinder(radius=radius, height=height, sections=32)
    caps = np.flatnonzero(np.abs(cylinder.face_normals[:, 2]) > 0.99)
    top = caps[cylinder.triangles_center[caps, 2] > 0]
    drop = caps if rng.random() < 0.5 else top
    path = _write(_remove_faces(cylinder, drop), out / f"open_caps_{seed}.stl")
    return ZooCase(path.stem, "open_caps", path, "repaired", "repaired", float(cylinder.volume))


def holes(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "holes")
    sphere = trimesh.creation.icosphere(subdivisions=3)
    sphere.apply_scale(rng.uniform(0.03, 0.06, size=3))
    centres = sphere.triangles_center
    drop = []
    for _ in range(int(rng.integers(1, 4))):
        seed_face = int(rng.integers(len(sphere.faces)))
        distances = np.linalg.norm(centres - centres[seed_face], axis=1)
        drop.extend(np.argsort(distances)[: int(rng.integers(1, 8))])
    path = _write(_remove_faces(sphere, np.unique(drop)), out / f"holes_{seed}.ply")
    return ZooCase(path.stem, "holes", path, "repaired", "repaired", float(sphere.volume))


def non_manifold(out: Path, seed: int) -> ZooCase:
    """A closed solid with a stray fin on one of its edges (an edge of three faces), and a second
    closed solid that meets the first along a single edge."""
    rng = _rng(seed, "non_manifold")
    size = rng.uniform(0.03, 0.06)
    a = trimesh.creation.box([size] * 3)
    b = trimesh.creation.box([size] * 3)
    b.apply_translation([size, size, 0.0])  # shares the edge x = y = size/2 with a
    mesh = _concatenate([a, b])
    mesh.merge_vertices()
    edge = mesh.edges_unique[int(rng.integers(len(mesh.edges_unique)))]
    tip = mesh.vertices[edge].mean(axis=0) + np.array([0.0, 0.0, 0.0])
    tip = tip + rng.normal(size=3) * 0.002 + (tip - mesh.centroid) * 0.3
    vertices = np.vstack([mesh.vertices, tip])
    faces = np.vstack([mesh.faces, [[edge[0], edge[1], len(vertices) - 1]]])
    path = _write(trimesh.Trimesh(vertices, faces, process=False), out / f"non_manifold_{seed}.obj")
    return ZooCase(path.stem, "non_manifold", path, "repaired", "", 2 * size**3)


# Steps between cells of a pinched polycube: across a face, or diagonally in a plane (the two cells
# then meet along an edge only).
_FACE_STEPS = [np.array(v) for v in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1))]
_EDGE_STEPS = [np.array(v) for v in ((1, 1, 0), (1, -1, 0), (-1, 1, 0), (-1, -1, 0), (1, 0, 1), (-1, 0, 1),
                                     (0, 1, 1), (0, -1, 1), (1, 0, -1), (-1, 0, -1), (0, 1, -1), (0, -1, -1))]


def pinched(out: Path, seed: int) -> ZooCase:
    """A polycube of flush cells some of which meet along an edge only (an edge of four faces once its
    vertices are welded), as a voxel or CAD tool writes it: the cells' union on even seeds, each cell
    a closed cube of its own on odd seeds, both as an STL triangle soup."""
    from drake_grasp.objects.generated import manifold, to_trimesh

    rng = _rng(seed, "pinched")
    edge = float(rng.uniform(0.02, 0.04))
    cells = [np.zeros(3, int), _EDGE_STEPS[int(rng.integers(len(_EDGE_STEPS)))]]  # one pinch at least
    while len(cells) < int(rng.integers(3, 8)):
        steps = _EDGE_STEPS if rng.random() < 0.4 else _FACE_STEPS
        cell = cells[int(rng.integers(len(cells)))] + steps[int(rng.integers(len(steps)))]
        if not any(np.array_equal(cell, c) for c in cells):
            cells.append(cell)
    if seed % 2 == 0:
        m = manifold()
        union = m.Manifold.batch_boolean([m.Manifold.cube((edge,) * 3, center=True).translate(tuple(edge * c))
                                          for c in cells], m.OpType.Add)
        mesh = to_trimesh(union)
    else:
        mesh = _concatenate([trimesh.creation.box([edge] * 3).apply_translation(edge * c) for c in cells])
    path = _write(mesh, out / f"pinched_{seed}.stl")
    # A pinch: two cells a diagonal step apart, neither of the two cells beside both of them present.
    present = {tuple(c) for c in cells}
    pinches = sum(1 for a in cells for step in _EDGE_STEPS if tuple(a + step) in present
                  and not any(tuple(a + part) in present for part in np.diag(step) if part.any()))
    if seed % 2 == 0 and pinches == 0:  # the union is a clean closed surface
        return ZooCase(path.stem, "pinched", path, "accepted", "", len(cells) * edge**3)
    return ZooCase(path.stem, "pinched", path, "repaired", "non-manifold edges split", len(cells) * edge**3)


def hollow(out: Path, seed: int) -> ZooCase:
    """A hollow object as CAD writes it: an outer shell wound outward and an inner wall wound inward
    (2-10 mm of material); its solid is the shell between them."""
    rng = _rng(seed, "hollow")
    outer = _base_convex(rng)
    wall = rng.uniform(0.002, 0.01)
    inner = outer.copy()
    inner.apply_translation(-outer.center_mass)
    inner.apply_scale(1.0 - 2.0 * wall / float(np.min(outer.extents)))
    inner.apply_translation(outer.center_mass)
    volume = float(outer.volume - inner.volume)
    inner.invert()
    path = _write(_concatenate([outer, inner]), out / f"hollow_{seed}.obj")
    return ZooCase(path.stem, "hollow", path, "accepted", "cavity", volume)


def flipped(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "flipped")
    mesh = _base_convex(rng)
    faces = mesh.faces.copy()
    flip = rng.random(len(faces)) < rng.uniform(0.1, 0.4)
    faces[flip] = faces[flip][:, ::-1]
    path = _write(trimesh.Trimesh(mesh.vertices, faces, process=False), out / f"flipped_{seed}.obj")
    return ZooCase(path.stem, "flipped", path, "repaired", "", float(mesh.volume))


def duplicated(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "duplicated")
    mesh = _base_convex(rng)
    copy = np.flatnonzero(rng.random(len(mesh.faces)) < rng.uniform(0.05, 0.2))
    faces = np.vstack([mesh.faces, mesh.faces[copy]])
    path = _write(trimesh.Trimesh(mesh.vertices, faces, process=False), out / f"duplicated_{seed}.stl")
    return ZooCase(path.stem, "duplicated", path, "repaired", "", float(mesh.volume))


def internal(out: Path, seed: int) -> ZooCase:
    """A closed box with an internal partition (an open sheet inside it) and a closed shell wholly
    inside it (a visual mesh's inner detail)."""
    rng = _rng(seed, "internal")
    extents = rng.uniform(0.05, 0.12, size=3)
    box = trimesh.creation.box(extents)
    h = 0.45 * extents
    z = rng.uniform(-0.2, 0.2) * extents[2]
    sheet = trimesh.Trimesh([[-h[0], -h[1], z], [h[0], -h[1], z], [h[0], h[1], z], [-h[0], h[1], z]],
                            [[0, 1, 2], [0, 2, 3]], process=False)
    inner = trimesh.creation.icosphere(subdivisions=2, radius=0.2 * float(extents.min()))
    path = _write(_concatenate([box, sheet, inner]), out / f"internal_{seed}.obj")
    return ZooCase(path.stem, "internal", path, "repaired", "", float(box.volume))


def degenerate(out: Path, seed: int) -> ZooCase:
    """A closed solid with zero-area triangles: repeated vertices and three points on a line."""
    rng = _rng(seed, "degenerate")
    mesh = _base_convex(rng)
    vertices, faces = mesh.vertices.copy(), mesh.faces.copy()
    extra = []
    for _ in range(int(rng.integers(2, 10))):
        face = faces[int(rng.integers(len(faces)))]
        extra.append([face[0], face[0], face[1]])  # a repeated vertex
        a, b = vertices[face[0]], vertices[face[1]]
        vertices = np.vstack([vertices, 0.5 * (a + b)])
        extra.append([face[0], len(vertices) - 1, face[1]])  # three collinear points
    faces = np.vstack([faces, extra])
    path = _write(trimesh.Trimesh(vertices, faces, process=False), out / f"degenerate_{seed}.obj")
    return ZooCase(path.stem, "degenerate", path, "repaired", "", float(mesh.volume))


def t_junctions(out: Path, seed: int) -> ZooCase:
    """A closed solid some of whose faces were split at a point of one edge while the face across that
    edge was not (a vertex on its neighbour's edge, as a CAD export leaves where it refined one part
    and not the part it meets): the seams are open, though no surface is missing."""
    rng = _rng(seed, "t_junctions")
    mesh = _base_convex(rng)
    vertices, faces = mesh.vertices.copy(), [tuple(face) for face in mesh.faces]
    for index in rng.choice(len(faces), size=int(rng.integers(2, 6)), replace=False):
        a, b, c = faces[index]
        on_edge = vertices[a] + rng.uniform(0.3, 0.7) * (vertices[b] - vertices[a])
        vertices = np.vstack([vertices, on_edge])
        faces[index] = (a, len(vertices) - 1, c)  # the face split at the new vertex; its neighbour not
        faces.append((len(vertices) - 1, b, c))
    path = _write(trimesh.Trimesh(vertices, np.array(faces), process=False), out / f"t_junctions_{seed}.obj")
    return ZooCase(path.stem, "t_junctions", path, "repaired", "split at T-junctions", float(mesh.volume))


def everything(out: Path, seed: int) -> ZooCase:
    """Several defects at once, as a real file has them: a solid stored as cells sharing faces, one
    cell with a hole, some faces flipped and some duplicated, a degenerate triangle, a stray fin,
    and the whole written as a triangle soup (STL) so that nothing is indexed."""
    rng = _rng(seed, "everything")
    base = _base_convex(rng)
    cells = _cells(base, rng, int(rng.integers(2, 5)))
    holed = cells[0]
    drop = np.argsort(np.linalg.norm(holed.triangles_center - holed.triangles_center[0], axis=1))[:2]
    cells[0] = _remove_faces(holed, drop)
    mesh = _concatenate(cells)
    faces = mesh.faces.copy()
    flip = rng.random(len(faces)) < 0.2
    faces[flip] = faces[flip][:, ::-1]
    copy = np.flatnonzero(rng.random(len(faces)) < 0.1)
    faces = np.vstack([faces, faces[copy], [[faces[0][0], faces[0][0], faces[0][1]]]])
    vertices = mesh.vertices
    a, b = vertices[faces[1][0]], vertices[faces[1][1]]
    fin_tip = 0.5 * (a + b) + (0.5 * (a + b) - base.center_mass) * 0.2
    vertices = np.vstack([vertices, fin_tip])
    faces = np.vstack([faces, [[faces[1][0], faces[1][1], len(vertices) - 1]]])
    path = _write(trimesh.Trimesh(vertices, faces, process=False), out / f"everything_{seed}.stl")
    # Cells in a soup share vertices where they touch, so their shared faces become edges of four
    # faces, split into patches that MeshFix closes one by one: the volume comes back within 7 % on
    # seeds 0-7 (measured), not exactly.
    return ZooCase(path.stem, "everything", path, "repaired", "repaired", float(base.volume), volume_tolerance=0.1)


def millimetres(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "millimetres")
    mesh = _base_convex(rng)
    volume = float(mesh.volume)
    mesh.apply_scale(1000.0)
    path = _write(mesh, out / f"millimetres_{seed}.stl")
    return ZooCase(path.stem, "millimetres", path, "accepted", "", volume, scale=0.001)


def separate(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "separate")
    a, b = _base_convex(rng), _base_convex(rng)
    gap = rng.uniform(0.01, 0.05)
    b.apply_translation([a.bounds[1, 0] - b.bounds[0, 0] + gap, 0.0, 0.0])
    path = _write(_concatenate([a, b]), out / f"separate_{seed}.obj")
    return ZooCase(path.stem, "separate", path, "refused", "separate parts")


def open_sheet(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "open_sheet")
    n = 12
    x, y = np.meshgrid(np.linspace(-0.05, 0.05, n), np.linspace(-0.05, 0.05, n))
    z = rng.uniform(0.0, 0.02) * np.sin(3 * x / 0.05) * np.cos(2 * y / 0.05)
    vertices = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    faces = []
    for i in range(n - 1):
        for j in range(n - 1):
            k = i * n + j
            faces += [[k, k + 1, k + n + 1], [k, k + n + 1, k + n]]
    path = _write(trimesh.Trimesh(vertices, faces, process=False), out / f"open_sheet_{seed}.stl")
    return ZooCase(path.stem, "open_sheet", path, "refused", "encloses no volume")


def point_cloud(out: Path, seed: int) -> ZooCase:
    rng = _rng(seed, "point_cloud")
    points = rng.normal(size=(200, 3)) * 0.03
    path = out / f"point_cloud_{seed}.ply"
    trimesh.PointCloud(points).export(path)
    return ZooCase(path.stem, "point_cloud", path, "refused", "no triangles")


def _box_inertia(mass: float, extents) -> np.ndarray:
    x, y, z = extents
    return mass / 12.0 * np.array([y * y + z * z, x * x + z * z, x * x + y * y])


def urdf_placeholder_inertia(out: Path, seed: int) -> ZooCase:
    """A URDF box whose inertia is a placeholder: izz = 0, or 1 kg·m² on a 0.1 kg object."""
    rng = _rng(seed, "urdf_placeholder_inertia")
    extents = rng.uniform(0.04, 0.1, size=3)
    ixx, iyy, izz = (0.1, 0.1, 0.0) if seed % 2 == 0 else (1.0, 1.0, 1.0)
    text = f"""<?xml version="1.0"?>
<robot name="placeholder_{seed}">
  <link name="body">
    <inertial>
      <origin xyz="0 0 0"/>
      <mass value="0.1"/>
      <inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/>
    </inertial>
    <visual><geometry><box size="{extents[0]} {extents[1]} {extents[2]}"/></geometry></visual>
    <collision><geometry><box size="{extents[0]} {extents[1]} {extents[2]}"/></geometry></collision>
  </link>
</robot>
"""
    path = out / f"urdf_placeholder_inertia_{seed}.urdf"
    path.write_text(text)
    return ZooCase(path.stem, "urdf_placeholder_inertia", path, "repaired", "inertia", float(np.prod(extents)))


def mjcf_placeholder_inertia(out: Path, seed: int) -> ZooCase:
    """An MJCF object as MuJoCo benchmarks ship them: one body, a collision mesh geom naming an STL
    (scaled), a visual geom, and an explicit inertial that is a placeholder."""
    rng = _rng(seed, "mjcf_placeholder_inertia")
    mesh = _base_convex(rng)
    mesh.apply_scale(1.25)  # the file is scaled by 0.8 in the model
    (out / "meshes").mkdir(exist_ok=True)
    mesh.export(out / "meshes" / f"mjcf_{seed}.stl")
    text = f"""<mujoco model="mjcf_object_{seed}">
  <compiler angle="radian" meshdir="meshes"/>
  <asset>
    <mesh file="mjcf_{seed}.stl" name="body_mesh" scale="0.8 0.8 0.8"/>
  </asset>
  <worldbody>
    <body name="object" pos="0 0 0.1">
      <inertial pos="0 0 0" mass="0.2" diaginertia="1 1 1e-9"/>
      <geom type="mesh" mesh="body_mesh" group="0" solimp="0.998 0.998 0.001" friction="0.95 0.3 0.1"/>
      <geom type="mesh" mesh="body_mesh" group="1" contype="0" conaffinity="0" rgba="1 0 0 1"/>
      <joint name="free" type="free"/>
    </body>
  </worldbody>
</mujoco>
"""
    path = out / f"mjcf_placeholder_inertia_{seed}.xml"
    path.write_text(text)
    return ZooCase(path.stem, "mjcf_placeholder_inertia", path, "repaired", "inertia",
                   float(mesh.volume) * 0.8**3)


def mjcf_density(out: Path, seed: int) -> ZooCase:
    """An MJCF object with a density on its mesh geom and a primitive geom beside it."""
    rng = _rng(seed, "mjcf_density")
    mesh = _base_convex(rng)
    (out / "meshes").mkdir(exist_ok=True)
    mesh.export(out / "meshes" / f"mjcf_density_{seed}.stl")
    text = f"""<mujoco model="mjcf_density_{seed}">
  <asset>
    <mesh file="meshes/mjcf_density_{seed}.stl" name="m"/>
  </asset>
  <worldbody>
    <body name="object">
      <geom type="mesh" mesh="m" density="300"/>
    </body>
  </worldbody>
</mujoco>
"""
    path = out / f"mjcf_density_{seed}.xml"
    path.write_text(text)
    return ZooCase(path.stem, "mjcf_density", path, "accepted", "", float(mesh.volume))


def gltf_binary(out: Path, seed: int) -> ZooCase:
    """A glTF binary (Y up, metres, as the format specifies) of a random solid."""
    rng = _rng(seed, "gltf_binary")
    mesh = _base_convex(rng)
    path = out / f"gltf_binary_{seed}.glb"
    mesh.export(path)
    return ZooCase(path.stem, "gltf_binary", path, "accepted", "", float(mesh.volume))


GENERATORS = {
    "shared_faces": shared_faces,
    "hull_gaps": hull_gaps,
    "overlapping": overlapping,
    "hollow": hollow,
    "open_caps": open_caps,
    "holes": holes,
    "non_manifold": non_manifold,
    "pinched": pinched,
    "flipped": flipped,
    "duplicated": duplicated,
    "internal": internal,
    "degenerate": degenerate,
    "t_junctions": t_junctions,
    "everything": everything,
    "millimetres": millimetres,
    "separate": separate,
    "open_sheet": open_sheet,
    "point_cloud": point_cloud,
    "urdf_placeholder_inertia": urdf_placeholder_inertia,
    "mjcf_placeholder_inertia": mjcf_placeholder_inertia,
    "mjcf_density": mjcf_density,
    "gltf_binary": gltf_binary,
}
CLASSES = tuple(GENERATORS)


def generate(out: str | Path, seeds=(0,), classes=CLASSES) -> list[ZooCase]:
    """Writes one file (or model with its meshes) per class and seed into `out`; the cases."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    return [GENERATORS[name](out, int(seed)) for name in classes for seed in seeds]
