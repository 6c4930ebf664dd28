"""Three systems on their own, on fixed inputs: GravityCompensation, ObjectEstimator, GraspExecutor.

Each is checked against an independent computation (Drake's inverse dynamics; the estimate's own
geometry; the executor's timings), not against itself.
"""

import numpy as np
import pytest
from pydrake.multibody.plant import ContactResults
from pydrake.multibody.tree import MultibodyForces
from pydrake.systems.analysis import Simulator

from drake_grasp.control.arm_motion import ArmKinematics
from drake_grasp.control.grasp_executor import GraspExecutor, GraspPhase
from drake_grasp.control.gravity_compensation import GravityCompensation
from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp
from drake_grasp.robot.hand import HandAction
from drake_grasp.objects import paper_object
from drake_grasp.primitives.estimate import OBJECT_NOT_FOUND, PERCEPTION_FAILED, ObjectEstimator
from drake_grasp.primitives.sequencer import ExplorationPhase
from drake_grasp.primitives.silhouette import CameraSample
from drake_grasp.protocol import ExecutionTimes
from drake_grasp.station import MakeStation, load_scenario


@pytest.fixture(scope="module")
def station():
    return MakeStation(load_scenario(), paper_object("soccer_ball"), camera=False)


def test_gravity_compensation_equals_inverse_dynamics_at_rest(station):
    """At rest, the torque that holds the arm still is what inverse dynamics asks for with v̇ = 0."""
    plant = station.plant
    system = GravityCompensation(plant, station.wam)
    context = system.CreateDefaultContext()
    plant_context = plant.CreateDefaultContext()
    rng = np.random.default_rng(3)
    wam_rows = [plant.get_joint(j).velocity_start() for j in plant.GetJointIndices(station.wam)
                if plant.get_joint(j).num_velocities() == 1]
    for _ in range(3):
        q = plant.GetPositions(plant_context)
        q[wam_rows] = rng.uniform(-1.0, 1.0, size=7)
        plant.SetPositions(plant_context, q)
        system.get_input_port().FixValue(context, np.concatenate([q, np.zeros(plant.num_velocities())]))
        u = system.get_output_port().Eval(context)
        forces = MultibodyForces(plant)
        plant.CalcForceElementsContribution(plant_context, forces)  # gravity is a force element
        tau_id = plant.CalcInverseDynamics(plant_context, np.zeros(plant.num_velocities()), forces)
        np.testing.assert_allclose(u, tau_id[wam_rows], atol=1e-9)
        assert np.max(np.abs(u)) > 1.0  # a real load: the shoulder holds several N·m


def _sample_vector(p_WC):
    return CameraSample(time=1.0, silhouette=None, p_WC=np.asarray(p_WC, float), R_WC=np.eye(3)).to_vector()


def _estimator_context(phase, centre, axis_info=(0.0, 1.0, 0.0), axis=(1.0, 0.0, 0.0),
                       extents_frame=(1.0, 0.0, 0.0)):
    estimator = ObjectEstimator()
    context = estimator.CreateDefaultContext()
    values = {"phase": [float(phase)], "camera_sample": _sample_vector([0.5, 0.0, 0.5]), "centre": centre,
              "extents": [0.1, 0.06, 0.04], "extents_frame": extents_frame, "axis": axis, "axis_info": axis_info, "sphere_resemblance": [0.2],
              "cylinder_resemblance": [0.7], "box_resemblance": [0.4], "evidence": np.arange(9.0)}
    for name, value in values.items():
        estimator.GetInputPort(name).FixValue(context, np.asarray(value, float))
    return estimator, context


def test_object_estimator_gathers_the_primitives_outputs():
    estimator, context = _estimator_context(ExplorationPhase.DONE, [0.55, 0.0, 0.1],
                                            axis_info=(1.0, 3.0, 0.0), axis=(0.0, 1.0, 0.0))
    estimate = estimator.GetOutputPort("estimate").Eval(context)
    assert estimate.status == "ok"
    np.testing.assert_allclose(estimate.centre, [0.55, 0.0, 0.1])
    assert estimate.depth == pytest.approx(np.linalg.norm([0.05, 0.0, -0.4]))  # from the camera's position
    np.testing.assert_allclose(estimate.principal_axis, [0.0, 1.0, 0.0])  # elongated: the axis is kept
    np.testing.assert_allclose(estimate.axes @ estimate.axes.T, np.eye(3), atol=1e-12)
    assert max(estimate.resemblances, key=estimate.resemblances.get) == "cylinder"
    assert estimate.elongation == 3.0


def test_object_estimator_reports_an_object_never_found():
    for phase, centre in ((ExplorationPhase.NOT_FOUND, [0.5, 0.0, 0.1]), (ExplorationPhase.RESEMBLANCE, [np.nan] * 3)):
        estimator, context = _estimator_context(phase, centre)
        assert estimator.GetOutputPort("estimate").Eval(context).status == OBJECT_NOT_FOUND


def test_object_estimator_reports_an_object_seen_but_never_measured():
    """Seen (the exploration ran to DONE) but no usable silhouette gave a centre: perception failed,
    with the reason; an elongated object whose axis never converged: found, but it cannot be grasped."""
    estimator, context = _estimator_context(ExplorationPhase.DONE, [np.nan] * 3)
    estimate = estimator.GetOutputPort("estimate").Eval(context)
    assert estimate.status == PERCEPTION_FAILED and not estimate.found
    assert "no usable silhouette" in estimate.problem()
    estimator, context = _estimator_context(ExplorationPhase.DONE, [0.55, 0.0, 0.1], axis_info=(1.0, 3.0, 0.0),
                                            axis=(np.nan,) * 3)
    estimate = estimator.GetOutputPort("estimate").Eval(context)
    assert estimate.found and "principal axis did not converge" in estimate.problem()
    with pytest.raises(ValueError, match="principal axis did not converge"):
        estimate.as_grasp_estimate()


def test_object_estimator_gives_an_upright_object_its_height_along_its_vertical_axis():
    """The depth primitive's extents are along (extents_frame, across it, up); an upright elongated
    object's principal axis is vertical, so its length is the vertical extent, and its horizontal axes
    are its sides' (extents_frame). The extents here: 10 cm along extents_frame, 6 cm across, 4 cm up."""
    tilt = 0.05  # rad from the vertical, as the axis primitive measures an upright carton
    axis = (np.sin(tilt), 0.0, np.cos(tilt))
    sides = (np.cos(0.5), np.sin(0.5), 0.0)  # the depth primitive's face direction, 0.5 rad from x
    estimator, context = _estimator_context(ExplorationPhase.DONE, [0.55, 0.0, 0.1], axis_info=(1.0, 1.3, 0.0),
                                            axis=axis, extents_frame=sides)
    estimate = estimator.GetOutputPort("estimate").Eval(context)
    a, b, c = estimate.axes.T
    np.testing.assert_allclose(a, axis)
    np.testing.assert_allclose(estimate.axes.T @ estimate.axes, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(np.cross(a, b), c, atol=1e-12)
    assert np.dot(c, sides) > 0.998  # c: along the sides' direction (made perpendicular to a)
    np.testing.assert_allclose(estimate.extents, [0.04, 0.06, 0.1])  # a: the vertical extent; c: 10 cm
    np.testing.assert_allclose(estimate.principal_axis, axis)
    assert estimate.problem() == ""
    # A lying object (its axis within 45 degrees of the horizontal) keeps the extents as they are.
    estimator, context = _estimator_context(ExplorationPhase.DONE, [0.55, 0.0, 0.1], axis_info=(1.0, 3.0, 0.0),
                                            axis=(np.cos(0.7), 0.0, np.sin(0.7)))
    np.testing.assert_allclose(estimator.GetOutputPort("estimate").Eval(context).extents, [0.1, 0.06, 0.04])


def test_grasp_executor_runs_its_phases_on_time_without_contact(station):
    """With no contact, the approach runs to its target; each later phase lasts its scenario time, and
    the hand opens, then closes as the grasp sequence says."""
    plant = station.plant
    scenario = station.scenario
    times = ExecutionTimes(close_time=0.3, lift_time=0.4, hold_time=0.5)
    q_start = np.asarray(scenario.protocol.start_configuration, float)
    plan = plan_compliant_grasp("spherical", oracle_estimate(station.X_WO_nominal(), station.object_spec))
    executor = GraspExecutor(plant, station.scene_graph, station.wam, plant.GetBodyIndices(station.hand), plan,
                             q_start, times)
    context = executor.CreateDefaultContext()
    executor.GetInputPort("wam.state").FixValue(context, np.concatenate([q_start, np.zeros(7)]))
    executor.GetInputPort("contact_results").FixValue(context, ContactResults())
    motion = executor.progress(context).motion
    simulator = Simulator(executor, context)
    assert executor.phase(context) == GraspPhase.MOVE
    assert executor.GetOutputPort("hand.command").Eval(context)[1] == float(HandAction.OPEN)

    simulator.AdvanceTo(motion.move_time - 0.02)
    assert executor.phase(context) == GraspPhase.MOVE
    simulator.AdvanceTo(motion.move_time + 0.02)
    assert executor.phase(context) == GraspPhase.APPROACH
    q_at_pregrasp = executor.GetOutputPort("wam.desired_state").Eval(context)[:7]
    X_WP = ArmKinematics(plant, station.wam).palm_pose(q_at_pregrasp)
    # The approach starts at the pre-grasp pose (within what the arm moved in 0.02 s of approach).
    assert np.linalg.norm(X_WP.translation() - plan.X_WP_pregrasp.translation()) < 0.005

    end_of_approach = motion.move_time + motion.approach_duration
    simulator.AdvanceTo(end_of_approach + 0.02)
    progress = executor.progress(context)
    assert progress.phase == GraspPhase.CLOSE and not progress.stopped_on_contact
    assert progress.approach_travel == pytest.approx(plan.approach_distance, abs=0.002)
    assert executor.GetOutputPort("hand.command").Eval(context)[1] == float(HandAction.CLOSE)

    simulator.AdvanceTo(end_of_approach + times.close_time + times.lift_time + times.hold_time + 0.1)
    progress = executor.progress(context)
    assert progress.phase == GraspPhase.DONE and progress.outcome == ""
    starts = progress.phase_times
    assert starts[GraspPhase.LIFT] - starts[GraspPhase.CLOSE] == pytest.approx(times.close_time, abs=0.011)
    assert starts[GraspPhase.HOLD] - starts[GraspPhase.LIFT] == pytest.approx(times.lift_time, abs=0.011)
    assert starts[GraspPhase.DONE] - starts[GraspPhase.HOLD] == pytest.approx(times.hold_time, abs=0.011)
    # The lift raised the palm by the lift height.
    q_end = executor.GetOutputPort("wam.desired_state").Eval(context)[:7]
    lifted = ArmKinematics(plant, station.wam).palm_pose(q_end).translation()
    assert lifted[2] - plan.X_WP_target.translation()[2] == pytest.approx(times.lift_height, abs=0.005)


def test_the_executor_runs_the_grasp_itself_when_reachable_and_names_every_turn_it_tried_when_not(station):
    """Reachable: the grasp's own pose, turn 0. Out of the WAM's reach (2 m away): its near-symmetric
    equivalents are tried too, and the error lists them (the spherical grasp's thirds)."""
    from drake_grasp.control.arm_motion import ReachError
    from pydrake.math import RigidTransform

    plant, scenario = station.plant, station.scenario
    q_start = np.asarray(scenario.protocol.start_configuration, float)
    executor = GraspExecutor(plant, station.scene_graph, station.wam, plant.GetBodyIndices(station.hand), None,
                             q_start, scenario.protocol.execution)
    plan = plan_compliant_grasp("spherical", oracle_estimate(station.X_WO_nominal(), station.object_spec))
    motion = executor.plan_reachable_motion(plan, q_start)
    assert motion.fallback == "" and motion.plan == plan and motion.unreachable == ""
    far = type(plan)(plan.grasp, plan.spread, RigidTransform(plan.X_WP_target.rotation(), [2.0, 0.0, 0.3]))
    with pytest.raises(ReachError, match=r"nor the grasp turned -120°, \+120° about the approach"):
        executor.plan_reachable_motion(far, q_start)


def test_a_path_that_brings_the_arm_or_the_hand_base_to_the_table_is_unreachable(station):
    """The arm's shell and the hand base stay clear of the table along a planned path: a top-down
    palm 20 cm above the table is clear; brought down to 2 mm above it, the palm's housing is
    within the margin, and plan_motion says so."""
    from drake_grasp.control.arm_motion import TABLE_MARGIN, ReachError
    from drake_grasp.grasps import GraspPlan
    from pydrake.math import RigidTransform, RotationMatrix

    plant, scenario = station.plant, station.scenario
    q_start = np.asarray(scenario.protocol.start_configuration, float)
    kinematics = ArmKinematics(plant, station.wam)
    p = station.X_WO_nominal().translation()
    down = RotationMatrix.MakeXRotation(np.pi)
    q_high = kinematics.solve(RigidTransform(down, [p[0], p[1], 0.2]), q_start)
    z, part = kinematics.lowest_point(q_high)
    # From above, the lowest part is the hand base's palm face, 20 cm up; the arm is above it.
    assert part == "hand base" and z == pytest.approx(0.2, abs=2e-3)
    kinematics.check_table_clearance([q_high])
    low = GraspPlan(None, 0.0, RigidTransform(down, [p[0], p[1], 0.002]), approach_distance=0.05,
                    stop_on_contact=False)
    executor = GraspExecutor(plant, station.scene_graph, station.wam, plant.GetBodyIndices(station.hand), None,
                             q_start, scenario.protocol.execution)
    with pytest.raises(ReachError, match="would strike the table"):
        executor.plan_motion(low, q_start)
    assert TABLE_MARGIN > 0
