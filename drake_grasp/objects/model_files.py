"""Objects from model files: SDFormat and URDF (parsed by Drake) and MuJoCo MJCF object files (read
here), with the file's inertia checked before it can reach the plant.

Why: a model file carries an inertial, and inertials in the wild are often placeholders (izz = 0,
1 kg·m² on a 0.1 kg object) that make the mass matrix singular or the object spin like a flywheel.
Every inertial read from a file is checked (:func:`inertia_problem`): finite and positive-definite,
the principal moments satisfy the triangle inequality, the moments fit inside the collision
geometry (no principal moment above mass × the largest distance of the geometry from the centre of
mass, squared), and the mass implies a plausible density for the collision geometry's volume (20 to
20,000 kg/m³: from expanded foam to tungsten). An implausible inertial is replaced by the one the
collision geometry gives at uniform density (keeping a plausible mass), with a one-line
`InertiaWarning` that names the bad value; ``inertia="file"`` keeps the file's, and refuses one
that cannot be simulated. Nothing read from a file reaches the plant unchecked.

MJCF: Drake's MJCF parser reads only OBJ meshes, and MuJoCo-based benchmarks ship objects as one
body with STL mesh geoms, so MJCF object files are read here: the geoms of the body tree under
``worldbody`` (bodies nested without joints are one rigid body; a free joint is allowed), their
poses, MuJoCo's defaults (``<default>`` classes), the compiler's ``meshdir``/``assetdir`` and
``angle``, mesh ``scale``, and each geom's ``mass`` or ``density`` (MuJoCo's default 1000 kg/m³)
or the body's ``<inertial>``. Collision geoms are those MuJoCo would collide (``contype`` or
``conaffinity`` non-zero); if none, every geom. The geoms become one mesh in the body frame that
goes through the same repair and joining as a mesh file (:mod:`drake_grasp.objects.mesh_files`).
"""

from __future__ import annotations

import hashlib
import math
import os
import warnings
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import numpy as np
import trimesh
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Mesh, Shape, Sphere
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.parsing import Parser

from drake_grasp.objects.mesh_files import _load_checked_mesh, _model_name, _one_line, object_from_triangles
from drake_grasp.objects.pieces import IMPORT_VERSION, _decompose
from drake_grasp.objects.spec import (
    DEFAULT_DENSITY, DEFAULT_MAX_PIECES, InertiaWarning, ObjectError, ObjectSpec, ShapePiece, YELLOW_PAPER_RGBA,
    _cached_hull_obj,
)
from drake_grasp.objects.mass_properties import (
    _make_spec, _mass_properties_sampled, _mass_properties_summed, _piece_points,
)

PLAUSIBLE_DENSITY = (20.0, 20_000.0)  # kg/m³: expanded foam to tungsten
INERTIA_CHOICES = ("check", "file", "geometry")


# --- Inertia checks (pure) --------------------------------------------------------------------------


def inertia_problem(mass: float, inertia: np.ndarray, volume: float | None = None,
                    radius: float | None = None) -> str | None:
    """Why an inertial cannot be simulated or is implausible for its geometry, or None.

    Args:
        mass: kg.
        inertia: 3×3 rotational inertia about the centre of mass, kg·m².
        volume: the collision geometry's volume (m³), for the density check; None skips it.
        radius: the largest distance (m) of the collision geometry from the centre of mass; None
            skips the size check.
    """
    inertia = np.asarray(inertia, float)
    if not (math.isfinite(mass) and mass > 0.0):
        return f"mass {mass:g} kg is not positive"
    if not np.all(np.isfinite(inertia)):
        return "the inertia has a non-finite entry"
    if not np.allclose(inertia, inertia.T, rtol=1e-9, atol=1e-15):
        return "the inertia is not symmetric"
    moments = np.linalg.eigvalsh(inertia)
    if moments[0] <= 1e-12 * max(moments[-1], 1e-300) or moments[0] <= 0.0:
        return f"the inertia is not positive-definite (principal moments {_moments(moments)} kg·m²)"
    if moments[2] > (moments[0] + moments[1]) * (1.0 + 1e-6):
        return f"the principal moments {_moments(moments)} kg·m² break the triangle inequality"
    if volume is not None and volume > 0.0:
        density = mass / volume
        if not PLAUSIBLE_DENSITY[0] <= density <= PLAUSIBLE_DENSITY[1]:
            return (f"mass {mass:g} kg in {volume * 1e6:.4g} cm³ of collision geometry is a density of "
                    f"{density:.4g} kg/m³ (plausible: {PLAUSIBLE_DENSITY[0]:g} to {PLAUSIBLE_DENSITY[1]:g})")
    if radius is not None and radius > 0.0 and moments[2] > 1.01 * mass * radius**2:
        return (f"principal moment {moments[2]:.3g} kg·m² exceeds what {mass:g} kg within {radius * 100:.3g} cm "
                f"of its centre of mass can have ({mass * radius**2:.3g} kg·m²)")
    return None


def simulable_problem(mass: float, inertia: np.ndarray) -> str | None:
    """Why an inertial cannot be simulated at all (not finite, not positive-definite, the triangle
    inequality broken), or None: what ``inertia="file"`` still refuses."""
    return inertia_problem(mass, inertia)


def _moments(moments: np.ndarray) -> str:
    return ", ".join(f"{m:.3g}" for m in moments)


def checked_mass_properties(label: str, file_mass: float, file_com: np.ndarray, file_inertia: np.ndarray,
                            geometry: tuple[float, np.ndarray, np.ndarray], radius_about, choice: str,
                            density: float = DEFAULT_DENSITY) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, unit inertia about it) for an object whose file gives `file_mass`
    (kg), `file_com` and `file_inertia` (kg·m² about file_com) and whose collision geometry gives
    `geometry` = (volume, centroid, unit inertia about it). `radius_about(point)` is the geometry's
    largest distance from a point. `choice`: "check" (the file's if plausible, else the geometry's
    with an InertiaWarning), "file" (the file's; ObjectError if it cannot be simulated), "geometry".
    """
    volume, centroid, unit_inertia = geometry
    if choice == "file":
        problem = simulable_problem(file_mass, file_inertia)
        if problem:
            raise ObjectError(f"{label}: the file's inertia cannot be simulated: {problem}")
        return file_mass, np.asarray(file_com, float), np.asarray(file_inertia, float) / file_mass
    if choice == "check":
        problem = inertia_problem(file_mass, file_inertia, volume, radius_about(np.asarray(file_com, float)))
        if problem is None:
            return file_mass, np.asarray(file_com, float), np.asarray(file_inertia, float) / file_mass
        mass = file_mass
        if not (math.isfinite(mass) and PLAUSIBLE_DENSITY[0] <= mass / volume <= PLAUSIBLE_DENSITY[1]):
            mass = density * volume
        warnings.warn(f"{label}: implausible inertia in the file ({problem}); using the collision geometry's "
                      f"at uniform density ({mass:.4g} kg; --inertia file keeps the file's)", InertiaWarning,
                      stacklevel=3)
        return mass, centroid, unit_inertia
    return (file_mass if math.isfinite(file_mass) and file_mass > 0 else density * volume), centroid, unit_inertia


def _check_choice(label: str, choice: str) -> None:
    if choice not in INERTIA_CHOICES:
        raise ObjectError(f"{label}: inertia must be one of {', '.join(INERTIA_CHOICES)}, got {choice!r}")
def _piece_from_drake_shape(
    shape: Shape, X_BG: RigidTransform, label: str, max_pieces: int
) -> list[ShapePiece]:
    """Pieces (posed in the body frame B) for one collision geometry of a parsed SDF."""
    p = tuple(float(v) for v in X_BG.translation())
    rpy = tuple(float(v) for v in RollPitchYaw(X_BG.rotation()).vector())
    if isinstance(shape, Sphere):
        return [ShapePiece("sphere", (shape.radius(),), p, rpy)]
    if isinstance(shape, Ellipsoid):
        return [ShapePiece("ellipsoid", (shape.a(), shape.b(), shape.c()), p, rpy)]
    if isinstance(shape, Box):
        return [ShapePiece("box", (shape.width(), shape.depth(), shape.height()), p, rpy)]
    if isinstance(shape, Cylinder):
        return [ShapePiece("cylinder", (shape.radius(), shape.length()), p, rpy)]
    if isinstance(shape, Capsule):
        return [ShapePiece("capsule", (shape.radius(), shape.length()), p, rpy)]
    if isinstance(shape, Convex):
        hull = shape.GetConvexHull()  # Scaled, in G; works for every format Drake reads.
        vertices = np.array([hull.vertex(i) for i in range(hull.num_vertices())])
        return [ShapePiece("convex", (), p, rpy, _cached_hull_obj("sdf_convex", vertices))]
    if isinstance(shape, Mesh):
        scale = np.asarray(shape.scale3())
        if not np.allclose(scale, scale[0]):
            raise ObjectError(f"{label}: non-uniform mesh scale is not supported")
        mesh = _load_checked_mesh(Path(shape.source().path()), label, float(scale[0]))
        key = hashlib.sha256(Path(shape.source().path()).read_bytes()).hexdigest()[:20]
        paths = _decompose(mesh, f"sdf_mesh-{key}-{float(scale[0])!r}-{max_pieces}", max_pieces, label)
        return [ShapePiece("convex", (), p, rpy, path) for path in paths]
    raise ObjectError(f"{label}: collision shape {type(shape).__name__} is not supported")


def object_from_sdf(
    path: str | os.PathLike,
    mass: float | None = None,
    name: str | None = None,
    *,
    density: float = DEFAULT_DENSITY,
    max_pieces: int = DEFAULT_MAX_PIECES,
    closest_primitive: str | None = None,
    rgba=YELLOW_PAPER_RGBA,
    friction: float | None = None,
    inertia: str = "check",
) -> ObjectSpec:
    """An object from an SDFormat (or URDF) file with one model of one free body.

    The file is parsed by Drake; its body's collision geometries become the pieces (non-convex
    meshes are decomposed like :func:`object_from_mesh`), its inertial gives mass, centre of mass
    and inertia (a missing or zero mass falls back to `mass` or density × volume). O is placed at
    the body's centre of mass with the body frame's axes; the object rests with its z up.

    Limits: one model with one body and no joints (not welded, not articulated); the file's
    visuals, friction and contact properties are replaced by ours (pieces drawn in `rgba`, the
    scene's ContactParameters); ``package://`` URIs need the package to be findable by Drake's
    default PackageMap; half spaces, height maps and other non-solid shapes are rejected.

    Args:
        path: The model file (.sdf or .urdf).
        mass: Mass (kg); default the file's, else density × volume.
        name: Model name; default the file's model name.
        density: Density (kg/m³) when neither `mass` nor the file gives one.
        max_pieces: Most convex pieces of a decomposed non-convex mesh.
        closest_primitive: Ground truth for shape resemblance if known.
        rgba: Visual colour.
        friction: Coulomb friction of this object; None uses the scene's.
        inertia: "check" (the file's inertial if plausible, else the collision geometry's, with an
            InertiaWarning), "file" (the file's; ObjectError if it cannot be simulated) or
            "geometry" (the collision geometry's at uniform density, with the file's mass).

    Raises:
        ObjectError: One line naming the file and the problem.
    """
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    label = os.fspath(path)
    path = Path(path).expanduser()
    _check_choice(label, inertia)
    if not path.is_file():
        raise ObjectError(f"{label}: file not found")
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
    try:
        models = Parser(plant).AddModels(str(path.resolve()))
    except Exception as error:  # Drake raises RuntimeError with multi-line messages.
        raise ObjectError(f"{label}: cannot parse ({_one_line(error)})") from None
    if len(models) != 1:
        raise ObjectError(f"{label}: expected one model, found {len(models)}")
    (model,) = models
    bodies = [plant.get_body(index) for index in plant.GetBodyIndices(model)]
    if len(bodies) != 1:
        raise ObjectError(f"{label}: expected one body, found {len(bodies)}")
    if plant.GetJointIndices(model):
        raise ObjectError(f"{label}: the body must be free (the model has joints or is static)")
    (body,) = bodies
    inspector = scene_graph.model_inspector()
    pieces_B = []
    for geometry_id in plant.GetCollisionGeometriesForBody(body):
        shape, X_BG = inspector.GetShape(geometry_id), inspector.GetPoseInFrame(geometry_id)
        pieces_B += _piece_from_drake_shape(shape, X_BG, label, max_pieces)
    if not pieces_B:
        raise ObjectError(f"{label}: the body has no collision geometry")
    file_mass = body.default_mass()
    mass_properties = None
    if file_mass > 0.0 and math.isfinite(file_mass):
        p_BScm = np.asarray(body.default_com(), float)
        unit_inertia_Bo = body.default_unit_inertia().CopyToFullMatrix3()
        shift = np.dot(p_BScm, p_BScm) * np.eye(3) - np.outer(p_BScm, p_BScm)
        file_inertia = file_mass * (unit_inertia_Bo - shift)  # About the centre of mass.
        pieces = tuple(pieces_B)
        geometry = _mass_properties_summed(pieces) if len(pieces) == 1 else _mass_properties_sampled(pieces)
        points = np.vstack([_piece_points(piece) for piece in pieces])
        checked_mass, p_BScm, unit_inertia = checked_mass_properties(
            label, file_mass, p_BScm, file_inertia, geometry,
            lambda p: float(np.max(np.linalg.norm(points - p, axis=1))), inertia, density)
        mass_properties = (geometry[0], p_BScm, unit_inertia)
        mass = checked_mass if mass is None else mass
    return _make_spec(
        name or _model_name(plant.GetModelInstanceName(model)),
        pieces_B,
        mass,
        density=density,
        mass_properties=mass_properties,
        closest_primitive=closest_primitive,
        rgba=rgba,
        friction=friction,
        source=str(path.resolve()),
    )




# --- MJCF ---------------------------------------------------------------------------------------

_MJCF_DEFAULT_DENSITY = 1000.0  # kg/m³: MuJoCo's default geom density


def _floats(text: str | None, count: int | None = None, label: str = "") -> np.ndarray | None:
    if text is None:
        return None
    try:
        values = np.array([float(v) for v in text.split()], float)
    except ValueError:
        raise ObjectError(f"{label}: bad number list {text!r}") from None
    if count is not None and len(values) != count:
        raise ObjectError(f"{label}: expected {count} numbers, got {text!r}")
    return values


def _mjcf_rotation(element, degrees: bool, label: str) -> np.ndarray:
    """The rotation an MJCF element's quat, axisangle, euler (xyz) or zaxis gives (3×3)."""
    if element.get("quat") is not None:
        w, x, y, z = _floats(element.get("quat"), 4, label)
        return RotationMatrix(_quaternion(w, x, y, z)).matrix()
    if element.get("axisangle") is not None:
        ax, ay, az, angle = _floats(element.get("axisangle"), 4, label)
        angle = math.radians(angle) if degrees else angle
        return trimesh.transformations.rotation_matrix(angle, [ax, ay, az])[:3, :3]
    if element.get("euler") is not None:
        angles = _floats(element.get("euler"), 3, label)
        angles = np.radians(angles) if degrees else angles
        return trimesh.transformations.euler_matrix(*angles, axes="rxyz")[:3, :3]
    if element.get("zaxis") is not None:
        z = _floats(element.get("zaxis"), 3, label)
        return trimesh.geometry.align_vectors([0, 0, 1], z / np.linalg.norm(z))[:3, :3]
    return np.eye(3)


def _quaternion(w, x, y, z):
    from pydrake.common.eigen_geometry import Quaternion

    q = np.array([w, x, y, z], float)
    return Quaternion(q / np.linalg.norm(q))


def _mjcf_defaults(root) -> dict:
    """Geom attributes of each default class ("main" is the top level), inheriting from parents."""
    classes = {"main": {}}

    def walk(element, inherited, name):
        attributes = dict(inherited)
        geom = element.find("geom")
        if geom is not None:
            attributes.update(geom.attrib)
        classes[name] = attributes
        for child in element.findall("default"):
            walk(child, attributes, child.get("class", name))

    for top in root.findall("default"):
        walk(top, {}, top.get("class", "main"))
    return classes


def _geom_mesh(geom: dict, meshes: dict, label: str) -> trimesh.Trimesh:
    """One MJCF geom as a closed triangle mesh in its own frame (m)."""
    kind = geom.get("type", "sphere")
    size = _floats(geom.get("size", "0 0 0"), None, label)
    if kind == "mesh":
        name = geom.get("mesh")
        if name not in meshes:
            raise ObjectError(f"{label}: geom names mesh {name!r}, which the file's assets do not define")
        return meshes[name].copy()
    if kind == "box":
        return trimesh.creation.box(2.0 * size[:3])
    if kind == "sphere":
        return trimesh.creation.icosphere(subdivisions=3, radius=size[0])
    if kind == "ellipsoid":
        sphere = trimesh.creation.icosphere(subdivisions=3)
        sphere.apply_scale(size[:3])
        return sphere
    if kind == "cylinder":
        return trimesh.creation.cylinder(radius=size[0], height=2.0 * size[1], sections=32)
    if kind == "capsule":
        return trimesh.creation.capsule(radius=size[0], height=2.0 * size[1], count=[32, 16])
    raise ObjectError(f"{label}: geom type {kind!r} is not a solid an object can be made of")


def _read_mjcf(path: Path, label: str) -> tuple[trimesh.Trimesh, float, tuple | None, str]:
    """(collision mesh in the root body's frame, mass from the geoms (kg), the body's explicit
    inertial (mass, com, inertia) or None, a digest of the file and its meshes)."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError) as error:
        raise ObjectError(f"{label}: cannot parse ({_one_line(error)})") from None
    if root.tag != "mujoco":
        raise ObjectError(f"{label}: not an MJCF file (its root element is <{root.tag}>, not <mujoco>)")
    compiler = root.find("compiler")
    compiler = compiler.attrib if compiler is not None else {}
    degrees = compiler.get("angle", "degree") != "radian"
    base = path.parent
    meshdir = base / compiler.get("meshdir", compiler.get("assetdir", ""))
    digest = hashlib.sha256(path.read_bytes())
    meshes = {}
    for asset in root.iter("asset"):
        for mesh in asset.findall("mesh"):
            file = mesh.get("file")
            if file is None:
                raise ObjectError(f"{label}: a mesh asset without a file (inline vertices are not supported)")
            mesh_path = meshdir / file
            name = mesh.get("name", Path(file).stem)
            if not mesh_path.is_file():
                raise ObjectError(f"{label}: mesh {name!r}: {mesh_path} not found")
            try:
                loaded = trimesh.load(mesh_path, force="mesh", process=False)
            except Exception as error:
                raise ObjectError(f"{label}: mesh {name!r}: cannot read {mesh_path.name} ({_one_line(error)})") from None
            if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
                raise ObjectError(f"{label}: mesh {name!r}: {mesh_path.name} contains no triangles")
            loaded = trimesh.Trimesh(np.asarray(loaded.vertices, float), np.asarray(loaded.faces, np.int64),
                                     process=False)
            scale = _floats(mesh.get("scale"), 3, label)
            if scale is not None:
                loaded.apply_transform(np.diag([*scale, 1.0]))
            meshes[name] = loaded
            digest.update(mesh_path.read_bytes())
    worldbody = root.find("worldbody")
    if worldbody is None:
        raise ObjectError(f"{label}: the file has no <worldbody>")
    defaults = _mjcf_defaults(root)
    pieces, mass_from_geoms, inertial = [], 0.0, None
    bodies = worldbody.findall("body")
    if len(bodies) != 1:
        raise ObjectError(f"{label}: expected one top-level body, found {len(bodies)}")

    def walk(body, X_RB: np.ndarray, default_class: str):
        nonlocal inertial
        for joint in body.findall("joint"):
            if joint.get("type", "hinge") != "free":
                raise ObjectError(f"{label}: the object is articulated (a {joint.get('type', 'hinge')} joint); "
                                  "one rigid body is expected")
        for element in body.findall("inertial"):
            mass = float(element.get("mass", "nan"))
            R = _mjcf_rotation(element, degrees, label)
            if element.get("fullinertia") is not None:
                xx, yy, zz, xy, xz, yz = _floats(element.get("fullinertia"), 6, label)
                inertia = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
            else:
                inertia = np.diag(_floats(element.get("diaginertia", "nan nan nan"), 3, label))
            pos = _floats(element.get("pos", "0 0 0"), 3, label)
            R_R = X_RB[:3, :3] @ R
            if inertial is not None:
                raise ObjectError(f"{label}: several bodies carry an <inertial>; one rigid body is expected")
            inertial = (mass, X_RB[:3, :3] @ pos + X_RB[:3, 3], R_R @ inertia @ R_R.T)
        for element in body.findall("geom"):
            cls = element.get("childclass", None) or element.get("class", default_class)
            geom = dict(defaults.get(cls, defaults["main"]))
            geom.update(element.attrib)
            collides = geom.get("contype", "1") != "0" or geom.get("conaffinity", "1") != "0"
            if element.get("fromto") is not None:
                raise ObjectError(f"{label}: geoms given by 'fromto' are not supported; give pos and quat")
            mesh = _geom_mesh(geom, meshes, label)
            X_BG = np.eye(4)
            X_BG[:3, :3] = _mjcf_rotation(element, degrees, label)
            X_BG[:3, 3] = _floats(geom.get("pos", "0 0 0"), 3, label)
            mesh.apply_transform(X_RB @ X_BG)
            pieces.append((collides, mesh, geom))
        for child in body.findall("body"):
            X_BC = np.eye(4)
            X_BC[:3, :3] = _mjcf_rotation(child, degrees, label)
            X_BC[:3, 3] = _floats(child.get("pos", "0 0 0"), 3, label)
            walk(child, X_RB @ X_BC, child.get("childclass", default_class))

    walk(bodies[0], np.eye(4), bodies[0].get("childclass", "main"))
    chosen = [p for p in pieces if p[0]] or pieces
    if not chosen:
        raise ObjectError(f"{label}: the body has no geoms")
    for _, mesh, geom in chosen:
        if geom.get("mass") is not None:
            mass_from_geoms += float(geom["mass"])
        else:
            volume = abs(float(mesh.volume)) if mesh.is_watertight else float(mesh.convex_hull.volume)
            mass_from_geoms += float(geom.get("density", _MJCF_DEFAULT_DENSITY)) * volume
    collision = trimesh.util.concatenate([mesh for _, mesh, _ in chosen])
    return collision, mass_from_geoms, inertial, digest.hexdigest()


def object_from_mjcf(
    path: str | os.PathLike,
    mass: float | None = None,
    name: str | None = None,
    *,
    density: float = DEFAULT_DENSITY,
    max_pieces: int = DEFAULT_MAX_PIECES,
    closest_primitive: str | None = None,
    rgba=YELLOW_PAPER_RGBA,
    friction: float | None = None,
    inertia: str = "check",
    join_gap: float | None = None,
    largest_component: bool = False,
    scale: float = 1.0,
) -> ObjectSpec:
    """An object from a MuJoCo MJCF object file (one rigid body of mesh or primitive geoms).

    The collision geoms become one mesh in the top body's frame, repaired and joined like a mesh
    file's (:func:`drake_grasp.objects.mesh_files.object_from_mesh`); its mass is `mass`, else the body's
    ``<inertial>`` mass, else the geoms' (``mass``, or ``density`` × volume). The inertial, if the
    file gives one, is checked (:func:`inertia_problem`; `inertia` as in :func:`object_from_sdf`);
    without one the inertia is the collision geometry's at uniform density, as MuJoCo computes it.
    The object rests with the body frame's z up (laid on a stable face if it would tip over).

    Raises:
        ObjectError: One line naming the file and the problem.
    """
    label = os.fspath(path)
    path = Path(path).expanduser()
    _check_choice(label, inertia)
    if not path.is_file():
        raise ObjectError(f"{label}: file not found")
    collision, geom_mass, inertial, digest = _read_mjcf(path, label)
    collision.apply_scale(scale)

    def mass_properties(volume, centroid, unit_inertia, requested_mass):
        file_mass = inertial[0] if inertial is not None else geom_mass
        if inertial is None or inertia == "geometry":
            chosen = file_mass if requested_mass is None else requested_mass
            return chosen, centroid, unit_inertia
        vertices = np.asarray(collision.vertices)
        checked_mass, com, unit = checked_mass_properties(
            label, file_mass, inertial[1] * scale, inertial[2] * scale**2, (volume, centroid, unit_inertia),
            lambda p: float(np.max(np.linalg.norm(vertices - p, axis=1))), inertia, density)
        return (checked_mass if requested_mass is None else requested_mass), com, unit

    return object_from_triangles(
        collision, label, path.stem, f"{digest}-mjcf{IMPORT_VERSION}", str(path.resolve()), mass=mass,
        name=name, density=density, scale=scale, max_pieces=max_pieces, closest_primitive=closest_primitive,
        rgba=rgba, friction=friction, largest_component=largest_component, join_gap=join_gap,
        inertia=mass_properties)
