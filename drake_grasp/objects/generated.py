"""What the object generators share (`novel`, `everyday`, `flower`, `near_primitives`, `round`): Manifold's
solids as trimesh meshes, meshes as OBJ text whose bytes depend only on the mesh, and the manifest.

Booleans and extrusions use Manifold (the ``manifold3d`` package; https://github.com/elalish/manifold),
whose operations are guaranteed to return a closed 2-manifold. The OBJ text has a fixed number format
(µm), so the same generator seed gives byte-identical files, and so the same object fingerprint
(`sweeps.fingerprint`), on every machine.
"""

from __future__ import annotations

import csv
import io
import json
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
