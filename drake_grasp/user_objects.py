"""Deprecated: split into :mod:`drake_grasp.objects.mesh_files` (reading, repair, joining),
:mod:`drake_grasp.objects.pieces` (convex pieces) and :mod:`drake_grasp.objects.names` (what a
command line names); this path works for one release, with a DeprecationWarning."""

import warnings

warnings.warn("drake_grasp.user_objects is deprecated: use drake_grasp.objects (mesh_files, pieces, names)",
              DeprecationWarning, stacklevel=2)


def __getattr__(name: str):
    import importlib

    for part in ("names", "mesh_files", "pieces"):
        module = importlib.import_module(f"drake_grasp.objects.{part}")
        if name in vars(module):
            return vars(module)[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
