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
