"""The exploration sequencer: the state machine that tells each primitive what to do, and when.

Phases (an Enum in abstract state, advanced by a periodic unrestricted update at the camera rate):

    APPROACH    depth: APPROACH (centre the object, bring it to a set image size); axis: TRACK.
    DEPTH_AXIS  depth and principal axis: EXPLORE, in parallel (their arcs are orthogonal).
    RESEMBLANCE depth, axis: TRACK; sphere, cylinder, box: EXPLORE, in parallel.
    DONE        everything OFF (the camera stops; the estimates are held).
    NOT_FOUND   the object was never in view during APPROACH: everything OFF.
    CONFIRM     (minimal exploration only) depth, axis: TRACK; the hypothesis's arc (`hypothesis`):
                its primitive CONFIRM (the arc at once), the box primitive EXPLORE (it records the
                views), the third OFF.

The paper's (full) exploration runs APPROACH, DEPTH_AXIS, RESEMBLANCE, DONE. The minimal exploration
(the paper's proposal, `SequencerParams.minimal` set: the scenario `minimal_exploration`) reads a shape
hypothesis at the end of APPROACH (`hypothesis.hypothesis_from_views`): a flat one is confirmed at once
(DONE); one with a confirming arc runs CONFIRM and is confirmed or not (`hypothesis.confirm`); what is
not confirmed, or has no hypothesis, falls back to DEPTH_AXIS and RESEMBLANCE from where the camera is.

The phases last fixed times (the scenario's `perception:`, diagrams/station.scenarios.yaml): a choice for determinism and a
bounded run time; the primitives' estimates settle well within them. A grasp supervisor can drive
the same primitives through their `command` ports instead of this sequencer.
"""


import dataclasses
import enum
import math
import typing

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import Context, LeafSystem

from drake_grasp.primitives import hypothesis
from drake_grasp.primitives.common import PrimitiveCommand
from drake_grasp.primitives.depth_views import TableTopVector
from drake_grasp.primitives.flat import table_top_flatness
from drake_grasp.primitives.scores import SHAPES
from drake_grasp.primitives.silhouette import CameraSample


class ExplorationPhase(enum.IntEnum):
    APPROACH = 0
    DEPTH_AXIS = 1
    RESEMBLANCE = 2
    DONE = 3
    NOT_FOUND = 4
    CONFIRM = 5

    @property
    def finished(self) -> bool:
        return self in (ExplorationPhase.DONE, ExplorationPhase.NOT_FOUND)


# Commands per phase: (depth, principal axis, resemblance).
_COMMANDS = {
    ExplorationPhase.APPROACH: (PrimitiveCommand.APPROACH, PrimitiveCommand.TRACK, PrimitiveCommand.OFF),
    ExplorationPhase.DEPTH_AXIS: (PrimitiveCommand.EXPLORE, PrimitiveCommand.EXPLORE, PrimitiveCommand.OFF),
    ExplorationPhase.RESEMBLANCE: (PrimitiveCommand.TRACK, PrimitiveCommand.TRACK, PrimitiveCommand.EXPLORE),
    ExplorationPhase.DONE: (PrimitiveCommand.OFF,) * 3,
    ExplorationPhase.NOT_FOUND: (PrimitiveCommand.OFF,) * 3,
    ExplorationPhase.CONFIRM: (PrimitiveCommand.TRACK, PrimitiveCommand.TRACK, PrimitiveCommand.EXPLORE),
}
# The resemblance primitive whose arc confirms a hypothesis (`hypothesis.ARC_OF`): in CONFIRM it gets
# CONFIRM, the box primitive EXPLORE (it records), the other one OFF.
_ARC_OWNER = {"axis": "cylinder", "cross": "sphere"}


@dataclasses.dataclass
class MinimalParams:
    """The minimal exploration's choices (`hypothesis`: why these values).

    Attributes:
        confirm_time: duration of the confirming arc, s.
        elongated: mean eccentricity from above that makes the hypothesis "elongated".
        round: mean eccentricity from above that makes it "round".
        clear: invariance (or sphere score) that confirms; 1 - clear confirms a box.
    """

    confirm_time: float = 2.5
    elongated: float = hypothesis.ELONGATED
    round: float = hypothesis.ROUND
    clear: float = hypothesis.CLEAR

    def validate(self) -> None:
        if not self.confirm_time > 0:
            raise ValueError("sequencer.minimal.confirm_time must be positive")
        if not 1.0 <= self.round < self.elongated:
            raise ValueError("sequencer.minimal: need 1 <= round < elongated")
        if not 0.5 < self.clear <= 1.0:
            raise ValueError("sequencer.minimal.clear must be in (0.5, 1]")


@dataclasses.dataclass
class SequencerParams:
    """ExplorationPhase durations, s (the scenario's `perception:`, diagrams/station.scenarios.yaml)."""

    approach_time: float = 1.5
    depth_axis_time: float = 4.0
    resemblance_time: float = 7.0
    # The minimal exploration (the paper's proposal); None: the paper's full exploration.
    minimal: typing.Optional[MinimalParams] = None

    def validate(self) -> None:
        for name in ("approach_time", "depth_axis_time", "resemblance_time"):
            if not getattr(self, name) > 0:
                raise ValueError(f"sequencer.{name} must be positive")
        if self.minimal is not None:
            self.minimal.validate()

    @property
    def total_time(self) -> float:
        """The longest exploration, s (a minimal one that falls back also runs its confirming arc)."""
        confirm = self.minimal.confirm_time if self.minimal is not None else 0.0
        return self.approach_time + confirm + self.depth_axis_time + self.resemblance_time


@dataclasses.dataclass(frozen=True)
class SequencerState:
    """Attributes: the phase, when it started (s), whether the object has been seen, and the
    start times of every phase entered so far (s)."""

    phase: ExplorationPhase = ExplorationPhase.APPROACH
    phase_start: float = 0.0
    object_seen: bool = False
    phase_starts: tuple[tuple[int, float], ...] = ((int(ExplorationPhase.APPROACH), 0.0),)
    hypothesis: object = None  # the minimal exploration's `hypothesis.Hypothesis` (None: not read yet)
    confirmation: object = None  # and its `hypothesis.Confirmation` (None: not decided yet)

    @property
    def outcome(self) -> dict:
        """What kind of exploration ran, for the record: {"kind": "full" | "confirmed" | "fallback",
        "hypothesis", "why"} (the last two for the minimal exploration)."""
        if self.hypothesis is None:
            return {"kind": "full"}
        c = self.confirmation
        kind = "confirmed" if c is not None and c.confirmed else ("fallback" if c is not None else "minimal")
        return {"kind": kind, "hypothesis": self.hypothesis.kind, "why": "" if c is None else c.why}

    def __deepcopy__(self, memo) -> "SequencerState":
        """Itself: the value is immutable, and Drake copies the whole state at every plant step
        (a generic deep copy of the nested tuples cost about 0.3 s a trial)."""
        return self


class ExplorationSequencer(LeafSystem):
    """Runs the exploration's phases (see the module docstring).

    Input ports:
        camera_sample (25): from SilhouetteCamera (to know whether the object has been seen).
        axis_info (3, minimal exploration): the principal-axis primitive's [elongated, mean
            eccentricity, ...] (the hypothesis reads the mean eccentricity).
        evidence (9, minimal exploration): the box primitive's `scores.ShapeEvidence` vector (it
            records every view of the confirming arc).
        table_top (27, optional): `depth_views.TableTopVector` (the flat hypothesis; none without it).
    Output ports:
        depth_command, axis_command (1 each): PrimitiveCommand values.
        resemblance_command (1): the resemblance primitives' command of the paper's phases.
        sphere_command, cylinder_command, box_command (1 each): each resemblance primitive's own command
            (the same as `resemblance_command` but in CONFIRM).
        phase (1): the ExplorationPhase value.
        camera_active (1): 1 until the exploration is finished, then 0 (for the camera's `active`).
        outcome (abstract dict): `SequencerState.outcome`, what kind of exploration ran.
    """

    def __init__(self, period: float, params: SequencerParams | None = None):
        super().__init__()
        self.params = params or SequencerParams()
        self.params.validate()
        self._camera_sample_port = self.DeclareVectorInputPort("camera_sample", CameraSample.SIZE)
        self._axis_info_port = self.DeclareVectorInputPort("axis_info", 3)
        self._evidence_port = self.DeclareVectorInputPort("evidence", 9)
        self._table_top_port = self.DeclareVectorInputPort("table_top", TableTopVector.SIZE)
        self._state = self.DeclareAbstractState(AbstractValue.Make(SequencerState()))
        ticket = {self.abstract_state_ticket(self._state)}
        for index, name in enumerate(("depth_command", "axis_command", "resemblance_command")):
            self.DeclareVectorOutputPort(name, 1, lambda context, output, i=index: output.SetAtIndex(
                0, float(_COMMANDS[self.state(context).phase][i])), ticket)
        for shape in SHAPES:
            self.DeclareVectorOutputPort(f"{shape}_command", 1, lambda context, output, s=shape: output.SetAtIndex(
                0, float(self.resemblance_command(self.state(context), s))), ticket)
        self.DeclareVectorOutputPort("phase", 1, lambda context, output: output.SetAtIndex(
            0, float(self.state(context).phase)), ticket)
        self.DeclareVectorOutputPort("camera_active", 1, lambda context, output: output.SetAtIndex(
            0, 0.0 if self.state(context).phase.finished else 1.0), ticket)
        self.DeclareAbstractOutputPort("outcome", lambda: AbstractValue.Make({"kind": "full"}),
                                       lambda context, output: output.set_value(self.state(context).outcome), ticket)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._Advance)

    def state(self, context: Context) -> SequencerState:
        return context.get_abstract_state(self._state).get_value()

    @staticmethod
    def resemblance_command(state: SequencerState, shape: str) -> PrimitiveCommand:
        """The command of one resemblance primitive in `state`."""
        if state.phase != ExplorationPhase.CONFIRM:
            return _COMMANDS[state.phase][2]
        if shape == "box":
            return PrimitiveCommand.EXPLORE
        return PrimitiveCommand.CONFIRM if _ARC_OWNER.get(state.hypothesis.arc) == shape else PrimitiveCommand.OFF

    def _Advance(self, context: Context, state) -> None:
        current = self.state(context)
        t = context.get_time()
        seen = current.object_seen or CameraSample.from_vector(self._camera_sample_port.Eval(context)).visible
        elapsed = t - current.phase_start
        p = self.params
        phase, guess, verdict = current.phase, current.hypothesis, current.confirmation
        if phase == ExplorationPhase.APPROACH and elapsed >= p.approach_time - 1e-9:
            if not seen:
                phase = ExplorationPhase.NOT_FOUND
            elif p.minimal is None:
                phase = ExplorationPhase.DEPTH_AXIS
            else:
                guess = self._Hypothesis(context)
                if guess.arc != "none":
                    phase = ExplorationPhase.CONFIRM
                else:
                    verdict = hypothesis.confirm(guess, math.nan, math.nan, p.minimal.clear)
                    phase = ExplorationPhase.DONE if verdict.confirmed else ExplorationPhase.DEPTH_AXIS
        elif phase == ExplorationPhase.CONFIRM and elapsed >= p.minimal.confirm_time - 1e-9:
            evidence = np.asarray(self._evidence_port.Eval(context), float)
            # [V_a, V_b, e0, I_a, I_b, ...]: both invariances 0 only when the arc gave too few views.
            measured = evidence[3] > 0.0 or evidence[4] > 0.0
            verdict = hypothesis.confirm(guess, float(evidence[3]), float(evidence[6]), p.minimal.clear, measured)
            phase = ExplorationPhase.DONE if verdict.confirmed else ExplorationPhase.DEPTH_AXIS
        elif phase == ExplorationPhase.DEPTH_AXIS and elapsed >= p.depth_axis_time - 1e-9:
            phase = ExplorationPhase.RESEMBLANCE
        elif phase == ExplorationPhase.RESEMBLANCE and elapsed >= p.resemblance_time - 1e-9:
            phase = ExplorationPhase.DONE
        if phase != current.phase:
            new = SequencerState(phase, t, seen, current.phase_starts + ((int(phase), t),), guess, verdict)
        else:
            new = dataclasses.replace(current, object_seen=seen)
        state.get_mutable_abstract_state(self._state).set_value(new)

    def _Hypothesis(self, context: Context) -> "hypothesis.Hypothesis":
        """The hypothesis from the approach's views: the axis primitive's mean eccentricity, and the
        flat resemblance of the table-top estimate where there is one."""
        p = self.params.minimal
        flat = math.nan
        if self._table_top_port.HasValue(context):
            top = TableTopVector.from_vector(self._table_top_port.Eval(context)).estimate
            if top is not None:
                flat, _ = table_top_flatness(top)
        eccentricity = float(self._axis_info_port.Eval(context)[1]) if self._axis_info_port.HasValue(context) \
            else math.nan
        return hypothesis.hypothesis_from_views(eccentricity, flat, p.elongated, p.round)


def phase_value(value: float) -> ExplorationPhase:
    """The ExplorationPhase of a `phase` port value."""
    return ExplorationPhase(int(np.round(value)))
