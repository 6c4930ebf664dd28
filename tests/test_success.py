"""The success test as a pure function: each failure reason at its threshold."""

import math

import pytest

from drake_grasp.success import DROPPED_DURING_LIFT, MISSED, SLIPPED_DURING_HOLD, GraspObservation, judge_grasp

LIFT, SLIP, SLIP_DEG = 0.10, 0.01, 10.0


def judge(**changes):
    held = dict(touched_after_close=True, rise_at_hold=0.10, lift_at_end=0.10, on_table_at_end=False,
                slip_distance=0.002, slip_angle=math.radians(2.0))
    return judge_grasp(GraspObservation(**{**held, **changes}), LIFT, SLIP, SLIP_DEG)


def test_a_held_object_succeeds():
    assert judge() == ""


@pytest.mark.parametrize("rise", [None, 0.0, 0.0499])
def test_not_lifted_is_missed_without_contact_and_dropped_with_it(rise):
    assert judge(touched_after_close=False, rise_at_hold=rise) == MISSED
    assert judge(touched_after_close=True, rise_at_hold=rise) == DROPPED_DURING_LIFT


def test_lifted_without_contact_at_close_is_judged_on_the_hold():
    # Contact is only asked of an object that was not lifted: one lifted anyway (e.g. held by the palm
    # and a finger that touched later) is judged like any other.
    assert judge(touched_after_close=False) == ""


def test_half_the_lift_height_is_enough():
    assert judge(rise_at_hold=0.05, lift_at_end=0.05) == ""
    assert judge(lift_at_end=0.0499) == SLIPPED_DURING_HOLD


@pytest.mark.parametrize("changes", [dict(on_table_at_end=True), dict(slip_distance=SLIP),
                                     dict(slip_angle=math.radians(SLIP_DEG))])
def test_falling_or_slipping_during_the_hold_fails_at_the_threshold(changes):
    assert judge(**changes) == SLIPPED_DURING_HOLD


def test_just_under_the_slip_thresholds_succeeds():
    assert judge(slip_distance=SLIP * 0.999, slip_angle=math.radians(SLIP_DEG) * 0.999) == ""
