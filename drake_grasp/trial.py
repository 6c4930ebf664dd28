"""One grasp trial: set up, execute a grasp plan, judge it with the paper's success test, record.

Every method (the compliant grasps, from camera estimates or ground truth, and grasps planned by the
Eigengrasp baseline) runs through `run_trial`, so all are executed by the same arm, hand controller
and timings, and judged by the same test (DESIGN.md §8):

* the object is placed with the trial's seeded variation (position, yaw, friction);
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
from pydrake.geometry import Meshcat, MeshcatVisualizer, MeshcatVisualizerParams, Role
from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from drake_grasp.control.arm_motion import ReachError
from drake_grasp.control.grasp_executor import GraspExecutor, Phase
from drake_grasp.grasps import GraspPlan
from drake_grasp.objects import ObjectSpec
from drake_grasp.protocol import TrialVariation
from drake_grasp.station import MakeStation, Scenario

# Failure reasons (the record's `failure` field).
MISSED = "missed"
DROPPED_DURING_LIFT = "dropped during lift"
SLIPPED_DURING_HOLD = "slipped during hold"
UNREACHABLE = "arm could not reach"
SIMULATION_ERROR = "simulation error"

PlanFunction = Callable[[RigidTransform, ObjectSpec], GraspPlan]


@dataclasses.dataclass
class TrialRecord:
    """Everything a trial measured. Distances in m, angles in rad, times in s."""

    object: str
    method: str
    grasp: str
    seed: int
    success: bool
    failure: str  # "" on success
    lift: float = float("nan")  # object's rise above its resting height at the end
    slip_distance: float = float("nan")  # in the palm frame, over the hold
    slip_angle: float = float("nan")
    contacts_after_close: str = ""  # hand links touching the object when the lift starts
    contacts_at_end: str = ""
    finger_angles: list = dataclasses.field(default_factory=list)  # [spread, prox 1..3, distal 1..3]
    breakaway: list = dataclasses.field(default_factory=list)
    breakaway_angles: list = dataclasses.field(default_factory=list)  # proximal angle at breakaway (nan: none)
    approach_stopped_on_contact: bool = False
    estimate_source: str = ""
    variation: dict = dataclasses.field(default_factory=dict)
    sim_time: float = 0.0
    wall_time: float = 0.0
    detail: str = ""
    # Camera-driven (compliant) trials: what the visual primitives measured and chose.
    resemblances: dict = dataclasses.field(default_factory=dict)
    chosen_grasp: str = ""
    estimate: dict = dataclasses.field(default_factory=dict)
    estimate_errors: dict = dataclasses.field(default_factory=dict)

    def summary(self) -> str:
        verdict = "SUCCESS" if self.success else f"FAILED ({self.failure})"
        slip = (f"slip {self.slip_distance * 1000:.1f} mm / {math.degrees(self.slip_angle):.1f} deg"
                if math.isfinite(self.slip_distance) else "no hold")
        lift = f"lift {self.lift * 100:.1f} cm" if math.isfinite(self.lift) else "no lift"
        return (f"{self.object} {self.method}/{self.grasp} seed {self.seed}: {verdict}; {lift}; {slip}; "
                f"touching [{self.contacts_at_end or self.contacts_after_close}]; "
                f"{self.sim_time:.1f} s simulated in {self.wall_time:.1f} s")


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


def run_trial(scenario: Scenario, spec: ObjectSpec, plan_function: PlanFunction, *, seed: int, method: str,
              grasp: str, replay_html: str | None = None, monitor_period: float = 0.05) -> TrialRecord:
    """Runs one trial and returns its record (never raises for a failed grasp or simulation).

    Args:
        scenario: the station scenario (its protocol gives the variation, thresholds and timings).
        spec: the object (placed as scenario.object says, then varied by the seed).
        plan_function: (X_WO of the varied object, its spec) -> GraspPlan. A compliant-grasp method
            must compute the plan from its estimate only; X_WO is there for oracle and planner methods.
        seed: the trial's seed: it fixes the variation, the same for every method.
        method, grasp: names for the record.
        replay_html: write a Meshcat replay there.
        monitor_period: how often the runner checks the executor's phase, s.
    """
    wall_start = time.perf_counter()
    protocol = scenario.protocol
    variation = TrialVariation.draw(seed, protocol)
    scenario, spec = apply_variation(scenario, spec, variation)
    record = TrialRecord(object=spec.name, method=method, grasp=grasp, seed=seed, success=False, failure="",
                         variation=dataclasses.asdict(variation))
    station = MakeStation(scenario, spec, camera=False)
    plant = station.plant
    X_WO = station.X_WO_nominal()
    try:
        plan = plan_function(X_WO, spec)
        hand_bodies = plant.GetBodyIndices(station.hand)
        executor = GraspExecutor(plant, station.scene_graph, station.wam, hand_bodies, plan,
                                 np.asarray(protocol.start_configuration, float), protocol.execution)
    except ReachError as e:
        record.failure, record.detail = UNREACHABLE, str(e)
        record.wall_time = time.perf_counter() - wall_start
        return record

    builder = DiagramBuilder()
    builder.AddNamedSystem("station", station.diagram)
    builder.AddNamedSystem("executor", executor)
    diagram_station = station.diagram
    builder.Connect(diagram_station.GetOutputPort("wam.state"), executor.GetInputPort("wam_state"))
    builder.Connect(diagram_station.GetOutputPort("contact_results"), executor.GetInputPort("contact_results"))
    builder.Connect(executor.GetOutputPort("wam_desired_state"), diagram_station.GetInputPort("wam.desired_state"))
    builder.Connect(executor.GetOutputPort("hand_command"), diagram_station.GetInputPort("hand.command"))
    builder.Connect(executor.GetOutputPort("finger_preshape"), diagram_station.GetInputPort("hand.finger_preshape"))
    meshcat = None
    if replay_html:
        meshcat = Meshcat()
        MeshcatVisualizer.AddToBuilder(builder, diagram_station.GetOutputPort("query_object"), meshcat,
                                       MeshcatVisualizerParams(role=Role.kIllustration))
    diagram = builder.Build()

    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    plant.SetPositions(plant_context, station.wam, np.asarray(protocol.start_configuration, float))
    station.hand_controller.SetInitialFingers(station.hand_controller.GetMyMutableContextFromRoot(context))
    executor_context = executor.GetMyContextFromRoot(context)
    object_body = plant.get_body(plant.GetBodyIndices(station.object_instance)[0])
    palm = plant.GetFrameByName("bh_palm")
    table_bodies = set(int(b) for b in plant.GetBodyIndices(plant.GetModelInstanceByName("table")))

    def X_PO() -> RigidTransform:
        return palm.CalcPoseInWorld(plant_context).inverse() @ object_body.EvalPoseInWorld(plant_context)

    def touching() -> tuple[list[str], bool]:
        """Hand links touching the object, and whether the object touches the table."""
        names, on_table = _object_contacts(plant, plant_context, object_body, table_bodies)
        return sorted(names), on_table

    execution = protocol.execution
    if meshcat is not None:
        p = X_WO.translation()
        meshcat.SetCameraPose(p + [0.45, -0.75, 0.45], p)
        meshcat.StartRecording()
    X_PO_hold, contacts_after_close = None, []
    time_limit = 60.0 + execution.hold_time
    try:
        simulator.Initialize()
        while executor.phase(executor_context) != Phase.DONE:
            if context.get_time() > time_limit:
                raise RuntimeError(f"the grasp sequence did not finish in {time_limit:.0f} s")
            phase_before = executor.phase(executor_context)
            simulator.AdvanceTo(context.get_time() + monitor_period)
            phase = executor.phase(executor_context)
            p_WO = object_body.EvalPoseInWorld(plant_context).translation()
            if not np.all(np.isfinite(p_WO)) or np.linalg.norm(p_WO) > 10.0:
                raise RuntimeError("the simulation diverged (object far away or not finite)")
            if phase_before == Phase.CLOSE and phase == Phase.LIFT:
                contacts_after_close, _ = touching()
            if phase_before != Phase.HOLD and phase == Phase.HOLD:
                X_PO_hold = X_PO()
                rise_hold = p_WO[2] - X_WO.translation()[2]
    except Exception as e:  # a failed simulation is a failed trial, never a crash of the run
        record.failure = SIMULATION_ERROR
        record.detail = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        record.sim_time = context.get_time()
        record.wall_time = time.perf_counter() - wall_start
        return record
    finally:
        if meshcat is not None:
            meshcat.StopRecording()
            meshcat.PublishRecording()
            with open(replay_html, "w") as f:
                f.write(meshcat.StaticHtml())

    progress = executor.progress(executor_context)
    contacts_end, on_table = touching()
    p_WO_end = object_body.EvalPoseInWorld(plant_context).translation()
    record.lift = float(p_WO_end[2] - X_WO.translation()[2])
    record.contacts_after_close = " ".join(contacts_after_close)
    record.contacts_at_end = " ".join(contacts_end)
    record.approach_stopped_on_contact = bool(progress.stopped_on_contact)
    record.estimate_source = getattr(plan, "source", "") or ""
    q_hand = station.hand_controller._index.joint_positions(plant.get_state_output_port(station.hand).Eval(plant_context))
    record.finger_angles = [float(q_hand[0])] + [float(a) for a in q_hand[2:8]]
    status = diagram_station.GetOutputPort("hand.finger_status").Eval(diagram_station.GetMyContextFromRoot(context))
    record.breakaway = [bool(b > 0.5) for b in status[:3]]
    record.breakaway_angles = [float(a) for a in status[3:]]
    if X_PO_hold is not None:
        slip = X_PO_hold.inverse() @ X_PO()
        record.slip_distance = float(np.linalg.norm(X_PO().translation() - X_PO_hold.translation()))
        record.slip_angle = float(slip.rotation().ToAngleAxis().angle())
    lift_needed = 0.5 * execution.lift_height
    if not contacts_after_close and (X_PO_hold is None or rise_hold < lift_needed):
        record.failure = MISSED
    elif X_PO_hold is None or rise_hold < lift_needed:
        record.failure = DROPPED_DURING_LIFT
    elif (on_table or record.lift < lift_needed or record.slip_distance >= protocol.slip_distance
          or record.slip_angle >= math.radians(protocol.slip_angle_deg)):
        record.failure = SLIPPED_DURING_HOLD
    record.success = record.failure == ""
    record.sim_time = context.get_time()
    record.wall_time = time.perf_counter() - wall_start
    return record


OBJECT_NOT_FOUND = "object not found"
GRASP_OF_SHAPE = {"sphere": "spherical", "cylinder": "cylindrical", "box": "box"}


def run_compliant_trial(scenario: Scenario, spec: ObjectSpec, *, seed: int, grasp: str | None = None,
                        replay_html: str | None = None, perception_config=None) -> TrialRecord:
    """The compliance-centric algorithm, one trial: explore with the wrist camera, decide, grasp.

    The exploration (`drake_grasp.perception`) looks at the object placed with the trial's seeded
    variation, from a start pose above its *nominal* placement, and estimates its centre, axes, size
    and the three shape resemblances. The decision is the grasp of the most resembling shape (or
    `grasp`, forced by the caller, for Fig. 6's all-grasps protocol). The grasp is computed from the
    estimate only and executed by `run_trial` (same seed, so the same object placement). No ground
    truth enters the decision or the grasp; the record keeps the estimate's errors for evaluation.

    The exploration and the grasp run as two simulations in sequence (the arm starts the grasp from
    the protocol's start configuration; the object, which the camera does not touch, is placed again).
    """
    from drake_grasp.grasps import plan_compliant_grasp
    from drake_grasp.perception import compare, explore, ground_truth

    wall_start = time.perf_counter()
    variation = TrialVariation.draw(seed, scenario.protocol)
    explored_scenario, explored_spec = apply_variation(scenario, spec, variation)
    nominal = np.array([scenario.object.x, scenario.object.y, 0.0])
    exploration = explore(explored_scenario, perception_config, explored_spec, look_at=nominal)
    estimate = exploration.estimate
    if not estimate.found:
        record = TrialRecord(object=spec.name, method="compliant", grasp=grasp or "", seed=seed, success=False,
                             failure=OBJECT_NOT_FOUND, variation=dataclasses.asdict(variation),
                             wall_time=time.perf_counter() - wall_start, estimate=estimate.to_dict())
        return record
    chosen = GRASP_OF_SHAPE[estimate.best_shape]
    executed = grasp or chosen
    grasp_estimate = estimate.as_grasp_estimate()

    def plan(X_WO, object_spec):  # the estimate only: X_WO and the spec are not looked at
        return plan_compliant_grasp(executed, grasp_estimate)

    record = run_trial(scenario, spec, plan, seed=seed, method="compliant", grasp=executed, replay_html=replay_html)
    errors = compare(estimate, ground_truth(explored_spec, exploration.X_WO_start))
    record.resemblances = dict(estimate.resemblances)
    record.chosen_grasp = chosen
    record.estimate_source = "camera"
    record.estimate = {k: v for k, v in estimate.to_dict().items() if k not in ("evidence",)}
    record.estimate_errors = {"centre": errors.centre, "depth": errors.depth, "axis_deg": errors.axis_deg,
                              "extents": [float(e) for e in errors.extents], "shape_correct": errors.shape_correct}
    record.sim_time += float(estimate.timings.get("sim_time", 0.0))
    record.wall_time = time.perf_counter() - wall_start
    return record


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
