"""The decision: which primitive shape, hence which compliant grasp, the resemblances choose.

The paper's rule is an argmax: execute the compliant grasp of the most resembling shape (sphere,
cylinder or box; paper Sec. 3). A fourth resemblance, "flat" (`primitives.flat`, from the table-top
estimate), cannot join that argmax as an equal: the box resemblance measures how much the
silhouette's area changes under the camera's arcs, and a flat object's area changes most of all, so
the box resemblance saturates (1.0) on every plate, flat T and stick measured (docs/results/flower.md).
Flatness is not a likeness of silhouettes but a measured size (height and largest extent above a
known table), so it decides first:

1. **flat** when the flat resemblance is at least `FLAT_THRESHOLD` (1/2: the object is thinner than
   2.5 cm or smaller than 7 cm, the middle of its logistic steps);
2. **upright** when the upright resemblance (`primitives.upright`, also from the table-top estimate)
   is at least `UPRIGHT_THRESHOLD` (1/2: standing more than 1.8 times as tall as its footprint is
   wide, and narrower than the hand wraps): the box grasp from above first, its palm on the top and its
   fingers down the sides (under a bottle's shoulder), then the cylindrical grasp round the vertical
   axis from the arm's side (`grasps.GRASPS_OF_SHAPE`, docs/design.md §5.4q). Like flatness, it is a
   measured shape that the silhouettes' box resemblance saturates on. But **flat** first where the slender resemblance
   (`primitives.upright`: upright, on a footprint thinner than 3.2 cm one way) is at least `SLENDER_THRESHOLD`
   (1/2): a peg or a marker on its end, which the cylindrical grasp's F1 and F2 pass either side of and
   the flower grasp's two-finger pinch holds (docs/design.md §5.4o). A flat grasp already used up
   leaves the upright one;
3. otherwise the paper's argmax over sphere, cylinder and box, refined by two measured shapes:

   a. where it picks the box and the round resemblance (`primitives.round_sides`, from the table-top
      estimate) is at least `ROUND_THRESHOLD` (1/2: sides that curve away below the top, on a compact
      footprint), the **cylinder** if the object is tall (the tall resemblance, `primitives.round_sides`,
      at least `TALL_THRESHOLD`: taller than the fingertips' sweep, 10.4 cm; behaviour 0.53.0): its grasp
      puts the palm on the top and wraps the fingers round a level axis (`funnel.planning.choose_grasp`),
      below the widest line of a tall round solid that the box grasp's fingertips close above
      (docs/design.md §5.4j). A cylinder already used up leaves the rule below. Otherwise the
      **sphere** instead, if the object is wide and not low (b.): the box resemblance
      saturates on every irregular solid, and three fingers round a ring or a blob wider than the box
      grasp wraps (the wide resemblance, `primitives.round_sides`, at least `WIDE_THRESHOLD`: the
      footprint's shorter side over 21 cm, or over 17 cm for an object taller than the fingertips'
      sweep, behaviour 0.50.0) hold it where two against one slip; a narrower round object
      keeps the box, which held more real files than the sphere did (docs/design.md §5.4j, behaviour
      0.38.0; without a wide resemblance, every round object, as before). A sphere already used up
      (`exclude`) leaves the box. A low round
      object (b.) keeps the box, unless it is also squat (`primitives.low.squat_resemblance`: lower than
      5.5 cm, a ring or a puck): then **flat**, the flower grasp, whose landed fingertips meet its round
      side at or above its widest line (§5.4k); a flat grasp already used up leaves the box;
   b. where the argmax picks the sphere and the low resemblance (`primitives.low`) is at least
      `LOW_THRESHOLD` (1/2: standing lower than the fingers' sweep, 10.4 cm, and narrow enough for the
      flower grasp to land round it), **flat** instead: the spherical grasp's rounded fingertips meet
      such an object below its equator and pop it out, and the flower grasp, landed on the table round
      it, holds it (docs/design.md §5.4i). A flat grasp already used up leaves the sphere;
   c. where the box remains and the thin-round resemblance (`primitives.round_sides`: lower than 3.2 cm,
      round-sided, whatever its footprint, and narrow enough for the flower grasp to land round it) is
      at least `THIN_ROUND_THRESHOLD` (1/2), **flat**: the box grasp's fingertips pass above the table
      and slip off or miss a low bar, tube or pebble that the flower grasp's landed tips hold
      (docs/design.md §5.4l); so too, where the box or the cylinder remains, where the thin-narrow
      resemblance (`primitives.narrow`: lower than 3.2 cm and narrower than 5 cm where the fingers
      close, a tool's handle) is at least `THIN_NARROW_THRESHOLD` (1/2): both grasps close the fingers
      across it from above, and their tips meet it curled in past the bottom of their arc (§5.4m). A
      flat grasp already used up leaves the box or the cylinder;
4. with the funnel search (`funnel.search`, a scenario's `perception.grasp_search`): a grasp whose
   funnel on the shape the camera saw is empty (ε = 0 at every pose scored) is not chosen when another's
   is not; the most resembling of those with a funnel is (`choose_with_funnels`). The paper's argmax
   stands whenever its grasp has a funnel, or no grasp has one. Steps 1 and 2 keep precedence: a plate
   gives ε = 0 to every grasp quasi-statically, so no funnel vetoes the flat choice, and an upright
   object's grasps run at their primitive's pose, as they were measured.

The *margin* says how clear the decision was, in [0, 1]: in step 3, the lead of the best resemblance
over the next; a flat resemblance near its threshold makes any decision close, so its own distance
from the threshold, 2 |flat - 1/2|, bounds the margin from above, and so does the upright one's, and
the low one's where the sphere leads, and the round one's where the box leads (on a round object the
low one's too, then the squat one's if it is low, the tall one's if not, and the wide one's if it is not
tall; on an object not round, the
thin-round one's, and the thin-narrow one's where the box or the cylinder leads).
Without those resemblances (the paper's perception), both are the paper's argmax and its lead.
"""

import math

from drake_grasp.primitives.scores import SHAPES

FLAT = "flat"
UPRIGHT = "upright"
SLENDER = "slender"  # not a choice: it turns an upright object's choice into the flat one (step 2)
LOW = "low"  # not a choice: it turns the sphere's choice into the flat one (step 3b)
ROUND = "round"  # not a choice: it turns the box's choice into the sphere's (step 3a)
WIDE = "wide"  # not a choice: only a wide round object's box turns into the sphere (step 3a)
TALL = "tall"  # not a choice: a tall round object's box turns into the cylinder (step 3a)
SQUAT = "squat"  # not a choice: it turns a low round object's box into the flat choice (step 3a)
THIN_ROUND = "thin_round"  # not a choice: it turns a thin round-sided object's box into the flat one (3c)
THIN_NARROW = "thin_narrow"  # not a choice: it turns a thin object's box or cylinder, narrow at the grasp, flat (3c)
CHOICES = SHAPES + (FLAT, UPRIGHT)
FLAT_THRESHOLD = 0.5
UPRIGHT_THRESHOLD = 0.5
SLENDER_THRESHOLD = 0.5
LOW_THRESHOLD = 0.5
ROUND_THRESHOLD = 0.5
WIDE_THRESHOLD = 0.5
TALL_THRESHOLD = 0.5
SQUAT_THRESHOLD = 0.5
THIN_ROUND_THRESHOLD = 0.5
THIN_NARROW_THRESHOLD = 0.5


def _value(resemblances: dict, shape: str) -> float:
    value = resemblances.get(shape)
    return math.nan if value is None else float(value)


def choose_shape(resemblances: dict, exclude=()) -> str | None:
    """The chosen shape (one of `CHOICES`) for resemblances {shape: value in [0, 1]}, or None when there
    are none. A missing or NaN flat resemblance leaves the paper's argmax.

    `exclude`: shapes whose grasp already failed on this object (a later attempt, `trial.attempts`):
    the rule runs without them, unless that leaves none of the paper's three."""
    if not resemblances:
        return None
    flat = _value(resemblances, FLAT)
    if FLAT not in exclude and math.isfinite(flat) and flat >= FLAT_THRESHOLD:
        return FLAT
    slender = _value(resemblances, SLENDER)
    if FLAT not in exclude and math.isfinite(slender) and slender >= SLENDER_THRESHOLD:
        return FLAT
    upright = _value(resemblances, UPRIGHT)
    if UPRIGHT not in exclude and math.isfinite(upright) and upright >= UPRIGHT_THRESHOLD:
        return UPRIGHT
    shapes = [s for s in SHAPES if s not in exclude] or list(SHAPES)
    return _refined(max(shapes, key=lambda s: resemblances.get(s, -1.0)), resemblances, exclude)


def _refined(shape: str, resemblances: dict, exclude=()) -> str:
    """The argmax's `shape` refined by the measured shapes (step 3): a round object's box is the cylinder
    if it is tall, the sphere if it is wide, or the flat choice if it is low and squat (3a), a low object's sphere the flat choice (3b), a thin
    round-sided object's box, or a thin object's box or cylinder where it is narrow at the grasp, the
    flat choice (3c); a choice in `exclude` is not made."""
    round_, low, squat = _value(resemblances, ROUND), _value(resemblances, LOW), _value(resemblances, SQUAT)
    is_low = math.isfinite(low) and low >= LOW_THRESHOLD
    is_round = math.isfinite(round_) and round_ >= ROUND_THRESHOLD
    wide = _value(resemblances, WIDE)
    is_wide = not math.isfinite(wide) or wide >= WIDE_THRESHOLD  # not measured: the rule before 0.38.0
    if shape == "box" and tall_round(resemblances) and "cylinder" not in exclude:  # not measured: as before 0.53.0
        return "cylinder"
    if shape == "box" and is_round and not is_low and is_wide and "sphere" not in exclude:
        return "sphere"
    if shape == "box" and is_round and is_low and FLAT not in exclude and math.isfinite(squat) \
            and squat >= SQUAT_THRESHOLD:
        return FLAT
    if shape == "sphere" and FLAT not in exclude and is_low:
        return FLAT
    thin_round, thin_narrow = _value(resemblances, THIN_ROUND), _value(resemblances, THIN_NARROW)
    if shape == "box" and FLAT not in exclude and math.isfinite(thin_round) and thin_round >= THIN_ROUND_THRESHOLD:
        return FLAT
    if shape in ("box", "cylinder") and FLAT not in exclude and math.isfinite(thin_narrow) \
            and thin_narrow >= THIN_NARROW_THRESHOLD:
        return FLAT
    return shape


def tall_round(resemblances: dict) -> bool:
    """Whether step 3a sends the box's choice to the cylinder: a round object, not low, and tall."""
    round_, low, tall = _value(resemblances, ROUND), _value(resemblances, LOW), _value(resemblances, TALL)
    return (math.isfinite(round_) and round_ >= ROUND_THRESHOLD and not (math.isfinite(low) and low >= LOW_THRESHOLD)
            and math.isfinite(tall) and tall >= TALL_THRESHOLD)


def decision_margin(resemblances: dict) -> float:
    """How clear the decision was, in [0, 1] (module docstring); NaN without finite resemblances."""
    values = sorted((_value(resemblances, s) for s in SHAPES if s in resemblances), reverse=True)
    if len(values) < 2 or not all(math.isfinite(v) for v in values):
        return math.nan
    lead = values[0] - values[1]
    if FLAT not in resemblances:
        return lead
    flat = _value(resemblances, FLAT)
    if not math.isfinite(flat):
        return math.nan
    # Each rule before the argmax bounds the margin by its own distance from its threshold, and
    # decides it when it fires.
    bound = 2.0 * abs(flat - FLAT_THRESHOLD)
    if flat >= FLAT_THRESHOLD:
        return bound
    slender = _value(resemblances, SLENDER)
    if math.isfinite(slender):
        bound = min(bound, 2.0 * abs(slender - SLENDER_THRESHOLD))
        if slender >= SLENDER_THRESHOLD:
            return bound
    upright = _value(resemblances, UPRIGHT)
    if math.isfinite(upright):
        bound = min(bound, 2.0 * abs(upright - UPRIGHT_THRESHOLD))
        if upright >= UPRIGHT_THRESHOLD:
            return bound
    leader = max((s for s in SHAPES if s in resemblances), key=lambda s: _value(resemblances, s))
    low, round_ = _value(resemblances, LOW), _value(resemblances, ROUND)
    squat = _value(resemblances, SQUAT)
    wide, tall = _value(resemblances, WIDE), _value(resemblances, TALL)
    if leader == "box" and math.isfinite(round_):  # step 3a: roundness decides, lowness if round, then
        # squatness if low, tallness if not, then wideness if not tall
        bound = min(bound, 2.0 * abs(round_ - ROUND_THRESHOLD))
        if round_ >= ROUND_THRESHOLD and math.isfinite(low):
            bound = min(bound, 2.0 * abs(low - LOW_THRESHOLD))
            if low >= LOW_THRESHOLD and math.isfinite(squat):
                bound = min(bound, 2.0 * abs(squat - SQUAT_THRESHOLD))
            elif low < LOW_THRESHOLD:
                if math.isfinite(tall):
                    bound = min(bound, 2.0 * abs(tall - TALL_THRESHOLD))
                if not (math.isfinite(tall) and tall >= TALL_THRESHOLD) and math.isfinite(wide):
                    bound = min(bound, 2.0 * abs(wide - WIDE_THRESHOLD))
    if leader == "sphere" and math.isfinite(low):  # step 3b
        bound = min(bound, 2.0 * abs(low - LOW_THRESHOLD))
    if leader == "cylinder" or (leader == "box" and not (math.isfinite(round_) and round_ >= ROUND_THRESHOLD)):  # 3c
        # Either resemblance fires it: the margin is the larger one's distance from its threshold when
        # one fires, else the nearer one's.
        rules = ((THIN_ROUND, THIN_ROUND_THRESHOLD),) if leader == "box" else ()
        rules += ((THIN_NARROW, THIN_NARROW_THRESHOLD),)
        distances = [(2.0 * abs(v - t), v >= t) for v, t in ((_value(resemblances, k), t) for k, t in rules)
                     if math.isfinite(v)]
        fired = [d for d, fires in distances if fires]
        if fired:
            bound = min(bound, max(fired))
        elif distances:
            bound = min(bound, min(d for d, _ in distances))
    return min(lead, bound)


def choose_with_funnels(resemblances: dict, empty: dict, exclude=()) -> str | None:
    """The chosen shape with the funnel search's veto (module docstring, step 3).

    Args:
        resemblances: {shape: value in [0, 1]}.
        empty: {shape: whether its grasp's funnel on the observed shape is empty}, for the shapes searched.
        exclude: as `choose_shape`'s.
    """
    chosen = choose_shape(resemblances, exclude)
    if chosen is None or chosen in (FLAT, UPRIGHT) or not empty.get(chosen, False):
        return chosen
    open_shapes = [s for s in SHAPES if s in empty and not empty[s] and s not in exclude]
    if not open_shapes:
        return chosen
    vetoed = tuple(exclude) + tuple(s for s in SHAPES if empty.get(s, False))
    return _refined(max(open_shapes, key=lambda s: resemblances.get(s, -1.0)), resemblances, vetoed)
