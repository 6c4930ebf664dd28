"""Open Inventor ASCII and VRML (2.0 and 1.0) files read as triangles, in the file's units and frame.

Why: GraspIt!'s objects and many older robotics models are Inventor (``.iv``) or VRML (``.wrl``)
files, which Coin reads for GraspIt; trimesh and Drake read neither. The scene graph
(:mod:`drake_grasp.objects.inventor_scene`) is walked as Coin renders it, and every shape it draws
becomes triangles where the walk puts it.

The walk: Inventor's transform nodes (``Transform``, ``Translation``, ``Rotation``, ``RotationXYZ``,
``Scale``, ``MatrixTransform``, ``ResetTransform``, ``Units``) post-multiply the current matrix, so
the node nearest a shape applies first; a ``Separator`` (and ``Selection``, ``WWWAnchor``) keeps
its children's transforms and coordinates to itself, a ``TransformSeparator`` its transforms, a
``Group`` neither. ``Switch`` draws the child ``whichChild`` names (none by default), ``LOD`` its first.
``Coordinate3``, ``Coordinate4`` and ``VertexProperty`` set the coordinates the vertex-based shapes
use, unless a shape names its own (``vertexProperty``, VRML's ``coord``). In a VRML 2.0 file,
``Transform`` (translation, rotation, scale, scaleOrientation, center) and ``Group``, ``Collision``,
``Anchor``, ``Billboard`` group their ``children`` with their own scope, ``Shape`` draws its
``geometry``, ``Switch`` its ``choice`` and ``LOD`` its first ``level``; Inventor nodes among them are
drawn too (GraspIt's ashtray puts an Inventor ``Cube`` in a VRML ``Transform``).

Shapes: ``IndexedFaceSet`` and ``FaceSet`` (polygons as triangle fans; a -1 ends a polygon),
``IndexedTriangleStripSet`` and ``TriangleStripSet`` (strips, alternate triangles turned), ``QuadMesh``,
and the primitives, centred on their origin: ``Cube`` (width, height, depth along x, y, z: exact)
and VRML's ``Box`` (size); ``Cylinder`` (radius, height along y) and ``Cone`` (bottomRadius, height
along y, apex up) as 32-sided prisms and pyramids; ``Sphere`` (radius) as an icosphere of 1,280
triangles. A primitive is always closed (Inventor's ``parts`` are not read). Faces wound clockwise
(``ShapeHints { vertexOrdering CLOCKWISE }``, VRML's ``ccw FALSE``) or under a mirroring transform are
turned outward. Points and lines draw no surface and are skipped, as are appearance, normals,
texture coordinates, lights, cameras, sensors and nodes not known here. A shape whose geometry is not
read (NURBS, 3D text, ``Extrusion``, ``ElevationGrid``) or that lives in another file (``File``,
``Inline``, ``WWWInline``) is an ObjectError naming it, and so is binary Inventor (one line each).
"""

from __future__ import annotations

import gzip
import math

import numpy as np

from drake_grasp.objects.inventor_scene import Node, parse_scene
from drake_grasp.objects.spec import ObjectError

SEGMENTS = 32  # sides of a tessellated Cylinder or Cone
SPHERE_SUBDIVISIONS = 3  # of the icosphere a Sphere becomes (1,280 triangles)

# Inventor's Units node: metres per unit.
_UNITS = {"METERS": 1.0, "CENTIMETERS": 0.01, "MILLIMETERS": 0.001, "MICROMETERS": 1e-6, "MICRONS": 1e-6,
          "NANOMETERS": 1e-9, "ANGSTROMS": 1e-10, "KILOMETERS": 1000.0, "FEET": 0.3048, "INCHES": 0.0254,
          "POINTS": 0.0254 / 72, "YARDS": 0.9144, "MILES": 1609.344, "NAUTICAL_MILES": 1852.0}
_SEPARATORS = frozenset(("Separator", "Selection", "WWWAnchor", "Annotation"))
_VRML_GROUPS = frozenset(("Transform", "Group", "Collision", "Anchor", "Billboard"))
_NO_SURFACE = frozenset(("PointSet", "LineSet", "IndexedLineSet", "MarkerSet", "IndexedMarkerSet", "NurbsCurve",
                         "IndexedNurbsCurve", "Text2"))
_NOT_READ = {"NurbsSurface": "a NURBS surface", "IndexedNurbsSurface": "a NURBS surface",
             "Text3": "3D text", "AsciiText": "3D text", "Text": "text", "Extrusion": "an extrusion",
             "ElevationGrid": "an elevation grid", "File": "geometry in another file",
             "Inline": "geometry in another file", "WWWInline": "geometry in another file"}


def header(data: bytes) -> str:
    """The first line of a file's bytes, as text (``#Inventor V2.1 ascii``, ``#VRML V2.0 utf8``)."""
    return data.split(b"\n", 1)[0].decode("latin-1").strip()


def read_inventor(data: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3) float64, triangles (m, 3) int64) of an Open Inventor ASCII or VRML file,
    every shape where its transforms put it, in the file's units (GraspIt's: millimetres) and frame.

    ObjectError (one line starting with `label`) for a file that is not Inventor or VRML, binary
    Inventor, broken syntax (naming the line), a number that is not one, an index out of range, a
    shape whose geometry is not read (naming it), or no surface at all."""
    if data[:2] == b"\x1f\x8b":
        try:
            data = gzip.decompress(data)
        except (OSError, EOFError) as error:
            raise ObjectError(f"{label}: damaged gzip-compressed file ({error})") from None
    first = header(data)
    words = first.split()
    if first.startswith("#Inventor") and "binary" in words:
        raise ObjectError(f"{label}: binary Open Inventor ({first!r}) is not read; save it as ASCII "
                          "(#Inventor V2.1 ascii)")
    if first.startswith("#VRML V2.0") or first.startswith("#VRML V1.0") or first.startswith("#Inventor"):
        dialect = "vrml2" if first.startswith("#VRML V2.0") else "inventor"
    else:
        raise ObjectError(f"{label}: not an Open Inventor or VRML file (its first line is {first[:60]!r}, not "
                          "'#Inventor V2.1 ascii' or '#VRML V2.0 utf8')")
    text = data.decode("utf-8", errors="replace")
    walk = _Walk(label, dialect)
    state = _State(np.eye(4), None, False, 1.0)
    for node in parse_scene(text, label):
        walk.node(node, state)
    if not walk.parts:
        skipped = sorted(walk.unknown)
        also = f" (not read: {', '.join(skipped[:6])})" if skipped else ""
        raise ObjectError(f"{label}: no surface: the file draws no shape that is read{also}")
    vertices, faces, offset = [], [], 0
    for v, f in walk.parts:
        vertices.append(v)
        faces.append(f + offset)
        offset += len(v)
    return np.vstack(vertices), np.vstack(faces).astype(np.int64)


class _State:
    """What the walk carries: the current matrix (file units), the coordinates vertex-based shapes
    use, whether faces are wound clockwise, and Inventor's current unit (metres per unit)."""

    def __init__(self, matrix, coords, clockwise, units):
        self.matrix, self.coords, self.clockwise, self.units = matrix, coords, clockwise, units

    def copy(self) -> _State:
        return _State(self.matrix.copy(), self.coords, self.clockwise, self.units)


class _Walk:
    """Traverses the scene as Coin renders it, collecting each shape's triangles (`parts`)."""

    def __init__(self, label: str, dialect: str):
        self.label, self.dialect = label, dialect
        self.parts: list[tuple[np.ndarray, np.ndarray]] = []
        self.unknown: set[str] = set()
        self.depth = 0

    def fail(self, node: Node, problem: str):
        raise ObjectError(f"{self.label}: {node.type} (line {node.line}): {problem}")

    def numbers(self, node: Node, field: str, default=None, count: int | None = None) -> np.ndarray:
        """A field's numbers (float64), or `default` if the node does not give the field."""
        values = node.fields.get(field)
        if values is None:
            return None if default is None else np.asarray(default, float)
        try:
            numbers = np.array(values, dtype=float) if values else np.zeros(0)
        except (ValueError, TypeError):
            bad = next(v for v in values if not _is_float(v))
            self.fail(node, f"{field} holds {str(getattr(bad, 'type', bad))[:40]!r}, not a number")
        if not np.all(np.isfinite(numbers)):
            self.fail(node, f"{field} holds a number that is not finite (NaN or inf)")
        if count is not None and len(numbers) != count:
            self.fail(node, f"{field} needs {count} numbers, got {len(numbers)}")
        return numbers

    def indices(self, node: Node, field: str) -> np.ndarray:
        numbers = self.numbers(node, field, ())
        if np.any(numbers != np.round(numbers)):
            self.fail(node, f"{field} holds a number that is not a whole index")
        return numbers.astype(np.int64)

    def children(self, node: Node, state: _State) -> None:
        for child in node.children + node.nodes("children"):
            self.node(child, state)

    def node(self, node: Node, state: _State) -> None:
        """Draws `node` under `state`, changing `state` as Inventor's property nodes do."""
        self.depth += 1
        if self.depth > 200:
            self.fail(node, "nodes nest deeper than 200 (a node that USEs itself?)")
        try:
            self._node(node, state)
        finally:
            self.depth -= 1

    def _node(self, node: Node, state: _State) -> None:
        kind = node.type
        if self.dialect == "vrml2" and kind in _VRML_GROUPS:
            inner = state.copy()
            if kind == "Transform":
                inner.matrix = inner.matrix @ self.transform(node, "scale")
            self.children(node, inner)
        elif kind == "Shape":
            for geometry in node.nodes("geometry"):
                self.shape(geometry, state)
        elif kind in _SEPARATORS:
            self.children(node, state.copy())
        elif kind == "TransformSeparator":
            matrix, units = state.matrix, state.units
            self.children(node, state)
            state.matrix, state.units = matrix, units
        elif kind in ("Group", "Collision", "Anchor", "Billboard"):
            self.children(node, state)
        elif kind in ("Switch", "Blinker"):
            chosen = node.children + node.nodes("choice")
            which = int(self.numbers(node, "whichChild", self.numbers(node, "whichChoice", [-1]))[0])
            for child in chosen if which == -3 else chosen[which:which + 1] if which >= 0 else ():
                self.node(child, state)
        elif kind in ("LOD", "LevelOfDetail"):
            chosen = node.children + node.nodes("level")
            if chosen:
                self.node(chosen[0], state)
        elif kind in ("Transform", "Translation", "Rotation", "RotationXYZ", "Scale", "MatrixTransform"):
            state.matrix = state.matrix @ self.inventor_transform(node)
        elif kind == "ResetTransform":
            if "TRANSFORM" in node.fields.get("whatToReset", ["TRANSFORM"]):
                state.matrix = np.eye(4)
        elif kind == "Units":
            unit = node.word("units", "METERS")
            if unit not in _UNITS:
                self.fail(node, f"unknown unit {unit[:40]!r}")
            factor = _UNITS[unit] / state.units
            state.matrix = state.matrix @ np.diag([factor, factor, factor, 1.0])
            state.units = _UNITS[unit]
        elif kind in ("Coordinate3", "Coordinate4"):
            state.coords = self.points(node, "point", 4 if kind == "Coordinate4" else 3)
        elif kind == "VertexProperty":
            if "vertex" in node.fields:
                state.coords = self.points(node, "vertex", 3)
        elif kind == "ShapeHints":
            state.clockwise = node.word("vertexOrdering", "UNKNOWN_ORDERING") == "CLOCKWISE"
        else:
            self.shape(node, state)

    def points(self, node: Node, field: str, width: int) -> np.ndarray:
        numbers = self.numbers(node, field, ())
        if len(numbers) % width:
            self.fail(node, f"{field} holds {len(numbers)} numbers, not a whole number of {width}-vectors")
        points = numbers.reshape(-1, width)
        if width == 4:
            if np.any(points[:, 3] == 0.0):
                self.fail(node, f"{field} holds a point at infinity (w = 0)")
            points = points[:, :3] / points[:, 3:]
        return points

    def shape(self, node: Node, state: _State) -> None:
        """The triangles of one shape node, placed by `state`; other nodes are skipped."""
        from drake_grasp.objects import inventor_shapes as shapes

        kind = node.type
        if kind in _NOT_READ:
            self.fail(node, f"{_NOT_READ[kind]} is not read; convert the file to triangles (OBJ, STL, PLY) first")
        if kind in _NO_SURFACE:
            return
        primitive = shapes.primitive(self, node)
        if primitive is not None:
            vertices, faces = primitive
            flip = False
        elif kind in ("IndexedFaceSet", "IndexedTriangleStripSet", "FaceSet", "TriangleStripSet", "QuadMesh"):
            vertices, faces = shapes.vertex_shape(self, node, self.coordinates(node, state))
            flip = state.clockwise if "ccw" not in node.fields else node.word("ccw", "TRUE") == "FALSE"
        else:
            self.unknown.add(kind)
            return
        if len(faces) == 0:
            return
        M = state.matrix
        if np.linalg.det(M[:3, :3]) < 0.0:
            flip = not flip
        if flip:
            faces = faces[:, ::-1]
        used, faces = np.unique(faces, return_inverse=True)  # only the vertices its faces use
        self.parts.append((vertices[used] @ M[:3, :3].T + M[:3, 3], faces.reshape(-1, 3)))

    def coordinates(self, node: Node, state: _State) -> np.ndarray:
        """The coordinates a vertex-based shape uses: its VRML ``coord``, its ``vertexProperty``,
        else the current ones."""
        for field, inner in (("coord", "point"), ("vertexProperty", "vertex")):
            for source in node.nodes(field):
                if inner in source.fields:
                    return self.points(source, inner, 3)
        if state.coords is None:
            self.fail(node, "no coordinates to index (no Coordinate3 before it, nor its own)")
        return state.coords

    def rotation(self, node: Node, field: str) -> np.ndarray:
        """A field's axis-angle rotation (x y z angle in radians) as a 3×3 matrix."""
        x, y, z, angle = self.numbers(node, field, (0.0, 0.0, 1.0, 0.0), 4)
        return _axis_angle(np.array([x, y, z]), angle)

    def transform(self, node: Node, scale_field: str) -> np.ndarray:
        """T·C·R·SR·S·SR⁻¹·C⁻¹ of a node with translation, rotation, a scale field (Inventor's
        scaleFactor, VRML's scale), scaleOrientation and center (4×4)."""
        translation = self.numbers(node, "translation", (0.0, 0.0, 0.0), 3)
        center = self.numbers(node, "center", (0.0, 0.0, 0.0), 3)
        scale = self.numbers(node, scale_field, (1.0, 1.0, 1.0), 3)
        R, SR = self.rotation(node, "rotation"), self.rotation(node, "scaleOrientation")
        linear = R @ SR @ np.diag(scale) @ SR.T
        matrix = np.eye(4)
        matrix[:3, :3] = linear
        matrix[:3, 3] = translation + center - linear @ center
        return matrix

    def inventor_transform(self, node: Node) -> np.ndarray:
        """The matrix of one of Inventor's transform nodes (4×4, acting on column vectors)."""
        kind, matrix = node.type, np.eye(4)
        if kind == "Transform":
            return self.transform(node, "scaleFactor")
        if kind == "Translation":
            matrix[:3, 3] = self.numbers(node, "translation", (0.0, 0.0, 0.0), 3)
        elif kind == "Rotation":
            matrix[:3, :3] = self.rotation(node, "rotation")
        elif kind == "RotationXYZ":
            axis = node.word("axis", "X")
            if axis not in ("X", "Y", "Z"):
                self.fail(node, f"axis {axis[:40]!r} is not X, Y or Z")
            angle = self.numbers(node, "angle", (0.0,), 1)[0]
            matrix[:3, :3] = _axis_angle(np.eye(3)["XYZ".index(axis)], angle)
        elif kind == "Scale":
            matrix[:3, :3] = np.diag(self.numbers(node, "scaleFactor", (1.0, 1.0, 1.0), 3))
        else:  # MatrixTransform: Inventor's matrices act on row vectors, so the file holds the transpose
            matrix = self.numbers(node, "matrix", np.eye(4).ravel(), 16).reshape(4, 4).T
        return matrix


def _axis_angle(axis: np.ndarray, angle: float) -> np.ndarray:
    """The rotation by `angle` (rad) about `axis` (any length; none: the identity), 3×3."""
    norm = float(np.linalg.norm(axis))
    if norm == 0.0 or angle == 0.0:
        return np.eye(3)
    x, y, z = axis / norm
    K = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


def _is_float(value) -> bool:
    try:
        float(value)
    except (ValueError, TypeError):
        return False
    return True
