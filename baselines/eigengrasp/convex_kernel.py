"""The region path of the convex-piece distance (convex_distance.py) as one compiled loop (numba).

Why: the planner asks, once per annealing step, for the distances from the hand's 19 virtual
contacts to every convex piece of the object. In numpy that is about 45 array operations on small
arrays (the region path of ``ConvexPiecesDistance``), whose cost is per operation (2-5 µs each), not
per element: on a 10-piece mesh the distance was about 60 % of a planner step. Here the same
algorithm runs as one ``numba.njit`` loop over plain float64/int arrays, point by point:

1. per piece, nearest bounding sphere first, the largest plane distance s_p = max_f (n_f · q + c_f)
   (a lower bound of the piece's distance; exact inside) and the nearest vertex (|v|² − 2 q · v,
   smallest), skipping pieces whose bounding sphere is farther than the nearest vertex so far
   (they cannot hold the closest point: the numpy path tests and rules them out by their planes);
2. the upper bound: the nearest vertex of all pieces (+ the same slack as the numpy path);
3. for each piece whose lower bound is within it: the Voronoi regions (convex_regions.py) of its
   nearest vertex's star and of its maximising facet, in the tables' order; the first region that
   holds the point names the feature (a vertex's region: all its slots), and its projector gives
   u = q − x;
4. per point, the closest such pair (the first of equal distances, as the numpy path's sort).

It decides as ``ConvexPiecesDistance._from_regions`` does and gives the same distances and gradients
(to rounding: the dot products are summed in another order). The skipped pieces only ever made the
numpy path give up in edge cases, so the kernel may settle a call the numpy path leaves to its
general path; both are exact. Where that path gives up (a
point inside or on a piece, or a pair that bounds cannot rule out with no region holding the point)
the kernel reports failure and the caller takes the numpy general path for the whole call, as
before.

Units: metres, in the object frame O. ``cache=True``: the compiled code is kept in __pycache__
beside this file (or NUMBA_CACHE_DIR), so only the first process after an install compiles it.
"""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True, nogil=True)
def region_distances(q, normals, offsets, vertices, vertex_sq, centres, radii, P, F, V, star_rows, star_ids,
                     facet_rows, facet_ids, projectors, vertex_slots, slack, distance, gradient):
    """Exact distances and unit gradients from points outside every piece, by feature regions.

    Args:
        q: (N, 3) points, m.
        normals: (3, P F) unit facet normals by coordinate, piece p's facet f in column p F + f
            (padding: zero).
        offsets: (P F,) facet offsets c_f (padding: −inf).
        vertices: (3, P V) hull vertices by coordinate (padding repeats a real one);
            vertex_sq: (P V,) their |v|².
        centres: (P, 3) and radii: (P,) each piece's bounding sphere (every vertex within radius of
            the centre), m: pieces whose sphere is farther than the nearest vertex found so far
            are skipped (they cannot hold the closest point; the numpy path tests them anyway).
        P, F, V: pieces, facets per piece, vertices per piece (padded counts).
        star_rows, star_ids, facet_rows, facet_ids, projectors, vertex_slots: the region tables
            (convex_regions.RegionTables, same layout).
        slack: added to the upper bound (m), as the numpy path.
        distance: (N,) output, m; gradient: (N, 3) output, unit.

    Returns:
        True when every point was settled; False when the numpy general path must decide (the
        outputs are then partial).
    """
    N = q.shape[0]
    G = star_ids.shape[1]
    H = vertex_slots
    sphere = np.empty(P)
    order = np.empty(P, dtype=np.int64)
    used = np.empty(P, dtype=np.bool_)
    lower = np.empty(P)
    nearest = np.empty(P, dtype=np.int64)
    best_facet = np.empty(P, dtype=np.int64)
    pair_d = np.empty(P)
    pair_u = np.empty((P, 3))
    inside = np.empty(G + 4, dtype=np.bool_)
    for n in range(N):
        x, y, z = q[n, 0], q[n, 1], q[n, 2]
        q_sq = x * x + y * y + z * z
        # Pieces by their bounding sphere's lower bound |q − c| − r (insertion sort; P is small).
        for p in range(P):
            dx, dy, dz = x - centres[p, 0], y - centres[p, 1], z - centres[p, 2]
            sphere[p] = np.sqrt(dx * dx + dy * dy + dz * dz) - radii[p]
            i = p
            while i > 0 and sphere[order[i - 1]] > sphere[p]:
                order[i] = order[i - 1]
                i -= 1
            order[i] = p
        # Per piece in that order, unless its sphere is beyond the nearest vertex so far: its
        # largest plane distance (a lower bound) and maximising facet, and its nearest vertex.
        # The piece of the nearest vertex of all is never skipped (its sphere bound is below the
        # vertex's distance), so `upper` is the numpy path's.
        vmin_all = np.inf
        for i in range(P):
            p = order[i]
            used[p] = False
            if sphere[p] > np.sqrt(max(vmin_all + q_sq, 0.0)) + slack:
                continue
            used[p] = True
            s_best = -np.inf
            f_best = 0
            for f in range(p * F, (p + 1) * F):
                s = normals[0, f] * x + normals[1, f] * y + normals[2, f] * z + offsets[f]
                if s > s_best:
                    s_best = s
                    f_best = f
            if not s_best > 0.0:  # inside or on a piece: the general path
                return False
            lower[p] = s_best
            best_facet[p] = f_best
            t_best = np.inf
            j_best = 0
            for j in range(p * V, (p + 1) * V):
                t = vertex_sq[j] - 2.0 * (vertices[0, j] * x + vertices[1, j] * y + vertices[2, j] * z)
                if t < t_best:
                    t_best = t
                    j_best = j
            nearest[p] = j_best
            if t_best < vmin_all:
                vmin_all = t_best
        upper = np.sqrt(max(vmin_all + q_sq, 0.0)) + slack
        d = np.inf
        closest = -1
        for p in range(P):  # in piece order: the first of equal distances wins, as in numpy
            pair_d[p] = np.inf
            if not used[p] or not lower[p] <= upper:
                used[p] = False
                continue
            star = nearest[p]
            facet = best_facet[p]
            for g in range(G):
                worst = -np.inf
                for r in range(4):
                    c = r * G + g
                    v = (x * star_rows[star, 0, c] + y * star_rows[star, 1, c] + z * star_rows[star, 2, c]
                         - star_rows[star, 3, c])
                    if v > worst:
                        worst = v
                inside[g] = worst <= 0.0
            for g in range(4):
                worst = -np.inf
                for r in range(4):
                    c = r * 4 + g
                    v = (x * facet_rows[facet, 0, c] + y * facet_rows[facet, 1, c] + z * facet_rows[facet, 2, c]
                         - facet_rows[facet, 3, c])
                    if v > worst:
                        worst = v
                inside[G + g] = worst <= 0.0
            if H > 1:  # the vertex's region is all its slots; slot 0 stands for it
                every = True
                for g in range(H):
                    every = every and inside[g]
                inside[0] = every
                for g in range(1, H):
                    inside[g] = False
            slot = -1
            for g in range(G + 4):
                if inside[g]:
                    slot = g
                    break
            if slot < 0:
                continue
            feature = star_ids[star, slot] if slot < G else facet_ids[facet, slot - G]
            u_sq = 0.0
            for i in range(3):
                u = (projectors[feature, i, 0] * x + projectors[feature, i, 1] * y + projectors[feature, i, 2] * z
                     - projectors[feature, i, 3])
                pair_u[p, i] = u
                u_sq += u * u
            pair_d[p] = np.sqrt(u_sq)
            if pair_d[p] < d:
                d = pair_d[p]
                closest = p
        if not d > 0.0 or closest < 0:  # on a feature (no direction), or no pair found
            return False
        for p in range(P):  # a pair with no region found must be ruled out by its lower bound
            if used[p] and pair_d[p] == np.inf and lower[p] <= d:
                return False
        distance[n] = d
        for i in range(3):
            gradient[n, i] = pair_u[closest, i] / d
    return True
