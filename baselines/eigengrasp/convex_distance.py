"""Exact signed distances from points to the union of an object's convex mesh pieces.

The planner's contact energy (docs/design.md §4.6) needs, once per annealing step, the distance and
the closest-point direction from each of the 19 virtual contacts to the object; for an object made of
convex mesh pieces (a decomposed user mesh, a catalogue hull) that is this module's job. Each call is
a fixed number of numpy operations on all points and pieces together: on arrays this small the cost
is per operation, not per element, so the count of operations is what the design minimises.

Two paths, both exact:

* the common one (every point outside every piece, as the planner's contacts always are): per
  (point, piece) pair that bounds cannot rule out, test the Voronoi regions of the features around
  the piece's nearest vertex and of its facet of largest plane distance (convex_regions.py); the
  feature whose region holds the point holds its closest point. About 45 numpy calls.
* the general one (the previous algorithm, about 80 calls), for a point inside a piece or a pair
  whose closest feature is none of those (on 3,000 recorded planner calls per object: never on
  generated 9- and 10-piece meshes, 3 times on the spectacle case; then the whole call takes it):
  closest points of a few triangles checked by the projection's optimality condition, then all
  visible facets.

Conventions: points and distances in metres, in the object frame O; for each point the signed
distance to the union of the pieces (negative inside) and the unit outward gradient of that distance
(for a point outside, the direction from the closest surface point to the point).

Pure numpy/scipy, no Drake.
"""

from __future__ import annotations

import numpy as np
import trimesh
from scipy.spatial import ConvexHull

from baselines.eigengrasp.convex_regions import MAX_STAR, REGION_TOLERANCE, region_tables
from drake_grasp.objects import ShapePiece

_TINY = 1e-12
_SLACK = 1e-9  # m, on the upper bound of a distance, for its rounding
_MAX_DEGREE = 5  # adjacent facets of a vertex tried first by the general path (about the median count)


class ConvexPiecesDistance:
    """Exact distances from points to the union of an object's convex mesh pieces, all at once.

    Each piece's hull is a set of planes n_f · x + c_f ≤ 0 (unit n_f), expressed in O once, padded
    to a common facet count; the pieces' facets and vertices are stacked so that one matrix product
    gives every point's plane distances to every facet and squared distances to every vertex. Per
    (point, piece), the plane distance s = max_f (n_f · q + c_f) is the exact signed distance for a
    point inside, and a lower bound outside; the nearest vertex of all pieces bounds the distance of
    a point from above. A point outside every piece then only needs the pieces whose lower bound is
    within that bound (usually one to three). For each such pair:

    0. (``_from_regions``, tried first when every point is outside every piece) the Voronoi regions
       of the piece's features around its nearest vertex and its maximising facet
       (convex_regions.py): the feature whose region holds the point gives the exact closest point.
       When some pair finds none and its lower bound does not rule its piece out, the call takes
       the general path below instead (``_general``), which needs no such luck:
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

    def __init__(self, pieces: tuple[ShapePiece, ...] | list[ShapePiece], tolerance: float = 1e-9,
                 max_star: int = MAX_STAR, compiled: bool = True):
        """
        Args:
            pieces: "convex" pieces (each its mesh_path's vertices, posed by X_OP).
            tolerance: Slack of the general path's in-triangle and optimality tests, m.
            max_star: Most features of a vertex's star the region path tests
                (convex_regions.region_tables); a larger star may leave its pairs to the general path.
            compiled: Run the region path as the compiled loop of convex_kernel.py (same results,
                to rounding); False: the numpy reference below. Either way a call the region path
                cannot settle takes the numpy general path.
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
        self._regions = region_tables(hulls, V, F, REGION_TOLERANCE, max_star)
        self.compiled = compiled
        if compiled:  # numba (~0.4 s to import) only where a mesh needs it
            from baselines.eigengrasp.convex_kernel import region_distances
            self._kernel = region_distances
        # The compiled loop's arguments: plain contiguous float64/int64 arrays.
        tables = self._regions
        centres = self._vertices.mean(axis=1)
        radii = np.linalg.norm(self._vertices - centres[:, None], axis=2).max(axis=1) * (1.0 + 1e-12) + 1e-12
        self._kernel_arguments = (
            np.ascontiguousarray(self._normals.T), np.ascontiguousarray(offsets.reshape(-1)),
            np.ascontiguousarray(vertex_rows.T), np.einsum("vj,vj->v", vertex_rows, vertex_rows),
            np.ascontiguousarray(centres), radii, P, F, V,
            np.ascontiguousarray(tables.star_rows, dtype=float), tables.star_ids.astype(np.int64),
            np.ascontiguousarray(tables.facet_rows, dtype=float), tables.facet_ids.astype(np.int64),
            np.ascontiguousarray(tables.projectors, dtype=float), int(tables.vertex_slots), _SLACK)
        self.general_calls = 0  # calls the region path could not settle (for benchmarks and tests)

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
        N, (P, F, _) = len(q), self._shape
        if self.compiled and N:
            q = np.ascontiguousarray(q)
            distance, gradient = np.empty(N), np.empty((N, 3))
            if self._kernel(q, *self._kernel_arguments, distance, gradient):
                return distance, gradient
            # Not settled: the numpy paths below decide (the region path fails there too).
        # In place: a second array of this size would cost more than the product (numpy's
        # temporary elision checks arrays over 256 KiB with a slow stack walk).
        products = q @ self._rows_T
        products += self._row_offsets
        lower = products[:, :P * F].reshape(N, P, F).max(axis=2)  # (N, P): exact inside, a lower bound outside
        if N and lower.min() > 0.0:
            found = self._from_regions(q, products, lower)
            if found is not None:
                return found
            self.general_calls += 1
        return self._general(q, products, lower)

    def _from_regions(self, q, products, lower):
        """The region path: (distance, gradient) for points outside every piece, or None.

        Args:
            q: (N, 3) points; products: (N, P F + P V) their plane distances and |v|² − 2 q·v;
            lower: (N, P) > 0, each piece's largest plane distance.

        Returns:
            As ``__call__``, or None when a pair that may hold a point's closest point has no
            feature region holding the point (the general path then decides).
        """
        N, (P, F, V) = len(q), self._shape
        tables = self._regions
        s = products[:, :P * F].reshape(N, P, F)
        vertex_terms = products[:, P * F:]
        # Pairs (point n, piece p) = n P + p whose lower bound is within the nearest vertex's
        # distance, in order of n (each point has one at least: its nearest vertex's piece).
        upper = np.sqrt(np.maximum(vertex_terms.min(axis=1) + np.einsum("nj,nj->n", q, q), 0.0)) + _SLACK
        k = np.flatnonzero(lower <= upper[:, None])
        n_k, p_k = np.divmod(k, P)
        # Each pair's nearest vertex (its star) and maximising facet (rows of views, not copies).
        star = p_k * V + vertex_terms.reshape(N, P, V)[n_k, p_k].argmin(axis=1)
        facet = p_k * F + s[n_k, p_k].argmax(axis=1)
        # Their features' region rows, all tested with one product (q, −1) · (w, h) per table.
        q_h = np.empty((N, 1, 4))
        q_h[:, 0, :3] = q
        q_h[:, 0, 3] = -1.0
        q_h = q_h[n_k]
        K, G = len(k), tables.star_ids.shape[1]
        value = np.concatenate((np.matmul(q_h, tables.star_rows[star]).reshape(K, 4, G),
                                np.matmul(q_h, tables.facet_rows[facet]).reshape(K, 4, 4)), axis=2)
        inside = np.maximum(np.maximum(value[:, 0], value[:, 1]), np.maximum(value[:, 2], value[:, 3])) <= 0.0
        # The vertex's region is all its slots'; slot 0 stands for it.
        H = tables.vertex_slots
        if H > 1:
            inside[:, 0] = inside[:, :H].all(axis=1)
            inside[:, 1:H] = False
        slot = inside.argmax(axis=1)
        pairs = np.arange(K)
        found = inside[pairs, slot]
        # The found feature's projector: q − x = Π q − Π a = [Π | Π a] (q, −1).
        ids = np.concatenate((tables.star_ids[star], tables.facet_ids[facet]), axis=1)
        u = np.matmul(tables.projectors[ids[pairs, slot]], q_h.reshape(K, 4, 1)).reshape(K, 3)
        pair_d = np.where(found, np.sqrt(np.einsum("kj,kj->k", u, u)), np.inf)
        # Per point, its closest pair: the first of its pairs once sorted by distance.
        closest = np.lexsort((pair_d, n_k))[np.searchsorted(n_k, np.arange(N))]
        d = pair_d[closest]
        # A pair with no region found must be ruled out by its lower bound.
        if not found.all() and np.any(~found & (lower.ravel()[k] <= d[n_k])):
            return None
        if not d.min() > 0.0:  # on a feature (no direction), or no pair found
            return None
        return d, u[closest] / d[:, None]

    def _general(self, q, products, lower):
        """The general path: (distance, gradient) for any points (arguments as ``_from_regions``)."""
        N, (P, F, V) = len(q), self._shape
        s = products[:, :P * F]  # (N, P F): every plane distance
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
