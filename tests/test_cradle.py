"""A cradle (drake_grasp.funnel.search.cradles): fingers under an object's widest line that ε rates 0."""

import numpy as np

from drake_grasp.funnel.observed_shape import observed_shape
from drake_grasp.funnel.params import FunnelParams
from drake_grasp.funnel.search import Variant, cradles, search
from drake_grasp.grasps import GraspType, ObjectEstimate
from drake_grasp.primitives import free_space
from drake_grasp.primitives.table_top import HeightMap
from drake_grasp.quasistatic import Contact

CENTRE = (0.55, 0.0)


def _contact(link: str, rise_deg: float) -> Contact:
    """A contact whose normal (into the object) rises `rise_deg` above the level."""
    a = np.radians(rise_deg)
    return Contact(link, np.zeros(3), np.array([np.cos(a), 0.0, np.sin(a)]), 0.0)


def test_fingers_under_the_widest_line_cradle_and_a_finger_pressing_down_or_missing_does_not():
    under = [_contact(f"bh_finger_{f}_distal", 30.0) for f in (1, 2, 3)]
    assert cradles(under) and cradles(under, every_finger_under=True)
    one_level = under[:2] + [_contact("bh_finger_3_distal", 0.0)]
    assert cradles(one_level) and not cradles(one_level, every_finger_under=True)
    assert not cradles(under[:2] + [_contact("bh_finger_3_distal", -30.0)])  # F3 presses it down
    assert not cradles(under + [_contact("bh_base", -90.0)])  # the palm on its top
    assert not cradles(under[:2])  # F3 touches nothing
    assert not cradles([_contact(f"bh_finger_{f}_distal", 0.0) for f in (1, 2, 3)])  # level: no cradle
    assert cradles(under[:2] + [_contact("bh_finger_3_proximal", 20.0)])  # any link of a finger
    assert not cradles([])


def _lying_cylinder(radius=0.02, length=0.08) -> HeightMap:
    """A cylinder lying along x, seen from above, carved as views from everywhere would carve it: every
    level under its lower surface is free."""
    m = HeightMap.around(CENTRE, 0.003, 128)
    ij = np.indices(m.heights.shape).reshape(2, -1).T
    x, y = (m.origin + (ij + 0.5) * m.cell - CENTRE).T
    inside = (np.abs(x) < length / 2) & (np.abs(y) < radius)
    half = np.sqrt(np.clip(radius**2 - y**2, 0.0, None))
    m.heights[:] = np.where(inside, radius + half, np.nan).reshape(m.heights.shape)
    centres = (np.arange(free_space.LEVELS) + 0.5) * free_space.LEVEL
    free = centres[None, :] < (radius - half)[:, None]
    bits = (free * (1 << np.arange(free_space.LEVELS, dtype=np.int64))).sum(axis=1).astype(float)
    m.carved = np.where(inside, bits, 0.0).reshape(m.heights.shape)
    return m


def test_a_lying_cylinder_cradled_at_the_primitive_pose_keeps_it():
    shape = observed_shape(_lying_cylinder())
    assert shape.carved
    estimate = ObjectEstimate(center=np.array([*CENTRE, 0.02]), R_WB=np.eye(3), size=np.array([0.08, 0.04, 0.04]),
                              principal_axis=np.array([1.0, 0.0, 0.0]), table_z=0.0)
    kept = search(shape, estimate, [GraspType.CYLINDRICAL], FunnelParams(), 0.0025).funnels[GraspType.CYLINDRICAL]
    moved = search(shape, estimate, [GraspType.CYLINDRICAL], FunnelParams(keep_cradled_primitive=False),
                   0.0025).funnels[GraspType.CYLINDRICAL]
    # The fingertips meet its lower flanks: ε = 0 at the primitive's pose either way.
    assert kept.primitive == 0.0 and moved.primitive == 0.0
    assert kept.cradled and not kept.empty and kept.best.variant == Variant()
    # Without the rule no pose scored has ε > 0 on this shape: the funnel is empty, and the decision
    # would veto the grasp (on a real camera's coarser shape, the search moved to a raised palm instead).
    assert not moved.cradled and moved.empty
    assert {c.variant for c in kept.candidates} == {c.variant for c in moved.candidates}


def test_the_lying_objects_lie_and_come_back_the_same_from_their_seed():
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).parent))
    from script_loader import load_script

    lying = load_script("lying_objects")
    first, again = lying.lying_objects(2002), lying.lying_objects(2002)
    assert [c for c, _, _ in first] == ["bottle"] * 6 + ["cylinder"] * 6
    for (_, _, mesh), (_, _, same) in zip(first, again):
        assert np.array_equal(mesh.vertices, same.vertices)
        assert mesh.is_watertight and mesh.extents[0] == max(mesh.extents)  # its axis along x: lying
        assert abs(mesh.extents[1] - mesh.extents[2]) < 1e-6  # round across
    assert not np.array_equal(first[0][2].vertices, lying.lying_objects(2001)[0][2].vertices)


def test_funnel_widths_are_rounded_so_that_a_tie_goes_to_the_stated_order():
    from scipy.spatial import ConvexHull

    from drake_grasp.funnel.search import EPSILON_DIGITS

    shape = observed_shape(_lying_cylinder())
    estimate = ObjectEstimate(center=np.array([*CENTRE, 0.02]), R_WB=np.eye(3), size=np.array([0.08, 0.04, 0.04]),
                              principal_axis=np.array([1.0, 0.0, 0.0]), table_z=0.0)
    params = FunnelParams(keep_cradled_primitive=False)
    first = search(shape, estimate, [GraspType.BOX], params, 0.0025).funnels[GraspType.BOX]
    ConvexHull(np.random.default_rng(0).normal(size=(40, 6)), qhull_options="QJ")  # qhull's state moves on
    again = search(shape, estimate, [GraspType.BOX], params, 0.0025).funnels[GraspType.BOX]
    assert [(c.variant, c.epsilon_mean) for c in first.candidates] == [(c.variant, c.epsilon_mean) for c in again.candidates]
    assert all(c.epsilon_mean == round(c.epsilon_mean, EPSILON_DIGITS) for c in first.candidates)
