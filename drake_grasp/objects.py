"""Object catalogue: the paper's nine objects, the primitive families of Fig. 4, user meshes.

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
by a hash of their content or of their source file. Generating them keeps every size in this file
(one source of truth, no model files to keep in sync) and works from an installed wheel, which does
not ship ``models/``.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import json
import math
import os
import re
import shutil
import tempfile
import warnings
from pathlib import Path
from typing import Callable

import numpy as np
import trimesh
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Mesh, Shape, Sphere
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.parsing import Parser
from pydrake.multibody.tree import CalcSpatialInertia
from scipy.spatial import ConvexHull, QhullError

from drake_grasp import piece_budget
from drake_grasp.contact import ContactParameters, compliant_proximity_sdf
from drake_grasp.geometry import cleaning

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


# --- The paper's nine objects (docs/design.md §4.3) ----------------------------------------------
# Sizes and masses are assumed (the paper gives none); YCB analogues in brackets. Every object is
# modelled in the pose it rests in on the table: z up, x along its longest horizontal extent.

_LYING_ALONG_X = (0.0, math.pi / 2.0, 0.0)  # rpy that turns a Drake cylinder/capsule's z onto x.

BANANA_CHORD = 0.18  # m, tip to tip [YCB 011 banana]
BANANA_DIAMETER = 0.036  # m
BANANA_BEND_RADIUS = 0.15  # m, radius of the centreline arc
BANANA_SEGMENTS = 4  # capsules in the chain (assumed)


def _banana() -> ObjectSpec:
    """A chain of capsules along a circular arc lying in the table plane, bulging towards +y."""
    radius = BANANA_DIAMETER / 2.0
    # The tips are the end capsules' caps: chord = 2·(R·sin θ + r), θ = half the arc angle.
    half_angle = math.asin((BANANA_CHORD / 2.0 - radius) / BANANA_BEND_RADIUS)
    angles = np.linspace(-half_angle, half_angle, BANANA_SEGMENTS + 1)
    centreline = np.column_stack(
        [
            BANANA_BEND_RADIUS * np.sin(angles),
            BANANA_BEND_RADIUS * np.cos(angles),
            np.zeros_like(angles),
        ]
    )
    pieces = []
    for a, b in zip(centreline[:-1], centreline[1:]):
        direction = b - a
        pieces.append(
            ShapePiece(
                "capsule",
                (radius, float(np.linalg.norm(direction))),
                p_OP=tuple((a + b) / 2.0),
                rpy_OP=(0.0, math.pi / 2.0, math.atan2(direction[1], direction[0])),
            )
        )
    return _make_spec(
        "banana", pieces, 0.12, overlapping=True, paper_class="annulus",
        closest_primitive="cylinder",
    )


def _apple() -> ObjectSpec:
    # 0.075 × 0.075 × 0.072 m [YCB 013 apple], 0.15 kg.
    pieces = [ShapePiece("ellipsoid", (0.075 / 2.0, 0.075 / 2.0, 0.072 / 2.0))]
    return _make_spec("apple", pieces, 0.15, paper_class="annulus", closest_primitive="sphere")


BELL_PEPPER_DIAMETER = 0.085  # m
BELL_PEPPER_HEIGHT = 0.09  # m
BELL_PEPPER_LOBES = 4
BELL_PEPPER_LOBE_OFFSET = 0.012  # m, distance of a lobe's axis from the pepper's axis (assumed)


def _bell_pepper() -> ObjectSpec:
    """The convex hull of four vertical ellipsoidal lobes: a rounded-square convex body."""
    lobe_radius = BELL_PEPPER_DIAMETER / 2.0 - BELL_PEPPER_LOBE_OFFSET
    semi = np.array([lobe_radius, lobe_radius, BELL_PEPPER_HEIGHT / 2.0])
    # A latitude-longitude grid that contains each lobe's equator and poles (the extremes).
    lat = np.linspace(-math.pi / 2.0, math.pi / 2.0, 11)
    lon = np.linspace(0.0, 2.0 * math.pi, 24, endpoint=False)
    lat, lon = np.meshgrid(lat, lon, indexing="ij")
    unit = np.column_stack(
        [(np.cos(lat) * np.cos(lon)).ravel(), (np.cos(lat) * np.sin(lon)).ravel(),
         np.sin(lat).ravel()]
    )
    points = []
    for k in range(BELL_PEPPER_LOBES):
        phi = 2.0 * math.pi * k / BELL_PEPPER_LOBES
        centre = BELL_PEPPER_LOBE_OFFSET * np.array([math.cos(phi), math.sin(phi), 0.0])
        points.append(unit * semi + centre)
    path = _cached_hull_obj("bell_pepper", np.vstack(points))
    pieces = [ShapePiece("convex", (), mesh_path=path)]
    return _make_spec(
        "bell_pepper", pieces, 0.16, paper_class="annulus", closest_primitive="sphere"
    )


def _sponge() -> ObjectSpec:
    # 0.11 × 0.07 × 0.035 m [YCB 026 sponge], 0.012 kg; a sharp box (exact contact).
    pieces = [ShapePiece("box", (0.11, 0.07, 0.035))]
    return _make_spec("sponge", pieces, 0.012, paper_class="annulus", closest_primitive="box")


SPECTACLE_CASE_SIZE = (0.16, 0.06, 0.04)  # m
SPECTACLE_CASE_EXPONENT = 4.0  # superellipsoid |x/a|^n + |y/b|^n + |z/c|^n = 1 (2 = ellipsoid)


def superellipsoid_points(
    semi_axes, exponent: float, n_lat: int = 13, n_lon: int = 32
) -> np.ndarray:
    """Surface points of the superellipsoid Σ|xᵢ/aᵢ|^n = 1, its extremes ±aᵢ included.

    Args:
        semi_axes: (a, b, c) semi-axes (m).
        exponent: n ≥ 1 (convex); 2 is an ellipsoid, large n approaches a box.
        n_lat: Latitude samples, poles included (odd, so that the equator is included).
        n_lon: Longitude samples (a multiple of 4, so that the ±x and ±y extremes are included).
    """
    e = 2.0 / exponent
    lat = np.linspace(-math.pi / 2.0, math.pi / 2.0, n_lat)
    lon = np.linspace(-math.pi, math.pi, n_lon, endpoint=False)
    lat, lon = np.meshgrid(lat, lon, indexing="ij")

    def signed_power(v):
        return np.sign(v) * np.abs(v) ** e

    a, b, c = semi_axes
    x = a * signed_power(np.cos(lat)) * signed_power(np.cos(lon))
    y = b * signed_power(np.cos(lat)) * signed_power(np.sin(lon))
    z = c * signed_power(np.sin(lat))
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


def _spectacle_case() -> ObjectSpec:
    """A superellipsoid of exponent 4 (a box with well-rounded edges), lying flat."""
    points = superellipsoid_points(np.array(SPECTACLE_CASE_SIZE) / 2.0, SPECTACLE_CASE_EXPONENT)
    path = _cached_hull_obj("spectacle_case", points)
    pieces = [ShapePiece("convex", (), mesh_path=path)]
    return _make_spec(
        "spectacle_case", pieces, 0.06, paper_class="annulus", closest_primitive="box"
    )


TOY_BRIDGE_SIZE = (0.15, 0.05, 0.06)  # m: span (x), width (y), height (z)
TOY_BRIDGE_BEAM_THICKNESS = 0.02  # m (assumed)
TOY_BRIDGE_LEG_WIDTH = 0.03  # m, along the span (assumed)


def _toy_bridge() -> ObjectSpec:
    """An arch: a beam on two legs (three boxes that touch and do not overlap)."""
    span, width, height = TOY_BRIDGE_SIZE
    leg_height = height - TOY_BRIDGE_BEAM_THICKNESS
    leg_x = span / 2.0 - TOY_BRIDGE_LEG_WIDTH / 2.0
    beam = (span, width, TOY_BRIDGE_BEAM_THICKNESS)
    leg = (TOY_BRIDGE_LEG_WIDTH, width, leg_height)
    pieces = [
        ShapePiece("box", beam, p_OP=(0.0, 0.0, height - TOY_BRIDGE_BEAM_THICKNESS / 2.0)),
        ShapePiece("box", leg, p_OP=(-leg_x, 0.0, leg_height / 2.0)),
        ShapePiece("box", leg, p_OP=(leg_x, 0.0, leg_height / 2.0)),
    ]
    return _make_spec("toy_bridge", pieces, 0.10, paper_class="annulus", closest_primitive="box")


def _soccer_ball() -> ObjectSpec:
    # Ø 0.20 m, 0.30 kg (a size-3 ball is Ø ~0.19 m, ~0.3 kg).
    pieces = [ShapePiece("sphere", (0.10,))]
    return _make_spec(
        "soccer_ball", pieces, 0.30, paper_class="sun_ray_sphere", closest_primitive="sphere"
    )


def _game_box() -> ObjectSpec:
    # 0.26 × 0.18 × 0.08 m lying flat, 0.40 kg.
    pieces = [ShapePiece("box", (0.26, 0.18, 0.08))]
    return _make_spec(
        "game_box", pieces, 0.40, paper_class="sun_ray_box", closest_primitive="box"
    )


def _bottle_case() -> ObjectSpec:
    # Ø 0.10 × 0.35 m, lying on its side with its axis along O's x, 0.35 kg.
    pieces = [ShapePiece("cylinder", (0.05, 0.35), rpy_OP=_LYING_ALONG_X)]
    return _make_spec(
        "bottle_case", pieces, 0.35, paper_class="sun_ray_cylinder", closest_primitive="cylinder"
    )


_PAPER_FACTORIES: dict[str, Callable[[], ObjectSpec]] = {
    "banana": _banana,
    "apple": _apple,
    "bell_pepper": _bell_pepper,
    "sponge": _sponge,
    "spectacle_case": _spectacle_case,
    "toy_bridge": _toy_bridge,
    "soccer_ball": _soccer_ball,
    "game_box": _game_box,
    "bottle_case": _bottle_case,
}

PAPER_OBJECTS: tuple[str, ...] = tuple(_PAPER_FACTORIES)
"""Names of the paper's nine objects, in the order of the table in docs/design.md §4.3 (annulus first)."""


@functools.lru_cache(maxsize=None)
def _paper_object_cached(name: str) -> ObjectSpec:
    return _PAPER_FACTORIES[name]()


def paper_object(name: str, *, rgba=None, friction: float | None = None) -> ObjectSpec:
    """One of the paper's nine objects (docs/design.md §4.3).

    Args:
        name: One of ``PAPER_OBJECTS``.
        rgba: Visual colour (RGBA, 0–1); default yellow paper.
        friction: Coulomb friction of this object; None uses the scene's.

    Raises:
        ObjectError: Unknown name (the message lists the valid names).
    """
    if name not in _PAPER_FACTORIES:
        raise ObjectError(f"unknown object {name!r}; valid names: {', '.join(PAPER_OBJECTS)}")
    spec = _paper_object_cached(name)
    if rgba is not None:
        spec = dataclasses.replace(spec, rgba=tuple(float(v) for v in rgba))
    if friction is not None:
        spec = dataclasses.replace(spec, friction=float(friction))
    return spec


# --- Primitive families (Fig. 4) -----------------------------------------------------------------


def _mm(size: float) -> str:
    return f"{size * 1000.0:.4g}mm".replace(".", "p")


PRIMITIVE_SIZE_RANGE = (0.001, 10.0)  # m: from a millimetre (Drake's geometry breaks down far below)
# to ten metres (far past anything the hand can hold: a number that large is a typo or the wrong unit)


def _check_size(label: str, **sizes: float) -> None:
    low, high = PRIMITIVE_SIZE_RANGE
    for key, value in sizes.items():
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
            raise ObjectError(f"{label}: {key} must be a positive number of metres, got {value!r}")
        if not low <= value <= high:
            raise ObjectError(f"{label}: {key} {value:g} m is outside [{low:g}, {high:g}] m (sizes are in metres)")


def sphere_object(
    diameter: float,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid sphere (Fig. 4's sphere family), named e.g. ``sphere_120mm``.

    Args:
        diameter: Diameter (m).
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    _check_size("sphere", diameter=diameter)
    return _make_spec(
        f"sphere_{_mm(diameter)}", [ShapePiece("sphere", (diameter / 2.0,))], mass, density=density,
        closest_primitive="sphere", rgba=rgba,
    )


def cube_object(
    edge: float,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid cube (Fig. 4's cube family) resting on a face, its edges along O's (and T's) axes.

    Args:
        edge: Edge length (m).
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    _check_size("cube", edge=edge)
    return _make_spec(
        f"cube_{_mm(edge)}", [ShapePiece("box", (edge, edge, edge))], mass, density=density,
        closest_primitive="box", rgba=rgba,
    )


def cylinder_object(
    diameter: float,
    length: float | None = None,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid cylinder (Fig. 4's cylinder family) lying on its side, its axis along O's x.

    In its nominal pose (R_TO = I) the axis lies along the table's x, so a cylindrical grasp from
    above closes its fingers along y, as for the cubes (the paper's Sec. 3, Fig. 4; docs/design.md §2);
    pose errors along x then run along the axis and errors along y across it.

    The length is **fixed** (``CYLINDER_FAMILY_LENGTH`` = 0.30 m) while the diameter grows:
    Fig. 4's size axis is what the fingers wrap around, the cross-section; a fixed length longer
    than the hand is wide keeps the fingers on the curved side (never the end caps) for every
    diameter and every pose error along the axis, so only the diameter changes between sizes. A
    proportional length would make small cylinders short stubs the fingers close past and large
    ones logs longer than the table.

    Args:
        diameter: Diameter (m).
        length: Length (m); default CYLINDER_FAMILY_LENGTH.
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    length = CYLINDER_FAMILY_LENGTH if length is None else length
    _check_size("cylinder", diameter=diameter, length=length)
    return _make_spec(
        f"cylinder_{_mm(diameter)}x{_mm(length)}",
        [ShapePiece("cylinder", (diameter / 2.0, length), rpy_OP=_LYING_ALONG_X)],
        mass, density=density, closest_primitive="cylinder", rgba=rgba,
    )


# --- User objects ---------------------------------------------------------------------------------


def _one_line(text: str) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= 200 else text[:197] + "..."


def _model_name(text: str) -> str:
    """`text` made a valid model name (letters, digits, '_', '-'; starting with a letter)."""
    name = re.sub(r"[^A-Za-z0-9_\-]", "_", text) or "object"
    return name if name[0].isalpha() else "object_" + name


def _load_checked_mesh(path: Path, label: str, scale: float) -> trimesh.Trimesh:
    """Loads a mesh and checks it is a closed, positive-volume solid (fixing inverted winding)."""
    if not path.exists():
        raise ObjectError(f"{label}: file not found")
    if not path.is_file():
        raise ObjectError(f"{label}: not a file")
    try:
        mesh = trimesh.load(path, force="mesh", process=False)
    except Exception as error:  # trimesh raises many types for unreadable files.
        reason = _one_line(error) or type(error).__name__
        raise ObjectError(f"{label}: cannot read mesh ({reason})") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise ObjectError(f"{label}: file contains no triangles")
    bad = int(np.count_nonzero(~np.isfinite(mesh.vertices).all(axis=1)))
    if bad:
        noun = "vertex is" if bad == 1 else "vertices are"
        raise ObjectError(f"{label}: {bad} {noun} not finite (NaN or inf)")
    mesh.apply_scale(scale)
    mesh.merge_vertices()
    extents = mesh.extents
    if not np.min(extents) > 1e-9 * max(np.max(extents), 1e-300):
        raise ObjectError(f"{label}: mesh has zero volume (it is flat)")
    if not mesh.is_watertight:
        edges = trimesh.grouping.group_rows(mesh.edges_sorted, require_count=1)
        if len(edges):
            raise ObjectError(f"{label}: mesh is not watertight ({len(edges)} open edges)")
        raise ObjectError(f"{label}: mesh is not watertight (edges shared by more than two faces)")
    if not mesh.is_winding_consistent:
        raise ObjectError(f"{label}: mesh has inconsistent face winding (normals point in and out)")
    volume = mesh.volume
    if abs(volume) <= 1e-9 * float(np.prod(extents)):
        raise ObjectError(f"{label}: mesh has zero volume")
    if volume < 0.0:
        mesh.invert()  # Consistently inverted winding: flip it (the solid itself is well defined).
    return mesh


CLEANING_VERSION = 1  # part of the cache key of decompositions: bump when cleaning changes


def _decompose(mesh: trimesh.Trimesh, key: str, max_pieces: int, label: str = "mesh") -> list[str]:
    """Convex pieces of `mesh` as OBJ files (vertices in the mesh frame), cached under `key`.

    Each piece first keeps at most `piece_budget.MAX_PIECE_VERTICES` of its vertices (a hull inside
    it, so that contact and the planner's distances stay cheap), then is cleaned for contact
    (:func:`drake_grasp.geometry.cleaning.clean_pieces`: no near-duplicate vertices, no sliver
    triangles, none thinner than MIN_THICKNESS), removing at most VOLUME_TOLERANCE of the mesh's
    volume (else ObjectError). Mass properties never come from the pieces: they come from the mesh.
    """
    key = f"{key}-{piece_budget.CACHE_TAG}-c{CLEANING_VERSION}"
    directory = cache_dir() / "decomposed" / key
    manifest = directory / "pieces.json"
    if manifest.exists():
        names = json.loads(manifest.read_text())["pieces"]
        return [str((directory / name).resolve()) for name in names]
    hull = mesh.convex_hull
    if mesh.volume >= (1.0 - CONVEXITY_TOLERANCE) * hull.volume:
        parts = [(hull.vertices, hull.faces)]
    else:
        import coacd  # Imported here: only non-convex user meshes need it.

        warnings.warn(f"{label}: non-convex: decomposing into at most {max_pieces} convex pieces (CoACD, "
                      "seconds to minutes; cached for next time)", MeshNote, stacklevel=3)

        coacd.set_log_level("error")
        result = coacd.run_coacd(
            coacd.Mesh(np.asarray(mesh.vertices, float), np.asarray(mesh.faces, np.int32)),
            threshold=COACD_THRESHOLD,
            max_convex_hull=max_pieces,
            seed=0,
        )
        parts = [(np.asarray(vertices, float), None) for vertices, _ in result]
    budgeted = [piece_budget.budgeted_piece(vertices)[0] for vertices, _ in parts]
    try:
        clean, _ = cleaning.clean_pieces(budgeted, float(mesh.volume))
    except cleaning.CleaningError as error:
        raise ObjectError(f"{label}: {error}") from None
    parts = [(piece.vertices, piece.faces) for piece in clean]
    # Write into a private directory, then rename it into place: a concurrent process (parallel
    # trials) either sees the complete directory or none, and the first to finish wins.
    directory.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(dir=directory.parent, prefix=key + ".tmp"))
    names = [f"piece_{index:03d}.obj" for index in range(len(parts))]
    for name, (vertices, faces) in zip(names, parts):
        (staging / name).write_text(_obj_text(vertices, faces))
    (staging / "pieces.json").write_text(json.dumps({"pieces": names}))
    try:
        os.rename(staging, directory)
    except OSError:
        shutil.rmtree(staging, ignore_errors=True)
        if not manifest.exists():
            raise
        # Another process got there first; use its pieces.
    names = json.loads(manifest.read_text())["pieces"]
    return [str((directory / name).resolve()) for name in names]


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
    or a point) over which its centre of mass lies, or so that no resting pose lowers its centre of
    mass by more than STABLE_POSE_TOLERANCE of its size (a sphere, rolling off the vertex its
    tessellation stands on)."""
    height = float(p_Ocm[2] - hull.vertices[:, 2].min())
    distances = np.einsum("ij,ij->i", hull.face_normals, hull.triangles[:, 0] - p_Ocm)
    if height - float(distances.min()) <= STABLE_POSE_TOLERANCE * float(np.max(hull.extents)):
        return True
    down = np.array([0.0, 0.0, -1.0])
    z_min = float(hull.vertices[:, 2].min())
    bottom = (hull.face_normals @ down > 1.0 - 1e-6) & (np.abs(hull.triangles[:, :, 2] - z_min).max(axis=1) < 1e-6)
    if not np.any(bottom):
        return False
    polygon = np.unique(np.round(hull.triangles[bottom].reshape(-1, 3)[:, :2], 9), axis=0)
    if len(polygon) < 3:
        return False  # a point or an edge
    try:
        equations = ConvexHull(polygon).equations  # a·x + b ≤ 0 inside
    except QhullError:  # collinear points: an edge
        return False
    return bool(np.all(equations[:, :2] @ p_Ocm[:2] + equations[:, 2] <= 1e-9))


def _user_solid(mesh: trimesh.Trimesh, label: str, keep_largest: bool) -> trimesh.Trimesh:
    """The solid a checked mesh encloses: its shells united; one component (or the largest)."""
    from drake_grasp.geometry.solid import enclosed_solid, largest_component

    solid = enclosed_solid(mesh)
    if solid.components > 1:
        if not keep_largest:
            raise ObjectError(f"{label}: {solid.components} separate solids that do not touch (one object must be "
                              "one piece); keep the largest with --largest-component")
        return largest_component(solid)
    return solid.mesh


def _likely_scale(extent: float) -> tuple[str, float] | None:
    """(unit, scale) that brings a largest extent `extent` (file units) into PLAUSIBLE_EXTENTS."""
    for unit, factor in (("millimetres", 0.001), ("centimetres", 0.01), ("inches", 0.0254)):
        if PLAUSIBLE_EXTENTS[0] <= extent * factor <= PLAUSIBLE_EXTENTS[1]:
            return unit, factor
    return None


def _warn_units(mesh: trimesh.Trimesh, label: str, scale: float) -> None:
    """One UnitsWarning when the object's largest extent (m) is implausible for the hand."""
    extent = float(np.max(mesh.extents))
    if PLAUSIBLE_EXTENTS[0] <= extent <= PLAUSIBLE_EXTENTS[1]:
        return
    if extent > PLAUSIBLE_EXTENTS[1]:
        guess = _likely_scale(extent / scale)
        hint = (f"is the file in {guess[0]}? use --scale {guess[1]:g}" if guess
                else "is the file in metres? set --scale")
        message = f"{label}: largest extent {extent:.3g} m: {hint}"
    else:
        message = (f"{label}: largest extent {extent * 1000:.3g} mm, smaller than the hand can grasp: "
                   "is the file in metres? set --scale")
    warnings.warn(message, UnitsWarning, stacklevel=3)


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
) -> ObjectSpec:
    """An object from a closed triangle mesh in any format trimesh reads (OBJ, STL, PLY, ...).

    The object is the solid the mesh encloses (:mod:`drake_grasp.geometry.solid`): closed shells
    that overlap are united (mass and inertia never count an overlap twice); shells that do not
    touch are an ObjectError naming their count, unless `largest_component` keeps the largest. A
    largest extent outside PLAUSIBLE_EXTENTS gets a one-line UnitsWarning naming the likely unit. A
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
    mesh = _load_checked_mesh(path, label, scale)
    if len(mesh.faces) > MAX_FACES:  # Said first: what follows takes a while on such a mesh.
        warnings.warn(f"{label}: {len(mesh.faces):,} faces; simplifying to {MAX_FACES:,} for contact and rendering",
                      MeshNote, stacklevel=2)
    mesh = _user_solid(mesh, label, largest_component)
    _warn_units(mesh, label, scale)
    digest = hashlib.sha256(path.read_bytes()).hexdigest()
    settings = f"{scale!r}|{max_pieces}|{COACD_THRESHOLD!r}|{CONVEXITY_TOLERANCE!r}|{largest_component}|{MAX_FACES}"
    key = hashlib.sha256((digest + settings).encode()).hexdigest()[:20]
    volume = float(mesh.volume)
    centroid = np.asarray(mesh.center_mass, float)
    unit_inertia = np.asarray(mesh.moment_inertia, float) / float(mesh.mass)
    contact_mesh = _simplified(mesh, label)
    piece_paths = _decompose(contact_mesh, f"{_model_name(path.stem)}-{key}", max_pieces, label)
    rpy_TO = (0.0, 0.0, 0.0)
    if stable_pose is None and not _rests_stably_upright(contact_mesh.convex_hull, centroid):
        warnings.warn(f"{label}: with its z up the object would tip over (it rests on an edge or a point, "
                      "or its centre of mass is not over its base); resting it on its most stable face",
                      UnstablePoseWarning, stacklevel=2)
        stable_pose = True
    if stable_pose:
        rpy_TO = tuple(RollPitchYaw(_lowest_resting_rotation(contact_mesh.convex_hull, centroid)).vector())
    pieces = [ShapePiece("convex", (), mesh_path=p) for p in piece_paths]
    return _make_spec(
        name or _model_name(path.stem),
        pieces,
        mass,
        density=density,
        mass_properties=(volume, centroid, unit_inertia),
        rpy_TO=rpy_TO,
        closest_primitive=closest_primitive,
        rgba=rgba,
        friction=friction,
        source=str(path.resolve()),
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

    Raises:
        ObjectError: One line naming the file and the problem.
    """
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    label = os.fspath(path)
    path = Path(path).expanduser()
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
        unit_inertia = unit_inertia_Bo - shift  # About the centre of mass.
        # Overlapping pieces overcount the volume; it is only reported, mass comes from the file.
        volume = _mass_properties_summed(tuple(pieces_B))[0]
        mass_properties = (volume, p_BScm, unit_inertia)
        mass = file_mass if mass is None else mass
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


# --- Names, primitive strings and paths ---------------------------------------------------------

_NUMBER = r"([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)"
_PRIMITIVE_PATTERNS = {
    "sphere": re.compile(rf"sphere:{_NUMBER}"),
    "cube": re.compile(rf"cube:{_NUMBER}"),
    "cylinder": re.compile(rf"cylinder:{_NUMBER}(?:x{_NUMBER})?"),
}
_PRIMITIVE_HELP = "sphere:DIAMETER, cube:EDGE, cylinder:DIAMETER[xLENGTH] (metres)"


def resolve_object(name_or_path: str | os.PathLike, **kw) -> ObjectSpec:
    """The object named on a command line.

    Args:
        name_or_path: A catalogue name (``PAPER_OBJECTS``); a primitive string such as
            ``sphere:0.12``, ``cube:0.08``, ``cylinder:0.1x0.3`` or ``cylinder:0.1`` (metres;
            length default CYLINDER_FAMILY_LENGTH); or the path of a mesh (any format trimesh
            reads) or an ``.sdf``/``.urdf`` model file.
        **kw: Passed on to :func:`paper_object`, :func:`sphere_object` (etc.),
            :func:`object_from_mesh` or :func:`object_from_sdf`.

    Raises:
        ObjectError: Unknown name (listing the valid names), bad primitive string, missing or bad
            file.
    """
    if not isinstance(name_or_path, str):
        return _object_from_file(Path(name_or_path), os.fspath(name_or_path), kw)
    text = name_or_path.strip()
    if not text:
        raise ObjectError("empty object name; give a catalogue name, a primitive such as sphere:0.12, "
                          "or a mesh file")
    if text in _PAPER_FACTORIES:
        return paper_object(text, **kw)
    kind = text.split(":", 1)[0].lower() if ":" in text else None
    if kind in _PRIMITIVE_PATTERNS:
        match = _PRIMITIVE_PATTERNS[kind].fullmatch(text.lower())
        if match is None:
            raise ObjectError(f"bad primitive {text!r}; expected {_PRIMITIVE_HELP}")
        values = [float(v) for v in match.groups() if v is not None]
        if kind == "sphere":
            return sphere_object(*values, **kw)
        if kind == "cube":
            return cube_object(*values, **kw)
        return cylinder_object(*values, **kw)
    path = Path(text).expanduser()
    if path.suffix or os.sep in text or "/" in text or path.exists():
        return _object_from_file(path, text, kw)
    raise ObjectError(
        f"unknown object {text!r}; valid names: {', '.join(PAPER_OBJECTS)}; or {_PRIMITIVE_HELP}; "
        "or a mesh/SDF file path"
    )


def resolve_user_object(
    name_or_path: str, *, scale: float = 1.0, largest_component: bool = False, **kw
) -> ObjectSpec:
    """:func:`resolve_object` with the options that only a mesh file takes (a command line's
    ``--scale`` and ``--largest-component``): ObjectError if they are given for anything else."""
    text = str(name_or_path).strip()
    if scale == 1.0 and not largest_component:
        return resolve_object(text, **kw)
    options = "--scale" if scale != 1.0 else "--largest-component"
    if not is_mesh_file(text):
        raise ObjectError(f"{text}: {options} applies to mesh files only (OBJ, STL, PLY)")
    if not (scale > 0.0 and math.isfinite(scale)):
        raise ObjectError(f"--scale must be positive, got {scale!r}")
    return resolve_object(text, scale=scale, largest_component=largest_component, **kw)


def is_mesh_file(name_or_path: str) -> bool:
    """Whether an object argument names a mesh file (what `--scale` applies to), not a catalogue
    object, a primitive or an SDF/URDF model."""
    text = str(name_or_path).strip()
    return not (text in _PAPER_FACTORIES or ":" in text or Path(text).suffix.lower() in (".sdf", ".urdf"))


def mesh_options(scale: float = 1.0, largest_component: bool = False) -> dict:
    """The mesh options that differ from their defaults, as keyword arguments of
    :func:`resolve_user_object` (plain data: a sweep's tasks carry them to its workers, and a
    record's fingerprint includes them)."""
    options = {}
    if scale != 1.0:
        options["scale"] = float(scale)
    if largest_component:
        options["largest_component"] = True
    return options


def _object_from_file(path: Path, label: str, kw: dict) -> ObjectSpec:
    if not path.exists():
        raise ObjectError(f"{label}: file not found")
    if path.suffix.lower() in (".sdf", ".urdf"):
        return object_from_sdf(path, **kw)
    return object_from_mesh(path, **kw)


# --- Drake model ----------------------------------------------------------------------------------


def _f(value: float) -> str:
    return f"{value + 0.0:.9g}"  # + 0.0 turns -0.0 into 0.0.


def _geometry_sdf(piece: ShapePiece) -> str:
    s = piece.size
    if piece.kind == "sphere":
        return f"<sphere><radius>{_f(s[0])}</radius></sphere>"
    if piece.kind == "ellipsoid":
        return f"<ellipsoid><radii>{_f(s[0])} {_f(s[1])} {_f(s[2])}</radii></ellipsoid>"
    if piece.kind == "box":
        return f"<box><size>{_f(s[0])} {_f(s[1])} {_f(s[2])}</size></box>"
    if piece.kind == "cylinder":
        return f"<cylinder><radius>{_f(s[0])}</radius><length>{_f(s[1])}</length></cylinder>"
    if piece.kind == "capsule":
        return f"<capsule><radius>{_f(s[0])}</radius><length>{_f(s[1])}</length></capsule>"
    # Drake resolves only file:// URIs (not plain paths) in SDFormat parsed from a string.
    return f"<mesh><uri>{Path(piece.mesh_path).as_uri()}</uri><drake:declare_convex/></mesh>"


def _facet_down(piece: ShapePiece, R_TO: RotationMatrix, resolution_hint: float) -> ShapePiece:
    """Spins a cylinder lying on its side about its own axis so that its contact mesh rests on a
    facet, not on an edge.

    Drake's compliant cylinder is a prism of n = ceil(2πr / resolution_hint) rim vertices at angles
    2πk/n about the cylinder's z from its x axis (geometry/proximity/make_cylinder_mesh.cc,
    MakeCylinderVolumeMeshWithMa). Resting on an edge, it rolls half a facet (5.8° for our bottle
    case at n = 31) before it settles; the spin puts a facet's middle straight down instead. The
    ideal cylinder is symmetric about its axis, so the spin changes only the tessellation.
    """
    R_OP, p_OP = _pose(piece)
    down_P = R_OP.T @ R_TO.matrix().T @ np.array([0.0, 0.0, -1.0])
    if abs(down_P[2]) > 1e-9:
        return piece  # Not lying on its side.
    n = math.ceil(2.0 * math.pi * piece.size[0] / resolution_hint)
    facet = 2.0 * math.pi / n
    spin = math.atan2(down_P[1], down_P[0]) - facet / 2.0
    R_OP_spun = RotationMatrix(R_OP) @ RotationMatrix.MakeZRotation(spin)
    rpy_OP = tuple(float(v) for v in RollPitchYaw(R_OP_spun).vector())
    return dataclasses.replace(piece, rpy_OP=rpy_OP)


def object_sdf(spec: ObjectSpec, contact: ContactParameters | None = None) -> str:
    """SDFormat 1.9 text of the object: one model and one body, both named ``spec.name``.

    The body frame is O; the inertial is at O (the centre of mass). Each piece is one collision
    geometry (compliant hydroelastic, `contact`'s parameters; friction ``spec.friction`` if set) and
    one visual of colour ``spec.rgba``. Mesh pieces are referenced by absolute ``file://`` URI.

    Args:
        spec: The object.
        contact: Contact parameters; default ``ContactParameters()``.
    """
    contact = ContactParameters() if contact is None else contact
    ixx, iyy, izz, ixy, ixz, iyz = spec.inertia
    rgba = " ".join(_f(v) for v in spec.rgba)
    elements = []
    for index, piece in enumerate(spec.pieces):
        if piece.kind == "cylinder":
            hint = contact.resolution_hint(piece.characteristic_size())
            piece = _facet_down(piece, spec.R_TO, hint)
        pose = " ".join(_f(v) for v in (*piece.p_OP, *piece.rpy_OP))
        geometry = _geometry_sdf(piece)
        proximity = compliant_proximity_sdf(contact, piece.characteristic_size(), spec.friction)
        elements.append(
            f'      <collision name="collision_{index}">\n'
            f"        <pose>{pose}</pose>\n"
            f"        <geometry>{geometry}</geometry>\n"
            f"        {proximity}\n"
            f"      </collision>\n"
            f'      <visual name="visual_{index}">\n'
            f"        <pose>{pose}</pose>\n"
            f"        <geometry>{geometry}</geometry>\n"
            f"        <material><diffuse>{rgba}</diffuse></material>\n"
            f"      </visual>\n"
        )
    return (
        '<?xml version="1.0"?>\n'
        '<sdf version="1.9" xmlns:drake="http://drake.mit.edu">\n'
        f'  <model name="{spec.name}">\n'
        f'    <link name="{spec.name}">\n'
        "      <inertial>\n"
        "        <pose>0 0 0 0 0 0</pose>\n"
        f"        <mass>{_f(spec.mass)}</mass>\n"
        f"        <inertia><ixx>{_f(ixx)}</ixx><iyy>{_f(iyy)}</iyy><izz>{_f(izz)}</izz>"
        f"<ixy>{_f(ixy)}</ixy><ixz>{_f(ixz)}</ixz><iyz>{_f(iyz)}</iyz></inertia>\n"
        "      </inertial>\n"
        + "".join(elements)
        + "    </link>\n"
        "  </model>\n"
        "</sdf>\n"
    )


def AddObject(plant, spec: ObjectSpec, contact: ContactParameters | None = None):
    """Adds the object to a MultibodyPlant (before Finalize) as a free body.

    Parsing is strict: a parser warning about our own model is an error.

    Args:
        plant: The MultibodyPlant (registered with a SceneGraph).
        spec: The object.
        contact: Contact parameters; default ``ContactParameters()``.

    Returns:
        The ModelInstanceIndex of the model named ``spec.name``; its body is
        ``plant.GetBodyByName(spec.name, model)``, whose frame is O.
    """
    parser = Parser(plant)
    parser.SetStrictParsing()
    (model,) = parser.AddModelsFromString(object_sdf(spec, contact), "sdf")
    return model


SUPPORT_TABLE_SIZE = (2.0, 2.0, 0.1)  # m: a slab large enough to be the table under any object


def RegisterSupportTable(plant, spec: ObjectSpec, friction: float = 0.5):
    """Registers (before Finalize) the table the object rests on, in a plant whose world frame is
    the object frame O: an anchored slab whose top is the table plane of the object's nominal
    resting pose (z_T = 0 at -rest_height below O, tilted by R_TO). Returns its geometry id.

    For kinematic queries (planning, quasi-static closing) that must respect the table.
    """
    from pydrake.geometry import Box, ProximityProperties, AddContactMaterial
    from pydrake.multibody.plant import CoulombFriction

    R_OT = spec.R_TO.inverse()
    p_OT = R_OT @ np.array([0.0, 0.0, -spec.rest_height])
    X_OT = RigidTransform(R_OT, p_OT)
    X_TS = RigidTransform([0.0, 0.0, -SUPPORT_TABLE_SIZE[2] / 2])
    properties = ProximityProperties()
    AddContactMaterial(friction=CoulombFriction(friction, friction), properties=properties)
    return plant.RegisterCollisionGeometry(plant.world_body(), X_OT @ X_TS, Box(*SUPPORT_TABLE_SIZE),
                                           "support_table", properties)
