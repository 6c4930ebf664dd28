"""3MF (``.3mf``) meshes: their triangles in metres, in the unit the file declares.

Why: 3MF is the format 3D-printing tools and model sites now ship (slicers such as PrusaSlicer,
Bambu Studio and Cura save projects as 3MF; Printables and Thingiverse offer it beside STL), so a
user with a printed object often has it as a 3MF. trimesh reads 3MF only with two optional packages
(``lxml`` and ``networkx``) that this project does not otherwise need, and a slicer's project keeps
each object in a part of its own (the Production extension's ``p:path``), so it is read here with the
standard library's ``zipfile`` and ``xml.etree``.

What is read, following the 3MF Core Specification (3MF Consortium, version 1.3, §3-§4) and its
Production Extension (version 1.2, §2):

* **the package**: a ZIP whose root relationship (``_rels/.rels``, type ``.../3dmodel``) names the
  model part, usually ``/3D/3dmodel.model``; without the relationship, that part;
* **the unit** (``<model unit="millimeter">``, the default; also micron, centimeter, inch, foot and
  meter) is applied, so the triangles come in metres, as a COLLADA file's do;
* **the build**: every ``<build><item objectid transform>``, each object's ``<mesh>`` (``<vertices>``
  and ``<triangles>``) and ``<components>`` followed down with their transforms, including a
  component in another model part of the package (``p:path``). The transform is the specification's
  3 × 4 matrix ``m00 m01 m02 m10 ... m32``, applied to row vectors (``[x y z 1] · M``). Objects of type
  ``support`` or ``solidsupport`` (a slicer's print supports) are left out, as they are not the object;
* an object described by **slices** (the Slice Extension's ``s:slicestackid``) is refused unless its
  mesh says it is full resolution (``s:meshresolution="fullres"``): writers give such an object a
  low-resolution stand-in (the consortium's sliced sphere carries a 2 cm box), and a wrong shape is
  worse than none;
* **only triangles** matter: colours, materials, textures, thumbnails and print settings are ignored,
  and so are the beams of a beam lattice (a file of beams alone is refused, saying so).

A package that is not a ZIP, has no model part, names an object it does not define, holds a cycle of
components or a triangle index out of range, or builds nothing, is refused in one line.
"""

from __future__ import annotations

import io
import posixpath
import xml.etree.ElementTree as ElementTree
import zipfile

import numpy as np

from drake_grasp.objects.spec import ObjectError

CORE_NAMESPACE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
PRODUCTION_NAMESPACE = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06"
SLICE_NAMESPACE = "http://schemas.microsoft.com/3dmanufacturing/slice/2015/07"
MODEL_RELATIONSHIP = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"
DEFAULT_MODEL_PART = "3D/3dmodel.model"

UNIT_METRES = {  # 3MF Core Specification §3.4: the model's unit attribute.
    "micron": 1e-6, "millimeter": 1e-3, "centimeter": 1e-2, "inch": 0.0254, "foot": 0.3048, "meter": 1.0,
}
SUPPORT_TYPES = ("support", "solidsupport")
MAX_COMPONENT_DEPTH = 32  # components nest; deeper than this is taken for a cycle


def is_3mf(data: bytes) -> bool:
    """Whether `data` is a ZIP package (every 3MF is one): its first bytes are a ZIP's local header."""
    return data[:4] == b"PK\x03\x04"


def _tag(element) -> str:
    """An element's tag without its namespace: 3MF files name the core namespace as the default one,
    and some writers use a prefix; either reads the same."""
    return element.tag.rsplit("}", 1)[-1]


def _children(element, name: str) -> list:
    return [child for child in element if _tag(child) == name]


def _transform(text: str | None, label: str) -> np.ndarray:
    """The 4 × 4 matrix (column vectors) of a 3MF ``transform`` attribute, or the identity if absent."""
    X = np.eye(4)
    if text is None:
        return X
    try:
        values = np.array([float(word) for word in text.split()])
    except ValueError:
        raise ObjectError(f"{label}: a transform is not 12 numbers ({text.strip()[:60]!r})") from None
    if len(values) != 12 or not np.isfinite(values).all():
        raise ObjectError(f"{label}: a transform is not 12 finite numbers ({text.strip()[:60]!r})")
    M = values.reshape(4, 3)  # rows: three of the linear map applied to row vectors, then the translation
    X[:3, :3] = M[:3].T
    X[:3, 3] = M[3]
    return X


def _model_part(package: zipfile.ZipFile, label: str) -> str:
    """The path of the package's root model part (no leading slash)."""
    names = set(package.namelist())
    if "_rels/.rels" in names:
        try:
            relationships = ElementTree.fromstring(package.read("_rels/.rels"))
        except ElementTree.ParseError as error:
            raise ObjectError(f"{label}: its _rels/.rels is not XML ({error})") from None
        for relationship in relationships:
            if relationship.get("Type") == MODEL_RELATIONSHIP and relationship.get("Target"):
                target = relationship.get("Target").lstrip("/")
                if target not in names:
                    raise ObjectError(f"{label}: its model part {target} is not in the package")
                return target
    if DEFAULT_MODEL_PART in names:
        return DEFAULT_MODEL_PART
    raise ObjectError(f"{label}: a ZIP without a 3MF model part (no {DEFAULT_MODEL_PART})")


class _Package:
    """The model parts of one 3MF package, parsed on first use, and their objects by (part, id)."""

    def __init__(self, package: zipfile.ZipFile, label: str):
        self.package, self.label = package, label
        self.objects: dict[str, dict[str, ElementTree.Element]] = {}
        self.roots: dict[str, ElementTree.Element] = {}
        self.beams = False  # a mesh carries a beam lattice (struts drawn as cylinders, not triangles)
        self.scales: dict[str, float] = {}

    def part(self, name: str) -> dict[str, ElementTree.Element]:
        """The objects of model part `name` by id (its root and unit kept)."""
        if name not in self.objects:
            try:
                root = ElementTree.fromstring(self.package.read(name))
            except KeyError:
                raise ObjectError(f"{self.label}: a component names the part /{name}, which is not in the package"
                                  ) from None
            except ElementTree.ParseError as error:
                raise ObjectError(f"{self.label}: its part /{name} is not XML ({error})") from None
            if _tag(root) != "model":
                raise ObjectError(f"{self.label}: its part /{name} is not a 3MF model (root <{_tag(root)}>)")
            unit = root.get("unit", "millimeter")
            if unit not in UNIT_METRES:
                raise ObjectError(f"{self.label}: unknown unit {unit!r} (3MF's are {', '.join(UNIT_METRES)})")
            self.scales[name] = UNIT_METRES[unit]
            self.objects[name] = {obj.get("id"): obj for resources in _children(root, "resources")
                                  for obj in _children(resources, "object")}
            self.roots[name] = root
        return self.objects[name]

    def triangles(self, part: str, object_id: str, X: np.ndarray, depth: int, out: list) -> None:
        """Append (vertices in the part's unit under `X`, faces) of object `object_id` of `part`."""
        if depth > MAX_COMPONENT_DEPTH:
            raise ObjectError(f"{self.label}: components nest deeper than {MAX_COMPONENT_DEPTH} (a cycle?)")
        obj = self.part(part).get(object_id)
        if obj is None:
            raise ObjectError(f"{self.label}: names object {object_id} of /{part}, which is not defined")
        if obj.get("type", "model") in SUPPORT_TYPES:
            return
        if obj.get(f"{{{SLICE_NAMESPACE}}}slicestackid") and \
                obj.get(f"{{{SLICE_NAMESPACE}}}meshresolution", "") != "fullres":
            raise ObjectError(f"{self.label}: object {object_id} is described by a stack of slices (the Slice "
                              "extension), and its mesh may be only a stand-in (a box round a sphere, in the 3MF "
                              "consortium's samples); export it as a full mesh")
        for mesh in _children(obj, "mesh"):
            out.append(self._mesh(mesh, X, part, object_id))
            self.beams |= any(_tag(child) == "beamlattice" for child in mesh)
        for components in _children(obj, "components"):
            for component in _children(components, "component"):
                child_part = (component.get(f"{{{PRODUCTION_NAMESPACE}}}path") or f"/{part}").lstrip("/")
                child_part = posixpath.normpath(child_part)
                X_child = X @ _transform(component.get("transform"), self.label)
                self.triangles(child_part, component.get("objectid"), X_child, depth + 1, out)

    def _mesh(self, mesh, X: np.ndarray, part: str, object_id: str) -> tuple[np.ndarray, np.ndarray]:
        where = f"object {object_id} of /{part}"
        try:
            vertices = np.array([[float(v.get(axis)) for axis in "xyz"]
                                 for block in _children(mesh, "vertices") for v in _children(block, "vertex")],
                                float).reshape(-1, 3)
            faces = np.array([[int(t.get(key)) for key in ("v1", "v2", "v3")]
                              for block in _children(mesh, "triangles") for t in _children(block, "triangle")],
                             np.int64).reshape(-1, 3)
        except (TypeError, ValueError):
            raise ObjectError(f"{self.label}: {where} has a vertex or triangle that is not numbers") from None
        if len(faces) and (faces.min() < 0 or faces.max() >= len(vertices)):
            raise ObjectError(f"{self.label}: {where} has a triangle index out of range "
                              f"(0-{len(vertices) - 1})")
        vertices = vertices @ X[:3, :3].T + X[:3, 3]
        return vertices * self.scales[part], faces


def read_3mf(data: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices in metres, triangle faces) of everything a 3MF package builds.

    Raises:
        ObjectError: One line naming the file and the problem.
    """
    try:
        package = zipfile.ZipFile(io.BytesIO(data))
    except zipfile.BadZipFile:
        raise ObjectError(f"{label}: not a 3MF file (not a ZIP package)") from None
    with package:
        model = _model_part(package, label)
        reader = _Package(package, label)
        reader.part(model)
        root = reader.roots[model]
        items = [item for build in _children(root, "build") for item in _children(build, "item")]
        if not items:
            raise ObjectError(f"{label}: the 3MF builds nothing (no <build> items)")
        pieces: list = []
        for item in items:
            item_part = (item.get(f"{{{PRODUCTION_NAMESPACE}}}path") or model).lstrip("/")
            reader.triangles(item_part, item.get("objectid"), _transform(item.get("transform"), label), 0, pieces)
    pieces = [(v, f) for v, f in pieces if len(f)]
    if not pieces and reader.beams:
        raise ObjectError(f"{label}: a beam lattice only (struts, the Beam Lattice extension): its beams are not "
                          "read; export the lattice as a triangle mesh")
    if not pieces:
        raise ObjectError(f"{label}: file contains no triangles (a point cloud or an empty mesh): no solid "
                          "can be recovered")
    offsets = np.cumsum([0] + [len(v) for v, _ in pieces[:-1]])
    vertices = np.vstack([v for v, _ in pieces])
    faces = np.vstack([f + offset for (_, f), offset in zip(pieces, offsets)])
    return vertices, faces
