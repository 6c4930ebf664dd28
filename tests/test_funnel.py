"""The funnel search: the observed shape, the scoring of poses, the decision's veto and the seam to the executor."""

import math

import numpy as np
import pytest
from scipy.spatial import ConvexHull, Delaunay

from drake_grasp.funnel.observed_shape import _strips, observed_shape
from drake_grasp.funnel.params import FunnelParams
from drake_grasp.funnel.search import Variant, neighbourhood_spacing, search, variants
from drake_grasp.grasps import GraspType, ObjectEstimate
from drake_grasp.primitives.decision import choose_with_funnels
from drake_grasp.primitives.table_top import HeightMap

CENTRE = (0.55, 0.0)


def height_map(height_of) -> HeightMap:
    """A 3 mm map around CENTRE whose cells take height_of(x, y) (m above the table; <= 0: empty)."""
    m = HeightMap.around(CENTRE, 0.003, 128)
    ij = np.indices(m.heights.shape).reshape(2, -1).T
    xy = m.origin + (ij + 0.5) * m.cell
    h = height_of(xy[:, 0] - CENTRE[0], xy[:, 1] - CENTRE[1])
    m.heights[:] = np.where(h > 0, h, np.nan).reshape(m.heights.shape)
    return m


def box_map(length=0.12, width=0.06, height=0.05):
    return height_map(lambda x, y: np.where((abs(x) < length / 2) & (abs(y) < width / 2), height, 0.0))


def ring_map(outer=0.05, inner=0.025, height=0.02):
    return height_map(lambda x, y: np.where((np.hypot(x, y) < outer) & (np.hypot(x, y) > inner), height, 0.0))


def inside(shape, point) -> bool:
    return any(Delaunay(p).find_simplex(point) >= 0 for p in shape.pieces)


def test_a_box_seen_from_above_is_one_piece_of_its_size_centred_on_it():
    shape = observed_shape(box_map())
    assert len(shape.pieces) == 1
    hull = ConvexHull(shape.pieces[0])
    assert hull.volume == pytest.approx(0.12 * 0.06 * 0.05, rel=0.15)
    assert shape.centre[:2] == pytest.approx(CENTRE, abs=0.003)
    assert shape.height == pytest.approx(0.05, abs=0.002)
    # The torque scale: the farthest corner from the centre (half the box's diagonal, within a block).
    assert shape.max_radius == pytest.approx(0.5 * math.sqrt(0.12**2 + 0.06**2 + 0.05**2), abs=0.01)


def test_a_ring_keeps_its_hole_open():
    shape = observed_shape(ring_map())
    assert len(shape.pieces) > 2
    assert not inside(shape, [CENTRE[0], CENTRE[1], 0.01])  # the hole, seen down to the table
    assert inside(shape, [CENTRE[0] + 0.0375, CENTRE[1], 0.01])  # the rim


def test_strips_merge_equal_runs_and_split_at_gaps():
    heights = np.array([[0.0, 0.02, 0.02, 0.0, 0.02],
                        [0.0, 0.02, 0.02, 0.0, 0.02],
                        [0.0, 0.03, 0.02, 0.0, 0.0]])
    assert _strips(heights) == [(0, 2, 1, 3), (0, 2, 4, 5), (2, 3, 1, 3)]


def test_no_map_is_no_shape():
    assert observed_shape(height_map(lambda x, y: np.zeros_like(x))) is None


def test_the_neighbourhood_follows_the_estimate_uncertainty_within_its_bounds():
    params = FunnelParams()
    assert neighbourhood_spacing(0.004, params) == pytest.approx(0.008)
    assert neighbourhood_spacing(0.0001, params) == params.min_spacing
    assert neighbourhood_spacing(0.1, params) == params.max_spacing
    assert neighbourhood_spacing(None, params) == params.max_spacing


def test_every_near_symmetric_turn_is_a_variant_of_its_own_after_the_primitive_pose():
    box = variants(GraspType.BOX, FunnelParams())
    assert box[0] == Variant()
    assert {v.turn for v in box} == {0.0, math.pi}
    assert {round(math.degrees(v.turn)) for v in variants(GraspType.SPHERICAL, FunnelParams())} == {0, 120, -120}
    assert len(variants(GraspType.SPHERICAL, FunnelParams(yaw_deg=0, raise_m=0, tilt_deg=0))) == 3


def test_the_decision_vetoes_an_empty_funnel_only_when_another_grasp_has_one():
    resemblances = {"sphere": 0.2, "cylinder": 0.5, "box": 0.9, "flat": 0.1}
    assert choose_with_funnels(resemblances, {"sphere": False, "cylinder": False, "box": False}) == "box"
    assert choose_with_funnels(resemblances, {"sphere": False, "cylinder": False, "box": True}) == "cylinder"
    assert choose_with_funnels(resemblances, {"sphere": False, "cylinder": True, "box": True}) == "sphere"
    assert choose_with_funnels(resemblances, {"sphere": True, "cylinder": True, "box": True}) == "box"
    # Flatness decides first: a plate's empty funnels do not veto the flat choice.
    flat = dict(resemblances, flat=0.9)
    assert choose_with_funnels(flat, {"sphere": False, "cylinder": False, "box": False}) == "flat"


def test_the_search_scores_every_grasp_on_the_observed_box_and_finds_its_funnel():
    shape = observed_shape(box_map())
    estimate = ObjectEstimate(center=shape.centre, R_WB=np.eye(3), size=np.array([0.12, 0.06, 0.05]), table_z=0.0)
    params = FunnelParams(keep_open_primitive=False)
    found = search(shape, estimate, [GraspType.BOX, GraspType.SPHERICAL], params, uncertainty_centre=0.003)
    box = found.funnels[GraspType.BOX]
    # 2 turns x 6 variants at their centre (9 poses each), then 2 variants on the 5 x 5 grid (16 more each).
    assert box.grasps == 12 * 9 + 2 * 16
    assert found.funnels[GraspType.SPHERICAL].grasps == 18 * 9 + 2 * 16
    assert found.neighbourhood == 9 and found.spacing == pytest.approx(0.006)
    assert box.primitive > 0 and not box.empty
    widest = max(c.epsilon_mean for c in box.candidates)
    # The primitive's pose stays first unless a pose's funnel is wider by more than min_gain.
    if widest > box.primitive * (1 + params.min_gain):
        assert box.best.epsilon_mean == widest
    else:
        assert box.best.variant == Variant()
    # By default an open funnel at the primitive's pose keeps that pose; the others follow as alternatives.
    kept = search(shape, estimate, [GraspType.BOX], FunnelParams(), uncertainty_centre=0.003).funnels[GraspType.BOX]
    assert kept.best.variant == Variant() and kept.primitive == box.primitive
    assert len(kept.candidates) == len(box.candidates)
    # Its plain half-turn comes next, before any moved pose: the alternative the paper's algorithm
    # executes when the arm cannot reach the primitive's pose.
    assert kept.candidates[1].variant == Variant(turn=math.pi)
    summary = found.summary()
    assert summary["grasps_closed"] == found.grasps and set(summary["funnels"]) == {"box", "spherical"}


class _Seen:
    """What `choose_grasp` reads of the primitives' estimate: resemblances and the table-top uncertainty."""

    def __init__(self, resemblances, uncertainty=0.003):
        self.resemblances = resemblances
        self.table_top = {"uncertainty": {"centre": uncertainty}}


def test_without_the_search_the_decision_is_the_papers_and_its_alternatives_the_near_symmetric_turns():
    from drake_grasp.funnel.planning import choose_grasp

    estimate = ObjectEstimate(center=np.array([0.55, 0.0, 0.025]), R_WB=np.eye(3), size=np.array([0.12, 0.06, 0.05]),
                              table_z=0.0)
    choice = choose_grasp(_Seen({"sphere": 0.1, "cylinder": 0.2, "box": 0.9}), estimate)
    assert choice.search is None and choice.chosen == choice.paper_choice == choice.executed == "box"
    assert [label for label, _ in choice.alternatives] == ["the grasp turned +180° about the approach"]
    # A height map without the search's parameters is not searched either (the paper's algorithm).
    assert choose_grasp(_Seen({"box": 1.0, "sphere": 0.0, "cylinder": 0.0}), estimate, None, None, box_map()).search is None


def test_with_the_search_the_executed_grasp_comes_with_its_candidates_widest_funnel_first():
    from drake_grasp.funnel.planning import choose_grasp

    m = box_map()
    shape = observed_shape(m)
    estimate = ObjectEstimate(center=shape.centre, R_WB=np.eye(3), size=np.array([0.12, 0.06, 0.05]), table_z=0.0)
    seen = _Seen({"sphere": 0.1, "cylinder": 0.2, "box": 0.9})
    choice = choose_grasp(seen, estimate, None, FunnelParams(), m)
    assert choice.search is not None and choice.executed == "box"
    funnel = choice.search.funnels[GraspType.BOX]
    assert choice.plan == funnel.best.plan and len(choice.alternatives) == len(funnel.candidates) - 1
    # Fig. 6's branches: the same map and estimate are searched once; a forced grasp takes its own funnel.
    forced = choose_grasp(seen, estimate, "spherical", FunnelParams(), m)
    assert forced.search is choice.search and forced.executed == "spherical" and forced.chosen == "box"
    assert forced.plan == choice.search.funnels[GraspType.SPHERICAL].ordered()[0].plan


def test_a_camera_driven_trial_searches_the_funnels_on_what_its_depth_views_saw(short_scenario):
    """The scenario `funnel` end to end: the depth views' height map reaches the supervisor, every grasp
    of the paper's three is scored on its column solid, and the record says what was searched."""
    from drake_grasp.objects import resolve_object
    from drake_grasp.station import load_scenario
    from drake_grasp.trial.compliant import run_compliant_trial

    scenario = load_scenario(scenario_name="funnel")
    scenario.protocol.execution.hold_time = short_scenario.protocol.execution.hold_time
    record = run_compliant_trial(scenario, resolve_object("cube:0.07"), seed=1)
    search = record.grasp_search
    assert set(search["funnels"]) == {"spherical", "cylindrical", "box"}
    assert search["grasps_closed"] == 474 and search["neighbourhood"] == 9 and search["pieces"] >= 1
    assert search["carved"]  # the scenario funnel carves (a cube's vertical sides leave nothing to drop)
    assert search["paper_choice"] == record.chosen_grasp  # a cube: the box grasp's funnel is open
    assert search["funnels"]["box"]["primitive"] > 0
    assert record.success, record.summary()


def test_a_sliver_of_the_observed_shape_is_left_out_of_its_spec():
    """A piece too thin to be a solid for contact (a sliver the carving left) carries no contact: the
    shape's spec keeps the other pieces (a repaired box with holes stopped its trial with an error
    there), and a shape of slivers alone is refused."""
    import itertools

    from drake_grasp.funnel.observed_shape import ObservedShape
    from drake_grasp.objects import ObjectError

    cube = np.array(list(itertools.product((0.0, 0.04), (0.0, 0.04), (0.0, 0.06))))
    sliver = np.array(list(itertools.product((0.04, 0.06), (0.0, 0.04), (0.06, 0.06 + 1e-7))))
    shape = ObservedShape(pieces=(cube, sliver), centre=np.array([0.02, 0.02, 0.03]), table_z=0.0, block=0.01)
    spec = shape.as_object_spec()
    assert len(spec.pieces) == 1 and spec.volume == pytest.approx(0.04 * 0.04 * 0.06, rel=1e-6)
    with pytest.raises(ObjectError, match="too thin"):
        ObservedShape(pieces=(sliver,), centre=np.array([0.05, 0.02, 0.06]), table_z=0.0, block=0.01).as_object_spec()
