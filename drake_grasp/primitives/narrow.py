"""The thin-narrow resemblance: how much a low object is narrow where the box grasp's fingers close.

The box grasp comes from above with the fingers across the object's principal axis. On an object lower
than the fingers' sweep the palm stops above the table by the sweep (`grasps.TABLE_CLEARANCE`), so the
fingertips meet the object near the bottom of their arc. That bottom lies 46 mm from the palm's centre
line (the proximal joints at 60°, the tips 5 mm above the table: `hand.fingertip_reach`,
`hand.fingertip_depth`). A footprint narrower than twice that is met after it, as the tips rise and
curl in past vertical: at 26 mm out (70°) they are 8 mm up, at 8 mm out (80°) 14 mm. A hammer's
handle, a screwdriver's or a clamp's bar, 2-4 cm across and 2-3.3 cm tall, is then squeezed between
the rounded ends of three curled tips. On the development seed of `objects.tools` (seed 7) the box and
cylindrical grasps, which close the same way from above, held 4 of 12 first attempts; the flower grasp,
its tips landed on the table and sliding in, held 4 of the 7 later attempts it made on those they
failed (docs/results/holding/tools.md). It is the mechanism, not the camera: from the true pose too,
the box grasp dropped a hammer 2.9 cm wide at the grasp and let a 3.3 cm screwdriver slip.

The footprint's own spans do not see it: a hammer's head makes its footprint 8-13 cm wide. So the width
is the height map's across the principal axis within the fingers' band (`table_top.grip_width`). The
resemblance is the product of:

* **thin**: a logistic step down in the height, the thin-round rule's (`round_sides.THIN_ROUND_HEIGHT`,
  3.2 cm: the paper's banana and sponge, read 3.55-3.65 cm tall, stay above), with the flower grasp's
  width limit (`low.lower_than`);
* **narrow**: a logistic step down in the grip width, 1/2 at `NARROW_WIDTH` (5 cm, twice the tips'
  reach at 70°), width `NARROW_WIDTH_WIDTH`. The everyday flat polycubes 2.8-3 cm tall that the box
  grasp carries at 1 kg, and the flower grasp drops (docs/results/holding/thin_band.md), are 7.9-9.8 cm
  wide there.

Where the box or the cylinder remains and this is at least 1/2, the flower grasp is chosen
(`primitives.decision`, step 3c; docs/design.md §5.4m).
"""

import math

import numpy as np

from drake_grasp.primitives.flat import step_down
from drake_grasp.primitives.low import lower_than
from drake_grasp.primitives.round_sides import THIN_ROUND_HEIGHT, THIN_ROUND_HEIGHT_WIDTH

NARROW_WIDTH = 0.05  # m
NARROW_WIDTH_WIDTH = 0.004  # m


def thin_narrow_resemblance(height: float, grip_width: float, footprint) -> float:
    """The resemblance in [0, 1] of an object `height` m tall whose footprint is `grip_width` m wide where
    the box grasp's fingers close and spans `footprint` (m, its two horizontal sides); NaN when the
    height or the grip width is not finite."""
    if not (math.isfinite(height) and math.isfinite(grip_width)):
        return math.nan
    return lower_than(height, THIN_ROUND_HEIGHT, THIN_ROUND_HEIGHT_WIDTH, footprint) \
        * step_down(float(grip_width), NARROW_WIDTH, NARROW_WIDTH_WIDTH)


def table_top_thin_narrowness(estimate) -> float:
    """`thin_narrow_resemblance` of a table-top estimate (`table_top.TableTopEstimate`)."""
    return thin_narrow_resemblance(float(estimate.height), float(estimate.grip_width),
                                   np.asarray(estimate.extents_sides, float)[:2])
