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
import time
from collections.abc import Callable

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.analysis import InitializeParams, Simulator
from pydrake.systems.framework import Context, DiagramBuilder

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
    """What `execute` saw besides the record: the supervisor's decision (None for a given plan), the
    object's true pose when the grasp was decided (for evaluating the estimate), and the wall time
    the run took, s (a branch's own part plus its share of the part it shared: `execute_branches`)."""

    decision: object = None
    X_WO_decision: RigidTransform | None = None
    wall_time: float = 0.0
    # At the end (stations with the wrist camera): the object's points the camera sees (`trial.sensing`:
    # what the robot can tell of a hold), and the object's true pose (where a next attempt finds it);
    # and the object's depth images as the lift began, as the hold began and at the end (whether it rose
    # with the hand, and whether it slid in it); and the share of the image the object fills nearer
    # than the camera ranges (`sensing.too_near_share`: pressed against the palm).
    seen_points: np.ndarray | None = None
    too_near: float = 0.0
    depth_at_lift: np.ndarray | None = None
    depth_at_hold: np.ndarray | None = None
    depth_at_end: np.ndarray | None = None
    X_WO_end: RigidTransform | None = None


@dataclasses.dataclass
class Branch:
    """One way a run goes on from its decision (`execute_branches`).

    Attributes:
        record: the record this branch fills.
        prepare: called with the root context before the decision, to set what makes this branch
            differ (for the camera-driven supervisor, the grasp it is forced to execute).
    """

    record: TrialRecord
    prepare: Callable[[Context], None] | None = None


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
    return execute_branches(builder, station, executor, protocol, q_start, [Branch(record)], time_limit,
                            replay_html, monitor_period, initialize)[0]


def execute_branches(builder: DiagramBuilder, station, executor: GraspExecutor, protocol, q_start: np.ndarray,
                     branches: list[Branch], time_limit: float, replay_html: str | None = None,
                     monitor_period: float = 0.05, initialize=None, wall_start: float | None = None) -> list[Executed]:
    """As `execute`, for several trials that are identical until the executor's decision: the run
    up to it (the camera's exploration) is simulated once, and each branch goes on from there.

    The first branch is simulated without a break, exactly as `execute` would. Each monitor period
    that starts while the executor explores begins with a copy of the root context (a clone, then
    its time and state copied again each period); the period in which the decision falls is
    therefore covered by a copy from its start, and every other branch continues from that copy,
    with its own Simulator and its own `prepare`, as if it had run from time 0 (docs/performance.md
    §7 shows the records identical). Nothing may differ between the branches before the decision
    but what `prepare` sets.

    Returns each branch's `Executed`, in order; each branch's record is filled as by `execute`. Its
    wall time is its own part plus an equal share of the shared part, which begins at `wall_start`
    (a `time.perf_counter()`; default: now).
    """
    if not branches:
        return []
    if replay_html and len(branches) > 1:
        raise ValueError("a replay shows one trial: run branches without one")
    meshcat = AddReplay(builder, station.diagram) if replay_html else None
    first = branches[0]
    sim = StartSimulation(builder.Build(), station, q_start, initialize)
    if first.prepare is not None:
        first.prepare(sim.context)
    wall_start = time.perf_counter() if wall_start is None else wall_start
    watch = _Watch(station, executor, sim.context, protocol, time_limit, monitor_period)
    with recording(meshcat, replay_html, look_at=station.X_WO_nominal().translation()):
        try:
            sim.simulator.Initialize()
            watch.run(sim.simulator, keep_snapshot=len(branches) > 1)
        except Exception as e:  # a failed simulation is a failed trial, never a crash of the run
            watch.failed(e)
    wall_end = time.perf_counter()
    shared = watch.wall_decided - wall_start if watch.wall_decided is not None else 0.0
    own = wall_end - (watch.wall_decided or wall_start)
    results = [watch.finish(first.record)]
    walls = [own]
    for branch in branches[1:]:
        branch_start = time.perf_counter()
        if watch.snapshot is None:  # the shared part failed before a decision: so does every branch
            results.append(watch.finish(branch.record))
        else:
            context = watch.snapshot.Clone()
            if branch.prepare is not None:
                branch.prepare(context)
            simulator = Simulator(sim.diagram, context)
            branch_watch = _Watch(station, executor, context, protocol, time_limit, monitor_period)
            try:
                simulator.Initialize(InitializeParams(suppress_initialization_events=True))
                branch_watch.run(simulator)
            except Exception as e:
                branch_watch.failed(e)
            results.append(branch_watch.finish(branch.record))
        walls.append(time.perf_counter() - branch_start)
    for run, wall in zip(results, walls):
        run.wall_time = wall + shared / len(branches)
    return results


class _Watch:
    """Watches one simulation of a grasp sequence every monitor period (the phase, divergence, the
    time limit, what the success test needs), and judges it at its end."""

    def __init__(self, station, executor: GraspExecutor, context: Context, protocol, time_limit: float,
                 monitor_period: float):
        plant = station.plant
        self.station, self.executor, self.context, self.protocol = station, executor, context, protocol
        self.time_limit, self.monitor_period = time_limit, monitor_period
        self.plant, self.plant_context = plant, plant.GetMyContextFromRoot(context)
        self.executor_context = executor.GetMyContextFromRoot(context)
        self.object_body = plant.get_body(plant.GetBodyIndices(station.object_instance)[0])
        self.palm = plant.GetFrameByName("bh_palm")
        self.table_bodies = set(int(b) for b in plant.GetBodyIndices(plant.GetModelInstanceByName("table")))
        self.X_WO = station.X_WO_nominal()  # the object at rest on the table: the lift is measured from it
        self.executed = Executed()
        self.X_PO_hold, self.rise_hold, self.contacts_after_close = None, None, []
        self.error: Exception | None = None
        self.wall_decided: float | None = None  # perf_counter when the phase left EXPLORE
        # With `run(keep_snapshot=True)`: the root context at the start of the monitor period in
        # which the phase left EXPLORE.
        self.snapshot: Context | None = None

    def phase(self) -> GraspPhase:
        return self.executor.phase(self.executor_context)

    def X_PO(self) -> RigidTransform:
        return (self.palm.CalcPoseInWorld(self.plant_context).inverse()
                @ self.object_body.EvalPoseInWorld(self.plant_context))

    def touching(self) -> tuple[list[str], bool]:
        """Hand links touching the object, and whether the object touches the table."""
        names, on_table = _object_contacts(self.plant, self.plant_context, self.object_body, self.table_bodies)
        return sorted(names), on_table

    def run(self, simulator: Simulator, keep_snapshot: bool = False) -> None:
        """Simulates the sequence to its end (raises what the simulation raises). With `keep_snapshot`,
        keeps a copy of the root context from the start of the monitor period in which the phase
        left EXPLORE (`snapshot`)."""
        context, last = self.context, None
        if self.phase() != GraspPhase.EXPLORE:
            self.executed.X_WO_decision = self.object_body.EvalPoseInWorld(self.plant_context)
        while self.phase() != GraspPhase.DONE:
            if context.get_time() > self.time_limit:
                raise RuntimeError(f"the grasp sequence did not finish in {self.time_limit:.0f} s")
            phase_before = self.phase()
            if keep_snapshot and phase_before == GraspPhase.EXPLORE:
                if last is None:
                    last = context.Clone()
                else:
                    _copy_time_and_state(context, last)
            simulator.AdvanceTo(context.get_time() + self.monitor_period)
            phase = self.phase()
            p_WO = self.object_body.EvalPoseInWorld(self.plant_context).translation()
            if not np.all(np.isfinite(p_WO)) or np.linalg.norm(p_WO) > 10.0:
                raise RuntimeError("the simulation diverged (object far away or not finite)")
            if phase_before == GraspPhase.EXPLORE and phase != GraspPhase.EXPLORE:
                self.executed.X_WO_decision = self.object_body.EvalPoseInWorld(self.plant_context)
                self.wall_decided = time.perf_counter()
                self.snapshot = last
            if phase_before == GraspPhase.CLOSE and phase == GraspPhase.LIFT:
                self.contacts_after_close, _ = self.touching()
                self.executed.depth_at_lift = self.object_depth(lift_start=True)
            if phase_before != GraspPhase.HOLD and phase == GraspPhase.HOLD:
                self.X_PO_hold = self.X_PO()
                self.rise_hold = float(p_WO[2] - self.X_WO.translation()[2])
                self.executed.depth_at_hold = self.object_depth()

    def object_depth(self, lift_start: bool = False) -> np.ndarray | None:
        """The object's depth image in the wrist camera now (`sensing.in_hand_depth`, m; as the lift
        starts, its pixels too near to range at the camera's nearest range: `sensing.lift_start_depth`),
        or None on a station without the camera."""
        if not self.station.diagram.HasOutputPort("camera.depth_image"):
            return None
        from drake_grasp.trial.sensing import in_hand_depth, lift_start_depth, object_depth_image

        image = object_depth_image(self.station, self.context)
        if lift_start:
            return lift_start_depth(*image, near=float(self.station.scenario.camera.z_near))
        return in_hand_depth(*image)

    def failed(self, e: Exception) -> None:
        """The simulation raised `e`: the trial fails with it."""
        self.error = e

    def finish(self, record: TrialRecord) -> Executed:
        """Fills `record` from what was watched (a failed simulation: SIMULATION_ERROR), and judges it
        with the success test; returns what the run saw besides."""
        plant, plant_context, protocol = self.plant, self.plant_context, self.protocol
        run = dataclasses.replace(self.executed)
        progress = self.executor.progress(self.executor_context)
        run.decision = progress.decision
        record.sim_time = self.context.get_time()
        if self.error is not None:
            record.failure = SIMULATION_ERROR
            message = str(self.error).strip()
            record.detail = message.splitlines()[0] if message else type(self.error).__name__
            return run
        if progress.outcome:  # the sequence ended before a grasp (object not found, arm could not reach)
            record.failure, record.detail = progress.outcome, progress.detail
            return run
        contacts_end, on_table = self.touching()
        run.X_WO_end = self.object_body.EvalPoseInWorld(plant_context)
        if self.station.diagram.HasOutputPort("camera.depth_image"):
            from drake_grasp.trial.sensing import (in_hand_depth, object_depth_image, too_near_share,
                                                   visible_object_points)

            image = object_depth_image(self.station, self.context)
            run.seen_points = visible_object_points(self.station, self.context, image=image)
            run.too_near = too_near_share(*image)
            run.depth_at_end = in_hand_depth(*image)
        p_WO_end = run.X_WO_end.translation()
        record.lift = float(p_WO_end[2] - self.X_WO.translation()[2])
        record.contacts_after_close = " ".join(self.contacts_after_close)
        record.contacts_at_end = " ".join(contacts_end)
        record.approach_stopped_on_contact = bool(progress.stopped_on_contact)
        if progress.motion is not None and progress.motion.fallback:  # the grasp's own pose was out of reach
            record.detail = f"executed {progress.motion.fallback}: {progress.motion.unreachable}"
        station = self.station
        q_hand = station.hand_controller.joint_angles(plant.get_state_output_port(station.hand).Eval(plant_context))
        record.finger_angles = [float(q_hand[0])] + [float(a) for a in q_hand[2:8]]
        station_system = station.diagram
        status = station_system.GetOutputPort("hand.finger_status").Eval(
            station_system.GetMyContextFromRoot(self.context))
        record.breakaway = [bool(b > 0.5) for b in status[:3]]
        record.breakaway_angles = [float(a) for a in status[3:]]
        if self.X_PO_hold is not None:
            X_PO = self.X_PO()
            slip = self.X_PO_hold.inverse() @ X_PO
            record.slip_distance = float(np.linalg.norm(X_PO.translation() - self.X_PO_hold.translation()))
            record.slip_angle = float(slip.rotation().ToAngleAxis().angle())
        observation = GraspObservation(touched_after_close=bool(self.contacts_after_close),
                                       rise_at_hold=self.rise_hold, lift_at_end=record.lift, on_table_at_end=on_table,
                                       slip_distance=record.slip_distance, slip_angle=record.slip_angle)
        record.failure = judge_grasp(observation, protocol.execution.lift_height, protocol.slip_distance,
                                     protocol.slip_angle_deg)
        record.success = record.failure == ""
        return run


def _copy_time_and_state(source: Context, target: Context) -> None:
    """Makes `target`, a clone of `source` taken earlier in the same simulation, equal to it again:
    time and state (continuous, discrete, abstract). Parameters are not copied: nothing changes
    them while a simulation runs, and copying them costs more than the rest of a period's
    simulation (SceneGraph keeps its geometry, hydroelastic meshes included, as a parameter)."""
    target.SetTime(source.get_time())
    if source.num_continuous_states():
        target.SetContinuousState(source.get_continuous_state_vector().CopyToVector())
    if source.num_discrete_state_groups():
        target.get_mutable_discrete_state().SetFrom(source.get_discrete_state())
    if source.num_abstract_states():
        target.get_mutable_abstract_state().SetFrom(source.get_abstract_state())


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
