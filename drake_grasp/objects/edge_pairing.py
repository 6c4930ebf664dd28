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


def unique_rows(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(inverse, counts) of the distinct rows of an integer array of 2 or 3 columns (vertex
    indices): rows packed into one int64 key where they fit (np.unique on one column is many
    times faster than on rows)."""
    rows = np.asarray(rows, np.int64)
    base = int(rows.max(initial=0)) + 1
    if base ** rows.shape[1] < 2**62:
        key = rows[:, 0]
        for column in range(1, rows.shape[1]):
            key = key * base + rows[:, column]
        _, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    else:
        _, inverse, counts = np.unique(rows, axis=0, return_inverse=True, return_counts=True)
    return inverse.ravel(), counts


def manifold_pairs(inverse: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """(K, 2): for each edge of exactly two faces, the indices of its two occurrences in the rows that
    `unique_rows` keyed (`inverse`, `counts` its results), in the order of the edges."""
    manifold = np.flatnonzero(counts[inverse] == 2)
    return manifold[np.argsort(inverse[manifold], kind="stable")].reshape(-1, 2)


def _pairings(vertices: np.ndarray, faces: np.ndarray, a: np.ndarray, b: np.ndarray,
              owners: np.ndarray) -> np.ndarray:
    """For E edges a-b of k faces each (`owners`, E × k face indices, k even, at least 4): (E, k/2, 2)
    the pairs of faces across the solid wedges of each edge, as positions in its row of `owners`, with
    -1 where an edge's faces do not alternate (that edge is then left alone). All edges at once: a
    voxel soup has thousands."""
    count, k = owners.shape
    bad = np.zeros(count, bool)
    start = vertices[a]
    along = vertices[b] - start
    length = np.linalg.norm(along, axis=1)
    bad |= length <= 0.0
    d = along / np.where(length > 0.0, length, 1.0)[:, None]
    corners = faces[owners]  # E × k × 3
    is_end = (corners == a[:, None, None]) | (corners == b[:, None, None])
    bad |= np.any(np.count_nonzero(~is_end, axis=2) != 1, axis=1)
    third = np.where(~is_end, corners, 0).max(axis=2)  # the one corner that is neither end
    u = vertices[third] - start[:, None, :]
    u -= np.einsum("ekc,ec->ek", u, d)[:, :, None] * d[:, None, :]
    norm = np.linalg.norm(u, axis=2)
    bad |= np.any(norm <= 0.0, axis=1)
    u /= np.where(norm > 0.0, norm, 1.0)[:, :, None]
    reference = u[:, :1, :]
    sine = np.einsum("ekc,ec->ek", np.cross(reference, u), d)
    cosine = np.einsum("ekc,ekc->ek", np.broadcast_to(reference, u.shape), u)
    angles = np.arctan2(sine, cosine) % (2.0 * np.pi)
    angles = np.where(angles > 2.0 * np.pi - COPLANAR_ANGLE, 0.0, angles)
    p = vertices[corners]  # E × k × 3 × 3
    normals = np.cross(p[:, :, 1] - p[:, :, 0], p[:, :, 2] - p[:, :, 0])
    side = np.einsum("ekc,ekc->ek", normals, np.cross(d[:, None, :], u))
    bad |= np.any(side == 0.0, axis=1)
    solid_ahead = side < 0.0  # the normal points back, out of the solid: the solid lies ahead
    # Sorted by angle about the edge; ties (one plane) with a face whose solid lies back first.
    rounded = np.round(angles / COPLANAR_ANGLE)
    rows = np.repeat(np.arange(count), k)
    order = np.lexsort((solid_ahead.ravel(), rounded.ravel(), rows)).reshape(count, k) - (np.arange(count) * k)[:, None]
    ahead = np.take_along_axis(solid_ahead, order, axis=1)
    first = np.argmax(ahead, axis=1)  # start at a face whose solid lies ahead
    rolled = (np.arange(k)[None, :] + first[:, None]) % k
    order = np.take_along_axis(order, rolled, axis=1)
    ahead = np.take_along_axis(ahead, rolled, axis=1)
    bad |= ~(np.all(ahead[:, 0::2], axis=1) & ~np.any(ahead[:, 1::2], axis=1))
    pairs = np.stack([order[:, 0::2], order[:, 1::2]], axis=2)
    pairs[bad] = -1
    return pairs


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
    inverse, counts = unique_rows(edges)
    crowded = np.flatnonzero(counts[inverse] >= 4)
    if len(crowded) == 0:
        return vertices, faces, 0
    # Corner-to-corner joins: across every manifold edge, and across each pair at an opened edge.
    rows = []  # (occurrence, occurrence) of one edge in two faces
    rows.append(manifold_pairs(inverse, counts))
    # The crowded edges' occurrences, edge by edge, then the edges grouped by their number of faces.
    by_edge = crowded[np.argsort(inverse[crowded], kind="stable")]
    _, starts, sizes = np.unique(inverse[by_edge], return_index=True, return_counts=True)
    opened, pinched = 0, []
    for k in np.unique(sizes):
        occurrences = by_edge[starts[sizes == k][:, None] + np.arange(k)[None, :]]  # E × k
        if k % 2:
            pairs = np.full((len(occurrences), k // 2, 2), -1)
        else:
            ends = edges[occurrences[:, 0]]
            pairs = _pairings(vertices, faces, ends[:, 0], ends[:, 1], owner[occurrences])
        paired = pairs[:, 0, 0] >= 0
        alone = occurrences[~paired]
        if len(alone):  # all their faces stay joined around their vertices (no copy is made)
            rows.append(np.column_stack([np.repeat(alone[:, 0], k - 1), alone[:, 1:].ravel()]))
        if np.any(paired):
            joined, positions = occurrences[paired], pairs[paired]
            rows.append(np.stack([np.take_along_axis(joined, positions[:, :, 0], axis=1),
                                  np.take_along_axis(joined, positions[:, :, 1], axis=1)], axis=2).reshape(-1, 2))
            opened += len(joined)
            pinched.append(edges[joined[:, 0]].ravel())
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
    new_faces = corner_vertex.copy()
    at_pinch = np.flatnonzero(np.isin(corner_vertex, np.unique(np.concatenate(pinched))))
    # Each (vertex, fan) pair at a pinched vertex: the first fan of each vertex keeps it, the others
    # get copies (pairs sorted by vertex, then fan).
    pairs, which = np.unique(np.column_stack([corner_vertex[at_pinch], fan[at_pinch]]), axis=0, return_inverse=True)
    first = np.concatenate([[True], pairs[1:, 0] != pairs[:-1, 0]])
    ids = pairs[:, 0].copy()
    ids[~first] = len(vertices) + np.arange(np.count_nonzero(~first))
    new_faces[at_pinch] = ids[which.ravel()]
    if np.any(~first):
        vertices = np.vstack([vertices, vertices[pairs[~first, 0]]])
    return vertices, new_faces.reshape(-1, 3), opened
