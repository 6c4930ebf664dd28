"""Signed distance and closest-point direction from query points to an object's primitive pieces.

The contact energy (docs/design.md §4.6) needs, for each of the 19 virtual contacts, the vector to the
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
from scipy.spatial import ConvexHull

from drake_grasp.objects import ShapePiece

ANALYTIC_KINDS = ("sphere", "box", "cylinder", "capsule")
"""Piece kinds handled here; the others need a geometry engine."""

_TINY = 1e-12
_SLACK = 1e-9  # m, on the upper bound of a distance, for its rounding
_MAX_DEGREE = 5  # adjacent facets of a vertex tried first (about the median count)


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
    to a common facet count; the pieces' facets and vertices are stacked so that one matrix product
    gives every point's plane distances to every facet and squared distances to every vertex. Per
    (point, piece), the plane distance s = max_f (n_f · q + c_f) is the exact signed distance for a
    point inside, and a lower bound outside; the nearest vertex of all pieces bounds the distance of
    a point from above. A point outside every piece then only needs the pieces whose lower bound is
    within that bound (usually one to three), and for each:

    1. the closest point x of a few of its triangles: the maximising facet and the facets around
       the piece's nearest vertex (each triangle's closest point: the projection onto its plane when
       that lies in the triangle, else the closest point of its three edges), accepted when
       (q − x) · (v − x) ≤ 0 for every hull vertex v (the optimality condition of a projection onto
       a convex set); this settles almost every pair;
    2. otherwise, unless the others' distances rule the piece out, the closest of the closest
       points of all its facets visible from q (s_f > 0) whose plane is no farther than the bound
       (one of them holds the piece's closest point).

    The union's distance is the smallest over the pieces (inside a piece: the most negative). The
    work is a fixed number of array operations on all points and pieces together, whatever their
    count (the planner calls this once per annealing step with the 19 virtual contacts).
    """

    def __init__(self, pieces: tuple[ShapePiece, ...] | list[ShapePiece], tolerance: float = 1e-9):
        """
        Args:
            pieces: "convex" pieces (each its mesh_path's vertices, posed by X_OP).
            tolerance: Slack of the in-triangle and optimality tests, m.
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
        F = max(len(h.simplices) for h in hulls)
        V = max(len(h.vertices) for h in hulls)
        P = len(hulls)
        # Padding facets have offset −inf: never the maximising one, never visible.
        normals = np.zeros((P, F, 3))
        offsets = np.full((P, F), -np.inf)
        triangles = np.zeros((P, F, 3, 3))
        # Padding vertices repeat a real one, which changes no minimum or maximum over them.
        self._vertices = np.empty((P, V, 3))
        # Each vertex's adjacent facets (at most _MAX_DEGREE of them), as stacked facet rows
        # p F + f, padded by repeating one.
        self._vertex_facet_rows = np.empty((P, V, _MAX_DEGREE), dtype=np.intp)
        for p, hull in enumerate(hulls):
            count = len(hull.simplices)
            normals[p, :count] = hull.equations[:, :3]
            offsets[p, :count] = hull.equations[:, 3]
            triangles[p, :count] = hull.points[hull.simplices]
            triangles[p, count:] = triangles[p, 0]
            real = np.minimum(np.arange(V), len(hull.vertices) - 1)
            self._vertices[p] = hull.points[hull.vertices][real]
            for j, v in enumerate(hull.vertices[real]):
                adjacent = np.flatnonzero((hull.simplices == v).any(axis=1))
                self._vertex_facet_rows[p, j] = p * F + adjacent[np.minimum(np.arange(_MAX_DEGREE), len(adjacent) - 1)]
        # In-plane outward normals of each facet's three edges, and their offsets.
        edges = np.roll(triangles, -1, axis=2) - triangles
        edge_normals = np.cross(edges, normals[:, :, None, :])
        opposite = np.roll(triangles, -2, axis=2)
        flip = np.einsum("pfej,pfej->pfe", opposite - triangles, edge_normals) > 0.0
        edge_normals[flip] *= -1.0
        edge_normals /= np.maximum(np.linalg.norm(edge_normals, axis=3, keepdims=True), _TINY)
        edge_offsets = np.einsum("pfej,pfej->pfe", edge_normals, triangles) + tolerance
        edge_lengths_sq = np.maximum(np.einsum("pfej,pfej->pfe", edges, edges), _TINY)
        self._shape = (P, F, V)
        self._tolerance = tolerance
        self._normals = normals.reshape(-1, 3)  # (P F, 3): facet p F + f
        # One matrix product for all planes and vertices: q · n_f + c_f and −2 q · v + |v|².
        vertex_rows = self._vertices.reshape(-1, 3)
        self._rows_T = np.ascontiguousarray(np.concatenate([self._normals, -2.0 * vertex_rows]).T)
        self._row_offsets = np.concatenate([offsets.reshape(-1), np.einsum("vj,vj->v", vertex_rows, vertex_rows)])
        # Per facet, in one table gathered by facet row: its edges' in-plane normals, edge vectors
        # and start vertices (9 rows of 3), for one product with the points.
        self._facet_rows = np.concatenate([edge_normals, edges, triangles], axis=2).reshape(P * F, 9, 3)
        # and the scalars that go with them: edge offsets, a·e, |e|², |a|² (4 × 3).
        a_dot_e = np.einsum("pfej,pfej->pfe", triangles, edges)
        self._facet_scalars = np.concatenate([edge_offsets, a_dot_e, edge_lengths_sq,
                                              np.einsum("pfej,pfej->pfe", triangles, triangles)],
                                             axis=2).reshape(P * F, 12)

    @property
    def num_pieces(self) -> int:
        return self._shape[0]

    def __call__(self, points_O: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Signed distances and outward unit gradients at the points.

        Args:
            points_O: (N, 3) query points in O, m.

        Returns:
            (distance (N,) m, gradient (N, 3) unit, in O) of the union of the pieces.
        """
        q = np.asarray(points_O, dtype=float)
        N, (P, F, V) = len(q), self._shape
        products = q @ self._rows_T + self._row_offsets
        s = products[:, :P * F]  # (N, P F): every plane distance
        lower = s.reshape(N, P, F).max(axis=2)  # (N, P): exact inside a piece, a lower bound outside
        d = lower.min(axis=1)
        outside = d > 0.0
        if not outside.any():  # every point inside a piece: the most negative plane distance
            return d, self._inside_gradients(s, lower.argmin(axis=1))
        # |v|² − 2 q·v per vertex; + |q|², the squared distances. The nearest vertex of all pieces
        # bounds the distance of a point from above (with slack for the rounding of this form).
        q_sq = np.einsum("nj,nj->n", q, q)
        vertex_terms = products[:, P * F:].reshape(N, P, V)
        upper = np.sqrt(np.maximum(vertex_terms.min(axis=(1, 2)) + q_sq, 0.0)) + _SLACK
        # The (point, piece) pairs that may hold the closest point of a point outside every piece.
        n_k, p_k = np.nonzero((lower <= upper[:, None]) & outside[:, None])
        K = len(n_k)
        # 1. A few facets per pair: the maximising one, and those around the nearest vertex.
        s_k = s.reshape(N, P, F)[n_k, p_k]  # (K, F)
        nearest = vertex_terms[n_k, p_k].argmin(axis=1)
        rows = np.concatenate([(p_k * F + s_k.argmax(axis=1))[:, None], self._vertex_facet_rows[p_k, nearest]],
                              axis=1)
        pair_d, u = self._closest_of_facets(q, q_sq, s, n_k, rows.ravel(), rows.shape[1])
        # Exact where max_v u · v ≤ u · x, u = q − x: one product with all vertices, this piece's.
        support = (u @ self._rows_T[:, P * F:]).reshape(K, P, V)[np.arange(K), p_k].min(axis=1) * -0.5
        exact = support - np.einsum("kj,kj->k", q[n_k] - u, u) <= self._tolerance * pair_d
        # 2. The others, unless the pairs' distances (upper bounds) rule their piece out.
        best = np.full(N, np.inf)
        np.minimum.at(best, n_k, pair_d)
        todo = np.flatnonzero(~exact & (lower[n_k, p_k] <= best[n_k]))
        if len(todo):
            visible = s_k[todo]
            t, f = np.nonzero((visible > 0.0) & (visible <= best[n_k[todo]][:, None] + _SLACK))
            d_t, u_t = self._closest_of_facets(q, q_sq, s, n_k[todo], p_k[todo][t] * F + f, None, t)
            pair_d[todo], u[todo] = d_t, u_t
        # Per point, the closest pair; inside a piece, its plane distance.
        d_np = np.where(outside[:, None], np.inf, lower)
        d_np[n_k, p_k] = pair_d
        closest = np.argmin(d_np, axis=1)
        d = d_np[np.arange(N), closest]
        if outside.all():
            pair = np.empty((N, P), dtype=np.intp)
            pair[n_k, p_k] = np.arange(K)
            return d, u[pair[np.arange(N), closest]] / d[:, None]
        g = self._inside_gradients(s, closest)
        i = np.flatnonzero(outside)
        pair = np.empty((N, P), dtype=np.intp)
        pair[n_k, p_k] = np.arange(K)
        g[i] = u[pair[i, closest[i]]] / d[i][:, None]
        return d, g

    def _inside_gradients(self, s, piece):
        """The normal of each point's `piece`'s maximising facet (the gradient inside it)."""
        N, (P, F, _) = len(s), self._shape
        return self._normals[piece * F + s.reshape(N, P, F)[np.arange(N), piece].argmax(axis=1)]

    def _closest_of_facets(self, q, q_sq, s, n, rows, per_pair, pair=None):
        """Per pair, the closest of some facets' closest points to the pair's point.

        Args:
            q: (N, 3) points; q_sq: (N,) |q|²; s: (N, P F) their plane distances.
            n: (K,) each pair's point.
            rows: (M,) facet rows; with `per_pair` D: D consecutive rows per pair, else `pair`
                (M,) says each row's pair.

        Returns:
            (distance (K,), u = q − x (K, 3)) for the closest point x of the pair's facets with
            s > 0 (+inf and an arbitrary u where there is none).
        """
        K = len(n)
        if per_pair is not None:
            pair = np.repeat(np.arange(K), per_pair)
        points = n[pair]
        s_m = s[points, rows]
        qm = q[points]
        # Per triangle: its edge planes (in the triangle when q · m_e ≤ c_e for all three), and
        # per edge the parameter t of its closest point a + t e and the squared distance
        # |q − a|² − t (2 (q − a)·e − t |e|²), in expanded form to pick the closest, recomputed
        # directly for the winner below.
        dots = np.einsum("mkj,mj->mk", self._facet_rows[rows], qm)  # (M, 9): q·m_e, q·e, q·a
        scalars = self._facet_scalars[rows]
        in_triangle = np.all(dots[:, 0:3] <= scalars[:, 0:3], axis=1)
        along = dots[:, 3:6] - scalars[:, 3:6]  # (q − a)·e
        t = np.clip(along / scalars[:, 6:9], 0.0, 1.0)
        dist_sq = q_sq[points][:, None] - 2.0 * dots[:, 6:9] + scalars[:, 9:12] - t * (2.0 * along - t * scalars[:, 6:9])
        e = np.argmin(dist_sq, axis=1)
        m = np.arange(len(rows))
        dist = np.where(in_triangle, s_m, np.sqrt(np.maximum(dist_sq[m, e], 0.0)))
        dist[s_m <= 0.0] = np.inf
        if per_pair is not None:
            first = np.argmin(dist.reshape(K, per_pair), axis=1) + np.arange(0, K * per_pair, per_pair)
            found = slice(None)
        else:  # sort the rows by (pair, distance), keep each pair's first
            order = np.lexsort((dist, pair))
            first = order[np.flatnonzero(np.r_[True, pair[order[1:]] != pair[order[:-1]]])]
            found = pair[first]
        # The winner's u = q − x: along the normal in the triangle, else from its edge's closest
        # point, recomputed directly.
        row, edge = rows[first], e[first]
        table = self._facet_rows[row]  # (W, 9, 3)
        w_k = np.arange(len(first))
        vector = table[w_k, 3 + edge]
        offset = qm[first] - table[w_k, 6 + edge]
        t_k = np.clip(np.einsum("kj,kj->k", offset, vector) / self._facet_scalars[row, 6 + edge], 0.0, 1.0)
        offset -= t_k[:, None] * vector
        inside, s_w = in_triangle[first], s_m[first]
        out_d, out_u = np.full(K, np.inf), np.ones((K, 3))
        out_d[found] = np.where(np.isinf(dist[first]), np.inf,
                                np.where(inside, s_w, np.sqrt(np.einsum("kj,kj->k", offset, offset))))
        out_u[found] = np.where(inside[:, None], s_w[:, None] * self._normals[row], offset)
        return out_d, out_u


_DISTANCE = {"sphere": _sphere, "box": _box, "cylinder": _cylinder, "capsule": _capsule}
