"""From an estimate to the grasp to execute and its candidate poses: the seam between the decision and
the executor.

`choose_grasp` is what the supervisor calls when the exploration ends. Without the funnel search (the
paper's algorithm: no `perception.grasp_search`, or no height map to close the hand on) it is the
paper's: the grasp of the most resembling shape (`primitives.decision`), at its primitive's pose, with
its near-symmetric equivalents as the alternatives the executor tries when the arm cannot reach it.
With the search, each of the paper's three grasps is scored on the shape the camera saw
(`funnel.search`); the decision vetoes a grasp whose funnel is empty (`decision.choose_with_funnels`),
and the grasp executed comes with its candidates in the search's order (the primitive's pose while
its funnel is open, else the widest funnel's centre, then the rest), which the executor tries in
that order until the arm reaches one (`GraspExecutor.plan_reachable_motion`).

The flower grasp, which the search does not score (a thin object gives every grasp ε = 0), faces the
footprint the camera saw: F1 and F2 on its fuller side (`facing_the_footprint`, `flower_facing`). An
upright object's grasps (the box grasp from above, then the wrap from the arm's side: `grasp_of`) run
at their primitive's pose, as they were measured.

One search per decision: the branches of one exploration (Fig. 6 executes every grasp from a copy of
the state at the decision) share it through a small cache keyed by what the search reads.
"""

from __future__ import annotations

import collections
import dataclasses
import hashlib

import numpy as np
from pydrake.math import RigidTransform

from drake_grasp.flower_facing import faces_fuller_side
from drake_grasp.funnel.observed_shape import observed_shape
from drake_grasp.funnel.params import FunnelParams
from drake_grasp.funnel.search import FunnelSearch, search
from drake_grasp.grasps import (ARM_BASE_XY, GRASP_OF_SHAPE, GRASPS_OF_SHAPE, NEAR_SYMMETRIES, GraspPlan, GraspType,
                                near_symmetric_alternatives, plan_compliant_grasp, turned_about_approach)
from drake_grasp.primitives.decision import FLAT, UPRIGHT, choose_shape, choose_with_funnels, tall_round
from drake_grasp.primitives.scores import SHAPES
from drake_grasp.primitives.table_top import HeightMap

_SEARCHED = tuple(GraspType(GRASP_OF_SHAPE[s]) for s in SHAPES)  # the paper's three grasps
_CACHE: collections.OrderedDict = collections.OrderedDict()
_CACHE_SIZE = 4


@dataclasses.dataclass(frozen=True)
class GraspChoice:
    """What the decision chose and what the executor is to try.

    Attributes:
        chosen: the decision's grasp (the funnel's veto applied).
        paper_choice: the paper's argmax alone (differs from `chosen` only where a funnel vetoed it).
        executed: `chosen`, or the grasp the caller forced.
        plan: the executed grasp's first pose.
        alternatives: (what it is, plan) to try in order when the arm cannot reach `plan`.
        search: the funnel search (None: the paper's algorithm).
    """

    chosen: str
    paper_choice: str
    executed: str
    plan: GraspPlan
    alternatives: list
    search: FunnelSearch | None = None


def choose_grasp(estimate, grasp_estimate, forced: str | None = None, params: FunnelParams | None = None,
                 height_map: HeightMap | None = None, exclude: tuple = ()) -> GraspChoice:
    """The grasp to execute and its candidates (module docstring).

    Args:
        estimate: the primitives' `primitives.estimate.ObjectEstimate` (its resemblances and table-top
            uncertainty).
        grasp_estimate: the `grasps.ObjectEstimate` the poses are computed from (with any added error).
        forced: execute this grasp instead of the chosen one.
        params: the funnel search's choices; None: the paper's algorithm.
        height_map: what the depth views saw; None or empty: the paper's algorithm.
        exclude: the grasps that already failed on this object, once per failure (a later attempt):
            the decision runs without the shapes whose grasps all used up their tries (`tries_left`),
            a shape with another grasp executes that one (`grasp_of`), and a flower grasp tried again
            is turned (`retry_plan`).
    """
    resemblances = dict(estimate.resemblances)
    excluded = tuple(shape for shape, grasps in GRASPS_OF_SHAPE.items()
                     if not any(tries_left(grasp, exclude) for grasp in grasps))
    shape = choose_shape(resemblances, excluded)
    paper_choice = grasp_of(shape, exclude)
    if shape == UPRIGHT and (forced or paper_choice) == GraspType.CYLINDRICAL.value:
        grasp_estimate = dataclasses.replace(grasp_estimate, principal_axis=np.array([0.0, 0.0, 1.0]))
    if shape == "cylinder" and (forced or paper_choice) == GraspType.CYLINDRICAL.value and tall_round(resemblances):
        grasp_estimate = level_axis(grasp_estimate)
    found = None
    if params is not None and height_map is not None and shape not in (FLAT, UPRIGHT):
        found = _search(grasp_estimate, params, height_map, _uncertainty_centre(estimate))
    if found is None:
        executed = forced or paper_choice
        plan = _faced_plan(executed, grasp_estimate, height_map, exclude)
        return GraspChoice(paper_choice, paper_choice, executed, plan, near_symmetric_alternatives(plan))
    empty = {shape: found.funnels[GraspType(GRASP_OF_SHAPE[shape])].empty for shape in SHAPES}
    chosen = GRASP_OF_SHAPE[choose_with_funnels(resemblances, empty, excluded)]
    executed = forced or chosen
    funnel = found.funnels.get(GraspType(executed))
    if funnel is None:  # a forced precision grasp: the search does not cover it
        plan = _faced_plan(executed, grasp_estimate, height_map, exclude)
        return GraspChoice(chosen, paper_choice, executed, plan, near_symmetric_alternatives(plan), found)
    ordered = funnel.ordered()
    first, rest = ordered[0], ordered[1:]
    alternatives = [(f"the pose {c.variant.describe()} (ε_mean {c.epsilon_mean:.3f})", c.plan) for c in rest]
    return GraspChoice(chosen, paper_choice, executed, first.plan, alternatives, found)


# How often a grasp is tried on one object before the decision runs without it. The flower grasp gets
# three tries: the from-above grasps stop their fingertips 5 mm above the table (grasps.TABLE_CLEARANCE),
# so on the small and thin objects the flat rule sends to it they miss (novel seed 31337: none of the 38
# from-above attempts after a failed flower grasp held), while the flower grasp itself holds a small
# object at some placements and not at others (ring 012: held at trial seeds 1 and 3, dropped at 2).
# The third (behaviour 0.52.0): once the object falls to rest before each look (trial.release), a third
# flower try held 6 of the 14 stored trials where the box grasp third held 3, the same 3 among them
# (docs/design.md §5.4h).
TRIES = {GraspType.PRECISION.value: 3}


def grasp_of(shape: str, failed: tuple = ()) -> str:
    """The grasp a chosen `shape` executes after the failures `failed` (grasp names, once per failure):
    the first of its grasps (`grasps.GRASPS_OF_SHAPE`) with tries left, else its last. An upright
    object's is the box grasp from above, then the cylindrical wrap from the arm's side."""
    grasps = GRASPS_OF_SHAPE[shape]
    return next((grasp for grasp in grasps if tries_left(grasp, failed)), grasps[-1])


def tries_left(grasp: str, failed: tuple) -> bool:
    """Whether `grasp` may be tried again after the failures `failed` (grasp names, once per failure)."""
    return failed.count(grasp) < TRIES.get(grasp, 1)


def retry_plan(plan: GraspPlan, failed: tuple) -> GraspPlan:
    """`plan`, turned by its first near-symmetry (`grasps.NEAR_SYMMETRIES`) for each time its grasp
    already failed on this object: a flower grasp tried again puts F3 on the side F1 and F2 were, so its
    fingertips meet the object elsewhere."""
    times = failed.count(plan.grasp.value) if plan.grasp is not None else 0
    turns = NEAR_SYMMETRIES.get(plan.grasp, ())
    return turned_about_approach(plan, turns[0] * times) if times and turns else plan


def level_axis(grasp_estimate):
    """`grasp_estimate` with its principal axis laid level (its horizontal part, or none where it has
    almost none: the footprint's sides then): the axis a tall round object's cylindrical grasp wraps
    (`primitives.decision`, step 3a). A round solid has no long axis worth the name, and the wrap round
    a tilted one comes in tilted, where the arm may not reach (two round handles 20-23 cm across: the
    arm reached none of 28 poses at 0.52.0); round a level one the palm comes down on the top."""
    axis = grasp_estimate.principal_axis
    if axis is None:
        return grasp_estimate
    level = np.asarray(axis, float) * [1.0, 1.0, 0.0]
    norm = float(np.linalg.norm(level))
    return dataclasses.replace(grasp_estimate, principal_axis=level / norm if norm > 0.5 else None)


def _faced_plan(grasp: str, grasp_estimate, height_map: HeightMap | None, exclude: tuple) -> GraspPlan:
    """`grasp` at its primitive's pose, faced to the footprint (`facing_the_footprint`) and turned for
    the tries it already used (`retry_plan`): a grasp the search does not place."""
    return retry_plan(facing_the_footprint(plan_compliant_grasp(grasp, grasp_estimate), height_map), exclude)


def facing_the_footprint(plan: GraspPlan, height_map: HeightMap | None) -> GraspPlan:
    """A three-finger flower grasp turned, if need be, so that F1 and F2 meet the fuller side of the
    footprint the camera saw (`flower_facing.faces_fuller_side`); every other plan, and every plan
    without a height map, as it is."""
    if plan.grasp is not GraspType.PRECISION or not plan.thumb_closes or height_map is None:
        return plan
    footprint_xy, _ = height_map.columns()
    if len(footprint_xy) == 0:
        return plan
    X = plan.X_WP_target
    R_WP = faces_fuller_side(X.rotation(), X.translation(), footprint_xy, X.translation()[:2] - ARM_BASE_XY)
    return dataclasses.replace(plan, X_WP_target=RigidTransform(R_WP, X.translation()))


def _uncertainty_centre(estimate) -> float | None:
    table_top = getattr(estimate, "table_top", None) or {}
    uncertainty = table_top.get("uncertainty") or {}
    value = uncertainty.get("centre")
    return None if value is None else float(value)


def _search(grasp_estimate, params: FunnelParams, height_map: HeightMap, uncertainty: float | None):
    """The search over the paper's three grasps, or None when the map holds no shape; cached."""
    digest = hashlib.sha256()
    for array in (height_map.heights, np.zeros(0) if height_map.carved is None else height_map.carved,
                  height_map.origin, grasp_estimate.center, grasp_estimate.R_WB,
                  grasp_estimate.size, np.zeros(0) if grasp_estimate.principal_axis is None
                  else grasp_estimate.principal_axis):
        digest.update(np.ascontiguousarray(np.nan_to_num(np.asarray(array, float), nan=-1.0)).tobytes())
    key = (digest.hexdigest(), height_map.cell, height_map.table_height, grasp_estimate.table_z, repr(params),
           uncertainty)
    if key in _CACHE:
        _CACHE.move_to_end(key)
        return _CACHE[key]
    shape = observed_shape(height_map)
    found = None if shape is None else search(shape, grasp_estimate, _SEARCHED, params, uncertainty)
    _CACHE[key] = found
    while len(_CACHE) > _CACHE_SIZE:
        _CACHE.popitem(last=False)
    return found
