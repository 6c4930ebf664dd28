"""Repairing a triangle mesh into closed shells: what a scan, a visual mesh or a CAD export needs
before it can be a rigid body.

Why: a real object file is rarely a clean closed 2-manifold. It has open edges and holes, edges
shared by three or more faces, flipped and duplicated faces, degenerate triangles, internal walls
between cells that share a face, and stray sheets. Mass, inertia and contact all need closed,
outward-wound shells. The steps, each counted for the one-line note a user sees:

1. weld vertices that coincide, drop degenerate triangles (repeated or collinear vertices), except
   that a collinear one in a surface that is closed with it is kept (the sliver of a T-junction:
   dropping it opens a slit that no hole filler closes);
1b. split faces at T-junctions: where a vertex of the open boundary lies on another face's open edge
   (a part subdivided apart from the part it meets, as a CAD export leaves it: IsaacGym's Factory
   "subdiv" meshes), that face is split there, so that the two sides' edges pair up;
2. drop duplicated faces: of two copies with the same winding one is kept; two copies with opposite
   windings are the wall between two cells that share that face, and both go (the cells become one
   shell);
2b. open pinched edges: where solids meet along an edge (an edge of four faces: polycube cells that
   touch only along an edge), the faces are paired solid by solid and each pair gets its own copy of
   the edge (drake_grasp.objects.edge_pairing);
3. split the rest into patches joined across manifold edges only (an edge of exactly two faces), so
   that a fin on an edge comes apart;
4. wind each patch consistently and outward (trimesh's BFS over face adjacency);
5. close each open patch: MeshFix (pymeshfix, Attene 2010) fills its holes and removes what is not
   manifold; a patch that still encloses no volume (a sheet, a fin, an internal partition) is
   dropped, and when nothing else is left the file is refused; but a model file's collision mesh
   whose vertices all lie on their convex hull is that hull (`convex_piece_hull`: the engines a URDF,
   SDF or MJCF is made for collide a mesh as its hull).

Why MeshFix: measured on the defect zoo (drake_grasp.objects.mesh_zoo, scripts/bench_repair.py),
trimesh.repair.fill_holes closes only holes of one or two triangles, and Manifold refuses any mesh
that is not already a manifold; MeshFix closed every open cap and hole. See docs/results/repair.md.

MeshFix is an optional dependency: pymeshfix is GPL-3 (its PyPI classifier says AGPL-3), this
package BSD-3-Clause, so it is the extra ``drake-grasp[repair]`` (scripts/setup installs it) and
imported only when a mesh has an open patch. Without it, closed meshes load as before and a mesh
that needs closing is refused with one line saying how to enable the repair.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import trimesh
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from drake_grasp.objects.edge_pairing import manifold_pairs, open_pinched_edges, unique_rows as _unique_rows

# A patch encloses a solid only if its volume is at least this fraction of its convex hull's.
MIN_FILL_FRACTION = 0.02
# A patch that had to be closed is a solid only if its mean thickness once closed (twice its volume
# over its area) is at least this fraction of the open patch's largest extent: a curved sheet closed
# along its boundary is a thin pillow (a 10 cm sheet waving ±2 cm: 6 mm), a tube without caps is not
# (a 6 × 10 cm tube: 23 mm), nor is a deep bowl; a shallow dish is refused with the sheets.
MIN_CLOSED_THICKNESS = 0.1
# ... unless its open boundary is at most this fraction of the square root of its area: then it was a
# solid with a few small holes (a model airplane's airframe open by three edges is thin for its 45 cm
# span, but its holes are specks), not a sheet (a square sheet's boundary is 4 times the root of its
# area), a tube without caps (6 × 10 cm: 2.7 times) or a bowl.
MAX_HOLES_PERIMETER = 0.05
# A vertex this close to a face's open edge (a fraction of the mesh's largest extent: 0.1 µm in 10 cm)
# lies on it: a T-junction, where one side of a seam was subdivided and the other not.
T_JUNCTION_TOLERANCE = 1e-6


class RepairError(ValueError):
    """No solid can honestly be recovered from the mesh (one line)."""


MESHFIX_MISSING = ("open mesh ({edges} open edges): closing it needs MeshFix, which is not installed; enable the "
                   "repair with pip install 'drake-grasp[repair]' (pymeshfix, GPL-3), or close the mesh first")


class _MeshFixMissing(RepairError):
    """pymeshfix is not installed and a patch needs closing (the caller names the file)."""


@dataclasses.dataclass
class RepairReport:
    """What was done to a mesh, counted (faces, holes) and measured (m³)."""

    welded_vertices: int = 0
    degenerate_faces: int = 0
    duplicate_faces: int = 0
    t_junctions: int = 0  # faces split where a vertex lay on their open edge
    internal_walls: int = 0  # faces dropped in opposite-wound pairs (walls between cells)
    non_manifold_edges: int = 0
    flipped_faces: int = 0
    open_edges: int = 0
    closed_patches: int = 0  # patches MeshFix closed
    dropped_faces: int = 0  # faces of sheets that enclose no volume
    volume_before: float = float("nan")  # of the repaired patches as given (divergence theorem)
    volume_after: float = float("nan")
    area_added: float = 0.0  # m²: surface MeshFix added to close the open patches
    area_closed: float = 0.0  # m²: the closed patches' whole surface

    @property
    def changed(self) -> bool:
        return any((self.degenerate_faces, self.duplicate_faces, self.internal_walls, self.non_manifold_edges,
                    self.flipped_faces, self.open_edges, self.dropped_faces, self.t_junctions))

    def describe(self) -> str:
        """One line: what was repaired and how much the volume changed (empty if nothing was)."""
        parts = []
        if self.open_edges:
            parts.append(f"closed {self.closed_patches} open surface{'s' if self.closed_patches != 1 else ''} "
                         f"({self.open_edges} open edges)")
        for count, what in ((self.t_junctions, "faces split at T-junctions"),
                            (self.non_manifold_edges, "non-manifold edges split"),
                            (self.flipped_faces, "faces re-wound"),
                            (self.duplicate_faces, "duplicate faces dropped"),
                            (self.internal_walls, "internal wall faces dropped"),
                            (self.degenerate_faces, "degenerate triangles dropped"),
                            (self.dropped_faces, "faces of sheets enclosing no volume dropped")):
            if count:
                parts.append(f"{count} {what}")
        if not parts:
            return ""
        text = "repaired: " + ", ".join(parts)
        if self.open_edges and self.area_closed > 0:
            text += (f"; the closing added {100 * self.area_added / self.area_closed:.1f} % of their surface "
                     "(a large share means a guessed shape: check it with --replay)")
        if self.open_edges and np.isfinite(self.volume_before) and self.volume_before > 0:
            change = 100.0 * (self.volume_after - self.volume_before) / self.volume_before
            text += f", volume {change:+.1f} % against the open surface's"
        return text


def _face_edges(faces: np.ndarray) -> np.ndarray:
    """(3 m, 2) the faces' edges as sorted vertex pairs: edge k (from vertex k to k + 1) of face i in
    row k m + i."""
    return np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)


def _patches(faces: np.ndarray) -> tuple[list[np.ndarray], int]:
    """Face indices of each patch (faces joined across edges of exactly two faces), and the number
    of edges of three or more faces."""
    edges = _face_edges(faces)
    owner = np.tile(np.arange(len(faces)), 3)
    inverse, counts = _unique_rows(edges)
    pairs = owner[manifold_pairs(inverse, counts)]
    n = len(faces)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    count, labels = connected_components(graph, directed=False)
    groups = np.argsort(labels, kind="stable")
    splits = np.cumsum(np.bincount(labels, minlength=count))[:-1]
    return np.split(groups, splits), int(np.count_nonzero(counts > 2))


def closed_parts(mesh: trimesh.Trimesh) -> list[trimesh.Trimesh]:
    """The parts of a mesh of closed shells joined across manifold edges only: solids that meet
    along an edge or at a vertex come apart (each part is what CoACD or a hull takes)."""
    patches, _ = _patches(np.asarray(mesh.faces))
    parts = []
    for indices in patches:
        part = trimesh.Trimesh(mesh.vertices, mesh.faces[indices], process=False)
        part.remove_unreferenced_vertices()
        parts.append(part)
    return parts


def _open_edges(faces: np.ndarray) -> np.ndarray:
    """(faces, 3) bool: whether face i's edge k (from its vertex k to k + 1) belongs to no other face."""
    inverse, counts = _unique_rows(_face_edges(faces))
    return (counts[inverse] == 1).reshape(3, -1).T


def split_t_junctions(vertices: np.ndarray, faces: np.ndarray, tolerance: float) -> tuple[np.ndarray, int]:
    """(faces, how many were split): each face with an open edge on which vertices of the open boundary
    lie (within `tolerance`, m, strictly between its ends) replaced by a fan from its opposite vertex
    through them. A closed mesh, or one whose holes are real, comes back as it was."""
    faces = np.asarray(faces, np.int64)
    vertices = np.asarray(vertices, float)
    split = 0
    for _ in range(4):  # a face split along one open edge may have another
        is_open = _open_edges(faces)
        if not is_open.any():
            break
        boundary = np.unique(np.concatenate([faces[is_open], faces[np.roll(is_open, 1, axis=1)]]))
        tree = cKDTree(vertices[boundary])
        kept, added = np.ones(len(faces), bool), []
        for index in np.flatnonzero(is_open.any(axis=1)):
            face = faces[index]
            for k in np.flatnonzero(is_open[index]):
                a, b, c = face[k], face[(k + 1) % 3], face[(k + 2) % 3]
                start, along = vertices[a], vertices[b] - vertices[a]
                length = float(np.linalg.norm(along))
                if length <= 2.0 * tolerance:
                    continue
                on = []
                for j in tree.query_ball_point(start + 0.5 * along, 0.5 * length + tolerance):
                    v = boundary[j]
                    t = float((vertices[v] - start) @ along) / length**2
                    if (v not in (a, b) and tolerance < t * length < length - tolerance
                            and np.linalg.norm(start + t * along - vertices[v]) <= tolerance):
                        on.append((t, v))
                if on:
                    chain = [a] + [v for _, v in sorted(on)] + [b]
                    added.extend((chain[i], chain[i + 1], c) for i in range(len(chain) - 1))
                    kept[index] = False
                    split += 1
                    break
        if not added:
            break
        faces = np.concatenate([faces[kept], np.asarray(added, np.int64)])
    return faces, split


def _drop_duplicates(faces: np.ndarray, report: RepairReport) -> np.ndarray:
    """Faces with duplicates resolved: of copies wound opposite ways, pairs are dropped (internal
    walls); of the copies left (all wound one way), one is kept. Order is kept."""
    inverse, counts = _unique_rows(np.sort(faces, axis=1))
    a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
    forward = ((a < b).astype(int) + (b < c) + (c < a)) == 2  # an even rotation of the sorted order
    n_forward = np.bincount(inverse, weights=forward, minlength=len(counts)).astype(int)
    pairs = np.minimum(n_forward, counts - n_forward)
    rest = counts - 2 * pairs
    report.internal_walls += int(2 * pairs.sum())
    report.duplicate_faces += int(np.maximum(rest - 1, 0).sum())
    majority = n_forward > counts - n_forward  # the winding of the copies left
    candidates = np.flatnonzero((rest[inverse] > 0) & (forward == majority[inverse]))
    _, first = np.unique(inverse[candidates], return_index=True)
    keep = np.zeros(len(faces), dtype=bool)
    keep[candidates[first]] = True
    return faces[keep]


def _meshfix(patch: trimesh.Trimesh, open_edges: int = 0) -> trimesh.Trimesh | None:
    try:
        import pymeshfix  # Imported here: only open meshes need it (an optional extra, GPL-3).
    except ImportError:
        raise _MeshFixMissing(MESHFIX_MISSING.format(edges=open_edges)) from None

    fixer = pymeshfix.MeshFix(np.asarray(patch.vertices, float), np.asarray(patch.faces, np.int32))
    fixer.repair(joincomp=False, remove_smallest_components=False)
    vertices, faces = np.asarray(fixer.points, float), np.asarray(fixer.faces, np.int64)
    if len(faces) < 4:
        return None
    return trimesh.Trimesh(vertices, faces, process=True)


def _consistent_winding(faces: np.ndarray) -> np.ndarray:
    """The faces re-wound so that every two faces across a manifold edge traverse it in opposite
    directions: a breadth-first walk over the face adjacency from each patch's first face, each face
    wound as its parent in the walk says (level by level, vectorised)."""
    from scipy.sparse.csgraph import shortest_path

    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    owner = np.tile(np.arange(len(faces)), 3)
    inverse, counts = _unique_rows(np.sort(edges, axis=1))
    occurrences = manifold_pairs(inverse, counts)
    pairs = owner[occurrences]
    directed = edges[occurrences]
    # Two faces agree when they traverse their shared edge in opposite directions.
    disagree = (directed[:, 0, 0] == directed[:, 1, 0]).astype(float) + 1.0  # 1 agree, 2 disagree
    n = len(faces)
    relation = coo_matrix((np.concatenate([disagree, disagree]),
                           (np.concatenate([pairs[:, 0], pairs[:, 1]]), np.concatenate([pairs[:, 1], pairs[:, 0]]))),
                          shape=(n, n)).tocsr()
    count, labels = connected_components(relation, directed=False)
    flip = np.zeros(n, dtype=bool)
    starts = np.unique(labels, return_index=True)[1]
    for start in starts:
        if np.count_nonzero(labels == labels[start]) == 1:
            continue
        depth, parent = shortest_path(relation, indices=start, unweighted=True, return_predecessors=True)
        reached = np.flatnonzero(np.isfinite(depth) & (parent >= 0))
        against = np.asarray(relation[reached, parent[reached]]).ravel() == 2.0
        wrong = np.zeros(n, dtype=bool)
        wrong[reached] = against
        level = depth[reached].astype(int)
        for d in range(1, int(level.max(initial=0)) + 1):
            at = reached[level == d]
            flip[at] = flip[parent[at]] ^ wrong[at]
    faces = faces.copy()
    faces[flip] = faces[flip][:, ::-1]
    return faces


def _outward(patch: trimesh.Trimesh, report: RepairReport) -> trimesh.Trimesh:
    faces = _consistent_winding(patch.faces)
    flipped = np.any(faces != patch.faces, axis=1)
    patch = trimesh.Trimesh(patch.vertices, faces, process=False)
    if patch.is_watertight and patch.volume < 0:
        patch.invert()
        flipped = ~flipped
    # Count the faces whose winding changed against the majority (the file's own convention).
    report.flipped_faces += int(min(np.count_nonzero(flipped), np.count_nonzero(~flipped)))
    # Most of its faces had to turn: the file wound this shell inward (an inner wall of a hollow
    # object, when it lies inside a shell wound the other way: drake_grasp.objects.solid).
    patch.metadata["inward"] = bool(np.count_nonzero(flipped) > len(flipped) / 2)
    return patch


def _encloses_volume(patch: trimesh.Trimesh, open_extent: float | None = None, nearly_closed: bool = False
                     ) -> bool:
    """Whether a patch is a closed solid; `open_extent` (m), for a patch that had to be closed, is the
    largest extent of the open patch it came from (see MIN_CLOSED_THICKNESS), and `nearly_closed`
    whether that patch's holes were small (see MAX_HOLES_PERIMETER)."""
    if not (patch.is_watertight and patch.is_winding_consistent):
        return False
    try:
        hull = patch.convex_hull.volume
    except Exception:  # qhull: flat
        return False
    if not patch.volume > MIN_FILL_FRACTION * hull > 0.0:
        return False
    if nearly_closed:
        return True
    if open_extent is not None:
        return 2.0 * patch.volume / patch.area >= MIN_CLOSED_THICKNESS * open_extent
    return True


def _file_parts(mesh: trimesh.Trimesh) -> list[np.ndarray]:
    """Face indices of the file's own parts: faces joined by shared vertex indices (before any
    welding). A file that stores cells or hulls as separate vertex lists keeps them apart here; a
    triangle soup (STL) has no such parts, and one list of all faces is returned."""
    faces = mesh.faces
    n = len(mesh.vertices)
    rows = np.repeat(faces[:, 0], 2)
    cols = faces[:, 1:].ravel()
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    count, labels = connected_components(graph, directed=False)
    face_labels = labels[faces[:, 0]]
    used = np.unique(face_labels)
    if len(used) == 1 or len(used) > len(faces) / 4:
        return [np.arange(len(faces))]
    return [np.flatnonzero(face_labels == label) for label in used]


def closed_shells(mesh: trimesh.Trimesh, label: str = "mesh") -> tuple[list[trimesh.Trimesh], RepairReport]:
    """The closed, outward-wound shells of a mesh (metres), repaired as the module says.

    The file's own parts (vertex lists it keeps apart) that are closed once their own vertices are
    welded (cells, hulls) are repaired one by one, so that cells sharing a face are not welded into
    edges of four faces; the parts that are open on their own (a visual mesh split by material, a
    triangle soup) are welded together first, since together they may close.

    Raises:
        RepairError: nothing in the mesh encloses a volume (an open sheet, a flat patch).
    """
    report = RepairReport()
    mesh = trimesh.Trimesh(np.asarray(mesh.vertices, float), np.asarray(mesh.faces, np.int64), process=False)
    shells = []
    opened = [0.0, 0.0]
    parts = _file_parts(mesh)
    pooled = []
    try:
        for indices in parts:
            part = trimesh.Trimesh(mesh.vertices, mesh.faces[indices], process=False)
            if len(parts) > 1:
                welded = part.copy()
                welded.merge_vertices(merge_tex=True, merge_norm=True)
                if not welded.is_watertight:
                    pooled.append(indices)
                    continue
            shells += _part_shells(part, report, opened)
        if pooled:
            part = trimesh.Trimesh(mesh.vertices, mesh.faces[np.concatenate(pooled)], process=False)
            shells += _part_shells(part, report, opened)
    except _MeshFixMissing as missing:
        raise RepairError(f"{label}: {missing}") from None
    if report.closed_patches:
        report.volume_before, report.volume_after = opened
    if not shells:
        raise RepairError(f"{label}: an open surface that encloses no volume (a sheet): no solid can be recovered")
    return shells, report


def _closed_without(mesh: trimesh.Trimesh, dropped: np.ndarray) -> bool:
    """Whether `mesh`'s faces without the `dropped` ones are a closed, consistently wound 2-manifold
    (trimesh's watertight and winding checks)."""
    kept = trimesh.Trimesh(mesh.vertices, mesh.faces[~dropped], process=False)
    return len(kept.faces) > 0 and kept.is_watertight and kept.is_winding_consistent


def _part_shells(mesh: trimesh.Trimesh, report: RepairReport, opened: list) -> list[trimesh.Trimesh]:
    """Closed shells of one part of a file (steps 1-5), counted into `report`; `opened` adds the
    volumes of the open patches before and after closing them."""
    vertex_count = len(mesh.vertices)
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    report.welded_vertices += vertex_count - len(mesh.vertices)
    faces = mesh.faces
    scale = float(np.max(mesh.extents)) if len(faces) else 1.0
    repeated = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
    triangles = mesh.vertices[faces]
    doubled_area = np.linalg.norm(np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1)
    degenerate = repeated | (doubled_area <= (1e-9 * scale) ** 2)
    if np.any(degenerate & ~repeated) and _closed_without(mesh, repeated):
        # A closed surface whose only flaw is a collinear (zero-area) triangle: it is the sliver of a
        # T-junction (a vertex on its neighbour's edge, as a boolean union and a round to micrometres
        # leave), and dropping it would open a slit no hole filler closes. It is kept: it adds no area
        # and no volume.
        degenerate = repeated
    report.degenerate_faces += int(np.count_nonzero(degenerate))
    faces, split = split_t_junctions(mesh.vertices, faces[~degenerate], T_JUNCTION_TOLERANCE * scale)
    report.t_junctions += split
    faces = _drop_duplicates(faces, report)
    if len(faces) == 0:
        return []
    vertices, faces, pinched = open_pinched_edges(mesh.vertices, faces)
    patches, non_manifold = _patches(faces)
    report.non_manifold_edges += non_manifold + pinched
    shells = []
    for indices in patches:
        patch = trimesh.Trimesh(vertices, faces[indices], process=False)
        patch.remove_unreferenced_vertices()
        patch = _outward(patch, report)
        if not patch.is_watertight:
            boundary = patch.edges_sorted[trimesh.grouping.group_rows(patch.edges_sorted, require_count=1)]
            open_edges = len(boundary)
            perimeter = float(np.linalg.norm(np.diff(patch.vertices[boundary], axis=1), axis=2).sum())
            closed = _meshfix(patch, open_edges) if len(patch.faces) >= 3 else None
            if closed is not None:
                closed = _outward(closed, RepairReport())
                closed.metadata["inward"] = patch.metadata.get("inward", False)
            # Small holes, and a closing that kept most of the surface (MeshFix drops faces it finds
            # intersecting; it kept 90 % of a P-51's airframe).
            nearly_closed = (perimeter <= MAX_HOLES_PERIMETER * math.sqrt(float(patch.area)) and closed is not None
                             and closed.area >= 0.8 * patch.area)
            if closed is None or not _encloses_volume(closed, float(np.max(patch.extents)), nearly_closed):
                report.dropped_faces += len(patch.faces)
                continue
            report.open_edges += open_edges
            report.closed_patches += 1
            centred = patch.copy()
            centred.apply_translation(-patch.vertices.mean(axis=0))
            opened[0] += abs(float(centred.volume))
            opened[1] += float(closed.volume)
            report.area_added += max(float(closed.area) - float(patch.area), 0.0)
            report.area_closed += float(closed.area)
            patch = closed
        elif not _encloses_volume(patch):
            report.dropped_faces += len(patch.faces)
            continue
        shells.append(patch)
    return shells


def _used_vertices(mesh: trimesh.Trimesh) -> np.ndarray:
    """The distinct vertices the mesh's faces use (m)."""
    return np.unique(np.asarray(mesh.vertices, float)[np.unique(np.asarray(mesh.faces))], axis=0)


def surface_hull(mesh: trimesh.Trimesh) -> trimesh.Trimesh | None:
    """The convex hull of a mesh's vertices if it encloses a volume (not flat, not a line), else
    None: what Bullet, MuJoCo and Drake's point contact collide a model file's collision mesh as,
    whatever its triangles close. SAPIEN's PartNet-Mobility parts are open surfaces (a bottle's body
    a shell without thickness, open at its neck), so for a model file's collision mesh that encloses
    nothing, the hull is the only solid the file gives (`mesh_files` takes it, with a note)."""
    vertices = _used_vertices(mesh)
    if len(vertices) < 4:
        return None
    try:
        hull = trimesh.convex.convex_hull(vertices)
    except Exception:  # qhull: the points are flat or a line
        return None
    extent = float(np.max(hull.extents))
    return hull if hull.is_watertight and hull.volume > (1e-3 * extent) ** 3 else None


def convex_piece_hull(mesh: trimesh.Trimesh) -> trimesh.Trimesh | None:
    """The convex hull of a mesh whose vertices all lie on it (within 0.1 % of its extent) and which
    encloses a volume, else None. A model file's collision mesh is often a convex piece of a
    decomposition written with faces doubled or missing (pybullet's dinnerware: a plate's rim as six
    8-vertex pieces of 16 triangles, none closed); Bullet and MuJoCo collide a mesh as its hull, and
    so does Drake's point contact, so the hull is the solid the file means (`mesh_files` takes it for a
    model file's collision mesh that `closed_shells` cannot close; a bare mesh file is still refused)."""
    hull = surface_hull(mesh)
    if hull is None:
        return None
    vertices = _used_vertices(mesh)
    extent = float(np.max(hull.extents))
    normals, offsets = np.asarray(hull.face_normals), np.einsum("ij,ij->i", hull.face_normals, hull.triangles[:, 0])
    outside = vertices @ normals.T - offsets  # <= 0 inside every face's plane; 0 on the hull
    return hull if bool(np.all(outside.max(axis=1) > -1e-3 * extent)) else None
