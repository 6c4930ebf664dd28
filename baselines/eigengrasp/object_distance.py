"""Signed distance and closest-point direction from query points to an object's primitive pieces.

The contact energy (docs/design.md §4.6) needs, for each of the 19 virtual contacts, the vector to the
closest point of the object. For the primitive pieces our objects are built of (sphere, box,
cylinder, capsule; objects.py) the closest point has a closed form, evaluated here in numpy for
all contacts and all pieces of a kind at once (the planner's inner loop). Convex mesh pieces are
handled all together too, exactly (``ConvexPiecesDistance``, convex_distance.py; imported here too).
Ellipsoids are left to Drake's exact pair queries (scene.py).

Conventions: points, distances in metres, in the object frame O. For each point the result is the
signed distance to the union of the pieces (negative inside) and the unit outward gradient of that
distance (for a point outside, the direction from the closest surface point to the point).

Pure numpy, no Drake.
"""

from __future__ import annotations

import numpy as np

from baselines.eigengrasp.convex_distance import ConvexPiecesDistance
from drake_grasp.objects import ShapePiece

__all__ = ["ANALYTIC_KINDS", "ConvexPiecesDistance", "PrimitiveDistance"]  # ConvexPiecesDistance: its old home

ANALYTIC_KINDS = ("sphere", "box", "cylinder", "capsule")
"""Piece kinds handled here; the others need a geometry engine."""

_TINY = 1e-12


class PrimitiveDistance:
    """Distances from points to the union of an object's analytic pieces.

    Build once per object (it caches the pieces' poses and sizes as arrays); call with the points.
    """

    def __init__(self, pieces: tuple[ShapePiece, ...] | list[ShapePiece]):
        """
        Args:
            pieces: Object pieces posed in O; those whose kind is not in ``ANALYTIC_KINDS`` are
                ignored (see ``skipped``).
        """
        self.skipped = [p for p in pieces if p.kind not in ANALYTIC_KINDS]
        self._groups = []
        for kind in ANALYTIC_KINDS:
            group = [p for p in pieces if p.kind == kind]
            if not group:
                continue
            R_OP = np.array([p.X_OP.rotation().matrix() for p in group])  # (M, 3, 3)
            p_OP = np.array([p.X_OP.translation() for p in group])  # (M, 3)
            size = np.array([p.size for p in group], dtype=float)  # (M, k)
            identity = bool(np.allclose(R_OP, np.eye(3)))
            self._groups.append((kind, R_OP, p_OP[:, None, :], size, identity))

    @property
    def num_pieces(self) -> int:
        """Number of analytic pieces handled."""
        return sum(len(g[1]) for g in self._groups)

    def __call__(self, points_O: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Signed distances and outward unit gradients at the points.

        Args:
            points_O: (N, 3) query points in O, m.

        Returns:
            (distance (N,) m, gradient (N, 3) unit), of the union of the analytic pieces (the
            closest piece per point). With no analytic piece: +inf distances and zero gradients.
        """
        best_d, best_g = None, None
        for kind, R_OP, p_OP, size, identity in self._groups:
            q = points_O[None, :, :] - p_OP  # (M, N, 3), still expressed in O
            if not identity:
                q = np.einsum("mni,mij->mnj", q, R_OP)  # expressed in the piece frames
            d, g = _DISTANCE[kind](q, size)
            if not identity:
                g = np.einsum("mnj,mij->mni", g, R_OP)
            if len(d) > 1:
                i = np.argmin(d, axis=0)
                cols = np.arange(d.shape[1])
                d, g = d[i, cols], g[i, cols]
            else:
                d, g = d[0], g[0]
            if best_d is None:
                best_d, best_g = d, g
            else:
                closer = d < best_d
                best_d = np.where(closer, d, best_d)
                best_g = np.where(closer[:, None], g, best_g)
        if best_d is None:
            n = len(points_O)
            return np.full(n, np.inf), np.zeros((n, 3))
        return best_d, best_g


def _sphere(q, size):
    length = np.sqrt(np.einsum("mni,mni->mn", q, q))
    d = length - size[:, 0:1]
    safe = np.maximum(length, _TINY)[..., None]
    g = q / safe
    if np.any(length < _TINY):
        g[length < _TINY] = (0.0, 0.0, 1.0)
    return d, g


def _box(q, size):
    half = 0.5 * size[:, None, :]  # (M, 1, 3)
    a = np.abs(q) - half
    out = np.maximum(a, 0.0)
    out_len = np.sqrt(np.einsum("mni,mni->mn", out, out))
    if out_len.min() > 0.0:  # every point outside
        return out_len, np.copysign(out, q) / out_len[..., None]
    sign = np.where(q < 0.0, -1.0, 1.0)
    inside = out_len <= 0.0
    a_max = a.max(axis=-1)
    d = out_len + np.minimum(a_max, 0.0)
    g = sign * out / np.maximum(out_len, _TINY)[..., None]
    axis = np.argmax(a, axis=-1)
    face = np.zeros_like(q)
    np.put_along_axis(face, axis[..., None], 1.0, axis=-1)
    g = np.where(inside[..., None], face * sign, g)
    return d, g


def _planar_box(rho, z_abs, radius, half_length):
    """2-D box distance in (radial, axial) coordinates; returns d, g_rho, g_z (g_z for |z|)."""
    a_r = rho - radius
    a_z = z_abs - half_length
    o_r, o_z = np.maximum(a_r, 0.0), np.maximum(a_z, 0.0)
    out_len = np.hypot(o_r, o_z)
    inside = out_len <= 0.0
    d = out_len + np.minimum(np.maximum(a_r, a_z), 0.0)
    safe = np.maximum(out_len, _TINY)
    g_r, g_z = o_r / safe, o_z / safe
    if inside.any():
        radial_face = a_r >= a_z
        g_r = np.where(inside, radial_face.astype(float), g_r)
        g_z = np.where(inside, 1.0 - radial_face, g_z)
    return d, g_r, g_z


def _cylinder(q, size):
    x, y, z = q[..., 0], q[..., 1], q[..., 2]
    rho = np.sqrt(x * x + y * y)
    radius, half_length = size[:, 0:1], 0.5 * size[:, 1:2]
    o_r = np.maximum(rho - radius, 0.0)
    o_z = np.maximum(np.abs(z) - half_length, 0.0)
    out_len = np.sqrt(o_r * o_r + o_z * o_z)
    if out_len.min() > 0.0 and rho.min() > _TINY:  # every point outside and off the axis
        g = np.empty_like(q)
        radial = o_r / (out_len * rho)
        g[..., 0] = x * radial
        g[..., 1] = y * radial
        g[..., 2] = np.copysign(o_z / out_len, z)
        return out_len, g
    d, g_r, g_z = _planar_box(rho, np.abs(z), radius, half_length)
    safe = np.maximum(rho, _TINY)
    e_x = np.where(rho < _TINY, 1.0, x / safe)
    e_y = np.where(rho < _TINY, 0.0, y / safe)
    g = np.stack([g_r * e_x, g_r * e_y, g_z * np.where(z < 0.0, -1.0, 1.0)], axis=-1)
    return d, g


def _capsule(q, size):
    half_length = 0.5 * size[:, 1:2]
    z_axis = np.clip(q[..., 2], -half_length, half_length)
    v = q.copy()
    v[..., 2] -= z_axis
    length = np.sqrt(np.einsum("mni,mni->mn", v, v))
    d = length - size[:, 0:1]
    g = v / np.maximum(length, _TINY)[..., None]
    if np.any(length < _TINY):
        g[length < _TINY] = (1.0, 0.0, 0.0)
    return d, g


_DISTANCE = {"sphere": _sphere, "box": _box, "cylinder": _cylinder, "capsule": _capsule}
