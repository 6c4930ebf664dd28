"""GraspIt! body files (``models/objects/*.xml``): an object's geometry, mass and inertia as GraspIt
reads them, in millimetres and grams, brought to metres and kilograms.

Why: a user comparing grasps with GraspIt! (graspit-simulator/graspit) has its objects as they ship:
an XML body file (root ``<root>``) naming an Open Inventor, VRML, OFF or PLY geometry file and giving
the mass, centre of gravity and inertia. How GraspIt reads them (its ``src/body.cpp``,
``Body::loadFromXml`` and ``DynamicBody::loadFromXml``; ``src/mytools.cpp``, ``getTransform``):

* ``<geometryFile type="...">`` names the geometry relative to the XML file's folder; its type is
  ``Inventor`` (the default; Coin reads VRML through it too), ``off`` or ``ply``. GraspIt's own files
  name ``soap.iv`` beside a ``soap.IV`` (found on a disk that ignores case): a name that matches one
  file of the folder but for case is read, with a note;
* ``<geometryScaling>`` (one factor) or ``<geometryScalingX/Y/Z>`` scale the geometry, then
  ``<geometryOffset><transform>`` places it: the offset is inserted before the scale in the scene, so
  it acts after it, in GraspIt's units. A transform's children (``translation`` in mm, ``rotation``
  as "degrees axis", ``rotationMatrix`` as nine numbers column by column, ``fullTransform`` as
  "(w x y z)[x y z]") compose left to right, each acting before the ones above it;
* ``<mass>`` is in grams; ``<cog>`` in millimetres in the body frame; ``<inertia_matrix>`` (nine
  numbers) is **per unit mass**, in mm², about the centre of gravity: GraspIt's default one is the
  geometry's at unit mass, translated to the centroid (``computeDefaultInertiaMatrix``), and its
  dynamics multiply it by the mass (``src/dynamics/dynamics.cpp``, ``iterateDynamics``). So the
  inertia is mass × matrix × 1e-6 kg·m². Its ``cube.xml`` bears this out: 416.64 mm² is a 50 mm
  cube's a²/6.

Here: the file's mass, centre of gravity and inertia are checked like any model file's
(:func:`drake_grasp.objects.inertia_checks.checked_mass_properties`; a centre of gravity outside the
geometry's convex hull, which no mass distribution has, is implausible too), and an implausible one is
replaced by the geometry's with an InertiaWarning. A file without ``<mass>`` gets the user's mass, else
density × volume, as every object file here (GraspIt's default is 300 g); without ``<cog>`` the
geometry's centroid, without ``<inertia_matrix>`` the geometry's inertia at uniform density (used at the
file's ``<cog>`` when it gives one, as GraspIt does). ``<material>`` (GraspIt's friction table: glass,
wood, rubber, plastic, metal, stone), ``<youngs>``, compliances and ``<useFlockOfBirds>`` are not used:
the scene's contact model applies to every object. The geometry goes through the same repair, joining
and convex decomposition as a mesh file (:func:`drake_grasp.objects.mesh_files.object_from_triangles`).
A GraspIt robot (``<robot>`` with a ``<palm>``) or world (``<world>``) file is refused in one line.
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
from scipy.spatial import ConvexHull, QhullError

from drake_grasp.objects import sizes
from drake_grasp.objects.inertia_checks import _check_choice, checked_mass_properties
from drake_grasp.objects.mesh_files import _one_line, object_from_triangles, read_triangles
from drake_grasp.objects.pieces import IMPORT_VERSION
from drake_grasp.objects.spec import (
    DEFAULT_DENSITY, DEFAULT_MAX_PIECES, InertiaWarning, MeshNote, ObjectError, ObjectSpec, YELLOW_PAPER_RGBA,
)

MILLIMETRE = 0.001  # m: GraspIt's unit of length
GRAM = 0.001  # kg: GraspIt's unit of mass
GEOMETRY_TYPES = {"Inventor": "iv", "off": "off", "ply": "ply"}  # GraspIt's names → read_triangles' file types
_ROBOT_TAGS = frozenset(("palm", "dof", "chain", "eigenGrasps", "virtualContacts", "approachDirection"))


def graspit_kind(path: str | os.PathLike) -> str | None:
    """What a GraspIt XML file holds: "body" (root ``<root>``), "robot" (``<robot>`` with a ``<palm>``,
    ``<dof>`` or ``<chain>``, not a URDF) or "world" (``<world>``); None for any other file (MJCF,
    URDF, not XML)."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError):
        return None
    if root.tag == "root":
        return "body"
    if root.tag == "world":
        return "world"
    if root.tag == "robot" and any(child.tag in _ROBOT_TAGS for child in root):
        return "robot"
    return None


def gives_inertia(path: str | os.PathLike) -> bool:
    """Whether a GraspIt body file gives an ``<inertia_matrix>`` (for `objects check`'s report)."""
    try:
        return ElementTree.parse(path).getroot().find("inertia_matrix") is not None
    except (ElementTree.ParseError, OSError):
        return False


def _numbers(root, tag: str, count: int, label: str) -> np.ndarray | None:
    """The numbers of child element `tag` (None if absent; :func:`_element_numbers`)."""
    element = root.find(tag)
    return None if element is None else _element_numbers(element, count, label)


def _element_numbers(element, count: int, label: str) -> np.ndarray:
    """The numbers of an element's text; ObjectError (one line) if they are not `count` finite numbers."""
    tag, text = element.tag, " ".join((element.text or "").split())
    try:
        values = np.array([float(v) for v in text.split()], float)
    except ValueError:
        raise ObjectError(f"{label}: <{tag}> {text[:60]!r} is not {'a number' if count == 1 else 'numbers'}") from None
    if len(values) != count:
        raise ObjectError(f"{label}: <{tag}> needs {count} number{'s' if count != 1 else ''}, got {len(values)} "
                          f"({text[:60]!r})")
    if not np.all(np.isfinite(values)):
        raise ObjectError(f"{label}: <{tag}> {text[:60]!r} is not finite (NaN or inf)")
    return values


def _scaling(root, label: str) -> np.ndarray:
    """The per-axis scale: ``<geometryScaling>`` if given, else ``<geometryScalingX/Y/Z>`` (each 1 if
    absent). ObjectError if one is not positive (GraspIt refuses it too)."""
    uniform = _numbers(root, "geometryScaling", 1, label)
    if uniform is not None:
        scale = np.repeat(uniform, 3)
    else:
        scale = np.array([_numbers(root, f"geometryScaling{axis}", 1, label) if root.find(f"geometryScaling{axis}")
                          is not None else [1.0] for axis in "XYZ"], float).ravel()
    if not np.all(scale > 0.0):
        raise ObjectError(f"{label}: geometry scaling must be positive, got {' '.join(f'{s:g}' for s in scale)}")
    return scale


def _offset(root, label: str) -> np.ndarray:
    """The 4×4 transform of ``<geometryOffset><transform>`` (mm), identity if absent."""
    element = root.find("geometryOffset")
    if element is None:
        return np.eye(4)
    transform = element.find("transform")
    if transform is None:
        raise ObjectError(f"{label}: <geometryOffset> without a <transform>")
    total = np.eye(4)
    for child in transform:
        step = np.eye(4)
        if child.tag == "translation":
            step[:3, 3] = _element_numbers(child, 3, label)
        elif child.tag == "rotation":
            words = (child.text or "").split()
            if len(words) != 2 or words[1] not in ("x", "y", "z") or not _is_number(words[0]):
                raise ObjectError(f"{label}: <rotation> {' '.join(words)[:40]!r} is not 'DEGREES x|y|z'")
            axis = np.eye(3)["xyz".index(words[1])]
            step = trimesh.transformations.rotation_matrix(math.radians(float(words[0])), axis)
        elif child.tag == "rotationMatrix":
            step[:3, :3] = _element_numbers(child, 9, label).reshape(3, 3).T  # Eigen fills column by column
            step[:3, :3] = _orthonormal(step[:3, :3])
        elif child.tag == "fullTransform":
            numbers = re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", child.text or "")
            if len(numbers) != 7:
                raise ObjectError(f"{label}: <fullTransform> {(child.text or '').strip()[:60]!r} is not "
                                  "'(w x y z)[x y z]'")
            w, x, y, z, *translation = (float(n) for n in numbers)
            step = trimesh.transformations.quaternion_matrix([w, x, y, z])
            step[:3, 3] = translation
        total = total @ step  # GraspIt's `totalTran % newTran`: the later child acts first
    return total


def _orthonormal(matrix: np.ndarray) -> np.ndarray:
    """The rotation nearest a matrix (GraspIt turns it into a quaternion, which is a rotation)."""
    u, _, vt = np.linalg.svd(matrix)
    rotation = u @ vt
    return rotation if np.linalg.det(rotation) > 0 else u @ np.diag([1.0, 1.0, -1.0]) @ vt


def _is_number(text: str) -> bool:
    try:
        return math.isfinite(float(text))
    except ValueError:
        return False


def _geometry_path(root, folder: Path, label: str) -> tuple[Path, str, str]:
    """(the geometry file, its name as the body file gives it, read_triangles' file type)."""
    element = root.find("geometryFile")
    if element is None:
        raise ObjectError(f"{label}: a GraspIt! body file without a <geometryFile>: no geometry to load "
                          "(GraspIt's default.xml is the template for bare geometry files, not an object)")
    name = (element.text or "").strip()
    kind = (element.get("type") or "").strip() or "Inventor"
    if kind not in GEOMETRY_TYPES:
        raise ObjectError(f"{label}: geometry type {kind[:40]!r} is not one GraspIt! reads ("
                          f"{', '.join(GEOMETRY_TYPES)})")
    if not name:
        raise ObjectError(f"{label}: <geometryFile> names no file")
    path = folder / name
    if not path.is_file():
        matches = ([p for p in path.parent.iterdir() if p.name.lower() == path.name.lower() and p.is_file()]
                   if path.parent.is_dir() else [])
        if len(matches) != 1:
            raise ObjectError(f"{label}: geometry file {name!r} not found (looked for {path})")
        warnings.warn(f"{label}: <geometryFile> names {name}; read {matches[0].name} (the names differ in case only, "
                      "as a disk that ignores case finds it)", MeshNote, stacklevel=3)
        path = matches[0]
    return path, name, GEOMETRY_TYPES[kind]


def _read_body(path: Path, label: str):
    """(mesh in metres in the body frame, mass kg or None, cog m or None, unit inertia m² or None,
    digest) of a GraspIt body file."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError) as error:
        raise ObjectError(f"{label}: cannot parse ({_one_line(error)})") from None
    if root.tag in ("robot", "world"):
        raise ObjectError(f"{label}: a GraspIt! {root.tag} file (<{root.tag}>): only GraspIt object body files "
                          "(<root> with a <geometryFile>) are read; give the body file of one of its objects")
    if root.tag != "root":
        raise ObjectError(f"{label}: not a GraspIt! body file (its root element is <{root.tag}>, not <root>)")
    geometry, name, kind = _geometry_path(root, path.parent, label)
    mass = _numbers(root, "mass", 1, label)
    if mass is not None and not mass[0] > 0.0:
        raise ObjectError(f"{label}: <mass> must be positive (grams), got {mass[0]:g}")
    cog = _numbers(root, "cog", 3, label)
    inertia = _numbers(root, "inertia_matrix", 9, label)
    scale, offset = _scaling(root, label), _offset(root, label)
    mesh = read_triangles(geometry, f"{label}: {name}", file_type=kind)
    mesh.apply_transform(offset @ np.diag([*scale, 1.0]))  # scaled, then placed (mm)
    mesh.apply_scale(MILLIMETRE)
    digest = hashlib.sha256(path.read_bytes() + b"|" + geometry.read_bytes()).hexdigest()
    return (mesh, None if mass is None else float(mass[0]) * GRAM,
            None if cog is None else cog * MILLIMETRE,
            None if inertia is None else inertia.reshape(3, 3) * MILLIMETRE**2, f"{digest}-graspit{IMPORT_VERSION}")


def _outside_hull(points: np.ndarray, point: np.ndarray) -> float:
    """How far (m) `point` lies outside the convex hull of `points` (0 inside or on it)."""
    try:
        equations = ConvexHull(points).equations  # n·x + d <= 0 inside, n unit
    except QhullError:
        return 0.0
    return max(0.0, float(np.max(equations[:, :3] @ point + equations[:, 3])))


def object_from_graspit(
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
) -> ObjectSpec:
    """An object from a GraspIt! body file (module docstring: what is read, and how).

    Args:
        path: The body file (``.xml``, root ``<root>``); its units are GraspIt's (mm, g).
        mass: Mass (kg); default the file's ``<mass>``, else density × volume (not GraspIt's 300 g).
        name: Model name; default the file's stem.
        density: Density (kg/m³) when neither `mass` nor the file gives one, and for an implausible mass.
        max_pieces: Most convex pieces of the decomposition.
        closest_primitive: Ground truth for shape resemblance if known.
        rgba: Visual colour.
        friction: Coulomb friction of this object; None uses the scene's (``<material>`` is not read).
        inertia: "check" (the file's ``<cog>`` and ``<inertia_matrix>`` if plausible, else the
            geometry's with an InertiaWarning), "file" (the file's; ObjectError if it cannot be
            simulated) or "geometry" (the geometry's at uniform density, with the file's mass).
        join_gap: Shells whose surfaces come this close (m) are one object.
        largest_component: Keep the largest of several separate parts instead of failing.

    Raises:
        ObjectError: One line naming the file and the problem.
    """
    label = os.fspath(path)
    path = Path(path).expanduser()
    _check_choice(label, inertia)
    if not path.is_file():
        raise ObjectError(f"{label}: file not found")
    mesh, file_mass, cog, unit_file, digest = _read_body(path, label)
    points = np.asarray(mesh.vertices)[np.unique(mesh.faces)]
    smallest, largest = sizes.widths(points)
    problem = sizes.size_problem(smallest, largest)
    if problem:  # the --scale hint does not apply: GraspIt's unit is the millimetre
        raise ObjectError(f"{label}: {problem.rsplit('; ', 1)[0]} (GraspIt! files are in millimetres, scaled by "
                          "their <geometryScaling>)")

    def mass_properties(volume, centroid, unit_inertia, requested_mass):
        chosen = requested_mass if requested_mass is not None else file_mass
        if (cog is None and unit_file is None) or inertia == "geometry":
            return chosen, centroid, unit_inertia
        check_mass = file_mass if file_mass is not None else (chosen if chosen is not None else density * volume)
        com = centroid if cog is None else cog
        unit = unit_inertia if unit_file is None else unit_file  # the geometry's at the file's cog, as GraspIt
        outside = _outside_hull(points, com)
        if inertia == "check" and outside > 1e-6 * largest:
            warnings.warn(f"{label}: implausible <cog> in the file ({outside * 1000:.3g} mm outside the geometry's "
                          "convex hull, where no mass distribution puts it); using the collision geometry's centre "
                          "and inertia (--inertia file keeps the file's)", InertiaWarning, stacklevel=3)
            return chosen, centroid, unit_inertia
        checked, com, unit = checked_mass_properties(
            label, check_mass, com, check_mass * unit, (volume, centroid, unit_inertia),
            lambda p: float(np.max(np.linalg.norm(points - p, axis=1))), inertia, density)
        return (checked if requested_mass is None else requested_mass), com, unit

    return object_from_triangles(
        mesh, label, path.stem, digest, str(path.resolve()), mass=mass, name=name, density=density,
        max_pieces=max_pieces, closest_primitive=closest_primitive, rgba=rgba, friction=friction,
        largest_component=largest_component, join_gap=join_gap, inertia=mass_properties)
