"""The object data model: `ShapePiece`, `ObjectSpec`, the geometry and mass properties of pieces,
and the cache of generated meshes.

Every other module of :mod:`drake_grasp.objects` builds on this one (the package's docstring lists
them); its names are also reachable as ``drake_grasp.objects.<name>``.

Every object is an :class:`ObjectSpec`: a rigid body made of convex pieces (Drake primitives or
convex meshes, so that contact queries are exact; docs/design.md §4.3), a mass, and the ground truth that
perception and the ε metric need.

Conventions (all SI: metres, kilograms, radians):

- **Object frame O.** Origin at the object's centre of mass at uniform density (i.e. the centroid
  of its volume; for the banana and the toy bridge this is not the centre of the bounding box).
  For the catalogue objects, O's axes are the object's natural axes: z up when it rests in its
  nominal pose, x along its longest horizontal extent (the principal axis of elongated objects).
  For user meshes, O's axes are the mesh file's axes.
- **Table-top frame T.** Origin on the table's top surface, z up. An object resting in its nominal
  pose has rotation ``R_TO`` (identity for the catalogue: every catalogue object is modelled in the
  pose it rests in, e.g. the bottle case's axis is O's x, lying) and its origin ``rest_height``
  above the table top; :meth:`ObjectSpec.nominal_X_TO` gives that pose.
- **Pieces.** Each :class:`ShapePiece` has its pose ``X_OP`` in O and sizes as Drake's shape
  constructors take them (radius, not diameter; a capsule's length excludes its caps).

The model handed to Drake (:func:`object_sdf`, :func:`AddObject`) is one model named ``spec.name``
with one body also named ``spec.name`` whose frame is O; each piece is one compliant-hydroelastic
collision geometry (parameters from :class:`drake_grasp.robot.contact.ContactParameters`) and one visual
in the object's colour (default yellow: the paper wrapped its objects in yellow paper).

Generated meshes (the bell pepper's lobed body, the spectacle case's superellipsoid, user-mesh hulls
and convex decompositions) are written at run time as OBJ files to a cache directory
(``$DRAKE_GRASP_CACHE``, else ``$XDG_CACHE_HOME/drake_grasp``, else ``~/.cache/drake_grasp``), named
by a hash of their content or of their source file. Generating them keeps every size in the code
(one source of truth, no model files to keep in sync) and works from an installed wheel, which does
not ship ``models/``.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import os
import tempfile
import warnings
from pathlib import Path

import numpy as np
import trimesh
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Shape, Sphere
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix

from drake_grasp.objects import cleaning

# A file whose up is y (glTF's convention, and an OpenUSD stage's fallback) is turned so that its up is
# z: +90 deg about x, (x, y, z) -> (x, -z, y). 4 x 4, for trimesh's apply_transform.
Y_UP_TO_Z_UP = trimesh.transformations.rotation_matrix(np.pi / 2, [1.0, 0.0, 0.0])

# --- Assumed numbers (docs/design.md §4.3: "assumed" numbers live here, named) --------------------

# Default density (kg/m³) of primitive-family objects and of user meshes given without a mass.
# Assumed: about the median density of the nine paper objects as sized and weighed below (sponge
# 45, soccer ball 72, game box 107, bottle case 127, spectacle case 194, toy bridge 370, bell
# pepper 465, banana 678, apple 707 kg/m³): household objects are light for their size.
DEFAULT_DENSITY = 200.0

# Colour of the yellow paper the paper's authors wrapped their objects in (RGBA, 0–1). Assumed.
YELLOW_PAPER_RGBA = (0.95, 0.80, 0.10, 1.0)

# Length (m) of the Fig. 4 cylinder family (assumed; fixed, see cylinder_object).
CYLINDER_FAMILY_LENGTH = 0.30

# An object is elongated, and gets a principal axis, when its extent along its axis of least
# inertia exceeds its extent along the other two principal axes by this factor (assumed).
ELONGATION_RATIO = 1.1

# A mesh is treated as convex when its volume is within this fraction of its hull's volume.
CONVEXITY_TOLERANCE = 0.01

MAX_FACES = 20_000  # a user mesh with more faces is simplified (quadric decimation) for contact
# Largest extents (m) of the objects this hand is for: a user's object outside them is probably not in
# metres (objects/sizes.py warns below 1 cm, refuses outside 3 mm-0.5 m and names the likely --scale).
PLAUSIBLE_EXTENTS = (0.01, 0.5)
# A resting pose whose centre of mass lies at most this fraction of the object's largest extent
# above its lowest possible resting height is stable enough not to warn: a tessellated sphere
# stands on a vertex, and rolls off it lowering its centre by a fraction of a millimetre.
STABLE_POSE_TOLERANCE = 0.02
# A face it rests on holds its centre of mass this far inside, as the angle it must tip through to fall
# (deg): pybullet's random_urdfs/372, an H standing 9.1 cm tall on the ridges of its two legs, its
# centre of mass 0.1 mm inside the sliver they make (0.1°), fell within 0.5 s of the first step on the
# simulation's compliant table. Generated objects meant to stand keep theirs: a standing pencil 0.9 cm
# across and 18.5 cm tall tips at 2.9°, a standing domino at 10-13°.
MIN_TIP_ANGLE = 1.0
# Upper bound on the convex pieces of a decomposed user mesh (CoACD's max_convex_hull).
DEFAULT_MAX_PIECES = 16

# CoACD concavity threshold (dimensionless, CoACD's default is 0.05): lower = more, finer pieces.
COACD_THRESHOLD = 0.05

PAPER_CLASSES = ("annulus", "sun_ray_sphere", "sun_ray_box", "sun_ray_cylinder")
PRIMITIVE_NAMES = ("sphere", "cylinder", "box")
SHAPE_KINDS = ("sphere", "ellipsoid", "box", "cylinder", "capsule", "convex")


class ObjectError(ValueError):
    """A bad object name, primitive string or model file; the message is one line."""


class UnitsWarning(UserWarning):
    """A user object's size suggests its file is not in metres."""


class MeshNote(UserWarning):
    """A one-line note on what was done to a user's mesh (simplified, decomposed: slow steps)."""


class StaticModelNote(MeshNote):
    """A model file's model is static (its simulator holds it fixed); it was loaded as a free body."""


class ArticulationNote(MeshNote):
    """A model file's object is articulated; its moving joints are held where the file puts them."""


class InertiaWarning(UserWarning):
    """A model file's inertia was implausible and was replaced by the collision geometry's."""


class UnstablePoseWarning(UserWarning):
    """A mesh given with its z up would tip over on the table, so it is rested on a stable face."""


@contextlib.contextmanager
def pose_warnings_announced():
    """A context in which UnstablePoseWarning is not shown: for a sweep's worker tasks, which load
    the same objects again after the command has checked them and said so once."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnstablePoseWarning)
        warnings.simplefilter("ignore", UnitsWarning)
        warnings.simplefilter("ignore", MeshNote)
        warnings.simplefilter("ignore", InertiaWarning)
        yield


# --- Data ---------------------------------------------------------------------------------------


@dataclasses.dataclass(frozen=True)
class ShapePiece:
    """One convex piece of an object, posed in the object frame O.

    Attributes:
        kind: One of ``SHAPE_KINDS``.
        size: As Drake's constructors (m): sphere ``(radius,)``; ellipsoid ``(a, b, c)``
            semi-axes along P's x, y, z; box ``(x, y, z)`` edge lengths; cylinder and capsule
            ``(radius, length)`` along P's z (a capsule's length excludes its hemispherical caps);
            convex ``()``.
        p_OP: Position of the piece frame P's origin in O (m).
        rpy_OP: Orientation of P in O as roll-pitch-yaw (rad; Drake's and SDFormat's convention).
        mesh_path: Absolute path of the OBJ file of a convex piece (vertices in P), else None.
    """

    kind: str
    size: tuple[float, ...]
    p_OP: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_OP: tuple[float, float, float] = (0.0, 0.0, 0.0)
    mesh_path: str | None = None

    def __post_init__(self):
        expected = {"sphere": 1, "ellipsoid": 3, "box": 3, "cylinder": 2, "capsule": 2, "convex": 0}
        if self.kind not in expected:
            raise ValueError(f"unknown piece kind {self.kind!r}; expected one of {SHAPE_KINDS}")
        if len(self.size) != expected[self.kind] or any(s <= 0 for s in self.size):
            raise ValueError(f"bad size {self.size} for a {self.kind}")
        if (self.kind == "convex") != (self.mesh_path is not None):
            raise ValueError("a convex piece needs a mesh_path, and only a convex piece has one")

    @property
    def X_OP(self) -> RigidTransform:
        """Pose of the piece frame P in the object frame O."""
        return RigidTransform(RollPitchYaw(*self.rpy_OP), np.array(self.p_OP))

    def drake_shape(self) -> Shape:
        """The piece as a pydrake.geometry shape (in P)."""
        if self.kind == "sphere":
            return Sphere(*self.size)
        if self.kind == "ellipsoid":
            return Ellipsoid(*self.size)
        if self.kind == "box":
            return Box(*self.size)
        if self.kind == "cylinder":
            return Cylinder(*self.size)
        if self.kind == "capsule":
            return Capsule(*self.size)
        return Convex(self.mesh_path)

    def characteristic_size(self) -> float:
        """The piece's smallest dimension (m), which sets its contact mesh resolution."""
        if self.kind == "sphere":
            return 2.0 * self.size[0]
        if self.kind == "ellipsoid":
            return 2.0 * min(self.size)
        if self.kind == "box":
            return min(self.size)
        if self.kind == "cylinder":
            return min(2.0 * self.size[0], self.size[1])
        if self.kind == "capsule":
            return 2.0 * self.size[0]
        vertices = _convex_vertices(self.mesh_path)
        return float(np.min(vertices.max(axis=0) - vertices.min(axis=0)))


@dataclasses.dataclass(frozen=True)
class ObjectSpec:
    """A graspable rigid object: convex pieces in its frame O, mass, and ground truth.

    Attributes:
        name: Model and body name (letters, digits, ``_``, ``-``, ``.``).
        pieces: The convex pieces whose union is the object.
        mass: Mass (kg).
        inertia: Rotational inertia about O's origin (the centre of mass), expressed in O, as
            the matrix entries ``(Ixx, Iyy, Izz, Ixy, Ixz, Iyz)`` (kg·m²; products of inertia
            with their sign in the matrix, as SDFormat's ``<ixy>``), at uniform density (or as
            an SDF model file gives it).
        volume: Volume of the union of the pieces (m³).
        extents: Size of the axis-aligned bounding box in O (m).
        rest_height: Height (m) of O's origin above the table top when resting in the nominal pose.
        rpy_TO: Nominal orientation of O in the table-top frame T, roll-pitch-yaw (rad).
        principal_axis: Unit vector in O of the object's long axis (its axis of least inertia) for
            elongated objects, else None.
        max_radius: Largest distance from the centre of mass to the surface (m): the torque scale
            ρ of the ε metric (docs/design.md §4.5).
        paper_class: The paper's SFA class: one of ``PAPER_CLASSES``, or None (primitive families,
            user objects).
        closest_primitive: 'sphere', 'cylinder' or 'box': the compliant grasp whose shape the
            object resembles (ground truth for the shape-resemblance primitives), or None when
            unknown (user objects unless given).
        rgba: Visual colour (RGBA, 0–1).
        friction: Coulomb friction coefficient of this object; None uses the scene's
            ``ContactParameters.friction``.
        source: The file a user object was made from, else None.
    """

    name: str
    pieces: tuple[ShapePiece, ...]
    mass: float
    inertia: tuple[float, float, float, float, float, float]
    volume: float
    extents: tuple[float, float, float]
    rest_height: float
    rpy_TO: tuple[float, float, float]
    principal_axis: tuple[float, float, float] | None
    max_radius: float
    paper_class: str | None
    closest_primitive: str | None
    rgba: tuple[float, float, float, float] = YELLOW_PAPER_RGBA
    friction: float | None = None
    source: str | None = None

    @property
    def R_TO(self) -> RotationMatrix:
        """Nominal orientation of O in the table-top frame T."""
        return RotationMatrix(RollPitchYaw(*self.rpy_TO))

    def nominal_X_TO(self, x: float = 0.0, y: float = 0.0, yaw: float = 0.0) -> RigidTransform:
        """Pose of O in the table-top frame T when resting in the nominal pose.

        Args:
            x: Position of O's origin along T's x (m).
            y: Position of O's origin along T's y (m).
            yaw: Rotation about T's z applied after ``R_TO`` (rad).
        """
        return RigidTransform(
            RotationMatrix.MakeZRotation(yaw) @ self.R_TO, np.array([x, y, self.rest_height])
        )

    def inertia_matrix(self) -> np.ndarray:
        """Rotational inertia about the centre of mass, expressed in O (3×3, kg·m²)."""
        ixx, iyy, izz, ixy, ixz, iyz = self.inertia
        return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


# --- Cache of generated meshes -------------------------------------------------------------------


def cache_dir() -> Path:
    """The directory of generated meshes (created on demand)."""
    root = os.environ.get("DRAKE_GRASP_CACHE")
    if root:
        path = Path(root)
    else:
        path = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "drake_grasp"
    path.mkdir(parents=True, exist_ok=True)
    return path


_obj_text = cleaning.obj_text  # a piece as written: the text the cleaning checks Drake's hull of


def _write_atomically(path: Path, text: str) -> None:
    """Writes `text` to `path` so that a concurrent reader never sees a partial file."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def _cached_hull_obj(label: str, points: np.ndarray) -> str:
    """Writes the convex hull of `points` (m), cleaned for contact (`geometry.cleaning`: no near
    vertices, no sliver triangles), as an OBJ in the cache; returns its absolute path."""
    piece = cleaning.clean_convex_points(np.asarray(points, dtype=float))
    if piece is None or (piece.original_volume - piece.volume) > cleaning.VOLUME_TOLERANCE * piece.original_volume:
        raise ObjectError(f"{label}: the convex hull is too thin or too small to be a solid for contact")
    text = _obj_text(piece.vertices, piece.faces)
    digest = hashlib.sha256(text.encode()).hexdigest()[:16]
    directory = cache_dir() / "generated"
    directory.mkdir(exist_ok=True)
    path = directory / f"{label}-{digest}.obj"
    if not path.exists():
        _write_atomically(path, text)
    return str(path.resolve())


@functools.lru_cache(maxsize=256)
def _convex_vertices(mesh_path: str) -> np.ndarray:
    return np.asarray(trimesh.load(mesh_path, force="mesh", process=False).vertices, dtype=float)


@functools.lru_cache(maxsize=256)
def _convex_halfspaces(mesh_path: str) -> tuple[np.ndarray, np.ndarray]:
    """(normals, offsets) of the hull's faces: a point p is inside iff normals·p ≤ offsets."""
    hull = trimesh.convex.convex_hull(_convex_vertices(mesh_path))
    return hull.face_normals, np.einsum("ij,ij->i", hull.face_normals, hull.triangles[:, 0])

