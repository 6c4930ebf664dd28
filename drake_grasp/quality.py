"""Grasp quality: the Ferrari–Canny ε metric over the L1 grasp wrench space (docs/design.md §4.5).

Pure numpy/scipy, no Drake: the functions take plain arrays (contacts expressed in one frame) and
return plain numbers, so they can run in inner loops (the Fig. 4 sweep, the Eigengrasp planner's
ranking) and be tested on hand-made arrays.

Convention (the project's, after GraspIt!'s ``QualEpsilon`` over the L1 grasp wrench space, which
the Eigengrasp planner ranks by; numbers and definitions cited, no code taken from it):

* Contact i sits at the point ``p_i`` (metres) with the unit normal ``n_i`` pointing **into** the
  object, i.e. along the force the hand can push with.
* Its Coulomb friction cone (coefficient μ) is linearised with m edges (``num_edges``; 8 by default,
  the count GraspIt!'s point contacts use). With the tangent frame ``t1 = n × (1, 0, 0)`` normalised
  (``n × (0, 0, 1)`` when n is parallel to x) and ``t2 = n × t1``, edge j is::

      f_ij = n_i + μ (cos θ_j t1 + sin θ_j t2),   θ_j = 2π j / m,   j = 0 … m − 1.

  The normal component of every edge is 1 (edges are not unit length), so the hull below holds the
  wrenches the contacts can exert with a total (L1) normal force of 1: forces are dimensionless
  (fractions of one unit of total normal force).
* The primitive wrench of edge j at contact i is ``w_ij = [f_ij ; (p_i − c) × f_ij / ρ]`` with ``c``
  the object's centre of mass and ρ the torque scale (metres; GraspIt! uses the largest distance
  from c to the object's surface, its "max radius"), which makes torques dimensionless too.
* GWS = convex hull of all ``w_ij`` in R^6 (computed by qhull). ε is the distance from the origin to
  the nearest facet of that hull when the origin is strictly inside it, else 0; also 0 when the hull
  is degenerate (the wrenches span less than 6 dimensions, e.g. any grasp with two point contacts:
  no wrench can have a moment about the line through the two contacts).

Other implementations differ (docs/design.md §4.5): Dex-Net scales torques by 1/median of the bounding-box
corner, OpenRAVE uses unit-length edges and the world origin. The torque scale and the edge count
are parameters here; the contact-quality planner energy (docs/design.md §4.6) uses the force-only 3-D variant,
available through :func:`wrench_space_quality` on the force rows of :func:`primitive_wrenches`.

Caveat of the convention: the tangent frame depends on the contact normal's orientation relative to
the world x axis, so the linearised cone (not the true cone) turns about n when the whole grasp is
rotated. ε is exactly invariant under translations, permutations of the contacts and rotations about
x (which commute with the frame construction); under other rotations it varies within the bounds
ε(μ cos(π/m)) ≤ ε ≤ ε(μ / cos(π/m)), because a regular m-gon of circumradius μ contains the disc
of radius μ cos(π/m). Use more edges where that matters.

Qhull options: scipy's default for 6-D input ("Qx", exact pre-merges, plus the always-on "Qt",
triangulated output), close to GraspIt!'s own "Qx C-0.0001" but without its 1e-4 centrum merging.
Facet normals in ``ConvexHull.equations`` are unit vectors with ``normal · x + offset ≤ 0`` inside,
so the distance from the origin to facet k is ``−offset_k``; results are exact to rounding,
deterministic, and keep the symmetries the tests check. Measured on grasp wrenches (8-edge cones,
3–6 contacts): "QJ" (joggled input) is about 2× faster but moves ε by ~1e-10 and turns flat or
nearly flat wrench sets into thin full-dimensional hulls, so it serves only as a fallback when the
default reports a precision error on a set that is not flat; "Q0" (no merging) is about 3×
faster, but the qhull manual warns that it leads to serious precision errors on degenerate input,
and grasp wrenches are degenerate by construction (the m edges of a cone are coplanar); "Qbb"
rescales the last coordinate, and scipy then reports ``equations`` and ``volume`` of the rescaled
hull. Flat wrench sets (fewer than 7 affinely independent wrenches, judged by the singular values
of the centred wrenches) are recognised before qhull is called. scripts/bench_quality.py measures ε
against a bare ``ConvexHull`` call on the same wrenches.
"""

from __future__ import annotations

import dataclasses
import numbers

import numpy as np
from scipy.spatial import ConvexHull, QhullError

# The project's ε convention (docs/design.md §4.4-4.5): μ 0.5 and 8 cone edges, as Fig. 4 and GraspIt!'s
# point contacts; every run-time and study use of ε takes these (funnel.search, studies.epsilon_physics).
FRICTION = 0.5
CONE_EDGES = 8

# Normals shorter than this (dimensionless; normals are directions and are normalised here) are
# rejected as zero.
_MIN_NORMAL_LENGTH = 1e-9
# |n × x| below this means "n parallel to x": the tangent frame then starts from n × z.
_PARALLEL_TO_X_TOLERANCE = 1e-9
# Relative tolerances, as fractions of the largest primitive wrench norm: the smallest singular
# value of the centred wrenches below which the wrench set counts as flat, and the facet offset
# above which the origin does not count as strictly inside the hull.
_FLATNESS_TOLERANCE = 1e-10
_INTERIOR_TOLERANCE = 1e-10
# Qhull options for the rare wrench set on which the default ("Qx", exact merges) reports a
# precision error although it is not flat.
_FALLBACK_QHULL_OPTIONS = "QJ"


@dataclasses.dataclass(frozen=True)
class GraspQuality:
    """The ε metric and the volume of a grasp wrench space.

    Attributes:
        epsilon: Distance (dimensionless: units of total normal force, torques divided by the torque
            scale) from the origin to the nearest facet of the GWS when the origin is strictly
            inside, else 0. Equals the magnitude of the smallest disturbance wrench, in its worst
            direction, that the grasp can resist with unit total normal force.
        volume: Volume of the GWS hull (dimensionless, d-dimensional for d-dimensional wrenches);
            0 for a degenerate hull. GraspIt!'s automated planner ranks by −(30·volume + 100·ε).
    """

    epsilon: float
    volume: float

    @property
    def is_force_closure(self) -> bool:
        """Whether the origin is strictly inside the GWS (ε > 0)."""
        return self.epsilon > 0.0


def contact_tangent_frames(normals) -> tuple[np.ndarray, np.ndarray]:
    """Tangent frames of contacts, in the project's convention.

    Args:
        normals: (N, 3) unit contact normals (dimensionless), pointing into the object. Not
            checked or normalised here; use :func:`primitive_wrenches` for checked input.

    Returns:
        (t1, t2), each (N, 3) unit vectors: ``t1 = n × (1, 0, 0)`` normalised, or
        ``n × (0, 0, 1)`` normalised when n is parallel to x; ``t2 = n × t1``.
    """
    normals = np.asarray(normals, dtype=float)
    n_x, n_y, n_z = normals[:, 0], normals[:, 1], normals[:, 2]
    zeros = np.zeros_like(n_x)
    # n × (1, 0, 0) = (0, n_z, −n_y); n × (0, 0, 1) = (n_y, −n_x, 0).
    t1 = np.stack((zeros, n_z, -n_y), axis=1)
    length = np.hypot(n_y, n_z)
    parallel_to_x = length < _PARALLEL_TO_X_TOLERANCE
    if np.any(parallel_to_x):
        t1[parallel_to_x] = np.stack((n_y, -n_x, zeros), axis=1)[parallel_to_x]
        length = np.where(parallel_to_x, np.hypot(n_x, n_y), length)
    t1 /= length[:, np.newaxis]
    t2 = np.cross(normals, t1)
    return t1, t2


def friction_cone_edges(normals, mu, num_edges: int = 8) -> np.ndarray:
    """Edges of the linearised friction cones, normal component 1 (not unit length).

    Args:
        normals: (N, 3) unit contact normals (dimensionless), pointing into the object. Not
            checked or normalised here; use :func:`primitive_wrenches` for checked input.
        mu: Friction coefficient (dimensionless), a scalar or one per contact, shape (N,).
        num_edges: Number m of edges per cone.

    Returns:
        (N, m, 3) array; ``[i, j]`` is ``n_i + μ_i (cos θ_j t1_i + sin θ_j t2_i)``, θ_j = 2πj/m.
    """
    normals = np.asarray(normals, dtype=float)
    t1, t2 = contact_tangent_frames(normals)
    angles = 2.0 * np.pi * np.arange(num_edges) / num_edges
    mu = np.broadcast_to(np.asarray(mu, dtype=float), (len(normals),))
    tangential = (np.cos(angles)[np.newaxis, :, np.newaxis] * t1[:, np.newaxis, :]
                  + np.sin(angles)[np.newaxis, :, np.newaxis] * t2[:, np.newaxis, :])
    return normals[:, np.newaxis, :] + mu[:, np.newaxis, np.newaxis] * tangential


def primitive_wrenches(points, normals, mu, center, torque_scale, num_edges: int = 8) -> np.ndarray:
    """Primitive wrenches of a grasp: one per friction-cone edge per contact.

    Args:
        points: (N, 3) contact points (metres), in any frame shared with ``normals`` and ``center``.
        normals: (N, 3) contact normals pointing into the object (dimensionless); normalised here,
            so they need not be exactly unit length, but must not be zero.
        mu: Friction coefficient (dimensionless, ≥ 0), a scalar or one per contact, shape (N,).
        center: (3,) point the torques are taken about (metres), the object's centre of mass.
        torque_scale: ρ (metres, > 0); torques are divided by it. GraspIt! uses the largest
            distance from the centre of mass to the object's surface.
        num_edges: Number m ≥ 3 of edges of each linearised friction cone.

    Returns:
        (N·m, 6) array, contact-major (row ``i·m + j`` is edge j of contact i; reshape to
        (N, m, 6) to group by contact); each row is ``[f_ij ; (p_i − c) × f_ij / ρ]``,
        dimensionless.

    Raises:
        ValueError: If any input is non-finite, mis-shaped or out of range (message says which).
    """
    points, normals, mu, center, torque_scale, num_edges = _validated(
        points, normals, mu, center, torque_scale, num_edges)
    return _primitive_wrenches(points, normals, mu, center, torque_scale, num_edges)


def wrench_space_quality(wrenches) -> GraspQuality:
    """ε and volume of the convex hull of given wrenches, in any dimension d ≥ 1.

    Use it for variants of the metric (e.g. the force-only 3-D wrench space with per-contact scaled
    cones of the contact-quality energy, docs/design.md §4.6); :func:`grasp_quality` builds the wrenches for
    the standard 6-D case.

    Args:
        wrenches: (K, d) primitive wrenches (any consistent units; ε comes out in the same units).

    Returns:
        GraspQuality with ε = distance from the origin to the nearest hull facet if the origin is
        strictly inside the hull, else 0, and the hull's d-dimensional volume. Both are 0 when the
        wrenches span fewer than d dimensions (fewer than d + 1 affinely independent wrenches).

    Raises:
        ValueError: If ``wrenches`` is not a finite 2-D array.
    """
    wrenches = np.asarray(wrenches, dtype=float)
    if wrenches.ndim != 2:
        raise ValueError(f"wrenches must be a 2-D array (K, d), got shape {wrenches.shape}")
    if not np.isfinite(wrenches).all():
        raise ValueError("wrenches contain NaN or inf")
    return _hull_quality(wrenches)


def grasp_quality(points, normals, mu, center, torque_scale, num_edges: int = 8) -> GraspQuality:
    """ε (Ferrari–Canny, L1) and volume of a grasp's wrench space, docs/design.md §4.5.

    Args:
        points: (N, 3) contact points (metres), in any frame shared with ``normals`` and ``center``.
            N = 0 (shape (0, 3) or an empty sequence) gives ε = volume = 0.
        normals: (N, 3) contact normals pointing into the object (dimensionless); normalised here,
            so they need not be exactly unit length, but must not be zero.
        mu: Friction coefficient (dimensionless, ≥ 0), a scalar or one per contact, shape (N,).
        center: (3,) point the torques are taken about (metres), the object's centre of mass.
        torque_scale: ρ (metres, > 0); torques are divided by it. GraspIt! uses the largest
            distance from the centre of mass to the object's surface.
        num_edges: Number m ≥ 3 of edges of each linearised friction cone (GraspIt!: 8).

    Returns:
        GraspQuality(epsilon, volume), both dimensionless; 0 and 0 for a degenerate GWS.

    Raises:
        ValueError: If any input is non-finite, mis-shaped or out of range (message says which).
    """
    points, normals, mu, center, torque_scale, num_edges = _validated(
        points, normals, mu, center, torque_scale, num_edges)
    if len(points) == 0:
        return GraspQuality(epsilon=0.0, volume=0.0)
    return _hull_quality(
        _primitive_wrenches(points, normals, mu, center, torque_scale, num_edges))


def epsilon_l1(points, normals, mu, center, torque_scale, num_edges: int = 8) -> float:
    """The ε metric of a grasp (Ferrari–Canny over the L1 grasp wrench space), docs/design.md §4.5.

    Same arguments as :func:`grasp_quality`, which also returns the hull volume.

    Args:
        points: (N, 3) contact points (metres).
        normals: (N, 3) contact normals pointing into the object (dimensionless, nonzero).
        mu: Friction coefficient (dimensionless, ≥ 0), scalar or shape (N,).
        center: (3,) centre of mass (metres), the point torques are taken about.
        torque_scale: ρ (metres, > 0) dividing the torques.
        num_edges: Number m ≥ 3 of edges per linearised friction cone.

    Returns:
        ε ≥ 0 (dimensionless); 0 if the grasp is not force-closure or its GWS is degenerate.

    Raises:
        ValueError: If any input is non-finite, mis-shaped or out of range (message says which).
    """
    return grasp_quality(points, normals, mu, center, torque_scale, num_edges).epsilon


def _primitive_wrenches(points, unit_normals, mu, center, torque_scale, num_edges) -> np.ndarray:
    """Unchecked core of :func:`primitive_wrenches` (normals already unit)."""
    forces = friction_cone_edges(unit_normals, mu, num_edges)           # (N, m, 3)
    lever_arms = (points - center) / torque_scale                         # (N, 3)
    torques = np.cross(lever_arms[:, np.newaxis, :], forces)              # (N, m, 3)
    return np.concatenate((forces, torques), axis=2).reshape(-1, 6)


def _hull_quality(wrenches: np.ndarray) -> GraspQuality:
    """ε and volume of conv(wrenches); wrenches already checked finite, shape (K, d)."""
    num_wrenches, dimension = wrenches.shape
    if num_wrenches < dimension + 1:
        return GraspQuality(epsilon=0.0, volume=0.0)
    scale = float(np.sqrt(np.max(np.einsum("ij,ij->i", wrenches, wrenches))))
    if scale == 0.0:
        return GraspQuality(epsilon=0.0, volume=0.0)
    # Flat wrench sets (e.g. two point contacts) span < d dimensions: settle them here rather than
    # through qhull's precision errors, which also makes nearly-flat sets deterministic.
    singular_values = np.linalg.svd(wrenches - wrenches.mean(axis=0), compute_uv=False)
    if singular_values[dimension - 1] <= _FLATNESS_TOLERANCE * scale:
        return GraspQuality(epsilon=0.0, volume=0.0)
    try:
        hull = ConvexHull(wrenches)
    except QhullError:
        # A precision error on a set that is not flat: joggling the input always yields a hull,
        # exact to ~1e-10 (see the module docstring).
        try:
            hull = ConvexHull(wrenches, qhull_options=_FALLBACK_QHULL_OPTIONS)
        except QhullError:
            return GraspQuality(epsilon=0.0, volume=0.0)
    offsets = hull.equations[:, -1]
    # Inside is normal·x + offset ≤ 0 with unit normals: the origin is strictly inside iff every
    # offset is negative, and its distance to facet k is −offset_k.
    largest_offset = float(offsets.max())
    epsilon = -largest_offset if largest_offset < -_INTERIOR_TOLERANCE * scale else 0.0
    return GraspQuality(epsilon=epsilon, volume=float(hull.volume))


def _validated(points, normals, mu, center, torque_scale, num_edges):
    """Checks and converts the inputs of the grasp functions; normalises the normals.

    Returns:
        (points (N, 3), unit normals (N, 3), mu (scalar or (N,)), center (3,), torque_scale,
        num_edges), as float arrays / Python numbers.

    Raises:
        ValueError: Naming the offending argument and what is wrong with it.
    """
    points = _as_contact_array(points, "points")
    normals = _as_contact_array(normals, "normals")
    if normals.shape != points.shape:
        raise ValueError(
            f"normals must have the same shape as points, got normals {normals.shape} and points "
            f"{points.shape}")

    mu = np.asarray(mu, dtype=float)
    if mu.ndim == 0:
        mu_description = f"{float(mu)}"
    elif mu.shape == (len(points),):
        mu_description = f"{mu.tolist()}"
    else:
        raise ValueError(
            f"mu must be a scalar or have shape ({len(points)},) (one per contact), got shape "
            f"{mu.shape}")
    if not np.isfinite(mu).all():
        raise ValueError(f"mu must be finite, got {mu_description}")
    if (mu < 0.0).any():
        raise ValueError(f"mu must be >= 0, got {mu_description}")

    center = np.asarray(center, dtype=float)
    if center.shape != (3,):
        raise ValueError(f"center must have shape (3,), got shape {center.shape}")
    if not np.isfinite(center).all():
        raise ValueError(f"center contains NaN or inf: {center.tolist()}")

    if isinstance(torque_scale, bool) or not isinstance(torque_scale, numbers.Real):
        raise ValueError(f"torque_scale must be a real number (metres), got {torque_scale!r}")
    torque_scale = float(torque_scale)
    if not np.isfinite(torque_scale) or torque_scale <= 0.0:
        raise ValueError(f"torque_scale must be finite and > 0 (metres), got {torque_scale}")

    if isinstance(num_edges, bool) or not isinstance(num_edges, numbers.Integral):
        raise ValueError(f"num_edges must be an integer >= 3, got {num_edges!r}")
    num_edges = int(num_edges)
    if num_edges < 3:
        raise ValueError(f"num_edges must be an integer >= 3, got {num_edges}")

    lengths = np.sqrt(np.einsum("ij,ij->i", normals, normals))
    too_short = np.flatnonzero(lengths < _MIN_NORMAL_LENGTH)
    if too_short.size:
        raise ValueError(
            f"normals must be nonzero: normal {int(too_short[0])} has length "
            f"{lengths[too_short[0]]:.3g} (< {_MIN_NORMAL_LENGTH:g})")
    return points, normals / lengths[:, np.newaxis], mu, center, torque_scale, num_edges


def _as_contact_array(values, name: str) -> np.ndarray:
    """``values`` as a finite (N, 3) float array; an empty sequence gives shape (0, 3)."""
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be an (N, 3) array of numbers ({error})") from None
    if array.ndim == 1 and array.size == 0:
        return array.reshape(0, 3)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"{name} must have shape (N, 3), got shape {array.shape}")
    if not np.isfinite(array).all():
        bad_row = int(np.flatnonzero(~np.isfinite(array).all(axis=1))[0])
        raise ValueError(f"{name} contain NaN or inf (row {bad_row}: {array[bad_row].tolist()})")
    return array
