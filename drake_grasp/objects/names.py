"""The objects a command line names: a catalogue name, a primitive string or a file, with the
options only object files take (`--scale`, `--largest-component`, `--join-gap`, `--inertia`,
`--package-path`)."""

from __future__ import annotations

import math
import os
import re
import warnings
from pathlib import Path

from drake_grasp.file_formats import MESH_FORMATS, MODEL_FORMATS
from drake_grasp.objects.catalogue import (
    PAPER_OBJECTS, _PAPER_FACTORIES, box_object, cube_object, cylinder_object, paper_object, sphere_object,
)
from drake_grasp.objects.mesh_files import object_from_mesh
from drake_grasp.objects.spec import ObjectError, ObjectSpec


_NUMBER = r"([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)"
_PRIMITIVE_PATTERNS = {
    "sphere": re.compile(rf"sphere:{_NUMBER}"),
    "cube": re.compile(rf"cube:{_NUMBER}"),
    "cylinder": re.compile(rf"cylinder:{_NUMBER}(?:x{_NUMBER})?"),
    "box": re.compile(rf"box:{_NUMBER}x{_NUMBER}x{_NUMBER}"),
}
_PRIMITIVE_HELP = "sphere:DIAMETER, cube:EDGE, cylinder:DIAMETER[xLENGTH], box:LENGTHxWIDTHxHEIGHT (metres)"


def resolve_object(name_or_path: str | os.PathLike, **kw) -> ObjectSpec:
    """The object named on a command line.

    Args:
        name_or_path: A catalogue name (``PAPER_OBJECTS``); a primitive string such as
            ``sphere:0.12``, ``cube:0.08``, ``cylinder:0.1x0.3`` or ``cylinder:0.1`` (metres;
            length default CYLINDER_FAMILY_LENGTH: lying along x), ``box:0.05x0.025x0.01`` (length
            along x, width, height; resting on a face); or the path of a mesh (any format trimesh
            reads, a MuJoCo ``.msh``, Drake's tetrahedral ``.vtk``, Open Inventor ``.iv``, VRML
            ``.wrl``) or an ``.sdf``/``.urdf``/MJCF model file, a GraspIt! body ``.xml``
            (:func:`drake_grasp.objects.graspit_files.object_from_graspit`), or a Gazebo model folder
            (its SDF file: :func:`gazebo_model_file`).
        **kw: Passed on to :func:`paper_object`, :func:`sphere_object` (etc.),
            :func:`object_from_mesh`, :func:`object_from_sdf`, ``object_from_mjcf`` or
            ``object_from_graspit``.

    Raises:
        ObjectError: Unknown name (listing the valid names), bad primitive string, missing or bad
            file.
    """
    if not isinstance(name_or_path, str):
        return _object_from_file(Path(name_or_path), os.fspath(name_or_path), kw)
    text = name_or_path.strip()
    if not text:
        raise ObjectError("empty object name; give a catalogue name, a primitive such as sphere:0.12, "
                          "or a mesh file")
    if text in _PAPER_FACTORIES:
        return paper_object(text, **kw)
    kind = text.split(":", 1)[0].lower() if ":" in text else None
    if kind in _PRIMITIVE_PATTERNS:
        match = _PRIMITIVE_PATTERNS[kind].fullmatch(text.lower())
        if match is None:
            raise ObjectError(f"bad primitive {text!r}; expected {_PRIMITIVE_HELP}")
        values = [float(v) for v in match.groups() if v is not None]
        if kind == "sphere":
            return sphere_object(*values, **kw)
        if kind == "cube":
            return cube_object(*values, **kw)
        if kind == "box":
            return box_object(*values, **kw)
        return cylinder_object(*values, **kw)
    path = Path(text).expanduser()
    if path.suffix or os.sep in text or "/" in text or path.exists():
        return _object_from_file(path, text, kw)
    raise ObjectError(
        f"unknown object {text!r}; valid names: {', '.join(PAPER_OBJECTS)}; or {_PRIMITIVE_HELP}; "
        "or a mesh/SDF file path"
    )


def resolve_user_object(
    name_or_path: str, *, scale: float = 1.0, largest_component: bool = False, join_gap: float | None = None,
    inertia: str = "check", package_path=(), **kw
) -> ObjectSpec:
    """:func:`resolve_object` with the options that only object files take (a command line's
    ``--scale``: mesh and model files; ``--largest-component``, ``--join-gap``: mesh files and MJCF;
    ``--inertia``: model files; ``--package-path``: SDF and URDF files): ObjectError if one is given
    for an object that does not take it."""
    text = str(name_or_path).strip()
    given = mesh_options(scale, largest_component, join_gap, inertia, package_path)
    if not given:
        return resolve_object(text, **kw)
    taken = options_for(text, **given)
    for option in given:
        if option not in taken:
            flag = "--" + option.replace("_", "-")
            kinds = (f"model files ({MODEL_FORMATS})" if option == "inertia" else
                     "mesh files, MJCF models and GraspIt! bodies" if option == "join_gap" else
                     "SDF and URDF model files" if option == "package_path" else
                     f"mesh files ({MESH_FORMATS}) and model files (SDF, URDF, MJCF)")
            raise ObjectError(f"{text}: {flag} applies to {kinds} only")
    if not (scale > 0.0 and math.isfinite(scale)):
        raise ObjectError(f"--scale must be positive, got {scale!r}")
    if join_gap is not None and not (join_gap >= 0.0 and math.isfinite(join_gap)):
        raise ObjectError(f"--join-gap must be a distance >= 0 (m), got {join_gap!r}")
    return resolve_object(text, **taken, **kw)


def is_mesh_file(name_or_path: str) -> bool:
    """Whether an object argument names a mesh file (what `--scale` applies to), not a catalogue
    object, a primitive or a model file (SDF, URDF, MJCF)."""
    text = str(name_or_path).strip()
    return not (text in _PAPER_FACTORIES or ":" in text or Path(text).suffix.lower() in MODEL_SUFFIXES)


def is_model_file(name_or_path: str) -> bool:
    """Whether an object argument names a model file (SDF, URDF, MJCF: what `--inertia` applies to)."""
    text = str(name_or_path).strip()
    return text not in _PAPER_FACTORIES and ":" not in text and Path(text).suffix.lower() in MODEL_SUFFIXES


def mesh_options(scale: float = 1.0, largest_component: bool = False, join_gap: float | None = None,
                 inertia: str = "check", package_path=()) -> dict:
    """The object-file options that differ from their defaults, as keyword arguments of
    :func:`resolve_user_object` (plain data: a sweep's tasks carry them to its workers, and a
    record's fingerprint includes them)."""
    options = {}
    if scale != 1.0:
        options["scale"] = float(scale)
    if largest_component:
        options["largest_component"] = True
    if join_gap is not None:
        options["join_gap"] = float(join_gap)
    if inertia != "check":
        options["inertia"] = inertia
    if package_path:
        options["package_path"] = tuple(str(Path(p).expanduser().resolve()) for p in package_path)
    return options


def options_for(name_or_path: str, **options) -> dict:
    """Of `options` (:func:`mesh_options`'s keywords), those the object takes: scale a mesh or
    model file (a GraspIt! body's unit is fixed, millimetres: `_object_from_file` refuses a scale for
    it); largest_component and join_gap a mesh file or an ``.xml``/``.mjcf`` model (MJCF, or a
    GraspIt! body); inertia a model file; package_path an SDF or URDF file (the ones that name ``package://`` URIs)."""
    text = str(name_or_path).strip()
    mjcf = is_model_file(text) and Path(text).suffix.lower() in (".xml", ".mjcf")
    takes = {"scale": is_mesh_file(text) or is_model_file(text), "largest_component": is_mesh_file(text) or mjcf,
             "join_gap": is_mesh_file(text) or mjcf, "inertia": is_model_file(text),
             "package_path": is_model_file(text) and not mjcf}
    return {k: v for k, v in options.items() if takes.get(k, False)}


MODEL_SUFFIXES = (".sdf", ".urdf", ".xml", ".mjcf")  # model files (model_files; a GraspIt! body .xml: graspit_files)


def gazebo_model_file(folder: Path, label: str | None = None) -> Path:
    """The SDFormat file of a Gazebo model folder: the one its ``model.config`` names in an ``<sdf>``
    element (of several, the highest ``version``), as Gazebo picks it. ObjectError (one line) for a
    folder without a model.config, one that is not XML or names no SDF, or an SDF that is missing."""
    import xml.etree.ElementTree as ElementTree

    label = label or os.fspath(folder)
    config = Path(folder) / "model.config"
    if not config.is_file():
        raise ObjectError(f"{label}: a folder; give an object file, or a Gazebo model folder (one with a model.config)")
    try:
        entries = ElementTree.parse(config).getroot().findall("sdf")
    except (ElementTree.ParseError, OSError) as error:
        raise ObjectError(f"{label}: model.config is not readable XML ({' '.join(str(error).split())})") from None

    def version(entry) -> tuple:
        return tuple(int(part) if part.isdigit() else 0 for part in (entry.get("version") or "0").split("."))

    named = [entry for entry in entries if (entry.text or "").strip()]
    if not named:
        raise ObjectError(f"{label}: model.config names no <sdf> file")
    sdf = Path(folder) / max(named, key=version).text.strip()
    if not sdf.is_file():
        raise ObjectError(f"{label}: model.config names {sdf.name}, which is not there")
    return sdf


def _object_from_file(path: Path, label: str, kw: dict) -> ObjectSpec:
    if not path.exists():
        raise ObjectError(f"{label}: file not found")
    if path.is_dir():  # a Gazebo model folder: its SDF file
        path = gazebo_model_file(path, label)
    if path.suffix.lower() in MODEL_SUFFIXES:
        from drake_grasp.objects import model_files

        if path.suffix.lower() in (".sdf", ".urdf"):
            return model_files.object_from_sdf(path, **kw)
        if path.suffix.lower() == ".xml":
            from drake_grasp.objects import graspit_files

            if graspit_files.graspit_kind(path):  # a GraspIt! body (robots and worlds refused)
                if kw.pop("scale", 1.0) != 1.0:
                    raise ObjectError(f"{label}: a GraspIt! body's unit is fixed (millimetres): --scale does not apply")
                return graspit_files.object_from_graspit(path, **kw)
        return model_files.object_from_mjcf(path, **kw)
    return object_from_mesh(path, **kw)


def load_error(name_or_path: str, scale: float = 1.0) -> str | None:
    """The one line saying why `name_or_path` does not load as a user's object
    (:func:`resolve_user_object` at `scale`), or None if it loads. A plain function of its arguments, so
    that a study can check all its files in a process pool before any trial starts (a new mesh's
    convex decomposition takes seconds to minutes, and is cached for the trials). The loader's notes
    and warnings are held back: the trials give them again, and a refusal stays one line."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            resolve_user_object(name_or_path, scale=scale)
        except ObjectError as error:
            return str(error)
    return None
