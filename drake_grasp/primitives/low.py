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
(`primitives.decision`). The height is measured, not inferred from silhouettes: the table-top
estimate's height above the table (as for the flat and upright resemblances, `primitives.flat`,
`primitives.upright`). The resemblance is a logistic step down in that height, 1/2 at `LOW_HEIGHT`,
the fingers' sweep at the spherical spread (10.4 cm), width `LOW_WIDTH`. Where exactly the spherical
grasp starts to hold is not sharp: from the true pose a 9.7 cm tall solid was held 2/2 by it and 1/2
by the flower grasp, but camera-driven the spherical grasp missed it at both seeds; a 9.1 cm one 1/2
and 2/2. The sweep is where the mechanism above says it must fail; the width is a choice.
"""

import math

from drake_grasp.primitives.flat import step_down
from drake_grasp.robot import hand

LOW_HEIGHT = hand.fingertip_sweep_depth(hand.ComplianceMode.SPHERICAL.spread)  # m, 0.104
LOW_WIDTH = 0.004  # m


def low_resemblance(height: float) -> float:
    """The resemblance in [0, 1] of an object standing `height` m above the table; NaN when the height
    is not finite."""
    if not math.isfinite(height):
        return math.nan
    return step_down(float(height), LOW_HEIGHT, LOW_WIDTH)


def table_top_lowness(estimate) -> float:
    """`low_resemblance` of a table-top estimate (`table_top.TableTopEstimate`): its height above the table."""
    return low_resemblance(float(estimate.height))
