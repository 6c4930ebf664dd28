"""COLLADA (``.dae``) meshes: their triangles in metres, as Gazebo reads them.

Why: Gazebo's model collection (osrf/gazebo_models: ``coke_can``, ``bowl``, ``hammer``,
``plastic_cup``, ``monkey_wrench`` ...) and many ROS packages name COLLADA meshes, which Drake's
parser does not read. trimesh reads their triangles (through pycollada) but neither applies the
file's unit nor reads a file that leaves an image or a material incomplete (its loader then returns
an empty scene: Gazebo's ``gear_part``, ``pulley_part`` and ``disk_part``).

What is read, and how Gazebo's own loader treats it:

* **the unit** (``<asset><unit meter="0.0254"/>``: inches) is applied: Gazebo scales by it, so
  ``coke_can.dae`` is drawn in millimetres and ``hammer.dae`` in inches. The model files rely on it:
  ``cordless_drill`` ships the same drill as a DAE in millimetres and as an STL in metres. A file
  that declares none is in metres, COLLADA's default;
* **the up axis** (``<up_axis>Y_UP</up_axis>``) is not applied: Gazebo does not apply it either (its
  mesh-import tutorial has the user turn a Y-up duck in the SDF), and ``coke_can.dae`` and
  ``plastic_cup.dae`` declare Y up while their cans stand along z. An object so loaded rests as
  Gazebo shows it;
* **the scene's node transforms** are applied to the geometries they instance; a file without a
  scene, or whose scene pycollada cannot follow (Gazebo's ``gear_part``, whose one node instances a
  material it leaves incomplete), gives every geometry as stored;
* **only triangles** matter: lines and points are skipped, and so are the parts pycollada finds
  incomplete or broken (an image without a file, a material it does not know), as trimesh skips
  unsupported ones.
"""

from __future__ import annotations

import warnings

import numpy as np

from drake_grasp.objects.spec import ObjectError


def _triangles(primitive) -> tuple[np.ndarray, np.ndarray] | None:
    """(vertices, faces) of one COLLADA primitive, or None for one without triangles (lines, points)."""
    import collada

    if isinstance(primitive, (collada.triangleset.TriangleSet, collada.triangleset.BoundTriangleSet)):
        triangles = primitive
    elif isinstance(primitive, (collada.polylist.Polylist, collada.polylist.BoundPolylist,
                                collada.polygons.Polygons, collada.polygons.BoundPolygons)):
        triangles = primitive.triangleset()
    else:
        return None
    vertex = np.asarray(triangles.vertex, float).reshape(-1, 3)
    index = np.asarray(triangles.vertex_index, np.int64).reshape(-1, 3)
    if len(vertex) == 0 or len(index) == 0:
        return None
    return vertex, index


def _gathered(primitives) -> tuple[list, list]:
    """The vertex arrays and face arrays (indices offset into their concatenation) of `primitives`."""
    vertices, faces, count = [], [], 0
    for primitive in primitives:
        found = _triangles(primitive)
        if found is None:
            continue
        vertex, index = found
        vertices.append(vertex)
        faces.append(index + count)
        count += len(vertex)
    return vertices, faces


def read_dae(data: bytes, label: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (n, 3) float64 in metres, faces (m, 3) int64) of a COLLADA file's bytes: every
    triangle its scene draws (each geometry where its nodes put it), in the file's declared unit
    scaled to metres (module docstring). ObjectError (one line starting with `label`) for a file
    that is not COLLADA or has no triangles, or without pycollada installed."""
    import io

    try:
        import collada
    except ImportError:
        raise ObjectError(f"{label}: reading COLLADA (.dae) needs pycollada: pip install pycollada") from None
    ignore = [collada.common.DaeUnsupportedError, collada.common.DaeBrokenRefError,
              collada.common.DaeIncompleteError]
    try:
        with warnings.catch_warnings():  # pycollada's transforms use numpy.matrix: not the user's concern
            warnings.simplefilter("ignore", PendingDeprecationWarning)
            document = collada.Collada(io.BytesIO(data), ignore=ignore)
            scene = ([p for geometry in document.scene.objects("geometry") for p in geometry.primitives()]
                     if document.scene is not None else [])
            vertices, faces = _gathered(scene)
            if not faces:  # no scene, or one whose nodes pycollada dropped (an instance of a broken material)
                vertices, faces = _gathered([p for geometry in document.geometries for p in geometry.primitives])
    except Exception as error:  # pycollada raises many types for what is not COLLADA, or broken.
        reason = " ".join(str(error).split())[:160] or type(error).__name__
        raise ObjectError(f"{label}: cannot read COLLADA ({reason})") from None
    unit = document.assetInfo.unitmeter
    unit = float(unit) if unit is not None and np.isfinite(unit) and unit > 0 else 1.0
    if not faces:
        raise ObjectError(f"{label}: COLLADA file draws no triangles: no solid can be recovered")
    return np.concatenate(vertices) * unit, np.concatenate(faces)
