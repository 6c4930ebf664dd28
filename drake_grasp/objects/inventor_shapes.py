"""The shapes of Open Inventor and VRML files as triangles in their own frame (file units): the
primitives tessellated, the face and strip sets' polygons and strips cut into triangles.

Conventions (Open Inventor's and VRML's): primitives are centred on their origin; a ``Cube`` spans
width × height × depth along x, y, z (VRML's ``Box``: size); ``Cylinder`` and ``Cone`` stand along y
(the cone's apex at +height/2); defaults are 2 units across. A polygon of an indexed set ends at a
-1; a strip's triangles alternate their turn, so every second one is reversed to keep the winding.
Used by :mod:`drake_grasp.objects.inventor_mesh`.
"""

from __future__ import annotations

import numpy as np
import trimesh

from drake_grasp.objects.inventor_scene import Node


def primitive(walk, node: Node) -> tuple[np.ndarray, np.ndarray] | None:
    """(vertices, faces) of a primitive shape node (Cube, Box, Cylinder, Cone, Sphere), or None for
    any other node. Sizes must not be negative (ObjectError through `walk`)."""
    from drake_grasp.objects.inventor_mesh import SEGMENTS, SPHERE_SUBDIVISIONS

    kind = node.type
    if kind == "Cube":
        size = np.concatenate([walk.numbers(node, field, (2.0,), 1) for field in ("width", "height", "depth")])
    elif kind == "Box":
        size = walk.numbers(node, "size", (2.0, 2.0, 2.0), 3)
    elif kind in ("Cylinder", "Cone"):
        radius = walk.numbers(node, "radius" if kind == "Cylinder" else "bottomRadius", (1.0,), 1)
        size = np.concatenate([radius, walk.numbers(node, "height", (2.0,), 1)])
    elif kind == "Sphere":
        size = walk.numbers(node, "radius", (1.0,), 1)
    else:
        return None
    if np.any(size < 0.0):
        walk.fail(node, f"a negative size ({', '.join(f'{s:g}' for s in size)})")
    if kind in ("Cube", "Box"):
        mesh = trimesh.creation.box(extents=size)
    elif kind == "Sphere":
        mesh = trimesh.creation.icosphere(subdivisions=SPHERE_SUBDIVISIONS, radius=size[0])
    else:
        radius, height = size
        if kind == "Cylinder":
            mesh = trimesh.creation.cylinder(radius=radius, height=height, sections=SEGMENTS)
        else:  # trimesh's cone stands on z = 0 with its apex at z = height
            mesh = trimesh.creation.cone(radius=radius, height=height, sections=SEGMENTS)
            mesh.apply_translation([0.0, 0.0, -height / 2.0])
        # Along z as trimesh makes them; Inventor's stand along y: turn z to y (x by -90°).
        mesh.apply_transform(np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0], [0, -1.0, 0, 0], [0, 0, 0, 1.0]]))
    return np.asarray(mesh.vertices, float), np.asarray(mesh.faces, np.int64)


def vertex_shape(walk, node: Node, coords: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of a face set, triangle strip set or quad mesh over `coords`."""
    kind = node.type
    if kind in ("IndexedFaceSet", "IndexedTriangleStripSet"):
        index = walk.indices(node, "coordIndex")
        used = index[index >= 0]
        if len(used) and used.max() >= len(coords):
            walk.fail(node, f"coordIndex {int(used.max())} is out of range (the coordinates are 0 to "
                      f"{len(coords) - 1})")
        starts, counts = _runs(index)
        cut = fans if kind == "IndexedFaceSet" else _strips
        return coords, cut(index, starts, counts)
    start = int(walk.indices(node, "startIndex")[0]) if "startIndex" in node.fields else 0
    if kind == "QuadMesh":
        rows = int(walk.indices(node, "verticesPerColumn")[0]) if "verticesPerColumn" in node.fields else 1
        columns = int(walk.indices(node, "verticesPerRow")[0]) if "verticesPerRow" in node.fields else 1
        _check_count(walk, node, start, rows * columns, len(coords))
        grid = start + np.arange(rows * columns).reshape(rows, columns)
        a, b, c, d = grid[:-1, :-1].ravel(), grid[:-1, 1:].ravel(), grid[1:, 1:].ravel(), grid[1:, :-1].ravel()
        return coords, np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    counts = walk.indices(node, "numVertices") if "numVertices" in node.fields else np.array([-1])
    filled, at = [], start
    for count in counts.tolist() if np.any(counts < 0) else ():
        count = len(coords) - at if count < 0 else count  # -1: the rest of the coordinates
        filled.append(count)
        at += count
    counts = np.array(filled, np.int64) if filled else counts
    _check_count(walk, node, start, int(counts.sum()), len(coords))
    starts = start + np.cumsum(counts) - counts
    cut = fans if kind == "FaceSet" else _strips
    return coords, cut(np.arange(len(coords)), starts, counts)


def _check_count(walk, node: Node, start: int, needed: int, available: int) -> None:
    if start < 0 or start + needed > available:
        walk.fail(node, f"needs coordinates {start} to {start + needed - 1}; there are {available}")


def _runs(index: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(start, length) of each run of an index list between its negative entries (-1 ends a
    polygon or a strip; a last one without it counts too)."""
    ends = np.flatnonzero(index < 0)
    starts = np.concatenate([[0], ends + 1])
    stops = np.concatenate([ends, [len(index)]])
    return starts, stops - starts


def _within(counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For runs of `counts` vertices (those of 3 or more), which run each of their `count - 2`
    triangles belongs to and its position k within the run."""
    triangles = counts - 2
    run = np.repeat(np.arange(len(counts)), triangles)
    k = np.arange(int(triangles.sum())) - np.repeat(np.cumsum(triangles) - triangles, triangles)
    return run, k


def fans(index: np.ndarray, starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Triangles (m, 3) of polygons, each a fan from its first vertex: `index` holds the polygons'
    vertex indices one after another, polygon i at `starts[i]` with `counts[i]` vertices (those under
    3 are skipped). Shared by Inventor's face sets and USD's meshes."""
    keep = counts >= 3
    starts, counts = starts[keep], counts[keep]
    run, k = _within(counts)
    first = starts[run]
    return np.column_stack([index[first], index[first + k + 1], index[first + k + 2]]).astype(np.int64)


def _strips(index: np.ndarray, starts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Triangles (m, 3) of triangle strips: (k, k+1, k+2), every second one turned (k+1, k, k+2)."""
    keep = counts >= 3
    starts, counts = starts[keep], counts[keep]
    run, k = _within(counts)
    at = starts[run] + k
    odd = k % 2 == 1
    a = np.where(odd, index[at + 1], index[at])
    b = np.where(odd, index[at], index[at + 1])
    return np.column_stack([a, b, index[at + 2]]).astype(np.int64)
