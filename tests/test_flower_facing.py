"""Which way the flower grasp faces (`flower_facing`, `funnel.planning.facing_the_footprint`)."""

import math

import numpy as np
import pytest
from pydrake.math import RotationMatrix

from drake_grasp.flower_facing import HALF_TURN, faces_fuller_side, support_gaps, thumb_to_the_right
from drake_grasp.funnel.planning import facing_the_footprint
from drake_grasp.grasps import GraspType, ObjectEstimate, box_grasp, precision_grasp
from drake_grasp.primitives.table_top import HeightMap
from drake_grasp.robot import hand

DOWN_X = RotationMatrix(np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]))  # z_P down, x_P along +x


def _thumb(R: RotationMatrix) -> np.ndarray:
    return np.array(R.col(1))[:2]  # F3 sits on the palm's +y (a copy: col() views the temporary)


def _grid(xmin, xmax, ymin, ymax, step=0.003):
    xs, ys = np.meshgrid(np.arange(xmin, xmax + 1e-9, step), np.arange(ymin, ymax + 1e-9, step))
    return np.column_stack([xs.ravel(), ys.ravel()])


def _l_footprint():
    """An L: a 9 x 2 cm bar along x at y in [-4.5, -2.5] cm, and a 2 x 7 cm arm up its left end."""
    return np.vstack([_grid(-0.045, 0.045, -0.045, -0.025), _grid(-0.045, -0.025, -0.025, 0.045)])


@pytest.mark.parametrize("reach", [(1.0, 0.0), (0.0, 1.0), (-0.6, 0.8)])
@pytest.mark.parametrize("turn", [0.0, math.pi])
def test_thumb_goes_to_the_right_of_the_reach(reach, turn):
    for yaw in (0.0, 0.3, 1.2, 2.5):
        R = DOWN_X @ RotationMatrix.MakeZRotation(turn + yaw)
        thumb = _thumb(thumb_to_the_right(R, np.array(reach)))
        right = np.array([reach[1], -reach[0]])
        assert thumb @ right == pytest.approx(abs(_thumb(R) @ right))  # the sign that puts it right


def test_a_rectangle_gives_no_gap_on_either_side():
    footprint = _grid(-0.03, 0.03, -0.015, 0.015)
    for R in (DOWN_X, DOWN_X @ HALF_TURN):
        f12, f3 = support_gaps(R, np.zeros(2), footprint)
        assert f12 < 0.004 and f3 < 0.004


def test_the_l_shows_its_notch_to_the_fingers_facing_it():
    # DOWN_X's +y_P is the world's -y: F3 faces the bar (y < 0), F1 and F2 the arm's side, where only
    # the arm (x < -2.5 cm) reaches the top: F2's line at x = +AW meets the bar 7 cm in.
    f12, f3 = support_gaps(DOWN_X, np.zeros(2), _l_footprint())
    assert f12 == pytest.approx(0.07, abs=0.004) and f3 < 0.004
    f12_turned, f3_turned = support_gaps(DOWN_X @ HALF_TURN, np.zeros(2), _l_footprint())
    assert f12_turned < 0.004 and f3_turned == pytest.approx(0.07, abs=0.004)


@pytest.mark.parametrize("turn", [0.0, math.pi])
def test_f1_and_f2_go_to_the_fuller_side_whatever_the_reach(turn):
    for reach in ((1.0, 0.0), (-1.0, 0.0)):
        R = faces_fuller_side(DOWN_X @ RotationMatrix.MakeZRotation(turn), np.zeros(2), _l_footprint(), np.array(reach))
        assert support_gaps(R, np.zeros(2), _l_footprint())[0] < 0.004  # F1 and F2 on the bar


def test_alike_sides_fall_back_to_the_thumb_on_the_right():
    footprint = _grid(-0.025, 0.025, -0.012, 0.012)
    R = faces_fuller_side(DOWN_X @ HALF_TURN, np.zeros(2), footprint, np.array([1.0, 0.0]))
    assert _thumb(R) @ np.array([0.0, -1.0]) > 0.99


def test_no_footprint_under_any_finger_falls_back_too():
    R = faces_fuller_side(DOWN_X @ HALF_TURN, np.zeros(2), np.array([[0.3, 0.3]]), np.array([1.0, 0.0]))
    assert _thumb(R) @ np.array([0.0, -1.0]) > 0.99


@pytest.mark.parametrize("axis_sign", [1.0, -1.0])
def test_the_flower_grasp_puts_f3_to_the_right_whatever_sign_the_estimate_s_axis_has(axis_sign):
    # A lying domino 55 cm out along the world's x: its axes carry no sign (a rectangle's side is a line).
    yaw = math.radians(8.0)
    a = axis_sign * np.array([math.cos(yaw), math.sin(yaw), 0.0])
    R_WB = np.column_stack([a, np.cross([0.0, 0.0, 1.0], a), [0.0, 0.0, 1.0]])
    estimate = ObjectEstimate(center=np.array([0.55, 0.0, 0.005]), R_WB=R_WB, size=np.array([0.05, 0.025, 0.01]),
                              table_z=0.0)
    plan = precision_grasp(estimate)
    assert plan.thumb_closes
    assert _thumb(plan.X_WP_target.rotation()) @ np.array([0.0, -1.0]) > 0.95


@pytest.mark.parametrize("yaw_deg", [0.0, 40.0, 90.0, 130.0])
def test_the_flower_grasp_closes_across_the_reach_on_a_near_square_footprint(yaw_deg):
    # A 7 cm ring seen by the camera: its footprint's axes are any pair; whichever the estimate calls
    # its longer side, F3 goes to the right of the reach, F1 and F2 to the left (the fingers close
    # across the reach, not along it).
    yaw = math.radians(yaw_deg)
    a = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    R_WB = np.column_stack([a, np.cross([0.0, 0.0, 1.0], a), [0.0, 0.0, 1.0]])
    for size in ([0.071, 0.070, 0.021], [0.070, 0.071, 0.021]):
        estimate = ObjectEstimate(center=np.array([0.55, 0.0, 0.0105]), R_WB=R_WB, size=np.array(size), table_z=0.0)
        plan = precision_grasp(estimate)
        assert plan.thumb_closes
        assert _thumb(plan.X_WP_target.rotation()) @ np.array([0.0, -1.0]) > math.cos(math.radians(46.0))
    # An elongated footprint still closes across its shorter side, wherever it points, and so does one
    # only 18 % longer than wide (a blob 11.1 x 9.4 cm: across its longer side it was missed).
    for size in ([0.10, 0.05, 0.01], [0.111, 0.094, 0.094]):
        estimate = ObjectEstimate(center=np.array([0.55, 0.0, size[2] / 2]), R_WB=R_WB, size=np.array(size),
                                  table_z=0.0)
        assert abs(np.array(precision_grasp(estimate).X_WP_target.rotation().col(0)) @ a) > 0.99


@pytest.mark.parametrize("axis_sign", [1.0, -1.0])
@pytest.mark.parametrize("size", [(0.022, 0.022, 0.022), (0.12, 0.012, 0.012)])
def test_the_pinch_leaves_the_open_f3_to_the_right_too(axis_sign, size):
    # A 2.2 cm cube (pinched along the reach) and a 1.2 cm stick (pinched end to end).
    yaw = math.radians(-9.0)
    a = axis_sign * np.array([math.cos(yaw), math.sin(yaw), 0.0])
    R_WB = np.column_stack([a, np.cross([0.0, 0.0, 1.0], a), [0.0, 0.0, 1.0]])
    estimate = ObjectEstimate(center=np.array([0.55, 0.0, size[2] / 2]), R_WB=R_WB, size=np.array(size), table_z=0.0)
    plan = precision_grasp(estimate)
    assert not plan.thumb_closes
    assert _thumb(plan.X_WP_target.rotation()) @ np.array([0.0, -1.0]) > 0.95


def _height_map(footprint_xy, centre=(0.55, 0.0), height=0.02):
    hmap = HeightMap.around(np.array(centre), 0.003, 64)
    points = np.column_stack([footprint_xy + np.array(centre), np.full(len(footprint_xy), height)])
    hmap.add(points)
    return hmap


def test_the_executed_flower_grasp_faces_the_footprint_the_camera_saw():
    # The L's estimate: its 9 x 9 cm box, axes along the world's. Planned alone, F3 goes right (-y),
    # onto the bar, and F2 faces the notch; the height map turns it.
    estimate = ObjectEstimate(center=np.array([0.55, 0.0, 0.01]), R_WB=np.eye(3), size=np.array([0.09, 0.088, 0.02]),
                              table_z=0.0)
    plan = precision_grasp(estimate)
    assert _thumb(plan.X_WP_target.rotation()) @ np.array([0.0, -1.0]) > 0.99
    faced = facing_the_footprint(plan, _height_map(_l_footprint()))
    R = faced.X_WP_target.rotation()
    assert _thumb(R) @ np.array([0.0, 1.0]) > 0.99  # F3 into the notch, F1 and F2 on the bar
    np.testing.assert_allclose(faced.X_WP_target.translation(), plan.X_WP_target.translation())
    assert faced.finger_preshape == plan.finger_preshape


def test_facing_leaves_every_other_plan_alone():
    estimate = ObjectEstimate(center=np.array([0.55, 0.0, 0.04]), R_WB=np.eye(3), size=np.array([0.09, 0.088, 0.08]),
                              table_z=0.0)
    plan = box_grasp(estimate)
    assert plan.grasp is GraspType.BOX
    assert facing_the_footprint(plan, _height_map(_l_footprint())) is plan
    flower = precision_grasp(estimate)
    assert facing_the_footprint(flower, None) is flower
    assert hand.AW == pytest.approx(0.025)  # the fingers' lines the gaps are measured on
