"""MuJoCo's binary ``.msh`` mesh format: read (checked) and written.

Why: MuJoCo-based benchmarks ship objects as MJCF files whose mesh assets are ``.msh`` files
(robosuite's can, cereal, lemon and milk name ``meshes/can.msh`` and the like), a format neither
trimesh nor Drake reads. It is small enough to read here, and a damaged file must be refused with a
line that says what is wrong, not read as garbage.

The format (MuJoCo's documentation, "mesh" asset, and ``user_mesh.cc``): four little-endian int32
counts ``nvertex, nnormal, ntexcoord, nface``, then float32 positions (3 × nvertex), normals
(3 × nnormal), texture coordinates (2 × ntexcoord), then int32 vertex indices of the triangles
(3 × nface), nothing after. Positions are in the file's units (MJCF ``scale`` applies after).
MuJoCo needs at least 4 vertices; a file with no faces is a point cloud whose convex hull MuJoCo
collides, and so is it here. Normals and texture coordinates are visual only and are skipped.
"""

from __future__ import annotations

import numpy as np

from drake_grasp.objects.spec import ObjectError

HEADER_BYTES = 16  # four int32 counts
_COUNTS = ("nvertex", "nnormal", "ntexcoord", "nface")


def read_msh(data: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3) float64, faces (m, 3) int64) of a ``.msh`` file's bytes.

    A file without faces gets its vertices' convex hull (as MuJoCo does). ObjectError (one line
    starting with `label`) for a file shorter than its header, a negative count, fewer than 4
    vertices, counts that disagree with the file's length (truncated, padded, or not a ``.msh``),
    vertices that are not finite, or a face index out of range.
    """
    if data.lstrip()[:11] == b"$MeshFormat":
        raise ObjectError(f"{label}: a Gmsh mesh (text .msh), not MuJoCo's binary .msh; export it as OBJ or STL")
    if len(data) < HEADER_BYTES:
        raise ObjectError(f"{label}: not a MuJoCo .msh file: {len(data)} bytes, shorter than its 16-byte header")
    counts = np.frombuffer(data[:HEADER_BYTES], dtype="<i4").astype(np.int64)
    named = ", ".join(f"{n} {c}" for n, c in zip(_COUNTS, counts))
    negative = [n for n, c in zip(_COUNTS, counts) if c < 0]
    if negative:
        raise ObjectError(f"{label}: damaged .msh file: negative count ({named})")
    nvertex, nnormal, ntexcoord, nface = (int(c) for c in counts)
    expected = HEADER_BYTES + 4 * (3 * nvertex + 3 * nnormal + 2 * ntexcoord + 3 * nface)
    if expected != len(data):
        what = "truncated" if expected > len(data) else "longer than its counts say"
        raise ObjectError(f"{label}: damaged .msh file ({what}): its counts ({named}) need {expected:,} bytes, "
                          f"the file has {len(data):,}")
    if nvertex < 4:
        raise ObjectError(f"{label}: .msh file has {nvertex} vertices; a mesh needs at least 4")
    start = HEADER_BYTES
    vertices = np.frombuffer(data, dtype="<f4", count=3 * nvertex, offset=start).reshape(-1, 3).astype(np.float64)
    start += 4 * (3 * nvertex + 3 * nnormal + 2 * ntexcoord)
    faces = np.frombuffer(data, dtype="<i4", count=3 * nface, offset=start).reshape(-1, 3).astype(np.int64)
    bad = int(np.count_nonzero(~np.isfinite(vertices).all(axis=1)))
    if bad:
        raise ObjectError(f"{label}: damaged .msh file: {bad} of its {nvertex} vertices are not finite (NaN or inf)")
    if len(faces):
        out = (faces < 0) | (faces >= nvertex)
        if np.any(out):
            first = int(faces[out][0])
            raise ObjectError(f"{label}: damaged .msh file: {int(np.count_nonzero(out))} face indices out of range "
                              f"(e.g. {first}; vertices are 0 to {nvertex - 1})")
        return vertices, faces
    return vertices, _hull_faces(vertices, label)


def _hull_faces(vertices: np.ndarray, label: str) -> np.ndarray:
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(vertices)
    except QhullError:
        raise ObjectError(f"{label}: .msh file has no faces and its vertices are flat (no hull)") from None
    faces = np.asarray(hull.simplices, np.int64)
    # Qhull does not orient its facets: wind each outward (its normal away from the centroid).
    centre = vertices[hull.vertices].mean(axis=0)
    a, b, c = (vertices[faces[:, i]] for i in range(3))
    inward = np.einsum("ij,ij->i", np.cross(b - a, c - a), a - centre) < 0
    faces[inward] = faces[inward][:, ::-1]
    return faces


def msh_bytes(vertices, faces, normals=None, texcoords=None) -> bytes:
    """A ``.msh`` file's bytes for `vertices` (n, 3), `faces` (m, 3) and optional per-vertex
    `normals` (n, 3) and `texcoords` (n, 2): what MuJoCo writes, for tests and conversions."""
    vertices = np.asarray(vertices, "<f4").reshape(-1, 3)
    faces = np.asarray(faces, "<i4").reshape(-1, 3)
    normals = np.zeros((0, 3), "<f4") if normals is None else np.asarray(normals, "<f4").reshape(-1, 3)
    texcoords = np.zeros((0, 2), "<f4") if texcoords is None else np.asarray(texcoords, "<f4").reshape(-1, 2)
    header = np.array([len(vertices), len(normals), len(texcoords), len(faces)], "<i4")
    return b"".join(a.tobytes() for a in (header, vertices, normals, texcoords, faces))
