"""The trial layer: one grasp trial, from its description to its record.

    TrialSpec (plain data) ──run──> TrialRecord

`run(spec)` is the one entry point every caller uses (the sweeps' runner, the command line, the
demo, the studies, the tests). One concept per module:

* `spec`: `TrialSpec`, a trial as plain data (object, method, grasp, seed, scenario, planned grasp,
  estimate error), and the planner's settings for a trial that plans;
* `record`: `TrialRecord`, what a trial measured, and the failure reasons;
* `execution`: the simulate-and-judge step every method goes through (`run_trial` for a given grasp
  plan), and the seed's variation of the scenario;
* `compliant`: the compliance-centric algorithm's trial (camera, supervisor, one Diagram);
* `eigengrasp`: the Eigengrasp planner's trial (plan, pick a reachable grasp, execute);
* `entry`: `run`, which turns a spec's method into one of those (the oracle's plan is there), and
  `run_shared`, which runs camera-driven trials that differ only in their grasp after one exploration.
"""

from drake_grasp.control.arm_motion import UNREACHABLE
from drake_grasp.primitives.estimate import OBJECT_NOT_FOUND, PERCEPTION_FAILED
from drake_grasp.success import DROPPED_DURING_LIFT, MISSED, SLIPPED_DURING_HOLD
from drake_grasp.trial.compliant import run_compliant_trial, run_compliant_trials
from drake_grasp.trial.eigengrasp import plan_reachable_grasp, reachable_grasps, run_eigengrasp_trial
from drake_grasp.trial.entry import exploration_key, oracle_plan, resolve, run, run_shared
from drake_grasp.trial.execution import apply_variation
from drake_grasp.trial.given_plan import PlanFunction, run_trial
from drake_grasp.trial.record import FAILURES, SIMULATION_ERROR, TrialRecord
from drake_grasp.trial.spec import METHODS, PlannerSettings, TrialSpec

__all__ = [
    "DROPPED_DURING_LIFT", "FAILURES", "METHODS", "MISSED", "OBJECT_NOT_FOUND", "PERCEPTION_FAILED",
    "SIMULATION_ERROR", "SLIPPED_DURING_HOLD", "UNREACHABLE", "PlanFunction", "PlannerSettings", "TrialRecord",
    "TrialSpec", "apply_variation", "exploration_key", "oracle_plan", "plan_reachable_grasp", "reachable_grasps",
    "resolve", "run", "run_compliant_trial", "run_compliant_trials", "run_eigengrasp_trial", "run_shared", "run_trial",
]
