"""Executing a grasp and judging it: the one simulate-and-judge step every method goes through.

Every method is executed by the same arm, hand controller and timings, and judged by the same test
(docs/design.md §4.7): `trial.assembly` builds every method's Diagram and hands it to `execute` here.
In every trial:

* the object is placed with the trial's seeded variation (position, yaw, friction): `apply_variation`;
* the executor moves to the pre-grasp pose, approaches (guarded), closes, lifts 10 cm and holds 10 s;
* success = the object is off the table at the end and moved less than 1 cm and 10 degrees relative
  to the palm during the hold.

A trial never crashes its caller: an unreachable plan, a simulation that throws or diverges, is a
failed trial with its reason.
"""

import dataclasses
import math

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import DiagramBuilder

from drake_grasp.control.grasp_executor import GraspExecutor, GraspPhase
from drake_grasp.objects import ObjectSpec
from drake_grasp.protocol import TrialVariation
from drake_grasp.simulation import AddReplay, StartSimulation, recording
from drake_grasp.station import Scenario
from drake_grasp.success import GraspObservation, judge_grasp
from drake_grasp.trial.record import SIMULATION_ERROR, TrialRecord

def apply_variation(scenario: Scenario, spec: ObjectSpec, variation: TrialVariation) -> tuple[Scenario, ObjectSpec]:
    """The scenario and object of one trial: placement offset and yawed, friction scaled."""
    scenario = dataclasses.replace(scenario, object=dataclasses.replace(
        scenario.object,
        x=scenario.object.x + variation.dx,
        y=scenario.object.y + variation.dy,
        yaw_deg=scenario.object.yaw_deg + math.degrees(variation.dyaw),
    ))
    base_friction = spec.friction if spec.friction is not None else scenario.contact.friction
    spec = dataclasses.replace(spec, friction=base_friction * variation.friction_scale)
    return scenario, spec


@dataclasses.dataclass
class Executed:
    """What `execute` saw besides the record: the supervisor's decision (None for a given plan) and
    the object's true pose when the grasp was decided (for evaluating the estimate)."""

    decision: object = None
    X_WO_decision: RigidTransform | None = None


def execute(builder: DiagramBuilder, station, executor: GraspExecutor, protocol, q_start: np.ndarray,
             record: TrialRecord, time_limit: float, replay_html: str | None, monitor_period: float,
             initialize=None) -> Executed:
    """Builds the Diagram in `builder`, simulates the executor's sequence to its end, and judges it
    with the success test, filling `record` (failure, lift, slip, contacts, fingers, sim_time).

    Args:
        builder: holds the station and the executor (or supervisor), connected.
        station: the station in it.
        executor: the sequence to run to GraspPhase.DONE.
        protocol: the scenario's TrialProtocol (the success test's thresholds).
        q_start: the arm's joint angles at time 0, rad.
        record: the record to fill.
        time_limit: simulated time after which the trial fails, s.
        replay_html: write a Meshcat replay there.
        monitor_period: how often the phase is checked, s.
        initialize: called with the root context before the simulation starts (more initial state).
    """
    plant = station.plant
    station_system = station.diagram
    meshcat = AddReplay(builder, station_system) if replay_html else None
    sim = StartSimulation(builder.Build(), station, q_start, initialize)
    simulator, context, plant_context = sim.simulator, sim.context, sim.plant_context
    executor_context = executor.GetMyContextFromRoot(context)
    object_body = plant.get_body(plant.GetBodyIndices(station.object_instance)[0])
    palm = plant.GetFrameByName("bh_palm")
    table_bodies = set(int(b) for b in plant.GetBodyIndices(plant.GetModelInstanceByName("table")))
    X_WO = station.X_WO_nominal()  # the object at rest on the table: the lift is measured from it
    run = Executed()

    def X_PO() -> RigidTransform:
        return palm.CalcPoseInWorld(plant_context).inverse() @ object_body.EvalPoseInWorld(plant_context)

    def touching() -> tuple[list[str], bool]:
        """Hand links touching the object, and whether the object touches the table."""
        names, on_table = _object_contacts(plant, plant_context, object_body, table_bodies)
        return sorted(names), on_table

    X_PO_hold, rise_hold, contacts_after_close = None, None, []
    try:
        with recording(meshcat, replay_html, look_at=X_WO.translation()):
            simulator.Initialize()
            if executor.phase(executor_context) != GraspPhase.EXPLORE:
                run.X_WO_decision = object_body.EvalPoseInWorld(plant_context)
            while executor.phase(executor_context) != GraspPhase.DONE:
                if context.get_time() > time_limit:
                    raise RuntimeError(f"the grasp sequence did not finish in {time_limit:.0f} s")
                phase_before = executor.phase(executor_context)
                simulator.AdvanceTo(context.get_time() + monitor_period)
                phase = executor.phase(executor_context)
                p_WO = object_body.EvalPoseInWorld(plant_context).translation()
                if not np.all(np.isfinite(p_WO)) or np.linalg.norm(p_WO) > 10.0:
                    raise RuntimeError("the simulation diverged (object far away or not finite)")
                if phase_before == GraspPhase.EXPLORE and phase != GraspPhase.EXPLORE:
                    run.X_WO_decision = object_body.EvalPoseInWorld(plant_context)
                if phase_before == GraspPhase.CLOSE and phase == GraspPhase.LIFT:
                    contacts_after_close, _ = touching()
                if phase_before != GraspPhase.HOLD and phase == GraspPhase.HOLD:
                    X_PO_hold = X_PO()
                    rise_hold = float(p_WO[2] - X_WO.translation()[2])
    except Exception as e:  # a failed simulation is a failed trial, never a crash of the run
        record.failure = SIMULATION_ERROR
        record.detail = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        record.sim_time = context.get_time()
        run.decision = executor.progress(executor_context).decision
        return run

    progress = executor.progress(executor_context)
    run.decision = progress.decision
    record.sim_time = context.get_time()
    if progress.outcome:  # the sequence ended before a grasp (object not found, arm could not reach)
        record.failure, record.detail = progress.outcome, progress.detail
        return run
    contacts_end, on_table = touching()
    p_WO_end = object_body.EvalPoseInWorld(plant_context).translation()
    record.lift = float(p_WO_end[2] - X_WO.translation()[2])
    record.contacts_after_close = " ".join(contacts_after_close)
    record.contacts_at_end = " ".join(contacts_end)
    record.approach_stopped_on_contact = bool(progress.stopped_on_contact)
    q_hand = station.hand_controller.joint_angles(plant.get_state_output_port(station.hand).Eval(plant_context))
    record.finger_angles = [float(q_hand[0])] + [float(a) for a in q_hand[2:8]]
    status = station_system.GetOutputPort("hand.finger_status").Eval(station_system.GetMyContextFromRoot(context))
    record.breakaway = [bool(b > 0.5) for b in status[:3]]
    record.breakaway_angles = [float(a) for a in status[3:]]
    if X_PO_hold is not None:
        slip = X_PO_hold.inverse() @ X_PO()
        record.slip_distance = float(np.linalg.norm(X_PO().translation() - X_PO_hold.translation()))
        record.slip_angle = float(slip.rotation().ToAngleAxis().angle())
    observation = GraspObservation(touched_after_close=bool(contacts_after_close), rise_at_hold=rise_hold,
                                   lift_at_end=record.lift, on_table_at_end=on_table,
                                   slip_distance=record.slip_distance, slip_angle=record.slip_angle)
    record.failure = judge_grasp(observation, protocol.execution.lift_height, protocol.slip_distance,
                                 protocol.slip_angle_deg)
    record.success = record.failure == ""
    return run


def _object_contacts(plant, plant_context, object_body, table_bodies: set) -> tuple[set, bool]:
    results = plant.get_contact_results_output_port().Eval(plant_context)
    inspector = plant.get_geometry_query_input_port().Eval(plant_context).inspector()
    object_index = int(object_body.index())
    names, on_table = set(), False

    def note(a: int, b: int):
        nonlocal on_table
        if a == object_index:
            a, b = b, a
        if b != object_index:
            return
        if a in table_bodies:
            on_table = True
        else:
            names.add(plant.get_body(BodyIndex(a)).name())

    for i in range(results.num_hydroelastic_contacts()):
        surface = results.hydroelastic_contact_info(i).contact_surface()
        bodies = [int(plant.GetBodyFromFrameId(inspector.GetFrameId(g)).index()) for g in (surface.id_M(), surface.id_N())]
        note(*bodies)
    for i in range(results.num_point_pair_contacts()):
        info = results.point_pair_contact_info(i)
        note(int(info.bodyA_index()), int(info.bodyB_index()))
    return names, on_table
