"""A trial of the compliance-centric algorithm: explore with the wrist camera, decide, grasp, in one Diagram.

What differs from every other method (docs/design.md §3.2): the wrist camera, the visual primitives,
the exploration sequencer and the supervisor, wired around the station by `assembly.assemble_and_run`,
which runs every method's trial the same way.
"""

import numpy as np
from drake_grasp.control.supervisor import AddCompliantGraspSupervisor
from drake_grasp.estimate_error import EstimateError
from drake_grasp.objects import ObjectSpec
from drake_grasp.perception.evaluation import compare, ground_truth
from drake_grasp.perception.wiring import (AddExplorationSequencer, AddVisualPrimitives, start_camera_pose,
                                           start_configuration)
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.station import Scenario
from drake_grasp.trial.assembly import Assembled, Wiring, assemble_and_run_branches
from drake_grasp.trial.record import TrialRecord
from drake_grasp.trial.sensing import sense_hold


def run_compliant_trial(scenario: Scenario, spec: ObjectSpec, *, seed: int, grasp: str | None = None,
                        replay_html: str | None = None, perception_config=None, monitor_period: float = 0.05,
                        estimate_error: EstimateError | None = None) -> TrialRecord:
    """The compliance-centric algorithm, one trial, in one Diagram: explore, decide, grasp.

    The wrist camera starts above the object's *nominal* placement, looking down; the object is placed
    with the trial's seeded variation. The visual primitives explore it and estimate its centre, axes,
    size and the three shape resemblances; the supervisor (`control.supervisor`) then executes the
    grasp of the most resembling shape (or `grasp`, forced by the caller, for Fig. 6's all-grasps
    protocol), computed from the estimate only, with the same executor, timings and success test as
    every other method. No ground truth enters the decision or the grasp; the record keeps the
    estimate and, for evaluation, its errors against the object's true pose when the decision was made.

    `estimate_error` (issue 15's capture regions) is added to the camera's estimate before the grasp
    is computed from it; the record keeps the camera's estimate as it was, and its errors.
    """
    return run_compliant_trials(scenario, spec, seed=seed, grasps=[grasp], replay_html=replay_html,
                                perception_config=perception_config, monitor_period=monitor_period,
                                estimate_error=estimate_error)[0]


def run_compliant_trials(scenario: Scenario, spec: ObjectSpec, *, seed: int, grasps: list[str | None],
                         replay_html: str | None = None, perception_config=None, monitor_period: float = 0.05,
                         estimate_error: EstimateError | None = None) -> list[TrialRecord]:
    """`run_compliant_trial` for each of `grasps` (None: the algorithm's own choice) after one
    exploration: the exploration and the decision's estimate do not depend on the grasp executed,
    so they are simulated once, and each grasp goes on from a copy of the state at the decision
    (`assembly.assemble_and_run_branches`). The records are those of the trials run one by one
    (wall time aside: each gets its share of the exploration's)."""
    return [_compliant_record(trial, scenario) for trial in run_compliant_branches(
        scenario, spec, seed=seed, grasps=grasps, replay_html=replay_html, perception_config=perception_config,
        monitor_period=monitor_period, estimate_error=estimate_error)]


def run_compliant_branches(scenario: Scenario, spec: ObjectSpec, *, seed: int, grasps: list[str | None],
                           replay_html: str | None = None, perception_config=None, monitor_period: float = 0.05,
                           estimate_error: EstimateError | None = None, exclude: tuple = ()) -> list[Assembled]:
    """The trials of `run_compliant_trials` as run (`assembly.Assembled`: each record, and what its
    simulation saw), for callers that go on from where a trial left the object (`trial.attempts`).
    `exclude`: grasps that already failed on this object, once per failure (`funnel.planning.choose_grasp`)."""
    config = perception_config or scenario.perception
    nominal = np.array([scenario.object.x, scenario.object.y, 0.0])  # where the object is expected

    def wire(builder, station, scenario, spec, record) -> Wiring:
        """Perception around the station, and the supervisor that decides and grasps."""
        protocol = scenario.protocol
        primitives = AddVisualPrimitives(builder, station, config, connect_arm=False, noise_seed=seed)
        sequencer = AddExplorationSequencer(builder, primitives, config)
        q_start = start_configuration(station, start_camera_pose(nominal, config, config.depth.table_height), config)
        supervisor = AddCompliantGraspSupervisor(builder, station, primitives, sequencer, q_start,
                                                 protocol.execution, grasps[0], estimate_error, config.grasp_search,
                                                 exclude)

        def start_camera_motion(context):
            motion = primitives.camera_motion
            motion.SetInitialPositions(motion.GetMyMutableContextFromRoot(context), q_start)

        def force_grasp(context, grasp):
            supervisor.set_forced_grasp(supervisor.GetMyMutableContextFromRoot(context), grasp)

        return Wiring(supervisor, q_start, config.sequencer.total_time + protocol.execution.hold_time + 60.0,
                      start_camera_motion, force_grasp)

    branches = [({"method": "compliant", "grasp": grasp or "", "estimate_source": "camera"}, grasp)
                for grasp in grasps]
    return assemble_and_run_branches(scenario, spec, seed=seed, branches=branches, camera=True, wire=wire,
                                     replay_html=replay_html, monitor_period=monitor_period)


def _compliant_record(trial: Assembled, scenario: Scenario) -> TrialRecord:
    """A camera-driven trial's record, with what the decision saw: the estimate, the resemblances,
    the chosen grasp and the estimate's errors against the truth at the decision; and what the wrist
    camera told of the hold (`sensing.sense_hold`, against the scenario's lift height and obvious slip,
    with its camera's intrinsics)."""
    record, run, spec = trial.record, trial.run, trial.spec
    lift_height, slip_distance = scenario.protocol.execution.lift_height, scenario.protocol.slip_distance
    decision = run.decision
    if decision is not None:
        estimate = decision.estimate
        record.grasp = decision.executed
        record.chosen_grasp = decision.chosen
        record.resemblances = dict(estimate.resemblances)
        record.estimate = {k: v for k, v in estimate.to_dict().items() if k not in ("evidence", "timings")}
        # Which estimate placed the grasp: the table-top one (its column solid) or the paper's silhouettes.
        record.estimate["estimator"] = "table-top" if estimate.table_top is not None else "silhouettes"
        record.estimate["decided_at"] = decision.time
        record.estimate["resemblance_margin"] = estimate.resemblance_margin
        if decision.grasp_search is not None:  # the funnel search: what it scored, and what it changed
            record.grasp_search = {**decision.grasp_search, "paper_choice": decision.paper_choice}
        if run.seen_points is not None and decision.plan is not None:  # what the robot can tell of the hold
            seen = decision.estimate.as_grasp_estimate()
            top = float(seen.center[2]) + seen.half_extent_along(np.array([0.0, 0.0, 1.0]))
            in_hand = None if run.depth_at_hold is None else (run.depth_at_hold, run.depth_at_end)
            lifted = None if run.depth_at_lift is None else (run.depth_at_lift, run.depth_at_end)
            record.sensed = sense_hold(run.seen_points, top, lift_height, seen.table_height, in_hand,
                                       slip_distance, lifted, CameraIntrinsics.from_camera_config(scenario.camera),
                                       run.too_near, scenario.protocol.slip_angle_deg).to_dict()
        if estimate.found and run.X_WO_decision is not None:
            errors = compare(estimate, ground_truth(spec, run.X_WO_decision))
            record.estimate_errors = {
                "centre": errors.centre, "depth": errors.depth, "axis_deg": errors.axis_deg,
                "extents": [float(e) for e in errors.extents], "shape_correct": errors.shape_correct}
    record.wall_time = trial.wall_time()
    return record
