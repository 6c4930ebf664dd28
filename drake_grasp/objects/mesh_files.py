"""Objects from mesh files: read, repaired into closed shells, joined into one object, in metres,
split into convex pieces for contact and rested on a stable face.

A mesh file (any format trimesh reads: OBJ, STL, PLY, OFF, glTF/GLB; MuJoCo's binary ``.msh``;
Drake's tetrahedral ``.vtk``, by its boundary surface; COLLADA ``.dae``, 3D printing's ``.3mf`` and
OpenUSD (with the optional ``usd-core``), in the unit they declare; Open
Inventor ``.iv`` and VRML ``.wrl``, GraspIt!'s geometry) is read as it stores its triangles (`--scale`,
glTF turned z up), repaired (:mod:`drake_grasp.objects.repair`), its shells joined into one rigid
object (:mod:`drake_grasp.objects.solid`), checked for a size the hand can grasp
(:mod:`drake_grasp.objects.sizes`), simplified if dense and decomposed into convex pieces
(:mod:`drake_grasp.objects.pieces`); the repaired solid and the pieces are cached by the file's
content. Mass properties come from the solid itself.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import re
import warnings
from pathlib import Path

import numpy as np
import trimesh
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.math import RollPitchYaw, RotationMatrix
from scipy.spatial import ConvexHull, QhullError

from drake_grasp.objects import (
    collada_mesh, inventor_mesh, mujoco_msh, other_formats, repair, sizes, threemf_mesh, usd_mesh, vtk_mesh,
    vtk_polydata,
)
from drake_grasp.objects.pieces import IMPORT_VERSION, _decompose
from drake_grasp.objects.settling import SET_DOWN_TILT_DEG, base_margin_deg, stays_up_in_simulator
from drake_grasp.objects.spec import (
    COACD_THRESHOLD, CONVEXITY_TOLERANCE, DEFAULT_DENSITY, DEFAULT_MAX_PIECES, MAX_FACES, MeshNote,
    MIN_TIP_ANGLE, ObjectError, ObjectSpec, PRIMITIVE_NAMES, STABLE_POSE_TOLERANCE, ShapePiece, UnstablePoseWarning,
    Y_UP_TO_Z_UP, YELLOW_PAPER_RGBA, cache_dir,
)
from drake_grasp.objects.mass_properties import _make_spec

__all__ = ["IMPORT_VERSION", "object_from_mesh", "object_from_triangles"]


def _one_line(text: str) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= 200 else text[:197] + "..."


def _model_name(text: str) -> str:
    """`text` made a valid model name (letters, digits, '_', '-'; starting with a letter)."""
    name = re.sub(r"[^A-Za-z0-9_\-]", "_", text) or "object"
    return name if name[0].isalpha() else "object_" + name


# Formats whose files are Y up (glTF 2.0 specifies +Y up, metres): turned so that their up is z.
_Y_UP_SUFFIXES = (".gltf", ".glb")
# Open Inventor and VRML (GraspIt!'s geometry; some of its VRML files are named .IV): read by their header.
INVENTOR_SUFFIXES = (".iv", ".wrl", ".vrml")


def read_triangles(path: Path, label: str, file_type: str | None = None) -> trimesh.Trimesh:
    """The triangles a mesh file stores, in its own units and frame: a MuJoCo ``.msh``
    (:mod:`drake_grasp.objects.mujoco_msh`), the boundary of Drake's tetrahedral ``.vtk``
    (:mod:`drake_grasp.objects.vtk_mesh`) or a VTK surface (:mod:`drake_grasp.objects.vtk_polydata`),
    an Open Inventor ``.iv`` or VRML ``.wrl`` file, as its header says it is (every shape where its
    transforms put it: :mod:`drake_grasp.objects.inventor_mesh`), or any format trimesh reads. A
    COLLADA ``.dae``, a 3MF package and an OpenUSD stage declare their unit, and come in metres
    (:mod:`drake_grasp.objects.collada_mesh`, :mod:`drake_grasp.objects.threemf_mesh`,
    :mod:`drake_grasp.objects.usd_mesh`: USD also turned z up, and read only with the optional
    ``usd-core``). A format users bring that is not read here (a xacro file, CAD:
    :mod:`drake_grasp.objects.other_formats`) is named with what to give instead.
    `file_type` names the format when the suffix does not (``"iv"``, ``"off"``, ``"ply"``: a GraspIt
    body file says which). ObjectError (one line) for a file that is missing, unreadable or damaged,
    has no triangles or has vertices that are not finite."""
    if not path.exists():
        raise ObjectError(f"{label}: file not found")
    if not path.is_file():
        raise ObjectError(f"{label}: not a file")
    suffix = "." + file_type.lower() if file_type else path.suffix.lower()
    if suffix in INVENTOR_SUFFIXES:
        vertices, faces = inventor_mesh.read_inventor(path.read_bytes(), label)
    elif suffix == ".msh":
        vertices, faces = mujoco_msh.read_msh(path.read_bytes(), label)
    elif suffix == ".dae":
        vertices, faces = collada_mesh.read_dae(path.read_bytes(), label)
    elif suffix == ".3mf":
        vertices, faces = threemf_mesh.read_3mf(path.read_bytes(), label)
    elif suffix in usd_mesh.USD_SUFFIXES:
        vertices, faces = usd_mesh.read_usd(path, label)
    elif suffix == ".vtk":
        data = path.read_bytes()
        if vtk_polydata.is_polydata(data):  # a surface (PCL's and VTK's scans), ASCII or binary
            vertices, faces = vtk_polydata.read_polydata(data, label)
        else:  # Drake's tetrahedral volume
            vertices, faces = vtk_mesh.boundary_surface(*vtk_mesh.read_vtk(data, label))
    else:
        if suffix in (".glb", ".gltf"):
            problem = other_formats.gltf_compression_problem(path)
            if problem:
                raise ObjectError(f"{label}: {problem}")
        try:
            mesh = trimesh.load(path, file_type=file_type, force="mesh", process=False)
        except Exception as error:  # trimesh raises many types for unreadable files.
            instead = other_formats.advice(path)
            if instead:
                raise ObjectError(f"{label}: {instead}") from None
            reason = _one_line(error) or type(error).__name__
            raise ObjectError(f"{label}: cannot read mesh ({reason})") from None
        if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
            raise ObjectError(f"{label}: file contains no triangles (a point cloud or an empty mesh): no solid "
                              "can be recovered")
        vertices, faces = mesh.vertices, mesh.faces
    vertices = np.asarray(vertices, float)
    bad = int(np.count_nonzero(~np.isfinite(vertices).all(axis=1)))
    if bad:
        noun = "vertex is" if bad == 1 else "vertices are"
        raise ObjectError(f"{label}: {bad} {noun} not finite (NaN or inf)")
    return trimesh.Trimesh(vertices, np.asarray(faces, np.int64), process=False)


def _read_mesh(path: Path, label: str, scale) -> trimesh.Trimesh:
    """The triangles of a mesh file as it stores them (:func:`read_triangles`), turned z up and
    scaled to metres (nothing welded or repaired yet). ObjectError for a flat mesh too.

    `scale` is one factor or three, one per axis of the z-up mesh frame, as a model file's
    non-uniform ``scale="sx sy sz"`` applies them (Drake's ``Mesh.scale3``); a mirroring scale
    (an odd number of negative factors) keeps the faces pointing out."""
    mesh = read_triangles(path, label)
    if path.suffix.lower() in _Y_UP_SUFFIXES:
        mesh.apply_transform(Y_UP_TO_Z_UP)
    # trimesh reverses the faces' winding under a mirroring transform, so they keep pointing out.
    mesh.apply_transform(np.diag([*np.broadcast_to(np.asarray(scale, float), (3,)), 1.0]))
    extents = mesh.extents
    if not np.min(extents) > 1e-9 * max(np.max(extents), 1e-300):
        raise ObjectError(f"{label}: mesh has zero volume (it is flat)")
    return mesh


def _solid_from_mesh(mesh: trimesh.Trimesh, label: str, join_gap: float | None = None,
                     keep_largest: bool = False, one_body: bool = False) -> trimesh.Trimesh:
    """The solid a mesh's triangles describe (metres): repaired into closed shells
    (:mod:`drake_grasp.objects.repair`, saying what was repaired with a MeshNote) and its shells
    joined into one object (:mod:`drake_grasp.objects.solid`). The mesh returned may hold several
    closed parts that touch or lie within the join gap: together they are the object."""
    try:
        shells, report = repair.closed_shells(mesh, label)
    except repair.RepairError as error:
        if not one_body:
            raise ObjectError(str(error)) from None
        hull = repair.convex_piece_hull(mesh)
        if hull is not None:
            warnings.warn(f"{label}: its triangles close nothing, but its {len(hull.vertices)} vertices all lie on their "
                          "convex hull: a convex piece, taken as that hull (as the physics engines a model file is made "
                          "for collide a mesh)", MeshNote, stacklevel=3)
            return hull
        hull = repair.surface_hull(mesh)
        if hull is None:
            raise ObjectError(str(error)) from None
        warnings.warn(f"{label}: its triangles close nothing (an open surface); taken as their convex hull, as the "
                      "physics engines a model file is made for collide a mesh (its hollows are filled)", MeshNote,
                      stacklevel=3)
        return hull
    if report.changed:
        warnings.warn(f"{label}: {report.describe()}", MeshNote, stacklevel=3)
    return _user_solid(shells, label, keep_largest, join_gap, one_body)


def _cached_solid(mesh: trimesh.Trimesh, label: str, key: str, join_gap: float | None,
                  keep_largest: bool, one_body: bool = False) -> trimesh.Trimesh:
    """:func:`_solid_from_mesh`, cached under `key` (a hash of the file's content and the options)
    beside the decompositions: a second load reads the repaired, joined solid and repeats its notes.
    A refused file is not cached (its error is computed again, and is the same)."""
    path = cache_dir() / "solids" / f"{key}-i{IMPORT_VERSION}.npz"
    if path.exists():
        stored = np.load(path, allow_pickle=False)
        for note in json.loads(str(stored["notes"])):
            warnings.warn(f"{label}: {note}", MeshNote, stacklevel=3)
        return trimesh.Trimesh(stored["vertices"], stored["faces"], process=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        solid = _solid_from_mesh(mesh, label, join_gap, keep_largest, one_body)
    notes = []
    for w in caught:
        text = str(w.message)
        if issubclass(w.category, MeshNote) and text.startswith(f"{label}: "):
            notes.append(text[len(label) + 2:])
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    path.parent.mkdir(parents=True, exist_ok=True)
    staging = path.with_name(f"{path.stem}.{os.getpid()}.tmp.npz")
    np.savez(staging, vertices=np.asarray(solid.vertices, float), faces=np.asarray(solid.faces, np.int64),
             notes=json.dumps(notes))
    os.replace(staging, path)  # atomic: a concurrent load sees the whole file or none
    return solid


def _content_digest(path: Path) -> str:
    """The key of a mesh file's cached solid and pieces: its bytes' SHA-256, and for COLLADA the
    reader's version (since 0.31.0 its declared unit is applied: a solid cached before is not reused)."""
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    return digest + "|dae-unit" if path.suffix.lower() == ".dae" else digest


def _load_checked_mesh(path: Path, label: str, scale, join_gap: float | None = None,
                       keep_largest: bool = False, one_body: bool = False) -> trimesh.Trimesh:
    """:func:`_read_mesh`, then :func:`_solid_from_mesh`, cached by the file's content and the
    options (a model file's mesh geometry; `scale` one factor or three; `one_body`: see
    :func:`_user_solid`)."""
    digest = _content_digest(path) if path.is_file() else ""
    options = f"{digest}|{_scale_key(scale)}|{join_gap!r}|{keep_largest}" + ("|one-body" if one_body else "")
    key = hashlib.sha256(options.encode()).hexdigest()[:24]
    return _cached_solid(_read_mesh(path, label, scale), label, key, join_gap, keep_largest, one_body)


def _scale_key(scale) -> str:
    """A scale's text for cache keys and the cache's folder names: a uniform one as its one factor, as
    before three were allowed; three as ``0.003x0.003x0.001`` (no brackets, commas or spaces: the
    folder is named in a file URI that Drake's parser must resolve)."""
    factors = np.broadcast_to(np.asarray(scale, float), (3,))
    if np.all(factors == factors[0]):
        return repr(float(factors[0]))
    return "x".join(repr(float(f)) for f in factors)


def _lowest_resting_rotation(hull: trimesh.Trimesh, p_Ocm: np.ndarray) -> RotationMatrix:
    """R_TO that rests the object on the hull face nearest its centre of mass.

    That pose has the lowest centre of mass of all resting poses, hence is stable: were the centre
    of mass's projection outside the face, tipping over its edge would lower it further.
    """
    down = np.array([0.0, 0.0, -1.0])
    distances = np.einsum("ij,ij->i", hull.face_normals, hull.triangles[:, 0] - p_Ocm)
    # Of equally near faces, prefer the one already facing down (keep the file's orientation).
    nearest = np.flatnonzero(distances <= distances.min() * (1.0 + 1e-9) + 1e-12)
    n_O = hull.face_normals[nearest[int(np.argmax(hull.face_normals[nearest] @ down))]]
    axis = np.cross(n_O, down)
    sin, cos = np.linalg.norm(axis), float(np.dot(n_O, down))
    if sin < 1e-12:
        return RotationMatrix() if cos > 0.0 else RotationMatrix.MakeXRotation(math.pi)
    return RotationMatrix(AngleAxis(math.atan2(sin, cos), axis / sin))


def _rests_stably_upright(hull: trimesh.Trimesh, p_Ocm: np.ndarray) -> bool:
    """Whether the object rests stably with its frame's z up: on a downward hull face (not an edge
    or a point) over which its centre of mass lies, at least MIN_TIP_ANGLE inside its edges as seen
    from the centre, or so that no resting pose lowers its centre of mass by more than
    STABLE_POSE_TOLERANCE of its size (a sphere, rolling off the vertex its tessellation stands on)."""
    if _rolls_little(hull, p_Ocm):
        return True
    height = float(p_Ocm[2] - hull.vertices[:, 2].min())
    down = np.array([0.0, 0.0, -1.0])
    z_min = float(hull.vertices[:, 2].min())
    bottom = (hull.face_normals @ down > 1.0 - 1e-6) & (np.abs(hull.triangles[:, :, 2] - z_min).max(axis=1) < 1e-6)
    if not np.any(bottom):
        return False
    polygon = np.unique(np.round(hull.triangles[bottom].reshape(-1, 3)[:, :2], 9), axis=0)
    if len(polygon) < 3:
        return False  # a point or an edge
    return _centre_over_base(polygon, p_Ocm, height)


def _rolls_little(hull: trimesh.Trimesh, p_Ocm: np.ndarray) -> bool:
    """Whether no resting pose lowers the centre of mass, from where it stands with the frame's z up,
    by more than STABLE_POSE_TOLERANCE of the object's size: a sphere, rolling off the vertex its
    tessellation stands on."""
    height = float(p_Ocm[2] - hull.vertices[:, 2].min())
    distances = np.einsum("ij,ij->i", hull.face_normals, hull.triangles[:, 0] - p_Ocm)
    return height - float(distances.min()) <= STABLE_POSE_TOLERANCE * float(np.max(hull.extents))


def _narrowly_upright(hull: trimesh.Trimesh, p_Ocm: np.ndarray) -> bool:
    """Whether the object, resting with its frame's z up, does so only just: not a rounded body that
    no pose lowers much (`_rests_stably_upright`'s sphere), and its centre of mass less than
    `settling.SET_DOWN_TILT_DEG` inside its base's edges as seen from the centre, so that set down as
    a hand sets a body down, that far from upright, it would fall. Such a body is set down in the
    simulator (`stays_up_in_simulator`) before it is loaded standing: BulletArm's 3DNet zucchini, 22 cm
    tall on a cut end 1.0° wide (the lowest-face test's limit is `MIN_TIP_ANGLE`, 1°), fell within the
    trial's first second, while the camera looked. (Not every narrow base: dropped 2° tilted in the
    simulator, a 7 × 2.7 × 17 cm box standing on end 6.4° inside its base falls too, and stands in trials.)"""
    if _rolls_little(hull, p_Ocm):
        return False
    offsets = np.asarray(hull.vertices, float) - np.asarray(p_Ocm, float)
    return base_margin_deg(offsets, np.array([0.0, 0.0, -1.0]), float(-offsets[:, 2].min())) < SET_DOWN_TILT_DEG


def _centre_over_base(base_xy: np.ndarray, p_Ocm: np.ndarray, height: float) -> bool:
    """Whether the centre of mass, `height` (m) above the base, lies over the base's polygon (the hull of
    `base_xy`) at least MIN_TIP_ANGLE inside its edges as seen from the centre; False for an edge."""
    try:
        equations = ConvexHull(base_xy).equations  # a·x + b ≤ 0 inside
    except QhullError:  # collinear points: an edge
        return False
    inside = height * math.tan(math.radians(MIN_TIP_ANGLE))  # how far inside its base the centre must lie
    return bool(np.all(equations[:, :2] @ p_Ocm[:2] + equations[:, 2] <= -inside + 1e-9))


# A body is laid down without asking the simulator only where it clearly tips over: its centre of mass
# MIN_TIP_ANGLE inside no base made of the hull's vertices within this share of its height (at least
# BASE_FLOOR) of its lowest point. A scanned base is not one plane: YCB's tuna can, as Gazebo ships it,
# stands on a 4 mm bulge below its rim, and the lowest-face test (`_rests_stably_upright`) would turn it
# upside down; a can settles on its rim. Nor is a body that balances on a point a rest, though a
# symmetric one balances there in the simulator too.
BASE_SHARE = 0.1
BASE_FLOOR = 0.005  # m


def clearly_tips_over(hull, p_BScm: np.ndarray) -> bool:
    """Whether a body standing z up tips over: its centre of mass less than MIN_TIP_ANGLE inside the
    base of the hull's vertices within BASE_SHARE of its height (at least BASE_FLOOR) of the lowest."""
    vertices = np.asarray(hull.vertices, float)
    z_min = float(vertices[:, 2].min())
    height = float(p_BScm[2]) - z_min
    base = np.unique(np.round(vertices[vertices[:, 2] <= z_min + max(BASE_FLOOR, BASE_SHARE * height)][:, :2], 6),
                     axis=0)
    return len(base) < 3 or not _centre_over_base(base, p_BScm, height)


def _user_solid(shells: list[trimesh.Trimesh], label: str, keep_largest: bool,
                join_gap: float | None = None, one_body: bool = False) -> trimesh.Trimesh:
    """The object closed shells make: those within the join gap of each other are one rigid object
    (their union); parts farther apart are an ObjectError naming their count and smallest gap,
    unless `keep_largest` keeps the largest (with a MeshNote).

    `one_body`: the mesh is a model file's collision geometry of one link, which the file declares one
    rigid body, so parts farther apart are that body's parts (with a MeshNote), as a physics engine
    takes them. pybullet's procedural random_urdfs ship such meshes: 897's convex pieces form five
    clusters 4.6 mm or more apart. A bare mesh declares nothing, and two objects in one file are
    as likely as one object in parts, so there the error stands."""
    from drake_grasp.objects.solid import solid_of_shells

    solid = solid_of_shells(shells, join_gap)
    specks = _scan_specks(solid)
    if specks:
        largest = max(float(np.max(c.mesh.extents)) for c in specks) * 1000
        share = 100 * sum(c.volume for c in specks) / sum(c.volume for c in solid.components)
        warnings.warn(f"{label}: left out {len(specks)} speck{'s' if len(specks) != 1 else ''} apart from the object "
                      f"(scan noise: together {share:.2g} % of the volume, the largest {largest:.2g} mm across)",
                      MeshNote, stacklevel=3)
        solid = dataclasses.replace(solid, components=solid.components[:-len(specks)])
    if len(solid.components) > 1 and one_body and not keep_largest:
        count, smallest = len(solid.components), solid.smallest_gap * 1000
        warnings.warn(f"{label}: {count} separate parts (the smallest gap {smallest:.1f} mm, over the join gap "
                      f"{solid.gap * 1000:.3g} mm) are one rigid body, as the file's link declares (mass and "
                      "inertia from their union)", MeshNote, stacklevel=3)
        return trimesh.util.concatenate([component.mesh for component in solid.components])
    if len(solid.components) > 1:
        count, gap, smallest = len(solid.components), solid.gap * 1000, solid.smallest_gap * 1000
        if not keep_largest:
            raise ObjectError(f"{label}: {count} separate parts farther apart than the join gap ({gap:.3g} mm; the "
                              f"smallest gap is {smallest:.1f} mm): one object must be one piece; join them with "
                              "--join-gap or keep the largest with --largest-component")
        warnings.warn(f"{label}: kept the largest of {count} separate parts (smallest gap {smallest:.1f} mm)",
                      MeshNote, stacklevel=3)
    elif len(solid.components[0].shells) > 1:
        bridged = (f"gaps up to {solid.largest_bridged_gap * 1000:.2f} mm bridged" if solid.largest_bridged_gap > 1e-5
                   else "they touch, overlap or nest")
        hollow = (f"; {solid.cavities} inner shell{'s' if solid.cavities != 1 else ''} wound inward: "
                  "a cavity, subtracted" if solid.cavities else "")
        joined = len(solid.components[0].shells)
        warnings.warn(f"{label}: {joined} closed shells within the join gap ({solid.gap * 1000:.3g} mm; {bridged}) "
                      f"form one object (mass and inertia from their union{hollow})", MeshNote, stacklevel=3)
    return solid.mesh


# A separate part this small beside the object is a speck of scan noise, not a part (m³ shares of the
# whole). Scanned objects keep such specks: the Columbia grasping group's scanned apple has 22 closed
# shells of 4-16 triangles, 1-10 mm across, beside its 5,922-triangle body, and its red mug 10.
SPECK_SHARE = 0.005  # of the volume, each
SPECKS_SHARE = 0.01  # of the volume, all together


def _scan_specks(solid) -> list:
    """The components of `solid` (largest first) that are specks of scan noise apart from the object:
    each under `SPECK_SHARE` of the volume and all of them together under `SPECKS_SHARE`; [] otherwise.
    Being the smallest, they are the components' tail."""
    if len(solid.components) < 2:
        return []
    total = sum(c.volume for c in solid.components)
    specks = [c for c in solid.components[1:] if c.volume < SPECK_SHARE * total]
    return specks if sum(c.volume for c in specks) < SPECKS_SHARE * total else []


def _simplified(mesh: trimesh.Trimesh, label: str) -> trimesh.Trimesh:
    """The mesh, or, above MAX_FACES faces, its quadric-decimation simplification (trimesh over the
    fast-simplification library) to MAX_FACES faces, when that stays a closed solid."""
    if len(mesh.faces) <= MAX_FACES:
        return mesh
    simple = mesh.simplify_quadric_decimation(face_count=MAX_FACES)
    simple.merge_vertices()
    if not (simple.is_watertight and simple.volume > 0.9 * mesh.volume):
        return mesh  # Decimation broke the surface: keep the full mesh (slower, still correct).
    return simple


def object_from_mesh(
    path: str | os.PathLike,
    mass: float | None = None,
    name: str | None = None,
    *,
    density: float = DEFAULT_DENSITY,
    scale: float = 1.0,
    max_pieces: int = DEFAULT_MAX_PIECES,
    stable_pose: bool | None = None,
    closest_primitive: str | None = None,
    rgba=YELLOW_PAPER_RGBA,
    friction: float | None = None,
    largest_component: bool = False,
    join_gap: float | None = None,
) -> ObjectSpec:
    """An object from a closed triangle mesh in any format trimesh reads (OBJ, STL, PLY, ...), a
    MuJoCo ``.msh``, the boundary of Drake's tetrahedral ``.vtk``, or an Open Inventor ``.iv`` or VRML
    ``.wrl`` file (GraspIt!'s geometry, in millimetres: `scale` 0.001).

    The object is the solid the mesh encloses (:mod:`drake_grasp.objects.solid`): closed shells
    that overlap are united (mass and inertia never count an overlap twice); shells that do not
    touch are an ObjectError naming their count, unless `largest_component` keeps the largest. An
    object no hand can grasp (:mod:`drake_grasp.objects.sizes`: largest extent outside 3 mm-0.5 m)
    is an ObjectError naming its size and the likely unit; one below 1 cm gets a UnitsWarning. A
    mesh of more than MAX_FACES faces is simplified for contact and rendering (quadric decimation,
    trimesh with fast-simplification), saying so with a MeshNote; mass properties come from the
    full mesh.

    Checks: the file exists and loads; vertices are finite; the mesh is not flat, is watertight,
    has consistent winding and non-zero volume. A mesh whose winding is consistently inverted
    (negative volume) is flipped and accepted. A convex mesh (volume within CONVEXITY_TOLERANCE of
    its hull's) becomes one convex piece (its hull); a non-convex one is split into at most
    `max_pieces` convex pieces by CoACD (seed 0, quiet). The pieces are cached by the file's
    content hash (and `scale` and the CoACD settings), so loading the same file again does not
    decompose it again. Mass properties come from the mesh itself (exact for a closed mesh).

    Args:
        path: The mesh file; its units must be metres (or use `scale`).
        mass: Mass (kg); default density × volume.
        name: Model name; default the file's stem.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        scale: Uniform scale applied to the file's coordinates (e.g. 0.001 for millimetres).
        max_pieces: Most convex pieces of a decomposition.
        stable_pose: If False, the object rests with the file's z up (R_TO = I) on its lowest
            point (which may not be a stable pose); if True, R_TO rests it on the hull face nearest
            its centre of mass (its lowest, hence stable, resting pose); if None (default), the
            file's z up when the object rests stably that way, else the stable pose (as it would
            fall), saying so with an `UnstablePoseWarning`. O's axes are the file's either way.
        closest_primitive: Ground truth for shape resemblance if known ('sphere', 'cylinder',
            'box'); default None.
        rgba: Visual colour.
        friction: Coulomb friction of this object; None uses the scene's.
        largest_component: Keep the largest of several separate components instead of failing.
        join_gap: Shells whose surfaces come this close (m) are one object; default
            :func:`drake_grasp.objects.solid.join_gap` (2 mm or 2 % of the largest extent).

    Raises:
        ObjectError: One line naming the file and the problem.
    """
    label = os.fspath(path)
    path = Path(path).expanduser()
    if closest_primitive not in (None, *PRIMITIVE_NAMES):
        raise ObjectError(
            f"{label}: closest_primitive must be one of {PRIMITIVE_NAMES}, "
            f"got {closest_primitive!r}"
        )
    if not (scale > 0.0 and math.isfinite(scale)):
        raise ObjectError(f"{label}: scale must be positive, got {scale!r}")
    if join_gap is not None and not (join_gap >= 0.0 and math.isfinite(join_gap)):
        raise ObjectError(f"{label}: join gap must be a distance >= 0 (m), got {join_gap!r}")
    mesh = _read_mesh(path, label, scale)
    return object_from_triangles(
        mesh, label, path.stem, _content_digest(path), str(path.resolve()), mass=mass,
        name=name, density=density, scale=scale, max_pieces=max_pieces, stable_pose=stable_pose,
        closest_primitive=closest_primitive, rgba=rgba, friction=friction, largest_component=largest_component,
        join_gap=join_gap)


def object_from_triangles(
    mesh: trimesh.Trimesh,
    label: str,
    stem: str,
    digest: str,
    source: str,
    *,
    mass: float | None = None,
    name: str | None = None,
    density: float = DEFAULT_DENSITY,
    scale: float = 1.0,
    max_pieces: int = DEFAULT_MAX_PIECES,
    stable_pose: bool | None = None,
    closest_primitive: str | None = None,
    rgba=YELLOW_PAPER_RGBA,
    friction: float | None = None,
    largest_component: bool = False,
    join_gap: float | None = None,
    inertia=None,
    one_body: bool = False,
) -> ObjectSpec:
    """The object a file's triangles describe (metres, in the file's frame), as
    :func:`object_from_mesh` makes it: `label` names the file in messages, `stem` names the model,
    `digest` (the content's hash) keys the cached decomposition, `source` is recorded. `inertia`,
    if given, is a function (volume, centroid, unit inertia, mass) → (mass, centroid, unit inertia)
    that replaces the mass properties computed from the solid (a model file's checked inertial).
    `one_body`: the triangles are the geoms of one body a model file declares rigid, so parts
    farther apart than the join gap are its parts, not an error (:func:`_user_solid`)."""
    if len(mesh.faces) > MAX_FACES:  # Said first: what follows takes a while on such a mesh.
        warnings.warn(f"{label}: {len(mesh.faces):,} faces; simplifying to {MAX_FACES:,} for contact and rendering",
                      MeshNote, stacklevel=2)
    if not largest_component:  # Refused before the repair (kept parts may still make it graspable).
        sizes.check_size(mesh.vertices[np.unique(mesh.faces)], label, scale, warn=False)
    solid_key = hashlib.sha256((f"{digest}|{scale!r}|{join_gap!r}|{largest_component}"
                                + ("|one-body" if one_body else "")).encode()).hexdigest()[:24]
    mesh = _cached_solid(mesh, label, solid_key, join_gap, largest_component, one_body)
    sizes.check_size(mesh.vertices, label, scale)
    settings = (f"{scale!r}|{max_pieces}|{COACD_THRESHOLD!r}|{CONVEXITY_TOLERANCE!r}|{largest_component}|{MAX_FACES}"
                f"|{join_gap!r}")
    key = hashlib.sha256((digest + settings).encode()).hexdigest()[:20]
    volume = float(mesh.volume)
    centroid = np.asarray(mesh.center_mass, float)
    unit_inertia = np.asarray(mesh.moment_inertia, float) / float(mesh.mass)
    contact_mesh = _simplified(mesh, label)
    piece_paths = _decompose(contact_mesh, f"{_model_name(stem)}-{key}", max_pieces, label)
    pieces = [ShapePiece("convex", (), mesh_path=p) for p in piece_paths]
    if inertia is not None:
        mass, centroid, unit_inertia = inertia(volume, centroid, unit_inertia, mass)

    def spec(rpy_TO: tuple[float, float, float]) -> ObjectSpec:
        return _make_spec(name or _model_name(stem), pieces, mass, density=density,
                          mass_properties=(volume, centroid, unit_inertia), rpy_TO=rpy_TO,
                          closest_primitive=closest_primitive, rgba=rgba, friction=friction, source=source)

    standing = spec((0.0, 0.0, 0.0))
    hull = contact_mesh.convex_hull
    upright = stable_pose is None and _rests_stably_upright(hull, centroid)
    if upright and _narrowly_upright(hull, centroid) and not stays_up_in_simulator(standing):
        # On its lowest face, but only just: set down as a hand sets it, it falls in the simulator.
        warnings.warn(f"{label}: with its z up the object would tip over (its centre of mass is only just inside "
                      "its base, and set down 2° from upright it falls); resting it on its most stable face",
                      UnstablePoseWarning, stacklevel=2)
        stable_pose = True
    if stable_pose is None and not upright:
        # A scanned base is not one plane (YCB's cans and bottles stand on a bulge or a rim): where the
        # lowest-face test sees an edge or a point but a base of vertices near it carries the body, the
        # station's simulator says whether it stands.
        if not clearly_tips_over(hull, centroid) and stays_up_in_simulator(standing):
            return standing
        warnings.warn(f"{label}: with its z up the object would tip over (it rests on an edge or a point, "
                      "or its centre of mass is not over its base); resting it on its most stable face",
                      UnstablePoseWarning, stacklevel=2)
        stable_pose = True
    if not stable_pose:
        return standing
    return spec(tuple(RollPitchYaw(_lowest_resting_rotation(hull, centroid)).vector()))
