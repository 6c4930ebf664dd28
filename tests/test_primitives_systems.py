"""Each visual-primitive LeafSystem alone, with fixed inputs (FixValue).

Where a test needs images of an object from several views, it makes them here: the silhouette of a
convex object is the convex hull of its projected surface points, filled on the pixel grid.
"""

import math

import numpy as np
import pytest
from matplotlib.path import Path
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.analysis import Simulator
from pydrake.systems.sensors import ImageLabel16I
from scipy.spatial import ConvexHull

from drake_grasp.control.camera_motion import CameraMotionParams, CameraTwistController
from drake_grasp.primitives.camera import SilhouetteCamera
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.common import PrimitiveCommand
from drake_grasp.primitives.depth import DepthParams, DepthPrimitive
from drake_grasp.primitives.principal_axis import PrincipalAxisPrimitive
from drake_grasp.primitives.resemblance import ShapeResemblancePrimitive
from drake_grasp.primitives.sequencer import ExplorationSequencer, ExplorationPhase, SequencerParams
from drake_grasp.primitives.silhouette import CameraSample, measure_silhouette

K = CameraIntrinsics.from_fov_y(320, 240, math.radians(60.0))
PERIOD = 0.05
R_DOWN = np.diag([1.0, -1.0, -1.0])  # looking straight down, image u along the world's x
_V, _U = np.mgrid[0:240, 0:320]
_PIXELS = np.column_stack([_U.ravel(), _V.ravel()]).astype(float)


def render_mask(points_W, R_WC, p_WC):
    """The silhouette of the convex hull of `points_W` seen by a camera at (R_WC, p_WC)."""
    p_C = (np.asarray(points_W) - p_WC) @ R_WC
    uv = np.column_stack([K.fx * p_C[:, 0] / p_C[:, 2] + K.cx, K.fy * p_C[:, 1] / p_C[:, 2] + K.cy])
    outline = Path(uv[ConvexHull(uv).vertices])
    return outline.contains_points(_PIXELS).reshape(240, 320)


def sphere_points(centre, radius, n=3000):
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    phi = i * math.pi * (3 - math.sqrt(5))
    rho = np.sqrt(1 - z * z)
    return np.asarray(centre) + radius * np.column_stack([rho * np.cos(phi), rho * np.sin(phi), z])


def box_points(centre, size):
    return np.array([np.asarray(centre) + np.asarray(size) / 2 * (2 * np.array(s) - 1) for s in np.ndindex(2, 2, 2)])


def orbit_pose(centre, radius, about, angle):
    """Camera on a circle about the world axis `about` ('x' or 'y') through `centre`, looking at it."""
    c, s = math.cos(angle), math.sin(angle)
    R = np.array([[1, 0, 0], [0, c, -s], [0, s, c]]) if about == "x" else np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    R_WC = R @ R_DOWN
    return R_WC, np.asarray(centre) - radius * R_WC[:, 2]


def sample_of(points_W, R_WC, p_WC, time):
    return CameraSample(time, measure_silhouette(render_mask(points_W, R_WC, p_WC)), p_WC, R_WC)


def step(system, context, time, **inputs):
    """One periodic discrete update at `time` with the given inputs fixed; the new state is kept."""
    context.SetTime(time)
    for name, value in inputs.items():
        system.GetInputPort(name).FixValue(context, value)
    context.SetDiscreteState(system.EvalUniquePeriodicDiscreteUpdate(context))


def output(system, context, name):
    return np.array(system.GetOutputPort(name).Eval(context))


def plus_views(points, centre, radius, amplitude, count=13):
    """Views on an arc about x, then about y, around `centre` (the resemblance primitives' motion)."""
    poses = [orbit_pose(centre, radius, "x", a) for a in np.linspace(-amplitude, amplitude, count)]
    poses += [orbit_pose(centre, radius, "y", a) for a in np.linspace(-amplitude, amplitude, count)]
    return [sample_of(points, R, p, PERIOD * (k + 1)) for k, (R, p) in enumerate(poses)]


# --- SilhouetteCamera -----------------------------------------------------------------------------


def test_silhouette_camera_measures_the_labelled_blob():
    camera = SilhouetteCamera(K, [7], PERIOD)
    assert [camera.get_input_port(i).get_name() for i in range(2)] == ["label_image", "X_WC"]
    context = camera.CreateDefaultContext()
    image = ImageLabel16I(320, 240)
    image.mutable_data[:] = 3  # the table
    image.mutable_data[100:140, 150:230] = 7  # the object: 80 x 40 px
    X_WC = RigidTransform(RotationMatrix(R_DOWN), [0.5, 0.0, 0.4])
    camera.GetInputPort("label_image").FixValue(context, image)
    camera.GetInputPort("X_WC").FixValue(context, X_WC)
    context.SetTime(0.25)
    sample = CameraSample.from_vector(camera.EvalUniquePeriodicDiscreteUpdate(context).get_vector(0).get_value())
    assert sample.time == 0.25 and sample.usable
    assert sample.silhouette.area == 80 * 40
    assert sample.silhouette.centroid == pytest.approx((189.5, 119.5))
    assert sample.silhouette.eccentricity == pytest.approx(2.0, rel=0.01)
    assert sample.p_WC == pytest.approx([0.5, 0.0, 0.4]) and sample.R_WC == pytest.approx(R_DOWN)
    image.mutable_data[:] = 3
    camera.GetInputPort("label_image").FixValue(context, image)
    assert not CameraSample.from_vector(camera.EvalUniquePeriodicDiscreteUpdate(context).get_vector(0).get_value()).visible
    # Stopped (`active` 0), it takes no image and holds its last sample.
    camera.GetInputPort("active").FixValue(context, [0.0])
    held = camera.EvalUniquePeriodicDiscreteUpdate(context).get_vector(0).get_value()
    np.testing.assert_array_equal(held, context.get_discrete_state_vector().get_value())


def test_silhouette_camera_with_colour_segmentation_takes_the_colour_image():
    from drake_grasp.primitives.camera import SegmentationParams

    camera = SilhouetteCamera(K, [7], PERIOD, SegmentationParams(method="color"))
    assert camera.get_input_port(0).get_name() == "color_image"
    rgba = np.zeros((240, 320, 4), np.uint8)
    rgba[..., 3] = 255
    rgba[50:90, 60:100, :3] = (240, 200, 25)  # yellow paper
    assert camera.mask(rgba).sum() == 40 * 40


# --- DepthPrimitive -------------------------------------------------------------------------------


def test_depth_primitive_centres_the_object_and_backs_off_at_the_border():
    depth = DepthPrimitive(K, PERIOD)
    context = depth.CreateDefaultContext()
    R, p = orbit_pose([0.55, 0.0, 0.05], 0.4, "x", 0.0)
    off_centre = sample_of(sphere_points([0.60, 0.0, 0.05], 0.05), R, p, 0.05)  # to the right (+u)
    step(depth, context, 0.05, camera_sample=off_centre.to_vector(), command=[PrimitiveCommand.TRACK], axis=[np.nan] * 3)
    twist = output(depth, context, "V_C_desired")
    assert twist[1] > 0 and abs(twist[0]) < 1e-9 and twist[5] == 0  # turn toward +x, no translation
    cut = sample_of(sphere_points([0.55, 0.0, 0.05], 0.3), R, p, 0.1)  # too big: cut by the border
    step(depth, context, 0.1, camera_sample=cut.to_vector())
    assert output(depth, context, "V_C_desired")[5] < 0
    step(depth, context, 0.15, command=[PrimitiveCommand.OFF])
    assert not output(depth, context, "V_C_desired").any()


def test_depth_primitive_approaches_a_small_object():
    depth = DepthPrimitive(K, PERIOD, DepthParams(min_camera_height=0.1))
    context = depth.CreateDefaultContext()
    R, p = orbit_pose([0.55, 0.0, 0.02], 0.5, "x", 0.0)
    small = sample_of(sphere_points([0.55, 0.0, 0.02], 0.02), R, p, 0.05)
    step(depth, context, 0.05, camera_sample=small.to_vector(), command=[PrimitiveCommand.APPROACH], axis=[np.nan] * 3)
    assert output(depth, context, "V_C_desired")[5] > 0


def test_depth_primitive_estimates_centre_depth_and_size_of_a_box_from_an_arc():
    centre = np.array([0.55, 0.01, 0.04])
    size = np.array([0.16, 0.10, 0.08])
    depth = DepthPrimitive(K, PERIOD, DepthParams(forget_time=0.0))
    context = depth.CreateDefaultContext()
    poses = [orbit_pose(centre, 0.45, about, a) for about in ("x", "y") for a in np.linspace(-0.5, 0.5, 9)]
    for k, (R, p) in enumerate(poses):
        sample = sample_of(box_points(centre, size), R, p, PERIOD * (k + 1))
        step(depth, context, sample.time, camera_sample=sample.to_vector(), command=[PrimitiveCommand.TRACK],
             axis=[1.0, 0.0, 0.0])
    assert output(depth, context, "fit_info")[0] == 1.0
    assert output(depth, context, "centre") == pytest.approx(centre, abs=0.002)
    assert output(depth, context, "depth")[0] == pytest.approx(np.linalg.norm(poses[-1][1] - centre), rel=0.01)
    assert output(depth, context, "extents") == pytest.approx(size, rel=0.03)


def test_depth_primitive_arcs_about_its_y_axis_when_exploring():
    depth = DepthPrimitive(K, PERIOD, DepthParams(arc_start=0.0, arc_period=2.0))
    context = depth.CreateDefaultContext()
    R, p = orbit_pose([0.55, 0.0, 0.05], 0.4, "x", 0.0)
    sample = sample_of(sphere_points([0.55, 0.0, 0.05], 0.05), R, p, 0.05)
    step(depth, context, 0.05, camera_sample=sample.to_vector(), command=[PrimitiveCommand.EXPLORE], axis=[np.nan] * 3)
    step(depth, context, 0.30, camera_sample=sample.to_vector())  # 0.25 s into the arc
    twist = output(depth, context, "V_C_desired")
    assert abs(twist[1]) > 0.1 and abs(twist[0]) < 0.05  # rotation about y_C ...
    assert abs(twist[3]) > 0.01  # ... and the translation that pivots about the object


# --- PrincipalAxisPrimitive -----------------------------------------------------------------------


def test_axis_primitive_rolls_to_align_the_blob_with_the_image_border():
    axis = PrincipalAxisPrimitive(K, PERIOD)
    context = axis.CreateDefaultContext()
    centre = np.array([0.55, 0.0, 0.05])
    R, p = orbit_pose(centre, 0.45, "x", 0.0)
    yaw = 0.3
    box = box_points([0, 0, 0], [0.25, 0.06, 0.06]) @ RotationMatrix.MakeZRotation(yaw).matrix().T + centre
    sample = sample_of(box, R, p, 0.05)
    step(axis, context, 0.05, camera_sample=sample.to_vector(), command=[PrimitiveCommand.TRACK], centre=centre)
    twist = output(axis, context, "V_C_desired")
    # The blob lies at −0.3 rad in the image (v points along −y): roll by −0.3 to align it.
    assert twist[2] == pytest.approx(axis.params.roll_gain * -yaw, rel=0.05) and not twist[3:].any()
    round_sample = sample_of(sphere_points(centre, 0.05), R, p, 0.1)
    step(axis, context, 0.1, camera_sample=round_sample.to_vector())
    assert output(axis, context, "V_C_desired")[2] == 0.0


def test_axis_primitive_finds_the_axis_in_space_from_an_arc_around_it():
    axis = PrincipalAxisPrimitive(K, PERIOD)
    context = axis.CreateDefaultContext()
    centre = np.array([0.55, 0.0, 0.04])
    box = box_points(centre, [0.26, 0.18, 0.08])  # the game box: elongated 1.44
    for k, angle in enumerate(np.linspace(-0.35, 0.35, 9)):
        R, p = orbit_pose(centre, 0.45, "x", angle)
        step(axis, context, PERIOD * (k + 1), camera_sample=sample_of(box, R, p, PERIOD * (k + 1)).to_vector(),
             command=[PrimitiveCommand.TRACK], centre=centre)
    found = output(axis, context, "axis")
    elongated, mean_eccentricity, _ = output(axis, context, "axis_info")
    assert elongated == 1.0 and mean_eccentricity > 1.3
    assert math.degrees(math.acos(min(abs(found[0]), 1.0))) < 1.0


# --- ShapeResemblancePrimitive --------------------------------------------------------------------


@pytest.mark.parametrize("shape, points, radius", [
    ("sphere", sphere_points([0.55, 0.0, 0.05], 0.05), 0.5),
    ("box", box_points([0.55, 0.0, 0.05], [0.1, 0.1, 0.1]), 0.6),
])
def test_resemblance_primitives_name_the_shape(shape, points, radius):
    centre = np.array([0.55, 0.0, 0.05])
    systems = {s: ShapeResemblancePrimitive(s, K, PERIOD) for s in ("sphere", "cylinder", "box")}
    contexts = {s: systems[s].CreateDefaultContext() for s in systems}
    views = plus_views(points, centre, radius, 0.7)
    for s, system in systems.items():
        for sample in views:
            step(system, contexts[s], sample.time, camera_sample=sample.to_vector(),
                 command=[PrimitiveCommand.EXPLORE], centre=centre, axis=[1.0, 0.0, 0.0])
    scores = {s: output(systems[s], contexts[s], "resemblance")[0] for s in systems}
    assert max(scores, key=scores.get) == shape, scores
    if shape == "sphere":
        assert scores["sphere"] >= 0.9


def test_resemblance_primitive_is_still_when_off_and_arcs_when_exploring():
    cylinder = ShapeResemblancePrimitive("cylinder", K, PERIOD)
    context = cylinder.CreateDefaultContext()
    centre = np.array([0.55, 0.0, 0.05])
    R, p = orbit_pose(centre, 0.4, "x", 0.0)
    sample = sample_of(sphere_points(centre, 0.05), R, p, 0.05)
    inputs = dict(camera_sample=sample.to_vector(), centre=centre, axis=[1.0, 0.0, 0.0])
    step(cylinder, context, 0.05, command=[PrimitiveCommand.OFF], **inputs)
    assert not output(cylinder, context, "V_C_desired").any() and output(cylinder, context, "resemblance")[0] == 0
    step(cylinder, context, 0.10, command=[PrimitiveCommand.EXPLORE], **inputs)
    assert output(cylinder, context, "frame")[3:6] == pytest.approx([1.0, 0.0, 0.0])
    step(cylinder, context, 0.60, **inputs)
    twist = output(cylinder, context, "V_C_desired")
    assert abs(twist[0]) > 0.1 and abs(twist[1]) < 1e-6  # about the axis (world x = camera x)


# --- ExplorationSequencer -------------------------------------------------------------------------


@pytest.mark.parametrize("visible", [True, False])
def test_sequencer_runs_the_phases(visible):
    params = SequencerParams(approach_time=0.5, depth_axis_time=1.0, resemblance_time=1.0)
    sequencer = ExplorationSequencer(PERIOD, params)
    simulator = Simulator(sequencer)
    context = simulator.get_mutable_context()
    R, p = orbit_pose([0.55, 0, 0.05], 0.4, "x", 0.0)
    sample = sample_of(sphere_points([0.55, 0, 0.05], 0.05), R, p, 0.0) if visible else CameraSample.empty()
    sequencer.GetInputPort("camera_sample").FixValue(context, sample.to_vector())

    def commands():
        return [int(sequencer.GetOutputPort(n).Eval(context)[0])
                for n in ("phase", "depth_command", "axis_command", "resemblance_command")]

    assert commands() == [ExplorationPhase.APPROACH, PrimitiveCommand.APPROACH, PrimitiveCommand.TRACK, PrimitiveCommand.OFF]
    simulator.AdvanceTo(0.75)
    if not visible:
        assert commands() == [ExplorationPhase.NOT_FOUND] + [PrimitiveCommand.OFF] * 3
        return
    assert commands() == [ExplorationPhase.DEPTH_AXIS, PrimitiveCommand.EXPLORE, PrimitiveCommand.EXPLORE, PrimitiveCommand.OFF]
    simulator.AdvanceTo(1.75)
    assert commands() == [ExplorationPhase.RESEMBLANCE, PrimitiveCommand.TRACK, PrimitiveCommand.TRACK, PrimitiveCommand.EXPLORE]
    simulator.AdvanceTo(2.75)
    assert commands() == [ExplorationPhase.DONE] + [PrimitiveCommand.OFF] * 3
    assert sequencer.state(context).phase.finished


@pytest.mark.parametrize("eccentricity, invariance_a, confirmed", [(3.0, 0.95, "cylinder"), (3.0, 0.05, "box"),
                                                                   (3.0, 0.5, None), (1.3, 0.95, None)])
def test_the_minimal_sequencer_confirms_or_falls_back(eccentricity, invariance_a, confirmed):
    from drake_grasp.primitives.sequencer import MinimalParams

    params = SequencerParams(approach_time=0.5, depth_axis_time=1.0, resemblance_time=1.0,
                             minimal=MinimalParams(confirm_time=0.5))
    sequencer = ExplorationSequencer(PERIOD, params)
    simulator = Simulator(sequencer)
    context = simulator.get_mutable_context()
    R, p = orbit_pose([0.55, 0, 0.05], 0.4, "x", 0.0)
    sequencer.GetInputPort("camera_sample").FixValue(
        context, sample_of(sphere_points([0.55, 0, 0.05], 0.05), R, p, 0.0).to_vector())
    sequencer.GetInputPort("axis_info").FixValue(context, [1.0, eccentricity, 0.0])
    # The box primitive's evidence: [V_a, V_b, e0, I_a, I_b, R, sphere, cylinder, box].
    sequencer.GetInputPort("evidence").FixValue(context, [0.0, 0.0, eccentricity, invariance_a, 1.0, 0.0, 0.0,
                                                          invariance_a, 1.0 - invariance_a])

    def commands():
        return [int(sequencer.GetOutputPort(n).Eval(context)[0])
                for n in ("phase", "sphere_command", "cylinder_command", "box_command")]

    simulator.AdvanceTo(0.6)
    if eccentricity < 1.5:  # neither elongated nor round: no hypothesis, the full exploration at once
        assert commands()[0] == ExplorationPhase.DEPTH_AXIS
        assert sequencer.GetOutputPort("outcome").Eval(context)["kind"] == "fallback"
        return
    # Elongated: the arc about the axis (the cylinder primitive's) confirms; the box primitive records.
    assert commands() == [ExplorationPhase.CONFIRM, PrimitiveCommand.OFF, PrimitiveCommand.CONFIRM,
                          PrimitiveCommand.EXPLORE]
    assert sequencer.GetOutputPort("outcome").Eval(context) == {"kind": "minimal", "hypothesis": "elongated",
                                                                "why": ""}
    simulator.AdvanceTo(1.1)
    outcome = sequencer.GetOutputPort("outcome").Eval(context)
    if confirmed:
        assert commands()[0] == ExplorationPhase.DONE and outcome["kind"] == "confirmed"
        assert confirmed in outcome["why"] or ("not invariant" in outcome["why"]) == (confirmed == "box")
        return
    assert commands() == [ExplorationPhase.DEPTH_AXIS] + [PrimitiveCommand.OFF] * 3 and outcome["kind"] == "fallback"
    simulator.AdvanceTo(3.2)  # the full exploration from there: depth and axis, then the resemblances
    assert commands()[0] == ExplorationPhase.DONE
    names = [ExplorationPhase(p).name for p, _ in sequencer.state(context).phase_starts]
    assert names == ["APPROACH", "CONFIRM", "DEPTH_AXIS", "RESEMBLANCE", "DONE"]


# --- CameraTwistController ------------------------------------------------------------------------


@pytest.fixture(scope="module")
def station():
    from drake_grasp.station import MakeStation, load_scenario

    return MakeStation(load_scenario(), camera=False)


def test_camera_twist_controller_moves_the_camera_as_asked(station):
    from drake_grasp.perception import camera_mount, load_perception_config, start_camera_pose, start_configuration

    frame, X_FC = camera_mount(station)
    controller = CameraTwistController(station.plant, station.wam, frame, X_FC, CameraMotionParams())
    assert controller.get_input_port(0).get_name() == "V_C_desired"
    config = load_perception_config()
    X_WC0 = start_camera_pose(np.array([0.55, 0.0, 0.0]), config)
    q0 = start_configuration(station, X_WC0, config)
    simulator = Simulator(controller)
    context = simulator.get_mutable_context()
    controller.SetInitialPositions(context, q0)
    assert controller.camera_pose(q0).translation() == pytest.approx(X_WC0.translation(), abs=2e-3)  # IK tolerance
    X_WC0 = controller.camera_pose(q0)
    twist = np.array([0.0, 0.2, 0.0, 0.0, 0.0, 0.05])  # turn about y_C at 0.2 rad/s, move forward 5 cm/s
    controller.GetInputPort("V_C_desired").FixValue(context, twist)
    simulator.AdvanceTo(1.0)
    state = controller.GetOutputPort("wam.desired_state").Eval(context)
    X_WC1 = controller.camera_pose(state[:7])
    R_C0C1 = X_WC0.rotation().inverse() @ X_WC1.rotation()
    assert R_C0C1.ToAngleAxis().angle() == pytest.approx(0.2, abs=0.01)
    assert R_C0C1.ToAngleAxis().axis() @ [0, 1, 0] == pytest.approx(1.0, abs=0.01)
    assert output(controller, context, "status")[0] == 0.0
    # Moved about 5 cm, mostly along the optical axis (which turned a little on the way).
    moved = X_WC1.translation() - X_WC0.translation()
    assert np.linalg.norm(moved) == pytest.approx(0.05, abs=0.005)
    assert np.all(np.abs(state[7:]) <= controller.params.joint_velocity_limit + 1e-9)
    # Stopped (`active` 0, as the supervisor sets it once it drives the arm), it holds its state.
    controller.GetInputPort("active").FixValue(context, [0.0])
    simulator.AdvanceTo(1.5)
    np.testing.assert_array_equal(controller.GetOutputPort("wam.desired_state").Eval(context), state)


def test_the_sequencer_stops_the_camera_when_the_exploration_is_over():
    sequencer = ExplorationSequencer(0.05, SequencerParams(0.1, 0.1, 0.1))
    context = sequencer.CreateDefaultContext()
    sample = np.zeros(25)
    sample[1] = 1.0  # the object is visible
    sequencer.GetInputPort("camera_sample").FixValue(context, sample)
    simulator = Simulator(sequencer, context)
    assert sequencer.GetOutputPort("camera_active").Eval(context)[0] == 1.0
    simulator.AdvanceTo(0.2)
    assert sequencer.GetOutputPort("camera_active").Eval(context)[0] == 1.0
    simulator.AdvanceTo(0.4)
    assert sequencer.state(context).phase == ExplorationPhase.DONE
    assert sequencer.GetOutputPort("camera_active").Eval(context)[0] == 0.0
