"""Active perception with the wrist camera, in two sides that the layout keeps apart:

* the algorithm's side: `wiring` (the visual primitives, the exploration sequencer and the camera
  motion wired around a station; the start pose) and `exploration` (one exploration, run, and its
  estimate);
* the evaluation side: `evaluation` (the object's true geometry and an estimate's errors against it,
  and their formatting), which only studies, records and reports read; ground truth never reaches
  the decision.

The names of all three are importable from here, as they were from the single module
`drake_grasp.perception` this package replaces.
"""

from drake_grasp.perception.evaluation import (  # noqa: F401
    EstimateErrors, GroundTruth, compare, comparison_record, format_comparison, ground_truth, object_extent,
    object_support, true_pose,
)
from drake_grasp.perception.exploration import (  # noqa: F401
    ExplorationResult, explore, read_estimate, resemblance_statistics, run_exploration,
)
from drake_grasp.perception.wiring import (  # noqa: F401
    AddExplorationSequencer, AddVisualPrimitives, Exploration, MakeExploration, VisualPrimitives, camera_mount,
    load_perception_config, object_labels, start_camera_pose, start_configuration, trial_noise_seed,
)

__all__ = [
    "AddExplorationSequencer", "AddVisualPrimitives", "EstimateErrors", "Exploration", "ExplorationResult",
    "GroundTruth", "MakeExploration", "VisualPrimitives", "camera_mount", "compare", "comparison_record", "explore",
    "format_comparison", "ground_truth", "load_perception_config", "object_extent", "object_labels",
    "object_support", "read_estimate", "resemblance_statistics", "run_exploration", "start_camera_pose",
    "start_configuration", "trial_noise_seed", "true_pose",
]
