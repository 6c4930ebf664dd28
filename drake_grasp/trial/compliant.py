"""A trial of the compliance-centric algorithm: explore with the wrist camera, decide, grasp, in one Diagram.

The station, the visual primitives, the exploration sequencer and the supervisor are wired into one
Diagram (docs/design.md §3.2) and run by the same `execution.execute` as every other method.
"""

import dataclasses
import time

import numpy as np
from pydrake.systems.framework import DiagramBuilder

from drake_grasp.control.supervisor import AddCompliantGraspSupervisor
from drake_grasp.estimate_error import EstimateError
from drake_grasp.objects import ObjectSpec
from drake_grasp.perception.evaluation import compare, ground_truth
from drake_grasp.perception.wiring import (AddExplorationSequencer, AddVisualPrimitives, start_camera_pose,
                                           start_configuration)
from drake_grasp.protocol import TrialVariation
from drake_grasp.station import MakeStation, Scenario
from drake_grasp.trial.execution import apply_variation, execute
from drake_grasp.trial.record import TrialRecord


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
    wall_start = time.perf_counter()
    config = perception_config or scenario.perception
    protocol = scenario.protocol
    variation = TrialVariation.draw(seed, protocol)
    nominal = np.array([scenario.object.x, scenario.object.y, 0.0])
    scenario, spec = apply_variation(scenario, spec, variation)
    record = TrialRecord(object=spec.name, method="compliant", grasp=grasp or "", seed=seed, success=False,
                         failure="", variation=dataclasses.asdict(variation), estimate_source="camera")
    station = MakeStation(scenario, spec, camera=True)
    builder = DiagramBuilder()
    builder.AddNamedSystem("station", station.diagram)
    primitives = AddVisualPrimitives(builder, station, config, connect_arm=False, noise_seed=seed)
    sequencer = AddExplorationSequencer(builder, primitives, config)
    q_start = start_configuration(station, start_camera_pose(nominal, config, config.depth.table_height), config)
    supervisor = AddCompliantGraspSupervisor(builder, station, primitives, sequencer, q_start,
                                             protocol.execution, grasp, estimate_error)

    def start_camera_motion(context):
        motion = primitives.camera_motion
        motion.SetInitialPositions(motion.GetMyMutableContextFromRoot(context), q_start)

    run = execute(builder, station, supervisor, protocol, q_start, record,
                  config.sequencer.total_time + protocol.execution.hold_time + 60.0, replay_html, monitor_period,
                  start_camera_motion)
    decision = run.decision
    if decision is not None:
        estimate = decision.estimate
        record.grasp = decision.executed
        record.chosen_grasp = decision.chosen
        record.resemblances = dict(estimate.resemblances)
        record.estimate = {k: v for k, v in estimate.to_dict().items() if k not in ("evidence", "timings")}
        record.estimate["decided_at"] = decision.time
        if estimate.found and run.X_WO_decision is not None:
            errors = compare(estimate, ground_truth(spec, run.X_WO_decision))
            record.estimate_errors = {
                "centre": errors.centre, "depth": errors.depth, "axis_deg": errors.axis_deg,
                "extents": [float(e) for e in errors.extents], "shape_correct": errors.shape_correct}
    record.wall_time = time.perf_counter() - wall_start
    return record
