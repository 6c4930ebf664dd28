"""Objects from model files: SDFormat and URDF (parsed by Drake) and MuJoCo MJCF object files (read
here), with the file's inertia checked before it can reach the plant.

SDFormat and URDF: Drake's parser takes mesh geometry only as OBJ, VTK or glTF (any other format is
refused with "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes"), while URDFs exported by
CAD tools and ROS packages commonly name STL, PLY or DAE meshes. Such a mesh is converted to an OBJ
in the cache (named by its content's hash; never beside the user's file) and the model text given to
the parser names the OBJ (:func:`drake_grasp.objects.readable_models.drake_readable_model`, which also
frees a static model); units and the file's ``scale`` are unchanged.

Every inertial read from a file is checked (:mod:`drake_grasp.objects.inertia_checks`), and an
implausible one replaced by the collision geometry's, before it can reach the plant.

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
import re
import warnings
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import numpy as np
import trimesh
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Mesh, Shape, Sphere
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.parsing import Parser

from drake_grasp.objects.mesh_files import (
    _load_checked_mesh, _model_name, _one_line, _scale_key, object_from_triangles, read_triangles,
)
from drake_grasp.objects import packages, sizes
from drake_grasp.objects.readable_models import drake_readable_model, quiet_unsupported_elements
from drake_grasp.objects.pieces import IMPORT_VERSION, _decompose
from drake_grasp.objects.spec import (
    DEFAULT_DENSITY, DEFAULT_MAX_PIECES, InertiaWarning, MeshNote, ObjectError, ObjectSpec, ShapePiece,
    YELLOW_PAPER_RGBA,
    _cached_hull_obj,
)
from drake_grasp.objects.mass_properties import (
    _make_spec, _mass_properties_sampled, _mass_properties_summed, _piece_points,
)
from drake_grasp.objects.inertia_checks import (  # noqa: F401  (re-exported: model files' inertia checks)
    INERTIA_CHOICES, PLAUSIBLE_DENSITY, _check_choice, checked_mass_properties, inertia_problem, simulable_problem,
)



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
        scale = np.asarray(shape.scale3(), float)  # per axis: a model file may scale a mesh unevenly
        mesh = _load_checked_mesh(Path(shape.source().path()), label, scale)
        key = hashlib.sha256(Path(shape.source().path()).read_bytes()).hexdigest()[:20]
        paths = _decompose(mesh, f"sdf_mesh-{key}-{_scale_key(scale)}-{max_pieces}", max_pieces, label)
        return [ShapePiece("convex", (), p, rpy, path) for path in paths]
    raise ObjectError(f"{label}: collision shape {type(shape).__name__} is not supported")


def _one_mesh_mass_properties(geometries, label: str) -> tuple[float, np.ndarray, np.ndarray] | None:
    """(volume m³, centroid in B, unit inertia m² about it in B) of a body whose collision geometry
    is one mesh, exact from its solid (cached; sampling its convex pieces takes seconds); else None."""
    if len(geometries) != 1 or not isinstance(geometries[0][0], Mesh):
        return None
    shape, X_BG = geometries[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # its notes were given when its pieces were made
        solid = _load_checked_mesh(Path(shape.source().path()), label, np.asarray(shape.scale3(), float))
    R_BG = X_BG.rotation().matrix()
    unit_inertia = np.asarray(solid.moment_inertia, float) / float(solid.mass)
    return float(solid.volume), R_BG @ np.asarray(solid.center_mass) + X_BG.translation(), R_BG @ unit_inertia @ R_BG.T


def non_finite_number(path: Path) -> str | None:
    """Where an SDFormat or URDF file gives a number that is NaN or inf (a size, a mass, a pose),
    named by its element's path, e.g. "link 'l' inertial mass 'nan'"; None if every number is finite
    or the file is not XML (the parser says why). Drake would stop at a NaN size with a generic parse
    error, and replace a NaN mass by a default one with a warning."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError):
        return None
    parents = {child: parent for parent in root.iter() for child in parent}
    for element in root.iter():
        texts = [(element.tag, element.text)] + [(f"{element.tag} {k}", v) for k, v in element.attrib.items()]
        for what, text in texts:
            try:
                values = [float(token) for token in (text or "").split()]
            except ValueError:
                continue
            if values and not all(math.isfinite(v) for v in values):
                where, node = [], parents.get(element)
                while node is not None and node is not root:
                    where.insert(0, f"{node.tag} {node.get('name')!r}" if node.get("name") else node.tag)
                    node = parents.get(node)
                return " ".join(where + [what, repr(text.strip())])
    return None


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
    package_path=(),
) -> ObjectSpec:
    """An object from an SDFormat (or URDF) file with one model of one free body.

    The file is parsed by Drake; its body's collision geometries become the pieces (non-convex
    meshes are decomposed like :func:`object_from_mesh`), its inertial gives mass, centre of mass
    and inertia (a missing or zero mass falls back to `mass` or density × volume). O is placed at
    the body's centre of mass with the body frame's axes; the object rests with its z up.

    Limits: one model with one body and no joints (not welded, not articulated); the file's
    visuals, friction and contact properties are replaced by ours (pieces drawn in `rgba`, the
    scene's ContactParameters; a compliant hydroelastic ``.vtk`` mesh is read as its boundary
    surface); a mesh Drake cannot read (STL, PLY, DAE, GLB) is read from an OBJ converted into the
    cache (:func:`drake_readable_model`); ``package://`` URIs resolve against the package.xml files
    in the file's folder and above it and under `package_path`, Gazebo's ``model://`` URIs against
    model folders there and on its model path (:mod:`drake_grasp.objects.packages`), else Drake's
    default PackageMap; a static model is loaded free (a note); half spaces, height maps and other non-solid shapes are
    rejected. An object no hand can grasp is refused (:mod:`drake_grasp.objects.sizes`).

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
        package_path: Folders holding a package.xml, or with package.xml files below them.

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
    where = non_finite_number(path)
    if where:
        raise ObjectError(f"{label}: {where} is not finite (NaN or inf)")
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
    parser = Parser(plant)
    local = packages.register_packages(parser.package_map(), path, package_path)
    problem = packages.missing_package_problem(path.read_text(errors="replace"), parser.package_map(), local, path)
    if problem:
        raise ObjectError(f"{label}: {problem}")
    kind = path.suffix.lower().lstrip(".")
    text = drake_readable_model(path, label, parser.package_map(), local) if kind in ("sdf", "urdf") else None
    try:
        with packages.quiet_downloads(), quiet_unsupported_elements():
            if text is None:
                models = parser.AddModels(str(path.resolve()))
            else:
                models = parser.AddModelsFromString(text, kind)
    except Exception as error:  # Drake raises RuntimeError with multi-line messages.
        message = str(error).replace(f"<literal-string>.{kind}", str(path.resolve()))
        problem = (packages.download_problem(message, local) or _missing_file_problem(message)
                   or f"cannot parse ({_one_line(message)})")
        raise ObjectError(f"{label}: {problem}") from None
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
    geometries = [(inspector.GetShape(g), inspector.GetPoseInFrame(g))
                  for g in plant.GetCollisionGeometriesForBody(body)]
    pieces_B = []
    for shape, X_BG in geometries:
        pieces_B += _piece_from_drake_shape(shape, X_BG, label, max_pieces)
    if not pieces_B:
        raise ObjectError(f"{label}: the body has no collision geometry")
    points = np.vstack([_piece_points(piece) for piece in pieces_B])
    sizes.check_size(points, label)
    file_mass = body.default_mass()
    mass_properties = None
    if file_mass > 0.0 and math.isfinite(file_mass):
        p_BScm = np.asarray(body.default_com(), float)
        unit_inertia_Bo = body.default_unit_inertia().CopyToFullMatrix3()
        shift = np.dot(p_BScm, p_BScm) * np.eye(3) - np.outer(p_BScm, p_BScm)
        file_inertia = file_mass * (unit_inertia_Bo - shift)  # About the centre of mass.
        pieces = tuple(pieces_B)
        geometry = (_one_mesh_mass_properties(geometries, label) or
                    (_mass_properties_summed(pieces) if len(pieces) == 1 else _mass_properties_sampled(pieces)))
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


def _floats(text: str | None, count: int | None = None, label: str = "", what: str = "number list"
            ) -> np.ndarray | None:
    """The numbers of an attribute (None if absent); ObjectError naming `what` if they are not
    numbers, not `count` of them, or not finite (a NaN size must not pass for a flat sheet)."""
    if text is None:
        return None
    try:
        values = np.array([float(v) for v in text.split()], float)
    except ValueError:
        raise ObjectError(f"{label}: bad {what} {text!r}") from None
    if count is not None and len(values) != count:
        raise ObjectError(f"{label}: {what}: expected {count} numbers, got {text!r}")
    if not np.all(np.isfinite(values)):
        raise ObjectError(f"{label}: {what} {text!r} is not finite (NaN or inf)")
    return values


def _geom_name(geom: dict) -> str:
    return f"geom {geom['name']!r}" if geom.get("name") else f"{geom.get('type', 'sphere')} geom"


def _mjcf_rotation(element, degrees: bool, label: str) -> np.ndarray:
    """The rotation an MJCF element's quat, axisangle, euler (xyz) or zaxis gives (3×3)."""
    if element.get("quat") is not None:
        w, x, y, z = _floats(element.get("quat"), 4, label, f"{element.tag} quat")
        return RotationMatrix(_quaternion(w, x, y, z)).matrix()
    if element.get("axisangle") is not None:
        ax, ay, az, angle = _floats(element.get("axisangle"), 4, label, f"{element.tag} axisangle")
        angle = math.radians(angle) if degrees else angle
        return trimesh.transformations.rotation_matrix(angle, [ax, ay, az])[:3, :3]
    if element.get("euler") is not None:
        angles = _floats(element.get("euler"), 3, label, f"{element.tag} euler")
        angles = np.radians(angles) if degrees else angles
        return trimesh.transformations.euler_matrix(*angles, axes="rxyz")[:3, :3]
    if element.get("zaxis") is not None:
        z = _floats(element.get("zaxis"), 3, label, f"{element.tag} zaxis")
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
    size = _floats(geom.get("size", "0 0 0"), None, label, f"{_geom_name(geom)} size")
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


_MAX_INCLUDE_DEPTH = 16  # nested <include>s deeper than this are taken for a cycle


def _expand_includes(element, main_dir: Path, label: str, digest, depth: int = 0) -> None:
    """Replace each ``<include file="..."/>`` under `element` by the children of the file's root
    (``<mujocoinclude>``, or ``<mujoco>`` as MuJoCo 3 also allows), in place and recursively.

    MuJoCo resolves an included file's path against the main model file's folder, whichever file
    names it, and so does this. Object collections built for MuJoCo (RoboHive's object_sim, for one)
    keep the body's geoms, the assets and the defaults in separate files that the object's file
    includes; without this their bodies read as empty."""
    for index, child in reversed(list(enumerate(list(element)))):
        if child.tag != "include":
            _expand_includes(child, main_dir, label, digest, depth)
            continue
        file = child.get("file")
        if file is None:
            raise ObjectError(f"{label}: an <include> without a file")
        if depth >= _MAX_INCLUDE_DEPTH:
            raise ObjectError(f"{label}: <include> of {file!r} nests deeper than {_MAX_INCLUDE_DEPTH} files "
                              "(an include cycle?)")
        included_path = main_dir / file
        if not included_path.is_file():
            raise ObjectError(f"{label}: included file {file!r} not found (looked for {included_path})")
        try:
            included = ElementTree.parse(included_path).getroot()
        except (ElementTree.ParseError, OSError) as error:
            raise ObjectError(f"{label}: included file {file!r}: cannot parse ({_one_line(error)})") from None
        if included.tag not in ("mujocoinclude", "mujoco"):
            raise ObjectError(f"{label}: included file {file!r} is not MJCF (its root element is "
                              f"<{included.tag}>)")
        digest.update(included_path.read_bytes())
        _expand_includes(included, main_dir, label, digest, depth + 1)
        element.remove(child)
        for offset, grandchild in enumerate(list(included)):
            element.insert(index + offset, grandchild)


def _missing_file_problem(error_text: str) -> str | None:
    """A one-line reason for Drake's parse error on a file the model names that is not there (a mesh
    a collection keeps out of its repository, say), or None: which file, and where it was looked for."""
    match = re.search(r"URI '([^']+)' resolved to '([^']+)' which does not exist", error_text)
    if match is None:
        return None
    return f"mesh {match.group(1)}: file not found (looked for {os.path.normpath(match.group(2))})"


def _is_free(body) -> bool:
    """Whether an MJCF body moves freely: a ``<freejoint>``, or a ``<joint type="free">``, of its own."""
    return body.find("freejoint") is not None or any(j.get("type") == "free" for j in body.findall("joint"))


def _the_object_body(label: str, bodies: list) -> list:
    """The top-level body that is the object, as a one-element list (ObjectError otherwise).

    One body is the object. Among several, the object is the one that moves freely: a body without a
    joint is welded to the world in MuJoCo, so it is the file's scene. Meta-World's object files, for
    one, include a scene (a table, walls) beside the object's body, which has a ``<freejoint>``; those
    bodies are left out, with a note naming them."""
    if len(bodies) == 1:
        return bodies
    def names(group) -> str:
        return ", ".join(repr(body.get("name", "unnamed")) for body in group)

    free = [body for body in bodies if _is_free(body)]
    if len(free) != 1:
        moving = f" ({len(free)} free: {names(free)})" if len(free) > 1 else " (none free)" if bodies else ""
        raise ObjectError(f"{label}: expected one top-level body, found {len(bodies)}{moving}; give a file with "
                          "the object alone, or with one free body beside a fixed scene")
    scene = [body for body in bodies if body is not free[0]]
    warnings.warn(f"{label}: the object is the free body {free[0].get('name', 'unnamed')!r}; "
                  f"{len(scene)} fixed to the world (the file's scene: {names(scene)}) left out", MeshNote,
                  stacklevel=4)
    return free


def _read_mjcf(path: Path, label: str) -> tuple[trimesh.Trimesh, float, tuple | None, str]:
    """(collision mesh in the root body's frame, mass from the geoms (kg), the body's explicit
    inertial (mass, com, inertia) or None, a digest of the file, the files it includes and its
    meshes)."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError) as error:
        raise ObjectError(f"{label}: cannot parse ({_one_line(error)})") from None
    if root.tag != "mujoco":
        raise ObjectError(f"{label}: not an MJCF file (its root element is <{root.tag}>, not <mujoco>)")
    digest = hashlib.sha256(path.read_bytes())
    _expand_includes(root, path.parent, label, digest)
    compiler = {}  # MuJoCo merges every <compiler> element's attributes, the later ones winning
    for element in root.findall("compiler"):
        compiler.update(element.attrib)
    degrees = compiler.get("angle", "degree") != "radian"
    base = path.parent
    meshdir = base / compiler.get("meshdir", compiler.get("assetdir", ""))
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
            loaded = read_triangles(mesh_path, f"{label}: mesh {name!r}: {mesh_path.name}")
            scale = _floats(mesh.get("scale"), 3, label, f"mesh {name!r} scale")
            if scale is not None:
                loaded.apply_transform(np.diag([*scale, 1.0]))
            meshes[name] = loaded
            digest.update(mesh_path.read_bytes())
    worldbodies = root.findall("worldbody")  # several, once included files are in: MuJoCo merges them
    if not worldbodies:
        raise ObjectError(f"{label}: the file has no <worldbody>")
    defaults = _mjcf_defaults(root)
    pieces, mass_from_geoms, inertial = [], 0.0, None
    # The world's own geoms (a floor plane, say) are not the object: only bodies are.
    bodies = _the_object_body(label, [body for worldbody in worldbodies for body in worldbody.findall("body")])

    def walk(body, X_RB: np.ndarray, default_class: str):
        nonlocal inertial
        for joint in body.findall("joint"):
            if joint.get("type", "hinge") != "free":
                raise ObjectError(f"{label}: the object is articulated (a {joint.get('type', 'hinge')} joint); "
                                  "one rigid body is expected")
        for element in body.findall("inertial"):
            given = _floats(element.get("mass"), 1, label, "inertial mass")
            mass = math.nan if given is None else float(given[0])
            R = _mjcf_rotation(element, degrees, label)
            if element.get("fullinertia") is not None:
                xx, yy, zz, xy, xz, yz = _floats(element.get("fullinertia"), 6, label, "inertial fullinertia")
                inertia = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
            else:
                diagonal = _floats(element.get("diaginertia"), 3, label, "inertial diaginertia")
                inertia = np.diag(np.full(3, math.nan) if diagonal is None else diagonal)
            pos = _floats(element.get("pos", "0 0 0"), 3, label, "inertial pos")
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
            X_BG[:3, 3] = _floats(geom.get("pos", "0 0 0"), 3, label, f"{_geom_name(geom)} pos")
            mesh.apply_transform(X_RB @ X_BG)
            pieces.append((collides, mesh, geom))
        for child in body.findall("body"):
            X_BC = np.eye(4)
            X_BC[:3, :3] = _mjcf_rotation(child, degrees, label)
            X_BC[:3, 3] = _floats(child.get("pos", "0 0 0"), 3, label, "body pos")
            walk(child, X_RB @ X_BC, child.get("childclass", default_class))

    walk(bodies[0], np.eye(4), bodies[0].get("childclass", "main"))
    chosen = [p for p in pieces if p[0]] or pieces
    if not chosen:
        raise ObjectError(f"{label}: the body has no geoms")
    for _, mesh, geom in chosen:
        if geom.get("mass") is not None:
            mass_from_geoms += float(_floats(geom["mass"], 1, label, f"{_geom_name(geom)} mass")[0])
        else:
            volume = abs(float(mesh.volume)) if mesh.is_watertight else float(mesh.convex_hull.volume)
            density = _floats(geom.get("density"), 1, label, f"{_geom_name(geom)} density")
            mass_from_geoms += float(_MJCF_DEFAULT_DENSITY if density is None else density[0]) * volume
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
