"""The names drake-grasp documents as public, for scripts and notebooks (scripts/simulate_*.py and
scripts/compare_fig7.py read as examples of them).

The pieces of a trial, bottom up: a scenario (`load_scenario`) and an object (`resolve_object`: a
catalogue name, a primitive or a file); the station Diagram (`MakeStation`); the visual primitives,
the exploration sequencer and the start of the camera motion (`AddVisualPrimitives`,
`AddExplorationSequencer`, `start_camera_pose`, `start_configuration`); the supervisor that decides
and grasps (`AddCompliantGraspSupervisor`); simulating and judging it (`execute`, filling a
`TrialRecord`). A whole trial is `run(TrialSpec(...))`; an exploration alone is `explore`; the
Eigengrasp planner is `plan_reachable_grasp`, and a given grasp runs as `TrialSpec(method="eigengrasp",
planned=...)`. Evaluation, never part of the decision: `ground_truth`, `compare`.
"""

from drake_grasp.control.supervisor import AddCompliantGraspSupervisor
from drake_grasp.objects import ObjectSpec, resolve_object, resolve_user_object
from drake_grasp.perception.evaluation import compare, ground_truth
from drake_grasp.perception.exploration import explore
from drake_grasp.perception.wiring import (
    AddExplorationSequencer, AddVisualPrimitives, start_camera_pose, start_configuration,
)
from drake_grasp.station import DEFAULT_SCENARIO_FILE, MakeStation, Scenario, default_scenario_name, load_scenario
from drake_grasp.trial import PlannerSettings, TrialRecord, TrialSpec, plan_reachable_grasp, run
from drake_grasp.trial.execution import execute



def scenario_for(object_name: str) -> Scenario:
    """The scenario a trial of this object uses when none is named: the best estimate (table-top)
    for an object file or a generated object, the paper's algorithm for its objects and primitives
    (`station.default_scenario_name`; `TrialSpec` without a scenario name does the same)."""
    return load_scenario(DEFAULT_SCENARIO_FILE, default_scenario_name(object_name))


__all__ = [
    "AddCompliantGraspSupervisor", "AddExplorationSequencer", "AddVisualPrimitives", "MakeStation", "ObjectSpec",
    "PlannerSettings", "Scenario", "TrialRecord", "TrialSpec", "compare", "execute", "explore", "ground_truth",
    "load_scenario", "plan_reachable_grasp", "resolve_object", "resolve_user_object", "run", "scenario_for",
    "start_camera_pose", "start_configuration",
]
