"""What the object generators share (`novel`, `everyday`, `flower`, `near_primitives`, `round`):
Manifold's solids as trimesh meshes, meshes as OBJ text whose bytes depend only on the mesh, a mesh
placed on the table, a one-link URDF, and the files and manifest they write.

Booleans and extrusions use Manifold (the ``manifold3d`` package; https://github.com/elalish/manifold),
whose operations are guaranteed to return a closed 2-manifold. The OBJ text has a fixed number format
(µm), so the same generator seed gives byte-identical files, and so the same object fingerprint
(`sweeps.fingerprint`), on every machine.
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import trimesh

CIRCULAR_SEGMENTS = 48  # facets around a generated cylinder, ellipsoid or torus


def manifold():
    """The ``manifold3d`` module (imported on first use: only the generators need it)."""
    import manifold3d

    return manifold3d


def to_trimesh(solid) -> trimesh.Trimesh:
    """A Manifold solid as a trimesh mesh (metres, vertices merged)."""
    mesh = solid.to_mesh()
    vertices = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    faces = np.asarray(mesh.tri_verts, dtype=np.int64)
    return trimesh.Trimesh(vertices, faces, process=True)


def obj_text(mesh: trimesh.Trimesh) -> str:
    """The mesh as Wavefront OBJ with a fixed number format (µm), so equal meshes give equal bytes."""
    out = io.StringIO()
    out.write("# drake-grasp novel object (metres)\n")
    for x, y, z in mesh.vertices:
        out.write(f"v {x:.6f} {y:.6f} {z:.6f}\n")
    for a, b, c in mesh.faces:
        out.write(f"f {a + 1} {b + 1} {c + 1}\n")
    return out.getvalue()


def write_manifest(out_dir: Path, rows: list[dict], fields: list[str]) -> None:
    """``manifest.json`` (every row whole) and ``manifest.csv`` (`fields`, the extents as one
    space-separated cell) of generated objects in `out_dir`."""
    (out_dir / "manifest.json").write_text(json.dumps(rows, indent=1) + "\n")
    with open(out_dir / "manifest.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields, lineterminator="\n", extrasaction="ignore")
        writer.writeheader()
        for row in rows:
            writer.writerow({**row, "extents_m": " ".join(f"{e:.6f}" for e in row["extents_m"])})


def write_generated(out_dir: Path, name: str, mesh: trimesh.Trimesh, shape_class: str, seed: int, index: int,
                    urdf: str | None = None, **extra) -> dict:
    """Writes generated object `name`: its mesh as ``name.obj`` and, given `urdf` (the text of a URDF
    naming that OBJ), ``name.urdf``. Returns its manifest row: "file" is what a user passes as
    ``--object``, "assets" the other files it needs, then its class, format ("mesh" or "urdf"), seed,
    index, largest extent, extents (m), volume (m³) and `extra`."""
    (out_dir / f"{name}.obj").write_text(obj_text(mesh))
    file, assets, kind = f"{name}.obj", [], "mesh"
    if urdf is not None:
        (out_dir / f"{name}.urdf").write_text(urdf)
        file, assets, kind = f"{name}.urdf", [f"{name}.obj"], "urdf"
    return {"file": file, "assets": assets, "class": shape_class, "format": kind, "seed": seed, "index": index,
            "size_m": round(float(np.max(mesh.extents)), 6), "extents_m": [round(float(e), 6) for e in mesh.extents],
            "volume_m3": float(f"{mesh.volume:.6e}"), **extra}


def inertial_element(mass: float, com, inertia) -> str:
    """A URDF inertial element, as XML text, of a real `mass` (kg) with its centre of mass `com` (m)
    and `inertia` (3 × 3, kg·m²) about it."""
    return (f'<inertial><origin xyz="{com[0]:.6f} {com[1]:.6f} {com[2]:.6f}"/><mass value="{mass:.6f}"/>'
            f'<inertia ixx="{inertia[0, 0]:.6e}" ixy="{inertia[0, 1]:.6e}" ixz="{inertia[0, 2]:.6e}" '
            f'iyy="{inertia[1, 1]:.6e}" iyz="{inertia[1, 2]:.6e}" izz="{inertia[2, 2]:.6e}"/></inertial>')


def one_link_urdf(name: str, mesh_file: str, inertial: str) -> str:
    """A one-link URDF named `name` whose visual and collision are `mesh_file`, with the `inertial`
    element given as XML text."""
    geometry = f'<geometry><mesh filename="{mesh_file}"/></geometry>'
    return (f'<?xml version="1.0"?>\n<robot name="{name}">\n  <link name="{name}">\n    {inertial}\n'
            f'    <visual>{geometry}</visual>\n    <collision>{geometry}</collision>\n  </link>\n</robot>\n')


def placed_on_table(mesh: trimesh.Trimesh, rng: np.random.Generator) -> trimesh.Trimesh:
    """`mesh` turned about z by an angle drawn from `rng`, centred in x and y, resting on z = 0, its
    vertices rounded to what an OBJ file holds (µm) and wound outward (in place; returned)."""
    mesh.apply_transform(trimesh.transformations.rotation_matrix(rng.uniform(0.0, 2.0 * math.pi), [0, 0, 1]))
    low, high = mesh.bounds
    mesh.apply_translation([-(low[0] + high[0]) / 2.0, -(low[1] + high[1]) / 2.0, -low[2]])
    mesh.vertices = np.round(mesh.vertices, 6)
    if mesh.volume < 0:
        mesh.invert()
    return mesh
