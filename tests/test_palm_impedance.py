"""The palm's impedance law (control.palm_impedance) on the real station: its force against a fixed
contact, its stiffness from a displacement, and the hand-over from the joint PD and back."""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.analysis import Simulator

from drake_grasp.control.arm_motion import ArmKinematics
from drake_grasp.control.palm_impedance import PalmImpedanceParams, palm_wrench, rotation_error
from drake_grasp.robot import arm
from drake_grasp.station import MakeStation, load_scenario

# A palm facing down, away from the object (the station's object rests at x = 0.55, y = 0).
_PALM_DOWN = RotationMatrix(np.diag([1.0, -1.0, -1.0]))


def _station_at(height: float):
    """The station (no camera) with the palm facing down `height` m above the table at (0.5, 0.3)."""
    scenario = load_scenario()
    station = MakeStation(scenario, camera=False)
    kinematics = ArmKinematics(station.plant, station.wam)
    X_WP = RigidTransform(_PALM_DOWN, [0.5, 0.3, height])
    q = kinematics.solve(X_WP, np.asarray(scenario.protocol.start_configuration, float))
    simulator = Simulator(station.diagram)
    context = simulator.get_mutable_context()
    station.plant.SetPositions(station.plant.GetMyMutableContextFromRoot(context), station.wam, q)
    diagram = station.diagram
    diagram.GetInputPort("wam.desired_state").FixValue(context, np.concatenate([q, np.zeros(7)]))
    diagram.GetInputPort("hand.command").FixValue(context, [0.0, 0.0])
    return station, simulator, kinematics, q


def _palm(station, context) -> RigidTransform:
    plant = station.plant
    return plant.GetFrameByName("bh_palm").CalcPoseInWorld(plant.GetMyContextFromRoot(context))


def _activate(station, context, X_WPd, force, stiffness=None):
    diagram = station.diagram
    diagram.GetInputPort("wam.arm_mode").FixValue(context, [1.0])
    diagram.GetInputPort("wam.palm_target").FixValue(context, X_WPd)
    diagram.GetInputPort("wam.palm_force").FixValue(context, [force])
    if stiffness is not None:
        diagram.GetInputPort("wam.palm_stiffness").FixValue(context, stiffness)


def test_the_wrench_law_is_the_spring_the_damper_and_the_force_in_the_palm_frame():
    X_WP = RigidTransform(_PALM_DOWN, [0.5, 0.0, 0.2])
    X_WPd = RigidTransform(_PALM_DOWN, [0.5, 0.01, 0.2])  # 1 cm along world y = -y_P
    k = np.array([10.0, 10.0, 10.0, 100.0, 200.0, 300.0])
    F = palm_wrench(X_WP, np.zeros(6), X_WPd, k, np.zeros(6), normal_force=5.0)
    np.testing.assert_allclose(F[:3], 0.0, atol=1e-12)
    # 200 N/m * 1 cm along world +y, and 5 N along z_P (world -z).
    np.testing.assert_allclose(F[3:], [0.0, 2.0, -5.0], atol=1e-9)
    turned = RotationMatrix.MakeZRotation(0.1) @ _PALM_DOWN
    np.testing.assert_allclose(rotation_error(_PALM_DOWN, turned), [0.0, 0.0, -0.1], atol=1e-12)


def test_bad_gains_are_refused_in_one_line():
    with pytest.raises(ValueError, match="stiffness needs 6"):
        PalmImpedanceParams(stiffness=[1.0] * 5).validate()
    with pytest.raises(ValueError, match="nullspace_damping"):
        PalmImpedanceParams(nullspace_damping=-1.0).validate()


def test_a_commanded_force_is_held_against_the_table_within_ten_percent():
    station, simulator, _, q = _station_at(0.06)
    context = simulator.get_mutable_context()
    X_WP0 = _palm(station, context)
    force = 12.0
    # Pure force along the normal (no stiffness along it): the palm descends onto the table and presses.
    stiffness = list(station.scenario.arm.impedance().stiffness)
    stiffness[5] = 0.0
    _activate(station, context, X_WP0, force, stiffness)
    simulator.AdvanceTo(1.5)
    results = station.diagram.GetOutputPort("contact_results").Eval(context)
    plant = station.plant
    table = {int(b) for b in plant.GetBodyIndices(plant.GetModelInstanceByName("table"))}
    robot = {int(b) for b in plant.GetBodyIndices(station.wam) + plant.GetBodyIndices(station.hand)}
    inspector = station.scene_graph.model_inspector()
    on_table = np.zeros(3)
    for i in range(results.num_hydroelastic_contacts()):
        info = results.hydroelastic_contact_info(i)
        surface = info.contact_surface()
        body_m = int(plant.GetBodyFromFrameId(inspector.GetFrameId(surface.id_M())).index())
        body_n = int(plant.GetBodyFromFrameId(inspector.GetFrameId(surface.id_N())).index())
        f = info.F_Ac_W().translational()  # on M
        if {body_m, body_n} & robot:
            on_table += f if body_m in table else (-f if body_n in table else 0.0)
    for i in range(results.num_point_pair_contacts()):
        info = results.point_pair_contact_info(i)
        a, b = int(info.bodyA_index()), int(info.bodyB_index())
        if {a, b} & robot:
            on_table += info.contact_force() if b in table else (-info.contact_force() if a in table else 0.0)
    assert _palm(station, context).translation()[2] < X_WP0.translation()[2] - 0.01  # it went down
    assert on_table[2] == pytest.approx(-force, rel=0.10), on_table  # the robot's push on the table only


def test_the_stiffness_along_the_normal_is_measured_from_a_displacement_within_ten_percent():
    station, simulator, _, q = _station_at(0.25)
    context = simulator.get_mutable_context()
    X_WP0 = _palm(station, context)
    k_z = station.scenario.arm.impedance().stiffness[5]
    displacements = []
    for force in (4.0, 10.0):
        _activate(station, context, X_WP0, force)
        simulator.AdvanceTo(context.get_time() + 1.5)
        displacements.append(float(X_WP0.translation()[2] - _palm(station, context).translation()[2]))
    measured = (10.0 - 4.0) / (displacements[1] - displacements[0])
    assert measured == pytest.approx(k_z, rel=0.10), displacements


def test_the_joint_pd_hands_over_and_takes_back_without_a_jump():
    station, simulator, kinematics, q = _station_at(0.15)
    context = simulator.get_mutable_context()
    simulator.AdvanceTo(0.3)
    X_WP0 = _palm(station, context)
    _activate(station, context, X_WP0, 0.0)
    path = []
    while context.get_time() < 1.0:
        simulator.AdvanceTo(context.get_time() + 0.02)
        path.append(_palm(station, context).translation())
        tau = station.diagram.GetSubsystemByName("wam_palm_impedance").GetOutputPort("wam.actuation").Eval(
            station.diagram.GetSubsystemContext(station.diagram.GetSubsystemByName("wam_palm_impedance"), context))
        assert np.all(np.abs(tau) <= arm.EFFORT_LIMITS)
    assert np.max(np.linalg.norm(np.array(path) - X_WP0.translation(), axis=1)) < 0.002
    # The elbow (null space) holds too.
    q_now = station.plant.GetPositions(station.plant.GetMyContextFromRoot(context), station.wam)
    assert np.abs(q_now - q).max() < math.radians(2.0)
    # Back to the joint PD at the measured configuration.
    station.diagram.GetInputPort("wam.desired_state").FixValue(context, np.concatenate([q_now, np.zeros(7)]))
    station.diagram.GetInputPort("wam.arm_mode").FixValue(context, [0.0])
    X_WP1 = _palm(station, context)
    simulator.AdvanceTo(context.get_time() + 0.5)
    assert np.linalg.norm(_palm(station, context).translation() - X_WP1.translation()) < 0.002


def test_a_scenario_sets_the_gains_and_a_bad_one_is_a_one_line_error(tmp_path):
    path = tmp_path / "s.yaml"
    path.write_text("soft:\n  arm: {palm_impedance: {stiffness: [5, 5, 5, 200, 200, 100]}}\n"
                    "bad:\n  arm: {palm_impedance: {damping: [1, 1, 1, 1, 1, -1]}}\n")
    assert load_scenario(path, "soft").arm.impedance().stiffness[3] == 200.0
    with pytest.raises(ValueError, match="arm.palm_impedance.damping") as e:
        load_scenario(path, "bad")
    assert "\n" not in str(e.value)
