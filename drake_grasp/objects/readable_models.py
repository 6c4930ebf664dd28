"""SDFormat and URDF text as Drake's parser can take it: each mesh it cannot read (STL, PLY, GLB,
MuJoCo .msh, COLLADA .dae) converted to an OBJ in the cache and named by it; a static model made free;
and the parser's warnings of the SDFormat elements it ignores held back.

Why its own module: `model_files` turns a parsed model into an object; this is what comes before the
parse, the file's text and its meshes (docs/object-formats.md).
"""

from __future__ import annotations

import contextlib
import hashlib
import html
import logging
import math
import os
import re
import warnings
import xml.etree.ElementTree as ElementTree
from pathlib import Path
from xml.sax.saxutils import escape

import numpy as np
import trimesh

from drake_grasp.objects import packages
from drake_grasp.objects.mesh_files import _Y_UP_SUFFIXES, _model_name, _one_line, read_triangles
from drake_grasp.objects.spec import MeshNote, ObjectError, StaticModelNote, _obj_text, _write_atomically, cache_dir

DRAKE_MESH_SUFFIXES = (".obj", ".vtk", ".gltf")  # what Drake's parser takes as mesh geometry
CONVERTED_VERSION = 2  # in the converted OBJs' names: a change to the conversion makes new files
_URDF_FILENAME = re.compile(r"""(\bfilename\s*=\s*)(["'])(.*?)\2""", re.DOTALL)
_SDF_URI = re.compile(r"(<uri\s*>)([^<]*)(</uri\s*>)")
_SDF_STATIC = re.compile(r"(<static\s*>)\s*(?:true|1)\s*(</static\s*>)", re.IGNORECASE)
# Gazebo's own format before SDFormat 1.3 (2013) had the root <gazebo version="1.x">; 1.3 renamed it
# <sdf>, and a model's elements read the same (pyrobosim ships its coke can in both).
_GAZEBO_OPEN = re.compile(r"<gazebo(\s[^>]*)?>")
_GAZEBO_CLOSE = re.compile(r"</gazebo\s*>")
# A URDF joint of type "floating", which MultibodyPlant does not support (it warns and leaves the child
# free, at the world's origin rather than where the joint puts it).
_URDF_FLOATING = re.compile(r"""(<joint\b[^>]*?\btype\s*=\s*)(["'])floating\2""", re.DOTALL)


# How many folders above a model file a relative mesh path that is not where the file says is looked
# for again (furniture-bench's lamp parts sit one folder deeper than their `../mesh/...` paths assume).
MISPLACED_MESH_LEVELS = 2


def found_above(reference: str, base: Path) -> tuple[Path, int] | None:
    """A relative mesh `reference` of a model file in the folder `base` that names no file there, but
    does from one of the `MISPLACED_MESH_LEVELS` folders above: (that file, how many folders up), else
    None. The whole relative path must match (``../mesh/lamp/lamp_bulb.obj``), not only the name, so
    a file it finds is the one the file's author meant at another depth."""
    if not reference or "://" in reference or Path(reference).is_absolute() or (base / reference).exists():
        return None
    for up, folder in enumerate(list(base.parents)[:MISPLACED_MESH_LEVELS], start=1):
        candidate = folder / reference
        if candidate.is_file():
            return candidate.resolve(), up
    return None


def _reference_path(reference: str, base: Path, package_map, local: dict, label: str) -> Path:
    """The file a model file's mesh reference names, resolved as Drake resolves it: ``package://``
    (and SDFormat's ``model://``) against the parser's PackageMap (the packages registered by
    :func:`drake_grasp.objects.packages.register_packages`), ``file://`` and absolute paths as
    they are, a relative path against the model file's folder `base`."""
    match = re.match(r"(package|model)://([^/]+)/(.*)", reference)
    if match:
        try:
            with packages.quiet_downloads():
                root = package_map.GetPath(match.group(2))
        except Exception as error:  # a remote package that cannot be downloaded
            problem = (packages.download_problem(str(error), local)
                       or f"cannot resolve {reference} ({_one_line(error)})")
            raise ObjectError(f"{label}: {problem}") from None
        return Path(root) / match.group(3)
    if reference.startswith("file://"):
        return Path(reference[len("file://"):])
    return base / reference


def _converted_obj(mesh_path: Path, label: str) -> Path:
    """An OBJ in the cache holding the triangles of a mesh file Drake cannot read (STL, PLY, GLB,
    MuJoCo .msh, COLLADA .dae: what :func:`drake_grasp.objects.mesh_files.read_triangles` reads), in
    the file's own units (a COLLADA file's declared unit applied, as Gazebo applies it; the model's
    ``scale`` still applies) and, for GLB, turned z up as Drake turns a glTF. Named by the file's
    content, so a second load reads it again without converting; written atomically. ObjectError
    (one line, from read_triangles) for a file that is missing or unreadable."""
    if not mesh_path.is_file():
        raise ObjectError(f"{label}: file not found")
    suffix = mesh_path.suffix.lower()
    digest = hashlib.sha256(mesh_path.read_bytes() + suffix.encode()).hexdigest()[:20]
    path = cache_dir() / "converted" / f"{_model_name(mesh_path.stem)}-{digest}-c{CONVERTED_VERSION}.obj"
    if not path.exists():
        mesh = read_triangles(mesh_path, label)
        if suffix in _Y_UP_SUFFIXES:
            mesh.apply_transform(trimesh.transformations.rotation_matrix(math.pi / 2, [1.0, 0.0, 0.0]))
        path.parent.mkdir(parents=True, exist_ok=True)
        _write_atomically(path, _obj_text(np.asarray(mesh.vertices), np.asarray(mesh.faces)))
    return path.resolve()


_VISUAL = re.compile(r"<visual\b[^>]*?/>|<visual\b.*?</visual\s*>", re.DOTALL)
_URDF_MATERIAL = re.compile(r"<material\b[^>]*?/>|<material\b.*?</material\s*>", re.DOTALL)


def has_visuals(path: Path) -> bool:
    """Whether an SDFormat or URDF file has a ``<visual>`` element (False if it is not XML)."""
    try:
        return any(True for _ in ElementTree.parse(path).getroot().iter("visual"))
    except (ElementTree.ParseError, OSError):
        return False


def drake_readable_model(path: Path, label: str, package_map, local: dict, visuals: bool = True) -> str | None:
    """The text of an SDFormat or URDF file with each mesh Drake cannot read converted to an OBJ
    (:func:`_converted_obj`) and named by it, and an SDFormat model that is static (Gazebo holds it
    fixed: osrf/gazebo_models' ``hammer``) made free, with a :class:`StaticModelNote`: an object to
    grasp is one the hand can lift; a file of Gazebo's format before SDFormat 1.3 (the root
    ``<gazebo version="1.2">``) is read as SDFormat 1.3, and a URDF joint of type ``floating``
    (which MultibodyPlant does not support) is made ``fixed``: `rigid_assembly` holds it where the
    file puts it, or, to the world, loads the object free as the file means. None if the file needs
    none of these (it is then parsed as it is) or is not XML (the parser says why).

    The text is parsed from a string, not from its folder, so every other path it gives is made an
    absolute ``file://`` URI (Drake refuses a bare path in a string); ``package://`` URIs are kept
    (the parser's PackageMap resolves them as before). Only the file-naming attributes and elements
    are rewritten (URDF ``filename``, SDFormat ``<uri>``), textually, so the rest of the file (its
    ``drake:`` elements, comments, scales) reaches the parser unchanged. Without `visuals`, the
    file's ``<visual>`` elements (and a URDF's ``<material>``s, which only visuals use) are left out
    too, and the text is always returned: for a file whose visuals Drake cannot parse."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError):
        return None
    legacy = root.tag == "gazebo" and (root.get("version") or "").strip().startswith("1.")
    if root.tag not in ("robot", "sdf") and not legacy:
        return None
    meshes = {((mesh.get("filename") if root.tag == "robot" else mesh.findtext("uri")) or "").strip()
              for mesh in root.iter("mesh")}
    unreadable = {reference for reference in meshes
                  if reference and Path(reference).suffix.lower() not in DRAKE_MESH_SUFFIXES}
    floating = root.tag == "robot" and any(joint.get("type") == "floating" for joint in root.iter("joint"))
    base = path.resolve().parent
    misplaced = {reference: found for reference in meshes if (found := found_above(reference, base)) is not None}
    static = root.tag != "robot" and any((model.findtext("static") or "").strip().lower() in ("true", "1")
                                         for model in root.findall("model"))
    if not unreadable and not static and not legacy and not floating and not misplaced and visuals:
        return None
    for reference, (found, up) in sorted(misplaced.items()):
        warnings.warn(f"{label}: mesh {reference} is not where the file says (looked for "
                      f"{os.path.normpath(base / reference)}); the same path from {up} folder{'s' if up > 1 else ''} "
                      f"higher names {found}, used", MeshNote, stacklevel=3)

    def rewritten(reference: str) -> str:
        if reference in misplaced:
            found = misplaced[reference][0]
            return f"file://{_converted_obj(found, f'{label}: mesh {reference}') if reference in unreadable else found}"
        if reference in unreadable:
            mesh_path = _reference_path(reference, base, package_map, local, label)
            return f"file://{_converted_obj(mesh_path, f'{label}: mesh {reference}')}"
        if not reference or "://" in reference:
            return reference
        return f"file://{(base / reference).resolve()}"  # not percent-encoded: Drake reads the path as it is

    def attribute(match) -> str:
        prefix, quote, value = match.groups()
        new = escape(rewritten(html.unescape(value).strip()), {'"': "&quot;", "'": "&apos;"})
        return f"{prefix}{quote}{new}{quote}"

    def element(match) -> str:
        start, value, end = match.groups()
        return f"{start}{escape(rewritten(html.unescape(value).strip()))}{end}"

    text = path.read_text(errors="replace")
    if not visuals:
        text = _VISUAL.sub("", text)
        text = _URDF_MATERIAL.sub("", text) if root.tag == "robot" else text
    if root.tag == "robot":  # a floating joint as a fixed one: `rigid_assembly` holds it where the file puts it
        return _URDF_FILENAME.sub(attribute, _URDF_FLOATING.sub(r"\g<1>\g<2>fixed\g<2>", text))
    if legacy:
        warnings.warn(f"{label}: Gazebo's format before SDFormat 1.3 (root <gazebo version=\"{root.get('version')}\">), "
                      "read as SDFormat 1.3, whose model elements are the same", MeshNote, stacklevel=3)
        text = _GAZEBO_CLOSE.sub("</sdf>", _GAZEBO_OPEN.sub('<sdf version="1.3">', text, count=1))
    if static:
        warnings.warn(f"{label}: the model is static in its file (Gazebo holds it fixed); loaded as a free body",
                      StaticModelNote, stacklevel=3)
        text = _SDF_STATIC.sub(r"\g<1>false\g<2>", text)
    return _SDF_URI.sub(element, text)


class _UnsupportedElement(logging.Filter):
    """Drops Drake's "Ignoring unsupported SDFormat element" warnings, and its note that a ball joint's
    axis is ignored (an object's joints are held: `rigid_assembly`) (`quiet_unsupported_elements`)."""

    def filter(self, record: logging.LogRecord) -> bool:
        message = record.getMessage()
        return "Ignoring unsupported SDFormat element" not in message and "ball joint axis will be ignored" not in message


@contextlib.contextmanager
def quiet_unsupported_elements():
    """A context in which Drake's parser does not warn of the SDFormat elements it ignores. Gazebo's
    model files are full of them (a visual's OGRE material ``<script>``, ``<self_collide>``,
    ``<velocity_decay>``, ``<plugin>``, ``<sensor>``), on every load, and none is anything an object
    here uses: its collision geometry and inertial (its visuals and contact properties are replaced by
    ours). Every other warning of the parser is kept."""
    logger, quiet = logging.getLogger("drake"), _UnsupportedElement()
    logger.addFilter(quiet)
    try:
        yield
    finally:
        logger.removeFilter(quiet)
