"""Where a model file's ``package://`` URIs point: the package.xml files found beside it and on the
command line's ``--package-path``, registered with Drake's parser.

Why: Drake's own model files name their meshes by package, not by path: drake_models' YCB SDFs use
``package://drake_models/ycb/meshes/003_cracker_box_textured.gltf`` with the package.xml at the
repository's root, two folders above the SDF. A Drake user runs them with that folder on the
parser's PackageMap; a user of this package names the SDF, so:

* the package.xml files in the model file's folder and in up to PACKAGE_SEARCH_LEVELS folders above
  it are registered (the nearest of a name wins), so that a checkout of drake_models needs nothing
  more;
* ``--package-path DIR`` (repeatable) registers DIR's package.xml, or every package.xml under DIR
  (as ROS_PACKAGE_PATH is crawled: a package's own folder is not searched further);
* Drake's default PackageMap already knows ``drake_models`` as a *remote* package (downloaded on
  first use, which fails offline): a local package of the same name replaces it (PackageMap.Remove,
  then AddPackageXml), so a local checkout is used instead of a download, and it never collides.

Gazebo's model files name theirs by model instead: osrf/gazebo_models' ``coke_can/model.sdf`` uses
``model://coke_can/meshes/coke_can.dae``, which Gazebo resolves against the folders on its model path
(``GAZEBO_MODEL_PATH``; ``GZ_SIM_RESOURCE_PATH`` for Gazebo Sim): ``model://NAME`` is the folder NAME in
one of them. Drake's parser resolves ``model://`` URIs through the same PackageMap as ``package://``
ones, so each such NAME is registered as a package whose folder is (:func:`gazebo_models`), first
found first: under a ``--package-path`` DIR (DIR itself if it is named NAME, else DIR/NAME); the
model file's own folder if it is named NAME, or a folder NAME beside it, there or in the
PACKAGE_SEARCH_LEVELS folders above (a checkout of a model collection needs nothing more); a folder
NAME on the model path variables.

A ``package://NAME/`` that no package.xml names resolves, like a Gazebo model, to a folder NAME beside
the model file or above it (or under a ``--package-path`` DIR), with a note: onshape-to-robot writes
``package://assets/part_1.stl`` beside an ``assets`` folder, and ROS descriptions are often copied
without their package.xml; pybullet and Genesis resolve them so.

A URI whose package or model is known neither locally nor remotely, or a remote package that cannot
be downloaded, is an ObjectError that says where it was looked for and how to give it.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
import warnings
import xml.etree.ElementTree as ElementTree
from pathlib import Path

from drake_grasp.objects.spec import MeshNote, ObjectError

PACKAGE_SEARCH_LEVELS = 8  # folders above a model file searched for package.xml (bounded: never the whole disk)
_URI = re.compile(r"package://([A-Za-z0-9_.\-]+)/")
_MODEL_URI = re.compile(r"model://([A-Za-z0-9_.\-]+)/")
_MESH_URI = re.compile(r"<mesh\b[^>]*>.*?<uri\s*>([^<]*)</uri\s*>", re.DOTALL)
# Gazebo's model path variables (Gazebo Classic's, Gazebo Sim's and its former name), searched in this order.
GAZEBO_PATH_VARIABLES = ("GAZEBO_MODEL_PATH", "GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH")


def package_name(package_xml: Path) -> str:
    """The <name> of a package.xml (ObjectError, one line, if it has none or is not XML)."""
    try:
        name = ElementTree.parse(package_xml).getroot().findtext("name")
    except (ElementTree.ParseError, OSError) as error:
        raise ObjectError(f"{package_xml}: not a readable package.xml ({' '.join(str(error).split())})") from None
    if not name or not name.strip():
        raise ObjectError(f"{package_xml}: package.xml without a <name>")
    return name.strip()


def packages_above(model_file: Path, levels: int = PACKAGE_SEARCH_LEVELS) -> dict[str, Path]:
    """{name: package.xml} of the package.xml files in `model_file`'s folder and the `levels`
    folders above it; of two with one name, the nearer. Unreadable ones are skipped (a model file
    that needs one gets the parser's error for its URI instead)."""
    found: dict[str, Path] = {}
    for folder in _folders_up(model_file, levels):
        candidate = folder / "package.xml"
        if candidate.is_file():
            try:
                found.setdefault(package_name(candidate), candidate)
            except ObjectError:
                pass
    return found


def _folders_up(model_file: Path, levels: int = PACKAGE_SEARCH_LEVELS) -> list[Path]:
    """`model_file`'s folder and the `levels` folders above it (fewer at the root), nearest first."""
    folders = [Path(model_file).resolve().parent]
    while len(folders) <= levels and folders[-1].parent != folders[-1]:
        folders.append(folders[-1].parent)
    return folders


def packages_under(directory: Path) -> dict[str, Path]:
    """{name: package.xml} of `directory`'s package.xml, or of every package.xml below it (hidden
    folders skipped; a package's own subfolders not searched). ObjectError for a directory that
    does not exist or holds no package.xml."""
    directory = Path(directory).expanduser()
    if not directory.is_dir():
        raise ObjectError(f"--package-path {directory}: not a directory")
    found: dict[str, Path] = {}
    for root, folders, files in os.walk(directory):
        folders[:] = sorted(f for f in folders if not f.startswith("."))
        if "package.xml" in files:
            path = Path(root) / "package.xml"
            found.setdefault(package_name(path), path)
            folders[:] = []
    if not found:
        raise ObjectError(f"--package-path {directory}: no package.xml in it or below it")
    return found


def referenced_packages(text: str) -> list[str]:
    """The package names a model file's ``package://NAME/...`` URIs use, in order of first use."""
    return list(dict.fromkeys(_URI.findall(text)))


def referenced_models(text: str, meshes_only: bool = False) -> list[str]:
    """The model names a model file's ``model://NAME/...`` URIs use (Gazebo's), in order of first use;
    with `meshes_only`, those of its mesh geometries' ``<uri>`` only: Drake reads no other (it ignores
    a visual's material script, which Gazebo's models often take from another model:
    ``model://arm_part/materials/scripts`` in ``gear_part``)."""
    if meshes_only:
        text = " ".join(_MESH_URI.findall(text))
    return list(dict.fromkeys(_MODEL_URI.findall(text)))


def gazebo_models(model_file: Path, names, package_path=(), environ=None) -> dict[str, Path]:
    """{name: folder} of the Gazebo models `names` (``model://NAME``) found as the module docstring
    says: under `package_path`, beside or above `model_file` (PACKAGE_SEARCH_LEVELS), then on the
    model path variables of `environ` (default os.environ). A name found nowhere is left out."""
    environ = os.environ if environ is None else environ
    near = _folders_up(model_file)
    on_path = [Path(entry).expanduser() for variable in GAZEBO_PATH_VARIABLES
               for entry in environ.get(variable, "").split(os.pathsep) if entry]
    roots = [Path(d).expanduser() for d in package_path] + near + on_path
    found: dict[str, Path] = {}
    for name in names:
        for root in roots:
            candidate = root if root.name == name else root / name
            if candidate.is_dir():
                found[name] = candidate.resolve()
                break
    return found


def register_packages(package_map, model_file: Path, package_path=()) -> dict[str, Path]:
    """Registers the local packages a model file can use with a Drake PackageMap: those found above
    it (:func:`packages_above`), then those of `package_path` (each :func:`packages_under`; given
    last, they win). A name the map already has (Drake's remote ``drake_models``) is replaced. Then
    the Gazebo models its ``model://`` URIs name (:func:`gazebo_models`), each as a package of that
    name rooted at its folder, unless a package.xml of that name was found. Returns {name: package.xml
    or model folder} of what was registered."""
    try:
        text = Path(model_file).read_text(errors="replace")
    except OSError:
        text = ""
    models = referenced_models(text)
    local = packages_above(model_file)
    for directory in package_path:
        try:
            local.update(packages_under(Path(directory)))
        except ObjectError:
            if not ((models or referenced_packages(text)) and Path(directory).expanduser().is_dir()):
                raise  # a folder of Gazebo models (or of package folders without package.xml) needs none
    for name, xml in local.items():
        if package_map.Contains(name):
            package_map.Remove(name)
        package_map.AddPackageXml(str(xml))
    wanted = [name for name in models if name not in local]
    for name, folder in gazebo_models(model_file, wanted, package_path).items():
        if package_map.Contains(name):
            package_map.Remove(name)
        package_map.Add(name, str(folder))
        local[name] = folder
    unknown = [name for name in referenced_packages(text) if name not in local and not package_map.Contains(name)]
    for name, folder in gazebo_models(model_file, unknown, package_path, environ={}).items():
        # No package.xml names it, but a folder of that name is beside the file or above it: CAD
        # exporters (onshape-to-robot's package://assets/) and ROS descriptions copied without their
        # package.xml mean that folder, and pybullet and Genesis resolve it so.
        package_map.Add(name, str(folder))
        local[name] = folder
        warnings.warn(f"{model_file}: package://{name}/ resolved to the folder {folder} (no package.xml names "
                      f"{name!r})", MeshNote, stacklevel=3)
    return local


def missing_package_problem(text: str, package_map, local: dict[str, Path], model_file: Path) -> str | None:
    """Why the model file's URIs cannot resolve before parsing it (a package Drake knows neither
    locally nor remotely, a Gazebo model found nowhere), or None."""
    for name in referenced_packages(text):
        if name not in local and not package_map.Contains(name):
            return (f"package://{name}/ is not known: no package.xml named {name!r} in the file's folder or the "
                    f"{PACKAGE_SEARCH_LEVELS} above it; give its folder with --package-path DIR")
    for name in referenced_models(text, meshes_only=True):
        if name not in local and not package_map.Contains(name):
            return (f"model://{name}/ is not known: no folder named {name!r} beside the file or in the "
                    f"{PACKAGE_SEARCH_LEVELS} folders above it, nor on GAZEBO_MODEL_PATH; give the folder that "
                    f"holds it with --package-path DIR")
    return None


def download_problem(error_text: str, local: dict[str, Path]) -> str | None:
    """A one-line reason for a parse error that was a remote package's failed download, or None."""
    match = re.search(r"when downloading '([^']+)'", error_text)
    if match is None:
        return None
    name = match.group(1)
    return (f"package://{name}/ has no local copy (no package.xml named {name!r} in the file's folder or the "
            f"{PACKAGE_SEARCH_LEVELS} above it, nor under --package-path) and Drake could not download it; give "
            f"a local copy's folder with --package-path DIR")


@contextlib.contextmanager
def quiet_downloads():
    """A context in which Drake's log says nothing below a warning (its INFO line "PackageMap:
    Downloading ..." for a remote package): a failed download is then one ObjectError line."""
    logger = logging.getLogger("drake")
    level = logger.level
    logger.setLevel(logging.WARNING)
    try:
        yield
    finally:
        logger.setLevel(level)
