"""The decision rule (primitives.decision): flatness decides first, then the paper's argmax."""

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
