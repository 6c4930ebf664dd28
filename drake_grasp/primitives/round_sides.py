"""The round resemblance: how much an object is round like a ball, from above and at its sides.

The paper's silhouettes cannot tell a ball-like solid from a box: the box resemblance measures how much
the silhouette's area changes under the camera's arcs, and saturates on every irregular solid (the
novel generator's blobs and rings, scans, the PyBullet random objects; docs/results/flower.md). So the
box grasp is chosen for them, and it closes two fingers against one across a solid whose sides curve
away: on the development seeds' blobs taller than the fingers' sweep and rings wider than the flower
grasp lands round, it held 8 of 18 trials from the camera, the spherical grasp, three fingers round
them, 13 (docs/design.md §5.4j).

What tells them apart is a measured shape, from the table-top height map (as for the flat, upright and
low resemblances):

* **round sides**: the map's *edge rise* (`table_top.edge_rise`), how much it rises within 6 mm inside
  the footprint's edge. Seen from above, a vertical side ends in a level top (0-1 mm on the everyday
  generator's boxes, mugs and polycubes, and on real mugs, cups and bowls); a round side curves up from
  the edge (5-29 mm on round solids, rings, blobs and scans 3-24 cm across). A logistic step up, 1/2 at
  `ROUND_RISE` (4 mm), width `ROUND_RISE_WIDTH`;
* **a compact footprint**: its longer side at most `COMPACT_RATIO` (1.6) times its shorter (a ring or a
  ball 1, a lumpy blob up to about 1.5); a banana or a screwdriver lying down has round sides too, and
  the box or cylindrical grasp across its length is the one for it. A logistic step down, width
  `COMPACT_RATIO_WIDTH`.

The resemblance is their product. Both middles are choices between the groups measured.

**Wide** (`wide_resemblance`, behaviour 0.38.0): where the round rule sends a round object to the
spherical grasp, only if its footprint's shorter side is wider than `WIDE_FOOTPRINT` (21 cm), a logistic
step up of width `WIDE_FOOTPRINT_WIDTH`. The box grasp closes across that side; at its standoff
(`grasps.box_grasp`) its proximal links meet the top edges at about 45° up to about 20 cm (the knuckles'
50 mm and the proximal links' 70 mm at 45°, both sides), and wider than that only the distal links
reach the sides. Measured camera-driven, the grasp forced, trial seeds 1-2, one attempt
(docs/results/holding/round_rule.md):

* round generated objects the rule sent to the sphere (novel seeds 1201 and 1301): wider than 22 cm
  (a blob, two rings), the spherical grasp 6/6 and the box grasp 0/6; 14-20 cm, 19/24 each;
* round real files the rule sent to the sphere (19 files: Columbia's scans, GraspIt!'s objects, the
  object_sim set, YCB's pudding box), all under 21 cm but one: the box grasp 22/38, the spherical 16/38
  (it dropped flasks, a cracker box, the bunny and a 1.8 kg sphere that the box grasp held; it held a
  teapot, a pitcher and a coffee can that the box grasp dropped).

So the middle is between the groups measured: 20 cm, where the two grasps tie, and 22 cm, where only
the spherical grasp holds. On 16 YCB models it was not chosen on, the change is even (the six it
touches: the box grasp 8/12, the spherical 9/12).

**Tall and wide** (behaviour 0.50.0): for an object taller than the fingertips' sweep (`low.LOW_HEIGHT`,
10.4 cm), the step's middle moves to `WIDE_TALL_FOOTPRINT` (17 cm), blended by a logistic step up in the
height (width `low.LOW_WIDTH`). The box grasp's fingertips sweep 10.4 cm below the top; on a round solid
taller than that they likely close above its widest line, on sides that slope away under them (a reason
not checked contact by contact), and such solids of 0.3-1 kg slipped out. Measured camera-driven, the
grasp forced, trial seeds 1-2, one attempt, on the round generated objects 13-20 cm tall of novel seeds
1201 and 1301 (behaviour 0.37.0) and 2405-2410 (0.49.0; docs/results/holding/round_rule.md), by the
estimated footprint's shorter side:

* 17-21 cm (11 blobs and unions): the spherical grasp 13/22, the box grasp 4/22;
* 13-17 cm (9 objects): the spherical grasp 15/18, the box grasp 14/18, a tie; and on real files of
  that size the box grasp held what the spherical grasp dropped (GraspIt!'s flasks, 13.6 cm);
* two rings lower than the sweep (8-9 cm tall, 19.5 cm across): both grasps 4/4, so a low object keeps
  21 cm.

So the middle for tall objects is 17 cm, between the tie below (union 2410_008, 16.6 cm: the box grasp
2/2, the spherical 0/2) and the spherical grasp's lead above.

**Tall** (`tall_resemblance`, behaviour 0.53.0): a round object taller than the fingertips' sweep
(`low.LOW_HEIGHT`, 10.4 cm; a logistic step up in the height alone, width `low.LOW_WIDTH`) takes the
cylindrical grasp where the box leads, before the wide step is asked (`primitives.decision`, step 3a).
The cylindrical grasp puts the palm on the top and wraps the fingers round a level axis; the box grasp
stands off a wide top (`grasps.box_grasp`), so its fingertips sweep a few centimetres less far down the
sides, and on a tall round solid they close above its widest line (the mechanism the tall-and-wide step
above names, not checked contact by contact). Measured camera-driven, the grasp forced, one attempt,
trial seeds 1-2, on the blobs and unions of the development seeds 2404-2450 that read round (records:
docs/results/holding/tall_round.md):

* the round rule kept the box (10 large objects 17-24 cm, the box grasp holding 10/20): the cylindrical
  grasp 20/20; on 22 objects 14-20 cm across that the box grasp holds (44/44), the cylindrical 44/44;
* the wide step sent to the sphere (19 objects 18-25 cm): the spherical grasp 24/38, the cylindrical
  27/38; and on fresh seeds 2431-2436 at 0.50.0 (large_fresh in round_rule.md) 17/22 and 16/22.

So it is at least the box's equal where the box holds, beats it where the box slips, and ties the
sphere, which stays second where the wide step asks for it (the cylinder used up).

**Thin and round-sided** (`thin_round_resemblance`): the same round sides without the compact footprint,
on an object lower than `THIN_ROUND_HEIGHT` (3.2 cm) that the flower grasp can land round (its
footprint's shorter side under `low.FLOWER_MAX_WIDTH`). A bar, a tube or an elongated pebble lying
down is not compact, so the round resemblance leaves it to the box grasp, whose fingertips pass 5 mm
above the table; on such objects 2.6-3.2 cm tall the box grasp slipped or missed where the flower grasp,
its tips landed on the table, held (docs/results/holding/thin_band.md). Vertical sides (a brick, a flat
polycube) keep the box grasp, which carries them at 1 kg where the flower grasp drops them. The paper's
banana, round-sided and read 3.65 cm tall, stays above the step.
"""

import math

import numpy as np

from drake_grasp.primitives.flat import step_down
from drake_grasp.primitives.low import low_resemblance, lower_than

ROUND_RISE = 0.004  # m
ROUND_RISE_WIDTH = 0.0007  # m
COMPACT_RATIO = 1.6
COMPACT_RATIO_WIDTH = 0.05
WIDE_FOOTPRINT = 0.21  # m
WIDE_FOOTPRINT_WIDTH = 0.005  # m
WIDE_TALL_FOOTPRINT = 0.17  # m, the middle for an object taller than the fingertips' sweep
THIN_ROUND_HEIGHT = 0.032  # m
THIN_ROUND_HEIGHT_WIDTH = 0.003  # m


def round_resemblance(edge_rise: float, footprint) -> float:
    """The resemblance in [0, 1] of an object whose height map rises `edge_rise` m inside its edge and
    whose footprint spans `footprint` (m, its two horizontal sides); NaN when either is not finite."""
    footprint = np.asarray(footprint, float)
    if not (math.isfinite(edge_rise) and np.all(np.isfinite(footprint))) or np.min(footprint) <= 0.0:
        return math.nan
    ratio = float(np.max(footprint) / np.min(footprint))
    return round_sided(edge_rise) * step_down(ratio, COMPACT_RATIO, COMPACT_RATIO_WIDTH)


def table_top_roundness(estimate) -> float:
    """`round_resemblance` of a table-top estimate (`table_top.TableTopEstimate`): its edge rise and its
    spans along its footprint's sides."""
    return round_resemblance(float(estimate.edge_rise), np.asarray(estimate.extents_sides, float)[:2])


def wide_resemblance(footprint, height: float = math.nan) -> float:
    """How much a footprint spanning `footprint` (m, its two horizontal sides) is wider than the box grasp
    wraps, in [0, 1]: a logistic step up in its shorter side, 1/2 at `WIDE_FOOTPRINT`, or nearer
    `WIDE_TALL_FOOTPRINT` the more the object, `height` m tall, stands above the fingertips' sweep
    (module docstring; a height not known: `WIDE_FOOTPRINT`); NaN when a side is not finite or not
    positive."""
    footprint = np.asarray(footprint, float)
    if footprint.size == 0 or not np.all(np.isfinite(footprint)) or np.min(footprint) <= 0.0:
        return math.nan
    return 1.0 - step_down(float(np.min(footprint)), wide_middle(height), WIDE_FOOTPRINT_WIDTH)


def wide_middle(height: float) -> float:
    """The wide step's middle (m) for an object `height` m tall: `WIDE_FOOTPRINT` below the fingertips'
    sweep, `WIDE_TALL_FOOTPRINT` above it, blended by a logistic step in the height; `WIDE_FOOTPRINT`
    when the height is not finite."""
    if not math.isfinite(height):
        return WIDE_FOOTPRINT
    taller = 1.0 - low_resemblance(float(height))  # no footprint: the height's step alone
    return WIDE_FOOTPRINT + (WIDE_TALL_FOOTPRINT - WIDE_FOOTPRINT) * taller


def table_top_wideness(estimate) -> float:
    """`wide_resemblance` of a table-top estimate (`table_top.TableTopEstimate`): the spans along its
    footprint's sides, and its height."""
    return wide_resemblance(np.asarray(estimate.extents_sides, float)[:2], float(estimate.height))


def tall_resemblance(height: float) -> float:
    """How much an object `height` m tall stands above the fingertips' sweep, in [0, 1]: a logistic step
    up in the height alone, 1/2 at `low.LOW_HEIGHT` (module docstring); NaN when not finite."""
    return 1.0 - low_resemblance(float(height))


def table_top_tallness(estimate) -> float:
    """`tall_resemblance` of a table-top estimate (`table_top.TableTopEstimate`): its height."""
    return tall_resemblance(float(estimate.height))


def round_sided(edge_rise: float) -> float:
    """How much a height map that rises `edge_rise` m inside its edge has round sides, in [0, 1]."""
    return 1.0 - step_down(float(edge_rise), ROUND_RISE, ROUND_RISE_WIDTH)


def thin_round_resemblance(height: float, edge_rise: float, footprint) -> float:
    """The resemblance in [0, 1] of an object `height` m tall, whose height map rises `edge_rise` m
    inside its edge and whose footprint spans `footprint` (m, its two horizontal sides), to a thin
    round-sided one the flower grasp lands round (module docstring); NaN when any is not finite."""
    footprint = np.asarray(footprint, float)
    if not (math.isfinite(height) and math.isfinite(edge_rise) and np.all(np.isfinite(footprint))):
        return math.nan
    return round_sided(edge_rise) * lower_than(height, THIN_ROUND_HEIGHT, THIN_ROUND_HEIGHT_WIDTH, footprint)


def table_top_thin_roundness(estimate) -> float:
    """`thin_round_resemblance` of a table-top estimate (`table_top.TableTopEstimate`)."""
    return thin_round_resemblance(float(estimate.height), float(estimate.edge_rise),
                                  np.asarray(estimate.extents_sides, float)[:2])
