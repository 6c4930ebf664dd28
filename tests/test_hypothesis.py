"""The minimal exploration's hypothesis and its confirmation (primitives.hypothesis): pure rules."""

import math

from drake_grasp.primitives.hypothesis import confirm, hypothesis_from_views


def test_the_hypothesis_is_read_from_the_first_views():
    assert hypothesis_from_views(1.05).kind == "round" and hypothesis_from_views(1.05).arc == "cross"
    assert hypothesis_from_views(2.5).kind == "elongated" and hypothesis_from_views(2.5).arc == "axis"
    assert hypothesis_from_views(1.3).kind == "none" and hypothesis_from_views(math.nan).kind == "none"
    # Flatness, measured from depth, comes first and needs no arc.
    flat = hypothesis_from_views(2.5, flat=0.9)
    assert flat.kind == "flat" and flat.arc == "none"
    assert hypothesis_from_views(2.5, flat=0.3).kind == "elongated"


def test_one_arc_confirms_or_leaves_the_hypothesis_open():
    elongated, round_ = hypothesis_from_views(2.5), hypothesis_from_views(1.05)
    assert confirm(elongated, 0.9, math.nan).shape == "cylinder"
    assert confirm(elongated, 0.1, math.nan).shape == "box"
    open_call = confirm(elongated, 0.5, math.nan)
    assert not open_call.confirmed and "I_a 0.50" in open_call.why
    assert confirm(round_, 1.0, 0.85).shape == "sphere"
    assert not confirm(round_, 1.0, 0.3).confirmed  # an upright cylinder or a cube: the full exploration
    assert confirm(hypothesis_from_views(2.5, flat=0.9), math.nan, math.nan).shape == "flat"
    assert not confirm(hypothesis_from_views(1.3), 1.0, 1.0).confirmed
    # Too few views to score (the scorer's zero invariances): never confirmed, whatever the numbers say.
    unmeasured = confirm(elongated, 0.0, 0.0, measured=False)
    assert not unmeasured.confirmed and "too few views" in unmeasured.why
