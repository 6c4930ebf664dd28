"""Active perception with the wrist camera: the exploration Diagram and one exploration.

The paper's perception (Sec. 4) as one Drake Diagram around the station:

    station.camera.label_image ─┐
    station.camera.X_WC ────────┴─> SilhouetteCamera (fixed rate) ──camera_sample──> every primitive,
                                                                                     the sequencer
    DepthPrimitive ──centre──> PrincipalAxisPrimitive, Sphere/Cylinder/Box ResemblancePrimitive
    PrincipalAxisPrimitive ──axis──> DepthPrimitive (its size model's frame), the resemblance primitives
    ExplorationSequencer ──depth/axis/resemblance_command──> the primitives
    every primitive ──V_C_desired──> Adder ──> CameraTwistController ──> station.wam.desired_state

`AddVisualPrimitives` adds the camera, the five primitives, the twist sum and the camera motion
controller to a builder that holds a station (a grasp supervisor can reuse it and drive the
primitives' `command` ports itself); `AddExplorationSequencer` adds the phase machine that drives them
here. `explore` builds it all for one scenario, starts the camera above the table looking down at a
point, simulates the exploration, and returns an `ExplorationResult`: the `ObjectEstimate`, and the
object's true poses for evaluation (`run_exploration` returns the estimate only). `ground_truth` and
`compare` measure an estimate against the object's true pose and geometry.

Choices (rates, gains, arcs, phase durations, score tolerances) are part of the scenario: its
`perception:` (`perception_config.PerceptionConfig`, numbers in diagrams/station.scenarios.yaml).
"""


import dataclasses
import math
import pathlib
import time

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.framework import DiagramBuilder, EventStatus
from pydrake.systems.primitives import Adder, ConstantVectorSource

from drake_grasp.control.arm_motion import ArmKinematics
from drake_grasp.control.camera_motion import CameraTwistController
from drake_grasp.hand import HAND_JOINTS, HandAction
from drake_grasp.objects import ObjectSpec
from drake_grasp.primitives.camera import SilhouetteCamera
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.depth import DepthPrimitive
from drake_grasp.primitives.estimate import OBJECT_NOT_FOUND, ObjectEstimate, ObjectEstimator
from drake_grasp.primitives.estimators import is_upright
from drake_grasp.primitives.principal_axis import PrincipalAxisPrimitive
from drake_grasp.primitives.resemblance import ShapeResemblancePrimitive
from drake_grasp.primitives.scores import SHAPES
from drake_grasp.primitives.sequencer import ExplorationSequencer, ExplorationPhase
from drake_grasp.simulation import AddReplay, StartSimulation, recording
from drake_grasp.perception_config import PerceptionConfig
from drake_grasp.station import DEFAULT_SCENARIO_FILE, MakeStation, Scenario, Station, load_scenario, object_rest_pose


def load_perception_config(filename: str | pathlib.Path = DEFAULT_SCENARIO_FILE,
                           name: str = "default") -> PerceptionConfig:
    """The perception configuration of the scenario `name` in a scenario file (its `perception:`).

    Raises:
        ValueError: (one line) if the file cannot be read or does not match the schema.
    """
    return load_scenario(filename, name).perception


# --- The Diagram -------------------------------------------------------------------------------------


@dataclasses.dataclass
class VisualPrimitives:
    """The systems `AddVisualPrimitives` added (to read their ports or drive their commands)."""

    camera: SilhouetteCamera
    depth: DepthPrimitive
    axis: PrincipalAxisPrimitive
    resemblance: dict[str, ShapeResemblancePrimitive]
    twist_sum: Adder
    camera_motion: CameraTwistController
    estimator: ObjectEstimator

    def primitives(self) -> list:
        return [self.depth, self.axis] + [self.resemblance[s] for s in SHAPES]


def object_labels(station: Station) -> list[int]:
    """The render labels of the object's bodies (the station labels each body by its index)."""
    return [int(i) for i in station.plant.GetBodyIndices(station.object_instance)]


def camera_mount(station: Station) -> tuple:
    """(frame F, X_FC): the plant frame the wrist camera is fixed to, and the camera's pose in it."""
    frame = station.plant.GetFrameByName("wrist_camera")
    return frame, station.scenario.camera.X_PB.GetDeterministicValue()


def trial_noise_seed(station: Station) -> int:
    """The key of the camera noise's random stream for the trial this station was built for.

    A trial's seed fixes its variation (object offset, yaw, friction scale: `trial.apply_variation`),
    and the station holds the varied placement and object; their exact values (as text) are hashed
    here to a 64-bit key, so the same trial seed gives the same noise, and different seeds give
    different noise. (With every variation set to 0 all trials share one key; a caller that knows the
    trial's seed may pass it to `AddVisualPrimitives` instead.)
    """
    import hashlib

    placement = station.scenario.object
    friction = station.object_spec.friction
    text = repr((float(placement.x), float(placement.y), float(placement.yaw_deg),
                 None if friction is None else float(friction)))
    return int.from_bytes(hashlib.sha256(text.encode()).digest()[:8], "little")


def AddVisualPrimitives(builder: DiagramBuilder, station: Station, config: PerceptionConfig,
                        *, connect_arm: bool = True, noise_seed: int | None = None) -> VisualPrimitives:
    """Adds the fixed-rate camera, the primitives, the twist sum, the camera motion controller and
    the estimator that gathers the primitives' outputs.

    Connects the station's camera outputs to the camera, and (with `connect_arm`) the controller to
    the station's `wam.desired_state`. The primitives' `command` inputs and the estimator's `phase`
    are left for the caller to drive.

    Args:
        builder: the builder that holds the station's Diagram (`station.diagram`).
        station: the station (MakeStation with camera=True).
        config: the choices.
        connect_arm: False when the caller routes the camera motion to the arm itself (a supervisor
            that moves the arm after the exploration).
        noise_seed: the key of the camera noise (`segmentation.color_noise`); None: the trial's own
            key, from its varied placement (`trial_noise_seed`).
    """
    station_system = station.diagram
    intrinsics = CameraIntrinsics.from_camera_config(station.scenario.camera)
    period = config.period
    camera = builder.AddNamedSystem(
        "silhouette_camera", SilhouetteCamera(intrinsics, object_labels(station), period, config.segmentation,
                                              trial_noise_seed(station) if noise_seed is None else noise_seed))
    image_port = "camera.label_image" if config.segmentation.method == "label" else "camera.color_image"
    builder.Connect(station_system.GetOutputPort(image_port), camera.image_input_port())
    builder.Connect(station_system.GetOutputPort("camera.X_WC"), camera.GetInputPort("X_WC"))

    depth = builder.AddNamedSystem("depth_primitive", DepthPrimitive(intrinsics, period, config.depth))
    axis = builder.AddNamedSystem("principal_axis_primitive", PrincipalAxisPrimitive(intrinsics, period, config.axis))
    resemblance = {
        shape: builder.AddNamedSystem(f"{shape}_resemblance_primitive", ShapeResemblancePrimitive(
            shape, intrinsics, period, getattr(config, shape), config.scores))
        for shape in SHAPES
    }
    primitives = [depth, axis] + [resemblance[s] for s in SHAPES]
    for primitive in primitives:
        builder.Connect(camera.GetOutputPort("camera_sample"), primitive.GetInputPort("camera_sample"))
    builder.Connect(depth.GetOutputPort("centre"), axis.GetInputPort("centre"))
    builder.Connect(axis.GetOutputPort("axis"), depth.GetInputPort("axis"))
    for shape in SHAPES:
        builder.Connect(depth.GetOutputPort("centre"), resemblance[shape].GetInputPort("centre"))
        builder.Connect(axis.GetOutputPort("axis"), resemblance[shape].GetInputPort("axis"))

    twist_sum = builder.AddNamedSystem("camera_twist_sum", Adder(len(primitives), 6))
    for i, primitive in enumerate(primitives):
        builder.Connect(primitive.GetOutputPort("V_C_desired"), twist_sum.get_input_port(i))
    frame, X_FC = camera_mount(station)
    camera_motion = builder.AddNamedSystem("camera_motion", CameraTwistController(
        station.plant, station.wam, frame, X_FC, config.camera_motion))
    builder.Connect(twist_sum.get_output_port(), camera_motion.GetInputPort("V_C_desired"))
    if connect_arm:
        builder.Connect(camera_motion.GetOutputPort("wam.desired_state"),
                        station_system.GetInputPort("wam.desired_state"))

    estimator = builder.AddNamedSystem("object_estimator", ObjectEstimator())
    for source, port, target in ((camera, "camera_sample", "camera_sample"), (depth, "centre", "centre"),
                                 (depth, "extents", "extents"), (depth, "extents_frame", "extents_frame"),
                                 (axis, "axis", "axis"),
                                 (axis, "axis_info", "axis_info"), (resemblance["box"], "evidence", "evidence")):
        builder.Connect(source.GetOutputPort(port), estimator.GetInputPort(target))
    for shape in SHAPES:
        builder.Connect(resemblance[shape].GetOutputPort("resemblance"),
                        estimator.GetInputPort(f"{shape}_resemblance"))
    return VisualPrimitives(camera, depth, axis, resemblance, twist_sum, camera_motion, estimator)


def AddExplorationSequencer(builder: DiagramBuilder, primitives: VisualPrimitives, config: PerceptionConfig
                            ) -> ExplorationSequencer:
    """Adds the phase machine and connects its commands to the primitives, its phase to the estimator,
    and stops the camera when the exploration is over."""
    sequencer = builder.AddNamedSystem("exploration_sequencer", ExplorationSequencer(config.period, config.sequencer))
    builder.Connect(primitives.camera.GetOutputPort("camera_sample"), sequencer.GetInputPort("camera_sample"))
    builder.Connect(sequencer.GetOutputPort("phase"), primitives.estimator.GetInputPort("phase"))
    builder.Connect(sequencer.GetOutputPort("camera_active"), primitives.camera.GetInputPort("active"))
    builder.Connect(sequencer.GetOutputPort("depth_command"), primitives.depth.GetInputPort("command"))
    builder.Connect(sequencer.GetOutputPort("axis_command"), primitives.axis.GetInputPort("command"))
    for shape in SHAPES:
        builder.Connect(sequencer.GetOutputPort("resemblance_command"),
                        primitives.resemblance[shape].GetInputPort("command"))
    return sequencer


@dataclasses.dataclass
class Exploration:
    """A built exploration: the Diagram and handles to what is inside it."""

    diagram: object
    station: Station
    station_system: object
    primitives: VisualPrimitives
    sequencer: ExplorationSequencer
    config: PerceptionConfig
    meshcat: Meshcat | None = None


def MakeExploration(scenario: Scenario, config: PerceptionConfig, object_spec: ObjectSpec | None = None, *,
                    replay: bool = False) -> Exploration:
    """The station (with its camera), the primitives and the sequencer; the hand held open. With
    `replay`, a Meshcat visualizer too (the Exploration's `meshcat`)."""
    station = MakeStation(scenario, object_spec, camera=True)
    builder = DiagramBuilder()
    station_system = builder.AddNamedSystem("station", station.diagram)
    primitives = AddVisualPrimitives(builder, station, config)
    sequencer = AddExplorationSequencer(builder, primitives, config)
    hand = builder.AddNamedSystem("hand_open", ConstantVectorSource([0.0, float(HandAction.OPEN)]))
    builder.Connect(hand.get_output_port(), station_system.GetInputPort("hand.command"))
    meshcat = AddReplay(builder, station_system) if replay else None
    diagram = builder.Build()
    diagram.set_name("exploration")
    return Exploration(diagram, station, station_system, primitives, sequencer, config, meshcat)


def start_camera_pose(look_at_W: np.ndarray, config: PerceptionConfig, table_height: float = 0.0) -> RigidTransform:
    """The camera `config.start_height` above the table over the point `look_at_W` (x, y used),
    looking straight down, its x axis along the world's x (image u along x, v along −y)."""
    p = np.array([look_at_W[0], look_at_W[1], table_height + config.start_height])
    return RigidTransform(RotationMatrix(np.diag([1.0, -1.0, -1.0])), p)


def start_configuration(station: Station, X_WC: RigidTransform, config: PerceptionConfig) -> np.ndarray:
    """Arm joint angles that put the camera at X_WC (inverse kinematics of the palm)."""
    plant = station.plant
    context = plant.CreateDefaultContext()
    frame, X_FC = camera_mount(station)
    palm = plant.GetFrameByName(HAND_JOINTS.palm_frame)
    X_CP = (frame.CalcPoseInWorld(context) @ X_FC).inverse() @ palm.CalcPoseInWorld(context)
    return ArmKinematics(plant, station.wam).solve(X_WC @ X_CP, np.asarray(config.start_configuration))


# --- The result --------------------------------------------------------------------------------------


@dataclasses.dataclass
class ExplorationResult:
    """One exploration: the estimate, and (for evaluation only) where the object really was.

    Attributes:
        estimate: what the primitives found.
        X_WO_start, X_WO_end: the object's true pose at the start and at the end (a round object
            can roll a little on the table while it is looked at).
    """

    estimate: ObjectEstimate
    X_WO_start: RigidTransform
    X_WO_end: RigidTransform


def run_exploration(scenario: Scenario, config: PerceptionConfig | None = None, object_spec: ObjectSpec | None = None,
                    *, look_at: np.ndarray | None = None, replay_html: str | None = None) -> ObjectEstimate:
    """Builds the exploration for `scenario`, runs it once, returns the estimate (see `explore`)."""
    return explore(scenario, config, object_spec, look_at=look_at, replay_html=replay_html).estimate


def explore(scenario: Scenario, config: PerceptionConfig | None = None, object_spec: ObjectSpec | None = None,
            *, look_at: np.ndarray | None = None, replay_html: str | None = None,
            on_finish=None) -> ExplorationResult:
    """Builds the exploration for `scenario` and runs it once.

    Deterministic: the same inputs give the same estimate (nothing here is random; per-trial
    variation of the object's placement is the caller's, in `scenario.object`).

    Args:
        scenario: the station scenario; `scenario.object` places the object.
        config: the choices (default: the scenario's `perception`).
        object_spec: the object, when already resolved.
        look_at: the point the camera starts above (default: the placement's x, y — where the object
            is expected; a trial passes the nominal placement, not the varied one).
        replay_html: if given, write a Meshcat replay of the exploration there.
        on_finish: if given, called as on_finish(exploration, root context) when the simulation has
            ended, to read more than the estimate (a study reads the resemblance primitives'
            statistics: `resemblance_statistics`).
    """
    config = config or scenario.perception
    wall_start = time.perf_counter()
    exploration = MakeExploration(scenario, config, object_spec, replay=bool(replay_html))
    station = exploration.station
    if look_at is None:
        look_at = np.array([scenario.object.x, scenario.object.y, 0.0])
    table_height = config.depth.table_height
    q0 = start_configuration(station, start_camera_pose(look_at, config, table_height), config)

    motion = exploration.primitives.camera_motion
    sim = StartSimulation(exploration.diagram, station, q0,
                          lambda root: motion.SetInitialPositions(motion.GetMyMutableContextFromRoot(root), q0))
    simulator, context, plant_context = sim.simulator, sim.context, sim.plant_context
    plant = station.plant
    sequencer = exploration.sequencer
    sequencer_context = sequencer.GetMyContextFromRoot(context)
    simulator.set_monitor(lambda root: EventStatus.ReachedTermination(sequencer, "exploration over")
                          if sequencer.state(sequencer_context).phase.finished else EventStatus.Succeeded())
    object_body = plant.get_body(plant.GetBodyIndices(station.object_instance)[0])
    X_WO_start = object_body.EvalPoseInWorld(plant_context)
    build_time = time.perf_counter() - wall_start

    sim_start = time.perf_counter()
    with recording(exploration.meshcat, replay_html):
        simulator.AdvanceTo(config.sequencer.total_time + 1.0)
    sim_wall = time.perf_counter() - sim_start

    if on_finish is not None:
        on_finish(exploration, context)
    state = sequencer.state(sequencer_context)
    timings = {
        "build_time": build_time,
        "sim_time": context.get_time(),
        "sim_wall_time": sim_wall,
        "wall_time": time.perf_counter() - wall_start,
        "frames": exploration.primitives.camera.frames,
        "phase_starts": {ExplorationPhase(p).name.lower(): t for p, t in state.phase_starts},
    }
    return ExplorationResult(read_estimate(exploration, context, timings), X_WO_start,
                             object_body.EvalPoseInWorld(plant_context))


def resemblance_statistics(exploration: Exploration, context, shape: str = "box"):
    """The silhouette statistics (`scores.FeatureStatistics`) a resemblance primitive gathered, in
    `context` (the exploration's root context): its resemblance is `scores.evaluate` of them. The
    three primitives see the same views from the same latched frame, so any one of them will do."""
    from drake_grasp.primitives.scores import FeatureStatistics

    primitive = exploration.primitives.resemblance[shape]
    return FeatureStatistics.from_vector(primitive.statistics_vector(primitive.GetMyContextFromRoot(context)))


def read_estimate(exploration: Exploration, context, timings: dict | None = None) -> ObjectEstimate:
    """The ObjectEstimate that the primitives' outputs hold in `context` (the exploration's root context)."""
    estimator = exploration.primitives.estimator
    estimate = estimator.GetOutputPort("estimate").Eval(estimator.GetMyContextFromRoot(context))
    return dataclasses.replace(estimate, timings=dict(timings or {}))


# --- Ground truth ------------------------------------------------------------------------------------


def _shape_support(kind: str, size: tuple, mesh_vertices: np.ndarray | None, u: np.ndarray) -> float:
    """Support function h(u) = max over the shape of u·x, for a Drake shape in its own frame."""
    if kind == "sphere":
        return size[0]
    if kind == "ellipsoid":
        return float(np.linalg.norm(np.asarray(size) * u))
    if kind == "box":
        return float(0.5 * np.abs(u) @ np.asarray(size))
    if kind in ("cylinder", "capsule"):
        radius, length = size
        lateral = math.hypot(u[0], u[1])
        return 0.5 * length * abs(u[2]) + radius * (lateral if kind == "cylinder" else 1.0)
    return float(np.max(mesh_vertices @ u))


def object_support(spec: ObjectSpec, X_WO: RigidTransform, u_W: np.ndarray) -> float:
    """max over the object of u·p (world), for a world direction u: the object's support function."""
    import trimesh

    best = -math.inf
    for piece in spec.pieces:
        X_WP = X_WO @ piece.X_OP
        R = X_WP.rotation().matrix()
        vertices = None
        if piece.kind == "convex":
            vertices = np.asarray(trimesh.load(piece.mesh_path, force="mesh", process=False).vertices, float)
        h = float(np.dot(u_W, X_WP.translation())) + _shape_support(piece.kind, piece.size, vertices, R.T @ u_W)
        best = max(best, h)
    return best


def object_extent(spec: ObjectSpec, X_WO: RigidTransform, u_W: np.ndarray) -> float:
    """The object's extent along the unit world direction u, m."""
    u = np.asarray(u_W, float) / np.linalg.norm(u_W)
    return object_support(spec, X_WO, u) + object_support(spec, X_WO, -u)


@dataclasses.dataclass
class GroundTruth:
    """The object as it really is (world frame): centre of mass, principal axis (or None), extents
    (length, width, height: along the principal axis or, for an object with none or an upright one,
    the longer side of the smallest horizontal bounding rectangle; across it; and vertically), and the
    closest primitive shape."""

    centre: np.ndarray
    principal_axis: np.ndarray | None
    extents: np.ndarray
    shape: str | None


def ground_truth(spec: ObjectSpec, X_WO: RigidTransform) -> GroundTruth:
    up = np.array([0.0, 0.0, 1.0])
    height = object_extent(spec, X_WO, up)
    axis = None
    if spec.principal_axis is not None:
        axis = X_WO.rotation().matrix() @ np.asarray(spec.principal_axis)
    lying = axis is not None and not is_upright(axis)  # an upright axis names no horizontal direction
    if lying:
        horizontal = axis - axis[2] * up
        directions = [math.atan2(horizontal[1], horizontal[0])]
    else:
        directions = np.linspace(0.0, math.pi / 2.0, 91)
    best = None
    for theta in directions:
        u = np.array([math.cos(theta), math.sin(theta), 0.0])
        v = np.array([-math.sin(theta), math.cos(theta), 0.0])
        lu, lv = object_extent(spec, X_WO, u), object_extent(spec, X_WO, v)
        if best is None or lu * lv < best[0] * best[1] - 1e-12:
            best = (lu, lv)
    length, width = best if lying else sorted(best, reverse=True)
    return GroundTruth(X_WO.translation().copy(), axis, np.array([length, width, height]), spec.closest_primitive)


@dataclasses.dataclass
class EstimateErrors:
    """An estimate against the truth.

    Attributes:
        centre: distance between the estimated and true centre, m.
        depth: relative depth error, (estimated − true distance) / true distance, from the final camera.
        axis_deg: angle between the estimated and true principal axes (None unless both exist).
        extents: relative errors of (length, width, height), sorted horizontal extents when the object
            has no principal axis, or an upright one (estimated or true).
        shape_correct: the highest resemblance names the true closest primitive (None if unknown).
    """

    centre: float
    depth: float
    axis_deg: float | None
    extents: np.ndarray
    shape_correct: bool | None

    def passes(self, centre_tol=0.01, depth_tol=0.05, axis_tol_deg=10.0, size_tol=0.15) -> bool:
        """The issue's acceptance thresholds (and the class, when known)."""
        ok = self.centre <= centre_tol and abs(self.depth) <= depth_tol and np.all(np.abs(self.extents) <= size_tol)
        ok = ok and (self.axis_deg is None or self.axis_deg <= axis_tol_deg)
        return bool(ok and self.shape_correct is not False)


def compare(estimate: ObjectEstimate, truth: GroundTruth) -> EstimateErrors:
    """How far `estimate` is from `truth` (the estimate must be found)."""
    if not estimate.found:
        raise ValueError("no estimate to compare: the object was not found")
    true_depth = float(np.linalg.norm(truth.centre - estimate.camera_position))
    axis_deg = None
    if truth.principal_axis is not None and estimate.principal_axis is not None:
        cosine = abs(float(np.dot(truth.principal_axis, estimate.principal_axis)))
        axis_deg = math.degrees(math.acos(min(cosine, 1.0)))
    extents = np.array(estimate.extents, float)
    if is_upright(np.asarray(estimate.axes)[:, 0]):  # along (vertical a, b, horizontal c): as the truth's
        extents = extents[[2, 1, 0]]                # (horizontal, horizontal, vertical)
    true_extents = np.array(truth.extents, float)
    if any(axis is None or is_upright(axis) for axis in (truth.principal_axis, estimate.principal_axis)):
        # No horizontal axis to tell length from width (a round object, or an upright one): sorted.
        extents[:2] = sorted(extents[:2], reverse=True)
        true_extents[:2] = sorted(true_extents[:2], reverse=True)
    shape_correct = None if truth.shape is None else estimate.best_shape == truth.shape
    return EstimateErrors(
        centre=float(np.linalg.norm(estimate.centre - truth.centre)),
        depth=(estimate.depth - true_depth) / true_depth,
        axis_deg=axis_deg,
        extents=(extents - true_extents) / true_extents,
        shape_correct=shape_correct,
    )


def true_pose(scenario: Scenario, spec: ObjectSpec) -> RigidTransform:
    """The object's resting pose for the scenario's placement (it does not move while looked at)."""
    return object_rest_pose(spec, scenario.object)


# --- Reporting (the `drake-grasp resemble` command) --------------------------------------------------


def comparison_record(result: ExplorationResult, spec: ObjectSpec) -> dict:
    """Plain data: the estimate beside the truth (at the end of the exploration) and the errors."""
    estimate = result.estimate
    record = {"object": spec.name, "estimate": estimate.to_dict(), "best_shape": estimate.best_shape}
    truth = ground_truth(spec, result.X_WO_end)
    record["truth"] = {
        "centre": truth.centre.tolist(),
        "depth": None if estimate.camera_position is None else
        float(np.linalg.norm(truth.centre - estimate.camera_position)),
        "principal_axis": None if truth.principal_axis is None else truth.principal_axis.tolist(),
        "extents": truth.extents.tolist(),
        "shape": truth.shape,
        "object_moved": float(np.linalg.norm(result.X_WO_end.translation() - result.X_WO_start.translation())),
    }
    if estimate.found:
        errors = compare(estimate, truth)
        record["errors"] = {"centre": errors.centre, "depth": errors.depth, "axis_deg": errors.axis_deg,
                            "extents": errors.extents.tolist(), "shape_correct": errors.shape_correct,
                            "within_tolerances": errors.passes()}
        if estimate.problem():  # seen, but a trial would end here: perception failed
            record["problem"] = estimate.problem()
    return record


def format_comparison(record: dict) -> list[str]:
    """Human-readable lines of a `comparison_record`: estimate | truth | error, then the resemblances."""
    estimate, truth = record["estimate"], record["truth"]
    timings = estimate["timings"]
    if estimate["status"] != "ok":
        why = ("the camera did not see it from the start pose" if estimate["status"] == OBJECT_NOT_FOUND else
               "the camera saw it, but every silhouette was cut by the image border")
        return [f"{record['object']}: {estimate['status']} ({why}); "
                f"{timings.get('sim_time', 0.0):.1f} s simulated in {timings.get('wall_time', 0.0):.1f} s"]

    def vector(v, digits=3):
        return "-" if v is None else "(" + ", ".join(f"{x:.{digits}f}" for x in v) + ")"

    errors = record["errors"]
    axis_error = "-" if errors["axis_deg"] is None else f"{errors['axis_deg']:.1f} deg"
    rows = [
        ("centre (m)", vector(estimate["centre"]), vector(truth["centre"]), f"{errors['centre'] * 1000:.1f} mm"),
        ("depth (m)", f"{estimate['depth']:.3f}", f"{truth['depth']:.3f}", f"{errors['depth'] * 100:+.1f} %"),
        ("principal axis", vector(estimate["principal_axis"], 2), vector(truth["principal_axis"], 2), axis_error),
        ("size (m)", " x ".join(f"{x:.3f}" for x in _as_truth_extents(estimate)),
         " x ".join(f"{x:.3f}" for x in truth["extents"]),
         " ".join(f"{e * 100:+.1f}" for e in errors["extents"]) + " %"),
    ]
    lines = [f"{'':16s} {'estimate':26s} {'truth':26s} error"]
    lines += [f"{name:16s} {a:26s} {b:26s} {c}" for name, a, b, c in rows]
    res = estimate["resemblances"]
    verdict = "" if truth["shape"] is None else \
        f" (truth: {truth['shape']}, {'right' if errors['shape_correct'] else 'WRONG'})"
    lines.append("resemblance      " + "  ".join(f"{s} {res[s]:.2f}" for s in SHAPES) +
                 f"  -> {record['best_shape']}{verdict}")
    lines.append(f"{record['object']}: {record['best_shape']} (resemblance {res[record['best_shape']]:.2f}); "
                 f"centre {errors['centre'] * 1000:.1f} mm, depth {errors['depth'] * 100:+.1f} %, axis {axis_error}; "
                 f"{timings['sim_time']:.1f} s simulated, {timings['frames']} frames, {timings['wall_time']:.1f} s wall")
    if record.get("problem"):
        lines.append(f"perception failed: {record['problem']} (a trial would end here)")
    return lines


def _as_truth_extents(estimate: dict) -> list:
    """An estimate's extents (plain data) in the truth's order: length, width (horizontal), height."""
    extents = list(estimate["extents"])
    return extents[::-1] if is_upright(np.asarray(estimate["axes"])[:, 0]) else extents
