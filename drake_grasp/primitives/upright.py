"""The upright resemblance: how much an object stands on the table like a bottle, taller than wide.

The paper's cylinder resemblance recognises a cylinder lying down: from above its silhouette is a
rectangle whose length stays as the camera arcs along it. A bottle standing up shows a disc from above,
and the silhouettes' area varies as the camera tilts down its side, so the box resemblance saturates
on it (1.0 on every standing bottle measured) and the box grasp closes on its neck and cap, which slip
out during the lift (docs/results/holding_everyday.md). What tells a standing bottle apart is a
measured shape, not a likeness of silhouettes: the table-top estimate's height above the table against
its footprint, as for the flat resemblance (`primitives.flat`).

The resemblance is a logistic step up in the ratio of the height to the footprint's larger side, 1/2 at
`UPRIGHT_RATIO` (1.8: the everyday generator's bottles stand 2-5 times as tall as wide, its mugs and
most boxes less than 1.5), width `UPRIGHT_RATIO_WIDTH`, times a step down in that larger side, 1/2 at
`UPRIGHT_SPAN` (11 cm: what the hand's fingers wrap around; a wider object is not grasped round its
axis). Both are choices.

The slender resemblance picks out, among upright objects, those too thin for that grasp: a peg, a
marker on its end, a vial, and a bottle or box thin one way (a sauce bottle, a juice box). The
cylindrical grasp closes F3 against F1 and F2, which sit 25 mm either side of F3's plane with their pads
from 13.5 mm out: round a standing object thinner than about 2.7 cm they pass either side and F3 alone
meets it, and pushes it over. Measured on standing cylinders 7 and 12 cm tall, the plain command, seeds
1-2 (docs/design.md §5.4o): 1.2-2.6 cm across, the cylindrical grasp 0/12 (missed, or dropped), the
flower grasp (its two-finger pinch) 12/12; 3.0 and 3.5 cm across, the cylindrical grasp held half, at
4 cm all (the flower grasp all six). It is the upright resemblance times a step down in the footprint's
**shorter** side, 1/2 at `SLENDER_SPAN` (3.2 cm, under the pinch's 3.5 cm, `grasps.PINCH_MAX_LENGTH`),
width `SLENDER_SPAN_WIDTH`. Up to behaviour 0.42.0 it was the upright resemblance's ratio step times a
step down in the larger side, so a standing object thin one way only kept the cylindrical grasp, which missed or dropped
Dex-Net's KIT sauce bottle (2.8 × 4.5 cm, 9.2 cm tall) at both seeds and 4 of 20 standing slabs and
elliptic tubes 2.0-3.0 cm thin and 3.9-6.1 cm wide; the flower grasp holds them (its two-finger pinch
where the footprint is under 3.5 cm both ways, else the three-finger flower; docs/design.md §5.4o).
"""

import math

import numpy as np

from drake_grasp.primitives.flat import step_down

UPRIGHT_RATIO = 1.8
UPRIGHT_RATIO_WIDTH = 0.1
UPRIGHT_SPAN = 0.11  # m
UPRIGHT_SPAN_WIDTH = 0.005  # m
SLENDER_SPAN = 0.032  # m
SLENDER_SPAN_WIDTH = 0.001  # m


def _standing_narrower_than(height: float, footprint: np.ndarray, span: float, span_width: float) -> float:
    """The ratio step (height over the footprint's larger side, 1/2 at `UPRIGHT_RATIO`) times a step down
    in that side, 1/2 at `span` (m, width `span_width`); NaN when either input is not finite."""
    footprint = np.asarray(footprint, float)
    if not (math.isfinite(height) and np.all(np.isfinite(footprint))) or height <= 0.0:
        return math.nan
    side = float(np.max(footprint))
    ratio = height / max(side, 1e-6)
    return (1.0 - step_down(ratio, UPRIGHT_RATIO, UPRIGHT_RATIO_WIDTH)) * step_down(side, span, span_width)


def upright_resemblance(height: float, footprint: np.ndarray) -> float:
    """The resemblance in [0, 1] of an object `height` m tall whose footprint spans `footprint` (m, its
    two horizontal sides), NaN when either is not finite."""
    return _standing_narrower_than(height, footprint, UPRIGHT_SPAN, UPRIGHT_SPAN_WIDTH)


def slender_resemblance(height: float, footprint: np.ndarray) -> float:
    """The slender resemblance in [0, 1] of an object `height` m tall whose footprint spans `footprint`
    (m, its two horizontal sides): upright, and thinner one way than the cylindrical grasp closes on
    (module docstring); NaN when either is not finite."""
    upright = upright_resemblance(height, footprint)
    if not math.isfinite(upright):
        return math.nan
    return upright * step_down(float(np.min(np.asarray(footprint, float))), SLENDER_SPAN, SLENDER_SPAN_WIDTH)


def table_top_uprightness(estimate) -> float:
    """`upright_resemblance` of a table-top estimate (`table_top.TableTopEstimate`)."""
    return upright_resemblance(float(estimate.height), np.asarray(estimate.extents_sides, float)[:2])


def table_top_slenderness(estimate) -> float:
    """`slender_resemblance` of a table-top estimate (`table_top.TableTopEstimate`)."""
    return slender_resemblance(float(estimate.height), np.asarray(estimate.extents_sides, float)[:2])
