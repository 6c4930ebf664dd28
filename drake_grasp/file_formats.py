"""The object file formats the project reads, as the command line's help and messages name them: one
list, so that a format added to the readers (`objects.mesh_files`, `objects.model_files`) is named
everywhere at once. Plain text and no imports, so the command line's parser stays quick to build."""

MESH_FORMATS = ("OBJ, STL, PLY, OFF, glTF/GLB, 3MF, COLLADA .dae, OpenUSD (with usd-core), MuJoCo .msh, "
                "VTK, Inventor .iv, VRML .wrl")
MODEL_FORMATS = "SDF, URDF, MJCF, a GraspIt! body .xml"
