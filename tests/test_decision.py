"""The decision rule (primitives.decision): flatness decides first, then the paper's argmax."""

import dataclasses
import math

import pytest

from drake_grasp.primitives.decision import FLAT_THRESHOLD, choose_shape, decision_margin
from drake_grasp.studies.fig6 import GraspStats, chosen_grasp


def test_without_a_flat_resemblance_the_paper_argmax_and_its_lead():
    res = {"sphere": 0.2, "cylinder": 0.7, "box": 0.6}
    assert choose_shape(res) == "cylinder"
    assert decision_margin(res) == pytest.approx(0.1)
    assert choose_shape({}) is None and math.isnan(decision_margin({}))


def test_flatness_overrides_a_saturated_box_resemblance():
    # A plate: its silhouette's area changes most of all under the arcs (box 1.0), but it is 8 mm thin.
    res = {"sphere": 0.0, "cylinder": 0.1, "box": 1.0, "flat": 0.9}
    assert choose_shape(res) == "flat"
    assert decision_margin(res) == pytest.approx(0.8)


def test_below_its_threshold_flatness_leaves_the_argmax_but_bounds_its_margin():
    res = {"sphere": 0.0, "cylinder": 0.1, "box": 1.0, "flat": FLAT_THRESHOLD - 0.05}
    assert choose_shape(res) == "box"
    assert decision_margin(res) == pytest.approx(0.1)  # 2 |flat - 1/2|, not the box's lead of 0.9
    res["flat"] = 0.0
    assert decision_margin(res) == pytest.approx(0.9)


def test_a_nan_flat_resemblance_leaves_the_argmax_and_makes_the_margin_unknown():
    res = {"sphere": 0.9, "cylinder": 0.1, "box": 0.2, "flat": math.nan}
    assert choose_shape(res) == "sphere"
    assert math.isnan(decision_margin(res))


def test_fig6_chooses_by_the_same_rule_on_mean_resemblances():
    stats = {"spherical": GraspStats(2, 0, 0.1), "cylindrical": GraspStats(2, 0, 0.2), "box": GraspStats(2, 1, 1.0),
             "precision": GraspStats(2, 2, 0.7)}
    assert chosen_grasp(stats) == "precision"
    stats["precision"] = GraspStats(2, 2, 0.3)
    assert chosen_grasp(stats) == "box"


def test_a_standing_bottle_is_upright_and_takes_the_box_grasp_then_the_wrap_after_flatness():
    from drake_grasp.grasps import GRASP_OF_SHAPE
    from drake_grasp.primitives.upright import upright_resemblance

    bottle = upright_resemblance(0.20, [0.07, 0.07])  # 20 cm tall, 7 cm across
    mug = upright_resemblance(0.09, [0.09, 0.08])
    carton = upright_resemblance(0.25, [0.15, 0.06])  # standing, but wider than the hand wraps
    assert bottle > 0.99 and mug < 0.01 and carton < 0.01
    assert math.isnan(upright_resemblance(math.nan, [0.07, 0.07]))
    res = {"sphere": 0.0, "cylinder": 0.0, "box": 1.0, "flat": 0.0, "upright": bottle}
    assert choose_shape(res) == "upright" and GRASP_OF_SHAPE["upright"] == "box"
    assert decision_margin(res) == pytest.approx(min(1.0, 2 * (bottle - 0.5)))
    assert choose_shape({**res, "flat": 0.9}) == "flat"  # a small flat object stays the flower's
    assert choose_shape(res, exclude=("upright",)) == "box"  # both upright grasps failed: the argmax's


def test_a_slender_standing_object_takes_the_flower_grasp_before_the_upright_one():
    from drake_grasp.grasps import GRASP_OF_SHAPE
    from drake_grasp.primitives.upright import slender_resemblance, upright_resemblance

    peg = (0.08, [0.0195, 0.0195])  # Gazebo's wooden peg: 8 cm tall, 1.95 cm across
    marker = (0.12, [0.026, 0.026])
    bottle = (0.20, [0.07, 0.07])
    domino = (0.03, [0.025, 0.01])  # standing, but not 1.8 times as tall as its footprint's larger side
    assert slender_resemblance(*peg) > 0.99 and slender_resemblance(*marker) > 0.99
    assert slender_resemblance(*bottle) < 0.01 and slender_resemblance(*domino) < 0.01
    assert slender_resemblance(0.12, [0.04, 0.04]) < 0.01  # the cylindrical grasp's F1 and F2 reach it
    sauce_bottle = (0.092, [0.028, 0.045])  # Dex-Net's KIT sauce bottle: thin one way only
    assert upright_resemblance(*sauce_bottle) > 0.9 and slender_resemblance(*sauce_bottle) > 0.9
    assert slender_resemblance(*sauce_bottle) == slender_resemblance(0.092, [0.045, 0.028])  # either order
    assert slender_resemblance(0.15, [0.04, 0.06]) < 0.01  # 4 cm thin: the wrap holds it
    assert slender_resemblance(0.30, [0.02, 0.14]) < 0.01  # a tray on edge: not upright (wider than the wrap)
    assert math.isnan(slender_resemblance(0.08, [math.nan, 0.02]))
    res = {"sphere": 0.0, "cylinder": 0.9, "box": 0.1, "flat": 0.19, "upright": upright_resemblance(*peg),
           "slender": slender_resemblance(*peg)}
    assert res["upright"] > 0.99  # upright, yet too thin for the cylindrical grasp round it
    assert choose_shape(res) == "flat" and GRASP_OF_SHAPE["flat"] == "precision"
    assert decision_margin(res) == pytest.approx(min(2 * (0.5 - 0.19), 2 * (res["slender"] - 0.5)))
    assert choose_shape(res, exclude=("flat",)) == "upright"  # the flower grasp failed: the upright one next
    no_slender = {k: v for k, v in res.items() if k != "slender"}
    assert choose_shape(no_slender) == "upright"  # an estimate without it (older records) as before


def test_a_low_round_object_takes_the_flower_grasp_where_the_sphere_leads():
    from drake_grasp.grasps import GRASP_OF_SHAPE
    from drake_grasp.primitives.decision import choose_with_funnels
    from drake_grasp.primitives.low import LOW_HEIGHT, low_resemblance

    apple, ball = low_resemblance(0.072), low_resemblance(0.22)  # a 7.2 cm apple, a 22 cm football
    assert apple > 0.99 and ball < 0.01 and math.isnan(low_resemblance(math.nan))
    assert low_resemblance(LOW_HEIGHT) == pytest.approx(0.5)
    res = {"sphere": 0.9, "cylinder": 0.1, "box": 0.5, "flat": 0.1, "upright": 0.0, "low": apple}
    assert choose_shape(res) == "flat" and GRASP_OF_SHAPE["flat"] == "precision"
    assert choose_shape({**res, "low": ball}) == "sphere"
    # Only the sphere's choice turns: a low box stays the box grasp's.
    assert choose_shape({**res, "sphere": 0.2}) == "box"
    # The flower grasp used up: the paper's sphere again.
    assert choose_shape(res, exclude=("flat",)) == "sphere"
    # The funnel's veto of another grasp can leave the sphere, which then turns too.
    assert choose_with_funnels({**res, "sphere": 0.4}, {"sphere": False, "cylinder": True, "box": True}) == "flat"
    # The margin: the lead (0.4), bounded by the low resemblance's distance from its threshold.
    near = {**res, "low": 0.6}
    assert choose_shape(near) == "flat" and decision_margin(near) == pytest.approx(0.2)
    assert decision_margin({**res, "low": 1.0}) == pytest.approx(0.4)


def test_the_seam_executes_the_flower_grasp_for_a_low_ball_and_the_spherical_one_for_a_tall_ball():
    """`funnel.planning.choose_grasp`, the one owner of the decision, on a camera's estimate of a ball
    with the table-top resemblances: 8 cm tall, the flower grasp; 20 cm, the paper's spherical grasp."""
    import numpy as np

    from drake_grasp.funnel.planning import choose_grasp
    from drake_grasp.primitives.estimate import ObjectEstimate
    from drake_grasp.primitives.low import low_resemblance

    for diameter, executed in ((0.08, "precision"), (0.20, "spherical")):
        estimate = ObjectEstimate(
            status="ok", centre=np.array([0.55, 0.0, diameter / 2]), depth=0.35,
            camera_position=np.array([0.55, 0.0, 0.45]), axes=np.eye(3), extents=np.full(3, diameter),
            principal_axis=None, resemblances={"sphere": 0.9, "cylinder": 0.1, "box": 0.4, "flat": 0.0,
                                               "upright": 0.0, "low": low_resemblance(diameter)})
        choice = choose_grasp(estimate, estimate.as_grasp_estimate())
        assert choice.chosen == choice.executed == executed
        assert choice.plan.grasp.value == executed


def test_the_seam_tries_a_standing_bottle_from_above_then_wraps_it_from_the_arms_side():
    """An upright object's grasps in order (docs/design.md §5.4q): the box grasp from above, its palm
    level over the top; after it failed, the cylindrical wrap from the arm's side, dipping 45°; after
    both, the paper's argmax without them (the sphere here)."""
    import numpy as np

    from drake_grasp.funnel.planning import choose_grasp, grasp_of
    from drake_grasp.primitives.estimate import ObjectEstimate
    from drake_grasp.primitives.upright import upright_resemblance

    height, width = 0.20, 0.07
    axes = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])  # first axis vertical
    estimate = ObjectEstimate(
        status="ok", centre=np.array([0.55, 0.0, height / 2]), depth=0.35,
        camera_position=np.array([0.55, 0.0, 0.45]), axes=axes, extents=np.array([height, width, width]),
        principal_axis=np.array([0.0, 0.0, 1.0]),
        resemblances={"sphere": 0.2, "cylinder": 0.0, "box": 1.0, "flat": 0.0,
                      "upright": upright_resemblance(height, [width, width])})
    first = choose_grasp(estimate, estimate.as_grasp_estimate())
    assert first.chosen == first.executed == first.plan.grasp.value == "box"
    approach = first.plan.X_WP_target.rotation().col(2)
    assert approach[2] < -0.99  # straight down onto the top
    assert first.plan.X_WP_target.translation()[2] == pytest.approx(height)  # the palm onto the top
    second = choose_grasp(estimate, estimate.as_grasp_estimate(), exclude=("box",))
    assert second.executed == second.plan.grasp.value == "cylindrical"
    approach = second.plan.X_WP_target.rotation().col(2)
    assert math.degrees(math.asin(-approach[2])) == pytest.approx(45.0, abs=1.0)  # from the side, dipping
    third = choose_grasp(estimate, estimate.as_grasp_estimate(), exclude=("box", "cylindrical"))
    assert third.executed == "spherical"
    assert grasp_of("upright") == "box" and grasp_of("upright", ("box",)) == "cylindrical"
    assert grasp_of("flat", ("precision",)) == "precision"  # the flower grasp's second try


def test_a_round_object_takes_the_spherical_grasp_where_the_box_leads():
    from drake_grasp.primitives.decision import choose_with_funnels
    from drake_grasp.primitives.low import FLOWER_MAX_WIDTH, low_resemblance
    from drake_grasp.primitives.round_sides import round_resemblance

    ring = round_resemblance(0.012, [0.23, 0.22])  # sides curving away, a round footprint
    box = round_resemblance(0.0005, [0.12, 0.10])  # a level top at vertical sides
    banana = round_resemblance(0.012, [0.20, 0.04])  # round sides, a slender footprint
    assert ring > 0.99 and box < 0.01 and banana < 0.01
    assert math.isnan(round_resemblance(math.nan, [0.1, 0.1])) and math.isnan(round_resemblance(0.01, [0.1, 0.0]))
    # A 23 cm ring 8 cm tall is low but wider than the flower grasp lands round: it keeps the sphere.
    wide, narrow = low_resemblance(0.08, [0.23, 0.23]), low_resemblance(0.08, [0.10, 0.10])
    assert wide < 0.01 and narrow > 0.99 and low_resemblance(0.08, [FLOWER_MAX_WIDTH] * 2) == pytest.approx(0.5, abs=0.01)
    res = {"sphere": 0.05, "cylinder": 0.01, "box": 0.95, "flat": 0.1, "upright": 0.0, "low": wide, "round": ring}
    assert choose_shape(res) == "sphere"
    assert choose_shape({**res, "round": box}) == "box" and choose_shape({**res, "round": banana}) == "box"
    # A low round object that the flower grasp lands round keeps the box (the flower grasp held such
    # objects no more often), unless it is squat, a ring or a puck under 5.5 cm: the flower grasp; where
    # the sphere leads, the flower grasp as before.
    from drake_grasp.primitives.low import squat_resemblance
    blob, puck = squat_resemblance(0.08, [0.10, 0.10]), squat_resemblance(0.035, [0.12, 0.12])
    assert blob < 0.01 and puck > 0.99 and squat_resemblance(0.035, [0.23, 0.23]) < 0.01
    assert choose_shape({**res, "low": narrow}) == "box" and choose_shape({**res, "low": narrow, "squat": blob}) == "box"
    assert choose_shape({**res, "low": narrow, "squat": puck}) == "flat"
    assert choose_shape({**res, "low": narrow, "squat": puck}, exclude=("flat",)) == "box"
    assert choose_shape({**res, "low": narrow, "squat": puck, "round": box}) == "box"
    assert decision_margin({**res, "low": narrow, "squat": 0.8}) == pytest.approx(0.6)
    assert choose_shape({**res, "low": narrow, "sphere": 0.99}) == "flat"
    # The spherical grasp used up (or its funnel empty): the box again.
    assert choose_shape(res, exclude=("sphere",)) == "box"
    assert choose_with_funnels(res, {"sphere": True, "cylinder": False, "box": False}) == "box"
    # The cylinder's lead is the paper's: a lying cylinder keeps its grasp.
    assert choose_shape({**res, "cylinder": 0.99}) == "cylinder"
    # The margin: the box's lead (0.9), bounded by the round resemblance's distance from its threshold.
    near = {**res, "round": 0.7}
    assert choose_shape(near) == "sphere" and decision_margin(near) == pytest.approx(0.4)


def test_a_tall_round_object_takes_the_sphere_from_a_narrower_footprint():
    from drake_grasp.primitives.round_sides import (WIDE_FOOTPRINT, WIDE_TALL_FOOTPRINT, wide_middle,
                                                    wide_resemblance)

    # A blob 16 cm tall on a 19 cm footprint is wide; a ring 8.5 cm tall on the same footprint is not.
    blob, ring = wide_resemblance([0.22, 0.19], 0.16), wide_resemblance([0.22, 0.19], 0.085)
    assert blob > 0.95 and ring < 0.05
    assert wide_middle(0.3) == pytest.approx(WIDE_TALL_FOOTPRINT, abs=1e-6)
    assert wide_middle(0.05) == pytest.approx(WIDE_FOOTPRINT, abs=1e-6)
    assert wide_middle(math.nan) == WIDE_FOOTPRINT  # a height not known: the rule of 0.38.0
    # A flask standing 20.7 cm tall on 13.6 cm keeps the box; union 2410_008 (16.6 cm) too.
    assert wide_resemblance([0.136, 0.136], 0.207) < 0.01 and wide_resemblance([0.238, 0.166], 0.156) < 0.5
    res = {"sphere": 0.05, "cylinder": 0.01, "box": 0.95, "flat": 0.1, "upright": 0.0, "low": 0.0, "round": 1.0}
    assert choose_shape({**res, "wide": blob}) == "sphere" and choose_shape({**res, "wide": ring}) == "box"


def test_a_tall_round_object_takes_the_cylindrical_grasp_round_a_level_axis():
    """Step 3a (behaviour 0.53.0): a round object taller than the fingertips' sweep takes the cylinder where
    the box leads, wide or not; the cylinder used up, the wide step as before; a low one is untouched."""
    import numpy as np

    from drake_grasp.funnel.planning import choose_grasp
    from drake_grasp.primitives.estimate import ObjectEstimate
    from drake_grasp.primitives.low import LOW_HEIGHT
    from drake_grasp.primitives.round_sides import tall_resemblance, wide_resemblance

    blob, ring = tall_resemblance(0.16), tall_resemblance(0.085)
    assert blob > 0.99 and ring < 0.01 and tall_resemblance(LOW_HEIGHT) == pytest.approx(0.5)
    assert math.isnan(tall_resemblance(math.nan))
    res = {"sphere": 0.3, "cylinder": 0.01, "box": 0.7, "flat": 0.0, "upright": 0.0, "low": 0.0, "round": 1.0}
    narrow, wide = wide_resemblance([0.17, 0.16], 0.16), wide_resemblance([0.22, 0.19], 0.16)
    assert choose_shape({**res, "tall": blob, "wide": narrow}) == "cylinder"
    assert choose_shape({**res, "tall": blob, "wide": wide}) == "cylinder"
    assert choose_shape({**res, "tall": blob, "wide": wide}, exclude=("cylinder",)) == "sphere"
    assert choose_shape({**res, "tall": blob, "wide": narrow}, exclude=("cylinder",)) == "box"
    assert choose_shape({**res, "tall": ring, "wide": wide}) == "sphere"  # lower than the sweep: as before
    assert choose_shape({**res, "tall": blob, "round": 0.0}) == "box"  # vertical sides: the box
    assert choose_shape({**res, "tall": blob, "sphere": 0.9}) == "sphere"  # the paper's sphere keeps its grasp
    assert choose_shape({k: v for k, v in res.items() if k != "round"} | {"tall": blob}) == "box"
    # The margin: bounded by the tall resemblance's distance from its threshold.
    assert decision_margin({**res, "tall": 0.7, "wide": 0.0}) == pytest.approx(0.4)
    # Executed round a level axis, the palm coming straight down on the top, though the silhouettes
    # read the blob elongated along a tilted axis.
    tilted = np.array([math.cos(0.6), 0.0, math.sin(0.6)])
    estimate = ObjectEstimate(
        status="ok", centre=np.array([0.55, 0.0, 0.08]), depth=0.35, camera_position=np.array([0.55, 0.0, 0.45]),
        axes=np.column_stack([tilted, [0.0, 1.0, 0.0], np.cross(tilted, [0.0, 1.0, 0.0])]),
        extents=np.array([0.18, 0.17, 0.16]), principal_axis=tilted,
        resemblances={**res, "tall": blob, "wide": narrow})
    choice = choose_grasp(estimate, estimate.as_grasp_estimate())
    assert choice.chosen == choice.executed == choice.plan.grasp.value == "cylindrical"
    R = choice.plan.X_WP_target.rotation().matrix()
    assert R[2, 2] < -0.99  # the approach straight down
    assert abs(R[:, 0] @ [1.0, 0.0, 0.0]) > 0.99  # the wrapped axis: the tilted one, laid level
    forced = choose_grasp(estimate, estimate.as_grasp_estimate(), forced="cylindrical")
    assert forced.plan.X_WP_target.rotation().matrix()[2, 2] < -0.99
    shorter = dataclasses.replace(estimate, resemblances={**res, "tall": ring, "wide": narrow})
    assert choose_grasp(shorter, shorter.as_grasp_estimate()).executed == "box"


def test_a_round_object_narrower_than_the_box_grasp_wraps_keeps_the_box():
    from drake_grasp.primitives.round_sides import WIDE_FOOTPRINT, wide_resemblance

    ring, flask = wide_resemblance([0.25, 0.24]), wide_resemblance([0.14, 0.136])  # footprints, m
    assert ring > 0.99 and flask < 0.01 and wide_resemblance([0.3, WIDE_FOOTPRINT]) == pytest.approx(0.5)
    assert math.isnan(wide_resemblance([0.1, math.nan])) and math.isnan(wide_resemblance([0.1, 0.0]))
    res = {"sphere": 0.05, "cylinder": 0.01, "box": 0.95, "flat": 0.1, "upright": 0.0, "low": 0.0, "round": 1.0}
    assert choose_shape({**res, "wide": ring}) == "sphere"
    assert choose_shape({**res, "wide": flask}) == "box"
    assert choose_shape(res) == "sphere"  # no wide resemblance measured: every round object, as before 0.38.0
    # The paper's sphere keeps its grasp whatever the width; a low squat ring still takes the flower grasp.
    assert choose_shape({**res, "sphere": 0.99, "wide": flask}) == "sphere"
    assert choose_shape({**res, "low": 1.0, "squat": 1.0, "wide": flask}) == "flat"
    # The margin: bounded by the wide resemblance's distance from its threshold.
    assert decision_margin({**res, "wide": 0.6}) == pytest.approx(0.2)


def test_a_thin_round_sided_object_takes_the_flower_grasp_where_the_box_remains():
    from drake_grasp.primitives.round_sides import thin_round_resemblance

    bar = thin_round_resemblance(0.028, 0.008, [0.12, 0.05])  # a 2.8 cm bar with round sides
    brick = thin_round_resemblance(0.028, 0.0005, [0.12, 0.05])  # vertical sides, a level top
    banana = thin_round_resemblance(0.0365, 0.012, [0.19, 0.05])  # the paper's banana, as read: taller
    wide = thin_round_resemblance(0.028, 0.008, [0.25, 0.22])  # wider than the flower grasp lands round
    assert bar > 0.75 and brick < 0.01 and banana < 0.2 and wide < 0.01
    assert math.isnan(thin_round_resemblance(math.nan, 0.008, [0.1, 0.05]))
    res = {"sphere": 0.05, "cylinder": 0.01, "box": 0.95, "flat": 0.3, "upright": 0.0, "low": 1.0,
           "round": 0.0, "squat": 1.0}
    assert choose_shape({**res, "thin_round": bar}) == "flat"
    assert choose_shape({**res, "thin_round": brick}) == "box" and choose_shape({**res, "thin_round": banana}) == "box"
    # The flower grasp used up: the box again; the paper's cylinder lead is left alone.
    assert choose_shape({**res, "thin_round": bar}, exclude=("flat",)) == "box"
    assert choose_shape({**res, "cylinder": 0.99, "thin_round": bar}) == "cylinder"
    # Without the resemblance (the paper's perception, or records before it): the argmax.
    assert choose_shape(res) == "box"
    # The margin: the box's lead (0.9), bounded by the rule's own distance from its threshold.
    assert decision_margin({**res, "flat": 0.1, "thin_round": 0.6}) == pytest.approx(0.2)


def test_a_thin_object_narrow_where_the_fingers_close_takes_the_flower_grasp():
    from drake_grasp.primitives.narrow import thin_narrow_resemblance

    handle = thin_narrow_resemblance(0.027, 0.028, [0.26, 0.09])  # a hammer: the handle 2.8 cm wide
    polycube = thin_narrow_resemblance(0.028, 0.079, [0.12, 0.08])  # a flat polycube, 7.9 cm wide there
    banana = thin_narrow_resemblance(0.0365, 0.04, [0.19, 0.05])  # the paper's banana, as read: taller
    wide = thin_narrow_resemblance(0.027, 0.028, [0.25, 0.22])  # wider than the flower grasp lands round
    assert handle > 0.75 and polycube < 0.01 and banana < 0.2 and wide < 0.01
    assert math.isnan(thin_narrow_resemblance(0.027, math.nan, [0.2, 0.1]))
    res = {"sphere": 0.0, "cylinder": 0.0, "box": 1.0, "flat": 0.3, "upright": 0.0, "low": 1.0,
           "round": 0.0, "squat": 1.0, "thin_round": 0.0}
    assert choose_shape({**res, "thin_narrow": handle}) == "flat"
    assert choose_shape({**res, "thin_narrow": polycube}) == "box"
    # The cylindrical grasp from above closes the same fingers across it: also the flower grasp.
    assert choose_shape({**res, "cylinder": 1.0, "box": 0.2, "thin_narrow": handle}) == "flat"
    # The flower grasp used up: the argmax's grasp again; a sphere's lead is another rule's (3b).
    assert choose_shape({**res, "thin_narrow": handle}, exclude=("flat",)) == "box"
    # The margin: bounded by the rule's own distance from its threshold.
    assert decision_margin({**res, "flat": 0.1, "thin_narrow": 0.8}) == pytest.approx(0.6)
    assert decision_margin({**res, "flat": 0.1, "thin_narrow": 0.45}) == pytest.approx(0.1)
    assert decision_margin({**res, "cylinder": 1.0, "box": 0.2, "flat": 0.1, "round": 0.9,
                            "thin_narrow": 0.8}) == pytest.approx(0.6)  # the round rule is the box's (3a)
