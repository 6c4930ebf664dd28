"""Objects: what a grasp is tried on, from the paper's catalogue to the files users bring.

One concept per module:

* `spec`: the data model (`ShapePiece`, `ObjectSpec`), the cache of generated meshes, the assumed
  numbers (density, tolerances); `mass_properties`: the pieces' geometry and mass properties, and
  an ObjectSpec built from them;
* `catalogue`: the paper's nine objects and Fig. 4's primitive families;
* importing files: `mesh_files` (read, repaired, joined, resting pose), `mujoco_msh` (MuJoCo's
  binary .msh), `vtk_mesh` (Drake's tetrahedral .vtk, by its boundary), `collada_mesh` (COLLADA
  .dae, in its declared unit), `inventor_mesh` with `inventor_scene` and `inventor_shapes` (Open
  Inventor .iv and VRML .wrl), `graspit_files` (GraspIt!'s body files), `threemf_mesh` (3D printing's
  .3mf, in its declared unit), `usd_mesh` (OpenUSD, with the optional usd-core), `other_formats`
  (formats not read, and what to give instead), `repair` (a real mesh into closed shells), `solid` (which shells are one object, and their union), `sizes` (the sizes the
  hand can grasp; a file outside them refused), `model_files` (SDFormat, URDF, MJCF) with `mjcf_files` (MJCF read here),
  `readable_models` (a model file's text and meshes as Drake's parser can take them),
  `inertia_checks` (a file's inertial checked), `packages` (where ``package://`` and Gazebo's
  ``model://`` URIs point),
  `names` (what a command line names, and the options object files take), `check`
  (`drake-grasp objects check`);
* convex pieces for contact: `pieces` (decomposition, merging), `piece_budget` (at most 64 vertices
  a piece), `cleaning` (no slivers, a minimum thickness);
* the Drake model: `drake_model` (SDFormat of an ObjectSpec, AddObject, the support table);
* generators: `novel` (novel test objects), `near_primitives`, `mesh_zoo` (defective files).

The data model's names are imported here; every other public name of these modules is reachable
as ``drake_grasp.objects.<name>`` too, looked up on first use (PEP 562), so that
``from drake_grasp.objects import resolve_object`` works without an import cycle.

Moved here in release 0.1 from ``drake_grasp.catalogue``, ``drake_grasp.user_objects`` (now
`mesh_files`, `pieces`, `names`), ``drake_grasp.object_model`` (now `drake_model`),
``drake_grasp.piece_budget`` and ``drake_grasp.geometry``; the old paths were removed in 0.3 (CHANGELOG.md).
"""

from drake_grasp.objects.spec import *  # noqa: F401,F403  (the data model: the package's core names)

# Modules whose names are looked up here on first use, in this order.
_PARTS = ("spec", "mass_properties", "catalogue", "names", "mesh_files", "pieces", "model_files", "drake_model", "check")


# Every module of the package (`from drake_grasp.objects import repair` imports it, as usual).
_MODULES = _PARTS + ("cleaning", "collada_mesh", "inertia_checks", "mesh_zoo", "mujoco_msh", "near_primitives", "novel", "packages",
                     "piece_budget", "readable_models", "repair", "sizes", "solid", "standing", "vtk_mesh",
                     "inventor_mesh", "inventor_scene", "inventor_shapes", "graspit_files", "threemf_mesh",
                     "other_formats", "usd_mesh", "mjcf_files")


def __getattr__(name: str):
    import importlib

    if name in _MODULES:
        return importlib.import_module(f"{__name__}.{name}")
    if not name.startswith("__"):
        for part in _PARTS:
            module = importlib.import_module(f"drake_grasp.objects.{part}")
            if name in vars(module):
                return vars(module)[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
