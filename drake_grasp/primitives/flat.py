"""The flat resemblance: how much an object is one of the paper's "flower" objects, thin or small.

The paper's three grasps come from above and close the fingers around the object; its future work
names the region where they cannot reach: small and flat objects that need a precision grasp. From
above, the BarrettHand's fingertips can only close a few millimetres above the table (they would
strike it otherwise), so a plate, a flat T or a stick gives them nothing to close on; and a ball much
smaller than the hand slips out of a grasp made for a fist-sized one.

Flatness and smallness are measured, not inferred from silhouettes: the table-top estimate
(`primitives.table_top`, from the wrist camera's depth views) gives the object's height above the
table and its footprint. The resemblance is the larger of

* thin: a logistic step down in the height h, 1/2 at `THIN_HEIGHT` (2.5 cm: 2 cm thick T and L
  shapes are thin, the paper's sponge and banana, 3.5 and 3.6 cm, are not), with the width
  `THIN_WIDTH`;
* small: the same step in the largest extent, 1/2 at `SMALL_SIZE` (7 cm: balls of 4-6 cm are small,
  the paper's 7.5 cm apple mostly not), width `SMALL_WIDTH`.

Both thresholds are choices, set where the three grasps stop holding (docs/design.md, "The flower").
"""

import math

import numpy as np

THIN_HEIGHT = 0.025  # m
THIN_WIDTH = 0.004  # m
SMALL_SIZE = 0.070  # m
SMALL_WIDTH = 0.007  # m


def step_down(x: float, middle: float, width: float) -> float:
    """1 well below `middle`, 0 well above, 1/2 at it (a logistic of width `width`)."""
    z = (x - middle) / width
    return 1.0 / (1.0 + math.exp(min(z, 700.0)))


def flat_resemblance(height: float, extents: np.ndarray) -> tuple[float, dict]:
    """(resemblance in [0, 1], evidence {"thin", "small"}) of an object `height` m tall whose extents
    (m, any order, the height among them or not) are `extents`."""
    if not (math.isfinite(height) and np.all(np.isfinite(extents))):
        return math.nan, {"thin": math.nan, "small": math.nan}
    size = max(float(np.max(extents)), float(height))
    thin = step_down(float(height), THIN_HEIGHT, THIN_WIDTH)
    small = step_down(size, SMALL_SIZE, SMALL_WIDTH)
    return max(thin, small), {"thin": thin, "small": small}


def table_top_flatness(estimate) -> tuple[float, dict]:
    """`flat_resemblance` of a table-top estimate (`table_top.TableTopEstimate`): its height above the
    table and its spans along its footprint's sides."""
    return flat_resemblance(float(estimate.height), np.asarray(estimate.extents_sides, float))
