"""Which way the flower grasp faces: F1 and F2 on the side of the object that can take them, else F3
to the right of the arm's reach.

The three-finger flower grasp (`grasps.precision_grasp`) closes F3 against F1 and F2 across the
object's shorter side. F3 meets that side at the palm's centre line; F1 and F2 meet the opposite side
25 mm either side of it (`hand.AW`). The grasp and its half-turn about the approach are the same
grasp only on a shape that is the same on both sides (`grasps.NEAR_SYMMETRIES`), and measurement says
the two differ even there (docs/design.md §5.4f, "Which way it faces"; flower seed 13, true pose,
trial seeds 0-2, each object with the palm as planned and turned half a turn):

* **Where the footprint is not symmetric** (an L), F1 and F2 must both find the object's edge near the
  footprint's side. Every trial in which one of them faced a notch 29-55 mm deep (the inside of the
  L) held 6 of 15; with both on the L's straight side, 15 of 15. `support_gaps` measures, on the
  footprint the camera saw (the table-top height map's columns), how far inside the footprint's side
  each finger's line first meets the object, and `faces_fuller_side` turns the palm when F1 and F2
  would find a deeper gap than they would turned.
* **Where the two sides are alike** (within `FACING_TOLERANCE`), F3 goes to the right of the line
  from the arm's base to the object, seen from above (`thumb_to_the_right`): lying dominoes held 8 of
  15 so and 1 of 15 with F3 to the left, tiles 9 and 6, plates 12 and 11. Why the arm's side matters
  was not traced (the palm pitches and rolls as the WAM lifts, and the arm is not symmetric about its
  reach). The estimate's axes carry no sign (a footprint rectangle's side is a line), so before this
  rule the side was a coin toss: the camera-driven flower grasp held lying dominoes 3/15 where the true
  pose, whose axes the object file fixes, held 8/15.

The two-finger pinch (F1 and F2 opposed at a 90 degree spread, F3 open) follows the second rule too.
Its F3 stays at its preshape, on one side of the pinch line, and the measurement says that side
matters as well (flower seed 19, true pose, as planned and turned: sticks pinched end to end 4/6 with
F3 to the right and 0/6 to the left; 2-3 cm cubes 15/15 and 14/15; standing dominoes 15/15 both. A
2.2 cm cube of seed 23, camera-driven: 3/3 and 0/3).

Pure functions of rotations and points (world frame, m); the palm frame P is the hand base's axes
(`robot.hand`: z along the palm normal, F3 on +y, F1 and F2 at x = -AW and +AW).
"""

from __future__ import annotations

import math

import numpy as np
from pydrake.math import RotationMatrix

from drake_grasp.robot import hand

# Two sides whose deepest finger gaps differ by less than this are alike (m): three cells of the
# table-top height map (3 mm), above its quantisation and the flower's 12 mm landing margin's share.
FACING_TOLERANCE = 0.010
# Half the width of the band about a finger's closing line in which the object's edge is looked for,
# m: half a finger link's width (`hand.FINGER_WIDTH`).
FINGER_BAND = 0.5 * hand.FINGER_WIDTH

HALF_TURN = RotationMatrix.MakeZRotation(math.pi)


def thumb_to_the_right(R_WP: RotationMatrix, reach_xy: np.ndarray) -> RotationMatrix:
    """`R_WP`, or it turned half a turn about its approach (z_P), whichever puts F3 (+y_P) to the right
    of the horizontal direction `reach_xy` (from the arm's base to the object). A palm whose y axis is
    vertical, or a reach of zero length, is returned as it is."""
    reach = np.asarray(reach_xy, float)[:2]
    y = np.array(R_WP.col(1))[:2]
    right = np.array([reach[1], -reach[0]])  # the reach turned a quarter-turn clockwise, seen from above
    side = float(y @ right)
    return R_WP @ HALF_TURN if side < 0.0 else R_WP


def support_gaps(R_WP: RotationMatrix, centre: np.ndarray, footprint_xy: np.ndarray,
                 band: float = FINGER_BAND) -> tuple[float, float]:
    """(F1's and F2's deeper gap, F3's gap), m: for each finger, how far inside the footprint's outline
    on its side (its farthest point along the finger's outward direction) the finger's line first meets
    an occupied cell (`inf` where its band holds none). The lines are the vertical planes of the
    fingers' closing, at x_P = -AW and +AW on the -y_P side (F1, F2) and x_P = 0 on the +y_P side
    (F3), each `band` wide either side.

    Args:
        R_WP: the palm's rotation (its approach vertical, from above).
        centre: the palm centre's horizontal position (x, y or x, y, z), m.
        footprint_xy: the occupied cells' centres (N × 2), m.
    """
    points = np.asarray(footprint_xy, float).reshape(-1, 2) - np.asarray(centre, float)[:2]
    x, y = np.array(R_WP.col(0))[:2], np.array(R_WP.col(1))[:2]
    along, out = points @ x, points @ y  # +out: towards F3
    def gap(offset: float, direction: float) -> float:
        reach = direction * out
        inside = np.abs(along - offset) <= band
        return float(reach.max() - reach[inside].max()) if np.any(inside) else math.inf
    return max(gap(-hand.AW, -1.0), gap(hand.AW, -1.0)), gap(0.0, 1.0)


def faces_fuller_side(R_WP: RotationMatrix, centre: np.ndarray, footprint_xy: np.ndarray,
                      reach_xy: np.ndarray, tolerance: float = FACING_TOLERANCE) -> RotationMatrix:
    """`R_WP` or its half-turn about z_P: the one whose F1 and F2 meet the footprint with the shallower
    gap (`support_gaps`); where the two are within `tolerance`, the one with F3 to the right of the
    reach (`thumb_to_the_right`)."""
    turned = R_WP @ HALF_TURN
    gap, gap_turned = (support_gaps(R, centre, footprint_xy)[0] for R in (R_WP, turned))
    if not (math.isinf(gap) and math.isinf(gap_turned)) and abs(gap - gap_turned) > tolerance:
        return R_WP if gap < gap_turned else turned
    return thumb_to_the_right(R_WP, reach_xy)
