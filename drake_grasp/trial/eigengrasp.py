"""A trial of the compliance-agnostic baseline: the Eigengrasp planner's grasp, executed and judged.

The planner (`baselines.eigengrasp`, docs/design.md §4.6) gets the exact object model, with the
table as an obstacle, and plans in the object's frame. The planner moves a free hand and knows nothing
of the arm, so the grasps executed are the best of its ranked candidates that the WAM can reach
(§5.6). A planned grasp is executed from a retreat along its palm normal to the planned hand pose
with the planned finger posture, then torque close: the same executor, timings and success test as
every compliant grasp (`execution.run_trial`), so the methods differ only in where the hand goes.
"""

import numpy as np
from pydrake.math import RigidTransform

from drake_grasp.control.arm_motion import UNREACHABLE, ArmKinematics, ReachError
from drake_grasp.estimate_error import EstimateError, perturb_pose
from drake_grasp.grasps import planned_grasp
from drake_grasp.objects import ObjectSpec
from drake_grasp.station import MakeStation, Scenario
from drake_grasp.trial.given_plan import PlanFunction, run_trial
from drake_grasp.trial.record import TrialRecord
from drake_grasp.trial.spec import PlannerSettings, TrialSpec


def reachable_grasps(plan: dict, scenario: Scenario, obj: ObjectSpec, count: int = 3) -> list[dict]:
    """The `count` best of the plan's ranked candidates that the WAM can execute.

    The planner moves a free hand (docs/design.md §4.6) and knows nothing of the arm: some of its best
    grasps come from beyond the object, where the WAM cannot take the hand. As a user of GraspIt!
    would, we execute the best grasps the arm can reach: pre-grasp and grasp poses solvable by
    inverse kinematics with the object at its nominal pose. Each returned grasp dict gets its rank in
    the planner's list ("planner_rank").

    Args:
        plan: the planner's result as plain data (`EigengraspPlan.to_dict`).
        scenario: the station scenario (the arm, its start, the object's placement).
        obj: the object planned for.
        count: how many grasps at most.
    """
    station = MakeStation(scenario, obj, camera=False)
    kinematics = ArmKinematics(station.plant, station.wam)
    X_WO = station.X_WO_nominal()
    q_start = np.asarray(scenario.protocol.start_configuration, float)
    chosen = []
    for rank, grasp in enumerate(plan["candidates"], start=1):
        grasp_plan = planned_grasp(RigidTransform(np.asarray(grasp["X_OH"])), np.asarray(grasp["joint_angles"]), X_WO)
        try:
            q = kinematics.solve(grasp_plan.X_WP_pregrasp, q_start)
            kinematics.solve(grasp_plan.X_WP_target, q)
        except ReachError:
            continue
        chosen.append(dict(grasp, planner_rank=rank))
        if len(chosen) == count:
            break
    return chosen


def plan_reachable_grasp(scenario: Scenario, obj: ObjectSpec, settings: PlannerSettings) -> tuple[dict | None, str]:
    """Plans with the Eigengrasp planner (table loaded) and picks its `settings.rank`-th best grasp the
    arm can reach. Returns (that grasp as the planner gave it, with its "planner_rank"; "") or, if the
    arm can reach fewer of the planner's grasps, (None, why)."""
    from baselines.eigengrasp.planner import plan_eigengrasp

    plan = plan_eigengrasp(obj, max_steps=settings.steps, seed=settings.seed, energy_name=settings.energy,
                           table=True).to_dict()
    reachable = reachable_grasps(plan, scenario, obj, count=settings.rank)
    if len(reachable) < settings.rank:
        return None, (f"the arm can reach {len(reachable)} of the planner's {len(plan['candidates'])} grasps, "
                      f"fewer than rank {settings.rank}")
    return reachable[settings.rank - 1], ""


def planned_plan(planned: dict, estimate_error: EstimateError | None = None) -> PlanFunction:
    """The plan function of a planned grasp ({"X_OH": 4x4, "joint_angles": 8}): the hand pose is
    expressed against the object's pose, with `estimate_error`'s offsets and yaw added to that pose
    (X_WH = X_WO_erred X_OH; its size scale does not apply: the planner has the exact model)."""
    X_OH = RigidTransform(np.asarray(planned["X_OH"], float))
    q = np.asarray(planned["joint_angles"], float)

    def plan(X_WO, object_spec):
        return planned_grasp(X_OH, q, perturb_pose(X_WO, object_spec, estimate_error))

    return plan


def run_eigengrasp_trial(spec: TrialSpec, scenario: Scenario, obj: ObjectSpec, replay_html: str | None = None,
                         monitor_period: float = 0.05) -> TrialRecord:
    """One planner trial: the spec's planned grasp, or, with none, plan now (`spec.planner`) and take
    its rank-th reachable grasp; execute it and judge it. The record keeps the grasp executed
    (`planned_grasp`); if the arm can reach too few of the planner's grasps, it fails as UNREACHABLE
    before anything moves."""
    if spec.planned is not None:
        planned, grasp = {"X_OH": spec.planned["X_OH"], "joint_angles": spec.planned["joint_angles"]}, spec.planned
    else:
        grasp, why = plan_reachable_grasp(scenario, obj, spec.planner or PlannerSettings())
        if grasp is None:
            return TrialRecord(object=obj.name, method="eigengrasp", grasp=spec.grasp, seed=spec.seed, success=False,
                               failure=UNREACHABLE, detail=why)
        planned = {"X_OH": grasp["X_OH"], "joint_angles": grasp["pregrasp_joint_angles"]}
    record = run_trial(scenario, obj, planned_plan(planned, spec.estimate_error), seed=spec.seed,
                       method="eigengrasp", grasp=spec.grasp, replay_html=replay_html, monitor_period=monitor_period)
    record.planned_grasp = dict(grasp)
    return record
