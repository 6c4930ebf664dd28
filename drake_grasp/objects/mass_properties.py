"""The geometry and mass properties of an object's pieces, and an `ObjectSpec` built from them.

Pieces are Drake primitives or convex meshes posed in the object frame (:mod:`drake_grasp.objects.spec`
states the conventions); their points, bounding boxes, containment tests and mass properties (summed
for pieces that do not overlap, sampled for ones that do) serve the catalogue, user files and the
ε metric alike. Units: metres, kilograms.
"""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
from pydrake.math import RollPitchYaw
from pydrake.multibody.tree import CalcSpatialInertia

from drake_grasp.objects.spec import (
    DEFAULT_DENSITY, ELONGATION_RATIO, ObjectError, ObjectSpec, ShapePiece, YELLOW_PAPER_RGBA,
    _convex_halfspaces, _convex_vertices,
)


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


def combined_mass_properties(parts) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass kg, centre of mass m, inertia about it kg·m²) of rigidly joined parts, each given as
    (mass, its centre of mass, its inertia about that centre), all in one frame: masses added, each
    inertia moved to the joint centre of mass (parallel axes). One part is returned as it is. The
    links of a model file (`rigid_assembly`) and an MJCF tree's <inertial>s combine so."""
    parts = [(float(m), np.asarray(c, float), np.asarray(inertia, float)) for m, c, inertia in parts]
    if len(parts) == 1:
        return parts[0]
    mass = sum(m for m, _, _ in parts)
    com = sum(m * c for m, c, _ in parts) / mass
    inertia = np.zeros((3, 3))
    for m, c, inertia_part in parts:
        d = c - com
        inertia += inertia_part + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return mass, com, inertia


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
    if not (mass > 0.0 and math.isfinite(mass)):
        raise ObjectError(f"{name}: mass must be a finite positive number (kg), got {mass}")
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
