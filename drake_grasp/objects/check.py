"""`drake-grasp objects check FILE`: load an object file exactly as a trial would, and say what was
found and done.

Why: a user's file goes through reading, repair, joining of shells, units, inertia checks, convex
decomposition and a resting pose before any trial runs. Each step speaks once, as a one-line note or
warning, while the file loads; this report gathers those lines with what the object became (its
size, volume, mass and where its inertia came from, its convex pieces, its resting pose) and the
time the load took (first load and again, from the cache), so that a user can check a file before
spending a study on it. A refused file is the same one-line error a trial gives (exit code 2).
"""

from __future__ import annotations

import collections
import dataclasses
import math
import time
import warnings
from pathlib import Path

import numpy as np

from drake_grasp.objects.spec import MeshNote, ObjectSpec, UnitsWarning, UnstablePoseWarning


@dataclasses.dataclass
class CheckReport:
    """What loading an object file found and did (SI units)."""

    file: str
    notes: list[str]  # every note and warning the load gave, in order, without the file's name
    extents: tuple[float, float, float]  # m, along O's axes
    volume: float  # m³
    mass: float  # kg
    density: float  # kg/m³
    inertia_source: str  # "mesh" (uniform density), "file" or "geometry (file's replaced)"
    principal_moments: tuple[float, float, float]  # kg·m² about the centre of mass
    pieces: int
    piece_vertices: int  # in the convex meshes
    primitives: dict  # {kind: count} of the pieces that are Drake's primitives (a box, a sphere), not meshes
    rpy_TO: tuple[float, float, float]  # rad: how it rests on the table
    rest_height: float  # m: its centre of mass above the table
    load_time: float  # s, first load in this process
    cached_load_time: float  # s, the same load again (decomposition cached)

    @property
    def piece_summary(self) -> str:
        """What the pieces are: "8 vertices", "a box", "a box and 2 cylinders; 120 vertices"."""
        kinds = [f"{'a' if n == 1 else n} {kind}{'es' if n > 1 and kind == 'box' else 's' if n > 1 else ''}"
                 for kind, n in sorted(self.primitives.items())]
        shapes = " and ".join(filter(None, [", ".join(kinds[:-1]), kinds[-1] if kinds else ""]))
        meshes = f"{self.piece_vertices} vertices" if self.piece_vertices or not shapes else ""
        return "; ".join(filter(None, [shapes, meshes]))

    def lines(self) -> list[str]:
        """The report as the command prints it."""
        x, y, z = (100 * v for v in self.extents)
        out = [f"{self.file}: accepted"]
        out += [f"  {note}" for note in self.notes]
        out.append(f"  size {x:.1f} x {y:.1f} x {z:.1f} cm; volume {self.volume * 1e6:.1f} cm³; mass {self.mass * 1000:.1f} g "
                   f"({self.density:.0f} kg/m³)")
        moments = ", ".join(f"{m:.3g}" for m in self.principal_moments)
        out.append(f"  inertia from {self.inertia_source}: principal moments {moments} kg·m²")
        out.append(f"  {self.pieces} convex piece{'s' if self.pieces != 1 else ''} for contact ({self.piece_summary})")
        roll, pitch, yaw = (math.degrees(a) for a in self.rpy_TO)
        pose = "with its z up" if max(abs(roll), abs(pitch)) < 1e-6 else f"turned roll {roll:.1f}°, pitch {pitch:.1f}°"
        out.append(f"  rests {pose}, centre of mass {self.rest_height * 100:.1f} cm above the table")
        out.append(f"  load {self.load_time:.2f} s (again, cached: {self.cached_load_time:.2f} s)")
        return out


def _load(argument: str, options: dict) -> tuple[ObjectSpec, list[warnings.WarningMessage], float]:
    from drake_grasp.objects.names import resolve_user_object

    start = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = resolve_user_object(argument, **options)
    return spec, caught, time.perf_counter() - start


def check_object(argument: str, **options) -> tuple[ObjectSpec, CheckReport]:
    """Loads an object argument (a file, a primitive or a catalogue name) as a trial does, with the
    command line's object-file options, and reports on it.

    Raises:
        ObjectError: the file is refused (one line naming it and why).
    """
    from drake_grasp.objects.model_files import InertiaWarning

    spec, caught, first = _load(argument, options)
    _, _, again = _load(argument, options)
    prefix = f"{argument}: "
    kinds = (MeshNote, UnitsWarning, UnstablePoseWarning, InertiaWarning)
    notes = []
    for w in caught:
        if issubclass(w.category, kinds):
            text = str(w.message)
            text = text[len(prefix):] if text.startswith(prefix) else text
            kind = "note" if issubclass(w.category, MeshNote) else "warning"
            notes.append(f"{kind}: {text}")
    suffix = Path(argument).suffix.lower()
    replaced = any(issubclass(w.category, InertiaWarning) for w in caught)
    if suffix in (".sdf", ".urdf", ".xml", ".mjcf"):
        source = "the collision geometry (the file's was replaced)" if replaced else "the file"
        if options.get("inertia") == "geometry":
            source = "the collision geometry"
        elif suffix == ".xml" and not replaced and _graspit_body_without_inertia(argument):
            source = "the solid at uniform density (the GraspIt! file gives no <inertia_matrix>)"
        elif suffix in (".sdf", ".urdf") and not _gives_inertial(argument):
            source = "the solid at uniform density (the file gives no <inertial>)"
    else:
        source = "the solid at uniform density"
    inertia = spec.inertia_matrix()
    vertices = 0
    for piece in spec.pieces:
        if piece.mesh_path:
            vertices += sum(1 for line in Path(piece.mesh_path).read_text().splitlines() if line.startswith("v "))
    primitives = collections.Counter(piece.kind for piece in spec.pieces if not piece.mesh_path)
    report = CheckReport(
        file=argument, notes=notes, extents=tuple(spec.extents), volume=spec.volume, mass=spec.mass,
        density=spec.mass / spec.volume if spec.volume > 0 else float("nan"), inertia_source=source,
        principal_moments=tuple(float(m) for m in np.linalg.eigvalsh(inertia)), pieces=len(spec.pieces),
        piece_vertices=vertices, primitives=dict(primitives), rpy_TO=tuple(spec.rpy_TO),
        rest_height=spec.rest_height, load_time=first, cached_load_time=again)
    return spec, report


def _gives_inertial(argument: str) -> bool:
    """Whether an SDFormat or URDF file gives any link an <inertial> (else Drake's parser gives its
    links no mass, and the loader uses the solid at uniform density)."""
    import xml.etree.ElementTree as ElementTree

    try:
        return any(True for _ in ElementTree.parse(Path(argument).expanduser()).getroot().iter("inertial"))
    except (ElementTree.ParseError, OSError):
        return True


def _graspit_body_without_inertia(argument: str) -> bool:
    from drake_grasp.objects import graspit_files

    return graspit_files.graspit_kind(argument) == "body" and not graspit_files.gives_inertia(argument)


def write_replay(spec: ObjectSpec, html_path: str | Path, visual: str | None = None, scale: float = 1.0) -> None:
    """A browser view (Meshcat, one offline HTML file) of the object's convex pieces for contact
    (coloured, half transparent) over its visual mesh (grey), in the object frame O."""
    from pydrake.geometry import Meshcat, Rgba
    from pydrake.math import RigidTransform, RollPitchYaw

    meshcat = Meshcat()
    palette = [(0.90, 0.30, 0.20), (0.20, 0.55, 0.90), (0.30, 0.75, 0.30), (0.95, 0.70, 0.15),
               (0.60, 0.35, 0.80), (0.15, 0.75, 0.75)]
    for index, piece in enumerate(spec.pieces):
        r, g, b = palette[index % len(palette)]
        path = f"/object/pieces/{index:03d}"
        meshcat.SetObject(path, piece.drake_shape(), Rgba(r, g, b, 0.55))
        meshcat.SetTransform(path, RigidTransform(RollPitchYaw(piece.rpy_OP).ToRotationMatrix(), piece.p_OP))
    if visual is not None:
        import trimesh

        from drake_grasp.objects import cache_dir
        from drake_grasp.objects.mesh_files import _read_mesh

        mesh = _read_mesh(Path(visual), visual, scale)
        mesh.apply_translation(-_centre_of_mass_offset(spec, mesh))
        directory = cache_dir() / "check"
        directory.mkdir(parents=True, exist_ok=True)
        obj = directory / f"visual_{abs(hash((visual, scale)))}.obj"
        trimesh.Trimesh(mesh.vertices, mesh.faces, process=False).export(obj)
        from pydrake.geometry import Mesh

        meshcat.SetObject("/object/visual", Mesh(str(obj)), Rgba(0.7, 0.7, 0.7, 0.35))
    meshcat.SetCameraPose([0.25, -0.35, 0.25], [0.0, 0.0, 0.0])
    Path(html_path).write_text(meshcat.StaticHtml())


def _centre_of_mass_offset(spec: ObjectSpec, mesh) -> np.ndarray:
    """Where O's origin (the centre of mass) lies in the file's frame: the pieces are posed in O, the
    visual mesh in the file's frame; their bounding boxes' lower corners give the offset."""
    lo = np.min([np.min(_vertices(piece), axis=0) for piece in spec.pieces if piece.mesh_path] or [np.zeros(3)], axis=0)
    return mesh.bounds[0] - lo


def _vertices(piece) -> np.ndarray:
    rows = [line.split()[1:4] for line in Path(piece.mesh_path).read_text().splitlines() if line.startswith("v ")]
    return np.asarray(rows, float) + np.asarray(piece.p_OP, float)
