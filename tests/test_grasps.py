"""The compliant grasps' geometry (pure functions of an object estimate) and the trial variation."""

import dataclasses
import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix

from drake_grasp.robot import hand
from drake_grasp import grasps
from drake_grasp.grasps import (
    TABLE_CLEARANCE,
    GraspType,
    ObjectEstimate,
    box_grasp,
    cylindrical_grasp,
    FLOWER_FORCE,
    FLOWER_MARGIN,
    FLOWER_PRESHAPE_RANGE,
    FLOWER_SINK,
    oracle_estimate,
    planned_grasp,
    precision_grasp,
    spherical_grasp,
)
from drake_grasp.robot.hand import ComplianceMode
from drake_grasp.objects import paper_object
from drake_grasp.protocol import TrialProtocol, TrialVariation


def _estimate(center, size, yaw=0.0, axis=None):
    R = RotationMatrix.MakeZRotation(yaw).matrix()
    return ObjectEstimate(np.array(center, float), R, np.array(size, float),
                          None if axis is None else R @ np.asarray(axis, float))


def test_spherical_grasp_comes_down_onto_the_top():
    plan = spherical_grasp(_estimate([0.5, 0.1, 0.1], [0.2, 0.2, 0.2]))
    assert plan.spread == pytest.approx(ComplianceMode.SPHERICAL.spread)
    np.testing.assert_allclose(plan.X_WP_target.translation(), [0.5, 0.1, 0.2])
    np.testing.assert_allclose(plan.X_WP_target.rotation().col(2), [0, 0, -1], atol=1e-12)
    # The pre-grasp pose is straight above, approach_distance back along the palm normal.
    np.testing.assert_allclose(plan.X_WP_pregrasp.translation(), [0.5, 0.1, 0.2 + plan.approach_distance])


def test_cylindrical_grasp_closes_across_the_principal_axis():
    yaw = math.radians(30)
    # Thick enough (25 cm) that the table clearance does not come into it.
    plan = cylindrical_grasp(_estimate([0.5, 0.0, 0.125], [0.35, 0.25, 0.25], yaw=yaw, axis=[1, 0, 0]))
    R = plan.X_WP_target.rotation()
    # Palm x along the axis: F1/F2 and F3 (on -y and +y of the hand) face each other across it.
    np.testing.assert_allclose(R.col(0), [math.cos(yaw), math.sin(yaw), 0], atol=1e-12)
    np.testing.assert_allclose(R.col(2), [0, 0, -1], atol=1e-12)
    np.testing.assert_allclose(plan.X_WP_target.translation(), [0.5, 0.0, 0.25], atol=1e-12)


def test_cylindrical_grasp_of_a_standing_cylinder_comes_from_the_arm_s_side_dipping():
    # A 30 cm cylinder standing 0.5 m out along the world's y from the arm's base (at the origin).
    plan = cylindrical_grasp(_estimate([0.0, 0.5, 0.15], [0.1, 0.1, 0.3], axis=[0, 0, 1]))
    R, p = plan.X_WP_target.rotation(), plan.X_WP_target.translation()
    dip = grasps.UPRIGHT_APPROACH_DIP
    np.testing.assert_allclose(R.col(2), [0, math.cos(dip), -math.sin(dip)], atol=1e-12)  # outward and down
    np.testing.assert_allclose(R.col(0), [0, math.sin(dip), math.cos(dip)], atol=1e-12)  # spread line: up the axis
    # The approach line runs through the axis at UPRIGHT_AIM_HEIGHT of the height; the palm stops
    # UPRIGHT_STANDOFF short of the near side (5 cm from the axis along the level direction, measured
    # along the approach), and the approach starts where one to the near side would.
    aim = np.array([0.0, 0.5, grasps.UPRIGHT_AIM_HEIGHT * 0.3])
    np.testing.assert_allclose(p, aim - (0.05 + grasps.UPRIGHT_STANDOFF) * R.col(2), atol=1e-12)
    np.testing.assert_allclose(plan.X_WP_pregrasp.translation(), aim - (0.05 + 0.12) * R.col(2), atol=1e-12)
    assert grasps.UPRIGHT_STANDOFF > 0.0


def test_box_grasp_stands_off_a_face_wider_than_the_knuckles():
    # Boxes 15 cm tall, so that the table clearance does not come into it.
    narrow = box_grasp(_estimate([0.5, 0, 0.075], [0.11, 0.07, 0.15]))
    np.testing.assert_allclose(narrow.X_WP_target.translation(), [0.5, 0, 0.15])
    wide = box_grasp(_estimate([0.5, 0, 0.075], [0.26, 0.18, 0.15]))
    standoff = wide.X_WP_target.translation()[2] - 0.15
    assert standoff == pytest.approx(0.09 - hand.A1 - (hand.PALM_HEIGHT - hand.DW))
    # Fingers close across the shorter side of the top face: palm x along the longer one.
    np.testing.assert_allclose(np.abs(wide.X_WP_target.rotation().col(0)), [1, 0, 0], atol=1e-12)
    assert wide.grasp == GraspType.BOX and wide.spread == ComplianceMode.CYLINDRICAL.spread


@pytest.mark.parametrize("grasp", [spherical_grasp, cylindrical_grasp, box_grasp])
def test_from_above_the_closing_fingertips_pass_over_the_table(grasp):
    # A low object on the table (top at 3.5 cm): the palm stays high enough that no fingertip
    # reaches the table during a free closing, and only just (the clearance).
    plan = grasp(_estimate([0.5, 0.0, 0.0175], [0.11, 0.07, 0.035], axis=[1, 0, 0]))
    X_WP = plan.X_WP_target
    X_WH = X_WP @ RigidTransform([0, 0, -hand.PALM_HEIGHT])
    corners = [[hand.A3, y, z] for y in (-hand.D3, hand.D3) for z in (-0.0125, 0.0125)]
    lowest = min(
        (X_WH @ hand.distal_points_in_base(f, plan.spread, p, p / 3, corners).T)[2].min()
        for f in (1, 2, 3) for p in np.linspace(0, hand.PROXIMAL_LIMITS[1], 141))
    assert TABLE_CLEARANCE - 1e-6 <= lowest <= TABLE_CLEARANCE + 1e-3


@pytest.mark.parametrize("height, length, across_longer", [
    (0.007, 0.10, True),    # a thin plate: across its longer side
    (0.0085, 0.12, True),
    (0.010, 0.10, False),   # thicker than FLOWER_THIN: across the shorter side
    (0.007, 0.20, False),   # a thin ruler too long for the tips to land outside it
])
def test_a_thin_object_is_closed_across_its_longer_side_where_the_tips_land_outside_it(height, length, across_longer):
    """Below FLOWER_THIN the three-finger flower closes across the longer side (x_P along the shorter),
    and its tips land FLOWER_MARGIN beyond half of that side; where they cannot, the shorter side."""
    yaw = math.radians(20)
    long_W = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    plan = precision_grasp(_estimate([0.5, 0.05, height / 2], [length, 0.06, height], yaw=yaw))
    assert plan.thumb_closes and plan.spread == ComplianceMode.CYLINDRICAL.spread
    x_P = plan.X_WP_target.rotation().col(0)
    closes_across = 0.06 if abs(x_P @ long_W) > 0.99 else length  # x_P runs along the side not closed across
    assert abs(abs(x_P @ long_W) - (0.0 if across_longer else 1.0)) < 1e-9
    assert hand.fingertip_reach(plan.finger_preshape[0]) >= closes_across / 2 + FLOWER_MARGIN - 1e-9 or \
        plan.finger_preshape[0] == pytest.approx(FLOWER_PRESHAPE_RANGE[0])


def _lowest_fingertip(plan):
    X_WH = plan.X_WP_target @ RigidTransform([0, 0, -hand.PALM_HEIGHT])
    corners = [[hand.A3, y, z] for y in (-hand.D3, hand.D3) for z in (-0.0125, 0.0125)]
    return min((X_WH @ hand.distal_points_in_base(f, plan.spread, p, p / 3, corners).T)[2].min()
               for f in (1, 2, 3) for p in np.linspace(0, hand.PROXIMAL_LIMITS[1], 141))


@pytest.mark.parametrize("height, width", [(0.010, 0.06), (0.02, 0.03), (0.012, 0.03)])
def test_the_flower_grasp_lands_the_fingertips_on_the_table_clear_of_the_object(height, width):
    """The preshaped fingertips' deepest point is FLOWER_SINK below the table at the landing target,
    their lowest centimetre lands FLOWER_MARGIN beyond the object's half-width, the palm is above the
    centre with the fingers across the short side, and the arm presses while the hand closes."""
    yaw = math.radians(20)
    plan = precision_grasp(_estimate([0.5, 0.05, height / 2], [0.10, width, height], yaw=yaw))
    assert plan.grasp == GraspType.PRECISION and plan.spread == ComplianceMode.CYLINDRICAL.spread
    assert plan.compliant_arm and plan.palm_force == FLOWER_FORCE
    angle = plan.finger_preshape[0]
    assert plan.finger_preshape == (angle,) * 3 + (angle / 3,) * 3
    assert FLOWER_PRESHAPE_RANGE[0] <= angle <= FLOWER_PRESHAPE_RANGE[1]
    assert hand.fingertip_reach(angle) >= width / 2 + FLOWER_MARGIN - 1e-9
    if angle < FLOWER_PRESHAPE_RANGE[1]:  # the largest such angle: a degree more would land on it
        assert hand.fingertip_reach(angle + math.radians(1)) < width / 2 + FLOWER_MARGIN
    tip_z = plan.X_WP_target.translation()[2] - hand.fingertip_depth(angle)
    assert tip_z == pytest.approx(-FLOWER_SINK, abs=1e-9)  # the table is at z = 0
    np.testing.assert_allclose(plan.X_WP_target.translation()[:2], [0.5, 0.05])
    np.testing.assert_allclose(np.abs(plan.X_WP_target.rotation().col(0) @ [math.cos(yaw), math.sin(yaw), 0]), 1.0)
    np.testing.assert_allclose(plan.X_WP_target.rotation().col(2), [0, 0, -1], atol=1e-12)
    assert GraspType.parse("Precision") == GraspType.PRECISION


def test_the_flower_grasp_lands_outside_the_measured_grip_not_the_footprint_box():
    """A hammer-like footprint 25 × 9 cm whose grip (the handle) reaches 1.3 cm either way where the
    fingers close: the tips land FLOWER_MARGIN outside the handle, not outside half the head's length.
    The reach counts only where it was measured along the fingers' row (GRIP_ALIGNMENT); across it, or
    without one, the box's half extent does."""
    yaw = math.radians(30)
    box = _estimate([0.5, 0.0, 0.0125], [0.25, 0.09, 0.025], yaw=yaw)
    along = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    gripped = dataclasses.replace(box, grip_axis=along, grip_reach=0.013)
    assert gripped.reach_across(along) == pytest.approx(0.013)
    assert gripped.reach_across(-along) == pytest.approx(0.013)
    assert box.reach_across(along) == pytest.approx(0.045)
    wide = dataclasses.replace(box, grip_reach=0.06)  # a reach beyond the box: the box's half extent
    assert dataclasses.replace(wide, grip_axis=along).reach_across(along) == pytest.approx(0.045)
    turned = RotationMatrix.MakeZRotation(math.radians(20)).matrix() @ along
    assert gripped.reach_across(turned) == pytest.approx(box.half_extent_along(np.cross([0, 0, 1], turned)))
    angle = precision_grasp(gripped).finger_preshape[0]
    assert hand.fingertip_reach(angle) >= 0.013 + FLOWER_MARGIN - 1e-9
    assert hand.fingertip_reach(angle + math.radians(1)) < 0.013 + FLOWER_MARGIN
    assert angle > precision_grasp(box).finger_preshape[0] + math.radians(5)  # the tips land nearer
    np.testing.assert_allclose(precision_grasp(gripped).X_WP_target.translation()[:2], [0.5, 0.0])


@pytest.mark.parametrize("size, pinches", [
    ((0.025, 0.025, 0.025), True),  # a 2.5 cm cube: F1 and F2 would pass either side of it
    ((0.01, 0.025, 0.05), True),  # a domino standing on its end
    ((0.034, 0.02, 0.018), True),
    ((0.025, 0.025, 0.015), False),  # too low to pinch: the tips ride over its sides
    ((0.036, 0.025, 0.03), False),  # long enough for the three-finger flower
    ((0.08, 0.05, 0.01), False),  # a plate
    ((0.12, 0.012, 0.012), True),  # a stick lying down: end to end
    ((0.06, 0.012, 0.012), False),  # too short: its ends are met too steeply
    ((0.12, 0.009, 0.009), False),  # its ends too low
    ((0.12, 0.04, 0.012), False),  # not slender: a strip, the three-finger flower
    ((0.12, 0.016, 0.016), False),  # thick enough for the flower across, whose funnel is wider
])
def test_the_flower_grasp_pinches_small_objects_and_sticks(size, pinches):
    """On a footprint shorter than PINCH_MAX_LENGTH with sides at least PINCH_MIN_HEIGHT tall, F1 and F2
    at a 90 deg spread face each other across its short side and F3 stays open; on a slender stick lying
    down, at its ends; else the three-finger flower grasp. The pinching tips land FLOWER_MARGIN clear of
    the sides (or ends), FLOWER_SINK below the table."""
    yaw = math.radians(-30)
    plan = precision_grasp(_estimate([0.5, 0.0, size[2] / 2], size, yaw=yaw))
    assert (grasps.flower_pinch_axis(_estimate([0.5, 0.0, size[2] / 2], size, yaw=yaw)) is not None) == pinches
    assert plan.grasp == GraspType.PRECISION and plan.compliant_arm and not plan.breakaway
    if not pinches:
        assert plan.spread == ComplianceMode.CYLINDRICAL.spread and plan.thumb_closes
        return
    assert plan.spread == grasps.PINCH_SPREAD and not plan.thumb_closes
    angle = plan.finger_preshape[0]
    assert plan.finger_preshape == pytest.approx((angle, angle, 0.0, angle / 3, angle / 3, 0.0))
    estimate = _estimate([0.5, 0.0, size[2] / 2], size, yaw=yaw)
    short = max(size[:2]) if max(size[:2]) >= 0.08 else min(size[:2])  # a stick end to end, else across
    assert estimate.half_extent_along(plan.X_WP_target.rotation().col(0)) == pytest.approx(short / 2)
    assert hand.fingertip_reach(angle, grasps.PINCH_SPREAD, fingers=(1, 2)) >= short / 2 + FLOWER_MARGIN - 1e-9
    assert hand.fingertip_reach(angle + math.radians(1), grasps.PINCH_SPREAD, fingers=(1, 2)) < short / 2 + FLOWER_MARGIN
    tip_z = plan.X_WP_target.translation()[2] - hand.fingertip_depth(angle, grasps.PINCH_SPREAD)
    assert tip_z == pytest.approx(-FLOWER_SINK, abs=1e-9)


def test_at_a_90_degree_spread_f1_and_f2_close_on_one_line_through_the_palm_centre():
    for spread, directions in ((0.0, {1: (0, -1), 2: (0, -1), 3: (0, 1)}),
                               (math.pi / 2, {1: (-1, 0), 2: (1, 0), 3: (0, 1)})):
        for finger, direction in directions.items():
            np.testing.assert_allclose(hand.closing_direction(finger, spread), direction, atol=1e-12)
    # At the cylindrical spread the reach is across the palm's y, as the flower grasp has always used.
    points = hand.closing_distal_points(math.radians(70))
    low = [p[p[:, 2] > p[:, 2].max() - 0.01] for p in points]
    assert hand.fingertip_reach(math.radians(70)) == pytest.approx(min(np.abs(p[:, 1]).min() for p in low))


def test_the_fingertips_depth_and_reach_follow_the_coupled_closing():
    """Closing past about 60 deg the tips rise and come nearer the closing plane (what the flower
    grasp's palm follows down)."""
    angles = np.radians([60, 70, 80, 90])
    depths = [hand.fingertip_depth(a) for a in angles]
    reaches = [hand.fingertip_reach(a) for a in angles]
    assert all(a > b for a, b in zip(depths, depths[1:])) and all(a > b for a, b in zip(reaches, reaches[1:]))
    assert 0.09 < depths[0] < 0.11  # the tips reach about 10 cm beyond the palm


@pytest.mark.parametrize("grasp", [spherical_grasp, box_grasp, precision_grasp])
def test_a_known_table_height_places_the_sweep_whatever_the_estimated_bottom(grasp):
    """Where the table's height is known (the table-top estimate's reference plane), the fingertips'
    sweep is placed from it, not from the estimate's bottom: an estimate 3 mm too low and too tall
    (the apple's, with the table-top estimate) places the palm as the true one does."""
    true = _estimate([0.5, 0.0, 0.0175], [0.11, 0.07, 0.035], axis=[1, 0, 0])
    low = _estimate([0.5, 0.0, 0.0165], [0.11, 0.07, 0.039], axis=[1, 0, 0])
    assert low.table_height == pytest.approx(true.table_height - 0.003)
    known = ObjectEstimate(low.center, low.R_WB, low.size, low.principal_axis, table_z=0.0)
    assert known.table_height == 0.0
    np.testing.assert_allclose(grasp(known).X_WP_target.translation(), grasp(true).X_WP_target.translation(),
                               atol=1e-12)
    assert grasp(low).X_WP_target.translation()[2] == pytest.approx(
        grasp(true).X_WP_target.translation()[2] - 0.003)


def test_oracle_estimate_is_the_ground_truth():
    spec = paper_object("bottle_case")
    X_WO = RigidTransform(RollPitchYaw(0, 0, 0.3), [0.5, 0.1, spec.rest_height])
    est = oracle_estimate(X_WO, spec)
    np.testing.assert_allclose(est.center, X_WO.translation())
    np.testing.assert_allclose(est.principal_axis, X_WO.rotation() @ np.asarray(spec.principal_axis))
    assert est.half_extent_along([0, 0, 1]) == pytest.approx(0.05)


def test_estimates_reject_nonsense():
    with pytest.raises(ValueError, match="non-finite"):
        ObjectEstimate(np.array([np.nan, 0, 0]), np.eye(3), np.ones(3))
    with pytest.raises(ValueError, match="positive"):
        ObjectEstimate(np.zeros(3), np.eye(3), np.array([0.1, 0.0, 0.1]))


def test_planned_grasp_puts_the_palm_where_the_planner_put_the_hand():
    X_WO = RigidTransform(RollPitchYaw(0, 0, 0.5), [0.6, 0.0, 0.1])
    X_OH = RigidTransform(RollPitchYaw(math.pi, 0, 0), [0.0, 0.0, 0.2])
    q = np.array([0.3, 0.3, 0.1, 0.2, 0.3, 0.05, 0.06, 0.07])
    plan = planned_grasp(X_OH, q, X_WO)
    X_WP = X_WO @ X_OH @ RigidTransform([0, 0, hand.PALM_HEIGHT])
    assert plan.X_WP_target.IsNearlyEqualTo(X_WP, 1e-12)
    assert plan.spread == pytest.approx(0.3)
    assert plan.finger_preshape == pytest.approx((0.1, 0.2, 0.3, 0.05, 0.06, 0.07))
    assert not plan.stop_on_contact


def test_trial_variation_is_seeded_and_bounded():
    protocol = TrialProtocol()
    a, b = TrialVariation.draw(7, protocol), TrialVariation.draw(7, protocol)
    assert a == b
    assert a != TrialVariation.draw(8, protocol)
    draws = [TrialVariation.draw(s, protocol) for s in range(200)]
    assert max(abs(d.dx) for d in draws) <= 0.01 and max(abs(d.dy) for d in draws) <= 0.01
    assert max(abs(d.dyaw) for d in draws) <= math.radians(10)
    assert all(0.8 <= d.friction_scale <= 1.2 for d in draws)


@pytest.mark.parametrize("grasp, turns", [("spherical", (2 * np.pi / 3, -2 * np.pi / 3)), ("box", (np.pi,)),
                                          ("cylindrical", (np.pi,))])
def test_each_compliant_grasp_knows_its_near_symmetric_equivalents(grasp, turns):
    """The grasp itself first, then its turns about the approach (thirds for the spherical grasp's three
    fingers, a half-turn for the two-sided grasps): the palm centre, the approach and the spread stay,
    only the fingers' directions turn."""
    from drake_grasp.grasps import near_symmetric_plans, plan_compliant_grasp

    plan = plan_compliant_grasp(grasp, _estimate([0.55, 0.02, 0.05], [0.12, 0.06, 0.1], axis=[1, 0, 0]))
    plans = near_symmetric_plans(plan)
    assert plans[0] == (0.0, plan)
    assert sorted(t for t, _ in plans[1:]) == pytest.approx(sorted(turns))
    for turn, other in plans[1:]:
        X, Y = plan.X_WP_target, other.X_WP_target
        np.testing.assert_allclose(Y.translation(), X.translation(), atol=1e-12)
        np.testing.assert_allclose(Y.rotation().col(2), X.rotation().col(2), atol=1e-12)
        x_turned = np.cos(turn) * X.rotation().col(0) + np.sin(turn) * X.rotation().col(1)
        np.testing.assert_allclose(Y.rotation().col(0), x_turned, atol=1e-12)
        assert other.spread == plan.spread and other.grasp == plan.grasp


def test_a_planners_grasp_has_no_near_symmetric_equivalent():
    from drake_grasp.grasps import GraspPlan, near_symmetric_plans

    plan = GraspPlan(None, 0.3, RigidTransform([0.5, 0.0, 0.3]))
    assert near_symmetric_plans(plan) == [(0.0, plan)]


def test_only_a_gentle_close_leaves_the_thumb_open():
    from drake_grasp.grasps import GraspPlan

    with pytest.raises(ValueError, match="gentle close"):
        GraspPlan(GraspType.PRECISION, grasps.PINCH_SPREAD, RigidTransform(), thumb_closes=False)
    assert not GraspPlan(GraspType.PRECISION, grasps.PINCH_SPREAD, RigidTransform(), breakaway=False,
                         thumb_closes=False).thumb_closes
