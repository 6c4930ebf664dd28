"""Files users bring that are not meshes or object models this project reads, and what to do instead.

Why: "file_type 'xacro' not supported" tells a user what failed but not how to go on, and each of
these formats has a one-step way to a file that loads: a ROS xacro file expands to a URDF, a CAD
file or a scene from a 3D tool exports a mesh. The advice is one line, given where the loader
would otherwise report it cannot read the file (exit code 2, before any work).
"""

from __future__ import annotations

from pathlib import Path

MESH_EXPORT = "export the object as a mesh (STL, OBJ, PLY, glTF or 3MF) and give that"

ADVICE = {
    ".xacro": ("a xacro macro file (ROS): expand it to a URDF first (`xacro FILE > object.urdf`, "
               "from ROS's xacro package) and give the URDF"),
    ".step": f"a CAD file (STEP): {MESH_EXPORT}; trimesh reads STEP itself if `cascadio` is installed",
    ".stp": f"a CAD file (STEP): {MESH_EXPORT}; trimesh reads STEP itself if `cascadio` is installed",
    ".iges": f"a CAD file (IGES): {MESH_EXPORT}",
    ".igs": f"a CAD file (IGES): {MESH_EXPORT}",
    ".sldprt": f"a SolidWorks part: {MESH_EXPORT}",
    ".f3d": f"a Fusion 360 design: {MESH_EXPORT}",
    ".fbx": f"an FBX scene: {MESH_EXPORT}",
    ".blend": f"a Blender file: {MESH_EXPORT} (File > Export)",
    ".max": f"a 3ds Max scene: {MESH_EXPORT}",
    ".skp": f"a SketchUp model: {MESH_EXPORT}",
    ".pcd": "a point cloud (PCL): a solid cannot be recovered from points alone; reconstruct a surface "
            "(e.g. Poisson reconstruction) and give the mesh",
    ".bag": "a ROS bag, not an object file: give the object's mesh or model file",
    ".world": "a world file (several models and a ground), not one object: give the object's own model file",
}


def advice(path: str | Path) -> str | None:
    """What `path` is and what to give instead, if its suffix names a format users bring that is not
    read here (a xacro file, CAD, a 3D tool's scene, a point cloud); None otherwise. (OpenUSD is read
    with the optional usd-core: :mod:`drake_grasp.objects.usd_mesh`.)"""
    suffixes = [suffix.lower() for suffix in Path(path).suffixes]
    for suffix in reversed(suffixes):
        if suffix in ADVICE:
            return ADVICE[suffix]
    return None


# glTF extensions that compress a mesh's geometry: trimesh decodes Draco with the optional DracoPy and
# meshopt not at all. Without a decoder it reads placeholder zeros (a "flat" mesh), so the file's own
# `extensionsRequired` is what tells the user why.
_GLTF_COMPRESSION = {
    "KHR_draco_mesh_compression": ("DracoPy", "the optional DracoPy (`pip install DracoPy`) decodes it"),
    "EXT_meshopt_compression": (None, "not decoded here"),
}


def gltf_required_extensions(path: str | Path) -> list[str]:
    """The `extensionsRequired` of a glTF (`.gltf` JSON or `.glb` binary) file; [] if it names none or
    cannot be read (the mesh reader then says why)."""
    import json
    import struct

    try:
        data = Path(path).read_bytes()
        if data[:4] == b"glTF":  # GLB: a 12-byte header, then the JSON chunk (length, type, text)
            length, kind = struct.unpack_from("<II", data, 12)
            text = data[20:20 + length] if kind == 0x4E4F534A else b"{}"
        else:
            text = data
        required = json.loads(text.decode("utf-8", errors="replace")).get("extensionsRequired", [])
    except (OSError, ValueError, struct.error, AttributeError):
        return []
    return [str(name) for name in required] if isinstance(required, list) else []


def gltf_compression_problem(path: str | Path) -> str | None:
    """Why a glTF file's geometry cannot be read here (compressed by an extension that no installed
    decoder reads), with what to do, or None."""
    import importlib.util

    for name in gltf_required_extensions(path):
        if name in _GLTF_COMPRESSION:
            module, how = _GLTF_COMPRESSION[name]
            if module is not None and importlib.util.find_spec(module) is not None:
                continue
            return (f"its meshes are compressed (glTF extension {name}): {how}; or export the object without "
                    "compression")
    return None
