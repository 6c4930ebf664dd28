"""The grasping station: a scenario (YAML) in, one Drake Diagram out.

The station holds the MultibodyPlant (table, object, WAM, BarrettHand) and its SceneGraph, the WAM's
joint PD actuators with gravity compensation and the palm's impedance law that can take over from
them (control.palm_impedance), the hand controller (torque close with breakaway), and
the wrist RgbdSensor. It exports named ports, so that whoever drives it (the demo, a trial, the
visual primitives) connects to names, not to the plant's internals:

Input ports:
    wam.desired_state   [q (7), v (7)] the WAM tracks, rad and rad/s.
    wam.arm_mode        1: the palm's impedance law drives the arm; 0 or unconnected: the joint PD.
    wam.palm_target, wam.palm_force, wam.palm_stiffness, wam.palm_damping
                        the impedance law's target pose (RigidTransform), force along the palm
                        normal (N), and gains per palm axis (unconnected: the scenario's).
    hand.command        [spread target (rad), HandAction].
    hand.finger_preshape   proximal angle per finger for HandAction.PRESHAPE (rad); else unused.
Output ports:
    wam.state, hand.state          the model instances' [q; v].
    hand.finger_status             broken_away (3), breakaway angle (3, rad).
    object.state                   the object's free-body state [quaternion wxyz, p_WO; w_WO, v_WO].
    body_poses, contact_results, query_object   (the plant's and the scene graph's).
    camera.color_image, camera.depth_image, camera.label_image   the wrist camera (RgbdSensor).

A system outside the station that reads or writes one of these signals names its port exactly so
(the grasp executor's `wam.state` in, `wam.desired_state`, `hand.command`, `hand.finger_preshape`
out), so that every connection reads `Connect(a.GetOutputPort(name), b.GetInputPort(name))`.

The scenario is a dataclass loaded with Drake's `yaml_load_typed`, in the style of Drake's
hardware_sim example; every number that is a choice (time step, contact model, gains, camera) lives in
the YAML files under diagrams/.
"""



import copy
import dataclasses
import math
import pathlib
import typing

from pydrake.geometry import (
    MakeRenderEngineVtk,
    RenderEngineVtkParams,
    SceneGraph,
)
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import ModelDirective, ModelDirectives, Parser, ProcessModelDirectives
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import ModelInstanceIndex, PdControllerGains
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.primitives import Adder
from pydrake.systems.sensors import CameraConfig, RgbdSensor

from drake_grasp.robot import arm
from drake_grasp.robot.contact import ContactParameters
from drake_grasp.control.gravity_compensation import GravityCompensation
from drake_grasp.control.palm_impedance import PalmImpedanceController, PalmImpedanceParams
from drake_grasp.control.hand_controller import HandController, HandControllerParams, SetHandActuatorGains
from drake_grasp.objects.drake_model import with_mass_scale
from drake_grasp.objects import AddObject, ObjectSpec, resolve_object
from drake_grasp.paths import DIAGRAMS_DIR, RegisterPackage
from drake_grasp.perception.config import PerceptionConfig
from drake_grasp.protocol import TrialProtocol
from drake_grasp.yaml_config import load_named

RENDERER_NAME = "vtk"


@dataclasses.dataclass
class ObjectPlacement:
    """Which object, and where it rests on the table.

    Attributes:
        name: a catalogue name (e.g. "soccer_ball"), a primitive ("sphere:0.12", "cube:0.08",
            "cylinder:0.1x0.3") or a mesh file path.
        x, y: position of the object's centre on the table, world frame, m.
        yaw_deg: rotation about the vertical from the object's nominal resting pose, degrees.
        mass_scale: multiplies the object's mass and its rotational inertia about its centre of mass
            (same shape, same centre of mass: a denser or lighter body), e.g. 0.5 or 2.0 in the
            sensitivity sweep. Omitted (None) = 1, the object's own mass; None is left out of the
            scenario's YAML dump, so scenarios without it keep their fingerprints.
        pose: the object's whole pose [x, y, z (m), roll, pitch, yaw (rad)] in the world, instead of its
            resting pose at (x, y, yaw_deg): where a grasp's next attempt finds the object the last one
            left (`trial.attempts`). None (left out of the dump): the resting pose.
    """

    name: str = "soccer_ball"
    x: float = 0.55
    y: float = 0.0
    yaw_deg: float = 0.0
    mass_scale: typing.Optional[float] = None
    pose: typing.Optional[list[float]] = None


@dataclasses.dataclass
class ArmParams:
    """The WAM's joint PD actuators (implicit in the plant) and feed-forward gravity compensation."""

    kp: list[float] = dataclasses.field(default_factory=lambda: [800.0, 800.0, 400.0, 400.0, 60.0, 60.0, 30.0])
    kd: list[float] = dataclasses.field(default_factory=lambda: [80.0, 80.0, 40.0, 40.0, 4.0, 4.0, 2.0])
    gravity_compensation: bool = True
    # The palm's task-space impedance (control.palm_impedance), the arm's compliance mode for grasps
    # that keep the fingertips on the table; inactive unless the station's wam.arm_mode asks for it.
    # None: PalmImpedanceParams' defaults (and a scenario's dump, its fingerprint, without it).
    palm_impedance: typing.Optional[PalmImpedanceParams] = None

    def impedance(self) -> PalmImpedanceParams:
        """The palm impedance's gains: the scenario's, or the defaults."""
        return self.palm_impedance or PalmImpedanceParams()


@dataclasses.dataclass
class Scenario:
    """Everything that makes one station. Load with `load_scenario`."""

    plant_config: MultibodyPlantConfig = dataclasses.field(default_factory=MultibodyPlantConfig)
    directives: list[ModelDirective] = dataclasses.field(default_factory=list)
    object: ObjectPlacement = dataclasses.field(default_factory=ObjectPlacement)
    contact: ContactParameters = dataclasses.field(default_factory=ContactParameters)
    camera: CameraConfig = dataclasses.field(default_factory=CameraConfig)
    hand: HandControllerParams = dataclasses.field(default_factory=HandControllerParams)
    arm: ArmParams = dataclasses.field(default_factory=ArmParams)
    protocol: TrialProtocol = dataclasses.field(default_factory=TrialProtocol)
    perception: PerceptionConfig = dataclasses.field(default_factory=PerceptionConfig)


DEFAULT_SCENARIO_FILE = DIAGRAMS_DIR / "station.scenarios.yaml"

# The scenario of the paper's algorithm (its visual primitives: the object's silhouettes), which the
# paper's experiments (`reproduce`, fig4, fig6, fig7, capture) keep; and the best the project has for a
# user's object: the table-top estimate (a column solid over the exploration's depth views, which also
# measures the table and the flat resemblance; docs/results/estimates.md) with the funnel search on the
# shape it saw (docs/design.md §5.4e).
PAPER_SCENARIO_NAME = "default"
BEST_SCENARIO_NAME = "funnel"


def default_scenario_name(object_name: str, scenario_file: str | pathlib.Path | None = None) -> str:
    """The scenario a single run uses when none is named (docs/trials.md, "Which estimate").

    The paper's objects (catalogue names) and primitive strings (sphere:0.12) keep the paper's
    algorithm, so that one trial of them is one trial of its figures; anything else a user brings
    (a mesh or model file, a generated object) gets the best estimate. A scenario file of the user's
    own is read as it is: its "default" scenario.
    """
    from drake_grasp.objects.names import is_mesh_file, is_model_file

    if scenario_file and pathlib.Path(scenario_file).resolve() != DEFAULT_SCENARIO_FILE.resolve():
        return PAPER_SCENARIO_NAME
    name = str(object_name).strip()
    return BEST_SCENARIO_NAME if is_mesh_file(name) or is_model_file(name) else PAPER_SCENARIO_NAME


def load_scenario(filename: str | pathlib.Path = DEFAULT_SCENARIO_FILE, scenario_name: str = "default") -> Scenario:
    """Loads the scenario `scenario_name` from a YAML file of named scenarios.

    Every scenario but the default one itself (diagrams/station.scenarios.yaml, "default") starts
    from the default scenario and overrides only what it says, nested fields included: a variant or
    a user's file names just what it changes (`perception: segmentation: method: color`).

    Raises:
        ValueError: (one line) if the file cannot be read or does not match the Scenario schema.
    """
    filename = pathlib.Path(filename)
    defaults = Scenario()
    if filename.resolve() != DEFAULT_SCENARIO_FILE.resolve() or scenario_name != "default":
        defaults = load_scenario(DEFAULT_SCENARIO_FILE, "default")
    scenario = load_named(Scenario, filename, scenario_name, defaults, "scenario")
    try:
        validate_scenario(scenario)
    except ValueError as e:
        raise ValueError(f"{filename}: scenario '{scenario_name}': {e}") from None
    return scenario


# The values Drake's MultibodyPlantConfig accepts for its string fields (checked here so that a typo
# is a one-line input error before any work, not a failure when the plant is built).
_PLANT_CONFIG_CHOICES = {
    "contact_model": ("point", "hydroelastic", "hydroelastic_with_fallback"),
    "discrete_contact_approximation": ("", "tamsi", "sap", "similar", "lagged"),
    "contact_surface_representation": ("triangle", "polygon"),
}


def validate_scenario(scenario: Scenario) -> None:
    """Raises ValueError (one line) naming the first out-of-range number in `scenario`."""
    config = scenario.plant_config
    if not (math.isfinite(config.time_step) and 0 < config.time_step <= 0.05):
        raise ValueError(f"plant_config.time_step must be in (0, 0.05] s, got {config.time_step}")
    for name, choices in _PLANT_CONFIG_CHOICES.items():
        value = getattr(config, name)
        if value not in choices:
            shown = ", ".join(repr(c) for c in choices)
            raise ValueError(f"plant_config.{name} must be one of {shown}, got {value!r}")
    placement = scenario.object
    for name in ("x", "y", "yaw_deg"):
        if not math.isfinite(getattr(placement, name)):
            raise ValueError(f"object.{name} must be a finite number, got {getattr(placement, name)}")
    if placement.mass_scale is not None and not (math.isfinite(placement.mass_scale) and placement.mass_scale > 0):
        raise ValueError(f"object.mass_scale must be a finite number > 0, got {placement.mass_scale}")
    if placement.pose is not None and (len(placement.pose) != 6 or not all(math.isfinite(v) for v in placement.pose)):
        raise ValueError(f"object.pose must be 6 finite numbers [x, y, z, roll, pitch, yaw], got {placement.pose}")
    if len(scenario.arm.kp) != arm.NUM_JOINTS or len(scenario.arm.kd) != arm.NUM_JOINTS:
        raise ValueError(f"arm.kp and arm.kd need {arm.NUM_JOINTS} gains each")
    try:
        scenario.arm.impedance().validate()
    except ValueError as e:
        raise ValueError(f"arm.palm_impedance.{e}") from None
    contact = scenario.contact
    if not (contact.friction >= 0 and math.isfinite(contact.friction)):
        raise ValueError(f"contact.friction must be >= 0, got {contact.friction}")
    if not (contact.hydroelastic_modulus > 0 and math.isfinite(contact.hydroelastic_modulus)):
        raise ValueError(f"contact.hydroelastic_modulus must be > 0 Pa, got {contact.hydroelastic_modulus}")
    scenario.protocol.validate()
    try:
        scenario.perception.validate()
    except ValueError as e:
        raise ValueError(f"perception.{e}") from None


@dataclasses.dataclass
class Station:
    """A built station: the Diagram and handles to what is inside it."""

    diagram: Diagram
    plant: MultibodyPlant
    scene_graph: SceneGraph
    wam: ModelInstanceIndex
    hand: ModelInstanceIndex
    object_instance: ModelInstanceIndex
    object_spec: ObjectSpec
    hand_controller: HandController
    scenario: Scenario

    def X_WO_nominal(self) -> RigidTransform:
        """The object's resting pose on the table from the scenario, world frame."""
        return object_rest_pose(self.object_spec, self.scenario.object)


def object_rest_pose(spec: ObjectSpec, placement: ObjectPlacement) -> RigidTransform:
    """Pose X_WO of an object resting on the table (top at z = 0) at the placement (or its whole `pose`)."""
    if placement.pose is not None:
        return RigidTransform(RollPitchYaw(*placement.pose[3:6]), placement.pose[0:3])
    R_WO = RollPitchYaw(0, 0, math.radians(placement.yaw_deg)).ToRotationMatrix() @ spec.R_TO
    return RigidTransform(R_WO, [placement.x, placement.y, spec.rest_height])


def MakeStation(scenario: Scenario, object_spec: ObjectSpec | None = None, *, camera: bool = True) -> Station:
    """Builds the station Diagram for `scenario`.

    Args:
        scenario: the scenario.
        object_spec: the object, when already resolved (else from scenario.object.name). The
            station's object is this one with `scenario.object.mass_scale` applied (`Station.object_spec`).
        camera: add the wrist RgbdSensor (and a VTK renderer).
    """
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(scenario.plant_config, builder)
    parser = RegisterPackage(Parser(plant))
    ProcessModelDirectives(ModelDirectives(directives=scenario.directives), parser)
    wam = plant.GetModelInstanceByName("wam")
    hand = plant.GetModelInstanceByName("hand")

    # The scenario's mass scale applies to the object the station simulates (never to a planner's model).
    spec = with_mass_scale(object_spec or resolve_object(scenario.object.name), scenario.object.mass_scale)
    object_instance = AddObject(plant, spec, scenario.contact)
    (object_body_index,) = plant.GetBodyIndices(object_instance)
    object_body = plant.get_body(object_body_index)
    plant.SetDefaultFloatingBaseBodyPose(object_body, object_rest_pose(spec, scenario.object))

    for i, name in enumerate(arm.JOINT_NAMES):
        actuator = plant.GetJointActuatorByName(name, wam)
        actuator.set_controller_gains(PdControllerGains(p=scenario.arm.kp[i], d=scenario.arm.kd[i]))
    SetHandActuatorGains(plant, hand, scenario.hand)
    plant.Finalize()

    # The WAM: implicit PD in the plant + feed-forward gravity compensation, and the palm's impedance
    # law, which takes the arm over from the PD while wam.arm_mode is 1 (control.palm_impedance).
    impedance = builder.AddNamedSystem("wam_palm_impedance",
                                       PalmImpedanceController(plant, wam, scenario.arm.impedance()))
    builder.Connect(plant.get_state_output_port(wam), impedance.GetInputPort("wam.state"))
    builder.Connect(impedance.GetOutputPort("wam.desired_state"), plant.get_desired_state_input_port(wam))
    builder.ExportInput(impedance.GetInputPort("joint_command"), "wam.desired_state")
    for port, name in (("active", "wam.arm_mode"), ("palm_target", "wam.palm_target"),
                       ("normal_force", "wam.palm_force"), ("stiffness", "wam.palm_stiffness"),
                       ("damping", "wam.palm_damping")):
        builder.ExportInput(impedance.GetInputPort(port), name)
    actuation = impedance.GetOutputPort("wam.actuation")
    if scenario.arm.gravity_compensation:
        gravity = builder.AddNamedSystem("wam_gravity_compensation", GravityCompensation(plant, wam))
        builder.Connect(plant.get_state_output_port(), gravity.get_input_port())
        total = builder.AddNamedSystem("wam_actuation", Adder(2, arm.NUM_JOINTS))
        builder.Connect(gravity.get_output_port(), total.get_input_port(0))
        builder.Connect(actuation, total.get_input_port(1))
        actuation = total.get_output_port()
    builder.Connect(actuation, plant.get_actuation_input_port(wam))

    # The hand.
    hand_params = dataclasses.replace(scenario.hand, period=scenario.plant_config.time_step) \
        if scenario.plant_config.time_step > 0 else scenario.hand
    controller = builder.AddNamedSystem("hand_controller", HandController(plant, hand, hand_params))
    builder.Connect(plant.get_state_output_port(hand), controller.GetInputPort("hand_state"))
    builder.Connect(plant.get_net_actuation_output_port(hand), controller.GetInputPort("hand_net_actuation"))
    builder.Connect(controller.GetOutputPort("hand_desired_state"), plant.get_desired_state_input_port(hand))
    builder.ExportInput(controller.GetInputPort("command"), "hand.command")
    builder.ExportInput(controller.GetInputPort("finger_preshape"), "hand.finger_preshape")
    builder.ExportOutput(controller.GetOutputPort("finger_status"), "hand.finger_status")

    builder.ExportOutput(plant.get_state_output_port(wam), "wam.state")
    builder.ExportOutput(plant.get_state_output_port(hand), "hand.state")
    builder.ExportOutput(plant.get_state_output_port(object_instance), "object.state")
    builder.ExportOutput(plant.get_state_output_port(), "plant.state")
    builder.ExportOutput(plant.get_body_poses_output_port(), "body_poses")
    builder.ExportOutput(plant.get_contact_results_output_port(), "contact_results")
    builder.ExportOutput(scene_graph.get_query_output_port(), "query_object")

    if camera:
        AddWristCamera(builder, plant, scene_graph, scenario.camera)

    diagram = builder.Build()
    diagram.set_name("station")
    return Station(diagram=diagram, plant=plant, scene_graph=scene_graph, wam=wam, hand=hand,
                   object_instance=object_instance, object_spec=spec, hand_controller=controller,
                   scenario=scenario)


def AddWristCamera(builder: DiagramBuilder, plant: MultibodyPlant, scene_graph: SceneGraph,
                   config: CameraConfig) -> RgbdSensor:
    """Adds the wrist RgbdSensor, mounted at `config.X_PB` relative to the hand's `wrist_camera` frame.

    The sensor renders on demand (when an image port is evaluated), so a diagram that never asks
    for images pays nothing for the camera.
    """
    if not scene_graph.HasRenderer(RENDERER_NAME):
        scene_graph.AddRenderer(RENDERER_NAME, MakeRenderEngineVtk(RenderEngineVtkParams()))
    config = copy.deepcopy(config)
    config.renderer_name = RENDERER_NAME
    color_camera, depth_camera = config.MakeCameras()
    mount = plant.GetFrameByName("wrist_camera")
    X_BodyMount = mount.GetFixedPoseInBodyFrame()
    X_MountSensor = config.X_PB.GetDeterministicValue()
    sensor = builder.AddNamedSystem(
        "wrist_camera",
        RgbdSensor(parent_id=plant.GetBodyFrameIdOrThrow(mount.body().index()),
                   X_PB=X_BodyMount @ X_MountSensor, color_camera=color_camera, depth_camera=depth_camera),
    )
    builder.Connect(scene_graph.get_query_output_port(), sensor.query_object_input_port())
    builder.ExportOutput(sensor.color_image_output_port(), "camera.color_image")
    builder.ExportOutput(sensor.depth_image_32F_output_port(), "camera.depth_image")
    builder.ExportOutput(sensor.label_image_output_port(), "camera.label_image")
    builder.ExportOutput(sensor.body_pose_in_world_output_port(), "camera.X_WC")
    return sensor
