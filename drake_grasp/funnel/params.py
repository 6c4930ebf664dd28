"""The funnel search's choices: a part of the scenario (`perception.grasp_search`), apart from the
search itself so that the scenario's schema needs no Drake model."""

import dataclasses
import math


@dataclasses.dataclass
class FunnelParams:
    """Choices of the funnel search (a scenario's `grasp_search`; absent: the primitive's pose, as the paper).

    Attributes:
        yaw_deg: the yaw variants about the approach, ±degrees.
        raise_m: the raised-palm variant, m back along the approach.
        tilt_deg: the tilt variants about the palm's y axis, ±degrees.
        min_spacing, max_spacing: bounds of the neighbourhood's spacing, m.
        spacing_per_uncertainty: the spacing is this many times the estimate's centre uncertainty.
        refine: variants per grasp scored on the 5 × 5 grid.
        min_gain: a pose displaces the primitive's only when its ε_mean exceeds the primitive's by more
            than this fraction (ε differences smaller than that are within what the coarse observed
            shape can tell).
        keep_open_primitive: keep the primitive's own pose whenever its funnel is not empty (ε_mean > 0),
            and search away from it only when it is: the paper's thesis is that the primitive's pose
            lies in the funnel's entrance, and on the objects tried, moving a pose whose funnel was
            open to a wider one lost more holds than it won (docs/results/funnel_search.md).
        keep_cradled_primitive: count the primitive's funnel as open, too, when the hand cradles the
            shape there (`funnel.search.cradles`: every finger under the object's widest line, pushing
            it up into the hand) at most of its neighbourhood's poses, though ε = 0 there: nothing
            presses the object down, so the wrench space holds no downward force, yet under the torque
            close such grasps lift it (docs/design.md §5.4s).
    """

    yaw_deg: float = 15.0
    raise_m: float = 0.015
    tilt_deg: float = 10.0
    min_spacing: float = 0.005
    max_spacing: float = 0.015
    spacing_per_uncertainty: float = 2.0
    refine: int = 2
    min_gain: float = 0.1
    keep_open_primitive: bool = True
    keep_cradled_primitive: bool = True

    def validate(self) -> None:
        for name in ("yaw_deg", "raise_m", "tilt_deg", "spacing_per_uncertainty", "min_gain"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise ValueError(f"grasp_search.{name} must be a non-negative number, got {value}")
        if not (0.001 <= self.min_spacing <= self.max_spacing <= 0.05):
            raise ValueError("grasp_search: need 0.001 <= min_spacing <= max_spacing <= 0.05 m, got "
                             f"{self.min_spacing}, {self.max_spacing}")
        if not 0 <= self.refine <= 20:
            raise ValueError(f"grasp_search.refine must be in [0, 20], got {self.refine}")
