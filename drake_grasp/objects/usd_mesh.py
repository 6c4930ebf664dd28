"""OpenUSD (``.usd``, ``.usda``, ``.usdc``, ``.usdz``) objects: their triangles in metres, z up, read with
Pixar's own library when it is installed.

Why: NVIDIA Isaac Sim and Omniverse ship their object sets as USD (Isaac's YCB props among them), and a
user coming from there has those files. USD's binary crate format has no reader but Pixar's, so
reading needs the optional ``usd-core`` package (``pip install usd-core``, about 30 MB); without it a
USD file is refused in one line that says so, and how to export a mesh instead.

What is read (the stage composed as USD composes it: references, payloads, variants):

* every ``UsdGeom.Mesh`` (polygons fanned into triangles), also inside instances (Isaac Sim makes
  its assets' meshes instanceable), and the implicit solids ``Cube``, ``Sphere``,
  ``Cylinder``, ``Cone`` and ``Capsule`` (tessellated, along their ``axis``), each placed by its
  world transform at the default time; prims of purpose ``guide`` are left out, as USD's renderers do;
* **the stage's unit**: ``metersPerUnit`` (USD's fallback is 0.01, centimetres), so the object comes in
  metres and needs no ``--scale``;
* **the up axis**: a Y-up stage (USD's fallback) is turned so that its up is z, as glTF is.

Materials, physics schemas (mass, collision approximations) and animation are not read: the mass is
the user's or density × volume, as for a mesh file.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.inventor_shapes import fans
from drake_grasp.objects.spec import Y_UP_TO_Z_UP, ObjectError

USD_SUFFIXES = (".usd", ".usda", ".usdc", ".usdz")
SEGMENTS = 32  # around a tessellated implicit solid


def _implicit_solid(prim, UsdGeom) -> trimesh.Trimesh | None:
    """The triangles of a Cube, Sphere, Cylinder, Cone or Capsule prim in its own frame (None for other
    prims). USD's cylinders, cones and capsules lie along their ``axis`` attribute (default Z)."""
    if prim.IsA(UsdGeom.Cube):
        return trimesh.creation.box([UsdGeom.Cube(prim).GetSizeAttr().Get()] * 3)
    if prim.IsA(UsdGeom.Sphere):
        return trimesh.creation.icosphere(subdivisions=3, radius=UsdGeom.Sphere(prim).GetRadiusAttr().Get())
    for kind, make in ((UsdGeom.Cylinder, trimesh.creation.cylinder), (UsdGeom.Cone, trimesh.creation.cone),
                       (UsdGeom.Capsule, trimesh.creation.capsule)):
        if prim.IsA(kind):
            shape = kind(prim)
            radius, height = shape.GetRadiusAttr().Get(), shape.GetHeightAttr().Get()
            if kind is UsdGeom.Cone:
                mesh = make(radius=radius, height=height, sections=SEGMENTS)
                mesh.apply_translation([0.0, 0.0, -height / 2.0])  # USD's cone is centred on its axis
            elif kind is UsdGeom.Capsule:
                mesh = make(radius=radius, height=height, count=[SEGMENTS, SEGMENTS])
            else:
                mesh = make(radius=radius, height=height, sections=SEGMENTS)
            axis = shape.GetAxisAttr().Get()
            if axis == "X":
                mesh.apply_transform(trimesh.transformations.rotation_matrix(math.pi / 2, [0.0, 1.0, 0.0]))
            elif axis == "Y":
                mesh.apply_transform(trimesh.transformations.rotation_matrix(-math.pi / 2, [1.0, 0.0, 0.0]))
            return mesh
    return None


def _polygon_mesh(prim, UsdGeom, label: str) -> tuple[np.ndarray, np.ndarray] | None:
    """(points, triangles) of a Mesh prim, its polygons fanned; None for one without faces. A face of
    fewer than 3 vertices (invalid in UsdGeom's schema, and skipped by its renderers) draws nothing
    and is skipped here too, as in Inventor's face sets."""
    mesh = UsdGeom.Mesh(prim)
    points = mesh.GetPointsAttr().Get()
    counts = mesh.GetFaceVertexCountsAttr().Get()
    indices = mesh.GetFaceVertexIndicesAttr().Get()
    if not points or not counts or not indices:
        return None
    points = np.asarray(points, float).reshape(-1, 3)
    counts = np.asarray(counts, np.int64)
    indices = np.asarray(indices, np.int64)
    if counts.sum() != len(indices) or np.any(counts < 0):
        raise ObjectError(f"{label}: mesh {prim.GetPath()} has face counts that do not match its indices")
    if indices.min() < 0 or indices.max() >= len(points):
        raise ObjectError(f"{label}: mesh {prim.GetPath()} has a point index out of range (0-{len(points) - 1})")
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    triangles = fans(indices, starts, counts)
    return (points, triangles) if len(triangles) else None


@contextlib.contextmanager
def _quiet_stderr():
    """USD reports what it could not compose (a material file in a format it has no plugin for, as
    the usd-wg's chess pieces name MaterialX files) on the process's stderr, line by line; the
    geometry is unaffected, so those reports are held back here."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as sink:
        os.dup2(sink.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)


def read_usd(path: Path, label: str) -> tuple[np.ndarray, np.ndarray]:
    """(vertices in metres with z up, triangle faces) of every solid a USD stage draws.

    Raises:
        ObjectError: One line: ``usd-core`` is not installed, the stage does not open, or it draws no
            triangles.
    """
    try:
        from pxr import Usd, UsdGeom
    except ImportError:
        raise ObjectError(f"{label}: an OpenUSD file: reading it needs the optional package usd-core "
                          "(pip install usd-core); or export the object as a mesh (STL, OBJ, glTF or 3MF)") from None
    try:
        with _quiet_stderr():
            stage = Usd.Stage.Open(str(path))
    except Exception as error:  # pxr raises Tf.ErrorException with multi-line text
        first = " ".join(str(error).split())[:160]
        raise ObjectError(f"{label}: USD could not open it ({first})") from None
    if stage is None:
        raise ObjectError(f"{label}: USD could not open it")
    cache = UsdGeom.XformCache(Usd.TimeCode.Default())
    vertices, faces, count = [], [], 0
    # Instance proxies too: Isaac Sim's assets make their meshes instanceable, and a plain traversal
    # stops at an instance.
    for prim in stage.Traverse(Usd.TraverseInstanceProxies(Usd.PrimDefaultPredicate)):
        if not prim.IsA(UsdGeom.Gprim) or UsdGeom.Imageable(prim).ComputePurpose() == UsdGeom.Tokens.guide:
            continue
        if prim.IsA(UsdGeom.Mesh):
            found = _polygon_mesh(prim, UsdGeom, label)
        else:
            solid = _implicit_solid(prim, UsdGeom)
            found = None if solid is None else (np.asarray(solid.vertices), np.asarray(solid.faces))
        if found is None or len(found[1]) == 0:
            continue
        points, triangles = found
        M = np.array(cache.GetLocalToWorldTransform(prim), float)  # row vectors: [p 1] · M
        vertices.append(points @ M[:3, :3] + M[3, :3])
        faces.append(triangles + count)
        count += len(points)
    if not faces:
        raise ObjectError(f"{label}: file contains no triangles (no mesh or solid in the USD stage): no solid "
                          "can be recovered")
    V = np.vstack(vertices) * float(UsdGeom.GetStageMetersPerUnit(stage))
    if UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y:
        V = V @ Y_UP_TO_Z_UP[:3, :3].T  # y up → z up, as glTF
    return V, np.vstack(faces)
