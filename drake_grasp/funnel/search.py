"""The widest funnel: hand poses around each compliant grasp's pose, scored on the shape the camera saw.

The paper's thesis (Sec. 2-3) is that a compliant grasp succeeds when the hand pose lies in the
entrance of its compliance funnel: the set of poses from which torque-close with breakaway ends in a
stable grasp. Its Fig. 4 measures that funnel quasi-statically (the hand approaches until contact and
closes with breakaway; the contacts are scored with the ε metric) and averages ε over the pose errors
(ε_mean). The search does the same at run time, with what the robot knows:

* **the shape** is the one the camera saw (`observed_shape`: the table-top height map's column solid,
  carved where the depth views saw free space under the object: docs/design.md §5.4r), never the
  object's file; ε's centre of mass and torque scale are the observed shape's;
* **the candidates** are each grasp's pose (`grasps.plan_compliant_grasp`, from the estimate) varied:
  its near-symmetric turns about the approach (`grasps.NEAR_SYMMETRIES`: each scored on its own), a yaw
  of ±`yaw_deg`, a palm raised by `raise_m`, and a tilt of ±`tilt_deg` about the palm's y axis (the
  approach leaning across the fingers' closing direction), then shifts across the palm;
* **the score** of a pose is its funnel's width: ε averaged over a 3 × 3 neighbourhood of palm shifts
  (along the palm's x and y) spaced `spacing` apart, the spacing sized by the estimate's own
  uncertainty (`neighbourhood_spacing`: how far the estimate's centre may be off);
* **coarse to fine**: every variant is scored at its own centre (9 grasps each); the best
  `refine` variants of each grasp are then scored at the 8 shifts around it too (a 5 × 5 grid of
  grasps), and the centre of the widest funnel among all of these is the pose executed.

Each quasi-static grasp starts where the executor's approach starts (the pre-grasp pose, the plan's
approach distance back along the palm normal), approaches until a link touches the shape or the
table, or until the plan's target, and closes with breakaway (`quasistatic.QuasiStaticHand`).

A grasp can hold what ε rates 0: where the fingers meet the shape under its widest line, pushing up
into it (a lying bottle's lower flanks, `cradles`), and none presses it down, nothing resists lifting
it out of the hand, so ε = 0; under the torque close the fingers lift it into the hand.
With `keep_cradled_primitive` (the default) the primitive's pose counts as open when every finger meets
the shape under its widest line there and most of its neighbourhood's poses cradle it or have ε > 0
(docs/design.md §5.4s).

Ties keep what the paper's algorithm would do: the primitive's own pose wins any tie (and any pose
less than `min_gain` better than it), then the variants in the order above, then the smaller shift.
With `keep_open_primitive` (the default) the primitive's pose is kept whenever its own funnel is open
(ε_mean > 0), and the search moves the pose only when it is not. Its plain near-symmetric turns follow
it (the alternatives the paper's algorithm executes when the arm cannot reach it: behaviour 0.18.0),
then the other candidates in the order of their funnels. A grasp whose every pose has ε = 0 (an empty
funnel) keeps its primitive pose. The decision rule that uses the funnels is `primitives.decision`'s.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from drake_grasp.funnel.observed_shape import ObservedShape
from drake_grasp.funnel.params import FunnelParams
from drake_grasp.grasps import NEAR_SYMMETRIES, GraspPlan, GraspType, ObjectEstimate, plan_compliant_grasp
from drake_grasp.quality import CONE_EDGES, FRICTION, grasp_quality



@dataclasses.dataclass(frozen=True)
class Variant:
    """A change of a grasp's pose, in its palm frame P: turn and yaw about z_P (rad), a tilt about y_P
    (rad), the palm raised along -z_P (m) and shifted along x_P, y_P (m)."""

    turn: float = 0.0
    yaw: float = 0.0
    tilt: float = 0.0
    raised: float = 0.0
    dx: float = 0.0
    dy: float = 0.0

    def shifted(self, dx: float, dy: float) -> "Variant":
        return dataclasses.replace(self, dx=self.dx + dx, dy=self.dy + dy)

    def apply(self, plan: GraspPlan) -> GraspPlan:
        """`plan` with its target pose changed by this variant (pre-grasp follows: same approach)."""
        X_PV = RigidTransform(RotationMatrix.MakeZRotation(self.turn + self.yaw) @ RotationMatrix.MakeYRotation(self.tilt),
                              [self.dx, self.dy, -self.raised])
        return dataclasses.replace(plan, X_WP_target=plan.X_WP_target @ X_PV)

    def describe(self) -> str:
        parts = []
        if self.turn:
            parts.append(f"turned {math.degrees(self.turn):+.0f}°")
        if self.yaw:
            parts.append(f"yaw {math.degrees(self.yaw):+.0f}°")
        if self.tilt:
            parts.append(f"tilt {math.degrees(self.tilt):+.0f}°")
        if self.raised:
            parts.append(f"raised {self.raised * 1000:.0f} mm")
        if self.dx or self.dy:
            parts.append(f"shifted ({self.dx * 1000:+.0f}, {self.dy * 1000:+.0f}) mm")
        return ", ".join(parts) or "the primitive's pose"

    def to_dict(self) -> dict:
        return {"turn_deg": math.degrees(self.turn), "yaw_deg": math.degrees(self.yaw),
                "tilt_deg": math.degrees(self.tilt), "raised": self.raised, "dx": self.dx, "dy": self.dy}


@dataclasses.dataclass(frozen=True)
class Candidate:
    """A scored pose: the variant of the grasp's primitive pose, and its funnel's ε_mean."""

    variant: Variant
    epsilon_mean: float
    plan: GraspPlan


@dataclasses.dataclass(frozen=True)
class GraspFunnel:
    """One grasp's search.

    Attributes:
        grasp: the compliant grasp.
        primitive: ε_mean at the primitive's own pose.
        cradled: the primitive's pose cradles the shape (`cradles`) and counts as open though its ε_mean
            is 0 (`FunnelParams.keep_cradled_primitive`).
        candidates: every centre scored, widest funnel first (ties: the primitive's pose, then the
            variants' order, then the smaller shift).
        grasps: quasi-static grasps closed for this grasp.
    """

    grasp: GraspType
    primitive: float
    candidates: tuple[Candidate, ...]
    grasps: int
    cradled: bool = False

    @property
    def best(self) -> Candidate:
        return self.candidates[0]

    @property
    def empty(self) -> bool:
        """No pose scored has ε > 0 and the primitive's pose does not cradle the shape: the funnel on
        the observed shape is empty."""
        return self.best.epsilon_mean <= 0.0 and not self.cradled

    def ordered(self) -> list[Candidate]:
        """The candidates to try in order: widest funnel first; an empty funnel's primitive pose first."""
        if self.empty:
            return sorted(self.candidates, key=lambda c: c.variant != Variant())
        return list(self.candidates)


@dataclasses.dataclass(frozen=True)
class FunnelSearch:
    """The search over every grasp of one decision (what the record keeps)."""

    funnels: dict  # GraspType -> GraspFunnel
    spacing: float
    neighbourhood: int
    pieces: int
    wall_time: float
    carved: bool = False  # the shape was the carved column solid (`ObservedShape.carved`)

    @property
    def grasps(self) -> int:
        return sum(f.grasps for f in self.funnels.values())

    def summary(self) -> dict:
        """Plain numbers for the record."""
        return {
            "spacing": self.spacing, "neighbourhood": self.neighbourhood, "pieces": self.pieces,
            "carved": self.carved, "grasps_closed": self.grasps, "wall_time": self.wall_time,
            "funnels": {g.value: {"primitive": f.primitive, "cradled": f.cradled, "best": f.best.epsilon_mean,
                                  "widest": max(c.epsilon_mean for c in f.candidates),
                                  "variant": f.best.variant.to_dict(), "candidates": len(f.candidates)}
                        for g, f in self.funnels.items()},
        }


def neighbourhood_spacing(uncertainty_centre: float | None, params: FunnelParams) -> float:
    """The neighbourhood's spacing, m: `spacing_per_uncertainty` times the estimate's centre
    uncertainty (m; None: unknown, the largest spacing), within the params' bounds."""
    if uncertainty_centre is None or not math.isfinite(uncertainty_centre):
        return params.max_spacing
    return float(np.clip(params.spacing_per_uncertainty * uncertainty_centre, params.min_spacing, params.max_spacing))


def variants(grasp: GraspType, params: FunnelParams) -> list[Variant]:
    """The variants scored at their centre, the primitive's pose first (module docstring)."""
    changes = [Variant()]
    yaw, tilt = math.radians(params.yaw_deg), math.radians(params.tilt_deg)
    if yaw:
        changes += [Variant(yaw=yaw), Variant(yaw=-yaw)]
    if params.raise_m:
        changes.append(Variant(raised=params.raise_m))
    if tilt:
        changes += [Variant(tilt=tilt), Variant(tilt=-tilt)]
    turns = (0.0,) + tuple(sorted(NEAR_SYMMETRIES.get(grasp, ()), key=lambda a: (abs(a), a)))
    return [dataclasses.replace(change, turn=turn) for turn in turns for change in changes]


_RING = [(i, j) for i in (-1, 0, 1) for j in (-1, 0, 1)]  # a 3 x 3 neighbourhood, the centre in the middle

# ε and ε_mean are rounded to this many decimals, so that equal funnels tie exactly and the tie goes to
# the order the module states: qhull's joggled fallback (`quality`) moves ε by up to about 1e-10, and by
# amounts that depend on the hulls the process computed before, which made a tie's winner depend on
# which trials a worker had run.
EPSILON_DIGITS = 9

# A contact pushes up into the object when its normal (into the object) rises at least this much (the
# sine of 10°): the finger is under the object's widest line there; one whose normal falls by as much
# presses the object down.
CRADLE_MIN_NORMAL_Z = math.sin(math.radians(10.0))
_FINGER_LINKS = tuple(tuple(f"bh_finger_{f}_{part}" for part in ("proximal", "distal")) for f in (1, 2, 3))


def cradles(contacts, every_finger_under: bool = False) -> bool:
    """Whether a quasi-static grasp's contacts (`quasistatic.Contact`: link names, normals into the
    object) cradle it: every finger touches it, no contact, the palm's included, presses it down (normal
    z above -`CRADLE_MIN_NORMAL_Z`), and some finger pushes up into it from under its widest line (normal
    z at least `CRADLE_MIN_NORMAL_Z`); with `every_finger_under`, every contact does. Such a grasp can
    have ε = 0 (nothing resists lifting the object out of the hand), yet the torque close lifts the
    object into it (docs/design.md §5.4s)."""
    if not contacts:
        return False
    links = {c.link for c in contacts}
    if not all(links & set(finger) for finger in _FINGER_LINKS):
        return False
    rises = [float(c.normal[2]) for c in contacts]
    if every_finger_under:
        return min(rises) >= CRADLE_MIN_NORMAL_Z
    return min(rises) > -CRADLE_MIN_NORMAL_Z and max(rises) >= CRADLE_MIN_NORMAL_Z


class FunnelScorer:
    """Closes the hand quasi-statically on one observed shape; built once per decision."""

    def __init__(self, shape: ObservedShape):
        from drake_grasp.quasistatic import QuasiStaticHand

        self.shape = shape
        self._hand = QuasiStaticHand(shape.as_object_spec(), table=True)
        self._torque_scale = shape.max_radius
        self.closed = 0

    def score(self, plan: GraspPlan) -> tuple[float, int]:
        """(ε, how it cradles the shape: 0 not, 1 `cradles`, 2 with every finger under its widest line)
        of the plan's grasp: from its pre-grasp pose, approach until contact (or its target), close with
        breakaway, score the contacts about the observed centre."""
        grasp = self._hand.grasp_plan(plan, self.shape.X_WO)
        self.closed += 1
        points, normals = grasp.contact_arrays()
        epsilon = float(grasp_quality(points, normals, FRICTION, np.zeros(3), self._torque_scale, CONE_EDGES).epsilon)
        cradle = 2 if cradles(grasp.contacts, every_finger_under=True) else int(cradles(grasp.contacts))
        return round(epsilon, EPSILON_DIGITS), cradle

    def epsilon(self, plan: GraspPlan) -> float:
        """ε of the plan's grasp (`score`)."""
        return self.score(plan)[0]


def search_grasp(scorer: FunnelScorer, grasp: GraspType, estimate: ObjectEstimate, spacing: float,
                 params: FunnelParams) -> GraspFunnel:
    """One grasp's funnel search (module docstring)."""
    base = plan_compliant_grasp(grasp, estimate)
    closed_before = scorer.closed
    cache: dict = {}

    def scored_pose(variant: Variant, i: int, j: int) -> tuple[float, int]:
        key = (variant, i, j)
        if key not in cache:
            cache[key] = scorer.score(variant.shifted(i * spacing, j * spacing).apply(base))
        return cache[key]

    def epsilon(variant: Variant, i: int, j: int) -> float:
        return scored_pose(variant, i, j)[0]

    def epsilon_mean(variant: Variant, ci: int, cj: int) -> float:
        return round(float(np.mean([epsilon(variant, ci + i, cj + j) for i, j in _RING])), EPSILON_DIGITS)

    order = variants(grasp, params)
    scored = []  # (ε_mean, variant order, shift size, centre, variant)
    for k, variant in enumerate(order):
        scored.append((epsilon_mean(variant, 0, 0), k, 0, (0, 0), variant))
    ranked = sorted(scored, key=lambda s: (-s[0], s[1]))
    for _, k, _, _, variant in ranked[:params.refine]:
        if ranked[0][0] <= 0.0:
            break  # nothing has a funnel at its centre: no shift is worth the cost
        for ci, cj in _RING:
            if (ci, cj) != (0, 0):
                scored.append((epsilon_mean(variant, ci, cj), k, abs(ci) + abs(cj), (ci, cj), variant))
    primitive = scored[0][0]
    cradled = False
    if params.keep_cradled_primitive and primitive <= 0.0 and scored_pose(Variant(), 0, 0)[1] == 2:
        # every finger under the widest line at the primitive's pose, and most of its neighbourhood's
        # poses cradling the shape or with ε > 0
        holding = sum(1 for i, j in _RING if epsilon(Variant(), i, j) > 0.0 or scored_pose(Variant(), i, j)[1])
        cradled = 2 * holding > len(_RING)

    def rank(value: float) -> float:  # within `min_gain` of the primitive's pose: a tie with it
        return value if value > primitive * (1.0 + params.min_gain) else min(value, primitive)

    scored.sort(key=lambda s: (-rank(s[0]), s[1], s[2], s[3]))
    if params.keep_open_primitive and (primitive > 0.0 or cradled):  # an open funnel at the primitive's pose: keep it,
        # then its plain near-symmetric turns (what the paper's algorithm executes when the arm cannot
        # reach the primitive's pose), then the poses the search moved, widest first (a stable sort)
        def kept_first(s) -> int:
            _, k, shift, _, variant = s
            if shift == 0 and variant == Variant(turn=variant.turn):
                return 0 if k == 0 else 1
            return 2

        scored.sort(key=kept_first)
    candidates = tuple(
        Candidate(variant.shifted(ci * spacing, cj * spacing), value,
                  variant.shifted(ci * spacing, cj * spacing).apply(base))
        for value, _, _, (ci, cj), variant in scored)
    return GraspFunnel(grasp, primitive, candidates, scorer.closed - closed_before, cradled)


def search(shape: ObservedShape, estimate: ObjectEstimate, grasps, params: FunnelParams,
           uncertainty_centre: float | None) -> FunnelSearch:
    """The funnel of each of `grasps` on the observed shape."""
    start = time.perf_counter()
    scorer = FunnelScorer(shape)
    spacing = neighbourhood_spacing(uncertainty_centre, params)
    funnels = {g: search_grasp(scorer, g, estimate, spacing, params) for g in grasps}
    return FunnelSearch(funnels, spacing, len(_RING), len(shape.pieces), time.perf_counter() - start, shape.carved)
