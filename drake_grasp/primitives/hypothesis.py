"""The minimal exploration's two decisions: a shape hypothesis from the first views, and its confirmation.

The paper (Sec. 4) calls its exploration a proof of concept and proposes: "first deriving a shape
hypothesis from 2D vision and then confirming this hypothesis through minimal camera motion. If the 2D
hypothesis cannot be confirmed, the robot uses the procedure above to recover." Here, after the
approach (the camera above the object, looking down, `sequencer` APPROACH), the hypothesis is read
from what the approach already measured, and the one motion chosen is the one that tells the
hypothesis from the shape it is most easily confused with:

* **flat** (the table-top estimate's flat resemblance, `primitives.flat`, is at least 1/2): flatness
  is measured from depth, not inferred, so it needs no motion: confirmed at once (the precision
  grasp's choice, `primitives.decision`, is made by the same rule).
* **elongated** (the silhouette's mean eccentricity from above at least `ELONGATED`): from above a
  lying cylinder and a box are both rectangles. The arc *about the object's axis* (the cylinder
  primitive's) tells them apart: a cylinder's silhouette does not change under it, a box's does.
  Confirmed as a cylinder when the invariance about the axis I_a is at least `CLEAR`, as a box when
  it is at most 1 - `CLEAR`; between the two, not confirmed.
* **round** (mean eccentricity at most `ROUND`): a sphere, or an upright cylinder or a cube seen from
  above. The arc *about the cross axis* (the sphere primitive's, a tilt) tells a sphere from both:
  only a sphere's silhouette does not change. Confirmed as a sphere when the sphere score of that one
  arc (`scores.evaluate`'s, with the arc about the axis not travelled) is at least `CLEAR`; otherwise
  not confirmed (an upright cylinder and a cube need the other arc too).
* between `ROUND` and `ELONGATED`: no hypothesis; the full exploration runs.

What is not confirmed falls back to the paper's full exploration from where the camera is. Every
threshold is a choice, stated here and in docs/design.md.

Pure functions: the sequencer (`sequencer.ExplorationSequencer`, minimal mode) calls them.
"""

import dataclasses
import math

from drake_grasp.primitives.decision import FLAT_THRESHOLD

ELONGATED = 1.5  # mean eccentricity from above: clearly elongated (the axis primitive's own test is 1.2)
ROUND = 1.15  # mean eccentricity from above: round (the axis servo acts from 1.15)
CLEAR = 0.7  # an invariance or a sphere score this high (or a box's invariance this low) confirms

FLAT, ELONGATED_SHAPE, ROUND_SHAPE, NONE = "flat", "elongated", "round", "none"
# The arc each hypothesis runs: about the principal axis (the cylinder primitive's), about the cross
# axis (the sphere primitive's), or none.
ARC_OF = {FLAT: "none", ELONGATED_SHAPE: "axis", ROUND_SHAPE: "cross", NONE: "none"}


@dataclasses.dataclass(frozen=True)
class Hypothesis:
    """A shape hypothesis from the first views.

    Attributes:
        kind: "flat", "elongated" (a lying cylinder or a box), "round" (a sphere, or an upright
            cylinder or a cube from above) or "none".
        eccentricity: the silhouette's mean eccentricity over the views it was read from.
        flat: the flat resemblance (NaN without the table-top estimate).
    """

    kind: str
    eccentricity: float
    flat: float = math.nan

    @property
    def arc(self) -> str:
        """The confirming arc: "axis", "cross" or "none"."""
        return ARC_OF[self.kind]


def hypothesis_from_views(mean_eccentricity: float, flat: float = math.nan, elongated: float = ELONGATED,
                          round_: float = ROUND) -> Hypothesis:
    """The hypothesis (module docstring) from the approach's mean eccentricity and the flat resemblance;
    `elongated` and `round_` are the eccentricity thresholds."""
    if math.isfinite(flat) and flat >= FLAT_THRESHOLD:
        return Hypothesis(FLAT, mean_eccentricity, flat)
    if not math.isfinite(mean_eccentricity):
        return Hypothesis(NONE, mean_eccentricity, flat)
    if mean_eccentricity >= elongated:
        return Hypothesis(ELONGATED_SHAPE, mean_eccentricity, flat)
    if mean_eccentricity <= round_:
        return Hypothesis(ROUND_SHAPE, mean_eccentricity, flat)
    return Hypothesis(NONE, mean_eccentricity, flat)


@dataclasses.dataclass(frozen=True)
class Confirmation:
    """The outcome: the confirmed shape (one of the decision's choices) or None, and why, in words."""

    shape: str | None
    why: str

    @property
    def confirmed(self) -> bool:
        return self.shape is not None


def confirm(hypothesis: Hypothesis, invariance_a: float, sphere: float, clear: float = CLEAR,
            measured: bool = True) -> Confirmation:
    """Whether the confirming arc confirmed the hypothesis: `invariance_a` is I_a over the arc about the
    axis, `sphere` the sphere score over the arc about the cross axis (`scores.ShapeEvidence`); `clear`
    the threshold; `measured` False when the arc gathered too few views to score (the scorer then
    gives zero invariances about both axes, which no measured arc does)."""
    if hypothesis.kind == FLAT:
        return Confirmation("flat", f"flat from depth (flat resemblance {hypothesis.flat:.2f})")
    if hypothesis.kind in (ELONGATED_SHAPE, ROUND_SHAPE) and not measured:
        return Confirmation(None, f"{hypothesis.kind}, but the confirming arc gathered too few views to score")
    if hypothesis.kind == ELONGATED_SHAPE:
        if not math.isfinite(invariance_a):
            return Confirmation(None, "elongated, but the arc about its axis measured nothing")
        if invariance_a >= clear:
            return Confirmation("cylinder", f"elongated, invariant about its axis (I_a {invariance_a:.2f})")
        if invariance_a <= 1.0 - clear:
            return Confirmation("box", f"elongated, not invariant about its axis (I_a {invariance_a:.2f})")
        return Confirmation(None, f"elongated, between a cylinder and a box about its axis (I_a {invariance_a:.2f})")
    if hypothesis.kind == ROUND_SHAPE:
        if math.isfinite(sphere) and sphere >= clear:
            return Confirmation("sphere", f"round, invariant under the tilt (sphere {sphere:.2f})")
        return Confirmation(None, f"round from above, but not a sphere under the tilt (sphere {sphere:.2f})")
    return Confirmation(None, f"no hypothesis from the first views (eccentricity {hypothesis.eccentricity:.2f})")
