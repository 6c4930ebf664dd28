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

A URI whose package is known neither locally nor remotely, or a remote package that cannot be
downloaded, is an ObjectError that says where a package.xml was looked for and how to give one.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
import xml.etree.ElementTree as ElementTree
from pathlib import Path

from drake_grasp.objects.spec import ObjectError

PACKAGE_SEARCH_LEVELS = 8  # folders above a model file searched for package.xml (bounded: never the whole disk)
_URI = re.compile(r"package://([A-Za-z0-9_.\-]+)/")


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
    folder = Path(model_file).resolve().parent
    for _ in range(levels + 1):
        candidate = folder / "package.xml"
        if candidate.is_file():
            try:
                found.setdefault(package_name(candidate), candidate)
            except ObjectError:
                pass
        if folder.parent == folder:
            break
        folder = folder.parent
    return found


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


def register_packages(package_map, model_file: Path, package_path=()) -> dict[str, Path]:
    """Registers the local packages a model file can use with a Drake PackageMap: those found above
    it (:func:`packages_above`), then those of `package_path` (each :func:`packages_under`; given
    last, they win). A name the map already has (Drake's remote ``drake_models``) is replaced.
    Returns {name: package.xml} of what was registered."""
    local = packages_above(model_file)
    for directory in package_path:
        local.update(packages_under(Path(directory)))
    for name, xml in local.items():
        if package_map.Contains(name):
            package_map.Remove(name)
        package_map.AddPackageXml(str(xml))
    return local


def missing_package_problem(text: str, package_map, local: dict[str, Path], model_file: Path) -> str | None:
    """Why the model file's URIs cannot resolve before parsing it (a package Drake knows neither
    locally nor remotely), or None."""
    for name in referenced_packages(text):
        if name not in local and not package_map.Contains(name):
            return (f"package://{name}/ is not known: no package.xml named {name!r} in the file's folder or the "
                    f"{PACKAGE_SEARCH_LEVELS} above it; give its folder with --package-path DIR")
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
