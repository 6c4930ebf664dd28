"""Voronoi regions of a convex polytope's features, as tables for a vectorised closest-point test.

Outside a convex polytope every point q has one closest point x, and it lies on one *feature*: a
vertex, the inside of an edge or the inside of a face. The points whose closest point lies on a given
feature form its Voronoi region, a polyhedron of a few half-spaces (all vectors unit):

* triangle (a, b, c) of a face with outward normal n and plane n·x + c₀ = 0: s = n·q + c₀ ≥ 0, and
  q in the triangle's prism, m_e·(q − a_e) ≤ 0 for each edge e (m_e: in-plane normal of the edge,
  pointing out of the triangle). Then q − x = s n.
* edge a → b between faces 1 and 2: 0 ≤ ê·(q − a) ≤ |b − a|, and (q − a)·m_i ≥ 0 for both faces
  (m_i: face i's in-plane normal at the edge, pointing out of the face). Then q − x = (I − ê êᵀ)(q − a).
* vertex v: ê_w·(q − v) ≤ 0 for every edge v → w (the edges span the polytope's tangent cone at v).
  Then q − x = q − v.

A point inside a region has its closest point on that feature, exactly: no other check is needed.
The query (convex_distance.py) tests, per (point, piece), the regions of a few features near the
point: the *star* of the piece's vertex nearest to it (the vertex, its edges, the edges opposite it
in its triangles, its triangles) and the piece's facet of largest plane distance (with its edges).
On the planner's contacts one of them holds the closest point for all but a few pairs in 100,000
(the rest go to the general path).

Faces that qhull triangulates as fans (a flat face of a decomposed piece: one corner in 20+ triangles)
are re-triangulated here as zig-zag strips, so that no vertex is in more than 4 triangles of one face
and the stars stay small. Edges between two triangles of one face are not features (their region is
empty).

Table layout, for a vectorised test: every feature has 4 region rows (coefficients w, offset h:
inside when w·q − h ≤ 0 for all 4, tolerance included in h) and a 3 × 4 projector [Π | Π a] with
q − x = Π q − Π a; a vertex takes one such feature per 4 of its edges (up to 16 edges), all needed.
Lengths in metres, in the frame the hulls are given in.

Pure numpy/scipy, no Drake.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import ConvexHull

REGION_TOLERANCE = 1e-12  # m: region boundaries are inclusive by this much (rounding of w·q)
MAX_STAR = 26  # most features tested per star; larger stars lose their last ones (see region_tables)
MAX_VERTEX_SLOTS = 4  # a vertex region of up to 16 edges; vertices with more are left to the general path

_NEVER = np.array([[0.0, 0.0, 0.0, -1.0]] * 4)  # region rows no point satisfies (w·q − h = 1)


def flat_faces(hull: ConvexHull) -> list[tuple[np.ndarray, list[int]]]:
    """The polytope's faces: qhull's triangles grouped by plane.

    qhull gives the triangles of one merged (flat) facet the same equation, bit for bit.

    Returns:
        Per face, (its equation [n, c₀] (4,), its vertices (hull point indices) around its boundary,
        in order). A face whose boundary is not one simple cycle (never seen) keeps qhull's triangles
        as separate faces.
    """
    equations, group = np.unique(hull.equations, axis=0, return_inverse=True)
    group = group.ravel()
    faces = []
    for g, equation in enumerate(equations):
        triangles = hull.simplices[group == g]
        if len(triangles) == 1:
            faces.append((equation, [int(v) for v in triangles[0]]))
            continue
        cycle = _boundary_cycle(triangles)
        if cycle is None:
            faces += [(equation, [int(v) for v in t]) for t in triangles]
        else:
            faces.append((equation, cycle))
    return faces


def _boundary_cycle(triangles: np.ndarray) -> list[int] | None:
    """The boundary of a triangulated disc as one vertex cycle, or None when it is not one."""
    count: dict[tuple[int, int], int] = {}
    for t in triangles:
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    neighbours: dict[int, list[int]] = {}
    for (a, b), n in count.items():
        if n == 1:
            neighbours.setdefault(int(a), []).append(int(b))
            neighbours.setdefault(int(b), []).append(int(a))
    if not neighbours or any(len(n) != 2 for n in neighbours.values()):
        return None
    start = next(iter(neighbours))
    cycle, previous = [start], None
    while True:
        a, b = neighbours[cycle[-1]]
        step = b if a == previous else a
        previous = cycle[-1]
        if step == start:
            break
        cycle.append(step)
        if len(cycle) > len(neighbours):
            return None
    return cycle if len(cycle) == len(neighbours) else None


def strip_triangles(cycle: list[int]) -> list[tuple[int, int, int]]:
    """A zig-zag triangulation of a convex polygon given by its vertex cycle.

    Every vertex is in at most 4 of its triangles (a fan puts one vertex in all of them).
    """
    lo, hi, out, turn = 0, len(cycle) - 1, [], False
    while hi - lo >= 2:
        if turn:
            out.append((cycle[lo], cycle[hi - 1], cycle[hi]))
            hi -= 1
        else:
            out.append((cycle[lo], cycle[lo + 1], cycle[hi]))
            lo += 1
        turn = not turn
    return out


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _away(m: np.ndarray, a: np.ndarray, inside: np.ndarray) -> np.ndarray:
    """m, or −m, whichever points from a away from the point `inside`."""
    return -m if m @ (inside - a) > 0.0 else m


def triangle_feature(corners: np.ndarray, equation: np.ndarray, tolerance: float):
    """Region rows (4, 4) and projector (3, 4) of a triangle (3, 3) lying in the plane `equation`."""
    n, c0 = equation[:3], equation[3]
    rows = np.empty((4, 4))
    rows[0, :3], rows[0, 3] = -n, c0  # s = n·q + c₀ ≥ 0 (no slack: s is the distance)
    for e in range(3):
        a, b, other = corners[e], corners[(e + 1) % 3], corners[(e + 2) % 3]
        m = _away(_unit(np.cross(b - a, n)), a, other)
        rows[1 + e, :3], rows[1 + e, 3] = m, m @ a + tolerance
    projector = np.empty((3, 4))
    projector[:, :3] = np.outer(n, n)
    projector[:, 3] = -c0 * n
    return rows, projector


def edge_feature(a: np.ndarray, b: np.ndarray, faces: list[tuple[np.ndarray, np.ndarray]], tolerance: float):
    """Region rows (4, 4) and projector (3, 4) of the edge a → b.

    Args:
        faces: the two faces at the edge, each as (unit normal, a point inside the face).

    Row 0 is ê·(a − q) ≤ tolerance (the vertex a's side); the star's vertex test reads it.
    """
    e = _unit(b - a)
    rows = np.empty((4, 4))
    rows[0, :3], rows[0, 3] = -e, -e @ a + tolerance
    rows[1, :3], rows[1, 3] = e, e @ b + tolerance
    for i, (n, inside) in enumerate(faces):
        m = _away(_unit(np.cross(e, n)), a, inside)
        rows[2 + i, :3], rows[2 + i, 3] = -m, -m @ a + tolerance
    projector = np.empty((3, 4))
    projector[:, :3] = np.eye(3) - np.outer(e, e)
    projector[:, 3] = projector[:, :3] @ a
    return rows, projector


def vertex_features(v: np.ndarray, neighbours: np.ndarray, slots: int, tolerance: float) -> np.ndarray:
    """The region rows of vertex v as `slots` features of 4 rows each, all needed (slots, 4, 4).

    The region is ê_w·(q − v) ≤ tolerance for each edge v → w (`neighbours`: (k, 3) the w). Up to
    4 `slots` edges fit; short lists repeat their first row. With more, no feature is ever
    satisfied (the vertex is then left to the general path).
    """
    if len(neighbours) > 4 * slots:
        return np.tile(_NEVER, (slots, 1, 1))
    e = neighbours - v
    e /= np.linalg.norm(e, axis=1, keepdims=True)
    rows = np.column_stack([e, e @ v + tolerance])
    return rows[np.minimum(np.arange(4 * slots), len(rows) - 1)].reshape(slots, 4, 4)


@dataclasses.dataclass
class RegionTables:
    """Feature regions of a set of convex pieces, laid out for the query in convex_distance.py.

    Pieces are padded to V vertices and F facets (the query's layout); row p V + j is piece p's
    vertex j, row p F + f its qhull facet f.

    Attributes:
        star_rows: (P V, 4, 4 G) region rows of each vertex's star, coefficient-major: element
            [c, r G + g] is coefficient c ([w_x, w_y, w_z, h]) of row r of slot g. Slots
            0..vertex_slots − 1 are the vertex (its region is all their rows; the query lets only
            slot 0 stand for it), then its edges, its triangles and the edges opposite it; unused
            slots are never satisfied.
        star_ids: (P V, G) each slot's feature (a row of ``projectors``).
        facet_rows: (P F, 4, 16) likewise for each qhull facet: the facet, then its three edges.
        facet_ids: (P F, 4).
        projectors: (features, 3, 4) [Π | Π a]; row 0 belongs to no region.
        vertex_slots: slots a vertex's region takes (4 edges each).
    """

    star_rows: np.ndarray
    star_ids: np.ndarray
    facet_rows: np.ndarray
    facet_ids: np.ndarray
    projectors: np.ndarray
    vertex_slots: int


def region_tables(hulls: list[ConvexHull], V: int, F: int, tolerance: float = REGION_TOLERANCE,
                  max_star: int = MAX_STAR) -> RegionTables:
    """Builds the region tables of convex pieces.

    Args:
        hulls: The pieces' hulls (points in the query's frame, m).
        V, F: Vertex and facet counts the pieces are padded to (at least each hull's).
        tolerance: Slack of the region boundaries, m.
        max_star: Most slots of a star (the vertex's included); a larger star loses its last
            features (its pairs may then need the general path).
    """
    registry: dict[tuple, int] = {}
    projectors: list[np.ndarray] = [np.zeros((3, 4))]
    # A vertex's region takes ceil(edges / 4) slots, for the most edges any vertex has (up to 16).
    most_edges = max(len(_edge_neighbours(flat_faces(h)).get(int(v), ())) for h in hulls for v in h.vertices)
    vertex_slots = int(np.clip(-(-most_edges // 4), 1, MAX_VERTEX_SLOTS))
    pieces = [_piece_features(h, vertex_slots, tolerance) for h in hulls]
    G = max(min(max(len(star) for piece in pieces for star in piece["stars"]), max_star), vertex_slots)
    P = len(hulls)
    star_rows = np.tile(_NEVER, (P * V, G, 1, 1))
    star_ids = np.zeros((P * V, G), dtype=np.intp)
    facet_rows = np.tile(_NEVER, (P * F, 4, 1, 1))
    facet_ids = np.zeros((P * F, 4), dtype=np.intp)

    def fill(rows, ids, features, p):
        for i, (key, region, projector) in enumerate(features[:len(ids)]):
            if (p,) + key not in registry:
                registry[(p,) + key] = len(projectors)
                projectors.append(projector)
            rows[i], ids[i] = region, registry[(p,) + key]

    for p, piece in enumerate(pieces):
        for j in range(V):  # padding vertices repeat the last one
            row = p * V + j
            fill(star_rows[row], star_ids[row], piece["stars"][min(j, len(piece["stars"]) - 1)], p)
        for f, features in enumerate(piece["facets"]):
            fill(facet_rows[p * F + f], facet_ids[p * F + f], features, p)
    # (slot, region row, coefficient) -> (coefficient, region row, slot), flattened per vertex/facet.
    return RegionTables(
        star_rows=np.ascontiguousarray(star_rows.transpose(0, 3, 2, 1)).reshape(P * V, 4, 4 * G),
        star_ids=star_ids,
        facet_rows=np.ascontiguousarray(facet_rows.transpose(0, 3, 2, 1)).reshape(P * F, 4, 16),
        facet_ids=facet_ids,
        projectors=np.array(projectors),
        vertex_slots=vertex_slots)


def _edge_neighbours(faces) -> dict[int, list[int]]:
    """Each vertex's neighbours along the faces' sides."""
    neighbours: dict[int, set[int]] = {}
    for _, cycle in faces:
        for a, b in zip(cycle, cycle[1:] + cycle[:1]):
            neighbours.setdefault(a, set()).add(b)
            neighbours.setdefault(b, set()).add(a)
    return {v: sorted(w) for v, w in neighbours.items()}


def _piece_features(hull: ConvexHull, vertex_slots: int, tolerance: float) -> dict:
    """One piece's features: per hull vertex (hull.vertices order) its star, per qhull facet its
    facet, then its three edges.

    A feature is (key, region rows (4, 4) [w, h], projector (3, 4)). A star: the vertex
    (`vertex_slots` features), its edges, the triangles at it, the edges opposite it in those triangles. The
    triangles are those of `flat_faces` strip-triangulated; an edge is a side of a face (an edge
    between two triangles of one face is no feature: its region is empty).
    """
    points = hull.points
    faces = flat_faces(hull)
    centres = [points[cycle].mean(axis=0) for _, cycle in faces]
    edge_faces: dict[tuple[int, int], list[int]] = {}
    for g, (_, cycle) in enumerate(faces):
        for a, b in zip(cycle, cycle[1:] + cycle[:1]):
            edge_faces.setdefault((min(a, b), max(a, b)), []).append(g)
    neighbours = _edge_neighbours(faces)

    def edge(a, b):
        faces_ab = edge_faces.get((min(a, b), max(a, b)))
        if faces_ab is None or len(faces_ab) != 2:  # not a side of two faces (never seen)
            return None
        region, projector = edge_feature(points[a], points[b],
                                         [(faces[g][0][:3], centres[g]) for g in faces_ab], tolerance)
        return ("edge", min(a, b), max(a, b)), region, projector

    triangles = [(g, t) for g, (_, cycle) in enumerate(faces) for t in strip_triangles(cycle)]
    at_vertex: dict[int, list[int]] = {}
    for i, (_, t) in enumerate(triangles):
        for v in t:
            at_vertex.setdefault(v, []).append(i)
    stars = []
    for v in (int(v) for v in hull.vertices):
        edges = [edge(v, w) for w in neighbours[v]]
        if any(e is None for e in edges):  # the region needs every edge: leave it to the general path
            vertex_rows = np.tile(_NEVER, (vertex_slots, 1, 1))
        else:
            vertex_rows = vertex_features(points[v], points[neighbours[v]], vertex_slots, tolerance)
        projector = np.column_stack([np.eye(3), points[v]])
        star = [(("vertex", v, i), vertex_rows[i], projector) for i in range(vertex_slots)]
        star += [e for e in edges if e is not None]
        for i in at_vertex[v]:
            g, t = triangles[i]
            region, projector = triangle_feature(points[list(t)], faces[g][0], tolerance)
            star.append((("triangle",) + tuple(sorted(t)), region, projector))
        for i in at_vertex[v]:
            a, b = [int(w) for w in triangles[i][1] if w != v]
            e = edge(a, b)
            if e is not None and all(e[0] != f[0] for f in star):
                star.append(e)
        stars.append(star)
    facets = []
    for f, t in enumerate(hull.simplices):
        region, projector = triangle_feature(points[t], hull.equations[f], tolerance)
        features = [(("facet", f), region, projector)]
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            e = edge(int(a), int(b))  # None for a diagonal of a flat face
            features.append(e if e is not None else features[0])
        facets.append(features)
    return {"stars": stars, "facets": facets}
