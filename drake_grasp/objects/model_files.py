"""Objects from model files: SDFormat and URDF (parsed by Drake) and MuJoCo MJCF object files (read in
`mjcf_files`), with the file's inertia checked before it can reach the plant.

SDFormat and URDF: Drake's parser takes mesh geometry only as OBJ, VTK or glTF (any other format is
refused with "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes"), while URDFs exported by
CAD tools and ROS packages commonly name STL, PLY or DAE meshes. Such a mesh is converted to an OBJ
in the cache (named by its content's hash; never beside the user's file) and the model text given to
the parser names the OBJ (:func:`drake_grasp.objects.readable_models.drake_readable_model`, which also
frees a static model); units and the file's ``scale`` are unchanged.

Every inertial read from a file is checked (:mod:`drake_grasp.objects.inertia_checks`), and an
implausible one replaced by the collision geometry's, before it can reach the plant.

MJCF object files are read by :mod:`drake_grasp.objects.mjcf_files` (Drake's MJCF parser reads only
OBJ meshes); `object_from_mjcf` is named here beside the other model-file loaders.
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
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import Parser

from drake_grasp.objects.mesh_files import (
    _centre_over_base, _load_checked_mesh, _lowest_resting_rotation, _model_name, _one_line, _scale_key,
    clearly_tips_over,
)
from drake_grasp.objects import packages, rigid_assembly, settling, sizes
from drake_grasp.objects.readable_models import drake_readable_model, has_visuals, quiet_unsupported_elements
from drake_grasp.objects.pieces import _decompose
from drake_grasp.objects.spec import (
    DEFAULT_DENSITY, DEFAULT_MAX_PIECES, MIN_TIP_ANGLE, InertiaWarning, MeshNote, ObjectError, ObjectSpec, ShapePiece,
    UnstablePoseWarning, YELLOW_PAPER_RGBA, _cached_hull_obj,
)
from drake_grasp.objects.mass_properties import (
    _make_spec, _mass_properties_sampled, _mass_properties_summed, _piece_points,
)
from drake_grasp.objects.inertia_checks import (  # noqa: F401  (re-exported: model files' inertia checks)
    INERTIA_CHOICES, PLAUSIBLE_DENSITY, _check_choice, checked_mass_properties, inertia_problem, simulable_problem,
)



def _piece_from_drake_shape(
    shape: Shape, X_BG: RigidTransform, label: str, max_pieces: int, scale: float = 1.0
) -> list[ShapePiece]:
    """Pieces (posed in the body frame B) for one collision geometry of a parsed SDF, every length
    multiplied by `scale` (a command line's ``--scale``)."""
    p = tuple(scale * float(v) for v in X_BG.translation())
    rpy = tuple(float(v) for v in RollPitchYaw(X_BG.rotation()).vector())
    if isinstance(shape, Sphere):
        return [ShapePiece("sphere", (scale * shape.radius(),), p, rpy)]
    if isinstance(shape, Ellipsoid):
        return [ShapePiece("ellipsoid", tuple(scale * v for v in (shape.a(), shape.b(), shape.c())), p, rpy)]
    if isinstance(shape, Box):
        return [ShapePiece("box", tuple(scale * v for v in (shape.width(), shape.depth(), shape.height())), p, rpy)]
    if isinstance(shape, Cylinder):
        return [ShapePiece("cylinder", (scale * shape.radius(), scale * shape.length()), p, rpy)]
    if isinstance(shape, Capsule):
        return [ShapePiece("capsule", (scale * shape.radius(), scale * shape.length()), p, rpy)]
    if isinstance(shape, Convex):
        hull = shape.GetConvexHull()  # Scaled, in G; works for every format Drake reads.
        vertices = scale * np.array([hull.vertex(i) for i in range(hull.num_vertices())])
        return [ShapePiece("convex", (), p, rpy, _cached_hull_obj("sdf_convex", vertices))]
    if isinstance(shape, Mesh):
        scale = scale * np.asarray(shape.scale3(), float)  # per axis: a model file may scale a mesh unevenly
        mesh = _load_checked_mesh(Path(shape.source().path()), label, scale, one_body=True)
        key = hashlib.sha256(Path(shape.source().path()).read_bytes()).hexdigest()[:20]
        paths = _decompose(mesh, f"sdf_mesh-{key}-{_scale_key(scale)}-{max_pieces}", max_pieces, label)
        return [ShapePiece("convex", (), p, rpy, path) for path in paths]
    raise ObjectError(f"{label}: collision shape {type(shape).__name__} is not supported")


def _one_mesh_mass_properties(geometries, label: str, scale: float = 1.0
                              ) -> tuple[float, np.ndarray, np.ndarray] | None:
    """(volume m³, centroid in B, unit inertia m² about it in B) of a body whose collision geometry
    is one mesh, exact from its solid (cached; sampling its convex pieces takes seconds); else None."""
    if len(geometries) != 1 or not isinstance(geometries[0][0], Mesh):
        return None
    shape, X_BG = geometries[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # its notes were given when its pieces were made
        solid = _load_checked_mesh(Path(shape.source().path()), label, scale * np.asarray(shape.scale3(), float),
                                   one_body=True)
    R_BG = X_BG.rotation().matrix()
    unit_inertia = np.asarray(solid.moment_inertia, float) / float(solid.mass)
    return (float(solid.volume), R_BG @ np.asarray(solid.center_mass) + scale * X_BG.translation(),
            R_BG @ unit_inertia @ R_BG.T)


def _resting_rpy(points_B: np.ndarray, p_BScm: np.ndarray, label: str) -> tuple[float, float, float] | None:
    """How a model file's body rests on the table (roll, pitch, yaw of its frame, rad): with its z up,
    unless it clearly tips over so (`mesh_files.clearly_tips_over`); then on its most stable face, with an
    UnstablePoseWarning, as a mesh file or an MJCF body that would tip over. A model file's frame is not
    always how it rests: 17 of 30 of pybullet's random_urdfs, z up, have their centre of mass off their
    base; such a body falls as the trial begins, while the camera looks, and the estimate merges it
    standing and fallen. None: z up is not clearly a rest either way, and the simulator must say
    (`_settled_rpy`)."""
    hull = trimesh.convex.convex_hull(points_B)
    outside = np.einsum("ij,ij->i", hull.face_normals, hull.triangles[:, 0] - p_BScm).min() < 0.0
    if outside:
        # A centre of mass outside the collision geometry is a placeholder (OCRTOC's plastic lemon: the
        # origin, outside its mesh), and how such a body rests cannot be told: z up, as the file has it.
        return (0.0, 0.0, 0.0)
    if not clearly_tips_over(hull, p_BScm):
        return (0.0, 0.0, 0.0) if settling.stays(np.asarray(hull.vertices), p_BScm) else None
    warnings.warn(f"{label}: with its z up the object would tip over (its centre of mass is not over its "
                  "base); resting it on its most stable face", UnstablePoseWarning, stacklevel=3)
    return _most_stable_rpy(hull, p_BScm)


def _most_stable_rpy(hull, p_BScm: np.ndarray) -> tuple[float, float, float]:
    return tuple(float(a) for a in RollPitchYaw(_lowest_resting_rotation(hull, p_BScm)).vector())


# A body that settles this far (deg) from z up is said to tip over (an UnstablePoseWarning). One that
# settles less than `settling.ROCK_DEG` from it keeps z up, as the file has it.
TIPS_DEG = 10.0
# A body that turned TIPS_DEG or more without its centre of mass falling this much (m) rolled on a round
# side (a can lying on its side rolls 15° at 1.5 kg): it rests as it rolled, without the warning.
TIP_DROP = 0.001


def _settled_rpy(spec: ObjectSpec, points_O: np.ndarray, label: str) -> tuple[float, float, float]:
    """How a body that z up neither clearly stands nor clearly tips over comes to rest: set down z up on
    the station's table in the simulator (`settling.settle_in_simulator`). A base of the vertices near
    the lowest one, the test above, takes a rounded bottom for a flat one: pybullet's random object 306,
    a 9 cm lump, stood on such a base in 0.39.0 and rolled 57° within 0.75 s of the trial's start, while
    the camera looked; Gazebo's YCB sponge, marker and fork stand on end in their files and fell flat.
    The simulator's rest is taken as it is (a scanned can rests on its compliant bulge, where a rigid
    roll would tip it onto its rim). A body still moving after SETTLE_TIME is rolled quasi-statically
    from where it got to (`settling.roll_to_rest`), and rests on the face the roll ends on if its centre
    of mass stands MIN_TIP_ANGLE inside its edges, else on its most stable face. A rest within
    `settling.ROCK_DEG` of z up keeps z up; one that rolled on a round side (its centre of mass no
    lower) rests as it rolled, without the warning."""
    try:
        R_TO, rested = settling.settle_in_simulator(spec)
    except RuntimeError as error:  # the simulator gave up (a body it cannot step): as the file has it
        warnings.warn(f"{label}: could not settle it in the simulator ({_one_line(str(error))}); it stands "
                      "z up as the file has it", UnstablePoseWarning, stacklevel=3)
        return (0.0, 0.0, 0.0)
    down = settling.table_down(R_TO)
    if not rested:
        hull = trimesh.convex.convex_hull(points_O)
        rest = settling.roll_to_rest(np.asarray(hull.vertices), np.zeros(3), down)
        if rest.margin_deg < MIN_TIP_ANGLE:
            warnings.warn(f"{label}: with its z up the object would tip over (it settles on no base); resting "
                          "it on its most stable face", UnstablePoseWarning, stacklevel=3)
            return _most_stable_rpy(hull, np.zeros(3))
        down = rest.down
    turned = settling.degrees_from_upright(down)
    if turned < settling.ROCK_DEG:
        return (0.0, 0.0, 0.0)
    dropped = float(np.max(-points_O[:, 2]) - np.max(points_O @ down))  # the centre of mass's fall, m
    if turned >= TIPS_DEG and dropped > TIP_DROP:
        warnings.warn(f"{label}: with its z up the object would tip over ({turned:.0f}° in the simulator); "
                      "resting it as it settles", UnstablePoseWarning, stacklevel=3)
    return tuple(float(a) for a in RollPitchYaw(settling.resting_rotation(down)).vector())


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
    scale: float = 1.0,
) -> ObjectSpec:
    """An object from an SDFormat (or URDF) file with one model: its links as one rigid body.

    The file is parsed by Drake; its body's collision geometries become the pieces (non-convex
    meshes are decomposed like :func:`object_from_mesh`), its inertial gives mass, centre of mass
    and inertia (a missing or zero mass falls back to `mass` or density × volume). O is placed at
    the body's centre of mass with the body frame's axes; the object rests with its z up, or on its most
    stable face if it clearly tips over (`_resting_rpy`).

    Limits: one model. Its links become one rigid body (:mod:`drake_grasp.objects.rigid_assembly`):
    links joined by fixed joints as one, an articulated object's moving joints held where the file
    puts them (a note), a joint to the world left out (loaded free, a note). The file's
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
        scale: Multiplies every length of the model (a command line's ``--scale``: a file in
            millimetres, or PartNet-Mobility's unit-sized objects); the file's own masses are kept
            (a density × volume mass scales with the cube), its inertias scale with the square.

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
    kind = path.suffix.lower().lstrip(".")

    def parsed(visuals: bool):
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
        parser = Parser(plant)
        local = packages.register_packages(parser.package_map(), path, package_path)
        problem = packages.missing_package_problem(path.read_text(errors="replace"), parser.package_map(), local, path)
        if problem:
            raise ObjectError(f"{label}: {problem}")
        text = (drake_readable_model(path, label, parser.package_map(), local, visuals=visuals)
                if kind in ("sdf", "urdf") else None)
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
            if "xmlns:xacro" in path.read_text(errors="replace"):
                problem += "; it is a xacro macro file (ROS): expand it first (`xacro FILE > object.urdf`)"
            return None, problem
        return (plant, scene_graph, models), None

    found, problem = parsed(visuals=True)
    if found is None and kind in ("sdf", "urdf") and has_visuals(path):
        # The visuals are replaced by ours: one Drake cannot parse (pybullet takes "r, g, b a" for a
        # colour, Drake four numbers) is no reason to refuse the object.
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MeshNote)  # its notes were given by the first parse
            found, _ = parsed(visuals=False)
        if found is not None:
            warnings.warn(f"{label}: its visual elements left out (Drake's parser: {problem}); drake-grasp draws "
                          "its own", MeshNote, stacklevel=2)
    if found is None:
        raise ObjectError(f"{label}: {problem}")
    plant, scene_graph, models = found
    model = _the_object_model(plant, models, label)
    assembly = rigid_assembly.rigid_assembly(plant, model, label, _declared_joints(path))  # B: the root link's frame
    geometries = assembly.collision_geometries(plant, scene_graph.model_inspector())
    pieces_B = []
    for shape, X_BG in geometries:
        pieces_B += _piece_from_drake_shape(shape, X_BG, label, max_pieces, scale)
    if not pieces_B:
        raise ObjectError(f"{label}: the body has no collision geometry")
    points = np.vstack([_piece_points(piece) for piece in pieces_B])
    sizes.check_size(points, label, scale)
    file_mass, p_BScm, file_inertia = assembly.mass_properties()  # a given mass does not scale; lengths do
    p_BScm, file_inertia = scale * p_BScm, scale**2 * file_inertia
    mass_properties = None
    if file_mass > 0.0 and math.isfinite(file_mass):
        pieces = tuple(pieces_B)
        geometry = (_one_mesh_mass_properties(geometries, label, scale) or
                    (_mass_properties_summed(pieces) if len(pieces) == 1 else _mass_properties_sampled(pieces)))
        checked_mass, p_BScm, unit_inertia = checked_mass_properties(
            label, file_mass, p_BScm, file_inertia, geometry,
            lambda p: float(np.max(np.linalg.norm(points - p, axis=1))), inertia, density)
        mass_properties = (geometry[0], p_BScm, unit_inertia)
        mass = checked_mass if mass is None else mass
    p_BScm = (mass_properties or _mass_properties_summed(tuple(pieces_B)))[1]  # as _make_spec places O
    rpy_TO = _resting_rpy(points, np.asarray(p_BScm, float), label)

    def spec_resting(rpy):
        return _make_spec(
            name or _model_name(plant.GetModelInstanceName(model)),
            pieces_B,
            mass,
            density=density,
            mass_properties=mass_properties,
            rpy_TO=rpy,
            closest_primitive=closest_primitive,
            rgba=rgba,
            friction=friction,
            source=str(path.resolve()),
        )

    if rpy_TO is not None:
        return spec_resting(rpy_TO)
    standing = spec_resting((0.0, 0.0, 0.0))
    return spec_resting(_settled_rpy(standing, points - np.asarray(p_BScm, float), label))


def _declared_joints(path: Path) -> dict[str, str]:
    """{joint name: its type} as an SDFormat or URDF file writes them (empty if it is not XML)."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError):
        return {}
    return {joint.get("name"): joint.get("type") for joint in root.iter("joint") if joint.get("name") and joint.get("type")}


def _the_object_model(plant, models: list, label: str):
    """The model instance that is the object. One model is; among several (an SDFormat world: a
    ground plane, a table, the object), the object is the one model not fixed to the world, as for
    MJCF (`mjcf_files._the_object_body`): the others are the file's scene, left out with a note.
    ObjectError (one line) when no model, or more than one, moves freely."""
    if len(models) == 1:
        return models[0]
    world = plant.world_body().index()

    def fixed(model) -> bool:  # Drake welds a static model's links to the world, in the model
        return any(plant.get_joint(j).parent_body().index() == world for j in plant.GetJointIndices(model))

    def names(group) -> str:
        return ", ".join(repr(plant.GetModelInstanceName(m)) for m in group)

    free = [m for m in models if not fixed(m)]
    if len(free) != 1:
        moving = f" ({len(free)} free: {names(free)})" if free else " (none free)"
        raise ObjectError(f"{label}: expected one model, found {len(models)}{moving}; give a file with the object "
                          "alone, or with one free model beside a static scene")
    scene = [m for m in models if m != free[0]]
    warnings.warn(f"{label}: the object is the free model {plant.GetModelInstanceName(free[0])!r}; {len(scene)} fixed "
                  f"to the world (the file's scene: {names(scene)}) left out", MeshNote, stacklevel=3)
    return free[0]


def _missing_file_problem(error_text: str) -> str | None:
    """A one-line reason for Drake's parse error on a file the model names that is not there (a mesh
    a collection keeps out of its repository, say), or None: which file, and where it was looked for."""
    match = re.search(r"URI '([^']+)' resolved to '([^']+)' which does not exist", error_text)
    if match is None:
        return None
    return f"mesh {match.group(1)}: file not found (looked for {os.path.normpath(match.group(2))})"


# MJCF object files: read in `objects.mjcf_files`, re-exported here where the loaders are named.
from drake_grasp.objects.mjcf_files import object_from_mjcf  # noqa: E402,F401
