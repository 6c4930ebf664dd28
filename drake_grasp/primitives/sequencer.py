"""The exploration sequencer: the state machine that tells each primitive what to do, and when.

Phases (an Enum in abstract state, advanced by a periodic unrestricted update at the camera rate):

    APPROACH    depth: APPROACH (centre the object, bring it to a set image size); axis: TRACK.
    DEPTH_AXIS  depth and principal axis: EXPLORE, in parallel (their arcs are orthogonal).
    RESEMBLANCE depth, axis: TRACK; sphere, cylinder, box: EXPLORE, in parallel.
    DONE        everything OFF (the camera stops; the estimates are held).
    NOT_FOUND   the object was never in view during APPROACH: everything OFF.

The phases last fixed times (the scenario's `perception:`, diagrams/station.scenarios.yaml): a choice for determinism and a
bounded run time; the primitives' estimates settle well within them. A grasp supervisor can drive
the same primitives through their `command` ports instead of this sequencer.
"""


import dataclasses
import enum

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import Context, LeafSystem

from drake_grasp.primitives.common import PrimitiveCommand
from drake_grasp.primitives.silhouette import CameraSample


class ExplorationPhase(enum.IntEnum):
    APPROACH = 0
    DEPTH_AXIS = 1
    RESEMBLANCE = 2
    DONE = 3
    NOT_FOUND = 4

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
}


@dataclasses.dataclass
class SequencerParams:
    """ExplorationPhase durations, s (the scenario's `perception:`, diagrams/station.scenarios.yaml)."""

    approach_time: float = 1.5
    depth_axis_time: float = 4.0
    resemblance_time: float = 7.0

    def validate(self) -> None:
        for name in ("approach_time", "depth_axis_time", "resemblance_time"):
            if not getattr(self, name) > 0:
                raise ValueError(f"sequencer.{name} must be positive")

    @property
    def total_time(self) -> float:
        return self.approach_time + self.depth_axis_time + self.resemblance_time


@dataclasses.dataclass(frozen=True)
class SequencerState:
    """Attributes: the phase, when it started (s), whether the object has been seen, and the
    start times of every phase entered so far (s)."""

    phase: ExplorationPhase = ExplorationPhase.APPROACH
    phase_start: float = 0.0
    object_seen: bool = False
    phase_starts: tuple[tuple[int, float], ...] = ((int(ExplorationPhase.APPROACH), 0.0),)

    def __deepcopy__(self, memo) -> "SequencerState":
        """Itself: the value is immutable, and Drake copies the whole state at every plant step
        (a generic deep copy of the nested tuples cost about 0.3 s a trial)."""
        return self


class ExplorationSequencer(LeafSystem):
    """Runs the exploration's phases (see the module docstring).

    Input ports:
        camera_sample (25): from SilhouetteCamera (to know whether the object has been seen).
    Output ports:
        depth_command, axis_command, resemblance_command (1 each): PrimitiveCommand values.
        phase (1): the ExplorationPhase value.
        camera_active (1): 1 until the exploration is finished, then 0 (for the camera's `active`).
    """

    def __init__(self, period: float, params: SequencerParams | None = None):
        super().__init__()
        self.params = params or SequencerParams()
        self.params.validate()
        self._camera_sample_port = self.DeclareVectorInputPort("camera_sample", CameraSample.SIZE)
        self._state = self.DeclareAbstractState(AbstractValue.Make(SequencerState()))
        for index, name in enumerate(("depth_command", "axis_command", "resemblance_command")):
            self.DeclareVectorOutputPort(name, 1, lambda context, output, i=index: output.SetAtIndex(
                0, float(_COMMANDS[self.state(context).phase][i])), {self.abstract_state_ticket(self._state)})
        self.DeclareVectorOutputPort("phase", 1, lambda context, output: output.SetAtIndex(
            0, float(self.state(context).phase)), {self.abstract_state_ticket(self._state)})
        self.DeclareVectorOutputPort("camera_active", 1, lambda context, output: output.SetAtIndex(
            0, 0.0 if self.state(context).phase.finished else 1.0), {self.abstract_state_ticket(self._state)})
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._Advance)

    def state(self, context: Context) -> SequencerState:
        return context.get_abstract_state(self._state).get_value()

    def _Advance(self, context: Context, state) -> None:
        current = self.state(context)
        t = context.get_time()
        seen = current.object_seen or CameraSample.from_vector(self._camera_sample_port.Eval(context)).visible
        elapsed = t - current.phase_start
        p = self.params
        phase = current.phase
        if phase == ExplorationPhase.APPROACH and elapsed >= p.approach_time - 1e-9:
            phase = ExplorationPhase.DEPTH_AXIS if seen else ExplorationPhase.NOT_FOUND
        elif phase == ExplorationPhase.DEPTH_AXIS and elapsed >= p.depth_axis_time - 1e-9:
            phase = ExplorationPhase.RESEMBLANCE
        elif phase == ExplorationPhase.RESEMBLANCE and elapsed >= p.resemblance_time - 1e-9:
            phase = ExplorationPhase.DONE
        if phase != current.phase:
            new = SequencerState(phase, t, seen, current.phase_starts + ((int(phase), t),))
        else:
            new = dataclasses.replace(current, object_seen=seen)
        state.get_mutable_abstract_state(self._state).set_value(new)


def phase_value(value: float) -> ExplorationPhase:
    """The ExplorationPhase of a `phase` port value."""
    return ExplorationPhase(int(np.round(value)))
