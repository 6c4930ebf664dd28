"""The BarrettHand's torque-close controller with the TorqueSwitch (breakaway) clutch.

On the real hand one motor drives both joints of a finger: in free motion the distal joint turns at
1/3 of the proximal rate (125:1 and 375:1 gears). When the torque on the proximal joint exceeds the
breakaway torque the clutch slips: the proximal joint holds its angle (its worm drive cannot be
back-driven) and the distal joint keeps closing, 4 times faster per motor turn, until it touches the
object or its 48 deg limit. If the distal link is stopped first, the motor stalls and the whole finger
stops. A stopped finger keeps squeezing with its stall torque. Reopening re-engages the clutch.
A gentle close (HandAction.GENTLE_CLOSE) keeps the motor's torque under the clutch's breakaway torque:
each finger stops, coupled, at its first contact and squeezes lightly there (the flower grasp's close,
whose fingertips meet a thin object's edge at the table and must not curl over it); in the lift that
follows (HandAction.SQUEEZE) a squeezing finger's motor rises to the lift's torque, still under the
clutch's, so that the squeeze also carries the object's weight, and the hold (HandAction.HOLD) keeps
the commands where the lift left them. A gentle pinch
(HandAction.GENTLE_PINCH) closes F1 and F2 so while F3 stays where its preshape put it (the flower
grasp's two-finger pinch of a small object, F1 and F2 opposed at a 90 deg spread).
Spread (F1 and F2, one motor) goes to the compliance mode's angle before the fingers close.

How it is simulated (docs/design.md §5.3): every finger joint has an implicit PD actuator in the plant
(stable at large gains and time steps); this controller turns the motor model into the desired joint
states those actuators track. Torque close is a *position lead*: a joint's command runs ahead of where
the joint will be at the next step (its measured angle plus its measured closing velocity times the
period) by at most ``lead = stall_torque / kp``, so a blocked joint is pushed with exactly its stall
torque while a free one follows the motor at full speed. Breakaway is detected from the *torque*: the actuation the plant applies on the proximal
joint (its ``net_actuation`` output) exceeding ``breakaway_torque``, as on the real clutch — not from a
stall detector.

The clutch logic is the pure function `advance_drive` (on the drive's flat vector of floats, as the
controller stores it; `advance_fingers` is the same on a `FingerDrive`); `HandController` is the thin
LeafSystem around it.
"""



import dataclasses
import math

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex, PdControllerGains
from pydrake.systems.framework import Context, DiscreteValues, LeafSystem

from drake_grasp.robot import hand
from drake_grasp.robot.hand import HAND_JOINTS, HandAction

NUM_FINGERS = 3

# Under HandAction.SQUEEZE a finger counts as squeezing (blocked by the object) while its command leads
# its measured angle by at least this share of the gentle close's lead: a finger at rest on nothing sits
# at its command (no lead), one stalled on the object leads by the whole gentle lead.
SQUEEZING_LEAD_SHARE = 0.8


@dataclasses.dataclass
class HandControllerParams:
    """Choices of the simulated hand drive (the facts are in `drake_grasp.robot.hand`).

    Attributes:
        breakaway_torque: proximal torque at which the clutch slips, N*m (GraspIt!: 0.5).
        proximal_drive_torque: largest torque the motor puts on a blocked proximal joint before
            breakaway, N*m. Must exceed `breakaway_torque`, or the clutch could never slip.
        distal_squeeze_torque: torque of a stalled distal joint, N*m; 0.75 N*m is a 15 N fingertip
            force at A3 = 50 mm (docs/design.md §4.1: 15-25 N, assumed).
        gentle_close_torque: the motor's torque on a blocked proximal joint under HandAction.GENTLE_CLOSE,
            N*m, under `breakaway_torque` so that the clutch never slips: each finger stops, coupled,
            at its first contact and squeezes there. The BH8's stalled fingertip force before
            breakaway is set by the commanded velocity and the motor's current limit (BH8-Series
            User's Manual, D3000 AF.00, §9.3.1, Figure 25: about 2-22 N). The distal joint's stall
            torque scales with it (one motor drives both). 0.3 N*m is about 4 N at the fingertip.
        lift_squeeze_torque: the motor's torque on a squeezing finger under HandAction.SQUEEZE (the
            gentle close's lift), N*m, between `gentle_close_torque` and `breakaway_torque`. The close
            stops each finger lightly at its first contact; while the object is lifted the motor's
            current rises so that the squeeze carries its weight as well: a few newtons at the
            fingertips are friction for 0.2-0.3 kg, not for a 0.5 kg part or a model file's 1 kg
            placeholder (docs/design.md §5.4f, "The firm lift"). 0.45 N*m is about 6 N at the
            fingertip, 10 % under the clutch's breakaway.
        spread_torque: stall torque of the spread drive, N*m (assumed).
        closing_time: time for a free proximal joint to go from open to its 140 deg limit, s.
        spread_time: time for the spread to go end to end (180 deg), s.
        proximal_gains, distal_gains, spread_gains: (kp N*m/rad, kd N*m*s/rad) of the joint PD actuators.
        period: controller update period, s.
    """

    breakaway_torque: float = hand.BREAKAWAY_TORQUE
    proximal_drive_torque: float = 1.0
    distal_squeeze_torque: float = hand.FINGERTIP_STALL_FORCE * hand.A3
    gentle_close_torque: float = 0.3
    lift_squeeze_torque: float = 0.45
    spread_torque: float = 1.0
    closing_time: float = 1.0
    spread_time: float = 0.5
    proximal_gains: list[float] = dataclasses.field(default_factory=lambda: [200.0, 0.6])
    distal_gains: list[float] = dataclasses.field(default_factory=lambda: [10.0, 0.04])
    spread_gains: list[float] = dataclasses.field(default_factory=lambda: [10.0, 0.3])
    period: float = 0.005

    def __post_init__(self):
        for name in ("breakaway_torque", "proximal_drive_torque", "distal_squeeze_torque", "gentle_close_torque",
                     "lift_squeeze_torque", "spread_torque",
                     "closing_time", "spread_time", "period"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"hand controller: {name} must be a positive number, got {value}")
        if self.proximal_drive_torque <= self.breakaway_torque:
            raise ValueError(
                "hand controller: proximal_drive_torque must exceed breakaway_torque "
                f"({self.proximal_drive_torque} <= {self.breakaway_torque}), or the clutch never slips"
            )
        if self.gentle_close_torque >= self.breakaway_torque:
            raise ValueError(
                "hand controller: gentle_close_torque must be under breakaway_torque "
                f"({self.gentle_close_torque} >= {self.breakaway_torque}), or a gentle close breaks away"
            )
        if not self.gentle_close_torque <= self.lift_squeeze_torque < self.breakaway_torque:
            raise ValueError(
                "hand controller: lift_squeeze_torque must be at least gentle_close_torque and under "
                f"breakaway_torque ({self.gentle_close_torque} <= {self.lift_squeeze_torque} < "
                f"{self.breakaway_torque}), or the lift loosens the squeeze or breaks away"
            )

    @property
    def proximal_speed(self) -> float:
        """Proximal closing rate of the free finger, rad/s."""
        return hand.PROXIMAL_LIMITS[1] / self.closing_time

    @property
    def spread_speed(self) -> float:
        """Spread rate, rad/s."""
        return (hand.SPREAD_LIMITS[1] - hand.SPREAD_LIMITS[0]) / self.spread_time

    @property
    def proximal_lead(self) -> float:
        return self.proximal_drive_torque / self.proximal_gains[0]

    @property
    def distal_lead(self) -> float:
        return self.distal_squeeze_torque / self.distal_gains[0]

    @property
    def gentle_proximal_lead(self) -> float:
        return self.gentle_close_torque / self.proximal_gains[0]

    @property
    def gentle_distal_lead(self) -> float:
        """The distal joint's lead under a gentle close: its stall torque scaled as the motor's."""
        return self.distal_lead * self.gentle_close_torque / self.proximal_drive_torque

    @property
    def lift_squeeze_lead(self) -> float:
        """A squeezing finger's proximal lead under HandAction.SQUEEZE: its torque over the PD gain."""
        return self.lift_squeeze_torque / self.proximal_gains[0]

    @property
    def spread_lead(self) -> float:
        return self.spread_torque / self.spread_gains[0]


# Layout of FingerDrive's vector form: where each field starts.
_SPREAD, _SPREAD_RATE, _PROXIMAL, _DISTAL, _BROKEN, _ANGLE, _PROXIMAL_RATE, _DISTAL_RATE = (
    0, 1, 2, 2 + NUM_FINGERS, 2 + 2 * NUM_FINGERS, 2 + 3 * NUM_FINGERS, 2 + 4 * NUM_FINGERS, 2 + 5 * NUM_FINGERS)


@dataclasses.dataclass
class FingerDrive:
    """State of the three finger drives and the spread drive (all angles in rad).

    Attributes:
        spread: spread command (both F1 and F2).
        proximal: proximal joint commands; after breakaway, the angle the proximal joint holds.
        distal: distal joint commands.
        broken_away: whether each finger's clutch has slipped.
        breakaway_angle: the proximal angle at which each clutch slipped (nan if it has not).
        spread_rate, proximal_rate, distal_rate: the commands' rates in the last update, rad/s
            (the desired velocities of the PD actuators).
    """

    spread: float = 0.0
    proximal: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(NUM_FINGERS))
    distal: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(NUM_FINGERS))
    broken_away: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(NUM_FINGERS, bool))
    breakaway_angle: np.ndarray = dataclasses.field(default_factory=lambda: np.full(NUM_FINGERS, np.nan))
    spread_rate: float = 0.0
    proximal_rate: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(NUM_FINGERS))
    distal_rate: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(NUM_FINGERS))

    # Size of the flat vector form (the LeafSystem's discrete state; layout: the _SPREAD... offsets).
    SIZE = _DISTAL_RATE + NUM_FINGERS

    def to_vector(self) -> np.ndarray:
        return np.concatenate([
            [self.spread, self.spread_rate], self.proximal, self.distal, self.broken_away.astype(float),
            self.breakaway_angle, self.proximal_rate, self.distal_rate,
        ])

    @classmethod
    def from_vector(cls, x: np.ndarray) -> "FingerDrive":
        x = np.asarray(x, dtype=float)
        f = NUM_FINGERS
        return cls(
            spread=float(x[_SPREAD]), spread_rate=float(x[_SPREAD_RATE]),
            proximal=x[_PROXIMAL:_PROXIMAL + f].copy(), distal=x[_DISTAL:_DISTAL + f].copy(),
            broken_away=x[_BROKEN:_BROKEN + f] > 0.5, breakaway_angle=x[_ANGLE:_ANGLE + f].copy(),
            proximal_rate=x[_PROXIMAL_RATE:_PROXIMAL_RATE + f].copy(),
            distal_rate=x[_DISTAL_RATE:_DISTAL_RATE + f].copy(),
        )


def _clip(x: float, lo: float, hi: float) -> float:
    """numpy.clip of one float, to the bit (NaN passes through; the lower bound wins a tie)."""
    if x != x:
        return x
    x = x if x > lo else lo
    return x if x < hi else hi


def _maximum(a: float, b: float) -> float:
    """numpy.maximum of two floats, to the bit (a when equal or NaN)."""
    return a if (a >= b or a != a) else b


def advance_drive(
    x: list[float],
    spread_target: float,
    action: HandAction,
    spread_measured: float,
    proximal_measured: list[float],
    distal_measured: list[float],
    proximal_torque: list[float],
    proximal_velocity: list[float],
    distal_velocity: list[float],
    params: HandControllerParams,
    dt: float,
    preshape=None,
) -> list[float]:
    """`advance_fingers` on FingerDrive's flat vector form, with plain floats: the same arithmetic
    in the same order (the same numbers to the bit), without building arrays of three numbers.

    It runs at every plant step (200 Hz), so it is written for speed: with a FingerDrive and numpy's
    small-array calls one update took about 180 us, on floats about 30 us (docs/performance.md).
    """
    F = NUM_FINGERS
    w_p = params.proximal_speed
    w_d_coupled = w_p * hand.DISTAL_PER_PROXIMAL
    w_d_free = w_d_coupled * hand.BREAKAWAY_SPEEDUP
    ratio = hand.DISTAL_PER_PROXIMAL
    proximal_lead, distal_lead, spread_lead = params.proximal_lead, params.distal_lead, params.spread_lead
    lo_s, hi_s = hand.SPREAD_LIMITS
    spread_target = _clip(float(spread_target), lo_s, hi_s)

    # Spread first: it moves toward the mode's angle, never leading the joint by more than its lead.
    spread_before = x[_SPREAD]
    max_step = params.spread_speed * dt
    spread = spread_before + _clip(spread_target - spread_before, -max_step, max_step)
    spread = _clip(spread, spread_measured - spread_lead, spread_measured + spread_lead)
    spread_ready = abs(spread_measured - spread_target) < math.radians(2.0) and spread == spread_target

    # Where each joint will be at the next update if it keeps closing as it does now.
    proximal_next = [q + _maximum(v, 0.0) * dt for q, v in zip(proximal_measured, proximal_velocity)]
    distal_next = [q + _maximum(v, 0.0) * dt for q, v in zip(distal_measured, distal_velocity)]
    proximal_before = x[_PROXIMAL:_PROXIMAL + F]
    distal_before = x[_DISTAL:_DISTAL + F]
    proximal, distal = list(proximal_before), list(distal_before)
    broken = [b > 0.5 for b in x[_BROKEN:_BROKEN + F]]
    angle = list(x[_ANGLE:_ANGLE + F])
    if action in (HandAction.CLOSE, HandAction.GENTLE_CLOSE, HandAction.GENTLE_PINCH) and spread_ready:
        # A gentle close keeps the motor's torque under the clutch's: smaller leads, and no breakaway.
        # A gentle pinch closes F1 and F2 so and leaves F3's commands where they are.
        gentle = action != HandAction.CLOSE
        lead_p = params.gentle_proximal_lead if gentle else proximal_lead
        lead_d = params.gentle_distal_lead if gentle else distal_lead
        for f in range(F - 1 if action == HandAction.GENTLE_PINCH else F):
            if not gentle and not broken[f] and proximal_torque[f] > params.breakaway_torque:
                # The clutch slips: the proximal joint holds where it is; the distal keeps closing.
                broken[f] = True
                angle[f] = proximal_measured[f]
                proximal[f] = proximal_measured[f]
            if broken[f]:
                distal[f] = min(distal[f] + w_d_free * dt, distal_next[f] + lead_d)
            else:
                # One motor turns both joints: it stalls as soon as either joint is blocked.
                proximal[f] = min(proximal[f] + w_p * dt, proximal_next[f] + lead_p,
                                  (distal_next[f] + lead_d) / ratio)
                distal[f] = proximal[f] * ratio
    elif action == HandAction.PRESHAPE and spread_ready:
        lo_p, hi_p = hand.PROXIMAL_LIMITS
        for f in range(F):
            target = _clip(float(preshape[f]), lo_p, hi_p)
            if target >= proximal[f]:
                proximal[f] = min(proximal[f] + w_p * dt, target, proximal_next[f] + proximal_lead,
                                  (distal_next[f] + distal_lead) / ratio)
            else:
                proximal[f] = max(proximal[f] - w_p * dt, target)
            distal[f] = proximal[f] * ratio
        broken, angle = [False] * F, [math.nan] * F
    elif action == HandAction.OPEN:
        # Reopen at the closing speeds, distal first back onto the coupled ratio; re-engage the clutch.
        open_limit = hand.PROXIMAL_LIMITS[0] - proximal_lead
        for f in range(F):
            proximal[f] = _maximum(_maximum(proximal[f] - w_p * dt, open_limit), proximal_measured[f] - proximal_lead)
            distal[f] = _maximum(_maximum(distal[f] - w_d_free * dt, proximal[f] * ratio),
                                 distal_measured[f] - distal_lead)
        broken, angle = [False] * F, [math.nan] * F
    elif action == HandAction.SQUEEZE:
        # A finger that squeezes (SQUEEZING_LEAD_SHARE) squeezes with the lift's torque; the others keep
        # their commands (F3 left at its preshape by a pinch, a finger that closed on nothing).
        squeezing_lead = SQUEEZING_LEAD_SHARE * params.gentle_proximal_lead
        for f in range(F):
            if not broken[f] and proximal[f] - proximal_measured[f] >= squeezing_lead:
                proximal[f] = _maximum(proximal[f], proximal_measured[f] + params.lift_squeeze_lead)
                distal[f] = proximal[f] * ratio
    # HOLD, or CLOSE while the spread is still moving: commands stay (a squeezing finger squeezes on).
    return ([spread, (spread - spread_before) / dt] + proximal + distal + [1.0 if b else 0.0 for b in broken]
            + angle + [(p - p0) / dt for p, p0 in zip(proximal, proximal_before)]
            + [(d - d0) / dt for d, d0 in zip(distal, distal_before)])


def advance_fingers(
    drive: FingerDrive,
    spread_target: float,
    action: HandAction,
    spread_measured: float,
    proximal_measured: np.ndarray,
    distal_measured: np.ndarray,
    proximal_torque: np.ndarray,
    proximal_velocity: np.ndarray,
    distal_velocity: np.ndarray,
    params: HandControllerParams,
    dt: float,
    preshape: np.ndarray | None = None,
) -> FingerDrive:
    """One update of the motor and clutch model. Pure: returns a new FingerDrive.

    Args:
        drive: the state after the previous update.
        spread_target: the compliance mode's spread angle, rad.
        action: open, close or hold.
        spread_measured: the mean of the two spread joint angles, rad.
        proximal_measured, distal_measured: joint angles of F1, F2, F3, rad.
        proximal_torque: actuation torque on each proximal joint, N*m (positive closes).
        proximal_velocity, distal_velocity: joint velocities, rad/s.
        preshape: with HandAction.PRESHAPE, the proximal angle (rad) each finger goes to, the
            distal following at a third of it (the clutch stays engaged; a blocked finger stalls).
        params: drive parameters.
        dt: time since the previous update, s.
    """
    def floats(a):
        return np.asarray(a, float).tolist()

    return FingerDrive.from_vector(advance_drive(
        floats(drive.to_vector()), spread_target, action, float(spread_measured), floats(proximal_measured),
        floats(distal_measured), floats(proximal_torque), floats(proximal_velocity), floats(distal_velocity),
        params, dt, None if preshape is None else floats(preshape)))


class HandController(LeafSystem):
    """Torque close with breakaway for the BarrettHand, as desired states for its PD actuators.

    Input ports:
        command: [spread target (rad), action (HandAction as a number)].
        finger_preshape: proximal angle of each finger for HandAction.PRESHAPE, rad (read only then:
            it may stay unconnected otherwise).
        hand_state: the hand model instance's state [q; v] (plant.get_state_output_port(hand)).
        hand_net_actuation: the hand's applied actuation (plant.get_net_actuation_output_port(hand)).
    Output ports:
        hand_desired_state: [qd; vd] in the hand's actuator order (plant.get_desired_state_input_port).
        finger_status: [broken_away (3, 0 or 1), breakaway_angle (3, rad, nan before breakaway)].

    Both outputs are functions of the drive alone; each update stores them as discrete state beside
    the drive, so that the ports are Drake's state output ports (read at every plant step without
    calling back into Python).
    """

    def __init__(self, plant: MultibodyPlant, hand_instance: ModelInstanceIndex,
                 params: HandControllerParams | None = None):
        super().__init__()
        self._params = params or HandControllerParams()
        self._index = HandIndexing(plant, hand_instance)
        num_q = plant.num_positions(hand_instance)
        num_v = plant.num_velocities(hand_instance)
        self._command_port = self.DeclareVectorInputPort("command", 2)
        self._preshape_port = self.DeclareVectorInputPort("finger_preshape", NUM_FINGERS)
        self._state_port = self.DeclareVectorInputPort("hand_state", num_q + num_v)
        self._actuation_port = self.DeclareVectorInputPort("hand_net_actuation", plant.num_actuators(hand_instance))
        initial = FingerDrive().to_vector().tolist()
        desired, status = self._outputs_of(initial)
        self._drive_index = self.DeclareDiscreteState(initial)
        self._desired_index = self.DeclareDiscreteState(desired)
        self._status_index = self.DeclareDiscreteState(status)
        self.DeclarePeriodicDiscreteUpdateEvent(self._params.period, 0.0, self._Update)
        self.DeclareStateOutputPort("hand_desired_state", self._desired_index)
        self.DeclareStateOutputPort("finger_status", self._status_index)

    @property
    def params(self) -> HandControllerParams:
        return self._params

    def SetInitialFingers(self, context: Context, spread: float = 0.0) -> None:
        """Starts the drive at an open hand with the given spread (rad)."""
        drive = FingerDrive(spread=spread).to_vector().tolist()
        desired, status = self._outputs_of(drive)
        context.SetDiscreteState(self._drive_index, drive)
        context.SetDiscreteState(self._desired_index, desired)
        context.SetDiscreteState(self._status_index, status)

    def _Update(self, context: Context, discrete_state: DiscreteValues) -> None:
        spread_target, action_value = self._command_port.Eval(context).tolist()
        action = HandAction(int(round(action_value)))
        q, v = self._index.positions_and_velocities(self._state_port.Eval(context))
        proximal_torque = self._index.proximal_actuation(self._actuation_port.Eval(context))
        preshape = self._preshape_port.Eval(context).tolist() if action == HandAction.PRESHAPE else None
        drive = advance_drive(
            context.get_discrete_state(self._drive_index).value().tolist(),
            spread_target=spread_target,
            action=action,
            spread_measured=(q[0] + q[1]) / 2.0,  # their mean (numpy's np.mean, to the bit)
            proximal_measured=q[2:5],
            distal_measured=q[5:8],
            proximal_torque=proximal_torque,
            proximal_velocity=v[2:5],
            distal_velocity=v[5:8],
            params=self._params,
            dt=self._params.period,
            preshape=preshape,
        )
        desired, status = self._outputs_of(drive)
        discrete_state.set_value(self._drive_index, drive)
        discrete_state.set_value(self._desired_index, desired)
        discrete_state.set_value(self._status_index, status)

    def joint_angles(self, hand_state: np.ndarray) -> np.ndarray:
        """The hand's joint angles in HAND_JOINTS.all order (rad), from its instance state [q; v]."""
        return self._index.joint_positions(hand_state)

    def _outputs_of(self, drive: list[float]) -> tuple[np.ndarray, list[float]]:
        """The outputs for a drive vector: the desired state [qd; vd] in actuator order, and the
        finger status [broken_away (3), breakaway_angle (3)]."""
        F = NUM_FINGERS
        spread, spread_rate = drive[_SPREAD], drive[_SPREAD_RATE]
        joints = ([spread, spread] + drive[_PROXIMAL:_PROXIMAL + F] + drive[_DISTAL:_DISTAL + F]
                  + [spread_rate, spread_rate] + drive[_PROXIMAL_RATE:_PROXIMAL_RATE + F]
                  + drive[_DISTAL_RATE:_DISTAL_RATE + F])
        return self._index.to_actuator_order(joints), drive[_BROKEN:_ANGLE + F]


class HandIndexing:
    """Maps the controller's joint order (HAND_JOINTS.all) to the plant's per-instance orders (the hand
    controller's, and the grasp executor's reading of the proximal angles)."""

    def __init__(self, plant: MultibodyPlant, hand_instance: ModelInstanceIndex):
        joints = [plant.GetJointByName(name, hand_instance) for name in HAND_JOINTS.all]
        instance_q_starts = sorted(
            plant.get_joint(j).position_start() for j in plant.GetJointIndices(hand_instance)
            if plant.get_joint(j).num_positions() > 0
        )
        instance_v_starts = sorted(
            plant.get_joint(j).velocity_start() for j in plant.GetJointIndices(hand_instance)
            if plant.get_joint(j).num_velocities() > 0
        )
        self._num_q = plant.num_positions(hand_instance)
        self._q_rows = np.array([instance_q_starts.index(j.position_start()) for j in joints])
        self._v_rows = np.array([instance_v_starts.index(j.velocity_start()) for j in joints])
        self._qv_rows = np.concatenate([self._q_rows, self._num_q + self._v_rows])
        actuators = sorted(plant.GetJointActuatorIndices(hand_instance), key=int)
        actuated_joints = [plant.get_joint_actuator(a).joint().name() for a in actuators]
        self.num_actuators = len(actuators)
        self._actuator_rows = np.array([actuated_joints.index(name) for name in HAND_JOINTS.all])
        self._proximal_actuator_rows = self._actuator_rows[2:5]
        # to_actuator_order as one gather: output k takes joints[order[k]]; the last slot is a 0
        # (an actuator that is not one of HAND_JOINTS.all gets no command).
        num_joints = len(HAND_JOINTS.all)
        order = np.full(2 * self.num_actuators, 2 * num_joints)
        order[self._actuator_rows] = np.arange(num_joints)
        order[self.num_actuators + self._actuator_rows] = num_joints + np.arange(num_joints)
        self._desired_order = order

    def joint_positions(self, hand_state: np.ndarray) -> np.ndarray:
        return np.asarray(hand_state)[self._q_rows]

    def positions_and_velocities(self, hand_state: np.ndarray) -> tuple[list[float], list[float]]:
        """The joint angles and velocities in HAND_JOINTS.all order, as lists of floats."""
        qv = hand_state[self._qv_rows].tolist()
        n = len(self._q_rows)
        return qv[:n], qv[n:]

    def proximal_actuation(self, net_actuation: np.ndarray) -> list[float]:
        """The actuation on the three proximal joints, N*m, as a list of floats."""
        return net_actuation[self._proximal_actuator_rows].tolist()

    def to_actuator_order(self, joints: list[float]) -> np.ndarray:
        """[qd; vd] in actuator order from [qd; vd] in HAND_JOINTS.all order (unknown actuators: 0)."""
        return np.asarray(joints + [0.0])[self._desired_order]


def SetHandActuatorGains(plant: MultibodyPlant, hand_instance: ModelInstanceIndex,
                         params: HandControllerParams) -> None:
    """Gives every hand actuator its PD gains (before plant.Finalize())."""
    gains = {"spread": params.spread_gains, "proximal": params.proximal_gains, "distal": params.distal_gains}
    for index in plant.GetJointActuatorIndices():
        actuator = plant.get_joint_actuator(index)
        if actuator.model_instance() != hand_instance:
            continue
        kind = actuator.joint().name().split("_")[1]  # bh_<kind>_<finger>
        kp, kd = gains[kind]
        actuator.set_controller_gains(PdControllerGains(p=kp, d=kd))
