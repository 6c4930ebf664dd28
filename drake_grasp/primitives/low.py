"""The low resemblance: how much an object stands lower than the spherical grasp can hold it from above.

The paper's spherical grasp comes from above with the fingers 120° apart and closes them round the
object. With the BH8-280's rounded fingertips, a round object lower than about the fingers' sweep
(`hand.fingertip_sweep_depth`, 10.4 cm) is met below its equator: the palm stops above the table by the
sweep, the tips meet the object a centimetre or two above the table, and their squeeze, up and in
from three sides, pops it out between the fingers (docs/design.md §4.1a: the paper's apple). From the
true pose, on 12 low round solids 3.7-9.7 cm tall (fruit and balls, lumpy ellipsoids; docs/design.md
§5.4i), the spherical grasp held 3 of 24 trials, the box grasp 14 and the flower grasp 21: the flower
grasp lands its fingertips on the table around the object and closes from below its equator.

So where the paper's argmax picks the sphere, an object this low takes the flower grasp instead
(`primitives.decision`), if the flower grasp can land round it: the footprint's shorter side at most
`FLOWER_MAX_WIDTH` (15.3 cm: the fingertips' reach at the flower's widest preshape, less its margin,
both sides; `grasps.flower_landing_angle`). A wider one (a 23 cm ring 8 cm tall) keeps the sphere,
which the flower grasp cannot close round. The height is measured, not inferred from silhouettes: the table-top
estimate's height above the table (as for the flat and upright resemblances, `primitives.flat`,
`primitives.upright`). The resemblance is a logistic step down in that height, 1/2 at `LOW_HEIGHT`,
the fingers' sweep at the spherical spread (10.4 cm), width `LOW_WIDTH`. Where exactly the spherical
grasp starts to hold is not sharp: from the true pose a 9.7 cm tall solid was held 2/2 by it and 1/2
by the flower grasp, but camera-driven the spherical grasp missed it at both seeds; a 9.1 cm one 1/2
and 2/2. The sweep is where the mechanism above says it must fail; the width is a choice.
"""

import math

import numpy as np

from drake_grasp.grasps import FLOWER_MARGIN, FLOWER_PRESHAPE_RANGE
from drake_grasp.primitives.flat import step_down
from drake_grasp.robot import hand

LOW_HEIGHT = hand.fingertip_sweep_depth(hand.ComplianceMode.SPHERICAL.spread)  # m, 0.104
LOW_WIDTH = 0.004  # m
FLOWER_MAX_WIDTH = 2.0 * (hand.fingertip_reach(FLOWER_PRESHAPE_RANGE[0], hand.ComplianceMode.CYLINDRICAL.spread)
                          - FLOWER_MARGIN)  # m, 0.153
FLOWER_MAX_WIDTH_WIDTH = 0.005  # m


def lower_than(height: float, middle: float, width: float, footprint) -> float:
    """A logistic step down in `height` (1/2 at `middle`, m), times one in the footprint's shorter side at
    `FLOWER_MAX_WIDTH` (the flower grasp must land round it) where `footprint` is known; NaN when the
    height is not finite."""
    if not math.isfinite(height):
        return math.nan
    step = step_down(float(height), middle, width)
    if footprint is not None and np.all(np.isfinite(np.asarray(footprint, float))):
        step *= step_down(float(np.min(footprint)), FLOWER_MAX_WIDTH, FLOWER_MAX_WIDTH_WIDTH)
    return step


def low_resemblance(height: float, footprint=None) -> float:
    """The resemblance in [0, 1] of an object standing `height` m above the table whose footprint spans
    `footprint` (m, its two horizontal sides; None: not known, no width limit); NaN when the height is
    not finite."""
    return lower_than(height, LOW_HEIGHT, LOW_WIDTH, footprint)


# The squat resemblance (docs/design.md §5.4k): a round object lower than this, that the box leads, takes
# the flower grasp. Its landed fingertips (radius 11.5 mm) close on a round side from the table up, so
# they meet it at or above its widest line when that line is low: on the development seeds' rings
# 2.7-5.1 cm tall and 7.8-15.1 cm across the flower grasp held 11 of 14 trials, the box grasp 19 of 29;
# on round solids 6.2-10 cm tall (low blobs, PyBullet's duck) it held no more than the box grasp. The
# middle between them is a choice.
SQUAT_HEIGHT = 0.055  # m
SQUAT_HEIGHT_WIDTH = 0.003  # m


def squat_resemblance(height: float, footprint=None) -> float:
    """The resemblance in [0, 1] of an object `height` m tall, with `footprint` as `low_resemblance`'s, to
    one the flower grasp's landed fingertips meet at or above its widest line (`SQUAT_HEIGHT`), and
    can land round (`FLOWER_MAX_WIDTH`); NaN when the height is not finite."""
    return lower_than(height, SQUAT_HEIGHT, SQUAT_HEIGHT_WIDTH, footprint)


def table_top_squatness(estimate) -> float:
    """`squat_resemblance` of a table-top estimate (`table_top.TableTopEstimate`)."""
    return squat_resemblance(float(estimate.height), np.asarray(estimate.extents_sides, float)[:2])


def table_top_lowness(estimate) -> float:
    """`low_resemblance` of a table-top estimate (`table_top.TableTopEstimate`): its height above the
    table and its spans along its footprint's sides."""
    return low_resemblance(float(estimate.height), np.asarray(estimate.extents_sides, float)[:2])
