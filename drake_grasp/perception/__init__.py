"""Active perception with the wrist camera, in two sides that the layout keeps apart:

* the algorithm's side: `wiring` (the visual primitives, the exploration sequencer and the camera
  motion wired around a station; the start pose) and `exploration` (one exploration, run, and its
  estimate);
* the evaluation side: `evaluation` (the object's true geometry and an estimate's errors against it,
  and their formatting), which only studies, records and reports read; ground truth never reaches
  the decision.

The names of all three are importable from here, as they were from the single module
`drake_grasp.perception` this package replaces.

`config` holds `PerceptionConfig`, the exploration's choices: a part of the station's scenario. The
station imports it, and `wiring` imports the station, so this package imports nothing eagerly: its
names are looked up on first use (PEP 562), and `import drake_grasp.perception.config` loads that
module alone, without an import cycle.
"""

import importlib

# Where each public name lives.
_WHERE = {
    "config": ("PerceptionConfig",),
    "evaluation": ("EstimateErrors", "GroundTruth", "compare", "comparison_record", "format_comparison",
                   "ground_truth", "object_extent", "object_support", "true_pose"),
    "exploration": ("ExplorationResult", "explore", "read_estimate", "resemblance_statistics", "run_exploration"),
    "wiring": ("AddExplorationSequencer", "AddVisualPrimitives", "Exploration", "MakeExploration", "VisualPrimitives",
               "camera_mount", "load_perception_config", "object_labels", "start_camera_pose", "start_configuration",
               "trial_noise_seed"),
}
_MODULE_OF = {name: module for module, names in _WHERE.items() for name in names}

__all__ = sorted(_MODULE_OF)


def __getattr__(name: str):
    if name in _WHERE:
        return importlib.import_module(f"{__name__}.{name}")
    if name in _MODULE_OF:
        return getattr(importlib.import_module(f"{__name__}.{_MODULE_OF[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_MODULE_OF) | set(_WHERE))
