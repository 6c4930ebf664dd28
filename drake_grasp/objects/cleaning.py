"""Cleaning the convex pieces handed to Drake, so that no contact query meets a degenerate face.

Why: Drake's compliant-rigid contact clips each rigid triangle by the four faces of every
tetrahedron of the compliant volume mesh (``SurfaceVolumeIntersector::ClipTriangleByTetrahedron``
in geometry/proximity/mesh_intersection.cc). Each face's half space is built from the unnormalised
cross product (B − A) × (C − A), and Drake's ``Plane`` / ``PosedHalfSpace`` constructor
(geometry/proximity/plane.cc) throws "Cannot instantiate plane from normal ...; its magnitude is too
small" when that vector's norm is below 1e-10, i.e. for a face of area below 5e-11 m² (a
triangle 10 µm on a side). A convex volume mesh is a fan of tetrahedra from the piece's centre to
its boundary triangles, so one tiny or sliver boundary triangle of a convex piece is enough: CoACD's
pieces (hulls of clipped mesh parts) carry many, and the first time such a tetrahedron overlaps
the table or a finger the simulation stops.

The cure here keeps every piece a convex hull of a *subset of its own vertices* (so a cleaned piece
lies inside the original one, and the volume it loses is exactly the difference of the hulls'
volumes): vertices closer than `min_edge` are merged (one is kept), and a vertex that makes a
triangle of the hull thinner than `min_altitude` is dropped, until no such triangle is left. A
piece thinner than `min_thickness` is dropped whole. Hulls are computed by Qhull (scipy.spatial).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import ConvexHull, QhullError, cKDTree

MIN_EDGE = 0.0003  # m: vertices of a piece closer than this are merged
MIN_ALTITUDE = 0.0001  # m: no hull triangle is thinner than this (its smallest height)
MIN_THICKNESS = 0.002  # m: a piece thinner than this is dropped
MAX_VERTICES = 1000  # most vertices of a cleaned piece (merging coarsens until it fits)
VOLUME_TOLERANCE = 0.02  # largest fraction of the object's volume that cleaning may remove


class CleaningError(ValueError):
    """Cleaning cannot make the shape safe without changing it by more than the tolerance."""


@dataclasses.dataclass(frozen=True)
class CleanPiece:
    """A cleaned convex piece: its hull's vertices and triangles (outward), and volumes (m³)."""

    vertices: np.ndarray
    faces: np.ndarray
    volume: float
    original_volume: float


def triangle_altitudes(triangles: np.ndarray) -> np.ndarray:
    """Smallest height of each triangle (n×3×3 → n, m): twice its area over its longest edge."""
    edges = np.linalg.norm(triangles - np.roll(triangles, 1, axis=1), axis=2)
    doubled_area = np.linalg.norm(
        np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1)
    return doubled_area / np.maximum(edges.max(axis=1), 1e-300)


def _merge_near(points: np.ndarray, radius: float) -> np.ndarray:
    """Indices of a subset of `points` with no two closer than `radius`: greedily, farthest from
    the centroid first, so that extreme points (a sphere's poles, a box's corners) are kept."""
    order = np.argsort(-np.linalg.norm(points - points.mean(axis=0), axis=1), kind="stable")
    tree = cKDTree(points)
    removed = np.zeros(len(points), dtype=bool)
    keep = []
    for i in order:
        if removed[i]:
            continue
        keep.append(i)
        removed[tree.query_ball_point(points[i], radius)] = True
    return np.sort(np.asarray(keep, dtype=int))


def _hull(points: np.ndarray) -> ConvexHull | None:
    try:
        return ConvexHull(points)
    except (QhullError, ValueError):  # fewer than 4 points, or all in a plane
        return None


def _outward_faces(hull: ConvexHull) -> np.ndarray:
    """Hull triangles (indices into hull.points) wound counter-clockwise seen from outside."""
    faces = hull.simplices.copy()
    tri = hull.points[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    flip = np.einsum("ij,ij->i", normals, hull.equations[:, :3]) < 0
    faces[flip] = faces[flip][:, ::-1]
    return faces


def min_width(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Width (m) of a convex polytope across its thinnest face direction (an upper bound of its
    true minimum width, exact for boxes and prisms)."""
    tri = vertices[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    heights = vertices @ normals.T  # vertices × faces
    return float(np.min(heights.max(axis=0) - heights.min(axis=0)))


def clean_convex_points(
    points: np.ndarray,
    *,
    min_edge: float = MIN_EDGE,
    min_altitude: float = MIN_ALTITUDE,
    max_vertices: int = MAX_VERTICES,
) -> CleanPiece | None:
    """The convex hull of a subset of `points` (m) with no vertices closer than `min_edge`, no
    triangle thinner than `min_altitude` and at most `max_vertices` vertices; None when nothing
    solid is left (the points span no volume at that resolution)."""
    points = np.asarray(points, dtype=float)
    hull = _hull(points)
    if hull is None:
        return None
    original_volume = float(hull.volume)
    vertices = points[np.sort(hull.vertices)]
    radius = min_edge
    if len(vertices) > max_vertices:  # Start near the spacing of max_vertices points on the surface.
        radius = max(min_edge, 0.8 * float(np.sqrt(hull.area / max_vertices)))
    while True:
        subset = vertices[_merge_near(vertices, radius)]
        if len(subset) <= max_vertices:
            break
        radius *= 1.25
    for _ in range(10_000):
        hull = _hull(subset)
        if hull is None:
            return None
        subset = subset[np.sort(hull.vertices)]
        hull = _hull(subset)
        if hull is None:
            return None
        faces = _outward_faces(hull)
        triangles = subset[faces]
        bad = np.flatnonzero(triangle_altitudes(triangles) < min_altitude)
        if len(bad) == 0:
            return CleanPiece(subset, faces, float(hull.volume), original_volume)
        # In a thin triangle the vertex opposite the longest edge lies closest to the others'
        # line: dropping it changes the hull least. Drop one per bad triangle, then recompute.
        edges = np.linalg.norm(triangles[bad] - np.roll(triangles[bad], 1, axis=1), axis=2)
        # Edge k joins vertex k and vertex k-1, so the vertex opposite edge k is k+1 (mod 3).
        opposite = (np.argmax(edges, axis=1) + 1) % 3
        drop = np.unique(faces[bad, opposite])
        subset = np.delete(subset, drop, axis=0)
        if len(subset) < 4:
            return None
    raise CleaningError("cleaning a convex piece did not converge")


def clean_pieces(
    pieces: list[np.ndarray],
    object_volume: float,
    *,
    min_thickness: float = MIN_THICKNESS,
    volume_tolerance: float = VOLUME_TOLERANCE,
    **kw,
) -> tuple[list[CleanPiece], float]:
    """Cleans the convex pieces (each given by its points, m) of an object of volume
    `object_volume` (m³): each becomes a :func:`clean_convex_points` hull, and pieces thinner
    than `min_thickness` or with nothing solid left are dropped.

    Returns:
        The clean pieces and the volume removed (m³), an upper bound of how much the union of the
        pieces shrank (every clean piece lies inside its original).

    Raises:
        CleaningError: if that removed volume exceeds `volume_tolerance` × `object_volume`, or no
            piece is left.
    """
    clean, removed = [], 0.0
    for points in pieces:
        piece = clean_convex_points(points, **kw)
        hull = _hull(np.asarray(points, float))
        original = float(hull.volume) if hull is not None else 0.0
        if piece is None or min_width(piece.vertices, piece.faces) < min_thickness:
            removed += original
            continue
        removed += piece.original_volume - piece.volume
        clean.append(piece)
    if not clean:
        raise CleaningError(f"every convex piece is thinner than {min_thickness * 1000:g} mm")
    if removed > volume_tolerance * object_volume:
        raise CleaningError(
            f"making the convex pieces safe for contact would remove {100 * removed / object_volume:.1f} % "
            f"of the volume (tolerance {100 * volume_tolerance:g} %): parts thinner than "
            f"{min_thickness * 1000:g} mm?")
    return clean, removed


def _hull_volume(points: np.ndarray) -> float:
    hull = _hull(points)
    return float(hull.volume) if hull is not None else 0.0


def merge_pieces(
    pieces: list[np.ndarray], max_pieces: int, *, min_thickness: float = MIN_THICKNESS, near: float = 0.002,
) -> tuple[list[np.ndarray], float]:
    """Convex pieces (each given by its points, m) merged into fewer: a piece thinner than
    `min_thickness` into the neighbour whose joint hull adds the least volume (instead of dropping
    it and the material it stands for), then, while there are more than `max_pieces`, the two
    neighbours whose joint hull adds the least. Neighbours are pieces whose bounding boxes lie
    within `near` (m) of each other (any two, if a piece has none).

    A merged piece is the convex hull of both: it lies outside their union by the volume it adds.
    Pair costs wait in a heap and a merge computes only the new piece's, so merging hundreds of
    cells stays cheap.

    Returns:
        The pieces' points (those not merged in the order given, merged ones after) and the volume
        (m³) the merges added, a bound of how much the union of the pieces grew.
    """
    import heapq
    import itertools

    live: dict[int, np.ndarray] = {}
    volume: dict[int, float] = {}
    thin: dict[int, bool] = {}
    boxes: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    ids = itertools.count()
    heap: list[tuple[float, int, int]] = []
    added = 0.0

    def add(points: np.ndarray, merged: bool = False) -> int:
        key = next(ids)
        hull = _hull(points)
        if hull is not None and merged:  # a merged piece keeps only its hull's vertices
            points = points[np.sort(hull.vertices)]
        live[key] = points
        volume[key] = float(hull.volume) if hull is not None else 0.0
        thin[key] = hull is None or min_width(hull.points, _outward_faces(hull)) < min_thickness
        boxes[key] = (points.min(axis=0), points.max(axis=0))
        return key

    def neighbours(i: int) -> list[int]:
        lo, hi = boxes[i][0] - near, boxes[i][1] + near
        found = [j for j in live if j != i and np.all(boxes[j][0] <= hi) and np.all(boxes[j][1] >= lo)]
        return found or [j for j in live if j != i]

    def cost(i: int, j: int) -> float:
        return _hull_volume(np.vstack([live[i], live[j]])) - volume[i] - volume[j]

    def merge(i: int, j: int) -> int:
        nonlocal added
        key = add(np.vstack([live.pop(i), live.pop(j)]), merged=True)
        added += max(volume[key] - volume[i] - volume[j], 0.0)
        return key

    for points in pieces:
        add(np.asarray(points, float))
    while len(live) > 1:
        thin_pieces = [i for i in live if thin[i]]
        if not thin_pieces:
            break
        i = thin_pieces[0]
        merge(i, min(neighbours(i), key=lambda j: cost(i, j)))
    if len(live) > max(max_pieces, 1):
        for i in list(live):
            for j in neighbours(i):
                if j > i:
                    heapq.heappush(heap, (cost(i, j), i, j))
    while len(live) > max(max_pieces, 1) and heap:
        _, i, j = heapq.heappop(heap)
        if i not in live or j not in live:
            continue  # one of them was merged already
        key = merge(i, j)
        for other in neighbours(key):
            heapq.heappush(heap, (cost(key, other), other, key))
    return list(live.values()), added
