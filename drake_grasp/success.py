"""The paper's success test, as a pure function of what a trial observed.

The paper (Sec. 5): a grasp succeeds if, after the object is lifted 10 cm off the table, there is no
obvious slip within 10 s. Made precise here (thresholds in the scenario's `protocol`): the object
rose at least half the lift height by the start of the hold, is off the table and still at least
that high at the end, and its pose relative to the palm moved less than `slip_distance` and
`slip_angle_deg` over the hold. A failed grasp is told apart by where it failed: the hand touched
nothing (missed), the object was not lifted (dropped during lift), or it fell or slipped while held.
"""

import dataclasses
import math

# Failure reasons (a trial record's `failure` field; "" is success).
MISSED = "missed"
DROPPED_DURING_LIFT = "dropped during lift"
SLIPPED_DURING_HOLD = "slipped during hold"


@dataclasses.dataclass(frozen=True)
class GraspObservation:
    """What a trial saw of its grasp (SI units: m, rad).

    Attributes:
        touched_after_close: some hand link touched the object when the lift began.
        rise_at_hold: the object's rise above its resting height when the hold began; None if the
            sequence never reached the hold.
        lift_at_end: the object's rise at the end of the hold.
        on_table_at_end: the object touches the table at the end.
        slip_distance: how far the object moved in the palm frame over the hold (nan: no hold).
        slip_angle: how far it turned in the palm frame over the hold (nan: no hold).
    """

    touched_after_close: bool
    rise_at_hold: float | None
    lift_at_end: float
    on_table_at_end: bool
    slip_distance: float
    slip_angle: float


def judge_grasp(observation: GraspObservation, lift_height: float, slip_distance: float,
                slip_angle_deg: float) -> str:
    """The failure reason of a grasp, or "" if it succeeded.

    Args:
        observation: what the trial saw.
        lift_height: how high the arm lifts, m; the object must rise at least half of it.
        slip_distance: the largest slip in the palm frame that still succeeds (exclusive), m.
        slip_angle_deg: the largest rotation in the palm frame that still succeeds (exclusive), deg.
    """
    lifted = observation.rise_at_hold is not None and observation.rise_at_hold >= 0.5 * lift_height
    if not lifted:
        return MISSED if not observation.touched_after_close else DROPPED_DURING_LIFT
    if (observation.on_table_at_end or observation.lift_at_end < 0.5 * lift_height
            or observation.slip_distance >= slip_distance or observation.slip_angle >= math.radians(slip_angle_deg)):
        return SLIPPED_DURING_HOLD
    return ""
