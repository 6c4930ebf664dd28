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
here. `MakeExploration` builds both around one scenario's station; `start_camera_pose` and
`start_configuration` place the camera above the table looking down at a point. Running an
exploration is `drake_grasp.perception.exploration`; measuring an estimate against the truth, for
evaluation only, is `drake_grasp.perception.evaluation`.

Choices (rates, gains, arcs, phase durations, score tolerances) are part of the scenario: its
`perception:` (`perception.config.PerceptionConfig`, numbers in diagrams/station.scenarios.yaml).
"""

import dataclasses
import pathlib

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import Adder, ConstantVectorSource

from drake_grasp.control.arm_motion import ArmKinematics
from drake_grasp.control.camera_motion import CameraTwistController
from drake_grasp.robot.hand import HAND_JOINTS, HandAction
from drake_grasp.objects import ObjectSpec
from drake_grasp.primitives.camera import SilhouetteCamera
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.depth import DepthPrimitive
from drake_grasp.primitives.depth_views import DepthViews, TableTopFrame
from drake_grasp.primitives.exploration_cost import ExplorationCost
from drake_grasp.primitives.estimate import ObjectEstimator
from drake_grasp.primitives.principal_axis import PrincipalAxisPrimitive
from drake_grasp.primitives.resemblance import ShapeResemblancePrimitive
from drake_grasp.primitives.scores import SHAPES
from drake_grasp.primitives.sequencer import ExplorationSequencer
from drake_grasp.simulation import AddReplay
from drake_grasp.perception.config import PerceptionConfig
from drake_grasp.station import DEFAULT_SCENARIO_FILE, MakeStation, Scenario, Station, load_scenario


def load_perception_config(filename: str | pathlib.Path = DEFAULT_SCENARIO_FILE,
                           name: str = "default") -> PerceptionConfig:
    """The perception configuration of the scenario `name` in a scenario file (its `perception:`).

    Raises:
        ValueError: (one line) if the file cannot be read or does not match the schema.
    """
    return load_scenario(filename, name).perception




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
    depth_views: DepthViews | None = None  # with a table-top estimate (`config.table_top`) only
    cost: ExplorationCost | None = None  # what the exploration cost (time, camera path, images)

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
    minimal = config.sequencer.minimal
    resemblance = {
        shape: builder.AddNamedSystem(f"{shape}_resemblance_primitive", ShapeResemblancePrimitive(
            shape, intrinsics, period, getattr(config, shape), config.scores,
            None if minimal is None else minimal.confirm_time))
        for shape in SHAPES
    }
    primitives = [depth, axis] + [resemblance[s] for s in SHAPES]
    for primitive in primitives:
        builder.Connect(camera.GetOutputPort("camera_sample"), primitive.GetInputPort("camera_sample"))
    builder.Connect(depth.GetOutputPort("centre"), axis.GetInputPort("centre"))
    builder.Connect(axis.GetOutputPort("axis"), depth.GetInputPort("axis"))
    # The resemblance primitives explore about the primitives' centre and axis; in the minimal
    # exploration about the table-top estimate's (`depth_views.TableTopFrame`), connected below.
    if minimal is None:
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
    cost = builder.AddNamedSystem("exploration_cost", ExplorationCost(period))
    builder.Connect(camera.GetOutputPort("camera_sample"), cost.GetInputPort("camera_sample"))
    builder.Connect(cost.GetOutputPort("cost"), estimator.GetInputPort("exploration_cost"))
    depth_views = None
    if config.table_top is not None:
        depth_views = builder.AddNamedSystem("depth_views", DepthViews(camera, config.table_top,
                                                                       config.depth.table_height))
        builder.Connect(station_system.GetOutputPort("camera.depth_image"), depth_views.GetInputPort("depth_image"))
        builder.Connect(station_system.GetOutputPort(image_port), depth_views.image_input_port())
        builder.Connect(station_system.GetOutputPort("camera.X_WC"), depth_views.GetInputPort("X_WC"))
        builder.Connect(depth_views.GetOutputPort("table_top"), estimator.GetInputPort("table_top"))
        if minimal is not None:
            frame = builder.AddNamedSystem("table_top_frame", TableTopFrame())
            builder.Connect(depth_views.GetOutputPort("table_top"), frame.GetInputPort("table_top"))
            for shape in SHAPES:
                builder.Connect(frame.GetOutputPort("centre"), resemblance[shape].GetInputPort("centre"))
                builder.Connect(frame.GetOutputPort("axis"), resemblance[shape].GetInputPort("axis"))
    return VisualPrimitives(camera, depth, axis, resemblance, twist_sum, camera_motion, estimator, depth_views, cost)


def AddExplorationSequencer(builder: DiagramBuilder, primitives: VisualPrimitives, config: PerceptionConfig
                            ) -> ExplorationSequencer:
    """Adds the phase machine and connects its commands to the primitives, its phase to the estimator,
    and stops the camera when the exploration is over."""
    sequencer = builder.AddNamedSystem("exploration_sequencer", ExplorationSequencer(config.period, config.sequencer))
    builder.Connect(primitives.camera.GetOutputPort("camera_sample"), sequencer.GetInputPort("camera_sample"))
    builder.Connect(sequencer.GetOutputPort("phase"), primitives.estimator.GetInputPort("phase"))
    builder.Connect(sequencer.GetOutputPort("camera_active"), primitives.camera.GetInputPort("active"))
    if primitives.depth_views is not None:
        builder.Connect(sequencer.GetOutputPort("camera_active"), primitives.depth_views.GetInputPort("active"))
    builder.Connect(sequencer.GetOutputPort("depth_command"), primitives.depth.GetInputPort("command"))
    builder.Connect(sequencer.GetOutputPort("axis_command"), primitives.axis.GetInputPort("command"))
    for shape in SHAPES:
        builder.Connect(sequencer.GetOutputPort(f"{shape}_command"), primitives.resemblance[shape].GetInputPort("command"))
    builder.Connect(sequencer.GetOutputPort("outcome"), primitives.estimator.GetInputPort("exploration_outcome"))
    if config.sequencer.minimal is not None:  # what the hypothesis and its confirmation read
        builder.Connect(primitives.axis.GetOutputPort("axis_info"), sequencer.GetInputPort("axis_info"))
        builder.Connect(primitives.resemblance["box"].GetOutputPort("evidence"), sequencer.GetInputPort("evidence"))
        if primitives.depth_views is not None:
            builder.Connect(primitives.depth_views.GetOutputPort("table_top"), sequencer.GetInputPort("table_top"))
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
