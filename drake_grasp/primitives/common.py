"""What every visual primitive shares: the command it obeys and the names of its ports.

A primitive is a LeafSystem updated periodically at the camera's rate. Its inputs are the latest
`camera_sample` (see `drake_grasp.primitives.silhouette.CameraSample`) and a `command`; its outputs are
a desired camera twist `V_C_desired` ([ω; v] of the camera frame C in the world, expressed in C,
rad/s and m/s; zero when the primitive is off) and its estimates. Whoever runs the primitives (the
exploration sequencer here, a grasp supervisor later) only writes commands; the twists of all
primitives are summed (a Drake Adder) and go to the camera motion controller.
"""


import enum

import numpy as np
from pydrake.systems.framework import Context, LeafSystem

from drake_grasp.primitives.camera_model import arc_angle, arc_command, orbit_twist
from drake_grasp.primitives.silhouette import CameraSample

TWIST_SIZE = 6


class PrimitiveCommand(enum.IntEnum):
    """What a primitive is told to do (the value on its `command` input port)."""

    OFF = 0  # no motion, no estimation; the estimates are held.
    TRACK = 1  # servo (keep the object centred / its axis aligned) and keep estimating; no exploration.
    APPROACH = 2  # TRACK, and move along the optical axis until the object fills a set part of the image.
    EXPLORE = 3  # TRACK, plus the primitive's exploratory arc.
    CONFIRM = 4  # EXPLORE with the arc at once and in the confirming time (the minimal exploration's).

    @property
    def exploring(self) -> bool:
        return self in (PrimitiveCommand.EXPLORE, PrimitiveCommand.CONFIRM)

    @classmethod
    def from_value(cls, value: float) -> "PrimitiveCommand":
        try:
            return cls(int(round(float(value))))
        except ValueError:
            return cls.OFF


class VisualPrimitive(LeafSystem):
    """Base of the primitives: the `camera_sample` and `command` inputs and the `V_C_desired` output.

    Subclasses declare their own state and outputs, and call `DeclareCameraRateUpdate` with their
    update method, which gets (context, discrete_state, sample, command, explore_time).
    `explore_time` is the time since the command last became EXPLORE or CONFIRM (or None when not
    exploring).
    """

    # Layout of the bookkeeping state group: [time of the last sample used, last command,
    # time the command became EXPLORE].
    _BOOK_LAST_TIME, _BOOK_LAST_COMMAND, _BOOK_EXPLORE_START = range(3)

    def __init__(self, period: float):
        super().__init__()
        if not period > 0:
            raise ValueError(f"a primitive's update period must be positive, got {period}")
        self.period = period
        self._camera_sample_port = self.DeclareVectorInputPort("camera_sample", CameraSample.SIZE)
        self._command_port = self.DeclareVectorInputPort("command", 1)
        self._twist_state = self.DeclareDiscreteState(TWIST_SIZE)
        self.DeclareStateOutputPort("V_C_desired", self._twist_state)
        self._bookkeeping = self.DeclareDiscreteState(np.array([-1.0, float(PrimitiveCommand.OFF), 0.0]))
        self._arc = self.DeclareDiscreteState(np.zeros(7))  # [latched, reference view (3), arc axis (3)]

    def DeclareCameraRateUpdate(self) -> None:
        self.DeclarePeriodicDiscreteUpdateEvent(self.period, 0.0, self._Update)

    def _Update(self, context: Context, discrete_state) -> None:
        command = PrimitiveCommand.from_value(self._command_port.Eval(context)[0])
        book = context.get_discrete_state(self._bookkeeping).get_value().copy()
        if command == PrimitiveCommand.OFF and book[self._BOOK_LAST_COMMAND] == PrimitiveCommand.OFF:
            # Off, and off before: the update would write what the state holds (no twist, the same
            # bookkeeping), so leave it. After the exploration every primitive stays here.
            return
        sample = CameraSample.from_vector(self._camera_sample_port.Eval(context))
        t = context.get_time()
        if command.exploring and book[self._BOOK_LAST_COMMAND] != command:
            book[self._BOOK_EXPLORE_START] = t
            discrete_state.get_mutable_vector(self._arc).SetFromVector(np.zeros(7))  # a new arc
        explore_time = t - book[self._BOOK_EXPLORE_START] if command.exploring else None
        new_sample = sample.time > book[self._BOOK_LAST_TIME] + 1e-9
        twist = np.zeros(TWIST_SIZE)
        if command != PrimitiveCommand.OFF:
            twist = self.DoUpdate(context, discrete_state, sample, new_sample, command, explore_time)
        book[self._BOOK_LAST_COMMAND] = float(command)
        if new_sample and command != PrimitiveCommand.OFF:
            book[self._BOOK_LAST_TIME] = sample.time
        discrete_state.get_mutable_vector(self._bookkeeping).SetFromVector(book)
        discrete_state.get_mutable_vector(self._twist_state).SetFromVector(twist)

    def DoUpdate(self, context: Context, discrete_state, sample: CameraSample, new_sample: bool,
                 command: PrimitiveCommand, explore_time: float | None) -> np.ndarray:
        """Updates the estimates (in `discrete_state`) and returns the desired camera twist (6)."""
        raise NotImplementedError

    def ArcTwist(self, discrete_state, sample: CameraSample, pivot_W: np.ndarray, axis_W: np.ndarray,
                 explore_time: float | None, params) -> np.ndarray:
        """The twist of the primitive's exploratory arc: the camera orbits `pivot_W` about `axis_W`.

        `params` has arc_amplitude (rad), arc_period (s), arc_sweeps, arc_start (s after EXPLORE began)
        and arc_gain (1/s). At the arc's start the current view direction (pivot → camera) and the
        axis (made perpendicular to it) are latched; the arc angle follows `arc_command` with a
        proportional correction from the measured angle, so the arc is centred on the start view and
        returns to it whatever the tracking errors.
        """
        arc = discrete_state.get_vector(self._arc).get_value().copy()
        t_arc = None if explore_time is None else explore_time - params.arc_start
        if (t_arc is None or t_arc < 0.0 or t_arc > params.arc_sweeps * params.arc_period
                or not (np.all(np.isfinite(pivot_W)) and np.all(np.isfinite(axis_W)))):
            return np.zeros(6)
        view = sample.p_WC - pivot_W
        view = view / np.linalg.norm(view)
        if arc[0] < 0.5:
            axis = np.asarray(axis_W, float) - float(np.dot(axis_W, view)) * view
            if np.linalg.norm(axis) < 1e-9:
                return np.zeros(6)
            arc = np.concatenate([[1.0], view, axis / np.linalg.norm(axis)])
            discrete_state.get_mutable_vector(self._arc).SetFromVector(arc)
        reference, axis = arc[1:4], arc[4:7]
        phi_desired, rate_desired = arc_command(t_arc, params.arc_amplitude, params.arc_period, params.arc_sweeps)
        rate = rate_desired + params.arc_gain * (phi_desired - arc_angle(view, reference, axis))
        R_CW = sample.R_WC.T
        return orbit_twist(R_CW @ (rate * axis), R_CW @ (pivot_W - sample.p_WC))


def SetDiscreteGroup(discrete_state, index, value) -> None:
    """discrete_state[index] = value (a helper for the update methods)."""
    discrete_state.get_mutable_vector(index).SetFromVector(np.asarray(value, float))

