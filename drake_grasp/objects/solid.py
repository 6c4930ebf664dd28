"""The solid a set of closed shells encloses: which shells are one object, and their union.

Why: an object file often stores one rigid object as several closed shells: CAD exports overlap a
handle's shell with a body's, fracture and voxel tools write closed cells that share faces, and
convex-decomposition tools write hulls with a millimetre between neighbours. One object is one
object: shells that touch, overlap, or lie within a join gap of each other are one rigid body.
Connectivity is decided by the distance between the shells' surfaces (and by containment, for a
shell wholly inside another), never by what a boolean union happens to return: Manifold's union
keeps solids that only share a face apart.

Mass and inertia come from the solid the shells enclose, their boolean union (Manifold, the
``manifold3d`` package, https://github.com/elalish/manifold: results are closed 2-manifolds):
overlaps are counted once, shells that touch add exactly. Two 6 × 6 × 3 cm boxes, one moved 3 cm
along the other: 216 cm³ summed, 162 cm³ enclosed.

Gaps are measured between points on the shells' surfaces (their vertices, and points filling each
triangle no farther apart than a quarter of the join gap), so a measured gap exceeds the true one
by at most that spacing.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import trimesh
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

DEFAULT_JOIN_GAP = 0.002  # m: shells this close are one object (or JOIN_GAP_FRACTION of its size)
JOIN_GAP_FRACTION = 0.02  # of the object's largest extent, when that is larger
MAX_SURFACE_SAMPLES = 400_000  # the sampling of every shell together is coarsened to about this
GAP_SAMPLES = 20_000  # points a side when measuring the smallest gap between separate parts


def join_gap(extent: float, gap: float | None = None) -> float:
    """The join gap (m) of an object of largest extent `extent` (m): `gap` if given, else
    DEFAULT_JOIN_GAP or JOIN_GAP_FRACTION of the extent, whichever is larger."""
    return float(gap) if gap is not None else max(DEFAULT_JOIN_GAP, JOIN_GAP_FRACTION * float(extent))


@dataclasses.dataclass(frozen=True)
class Component:
    """Shells that are one object: their indices, their union's boundary (metres) and its
    volume (m³)."""

    shells: tuple[int, ...]
    mesh: trimesh.Trimesh
    volume: float


@dataclasses.dataclass(frozen=True)
class Solid:
    """The objects a set of shells makes (largest volume first), the join gap (m) used, the
    smallest gap (m) between two components (inf for one) and the largest gap (m) the join
    bridged (0 when the joined shells touch or overlap)."""

    components: tuple[Component, ...]
    shells: int
    gap: float
    smallest_gap: float
    largest_bridged_gap: float = 0.0  # m: the widest gap between two shells that were joined
    cavities: int = 0  # inner shells wound inward: the walls of a hollow object's cavities

    @property
    def mesh(self) -> trimesh.Trimesh:
        """The first (largest) component's solid."""
        return self.components[0].mesh


def _surface_points(mesh: trimesh.Trimesh, spacing: float) -> np.ndarray:
    """Vertices and points filling each triangle on a barycentric lattice no coarser than `spacing`."""
    triangles = mesh.triangles
    longest = np.linalg.norm(triangles - np.roll(triangles, 1, axis=1), axis=2).max(axis=1)
    steps = np.clip(np.ceil(longest / spacing).astype(int), 1, 200)
    points = [mesh.vertices]
    for k in np.unique(steps[steps > 1]):
        chosen = triangles[steps == k]
        i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
        keep = (i + j) <= k
        u, v = i[keep] / k, j[keep] / k
        weights = np.column_stack([1.0 - u - v, u, v])  # (m, 3)
        points.append(np.einsum("mk,tkd->tmd", weights, chosen).reshape(-1, 3))
    return np.vstack(points)


def _winding_number(mesh: trimesh.Trimesh, point: np.ndarray) -> float:
    """The generalized winding number of a closed mesh about a point (1 inside, 0 outside):
    the solid angle of its triangles seen from the point over 4π (Van Oosterom and Strackee)."""
    a, b, c = (mesh.triangles - point).transpose(1, 0, 2)
    la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
    numerator = np.einsum("ij,ij->i", a, np.cross(b, c))
    denominator = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", b, c) * la
                   + np.einsum("ij,ij->i", c, a) * lb)
    return float(np.sum(2.0 * np.arctan2(numerator, denominator)) / (4.0 * np.pi))


_NEIGHBOURS = np.array([(x, y, z) for x in (-1, 0, 1) for y in (-1, 0, 1) for z in (-1, 0, 1)])


class _Voxels:
    """The points of one shell's surface hashed into cubes of the join gap's size: two surfaces
    within the gap of each other have points in the same or neighbouring cubes."""

    _K = 1 << 20

    def __init__(self, points: np.ndarray, origin: np.ndarray, gap: float):
        self.points = points
        cells = np.floor((points - origin) / gap).astype(np.int64) + 1
        codes = self._encode(cells)
        self.order = np.argsort(codes, kind="stable")
        self.sorted_codes = codes[self.order]
        unique = np.unique(codes)
        self.unique = unique
        k = self._K
        self.cells = np.column_stack([unique % k, (unique // k) % k, unique // (k * k)])
        self._tree = None
        self._around = None

    @classmethod
    def _encode(cls, cells: np.ndarray) -> np.ndarray:
        return cells[:, 0] + cls._K * (cells[:, 1] + cls._K * cells[:, 2])

    @property
    def tree(self) -> cKDTree:
        if self._tree is None:
            self._tree = cKDTree(self.points)
        return self._tree

    @property
    def around(self) -> np.ndarray:
        """Codes of the cubes this shell's points occupy and of their neighbours."""
        if self._around is None:
            self._around = np.unique(self._encode((self.cells[:, None, :] + _NEIGHBOURS).reshape(-1, 3)))
        return self._around

    def distance(self, other: "_Voxels", gap: float) -> float:
        """The smallest distance (m) from a point of this shell to a point of `other`, if within
        `gap`; inf otherwise (only the points in cubes next to `other`'s are searched)."""
        shared = np.intersect1d(self.unique, other.around, assume_unique=True)
        if len(shared) == 0:
            return float("inf")
        left = np.searchsorted(self.sorted_codes, shared, side="left")
        right = np.searchsorted(self.sorted_codes, shared, side="right")
        lengths = right - left
        starts = np.repeat(left - np.concatenate([[0], np.cumsum(lengths)[:-1]]), lengths)
        candidates = self.points[self.order[starts + np.arange(lengths.sum())]]
        distances, _ = other.tree.query(candidates, k=1, distance_upper_bound=gap * (1 + 1e-9))
        return float(distances.min()) if len(distances) else float("inf")


def _to_manifold(mesh: trimesh.Trimesh):
    import manifold3d

    return manifold3d.Manifold(manifold3d.Mesh(
        vert_properties=np.asarray(mesh.vertices, dtype=np.float32),
        tri_verts=np.asarray(mesh.faces, dtype=np.uint32)))


def union(shells: list[trimesh.Trimesh], cavities: list[trimesh.Trimesh] = ()) -> trimesh.Trimesh:
    """The boolean union of closed, outward shells, less the union of `cavities` (Manifold, single
    precision: about 1e-7 of the object's size); one shell and no cavity is returned as it is. A
    shell Manifold cannot take (not a manifold after repair) is added as it is, so its volume still
    counts."""
    if len(shells) == 1 and not cavities:
        return shells[0]
    import manifold3d

    solids, rest = [], []
    for shell in shells:
        solid = _to_manifold(shell)
        if solid.status() == manifold3d.Error.NoError and not solid.is_empty():
            solids.append(solid)
        else:
            rest.append(shell)
    holes = [h for h in (_to_manifold(c) for c in cavities)
             if h.status() == manifold3d.Error.NoError and not h.is_empty()]
    meshes = list(rest)
    if solids:
        result = manifold3d.Manifold.batch_boolean(solids, manifold3d.OpType.Add)
        if holes:
            result = result - manifold3d.Manifold.batch_boolean(holes, manifold3d.OpType.Add)
        result = result.to_mesh()
        # process=False: Manifold keeps apart the vertices of solids that only touch; welding them
        # would make edges of four faces where the union is, in fact, two closed solids.
        meshes.insert(0, trimesh.Trimesh(np.asarray(result.vert_properties, dtype=float)[:, :3],
                                         np.asarray(result.tri_verts, dtype=np.int64), process=False))
    return meshes[0] if len(meshes) == 1 else trimesh.util.concatenate(meshes)


def solid_of_shells(shells: list[trimesh.Trimesh], gap: float | None = None) -> Solid:
    """Groups closed, outward shells (metres) into objects and unites each group.

    Two shells are one object when their surfaces come within the join gap (:func:`join_gap` of
    the shells' largest extent, or `gap`), or when one lies inside the other. Components are
    sorted by volume, largest first.
    """
    extent = float(np.max(np.ptp(np.vstack([s.vertices for s in shells]), axis=0)))
    gap = join_gap(extent, gap)
    n = len(shells)
    if n == 1:
        return Solid((Component((0,), shells[0], float(shells[0].volume)),), 1, gap, float("inf"), 0.0)
    area = sum(float(s.area) for s in shells)
    spacing = max(gap / 4.0, np.sqrt(2.0 * area / MAX_SURFACE_SAMPLES), 1e-6 * extent)
    points = [_surface_points(s, spacing) for s in shells]
    origin = np.min([p.min(axis=0) for p in points], axis=0)
    voxels = [_Voxels(p, origin, gap) for p in points]
    boxes = np.array([s.bounds for s in shells])
    edges = set()
    bridged = 0.0
    for i in range(n):
        for j in range(i + 1, n):
            if np.any(boxes[i][0] > boxes[j][1] + gap) or np.any(boxes[j][0] > boxes[i][1] + gap):
                continue  # their bounding boxes are farther apart than the gap
            distance = voxels[i].distance(voxels[j], gap)
            if np.isfinite(distance):
                edges.add((i, j))
                bridged = max(bridged, distance)
    # A shell wholly inside another is part of it too: a visual mesh's inner detail (united), or, when
    # the file wound it the other way from its container, the inner wall of a hollow object (its
    # cavity, subtracted).
    inward = [bool(s.metadata.get("inward", False)) for s in shells]
    cavities = set()
    for i in range(n):
        for j in range(n):
            if i == j or not (np.all(boxes[i][0] >= boxes[j][0]) and np.all(boxes[i][1] <= boxes[j][1])):
                continue
            if inward[i] == inward[j] and (min(i, j), max(i, j)) in edges:
                continue
            if _winding_number(shells[j], shells[i].vertices[0]) > 0.5:
                edges.add((min(i, j), max(i, j)))
                if inward[i] != inward[j]:
                    cavities.add(i)
    rows = [e[0] for e in edges]
    cols = [e[1] for e in edges]
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    count, labels = connected_components(graph, directed=False)
    groups = [tuple(int(i) for i in np.flatnonzero(labels == label)) for label in range(count)]
    components = []
    for group in groups:
        mesh = union([shells[i] for i in group if i not in cavities],
                     [shells[i] for i in group if i in cavities])
        components.append(Component(group, mesh, float(mesh.volume)))
    components.sort(key=lambda c: -c.volume)
    smallest = float("inf")
    if count > 1:
        # Measured on every k-th point (at most GAP_SAMPLES a side): the message's number, not a decision.
        everything = np.vstack(points)
        label_of_point = labels[np.concatenate([np.full(len(p), i) for i, p in enumerate(points)])]
        for label in range(count):
            mine, others = everything[label_of_point == label], everything[label_of_point != label]
            mine = mine[:: max(1, len(mine) // GAP_SAMPLES)]
            others = others[:: max(1, len(others) // GAP_SAMPLES)]
            distances, _ = cKDTree(others).query(mine, k=1)
            smallest = min(smallest, float(distances.min()))
    return Solid(tuple(components), n, gap, smallest, bridged, len(cavities))
