"""Opening non-manifold edges where solids meet along an edge: the faces around such an edge paired
solid by solid, and the edge's vertices given one copy per pair.

Why: two cells of a polycube that touch only along an edge (or two cubes of a voxel export, or two
bodies of one STL that share an edge) leave an edge of four faces once their vertices are welded. A
surface with such an edge is no 2-manifold, so it cannot be closed, cut into patches that are, or
handed to a convex decomposition. Yet nothing is missing: around the edge, the four faces bound two
solid wedges and two empty ones. Pairing each face with the next face across its own solid wedge,
and giving each pair its own copy of the edge, opens the pinch into two sheets that touch, and every
edge has two faces again. The volume, the area and the shape are unchanged; only the connectivity
at the pinch is.

The same pairing handles two faces that coincide with opposite windings but different triangulations
(cells of a triangle soup sharing a face: each cell keeps its own copy), since ties in angle are
ordered so that each face still pairs across its own solid.

The rule, at an edge a-b of 2k faces (k ≥ 2):

1. each face's direction into itself from the edge, u (perpendicular to the edge), gives its angle
   about the edge; its normal, by its winding, says on which side of it the solid lies (the normal
   points out of the solid);
2. the faces sorted by angle (faces at one angle ordered so that a face whose solid lies back comes
   before one whose solid lies ahead) must alternate: solid ahead, solid back, ...; each face whose
   solid lies ahead is paired with the face after it. An edge whose faces do not alternate (a fin,
   inconsistent windings, an odd count) is left as it was, for the patch split to deal with;
3. around each vertex of a paired edge, the faces joined across its manifold edges and across the
   pairs form fans; each fan after the first gets its own copy of the vertex.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

# Faces whose angles about an edge differ by less than this (rad) lie in one plane (a shared face).
COPLANAR_ANGLE = 1e-6


def _pairing(vertices: np.ndarray, faces: np.ndarray, a: int, b: int, owners: np.ndarray) -> list | None:
    """Pairs of face indices across the solid wedges at edge a-b, or None where they do not
    alternate (the edge is then left alone)."""
    if len(owners) < 4 or len(owners) % 2:
        return None
    start = vertices[a]
    along = vertices[b] - start
    length = float(np.linalg.norm(along))
    if length <= 0.0:
        return None
    d = along / length
    angles, solid_ahead = [], []
    reference = None
    for face in owners:
        corners = faces[face]
        third = corners[(corners != a) & (corners != b)]
        if len(third) != 1:
            return None
        u = vertices[third[0]] - start
        u = u - (u @ d) * d
        norm = float(np.linalg.norm(u))
        if norm <= 0.0:
            return None
        u /= norm
        if reference is None:
            reference = u
        angle = float(np.arctan2(np.cross(reference, u) @ d, reference @ u)) % (2.0 * np.pi)
        angles.append(0.0 if angle > 2.0 * np.pi - COPLANAR_ANGLE else angle)
        p = vertices[corners]
        normal = np.cross(p[1] - p[0], p[2] - p[0])
        side = float(normal @ np.cross(d, u))
        if side == 0.0:
            return None
        solid_ahead.append(side < 0.0)  # the normal points back, out of the solid: the solid lies ahead
    angles = np.asarray(angles)
    solid_ahead = np.asarray(solid_ahead)
    # Ties (one plane) ordered so that a face whose solid lies back comes first.
    rounded = np.round(angles / COPLANAR_ANGLE)
    order = np.lexsort((solid_ahead, rounded))
    ahead = solid_ahead[order]
    first = int(np.argmax(ahead))
    order, ahead = np.roll(order, -first), np.roll(ahead, -first)
    if not (np.all(ahead[0::2]) and not np.any(ahead[1::2])):
        return None
    return [(int(owners[order[i]]), int(owners[order[i + 1]])) for i in range(0, len(order), 2)]


def open_pinched_edges(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """(vertices, faces, edges opened): the mesh with each edge of four or more faces that pairs up
    (see the module) opened into one edge per pair, its end vertices copied once per fan. A mesh
    without such edges comes back as it was (the same arrays)."""
    faces = np.asarray(faces, np.int64)
    vertices = np.asarray(vertices, float)
    m = len(faces)
    if m == 0:
        return vertices, faces, 0
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    edges = np.sort(directed, axis=1)
    owner = np.tile(np.arange(m), 3)
    slot = np.repeat(np.arange(3), m)  # edge k of a face runs from its corner k to corner k + 1
    key = edges[:, 0] * (int(edges.max()) + 1) + edges[:, 1]  # one int64 per edge (fits below 2^31 vertices)
    _, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    crowded = np.flatnonzero(counts[inverse] >= 4)
    if len(crowded) == 0:
        return vertices, faces, 0
    # Corner-to-corner joins: across every manifold edge, and across each pair at an opened edge.
    rows = []  # (occurrence, occurrence) of one edge in two faces
    manifold = np.flatnonzero(counts[inverse] == 2)
    order = np.argsort(inverse[manifold], kind="stable")
    rows.append(manifold[order].reshape(-1, 2))
    opened, pinched = 0, set()
    groups = {}
    for occurrence in crowded:
        groups.setdefault(int(inverse[occurrence]), []).append(int(occurrence))
    for occurrences in groups.values():
        occurrences = np.asarray(occurrences)
        a, b = edges[occurrences[0]]
        pairs = _pairing(vertices, faces, int(a), int(b), owner[occurrences])
        if pairs is None:
            # Left as it was: all its faces stay joined around its vertices (no copy is made).
            rows.append(np.column_stack([np.repeat(occurrences[0], len(occurrences) - 1), occurrences[1:]]))
            continue
        at = {int(owner[o]): int(o) for o in occurrences}
        rows.append(np.array([(at[f], at[g]) for f, g in pairs]))
        opened += 1
        pinched.update((int(a), int(b)))
    if not opened:
        return vertices, faces, 0
    joins = np.concatenate(rows)
    # An occurrence's two corners: corner `slot` holds its first vertex, corner `slot + 1` its second.
    first = owner * 3 + slot
    second = owner * 3 + (slot + 1) % 3
    start_vertex = directed[:, 0]
    i, j = joins[:, 0], joins[:, 1]
    same = start_vertex[i] == start_vertex[j]
    left = np.concatenate([first[i], second[i]])
    right = np.concatenate([np.where(same, first[j], second[j]), np.where(same, second[j], first[j])])
    graph = coo_matrix((np.ones(len(left)), (left, right)), shape=(3 * m, 3 * m))
    _, fan = connected_components(graph, directed=False)
    corner_vertex = faces.ravel()
    new_faces = faces.ravel().copy()
    extra = []
    for vertex in sorted(pinched):
        corners = np.flatnonzero(corner_vertex == vertex)
        labels = np.unique(fan[corners])
        for label in labels[1:]:
            new_faces[corners[fan[corners] == label]] = len(vertices) + len(extra)
            extra.append(vertex)
    if extra:
        vertices = np.vstack([vertices, vertices[np.asarray(extra)]])
    return vertices, new_faces.reshape(-1, 3), opened
