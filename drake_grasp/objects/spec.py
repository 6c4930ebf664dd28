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
collision geometry (parameters from :class:`drake_grasp.contact.ContactParameters`) and one visual
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
import math
import os
import re
import tempfile
import warnings
from pathlib import Path

import numpy as np
import trimesh
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Shape, Sphere
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.tree import CalcSpatialInertia

from drake_grasp.objects import cleaning

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
# A user object larger or smaller than these (m) is probably not in metres (the hand spans ~0.3 m).
PLAUSIBLE_EXTENTS = (0.01, 1.0)
# A resting pose whose centre of mass lies at most this fraction of the object's largest extent
# above its lowest possible resting height is stable enough not to warn: a tessellated sphere
# stands on a vertex, and rolls off it lowering its centre by a fraction of a millimetre.
STABLE_POSE_TOLERANCE = 0.02
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


def _obj_text(vertices: np.ndarray, faces: np.ndarray) -> str:
    lines = ["# generated by drake_grasp.objects"]
    lines += [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    return "\n".join(lines) + "\n"


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


# --- Geometry of pieces --------------------------------------------------------------------------


def _pose(piece: ShapePiece) -> tuple[np.ndarray, np.ndarray]:
    """(R_OP, p_OP) as numpy arrays."""
    return RollPitchYaw(*piece.rpy_OP).ToRotationMatrix().matrix(), np.array(piece.p_OP, float)


def _fibonacci_sphere(n: int) -> np.ndarray:
    """n unit vectors spread evenly over the sphere (n×3), the poles included."""
    i = np.arange(n)
    z = 1.0 - 2.0 * i / (n - 1)
    rho = np.sqrt(np.clip(1.0 - z * z, 0.0, 1.0))
    phi = i * math.pi * (3.0 - math.sqrt(5.0))
    return np.column_stack([rho * np.cos(phi), rho * np.sin(phi), z])


def _piece_aabb(piece: ShapePiece, R_AO: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exact axis-aligned bounding box (lo, hi) of a piece in a frame A = R_AO·O (same origin)."""
    R_OP, p_OP = _pose(piece)
    R = R_AO @ R_OP
    c = R_AO @ p_OP
    if piece.kind == "convex":
        points = _convex_vertices(piece.mesh_path) @ R.T + c
        return points.min(axis=0), points.max(axis=0)
    if piece.kind == "sphere":
        half = np.full(3, piece.size[0])
    elif piece.kind == "ellipsoid":
        half = np.sqrt((R * np.array(piece.size)) ** 2 @ np.ones(3))
    elif piece.kind == "box":
        half = np.abs(R) @ (np.array(piece.size) / 2.0)
    else:
        radius, length = piece.size
        u = R[:, 2]
        if piece.kind == "cylinder":
            half = np.abs(u) * length / 2.0 + radius * np.sqrt(np.clip(1.0 - u * u, 0.0, 1.0))
        else:
            half = np.abs(u) * length / 2.0 + radius
    return c - half, c + half


def _piece_points(piece: ShapePiece, n: int = 2000) -> np.ndarray:
    """Surface points of a piece in O whose hull approximates it; includes the points farthest
    from O's origin exactly (for max_radius)."""
    R_OP, p_OP = _pose(piece)
    q = -R_OP.T @ p_OP  # O's origin, in P.
    if piece.kind == "convex":
        points_P = _convex_vertices(piece.mesh_path)
    elif piece.kind in ("sphere", "ellipsoid"):
        semi = np.array(piece.size * 3 if piece.kind == "sphere" else piece.size)
        points_P = np.vstack([_fibonacci_sphere(n) * semi, np.diag(semi), -np.diag(semi)])
        if piece.kind == "sphere" and np.linalg.norm(q) > 0:
            points_P = np.vstack([points_P, -q / np.linalg.norm(q) * semi[0]])
    elif piece.kind == "box":
        half = np.array(piece.size) / 2.0
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        points_P = signs * half
    elif piece.kind == "cylinder":
        radius, length = piece.size
        angles = np.linspace(0.0, 2.0 * math.pi, 360, endpoint=False)
        rim = np.column_stack([radius * np.cos(angles), radius * np.sin(angles)])
        if np.linalg.norm(q[:2]) > 0:
            rim = np.vstack([rim, -q[:2] / np.linalg.norm(q[:2]) * radius])
        points_P = np.vstack(
            [np.column_stack([rim, np.full(len(rim), z)]) for z in (-length / 2, length / 2)]
        )
    else:  # capsule
        radius, length = piece.size
        unit = _fibonacci_sphere(n)
        points_P = unit * radius + np.outer(np.sign(unit[:, 2]), [0.0, 0.0, length / 2.0])
        for end in (np.array([0, 0, -length / 2]), np.array([0, 0, length / 2])):
            away = end - q
            if np.linalg.norm(away) > 0:
                points_P = np.vstack([points_P, end + away / np.linalg.norm(away) * radius])
    return points_P @ R_OP.T + p_OP


def _piece_contains(piece: ShapePiece, points_O: np.ndarray) -> np.ndarray:
    """Whether each point (n×3, in O) lies inside the piece."""
    R_OP, p_OP = _pose(piece)
    p = (points_O - p_OP) @ R_OP  # In P.
    if piece.kind == "sphere":
        return np.einsum("ij,ij->i", p, p) <= piece.size[0] ** 2
    if piece.kind == "ellipsoid":
        return np.sum((p / np.array(piece.size)) ** 2, axis=1) <= 1.0
    if piece.kind == "box":
        return np.all(np.abs(p) <= np.array(piece.size) / 2.0, axis=1)
    if piece.kind == "cylinder":
        radius, length = piece.size
        return (p[:, 0] ** 2 + p[:, 1] ** 2 <= radius**2) & (np.abs(p[:, 2]) <= length / 2.0)
    if piece.kind == "capsule":
        radius, length = piece.size
        z = np.clip(p[:, 2], -length / 2.0, length / 2.0)
        return p[:, 0] ** 2 + p[:, 1] ** 2 + (p[:, 2] - z) ** 2 <= radius**2
    normals, offsets = _convex_halfspaces(piece.mesh_path)
    return np.all(p @ normals.T <= offsets + 1e-12, axis=1)


def _mass_properties_summed(pieces: tuple[ShapePiece, ...]) -> tuple[float, np.ndarray, np.ndarray]:
    """Volume (m³), centroid in O (m) and unit inertia about the centroid in O (m²) of pieces that
    do not overlap (their volumes add), from Drake's exact per-shape inertias."""
    volumes, centroids, inertias = [], [], []
    for piece in pieces:
        R_OP, p_OP = _pose(piece)
        M_PPo_P = CalcSpatialInertia(piece.drake_shape(), 1.0)  # density 1: mass = volume.
        volume = M_PPo_P.get_mass()
        p_PScm = M_PPo_P.get_com()
        I_SPo_P = M_PPo_P.CalcRotationalInertia().CopyToFullMatrix3()
        # Central inertia of the piece in P, then re-expressed in O.
        I_Scm_P = I_SPo_P - volume * (np.dot(p_PScm, p_PScm) * np.eye(3) - np.outer(p_PScm, p_PScm))
        volumes.append(volume)
        centroids.append(R_OP @ p_PScm + p_OP)
        inertias.append(R_OP @ I_Scm_P @ R_OP.T)
    volume = float(sum(volumes))
    centroid = sum(v * c for v, c in zip(volumes, centroids)) / volume
    inertia = np.zeros((3, 3))
    for v, c, inertia_piece in zip(volumes, centroids, inertias):
        d = c - centroid
        inertia += inertia_piece + v * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return volume, centroid, inertia / volume


def _mass_properties_sampled(
    pieces: tuple[ShapePiece, ...], samples: int = 1_500_000
) -> tuple[float, np.ndarray, np.ndarray]:
    """Volume, centroid and unit inertia of a union of *overlapping* pieces, by the midpoint rule
    on a regular grid of about `samples` cells over the bounding box (error well under 1 %)."""
    lo, hi = _aabb(pieces, np.eye(3))
    spacing = (np.prod(hi - lo) / samples) ** (1.0 / 3.0)
    counts = np.maximum(np.ceil((hi - lo) / spacing), 1).astype(int)
    steps = (hi - lo) / counts
    # Cell centres, symmetric about the box's centre so that symmetric objects stay symmetric.
    axes = [a + (np.arange(n) + 0.5) * h for a, n, h in zip(lo, counts, steps)]
    count, first, second = 0, np.zeros(3), np.zeros((3, 3))
    for x in axes[0]:
        yy, zz = np.meshgrid(axes[1], axes[2], indexing="ij")
        points = np.column_stack([np.full(yy.size, x), yy.ravel(), zz.ravel()])
        inside = np.zeros(len(points), dtype=bool)
        for piece in pieces:
            inside |= _piece_contains(piece, points)
        points = points[inside]
        count += len(points)
        first += points.sum(axis=0)
        second += points.T @ points
    volume = count * float(np.prod(steps))
    centroid = first / count
    covariance = second / count - np.outer(centroid, centroid)  # E[(p - c)(p - c)ᵀ]
    unit_inertia = np.trace(covariance) * np.eye(3) - covariance
    return volume, centroid, unit_inertia


def _aabb(pieces, R_AO: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    boxes = [_piece_aabb(piece, R_AO) for piece in pieces]
    return np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)


def _shift(piece: ShapePiece, offset: np.ndarray) -> ShapePiece:
    return dataclasses.replace(piece, p_OP=tuple(float(v) for v in np.array(piece.p_OP) + offset))


def _principal_axis(
    points_O: np.ndarray, unit_inertia: np.ndarray
) -> tuple[float, float, float] | None:
    """The axis of least inertia, if the object is elongated along it (see ELONGATION_RATIO)."""
    _, axes = np.linalg.eigh(unit_inertia)  # Ascending moments: column 0 = least inertia.
    spans = [np.ptp(points_O @ axes[:, k]) for k in range(3)]
    if spans[0] < ELONGATION_RATIO * max(spans[1], spans[2]):
        return None
    axis = axes[:, 0]
    axis = np.where(np.abs(axis) < 1e-12, 0.0, axis)
    axis = axis * np.sign(axis[np.argmax(np.abs(axis))])
    return tuple(float(v) + 0.0 for v in axis / np.linalg.norm(axis))  # + 0.0: no -0.0.


_INERTIA_ENTRIES = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))  # Ixx Iyy Izz Ixy Ixz Iyz


def _make_spec(
    name: str,
    pieces_B: list[ShapePiece],
    mass: float | None,
    *,
    density: float = DEFAULT_DENSITY,
    overlapping: bool = False,
    mass_properties: tuple[float, np.ndarray, np.ndarray] | None = None,
    rpy_TO: tuple[float, float, float] = (0.0, 0.0, 0.0),
    paper_class: str | None = None,
    closest_primitive: str | None = None,
    rgba: tuple[float, float, float, float] = YELLOW_PAPER_RGBA,
    friction: float | None = None,
    source: str | None = None,
) -> ObjectSpec:
    """Builds an ObjectSpec from pieces posed in a build frame B (any origin, O's axes).

    O is placed at the centroid of the union; `mass_properties` (volume, centroid in B, unit
    inertia about the centroid) overrides the computation from the pieces (e.g. a user mesh's exact
    values). With `mass` None the mass is density × volume.
    """
    if not re.fullmatch(r"[A-Za-z0-9_.\-]+", name):
        raise ObjectError(f"bad object name {name!r}: use letters, digits, '_', '-', '.'")
    pieces_B = tuple(pieces_B)
    if mass_properties is None:
        if overlapping and len(pieces_B) > 1:
            mass_properties = _mass_properties_sampled(pieces_B)
        else:
            mass_properties = _mass_properties_summed(pieces_B)
    volume, p_BO, unit_inertia = mass_properties
    pieces = tuple(_shift(piece, -np.asarray(p_BO)) for piece in pieces_B)
    mass = float(density * volume if mass is None else mass)
    if not mass > 0.0:
        raise ObjectError(f"{name}: mass must be positive, got {mass}")
    inertia = mass * unit_inertia
    lo, hi = _aabb(pieces, np.eye(3))
    lo_T, _ = _aabb(pieces, RollPitchYaw(*rpy_TO).ToRotationMatrix().matrix())
    points = np.vstack([_piece_points(piece) for piece in pieces])
    return ObjectSpec(
        name=name,
        pieces=pieces,
        mass=mass,
        inertia=tuple(float(inertia[i, j]) for i, j in _INERTIA_ENTRIES),
        volume=float(volume),
        extents=tuple(float(v) for v in hi - lo),
        rest_height=float(-lo_T[2]),
        rpy_TO=tuple(float(v) for v in rpy_TO),
        principal_axis=_principal_axis(points, unit_inertia),
        max_radius=float(np.max(np.linalg.norm(points, axis=1))),
        paper_class=paper_class,
        closest_primitive=closest_primitive,
        rgba=tuple(float(v) for v in rgba),
        friction=friction,
        source=source,
    )
