"""Drake's tetrahedral ``.vtk`` meshes: read (legacy ASCII VTK, an unstructured grid of tetrahedra)
and reduced to their boundary surface.

Why: Drake's model files give a compliant hydroelastic object its volume as a tetrahedral mesh in a
``.vtk`` file (drake_models' yellow bell pepper: ``<drake:compliant_hydroelastic/>`` on
``veggies/assets/yellow_bell_pepper_no_stem_low.vtk``; the bowl's ``evo_bowl_fine44k.vtk``).
Neither trimesh nor pydrake reads it from Python. An object here is the solid its surface
encloses, decomposed into convex pieces for contact (docs/design.md §5.2), so the tetrahedra are
reduced to their boundary: the triangles that belong to exactly one tetrahedron, each wound with its
normal away from the tetrahedron's fourth vertex (outward). That surface then goes through the same
repair, joining, decomposition and mass properties as any mesh file. Drake's own pressure field on
the tetrahedra is not used: the scenario's contact model replaces the file's (as for every object).

Read: the legacy format's versions 2.0 to 4.2 (``CELLS n size`` followed by counted cells) and 5.1
(``OFFSETS`` and ``CONNECTIVITY`` arrays), ASCII, dataset ``UNSTRUCTURED_GRID``, cells of type 10
(VTK_TETRA). Point and cell data after the cells (Drake's files have none) are ignored.
"""

from __future__ import annotations

import numpy as np

from drake_grasp.objects.spec import ObjectError
from drake_grasp.objects.vtk_polydata import check_indices, counted_cells, is_number, offset_cells, vtk_header

VTK_TETRA = 10
_SECTIONS = ("POINTS", "CELLS", "CELL_TYPES", "POINT_DATA", "CELL_DATA", "FIELD", "METADATA")


def read_vtk(data: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3) float64, tetrahedra (m, 4) int64) of a legacy ASCII VTK unstructured grid.

    ObjectError (one line starting with `label`) for a file that is not legacy VTK, is binary, is
    not an unstructured grid, is shorter than its counts say, has points that are not finite, cell
    indices out of range, or cells other than tetrahedra.
    """
    header = vtk_header(data)  # the header alone: a binary file's data is not text
    if header is None:
        raise ObjectError(f"{label}: not a legacy VTK file (its first line is not '# vtk DataFile Version ...')")
    if header[1] != "ASCII":
        raise ObjectError(f"{label}: a {header[1] or 'non-ASCII'} VTK unstructured grid; only ASCII ones are read "
                          "(as Drake writes them; surfaces, DATASET POLYDATA, are read ASCII or binary)")
    try:
        lines = data.decode("ascii").split("\n", 3)
    except UnicodeDecodeError:
        raise ObjectError(f"{label}: an ASCII VTK file holding bytes that are not ASCII text") from None
    try:
        version = float(header[0].split("Version", 1)[1].split()[0])
    except (IndexError, ValueError):
        version = 2.0
    tokens = lines[3].split()
    if len(tokens) < 2 or tokens[0].upper() != "DATASET" or tokens[1].upper() != "UNSTRUCTURED_GRID":
        found = " ".join(tokens[:2]) or "nothing"
        raise ObjectError(f"{label}: VTK dataset is {found!r}, not DATASET UNSTRUCTURED_GRID (a tetrahedral mesh)")
    reader = _Tokens(tokens, 2, label)
    points = cells = types = None
    in_metadata = False
    while not reader.done():
        keyword = reader.next().upper()
        if keyword not in _SECTIONS:
            if not in_metadata:  # a number here: a section held more than its count said
                raise ObjectError(f"{label}: VTK file holds {keyword!r} where a section should start (a count "
                                  "disagrees with the numbers that follow it)")
            continue
        in_metadata = keyword == "METADATA"  # its contents run to the next section
        if keyword == "POINTS":
            count = reader.count("POINTS")
            reader.next()  # the data type: float or double
            points = reader.numbers(3 * count, float, "POINTS").reshape(-1, 3)
        elif keyword == "CELLS":
            cells = _cells(reader, version)
        elif keyword == "CELL_TYPES":
            types = reader.numbers(reader.count("CELL_TYPES"), np.int64, "CELL_TYPES")
        elif keyword in ("POINT_DATA", "CELL_DATA", "FIELD"):
            break
    if points is None or cells is None:
        raise ObjectError(f"{label}: VTK file has no {'POINTS' if points is None else 'CELLS'} section")
    if types is not None and len(types) != len(cells):
        raise ObjectError(f"{label}: VTK file has {len(cells)} cells but {len(types)} cell types")
    if not np.all(np.isfinite(points)):
        bad = int(np.count_nonzero(~np.isfinite(points).all(axis=1)))
        raise ObjectError(f"{label}: {bad} of the VTK file's {len(points)} points are not finite (NaN or inf)")
    kinds = np.asarray(types if types is not None else [VTK_TETRA if len(c) == 4 else -1 for c in cells])
    others = sorted(set(int(k) for k in kinds) - {VTK_TETRA})
    if others or any(len(c) != 4 for c in cells):
        raise ObjectError(f"{label}: VTK cells of type {', '.join(map(str, others)) or 'other'}; only tetrahedra "
                          "(type 10, as in Drake's hydroelastic meshes) are read")
    if not cells:
        raise ObjectError(f"{label}: VTK file has no tetrahedra")
    tets = np.asarray(cells, np.int64)
    check_indices(tets, len(points), label, "cell")
    return points, tets


class _Tokens:
    """The whitespace-separated tokens of a VTK file's body, read in order."""

    def __init__(self, tokens: list[str], start: int, label: str):
        self.tokens, self.i, self.label = tokens, start, label

    def done(self) -> bool:
        return self.i >= len(self.tokens)

    def next(self) -> str:
        if self.done():
            raise ObjectError(f"{self.label}: VTK file ends early (truncated)")
        self.i += 1
        return self.tokens[self.i - 1]

    def count(self, section: str) -> int:
        text = self.next()
        try:
            value = int(text)
        except ValueError:
            raise ObjectError(f"{self.label}: VTK {section} count {text!r} is not a whole number") from None
        if value < 0:
            raise ObjectError(f"{self.label}: VTK {section} count {value} is negative")
        return value

    def numbers(self, count: int, dtype, section: str) -> np.ndarray:
        chunk = self.tokens[self.i:self.i + count]
        if len(chunk) < count:
            raise ObjectError(f"{self.label}: VTK {section} section is truncated: {len(chunk):,} of {count:,} "
                              "numbers")
        try:
            values = np.array(chunk, dtype=float)
        except ValueError:
            bad = next(t for t in chunk if not is_number(t))
            raise ObjectError(f"{self.label}: VTK {section} section holds {bad!r}, not a number") from None
        self.i += count
        if dtype is not float:
            if not np.all(values == np.round(values)):
                raise ObjectError(f"{self.label}: VTK {section} section holds a fraction where an index belongs")
            return values.astype(dtype)
        return values


def _cells(reader: _Tokens, version: float) -> list[np.ndarray]:
    """The cells' point indices: version 5 and later as OFFSETS and CONNECTIVITY arrays, before
    that as counted lists (n i0 ... in-1)."""
    first, second = reader.count("CELLS"), reader.count("CELLS")
    if version >= 5.0:
        offsets = connectivity = None
        for _ in range(2):
            keyword = reader.next().upper()
            reader.next()  # the array's type, e.g. vtktypeint64
            if keyword == "OFFSETS":
                offsets = reader.numbers(first, np.int64, "OFFSETS")
            elif keyword == "CONNECTIVITY":
                connectivity = reader.numbers(second, np.int64, "CONNECTIVITY")
        if offsets is None or connectivity is None:
            raise ObjectError(f"{reader.label}: VTK 5 CELLS section without OFFSETS and CONNECTIVITY")
        return offset_cells(offsets, connectivity, reader.label, "CELLS")
    return counted_cells(reader.numbers(second, np.int64, "CELLS"), first, second, reader.label, "CELLS")


def boundary_surface(points: np.ndarray, tets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, faces) of a tetrahedral mesh's boundary: the triangles of exactly one
    tetrahedron, each wound outward (its normal away from that tetrahedron's fourth vertex); only
    the vertices the boundary uses are kept (renumbered)."""
    points, tets = np.asarray(points, float), np.asarray(tets, np.int64)
    # Each tetrahedron's four faces, each with the vertex opposite it.
    order = np.array([[1, 2, 3, 0], [0, 2, 3, 1], [0, 1, 3, 2], [0, 1, 2, 3]])
    quads = tets[:, order].reshape(-1, 4)
    faces, opposite = quads[:, :3], quads[:, 3]
    _, inverse, counts = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True, return_counts=True)
    once = counts[inverse.ravel()] == 1
    faces, opposite = faces[once], opposite[once]
    a, b, c = (points[faces[:, i]] for i in range(3))
    inward = np.einsum("ij,ij->i", np.cross(b - a, c - a), points[opposite] - a) > 0
    faces[inward] = faces[inward][:, ::-1]
    used, renumbered = np.unique(faces, return_inverse=True)
    return points[used], renumbered.reshape(-1, 3).astype(np.int64)


def vtk_text(points, tets, title: str = "Tetrahedral mesh") -> str:
    """A legacy ASCII VTK (version 2.0) unstructured grid of tetrahedra, as Drake writes its
    hydroelastic meshes: for tests and conversions."""
    points, tets = np.asarray(points, float).reshape(-1, 3), np.asarray(tets, np.int64).reshape(-1, 4)
    lines = ["# vtk DataFile Version 2.0", title, "ASCII", "DATASET UNSTRUCTURED_GRID", f"POINTS {len(points)} double"]
    lines += [" ".join(repr(float(v)) for v in p) for p in points]
    lines.append(f"CELLS {len(tets)} {5 * len(tets)}")
    lines += ["4 " + " ".join(str(int(i)) for i in t) for t in tets]
    lines.append(f"CELL_TYPES {len(tets)}")
    lines += [str(VTK_TETRA)] * len(tets)
    return "\n".join(lines) + "\n"
