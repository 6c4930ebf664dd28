"""The solid a closed mesh encloses: its shells, their union, its separate components.

Why: CAD tools often export one object as several closed shells that overlap (a handle's shell
passing into a body's). Summing the shells' volumes counts the overlap twice (two 6 cm × 6 cm ×
3 cm boxes, one moved 3 cm along the other: 216 cm³ summed, 162 cm³ enclosed), so mass and inertia must
come from their boolean union. Shells that do not touch after the union are separate objects, which
one rigid body cannot honestly model.

Booleans use Manifold (the ``manifold3d`` package, https://github.com/elalish/manifold), whose
results are guaranteed closed 2-manifolds.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import trimesh


@dataclasses.dataclass(frozen=True)
class Solid:
    """The enclosed solid of a mesh: its boundary mesh (metres), how many closed shells the file
    held and how many separate components (touching shells merged) they make."""

    mesh: trimesh.Trimesh
    shells: int
    components: int


def _to_manifold(mesh: trimesh.Trimesh):
    import manifold3d  # Imported here: only meshes of several shells need it.

    return manifold3d.Manifold(manifold3d.Mesh(
        vert_properties=np.asarray(mesh.vertices, dtype=np.float32),
        tri_verts=np.asarray(mesh.faces, dtype=np.uint32)))


def _to_trimesh(solid) -> trimesh.Trimesh:
    result = solid.to_mesh()
    return trimesh.Trimesh(np.asarray(result.vert_properties, dtype=float)[:, :3],
                           np.asarray(result.tri_verts, dtype=np.int64), process=True)


def enclosed_solid(mesh: trimesh.Trimesh) -> Solid:
    """The union of a closed mesh's shells (connected sets of faces), and its components.

    A mesh of one shell is returned as it is. Otherwise each shell is made outward-facing and the
    shells are united (Manifold, in single precision: about 1e-7 of the object's size); the
    result's components are the parts that do not touch.
    """
    if mesh.body_count <= 1:  # Vertex-connected components: cheap, and enough to rule shells out.
        return Solid(mesh, 1, 1)
    shells = mesh.split(only_watertight=False)
    import manifold3d

    solids = []
    for shell in shells:
        shell = shell.copy()
        if shell.volume < 0:
            shell.invert()
        solids.append(_to_manifold(shell))
    union = manifold3d.Manifold.batch_boolean(solids, manifold3d.OpType.Add)
    parts = union.decompose()
    return Solid(_to_trimesh(union), len(shells), len(parts))


def largest_component(solid: Solid) -> trimesh.Trimesh:
    """The component of largest volume."""
    parts = solid.mesh.split(only_watertight=False)
    return max(parts, key=lambda part: abs(part.volume)) if len(parts) > 1 else solid.mesh
