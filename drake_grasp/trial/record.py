"""What one trial measured (`TrialRecord`), and the reasons a trial fails.

A record is plain data: the runner turns it into a CSV row (`sweeps.runner`), the command line
prints it as JSON. Distances in m, angles in rad, times in s.
"""

import dataclasses
import math

from drake_grasp.control.arm_motion import UNREACHABLE
from drake_grasp.primitives.estimate import OBJECT_NOT_FOUND, PERCEPTION_FAILED
from drake_grasp.success import DROPPED_DURING_LIFT, MISSED, SLIPPED_DURING_HOLD

# Failure reasons (the record's `failure` field; its `detail` says more): those of the success test,
# and a simulation that could not be carried out.
SIMULATION_ERROR = "simulation error"
# Every failure reason, including the three that end a sequence before the grasp: the camera never saw
# the object, the estimate of what it saw cannot place a grasp (PERCEPTION_FAILED, re-exported here
# from primitives.estimate, where the supervisor's decision finds it), and the arm cannot reach the grasp.
FAILURES = (MISSED, DROPPED_DURING_LIFT, SLIPPED_DURING_HOLD, OBJECT_NOT_FOUND, PERCEPTION_FAILED, UNREACHABLE,
            SIMULATION_ERROR)


@dataclasses.dataclass
class TrialRecord:
    """Everything a trial measured. Distances in m, angles in rad, times in s."""

    object: str
    method: str
    grasp: str
    seed: int
    success: bool
    failure: str  # "" on success
    lift: float = float("nan")  # object's rise above its resting height at the end
    slip_distance: float = float("nan")  # in the palm frame, over the hold
    slip_angle: float = float("nan")
    contacts_after_close: str = ""  # hand links touching the object when the lift starts
    contacts_at_end: str = ""
    finger_angles: list = dataclasses.field(default_factory=list)  # [spread, prox 1..3, distal 1..3]
    breakaway: list = dataclasses.field(default_factory=list)
    breakaway_angles: list = dataclasses.field(default_factory=list)  # proximal angle at breakaway (nan: none)
    approach_stopped_on_contact: bool = False
    estimate_source: str = ""
    # The seed's variation (protocol.TrialVariation) and, when the spec has one, "estimate_error".
    variation: dict = dataclasses.field(default_factory=dict)
    sim_time: float = 0.0
    wall_time: float = 0.0
    detail: str = ""
    # Camera-driven (compliant) trials: what the visual primitives measured and chose.
    resemblances: dict = dataclasses.field(default_factory=dict)
    chosen_grasp: str = ""
    estimate: dict = dataclasses.field(default_factory=dict)
    estimate_errors: dict = dataclasses.field(default_factory=dict)
    # With the funnel search (funnel.search): each grasp's ε_mean at its primitive's pose and at the
    # widest funnel's centre, the pose executed, the paper's own choice, and the search's cost.
    grasp_search: dict = dataclasses.field(default_factory=dict)
    # Camera-driven trials: what the wrist camera told of the hold at the end (trial.sensing): the
    # robot's own verdict, which decides whether it tries again (the success test is the simulator's).
    sensed: dict = dataclasses.field(default_factory=dict)
    # With more than one attempt (trial.attempts): each attempt's grasp, outcome and sensed verdict, in
    # order; the record's own fields are the last attempt's (times summed over all).
    attempts: list = dataclasses.field(default_factory=list)
    # Planner (eigengrasp) trials: the planned grasp executed, as given or as the planner gave it
    # (None if the arm could reach too few of the planner's grasps).
    planned_grasp: dict | None = None

    def to_dict(self) -> dict:
        """The record as plain data (the command line's JSON); `planned_grasp` only for planner trials."""
        record = dataclasses.asdict(self)
        if self.method != "eigengrasp":
            del record["planned_grasp"]
        return record

    def summary(self) -> str:
        failure = self.failure
        if failure == PERCEPTION_FAILED and self.detail:  # why it failed: it names no phase of the grasp
            failure = f"{failure}: {self.detail}"
        verdict = "SUCCESS" if self.success else f"FAILED ({failure})"
        slip = (f"slip {self.slip_distance * 1000:.1f} mm / {math.degrees(self.slip_angle):.1f} deg"
                if math.isfinite(self.slip_distance) else "no hold")
        lift = f"lift {self.lift * 100:.1f} cm" if math.isfinite(self.lift) else "no lift"
        estimator = self.estimate.get("estimator")
        searched = ", funnel search" if self.grasp_search else ""
        seen = f" ({estimator} estimate{searched})" if estimator else ""
        if len(self.attempts) > 1:
            tried = ", ".join(f"{a['grasp'] or '-'} {'held' if a['success'] else a['failure']}" for a in self.attempts)
            verdict = f"{verdict} after {len(self.attempts)} attempts ({tried})"
        return (f"{self.object} {self.method}/{self.grasp}{seen} seed {self.seed}: {verdict}; {lift}; {slip}; "
                f"touching [{self.contacts_at_end or self.contacts_after_close}]; "
                f"{self.sim_time:.1f} s simulated in {self.wall_time:.1f} s")
