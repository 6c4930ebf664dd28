"""Signed distance and closest-point direction from query points to an object's primitive pieces.

The contact energy (DESIGN.md §7) needs, for each of the 19 virtual contacts, the vector to the
closest point of the object. For the primitive pieces our objects are built of (sphere, box,
cylinder, capsule; objects.py) the closest point has a closed form, evaluated here in numpy for
all contacts and all pieces of a kind at once (the planner's inner loop). Convex mesh pieces are
handled all together too, exactly, from their hulls' planes (``ConvexPiecesDistance``). Ellipsoids
are left to Drake's exact pair queries (scene.py).

Conventions: points, distances in metres, in the object frame O. For each point the result is the
signed distance to the union of the pieces (negative inside) and the unit outward gradient of that
distance (for a point outside, the direction from the closest surface point to the point).

Pure numpy, no Drake.
"""

from __future__ import annotations

import numpy as np
import trimesh
import trimesh.triangles
from scipy.spatial import ConvexHull

from drake_grasp.objects import ShapePiece

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


class ConvexPiecesDistance:
    """Exact distances from points to the union of an object's convex mesh pieces, all at once.

    Each piece's hull is a set of planes n_f · x + c_f ≤ 0 (unit n_f), expressed in O once, padded
    to a common facet count so that one array product gives every point's plane distances to every
    piece. Per (point, piece), the plane distance s = max_f (n_f · q + c_f) is the exact signed
    distance for a point inside, and for a point outside whose projection q − s n_f onto the
    maximising facet's plane lies in that facet; in general it is a lower bound. Pieces are then
    culled: a piece whose lower bound is not below the point's smallest exact distance, or above the
    distance to the nearest vertex of any piece, cannot be the closest. The others get exact
    distances, cheap tests first, culling again between them:

    1. the closest point x of the maximising facet's boundary (an edge or a vertex), accepted when
       (q − x) · (v − x) ≤ 0 for every hull vertex v (the optimality condition of a projection onto
       a convex set); this settles most pairs;
    2. the piece's nearest vertex w, accepted by the same test (often the answer for a far point
       near a corner that is not on the maximising facet);
    3. the closest of the closest points of the facets visible from q (s_f > 0), one of which holds
       the piece's closest point (trimesh's point-triangle projection), skipping those whose
       bounding sphere is farther than the piece's nearest vertex.

    The union's distance is the smallest over the pieces (inside a piece: the most negative).
    """

    def __init__(self, pieces: tuple[ShapePiece, ...] | list[ShapePiece], tolerance: float = 1e-9):
        """
        Args:
            pieces: "convex" pieces (each its mesh_path's vertices, posed by X_OP).
            tolerance: Slack of the in-facet and optimality tests, m.
        """
        hulls = []
        for piece in pieces:
            if piece.kind != "convex":
                raise ValueError(f"expected convex pieces, got a {piece.kind}")
            vertices_P = np.asarray(trimesh.load(piece.mesh_path, force="mesh", process=False).vertices, dtype=float)
            X_OP = piece.X_OP
            hulls.append(ConvexHull(vertices_P @ X_OP.rotation().matrix().T + X_OP.translation()))
        if not hulls:
            raise ValueError("no convex piece")
        num_facets = max(len(h.simplices) for h in hulls)
        num_vertices = max(len(h.vertices) for h in hulls)
        P = len(hulls)
        # Padding facets have offset −inf: never the maximising one, never visible.
        self._normals = np.zeros((P, num_facets, 3))
        self._offsets = np.full((P, num_facets), -np.inf)
        self._triangles = np.zeros((P, num_facets, 3, 3))
        # Padding vertices repeat a real one, which changes no maximum over the vertices.
        self._vertices = np.empty((P, num_vertices, 3))
        for p, hull in enumerate(hulls):
            F = len(hull.simplices)
            self._normals[p, :F] = hull.equations[:, :3]
            self._offsets[p, :F] = hull.equations[:, 3]
            self._triangles[p, :F] = hull.points[hull.simplices]
            self._triangles[p, F:] = self._triangles[p, 0]
            vertices = hull.points[hull.vertices]
            self._vertices[p] = vertices[np.minimum(np.arange(num_vertices), len(vertices) - 1)]
        # In-plane outward normals of each facet's three edges, and their offsets.
        triangles = self._triangles
        edges = np.roll(triangles, -1, axis=2) - triangles
        edge_normals = np.cross(edges, self._normals[:, :, None, :])
        opposite = np.roll(triangles, -2, axis=2)
        flip = np.einsum("pfej,pfej->pfe", opposite - triangles, edge_normals) > 0.0
        edge_normals[flip] *= -1.0
        edge_normals /= np.maximum(np.linalg.norm(edge_normals, axis=3, keepdims=True), _TINY)
        self._edge_normals = edge_normals
        self._edge_offsets = np.einsum("pfej,pfej->pfe", edge_normals, triangles) + tolerance
        self._edges = edges
        self._edge_lengths_sq = np.maximum(np.einsum("pfej,pfej->pfe", edges, edges), _TINY)
        self._tolerance = tolerance
        self._facet_centres = triangles.mean(axis=2)  # (P, F, 3)
        self._facet_radii = np.linalg.norm(triangles - self._facet_centres[:, :, None, :], axis=3).max(axis=2)
        self._normals_rows = self._normals.reshape(-1, 3)  # (P F, 3), for one matrix product
        self._vertex_rows = self._vertices.reshape(-1, 3)  # (P V, 3)
        self._vertex_sq = np.einsum("vj,vj->v", self._vertex_rows, self._vertex_rows)

    @property
    def num_pieces(self) -> int:
        return len(self._normals)

    def __call__(self, points_O: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Signed distances and outward unit gradients at the points.

        Args:
            points_O: (N, 3) query points in O, m.

        Returns:
            (distance (N,) m, gradient (N, 3) unit, in O) of the union of the pieces.
        """
        q = np.asarray(points_O, dtype=float)
        N, (P, F) = len(q), self._offsets.shape
        s = (q @ self._normals_rows.T).reshape(N, P, F) + self._offsets  # (N, P, F)
        facet = np.argmax(s, axis=2)  # (N, P)
        d = s.max(axis=2)  # (N, P), lower bounds
        piece = np.broadcast_to(np.arange(P), facet.shape)
        g = self._normals[piece, facet]  # (N, P, 3)
        foot = q[:, None, :] - d[..., None] * g
        in_facet = np.all(np.einsum("npej,npj->npe", self._edge_normals[piece, facet], foot)
                          <= self._edge_offsets[piece, facet], axis=2)
        exact = in_facet | (d <= 0.0)
        if not exact.all():
            # Squared distances to every vertex, |q|² − 2 q·v + |v|²: the nearest vertex of a piece
            # bounds the piece's distance from above (and is fallback 2's candidate).
            vertex_dist_sq = ((q @ self._vertex_rows.T) * -2.0 + self._vertex_sq).reshape(N, P, -1)
            vertex_dist_sq += np.einsum("nj,nj->n", q, q)[:, None, None]
            nearest = np.argmin(vertex_dist_sq, axis=2)  # (N, P)
            upper = np.sqrt(np.maximum(vertex_dist_sq.min(axis=(1, 2)), 0.0))  # (N,)
            for fallback in (self._edge_fallback, self._vertex_fallback, self._visible_facets_fallback):
                # Only pieces that may be the closest need the exact distance: not those whose lower
                # bound is at least the smallest exact distance, or above a piece's upper bound.
                best_exact = np.where(exact, d, np.inf).min(axis=1)
                hopeless = ~exact & ((d >= best_exact[:, None]) | (d > upper[:, None]))
                d[hopeless] = np.inf
                exact |= hopeless
                if exact.all():
                    break
                fallback(q, s, facet, nearest, ~exact, d, g, exact)
        closest = np.argmin(d, axis=1)
        rows = np.arange(N)
        return d[rows, closest], g[rows, closest]

    def _vertex_fallback(self, q, s, facet, nearest, todo, d, g, exact) -> None:
        """Fallback 2, in place: the piece's nearest vertex v, where it passes the optimality test."""
        n_k, p_k = np.nonzero(todo)
        vertices = self._vertices[p_k]  # (K, V, 3)
        v = vertices[np.arange(len(n_k)), nearest[n_k, p_k]]
        offset = q[n_k] - v
        lengths = np.sqrt(np.einsum("kj,kj->k", offset, offset))
        worst = np.einsum("kvj,kj->kv", vertices, offset).max(axis=1) - np.einsum("kj,kj->k", v, offset)
        ok = (worst <= self._tolerance * lengths) & (lengths > _TINY)
        n_k, p_k = n_k[ok], p_k[ok]
        d[n_k, p_k] = lengths[ok]
        g[n_k, p_k] = offset[ok] / lengths[ok][:, None]
        exact[n_k, p_k] = True

    def _edge_fallback(self, q, s, facet, nearest, todo, d, g, exact) -> None:
        """Fallback 1, in place: the closest point x of the maximising facet's boundary, where it
        passes the optimality test against every vertex of the piece."""
        n_k, p_k = np.nonzero(todo)
        f_k = facet[n_k, p_k]
        qk = q[n_k]
        triangles, edges = self._triangles[p_k, f_k], self._edges[p_k, f_k]
        lengths_sq = self._edge_lengths_sq[p_k, f_k]
        w = qk[:, None, :] - triangles  # (K, 3 edges, 3)
        t = np.clip(np.einsum("kej,kej->ke", w, edges) / lengths_sq, 0.0, 1.0)
        offset = w - t[..., None] * edges  # from each edge's closest point to q
        dist_sq = np.einsum("kej,kej->ke", offset, offset)
        e = np.argmin(dist_sq, axis=1)
        k = np.arange(len(n_k))
        v = offset[k, e]  # q − x
        x = qk - v
        lengths = np.sqrt(dist_sq[k, e])
        worst = np.einsum("kvj,kj->kv", self._vertices[p_k], v).max(axis=1) - np.einsum("kj,kj->k", x, v)
        ok = worst <= self._tolerance * lengths
        n_k, p_k = n_k[ok], p_k[ok]
        d[n_k, p_k] = lengths[ok]
        g[n_k, p_k] = v[ok] / lengths[ok][:, None]
        exact[n_k, p_k] = True

    def _visible_facets_fallback(self, q, s, facet, nearest, todo, d, g, exact) -> None:
        """Fallback 3, in place: the closest of the closest points of the facets visible from q."""
        n_k, p_k = np.nonzero(todo)
        # A facet whose bounding sphere is farther than the piece's nearest vertex cannot hold the
        # closest point.
        upper = np.linalg.norm(q[n_k] - self._vertices[p_k, nearest[n_k, p_k]], axis=1)
        to_centres = np.linalg.norm(q[n_k, None, :] - self._facet_centres[p_k], axis=2)  # (K, F)
        pair, f = np.nonzero((s[n_k, p_k] > 0.0) & (to_centres - self._facet_radii[p_k] <= upper[:, None]))
        closest = trimesh.triangles.closest_point(self._triangles[p_k[pair], f], q[n_k[pair]])
        v = q[n_k[pair]] - closest
        dist = np.linalg.norm(v, axis=1)
        best = np.full(len(n_k), np.inf)
        np.minimum.at(best, pair, dist)
        winner = np.flatnonzero(dist == best[pair])
        winner = winner[np.unique(pair[winner], return_index=True)[1]]  # one facet per pair
        d[n_k, p_k] = best
        g[n_k[pair[winner]], p_k[pair[winner]]] = v[winner] / np.maximum(dist[winner], _TINY)[:, None]
        exact[n_k, p_k] = True


_DISTANCE = {"sphere": _sphere, "box": _box, "cylinder": _cylinder, "capsule": _capsule}
