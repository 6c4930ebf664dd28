"""The torque-close controller with breakaway: the pure clutch model, then real closing in Drake."""

import math

import numpy as np
import pytest
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource, VectorLogSink

from drake_grasp.robot import hand
from drake_grasp.control.hand_controller import (
    FingerDrive,
    HandController,
    HandControllerParams,
    SetHandActuatorGains,
    advance_fingers,
)
from drake_grasp.robot.hand import ComplianceMode, HandAction
from drake_grasp.robot.modelgen import HAND_SDF
from drake_grasp.paths import RegisterPackage

TIME_STEP = 0.005


# --- The pure clutch model. ----------------------------------------------------------------------

def _step(drive, action=HandAction.CLOSE, spread=0.0, q_p=None, q_d=None, tau=None, params=None,
          v_d=None):
    params = params or HandControllerParams()
    q_p = drive.proximal.copy() if q_p is None else np.asarray(q_p, float)
    q_d = drive.distal.copy() if q_d is None else np.asarray(q_d, float)
    tau = np.zeros(3) if tau is None else np.asarray(tau, float)
    # The joints are where they were commanded, at rest (a worst case for the lead: no velocity).
    # The joints are where they were commanded, moving as they were commanded (perfect tracking).
    # unless told otherwise.
    v_d = drive.distal_rate if v_d is None else np.asarray(v_d, float)
    return advance_fingers(drive, spread, action, drive.spread, q_p, q_d, tau, drive.proximal_rate,
                           v_d, params, params.period)


def test_free_closing_keeps_distal_at_a_third_of_proximal():
    drive = FingerDrive()
    for _ in range(100):
        drive = _step(drive)
    assert np.all(drive.proximal > 0.3)
    np.testing.assert_allclose(drive.distal, drive.proximal / 3)
    assert not drive.broken_away.any()


def test_breakaway_freezes_proximal_and_speeds_up_distal_fourfold():
    params = HandControllerParams()
    drive = FingerDrive()
    for _ in range(40):
        drive = _step(drive, params=params)
    coupled_rate = drive.distal_rate[0]
    # Finger 2's proximal link is blocked: the torque on it exceeds the breakaway torque.
    tau = np.array([0.0, params.breakaway_torque + 0.01, 0.0])
    measured = drive.proximal.copy()
    drive = _step(drive, q_p=measured, tau=tau, params=params)
    assert list(drive.broken_away) == [False, True, False]
    assert drive.breakaway_angle[1] == pytest.approx(measured[1])
    held = drive.proximal[1]
    for _ in range(10):
        drive = _step(drive, params=params)
    assert drive.proximal[1] == held
    assert drive.distal_rate[1] == pytest.approx(4 * coupled_rate)


def test_blocked_distal_stalls_the_whole_finger():
    drive = FingerDrive()
    for _ in range(40):
        drive = _step(drive)
    stuck = drive.distal.copy()
    before = drive.proximal.copy()
    for _ in range(20):
        drive = _step(drive, q_d=stuck, v_d=np.zeros(3))  # the distal links do not move any more
    lead = HandControllerParams().distal_lead
    assert np.all(drive.distal <= stuck + lead + 1e-12)
    assert np.all(drive.proximal <= before + 3 * lead + 1e-12)
    assert not drive.broken_away.any()


def test_opening_reengages_the_clutch():
    drive = FingerDrive()
    drive.broken_away[:] = True
    drive.proximal[:] = 1.0
    drive.distal[:] = 0.8
    for _ in range(300):
        drive = _step(drive, action=HandAction.OPEN)
    assert not drive.broken_away.any()
    assert np.all(drive.proximal <= 0.0) and np.all(drive.distal <= 0.0)


def test_fingers_wait_for_the_spread():
    drive = _step(FingerDrive(), spread=ComplianceMode.SPHERICAL.spread)
    assert np.all(drive.proximal == 0.0)
    assert 0 < drive.spread < ComplianceMode.SPHERICAL.spread


def test_params_reject_a_drive_that_cannot_break_away():
    with pytest.raises(ValueError, match="must exceed breakaway_torque"):
        HandControllerParams(proximal_drive_torque=0.4)
    with pytest.raises(ValueError, match="closing_time"):
        HandControllerParams(closing_time=float("nan"))


# --- Closing in simulation: a hand welded palm-up in the world. ----------------------------------

_FIXED_OBSTACLE = """<?xml version="1.0"?>
<sdf version="1.9"><model name="obstacle"><static>true</static><link name="body">
<collision name="c"><pose>{pose}</pose><geometry>{geometry}</geometry>
<drake:proximity_properties><drake:rigid_hydroelastic/><drake:mesh_resolution_hint>0.005</drake:mesh_resolution_hint>
<drake:mu_dynamic>0.5</drake:mu_dynamic><drake:mu_static>0.5</drake:mu_static>
</drake:proximity_properties></collision></link></model></sdf>"""


def close_hand(mode: ComplianceMode, obstacles=(), duration=2.5):
    """Closes the hand (palm up, base at the world origin) around fixed obstacles.

    Returns (final joint angles [spread1, spread2, prox1..3, dist1..3], finger_status, log of q,
    names of the hand bodies in contact at the end).
    """
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(
        MultibodyPlantConfig(time_step=TIME_STEP, discrete_contact_approximation="lagged"), builder)
    parser = RegisterPackage(Parser(plant))
    (hand_instance,) = parser.AddModels(str(HAND_SDF))
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("bh_base"))
    for i, (pose, geometry) in enumerate(obstacles):
        parser.SetAutoRenaming(True)
        parser.AddModelsFromString(_FIXED_OBSTACLE.format(pose=pose, geometry=geometry), "sdf")
    params = HandControllerParams(period=TIME_STEP)
    SetHandActuatorGains(plant, hand_instance, params)
    plant.Finalize()
    controller = builder.AddSystem(HandController(plant, hand_instance, params))
    builder.Connect(plant.get_state_output_port(hand_instance), controller.GetInputPort("hand_state"))
    builder.Connect(plant.get_net_actuation_output_port(hand_instance), controller.GetInputPort("hand_net_actuation"))
    builder.Connect(controller.GetOutputPort("hand_desired_state"), plant.get_desired_state_input_port(hand_instance))
    command = builder.AddSystem(ConstantVectorSource([mode.spread, float(HandAction.CLOSE)]))
    builder.Connect(command.get_output_port(), controller.GetInputPort("command"))
    q_log = builder.AddSystem(VectorLogSink(16))
    builder.Connect(plant.get_state_output_port(hand_instance), q_log.get_input_port())
    diagram = builder.Build()
    simulator = Simulator(diagram)
    simulator.AdvanceTo(duration)
    context = simulator.get_context()
    index = controller._index
    q = index.joint_positions(plant.get_state_output_port(hand_instance).Eval(plant.GetMyContextFromRoot(context)))
    status = controller.GetOutputPort("finger_status").Eval(controller.GetMyContextFromRoot(context))
    log = q_log.FindLog(context)
    q_hist = np.array([index.joint_positions(x) for x in log.data().T])
    return q, status, q_hist, _bodies_in_contact(plant, plant.GetMyContextFromRoot(context))


def _bodies_in_contact(plant, plant_context):
    results = plant.get_contact_results_output_port().Eval(plant_context)
    inspector = plant.get_geometry_query_input_port().Eval(plant_context).inspector()
    names = set()
    for i in range(results.num_hydroelastic_contacts()):
        surface = results.hydroelastic_contact_info(i).contact_surface()
        for geometry in (surface.id_M(), surface.id_N()):
            names.add(plant.GetBodyFromFrameId(inspector.GetFrameId(geometry)).name())
    for i in range(results.num_point_pair_contacts()):
        info = results.point_pair_contact_info(i)
        names.update(plant.get_body(b).name() for b in (info.bodyA_index(), info.bodyB_index()))
    return names


def test_free_closing_in_simulation_ends_at_the_limits_with_distal_a_third_of_proximal():
    q, status, q_hist, _ = close_hand(ComplianceMode.CYLINDRICAL)
    moving = q_hist[:, 2] < hand.PROXIMAL_LIMITS[1] - math.radians(1)
    # Coupled phase: distal = proximal / 3 within 1 deg on every finger.
    err = q_hist[moving][:, 5:8] - q_hist[moving][:, 2:5] / 3
    assert np.abs(err).max() < math.radians(1.0)
    np.testing.assert_allclose(q[2:5], hand.PROXIMAL_LIMITS[1], atol=math.radians(1))
    np.testing.assert_allclose(q[5:8], hand.DISTAL_LIMITS[1], atol=math.radians(1))
    # The joint limit stops the proximal link, and so the clutch slips there.
    assert np.all(status[:3] == 1.0)


def test_closing_on_a_fixed_cylinder_stops_proximal_links_and_wraps_distal_links():
    # A cylinder along x over the palm, between F1/F2 (-y side) and F3 (+y side), low and wide
    # enough that the proximal links meet it first (on a cylinder resting on the palm the bent
    # distal links touch as early as the proximal ones, and nothing is left to wrap).
    radius, height = 0.06, 0.12
    cylinder = (f"0 0 {height} 0 {math.pi / 2} 0",
                f"<cylinder><radius>{radius}</radius><length>0.3</length></cylinder>")
    q, status, _, touching = close_hand(ComplianceMode.CYLINDRICAL, [cylinder])
    for finger in (1, 2, 3):
        assert {f"bh_finger_{finger}_proximal", f"bh_finger_{finger}_distal"} <= touching
    assert np.all(status[:3] == 1.0), "every proximal link must touch and break away"
    breakaway = status[3:]
    assert np.all(breakaway < hand.PROXIMAL_LIMITS[1] - math.radians(10))
    np.testing.assert_allclose(q[2:5], breakaway, atol=math.radians(2))  # proximal held
    # The distal links wrapped on past the coupled ratio, and stopped on the cylinder, not the limit.
    assert np.all(q[5:8] > breakaway / 3 + math.radians(5))
    assert np.all(q[5:8] < hand.DISTAL_LIMITS[1] - math.radians(2))


def test_on_an_asymmetric_object_the_fingers_stop_at_different_angles():
    # A box offset toward F3: F3 meets it early, F1 and F2 close further.
    box = ("0 0.03 0.13 0 0 0", "<box><size>0.3 0.04 0.06</size></box>")
    q, status, _, _ = close_hand(ComplianceMode.CYLINDRICAL, [box])
    assert q[4] < q[2] - math.radians(10) and q[4] < q[3] - math.radians(10)
    assert abs(q[2] - q[3]) < math.radians(3)  # F1 and F2 are symmetric about the box


def test_preshape_moves_coupled_fingers_to_their_targets_and_back():
    params = HandControllerParams()
    drive = FingerDrive()
    target = np.array([0.3, 0.6, 1.0])
    zero = np.zeros(3)
    for _ in range(300):
        drive = advance_fingers(drive, 0.0, HandAction.PRESHAPE, 0.0, drive.proximal, drive.distal, zero,
                                drive.proximal_rate, drive.distal_rate, params, params.period, preshape=target)
    np.testing.assert_allclose(drive.proximal, target)
    np.testing.assert_allclose(drive.distal, target / 3)
    for _ in range(300):
        drive = advance_fingers(drive, 0.0, HandAction.PRESHAPE, 0.0, drive.proximal, drive.distal, zero,
                                drive.proximal_rate, drive.distal_rate, params, params.period, preshape=zero)
    np.testing.assert_allclose(drive.proximal, 0.0)


def test_a_gentle_close_never_breaks_away_and_stalls_with_its_own_lead():
    params = HandControllerParams()
    drive = FingerDrive()
    for _ in range(40):
        drive = _step(drive, action=HandAction.GENTLE_CLOSE, params=params)
    assert np.all(drive.proximal > 0.1)
    np.testing.assert_allclose(drive.distal, drive.proximal * hand.DISTAL_PER_PROXIMAL)
    # F2 is blocked where it is, and the torque on it is far past the breakaway torque: no breakaway.
    blocked = drive.proximal.copy()
    for _ in range(40):
        drive = _step(drive, action=HandAction.GENTLE_CLOSE, params=params,
                      q_p=[drive.proximal[0], blocked[1], drive.proximal[2]],
                      tau=[0.0, 2.0 * params.breakaway_torque, 0.0])
    assert not drive.broken_away.any()
    # The blocked finger's command leads it by the gentle torque over the PD gain, and no more.
    assert drive.proximal[1] == pytest.approx(blocked[1] + params.gentle_close_torque / params.proximal_gains[0])
    assert drive.proximal[1] - blocked[1] < params.proximal_lead
    assert drive.proximal[0] > drive.proximal[1] + 0.1  # the free fingers close on


def test_a_gentle_close_must_stay_under_the_breakaway_torque():
    with pytest.raises(ValueError, match="gentle_close_torque"):
        HandControllerParams(gentle_close_torque=0.6)


def test_a_gentle_pinch_closes_f1_and_f2_and_leaves_f3_where_it_is():
    """The flower's two-finger pinch: F1 and F2 close as in a gentle close, F3 keeps its command."""
    params = HandControllerParams()
    drive = FingerDrive()
    for _ in range(40):
        drive = _step(drive, action=HandAction.GENTLE_PINCH, params=params)
    assert np.all(drive.proximal[:2] > 0.1) and drive.proximal[2] == 0.0 and drive.distal[2] == 0.0
    np.testing.assert_allclose(drive.distal[:2], drive.proximal[:2] * hand.DISTAL_PER_PROXIMAL)
    gentle = FingerDrive()
    for _ in range(40):
        gentle = _step(gentle, action=HandAction.GENTLE_CLOSE, params=params)
    np.testing.assert_array_equal(drive.proximal[:2], gentle.proximal[:2])
    assert not drive.broken_away.any()



def test_the_lift_squeezes_the_fingers_that_squeeze_harder_and_the_hold_keeps_it():
    """After a gentle close, SQUEEZE raises a blocked finger's lead to the lift's torque; a finger that
    closed on nothing (or F3 left at a pinch's preshape) keeps its command; HOLD then keeps them all."""
    params = HandControllerParams()
    drive = FingerDrive()
    for _ in range(40):
        drive = _step(drive, action=HandAction.GENTLE_CLOSE, params=params)
    blocked = drive.proximal.copy()
    # F1 and F2 are blocked where they are; F3 closes on.
    for _ in range(20):
        drive = _step(drive, action=HandAction.GENTLE_CLOSE, params=params,
                      q_p=[blocked[0], blocked[1], drive.proximal[2]])
    assert drive.proximal[0] == pytest.approx(blocked[0] + params.gentle_proximal_lead)
    # F3 now rests where its command is: it squeezes nothing.
    f3 = drive.proximal[2]
    held = _step(drive, action=HandAction.HOLD, params=params, q_p=[blocked[0], blocked[1], f3])
    np.testing.assert_array_equal(held.proximal, drive.proximal)  # HOLD alone changes nothing
    for _ in range(5):
        drive = _step(drive, action=HandAction.SQUEEZE, params=params, q_p=[blocked[0], blocked[1], f3])
    np.testing.assert_allclose(drive.proximal[:2], blocked[:2] + params.lift_squeeze_lead)
    np.testing.assert_allclose(drive.distal, drive.proximal * hand.DISTAL_PER_PROXIMAL)
    assert drive.proximal[2] == f3
    assert params.lift_squeeze_lead * params.proximal_gains[0] == pytest.approx(params.lift_squeeze_torque)
    assert not drive.broken_away.any()
    # The object gives a little in the hold: the commands stay where the lift left them.
    squeezed = drive.proximal.copy()
    for _ in range(5):
        drive = _step(drive, action=HandAction.HOLD, params=params,
                      q_p=[blocked[0] + 0.01, blocked[1] + 0.01, f3])
    np.testing.assert_array_equal(drive.proximal, squeezed)


def test_the_lift_squeeze_lies_between_the_gentle_close_and_the_breakaway():
    with pytest.raises(ValueError, match="lift_squeeze_torque"):
        HandControllerParams(lift_squeeze_torque=0.5)
    with pytest.raises(ValueError, match="lift_squeeze_torque"):
        HandControllerParams(lift_squeeze_torque=0.2)
