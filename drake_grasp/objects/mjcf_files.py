"""MuJoCo MJCF object files, read here (Drake's MJCF parser reads only OBJ meshes, and MuJoCo-based
benchmarks ship objects as one body with STL mesh geoms).

What is read: the geoms of the body tree under ``worldbody`` (bodies and MuJoCo 3 ``<frame>``s nested
without joints are one rigid body; a free joint is allowed; beside a scene welded to the world, the one
free body is the object: `_the_object_body`), their poses, MuJoCo's defaults (``<default>`` classes),
``<include>``d files, the compiler's ``meshdir``/``assetdir``, ``angle`` and ``eulerseq``, mesh
``scale``, and each geom's ``mass`` or ``density`` (MuJoCo's default 1000 kg/m³) or the body's
``<inertial>``. Collision geoms are those MuJoCo would collide (``contype`` or ``conaffinity``
non-zero); if none, every geom; only their mesh files are read (a visual-only mesh may be missing).
The geoms become one mesh in the body frame that goes through the same repair and joining as a mesh
file (:mod:`drake_grasp.objects.mesh_files`); the file declares them one rigid body, so parts apart
are its parts, as in a URDF's link. The file's inertial is checked
(:mod:`drake_grasp.objects.inertia_checks`). Split from :mod:`drake_grasp.objects.model_files`, which
names it among the model-file loaders.
"""

from __future__ import annotations

import hashlib
import math
import os
import warnings
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.inertia_checks import _check_choice, checked_mass_properties
from drake_grasp.objects.mass_properties import combined_mass_properties
from drake_grasp.objects.rigid_assembly import articulation_message
from drake_grasp.objects.mesh_files import _one_line, object_from_triangles, read_triangles
from drake_grasp.objects.pieces import IMPORT_VERSION
from drake_grasp.objects.spec import (ArticulationNote, DEFAULT_DENSITY, DEFAULT_MAX_PIECES, MeshNote, ObjectError, ObjectSpec,
                                      YELLOW_PAPER_RGBA)


_MJCF_DEFAULT_DENSITY = 1000.0  # kg/m³: MuJoCo's default geom density


def _floats(text: str | None, count: int | None = None, label: str = "", what: str = "number list"
            ) -> np.ndarray | None:
    """The numbers of an attribute (None if absent); ObjectError naming `what` if they are not
    numbers, not `count` of them, or not finite (a NaN size must not pass for a flat sheet)."""
    if text is None:
        return None
    try:
        values = np.array([float(v) for v in text.split()], float)
    except ValueError:
        raise ObjectError(f"{label}: bad {what} {text!r}") from None
    if count is not None and len(values) != count:
        raise ObjectError(f"{label}: {what}: expected {count} numbers, got {text!r}")
    if not np.all(np.isfinite(values)):
        raise ObjectError(f"{label}: {what} {text!r} is not finite (NaN or inf)")
    return values


def _geom_name(geom: dict) -> str:
    return f"geom {geom['name']!r}" if geom.get("name") else f"{geom.get('type', 'sphere')} geom"


def _mjcf_rotation(element, degrees: bool, label: str, eulerseq: str = "xyz") -> np.ndarray:
    """The rotation an MJCF element's quat, axisangle, euler, xyaxes or zaxis gives (3×3), as MuJoCo
    reads them: a quat is (w, x, y, z); euler angles follow the compiler's `eulerseq`, each lowercase
    axis turning with the frame (intrinsic) and each uppercase one about the fixed frame."""
    if element.get("quat") is not None:
        q = _floats(element.get("quat"), 4, label, f"{element.tag} quat")
        if np.linalg.norm(q) < 1e-9:
            raise ObjectError(f"{label}: {element.tag} quat {element.get('quat')!r} is zero, not a rotation")
        return trimesh.transformations.quaternion_matrix(q / np.linalg.norm(q))[:3, :3]  # (w, x, y, z) as MJCF
    if element.get("axisangle") is not None:
        ax, ay, az, angle = _floats(element.get("axisangle"), 4, label, f"{element.tag} axisangle")
        angle = math.radians(angle) if degrees else angle
        return trimesh.transformations.rotation_matrix(angle, [ax, ay, az])[:3, :3]
    if element.get("euler") is not None:
        angles = _floats(element.get("euler"), 3, label, f"{element.tag} euler")
        angles = np.radians(angles) if degrees else angles
        R = np.eye(3)
        for axis, angle in zip(eulerseq, angles):
            turn = trimesh.transformations.rotation_matrix(angle, np.eye(3)["xyz".index(axis.lower())])[:3, :3]
            R = R @ turn if axis.islower() else turn @ R
        return R
    if element.get("xyaxes") is not None:
        axes = _floats(element.get("xyaxes"), 6, label, f"{element.tag} xyaxes")
        x = axes[:3] / np.linalg.norm(axes[:3])
        y = axes[3:] - (axes[3:] @ x) * x
        if np.linalg.norm(y) < 1e-9:
            raise ObjectError(f"{label}: {element.tag} xyaxes {element.get('xyaxes')!r}: the axes are parallel")
        y = y / np.linalg.norm(y)
        return np.column_stack([x, y, np.cross(x, y)])
    if element.get("zaxis") is not None:
        z = _floats(element.get("zaxis"), 3, label, f"{element.tag} zaxis")
        return trimesh.geometry.align_vectors([0, 0, 1], z / np.linalg.norm(z))[:3, :3]
    return np.eye(3)


def _mjcf_defaults(root) -> dict:
    """Geom attributes of each default class ("main" is the top level), inheriting from parents."""
    classes = {"main": {}}

    def walk(element, inherited, name):
        attributes = dict(inherited)
        geom = element.find("geom")
        if geom is not None:
            attributes.update(geom.attrib)
        classes[name] = attributes
        for child in element.findall("default"):
            walk(child, attributes, child.get("class", name))

    for top in root.findall("default"):
        walk(top, {}, top.get("class", "main"))
    return classes


def _from_to(geom: dict, label: str) -> tuple[np.ndarray, dict]:
    """The frame (4×4 in the body) and size of a geom given by ``fromto`` (x1 y1 z1 x2 y2 z2), as
    MuJoCo reads it: the geom's z axis runs from the first point to the second, its centre between
    them, and its half-length along z is half their distance; a capsule's or cylinder's radius is
    its first size, a box's or ellipsoid's x and y half-sizes its first two. Robot and object
    models often give their capsules and cylinders so."""
    kind = geom.get("type", "sphere")
    if kind not in ("capsule", "cylinder", "box", "ellipsoid"):
        raise ObjectError(f"{label}: {_geom_name(geom)}: 'fromto' is for capsules, cylinders, boxes and "
                          f"ellipsoids, not a {kind}")
    ends = _floats(geom["fromto"], 6, label, f"{_geom_name(geom)} fromto")
    start, end = ends[:3], ends[3:]
    half_length = float(np.linalg.norm(end - start)) / 2.0
    if half_length <= 0.0:
        raise ObjectError(f"{label}: {_geom_name(geom)}: 'fromto' gives two equal points")
    size = _floats(geom.get("size", "0 0 0"), None, label, f"{_geom_name(geom)} size")
    widths = list(size[:1]) if kind in ("capsule", "cylinder") else list(size[:2])
    X = np.eye(4)
    X[:3, :3] = trimesh.geometry.align_vectors([0, 0, 1], (end - start) / (2.0 * half_length))[:3, :3]
    X[:3, 3] = (start + end) / 2.0
    return X, {**geom, "size": " ".join(str(v) for v in [*widths, half_length])}


def _meshdir_hint(relative: str, meshdir: Path) -> str:
    """Where a missing mesh may be: collections that load their MJCF files from code (robogym) name
    meshes relative to a folder the code sets, not to the file's. If the mesh's `relative` path exists
    under a folder beside `meshdir` (the file's folder unless its compiler says otherwise) or one of its
    ancestors (up to four levels up), say so, and how MuJoCo would be told (``<compiler meshdir>``);
    else nothing."""
    if Path(relative).is_absolute():
        return ""
    ancestor = meshdir
    for _ in range(5):
        if ancestor.is_dir():
            for candidate in sorted(p for p in ancestor.iterdir() if p.is_dir()):
                if (candidate / relative).is_file():
                    return f" (it is under {candidate}: give the file <compiler meshdir=\"{candidate}\"/>)"
        if ancestor.parent == ancestor:
            break
        ancestor = ancestor.parent
    return ""


def _geom_mesh(geom: dict, meshes: dict, label: str) -> trimesh.Trimesh:
    """One MJCF geom as a closed triangle mesh in its own frame (m). `meshes` maps an asset's name to
    its folder (the compiler's meshdir), its path as the file writes it and its scale; the file is
    read here, so that a mesh no chosen geom uses (a visual-only one, which object collections often
    ship apart) is never needed."""
    kind = geom.get("type", "sphere")
    size = _floats(geom.get("size", "0 0 0"), None, label, f"{_geom_name(geom)} size")
    if kind == "mesh":
        name = geom.get("mesh")
        if name not in meshes:
            raise ObjectError(f"{label}: geom names mesh {name!r}, which the file's assets do not define")
        meshdir, file, scale = meshes[name]
        mesh_path = meshdir / file
        if not mesh_path.is_file():
            raise ObjectError(f"{label}: mesh {name!r}: {mesh_path} not found{_meshdir_hint(file, meshdir)}")
        loaded = read_triangles(mesh_path, f"{label}: mesh {name!r}: {mesh_path.name}")
        if scale is not None:
            loaded.apply_transform(np.diag([*scale, 1.0]))
        return loaded
    if kind == "box":
        return trimesh.creation.box(2.0 * size[:3])
    if kind == "sphere":
        return trimesh.creation.icosphere(subdivisions=3, radius=size[0])
    if kind == "ellipsoid":
        sphere = trimesh.creation.icosphere(subdivisions=3)
        sphere.apply_scale(size[:3])
        return sphere
    if kind == "cylinder":
        return trimesh.creation.cylinder(radius=size[0], height=2.0 * size[1], sections=32)
    if kind == "capsule":
        return trimesh.creation.capsule(radius=size[0], height=2.0 * size[1], count=[32, 16])
    raise ObjectError(f"{label}: geom type {kind!r} is not a solid an object can be made of")


_MAX_INCLUDE_DEPTH = 16  # nested <include>s deeper than this are taken for a cycle


def _expand_includes(element, main_dir: Path, label: str, digest, depth: int = 0) -> None:
    """Replace each ``<include file="..."/>`` under `element` by the children of the file's root
    (``<mujocoinclude>``, or ``<mujoco>`` as MuJoCo 3 also allows), in place and recursively.

    MuJoCo resolves an included file's path against the main model file's folder, whichever file
    names it, and so does this. Object collections built for MuJoCo (RoboHive's object_sim, for one)
    keep the body's geoms, the assets and the defaults in separate files that the object's file
    includes; without this their bodies read as empty."""
    for index, child in reversed(list(enumerate(list(element)))):
        if child.tag != "include":
            _expand_includes(child, main_dir, label, digest, depth)
            continue
        file = child.get("file")
        if file is None:
            raise ObjectError(f"{label}: an <include> without a file")
        if depth >= _MAX_INCLUDE_DEPTH:
            raise ObjectError(f"{label}: <include> of {file!r} nests deeper than {_MAX_INCLUDE_DEPTH} files "
                              "(an include cycle?)")
        included_path = main_dir / file
        if not included_path.is_file():
            raise ObjectError(f"{label}: included file {file!r} not found (looked for {included_path})")
        try:
            included = ElementTree.parse(included_path).getroot()
        except (ElementTree.ParseError, OSError) as error:
            raise ObjectError(f"{label}: included file {file!r}: cannot parse ({_one_line(error)})") from None
        if included.tag not in ("mujocoinclude", "mujoco"):
            raise ObjectError(f"{label}: included file {file!r} is not MJCF (its root element is "
                              f"<{included.tag}>)")
        digest.update(included_path.read_bytes())
        _expand_includes(included, main_dir, label, digest, depth + 1)
        element.remove(child)
        for offset, grandchild in enumerate(list(included)):
            element.insert(index + offset, grandchild)


def _is_free(body) -> bool:
    """Whether an MJCF body moves freely: a ``<freejoint>``, or a ``<joint type="free">``, of its own."""
    return body.find("freejoint") is not None or any(j.get("type") == "free" for j in body.findall("joint"))


def _the_object_body(label: str, bodies: list) -> list:
    """The top-level body that is the object, as a one-element list (ObjectError otherwise).

    One body is the object. Among several, the object is the one that moves freely: a body without a
    joint is welded to the world in MuJoCo, so it is the file's scene. Meta-World's object files, for
    one, include a scene (a table, walls) beside the object's body, which has a ``<freejoint>``; those
    bodies are left out, with a note naming them."""
    if len(bodies) == 1:
        return bodies

    def names(group) -> str:
        return ", ".join(repr(body.get("name", "unnamed")) for body in group)

    free = [body for body in bodies if _is_free(body)]
    if len(free) != 1:
        moving = f" ({len(free)} free: {names(free)})" if len(free) > 1 else " (none free)" if bodies else ""
        raise ObjectError(f"{label}: expected one top-level body, found {len(bodies)}{moving}; give a file with "
                          "the object alone, or with one free body beside a fixed scene")
    scene = [body for body in bodies if body is not free[0]]
    warnings.warn(f"{label}: the object is the free body {free[0].get('name', 'unnamed')!r}; "
                  f"{len(scene)} fixed to the world (the file's scene: {names(scene)}) left out", MeshNote,
                  stacklevel=4)
    return free


def _read_mjcf(path: Path, label: str) -> tuple[trimesh.Trimesh, tuple[float, float], tuple | None, str]:
    """(collision mesh in the root body's frame, the geoms' mass (kg) as (their given masses, their
    density × volume in the file's unit, which a scale multiplies by its cube), the body's explicit
    inertial (mass, com, inertia) or None, a digest of the file, the files it includes and its
    meshes)."""
    try:
        root = ElementTree.parse(path).getroot()
    except (ElementTree.ParseError, OSError) as error:
        raise ObjectError(f"{label}: cannot parse ({_one_line(error)})") from None
    if root.tag != "mujoco":
        raise ObjectError(f"{label}: not an MJCF file (its root element is <{root.tag}>, not <mujoco>)")
    digest = hashlib.sha256(path.read_bytes())
    _expand_includes(root, path.parent, label, digest)
    compiler = {}  # MuJoCo merges every <compiler> element's attributes, the later ones winning
    for element in root.findall("compiler"):
        compiler.update(element.attrib)
    degrees = compiler.get("angle", "degree") != "radian"
    eulerseq = compiler.get("eulerseq", "xyz").strip()
    if len(eulerseq) != 3 or any(axis not in "xyzXYZ" for axis in eulerseq):
        raise ObjectError(f"{label}: compiler eulerseq {eulerseq!r}: expected three of x, y, z, X, Y, Z")
    base = path.parent
    meshdir = base / compiler.get("meshdir", compiler.get("assetdir", ""))
    meshes = {}
    for asset in root.iter("asset"):
        for mesh in asset.findall("mesh"):
            file = mesh.get("file")
            if file is None:
                raise ObjectError(f"{label}: a mesh asset without a file (inline vertices are not supported)")
            name = mesh.get("name", Path(file).stem)
            meshes[name] = (meshdir, file, _floats(mesh.get("scale"), 3, label, f"mesh {name!r} scale"))
    worldbodies = root.findall("worldbody")  # several, once included files are in: MuJoCo merges them
    if not worldbodies:
        raise ObjectError(f"{label}: the file has no <worldbody>")
    defaults = _mjcf_defaults(root)
    pieces = []
    given_mass, density_volume = 0.0, 0.0  # kg: the geoms' own masses, and density × volume in the file's unit
    # The world's own geoms (a floor plane, say) are not the object: only bodies are.
    def top_bodies(element) -> list:  # the world's bodies, also those inside (nested) <frame>s
        return element.findall("body") + [b for frame in element.findall("frame") for b in top_bodies(frame)]

    bodies = _the_object_body(label, [body for worldbody in worldbodies for body in top_bodies(worldbody)])

    inertials, held = [], []

    def walk(body, X_RB: np.ndarray, default_class: str):
        for joint in body.findall("joint"):
            if joint.get("type", "hinge") != "free":
                held.append(f"{joint.get('type', 'hinge')} joint {joint.get('name', 'unnamed')!r}")
        for element in body.findall("inertial"):
            given = _floats(element.get("mass"), 1, label, "inertial mass")
            mass = math.nan if given is None else float(given[0])
            R = _mjcf_rotation(element, degrees, label, eulerseq)
            if element.get("fullinertia") is not None:
                xx, yy, zz, xy, xz, yz = _floats(element.get("fullinertia"), 6, label, "inertial fullinertia")
                inertia = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
            else:
                diagonal = _floats(element.get("diaginertia"), 3, label, "inertial diaginertia")
                inertia = np.diag(np.full(3, math.nan) if diagonal is None else diagonal)
            pos = _floats(element.get("pos", "0 0 0"), 3, label, "inertial pos")
            R_R = X_RB[:3, :3] @ R
            inertials.append((mass, X_RB[:3, :3] @ pos + X_RB[:3, 3], R_R @ inertia @ R_R.T))
        for element in body.findall("geom"):
            cls = element.get("childclass", None) or element.get("class", default_class)
            geom = dict(defaults.get(cls, defaults["main"]))
            geom.update(element.attrib)
            collides = geom.get("contype", "1") != "0" or geom.get("conaffinity", "1") != "0"
            if geom.get("fromto") is not None:
                X_BG, geom = _from_to(geom, label)
            else:
                X_BG = np.eye(4)
                X_BG[:3, :3] = _mjcf_rotation(element, degrees, label, eulerseq)
                X_BG[:3, 3] = _floats(geom.get("pos", "0 0 0"), 3, label, f"{_geom_name(geom)} pos")
            pieces.append((collides, X_RB @ X_BG, geom))
        # A <frame> (MuJoCo 3) only places what it holds; its geoms and bodies are the body's.
        for child in body.findall("body") + body.findall("frame"):
            X_BC = np.eye(4)
            X_BC[:3, :3] = _mjcf_rotation(child, degrees, label, eulerseq)
            X_BC[:3, 3] = _floats(child.get("pos", "0 0 0"), 3, label, f"{child.tag} pos")
            walk(child, X_RB @ X_BC, child.get("childclass", default_class))

    walk(bodies[0], np.eye(4), bodies[0].get("childclass", "main"))
    if held:
        warnings.warn(articulation_message(label, held), ArticulationNote, stacklevel=4)
    inertial = combined_mass_properties(inertials) if inertials else None
    chosen = [p for p in pieces if p[0]] or pieces
    if not chosen:
        raise ObjectError(f"{label}: the body has no geoms")
    chosen = [(collides, _geom_mesh(geom, meshes, label).apply_transform(X_RG), geom)
              for collides, X_RG, geom in chosen]
    for used in sorted({str(Path(*meshes[geom["mesh"]][:2])) for _, _, geom in chosen if geom.get("type") == "mesh"}):
        digest.update(Path(used).read_bytes())
    for _, mesh, geom in chosen:
        if geom.get("mass") is not None:
            given_mass += float(_floats(geom["mass"], 1, label, f"{_geom_name(geom)} mass")[0])
        else:
            volume = abs(float(mesh.volume)) if mesh.is_watertight else float(mesh.convex_hull.volume)
            density = _floats(geom.get("density"), 1, label, f"{_geom_name(geom)} density")
            density_volume += float(_MJCF_DEFAULT_DENSITY if density is None else density[0]) * volume
    collision = trimesh.util.concatenate([mesh for _, mesh, _ in chosen])
    return collision, (given_mass, density_volume), inertial, digest.hexdigest()


def object_from_mjcf(
    path: str | os.PathLike,
    mass: float | None = None,
    name: str | None = None,
    *,
    density: float = DEFAULT_DENSITY,
    max_pieces: int = DEFAULT_MAX_PIECES,
    closest_primitive: str | None = None,
    rgba=YELLOW_PAPER_RGBA,
    friction: float | None = None,
    inertia: str = "check",
    join_gap: float | None = None,
    largest_component: bool = False,
    scale: float = 1.0,
) -> ObjectSpec:
    """An object from a MuJoCo MJCF object file (one rigid body of mesh or primitive geoms).

    The collision geoms become one mesh in the top body's frame, repaired and joined like a mesh
    file's (:func:`drake_grasp.objects.mesh_files.object_from_mesh`); its mass is `mass`, else the body's
    ``<inertial>`` mass, else the geoms' (``mass``, or ``density`` × volume). The inertial, if the
    file gives one, is checked (:func:`inertia_problem`; `inertia` as in :func:`object_from_sdf`);
    without one the inertia is the collision geometry's at uniform density, as MuJoCo computes it.
    The object rests with the body frame's z up (laid on a stable face if it would tip over).

    Raises:
        ObjectError: One line naming the file and the problem.
    """
    label = os.fspath(path)
    path = Path(path).expanduser()
    _check_choice(label, inertia)
    if not path.is_file():
        raise ObjectError(f"{label}: file not found")
    collision, (given_mass, density_volume), inertial, digest = _read_mjcf(path, label)
    collision.apply_scale(scale)
    geom_mass = given_mass + density_volume * scale**3  # a volume scales as the cube; a given mass does not

    def mass_properties(volume, centroid, unit_inertia, requested_mass):
        file_mass = inertial[0] if inertial is not None else geom_mass
        if inertial is None or inertia == "geometry":
            chosen = file_mass if requested_mass is None else requested_mass
            return chosen, centroid, unit_inertia
        vertices = np.asarray(collision.vertices)
        checked_mass, com, unit = checked_mass_properties(
            label, file_mass, inertial[1] * scale, inertial[2] * scale**2, (volume, centroid, unit_inertia),
            lambda p: float(np.max(np.linalg.norm(vertices - p, axis=1))), inertia, density)
        return (checked_mass if requested_mass is None else requested_mass), com, unit

    return object_from_triangles(
        collision, label, path.stem, f"{digest}-mjcf{IMPORT_VERSION}", str(path.resolve()), mass=mass,
        name=name, density=density, scale=scale, max_pieces=max_pieces, closest_primitive=closest_primitive,
        rgba=rgba, friction=friction, largest_component=largest_component, join_gap=join_gap,
        inertia=mass_properties, one_body=True)
