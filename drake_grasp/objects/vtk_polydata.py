"""Surface meshes in legacy VTK files (``DATASET POLYDATA``), ASCII or binary, read as triangles.

Why: the Point Cloud Library and the tools around it (``pcl_ply2vtk``, ``pcl_mesh2vtk``, VTK's own
writers) save a scanned object's surface as a legacy ``.vtk`` file of polygons, most often binary.
Object collections of grasping labs ship them so: the Columbia grasping group's household objects
(CURG-BCI/object_models: a mustard bottle, mugs, blocks and fruit as binary POLYDATA, in
millimetres). Neither trimesh nor pydrake reads them from Python. Drake's own ``.vtk`` files are
tetrahedral volumes (:mod:`drake_grasp.objects.vtk_mesh`); this module reads the other kind.

Read: the legacy format's versions 2.0 to 4.2 (each cell section ``POLYGONS n size`` followed by
counted lists ``k i0 ... ik-1``) and 5.1 (``OFFSETS`` and ``CONNECTIVITY`` arrays); ASCII or
BINARY (big-endian, as the format prescribes); ``POINTS`` as float or double. ``POLYGONS`` become
triangle fans and ``TRIANGLE_STRIPS`` triangles; ``VERTICES`` and ``LINES`` hold no surface and are
skipped, and so is everything from ``POINT_DATA``, ``CELL_DATA`` or ``FIELD`` on (normals, colours).
The triangles are in the file's own units and frame: `--scale` converts millimetres.
"""

from __future__ import annotations

import numpy as np

from drake_grasp.objects.spec import ObjectError

# The legacy format's data types, big-endian in a binary file.
_DTYPES = {
    "float": ">f4", "double": ">f8", "int": ">i4", "unsigned_int": ">u4", "long": ">i8",
    "unsigned_long": ">u8", "short": ">i2", "unsigned_short": ">u2", "char": ">i1", "unsigned_char": ">u1",
    "bit": ">u1", "vtktypeint64": ">i8", "vtktypeint32": ">i4", "vtktypeuint64": ">u8", "vtktypeuint32": ">u4",
}
_CELL_SECTIONS = ("VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS")
_DATA_SECTIONS = ("POINT_DATA", "CELL_DATA", "FIELD")
_WHITESPACE = b" \t\r\n"


def vtk_header(data: bytes) -> tuple[str, str, str] | None:
    """(version line, ``ASCII`` or ``BINARY``, the DATASET line) of a legacy VTK file, or None if its
    first line is not ``# vtk DataFile Version ...``. Only the four header lines are decoded: the
    data of a binary file is not text."""
    lines = data.split(b"\n", 4)
    if len(lines) < 4:
        return None
    try:
        version, _, encoding, dataset = (line.decode("ascii").strip() for line in lines[:4])
    except UnicodeDecodeError:
        return None
    if not version.startswith("# vtk DataFile Version"):
        return None
    return version, encoding.upper(), dataset


def is_polydata(data: bytes) -> bool:
    """Whether `data` is a legacy VTK file whose dataset is POLYDATA."""
    header = vtk_header(data)
    return header is not None and header[2].split()[1:2] == ["POLYDATA"]


def read_polydata(data: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3) float64, triangles (m, 3) int64) of a legacy VTK POLYDATA file.

    ObjectError (one line starting with `label`) for a file that is not legacy VTK POLYDATA, whose
    encoding is neither ASCII nor BINARY, that is shorter than its counts say, whose points are not
    finite, whose indices are out of range, or that holds no polygon or triangle strip.
    """
    header = vtk_header(data)
    if header is None:
        raise ObjectError(f"{label}: not a legacy VTK file (its first line is not '# vtk DataFile Version ...')")
    version_line, encoding, dataset = header
    if dataset.split()[:2] != ["DATASET", "POLYDATA"]:
        raise ObjectError(f"{label}: VTK dataset is {dataset!r}, not DATASET POLYDATA")
    if encoding not in ("ASCII", "BINARY"):
        raise ObjectError(f"{label}: VTK encoding {encoding!r} is neither ASCII nor BINARY")
    try:
        version = float(version_line.split("Version", 1)[1].split()[0])
    except (IndexError, ValueError):
        version = 2.0
    start = sum(len(line) + 1 for line in data.split(b"\n", 4)[:4])
    cursor = _Cursor(data, start, encoding == "BINARY", label)
    points, triangles = None, []
    while True:
        keyword = cursor.word()
        if keyword is None or keyword.upper() in _DATA_SECTIONS:
            break
        keyword = keyword.upper()
        if keyword == "POINTS":
            count = cursor.count("POINTS")
            points = cursor.numbers(3 * count, cursor.word() or "", "POINTS").astype(float).reshape(-1, 3)
        elif keyword in _CELL_SECTIONS:
            cells = _cells(cursor, keyword, version)
            if keyword == "POLYGONS":
                triangles += [_fan(cell) for cell in cells if len(cell) >= 3]
            elif keyword == "TRIANGLE_STRIPS":
                triangles += [_strip(cell) for cell in cells if len(cell) >= 3]
        elif keyword == "METADATA":
            cursor.skip_metadata()
        else:
            raise ObjectError(f"{label}: VTK file holds {keyword[:40]!r} where a section should start (a count "
                              "disagrees with the numbers that follow it)")
    if points is None:
        raise ObjectError(f"{label}: VTK file has no POINTS section")
    if not np.all(np.isfinite(points)):
        bad = int(np.count_nonzero(~np.isfinite(points).all(axis=1)))
        raise ObjectError(f"{label}: {bad} of the VTK file's {len(points)} points are not finite (NaN or inf)")
    if not triangles:
        raise ObjectError(f"{label}: VTK file holds no polygons or triangle strips: no surface (a point cloud?)")
    faces = np.vstack(triangles).astype(np.int64)
    check_indices(faces, len(points), label, "polygon")
    return points, faces


def check_indices(indices: np.ndarray, points: int, label: str, kind: str) -> None:
    """ObjectError naming how many of a VTK file's `kind` (cell, polygon) indices fall outside its
    `points` points. Shared with the tetrahedral reader."""
    out = (indices < 0) | (indices >= points)
    if np.any(out):
        raise ObjectError(f"{label}: {int(np.count_nonzero(out))} VTK {kind} indices out of range (e.g. "
                          f"{int(indices[out][0])}; points are 0 to {points - 1})")


class _Cursor:
    """Reads a legacy VTK file's body after its header: keywords and counts as ASCII words, data as
    ASCII numbers or, in a binary file, big-endian arrays that follow their keyword's line."""

    def __init__(self, data: bytes, position: int, binary: bool, label: str):
        self.data, self.i, self.binary, self.label = data, position, binary, label

    def word(self) -> str | None:
        """The next whitespace-separated word (None at the end of the file)."""
        data, n = self.data, len(self.data)
        while self.i < n and data[self.i] in _WHITESPACE:
            self.i += 1
        if self.i >= n:
            return None
        start = self.i
        while self.i < n and data[self.i] not in _WHITESPACE:
            self.i += 1
        try:
            return data[start:self.i].decode("ascii")
        except UnicodeDecodeError:
            raise ObjectError(f"{self.label}: VTK file holds binary data where a section should start (a count "
                              "disagrees with the data that follows it)") from None

    def count(self, section: str) -> int:
        text = self.word()
        try:
            value = int(text or "")
        except ValueError:
            raise ObjectError(f"{self.label}: VTK {section} count {text!r} is not a whole number") from None
        if value < 0:
            raise ObjectError(f"{self.label}: VTK {section} count {value} is negative")
        return value

    def numbers(self, count: int, vtk_type: str, section: str) -> np.ndarray:
        """`count` numbers of the data type `vtk_type` (binary) or as ASCII words."""
        if self.binary:
            dtype = _DTYPES.get(vtk_type.lower())
            if dtype is None:
                raise ObjectError(f"{self.label}: VTK {section} data type {vtk_type!r} is not one the format defines")
            # The data starts after the end of its keyword's line.
            while self.i < len(self.data) and self.data[self.i] in b" \t\r":
                self.i += 1
            if self.i < len(self.data) and self.data[self.i] == ord("\n"):
                self.i += 1
            size = count * np.dtype(dtype).itemsize
            if self.i + size > len(self.data):
                raise ObjectError(f"{self.label}: VTK {section} section is truncated: {(len(self.data) - self.i):,} "
                                  f"of {size:,} bytes")
            values = np.frombuffer(self.data, dtype=dtype, count=count, offset=self.i)
            self.i += size
            return values.astype(np.float64 if values.dtype.kind == "f" else np.int64)
        words = [self.word() for _ in range(count)]
        if words and words[-1] is None:
            read = sum(w is not None for w in words)
            raise ObjectError(f"{self.label}: VTK {section} section is truncated: {read:,} of {count:,} numbers")
        try:
            return np.array(words, dtype=float)
        except ValueError:
            bad = next(w for w in words if not is_number(w))
            raise ObjectError(f"{self.label}: VTK {section} section holds {bad!r}, not a number") from None

    def skip_metadata(self) -> None:
        """A version 5 METADATA block: ASCII lines up to the next blank line."""
        end = self.data.find(b"\n\n", self.i)
        self.i = len(self.data) if end < 0 else end + 2


def is_number(text: str) -> bool:
    """Whether a word of a VTK file reads as a number (for naming the one that does not)."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def _cells(cursor: _Cursor, section: str, version: float) -> list[np.ndarray]:
    """A cell section's point lists: version 5 and later as OFFSETS and CONNECTIVITY arrays, before
    that as counted lists (k i0 ... ik-1) of ``int``."""
    first, second = cursor.count(section), cursor.count(section)
    if version >= 5.0:
        arrays = {}
        for _ in range(2):
            name = (cursor.word() or "").upper()
            kind = cursor.word() or ""
            if name not in ("OFFSETS", "CONNECTIVITY"):
                raise ObjectError(f"{cursor.label}: VTK 5 {section} section without OFFSETS and CONNECTIVITY")
            arrays[name] = _indices(cursor.numbers(first if name == "OFFSETS" else second, kind, name), cursor.label,
                                    name)
        return offset_cells(arrays["OFFSETS"], arrays["CONNECTIVITY"], cursor.label, section)
    return counted_cells(_indices(cursor.numbers(second, "int", section), cursor.label, section), first, second,
                         cursor.label, section)


def offset_cells(offsets: np.ndarray, connectivity: np.ndarray, label: str, section: str) -> list[np.ndarray]:
    """A version 5 cell section's point lists from its OFFSETS and CONNECTIVITY arrays (ObjectError if
    the offsets do not index the connectivity). Shared with the tetrahedral reader."""
    if len(offsets) == 0 or offsets[0] != 0 or offsets[-1] != len(connectivity) or np.any(np.diff(offsets) < 0):
        raise ObjectError(f"{label}: VTK {section} OFFSETS do not index the CONNECTIVITY array")
    return [connectivity[a:b] for a, b in zip(offsets[:-1], offsets[1:])]


def counted_cells(flat: np.ndarray, first: int, second: int, label: str, section: str) -> list[np.ndarray]:
    """The point lists of a cell section of versions 2-4: `first` counted lists (k i0 ... ik-1) in
    `second` numbers `flat` (ObjectError if they disagree). Shared with the tetrahedral reader."""
    cells, i = [], 0
    for _ in range(first):
        if i >= len(flat) or flat[i] < 0 or i + 1 + flat[i] > len(flat):
            raise ObjectError(f"{label}: VTK {section} section does not hold the {first:,} cells it counts")
        cells.append(flat[i + 1:i + 1 + flat[i]])
        i += 1 + int(flat[i])
    if i != len(flat):
        raise ObjectError(f"{label}: VTK {section} size {second:,} disagrees with its {first:,} cells")
    return cells


def _indices(values: np.ndarray, label: str, section: str) -> np.ndarray:
    if not np.all(values == np.round(values)):
        raise ObjectError(f"{label}: VTK {section} section holds a fraction where an index belongs")
    return values.astype(np.int64)


def _fan(polygon: np.ndarray) -> np.ndarray:
    """A convex polygon's triangles (i0, ik, ik+1), wound as the polygon is."""
    return np.column_stack([np.full(len(polygon) - 2, polygon[0]), polygon[1:-1], polygon[2:]])


def _strip(strip: np.ndarray) -> np.ndarray:
    """A triangle strip's triangles, every second one reversed so that all keep the strip's winding."""
    triangles = np.column_stack([strip[:-2], strip[1:-1], strip[2:]])
    triangles[1::2] = triangles[1::2][:, [1, 0, 2]]
    return triangles


def polydata_bytes(vertices, faces, binary: bool = True, version: str = "3.0") -> bytes:
    """A legacy VTK POLYDATA file of `vertices` and polygons `faces` (one row each, any size), as PCL
    and VTK write them (``POINTS ... float``, counted ``POLYGONS``): for tests and conversions."""
    vertices, faces = np.asarray(vertices, float).reshape(-1, 3), np.asarray(faces, np.int64)
    encoding = "BINARY" if binary else "ASCII"
    head = f"# vtk DataFile Version {version}\nvtk output\n{encoding}\nDATASET POLYDATA\nPOINTS {len(vertices)} float\n"
    cells = np.column_stack([np.full(len(faces), faces.shape[1]), faces])
    polygons = f"\nPOLYGONS {len(faces)} {cells.size}\n"
    if binary:
        return (head.encode() + vertices.astype(">f4").tobytes() + polygons.encode() + cells.astype(">i4").tobytes()
                + b"\n")
    body = "\n".join(" ".join(repr(float(v)) for v in p) for p in vertices)
    rows = "\n".join(" ".join(str(int(i)) for i in c) for c in cells)
    return (head + body + polygons + rows + "\n").encode()
