"""The BarrettHand's torque-close controller with the TorqueSwitch (breakaway) clutch.

On the real hand one motor drives both joints of a finger: in free motion the distal joint turns at
1/3 of the proximal rate (125:1 and 375:1 gears). When the torque on the proximal joint exceeds the
breakaway torque the clutch slips: the proximal joint holds its angle (its worm drive cannot be
back-driven) and the distal joint keeps closing, 4 times faster per motor turn, until it touches the
object or its 48 deg limit. If the distal link is stopped first, the motor stalls and the whole finger
stops. A stopped finger keeps squeezing with its stall torque. Reopening re-engages the clutch.
Spread (F1 and F2, one motor) goes to the compliance mode's angle before the fingers close.

How it is simulated (docs/design.md §5.3): every finger joint has an implicit PD actuator in the plant
(stable at large gains and time steps); this controller turns the motor model into the desired joint
states those actuators track. Torque close is a *position lead*: a joint's command runs ahead of where
the joint will be at the next step (its measured angle plus its measured closing velocity times the
period) by at most ``lead = stall_torque / kp``, so a blocked joint is pushed with exactly its stall
torque while a free one follows the motor at full speed. Breakaway is detected from the *torque*: the actuation the plant applies on the proximal
joint (its ``net_actuation`` output) exceeding ``breakaway_torque``, as on the real clutch — not from a
stall detector.

The clutch logic is the pure function `advance_fingers`; `HandController` is the thin LeafSystem around it.
"""



import dataclasses
import math

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex, PdControllerGains
from pydrake.systems.framework import BasicVector, Context, DiscreteValues, LeafSystem

from drake_grasp import hand
from drake_grasp.hand import HAND_JOINTS, HandAction

NUM_FINGERS = 3


@dataclasses.dataclass
class HandControllerParams:
    """Choices of the simulated hand drive (the facts are in `drake_grasp.hand`).

    Attributes:
        breakaway_torque: proximal torque at which the clutch slips, N*m (GraspIt!: 0.5).
        proximal_drive_torque: largest torque the motor puts on a blocked proximal joint before
            breakaway, N*m. Must exceed `breakaway_torque`, or the clutch could never slip.
        distal_squeeze_torque: torque of a stalled distal joint, N*m; 0.75 N*m is a 15 N fingertip
            force at A3 = 50 mm (docs/design.md §4.1: 15-25 N, assumed).
        spread_torque: stall torque of the spread drive, N*m (assumed).
        closing_time: time for a free proximal joint to go from open to its 140 deg limit, s.
        spread_time: time for the spread to go end to end (180 deg), s.
        proximal_gains, distal_gains, spread_gains: (kp N*m/rad, kd N*m*s/rad) of the joint PD actuators.
        period: controller update period, s.
    """

    breakaway_torque: float = hand.BREAKAWAY_TORQUE
    proximal_drive_torque: float = 1.0
    distal_squeeze_torque: float = hand.FINGERTIP_STALL_FORCE * hand.A3
    spread_torque: float = 1.0
    closing_time: float = 1.0
    spread_time: float = 0.5
    proximal_gains: list[float] = dataclasses.field(default_factory=lambda: [200.0, 0.6])
    distal_gains: list[float] = dataclasses.field(default_factory=lambda: [10.0, 0.04])
    spread_gains: list[float] = dataclasses.field(default_factory=lambda: [10.0, 0.3])
    period: float = 0.005

    def __post_init__(self):
        for name in ("breakaway_torque", "proximal_drive_torque", "distal_squeeze_torque", "spread_torque",
                     "closing_time", "spread_time", "period"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"hand controller: {name} must be a positive number, got {value}")
        if self.proximal_drive_torque <= self.breakaway_torque:
            raise ValueError(
                "hand controller: proximal_drive_torque must exceed breakaway_torque "
                f"({self.proximal_drive_torque} <= {self.breakaway_torque}), or the clutch never slips"
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
    def spread_lead(self) -> float:
        return self.spread_torque / self.spread_gains[0]


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

    # Layout of the flat vector form (the LeafSystem's discrete state).
    SIZE = 2 + 6 * NUM_FINGERS

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
            spread=float(x[0]), spread_rate=float(x[1]), proximal=x[2:2 + f].copy(),
            distal=x[2 + f:2 + 2 * f].copy(), broken_away=x[2 + 2 * f:2 + 3 * f] > 0.5,
            breakaway_angle=x[2 + 3 * f:2 + 4 * f].copy(), proximal_rate=x[2 + 4 * f:2 + 5 * f].copy(),
            distal_rate=x[2 + 5 * f:2 + 6 * f].copy(),
        )


def _toward(value: float | np.ndarray, target, max_step):
    return value + np.clip(target - value, -max_step, max_step)


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
    new = FingerDrive.from_vector(drive.to_vector())
    w_p = params.proximal_speed
    w_d_coupled = w_p * hand.DISTAL_PER_PROXIMAL
    w_d_free = w_d_coupled * hand.BREAKAWAY_SPEEDUP
    lo_s, hi_s = hand.SPREAD_LIMITS
    spread_target = float(np.clip(spread_target, lo_s, hi_s))

    # Spread first: it moves toward the mode's angle, never leading the joint by more than its lead.
    spread = _toward(drive.spread, spread_target, params.spread_speed * dt)
    spread = float(np.clip(spread, spread_measured - params.spread_lead, spread_measured + params.spread_lead))
    new.spread_rate = (spread - drive.spread) / dt
    new.spread = spread
    spread_ready = abs(spread_measured - spread_target) < math.radians(2.0) and spread == spread_target

    # Where each joint will be at the next update if it keeps closing as it does now.
    proximal_next = proximal_measured + np.maximum(proximal_velocity, 0.0) * dt
    distal_next = distal_measured + np.maximum(distal_velocity, 0.0) * dt
    proximal, distal = drive.proximal.copy(), drive.distal.copy()
    if action == HandAction.CLOSE and spread_ready:
        for f in range(NUM_FINGERS):
            if not drive.broken_away[f] and proximal_torque[f] > params.breakaway_torque:
                # The clutch slips: the proximal joint holds where it is; the distal keeps closing.
                new.broken_away[f] = True
                new.breakaway_angle[f] = proximal_measured[f]
                proximal[f] = proximal_measured[f]
            if new.broken_away[f]:
                distal[f] = min(distal[f] + w_d_free * dt, distal_next[f] + params.distal_lead)
            else:
                # One motor turns both joints: it stalls as soon as either joint is blocked.
                proximal[f] = min(
                    proximal[f] + w_p * dt,
                    proximal_next[f] + params.proximal_lead,
                    (distal_next[f] + params.distal_lead) / hand.DISTAL_PER_PROXIMAL,
                )
                distal[f] = proximal[f] * hand.DISTAL_PER_PROXIMAL
    elif action == HandAction.PRESHAPE and spread_ready:
        target = np.clip(np.asarray(preshape, float), *hand.PROXIMAL_LIMITS)
        for f in range(NUM_FINGERS):
            if target[f] >= proximal[f]:
                proximal[f] = min(proximal[f] + w_p * dt, target[f], proximal_next[f] + params.proximal_lead,
                                  (distal_next[f] + params.distal_lead) / hand.DISTAL_PER_PROXIMAL)
            else:
                proximal[f] = max(proximal[f] - w_p * dt, target[f])
            distal[f] = proximal[f] * hand.DISTAL_PER_PROXIMAL
        new.broken_away[:] = False
        new.breakaway_angle[:] = np.nan
    elif action == HandAction.OPEN:
        # Reopen at the closing speeds, distal first back onto the coupled ratio; re-engage the clutch.
        proximal = np.maximum(proximal - w_p * dt, hand.PROXIMAL_LIMITS[0] - params.proximal_lead)
        proximal = np.maximum(proximal, proximal_measured - params.proximal_lead)
        distal = np.maximum(distal - w_d_free * dt, proximal * hand.DISTAL_PER_PROXIMAL)
        distal = np.maximum(distal, distal_measured - params.distal_lead)
        new.broken_away[:] = False
        new.breakaway_angle[:] = np.nan
    # HOLD, or CLOSE while the spread is still moving: commands stay (a squeezing finger squeezes on).
    new.proximal_rate = (proximal - drive.proximal) / dt
    new.distal_rate = (distal - drive.distal) / dt
    new.proximal, new.distal = proximal, distal
    return new


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
    """

    def __init__(self, plant: MultibodyPlant, hand_instance: ModelInstanceIndex,
                 params: HandControllerParams | None = None):
        super().__init__()
        self._params = params or HandControllerParams()
        self._index = _HandIndexing(plant, hand_instance)
        num_q = plant.num_positions(hand_instance)
        num_v = plant.num_velocities(hand_instance)
        self._command_port = self.DeclareVectorInputPort("command", 2)
        self._preshape_port = self.DeclareVectorInputPort("finger_preshape", NUM_FINGERS)
        self._state_port = self.DeclareVectorInputPort("hand_state", num_q + num_v)
        self._actuation_port = self.DeclareVectorInputPort("hand_net_actuation", plant.num_actuators(hand_instance))
        self._drive_index = self.DeclareDiscreteState(FingerDrive().to_vector())
        self.DeclarePeriodicDiscreteUpdateEvent(self._params.period, 0.0, self._Update)
        self.DeclareVectorOutputPort("hand_desired_state", 2 * self._index.num_actuators, self._CalcDesiredState,
                                     {self.xd_ticket()})
        self.DeclareVectorOutputPort("finger_status", 2 * NUM_FINGERS, self._CalcFingerStatus, {self.xd_ticket()})

    @property
    def params(self) -> HandControllerParams:
        return self._params

    def SetInitialFingers(self, context: Context, spread: float = 0.0) -> None:
        """Starts the drive at an open hand with the given spread (rad)."""
        drive = FingerDrive(spread=spread)
        context.SetDiscreteState(self._drive_index, drive.to_vector())

    def _Update(self, context: Context, discrete_state: DiscreteValues) -> None:
        command = self._command_port.Eval(context)
        state = self._state_port.Eval(context)
        actuation = self._actuation_port.Eval(context)
        q = self._index.joint_positions(state)
        v = self._index.joint_velocities(state)
        drive = FingerDrive.from_vector(context.get_discrete_state(self._drive_index).value())
        action = HandAction(int(round(command[1])))
        preshape = self._preshape_port.Eval(context) if action == HandAction.PRESHAPE else None
        new = advance_fingers(
            drive,
            spread_target=float(command[0]),
            action=action,
            spread_measured=float(np.mean(q[0:2])),
            proximal_measured=q[2:5],
            distal_measured=q[5:8],
            proximal_torque=self._index.actuation(actuation)[2:5],
            proximal_velocity=v[2:5],
            distal_velocity=v[5:8],
            params=self._params,
            dt=self._params.period,
            preshape=preshape,
        )
        discrete_state.set_value(self._drive_index, new.to_vector())

    def joint_angles(self, hand_state: np.ndarray) -> np.ndarray:
        """The hand's joint angles in HAND_JOINTS.all order (rad), from its instance state [q; v]."""
        return self._index.joint_positions(hand_state)

    def _CalcDesiredState(self, context: Context, output: BasicVector) -> None:
        drive = FingerDrive.from_vector(context.get_discrete_state(self._drive_index).value())
        q_d = np.concatenate([[drive.spread, drive.spread], drive.proximal, drive.distal])
        v_d = np.concatenate([[drive.spread_rate, drive.spread_rate], drive.proximal_rate, drive.distal_rate])
        output.SetFromVector(self._index.to_actuator_order(q_d, v_d))

    def _CalcFingerStatus(self, context: Context, output: BasicVector) -> None:
        drive = FingerDrive.from_vector(context.get_discrete_state(self._drive_index).value())
        output.SetFromVector(np.concatenate([drive.broken_away.astype(float), drive.breakaway_angle]))


class _HandIndexing:
    """Maps the controller's joint order (HAND_JOINTS.all) to the plant's per-instance orders."""

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
        actuators = sorted(plant.GetJointActuatorIndices(hand_instance), key=int)
        actuated_joints = [plant.get_joint_actuator(a).joint().name() for a in actuators]
        self.num_actuators = len(actuators)
        self._actuator_rows = np.array([actuated_joints.index(name) for name in HAND_JOINTS.all])

    def joint_positions(self, hand_state: np.ndarray) -> np.ndarray:
        return np.asarray(hand_state)[self._q_rows]

    def joint_velocities(self, hand_state: np.ndarray) -> np.ndarray:
        return np.asarray(hand_state)[self._num_q + self._v_rows]

    def actuation(self, net_actuation: np.ndarray) -> np.ndarray:
        return np.asarray(net_actuation)[self._actuator_rows]

    def to_actuator_order(self, q_d: np.ndarray, v_d: np.ndarray) -> np.ndarray:
        out_q = np.zeros(self.num_actuators)
        out_v = np.zeros(self.num_actuators)
        out_q[self._actuator_rows] = q_d
        out_v[self._actuator_rows] = v_d
        return np.concatenate([out_q, out_v])


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
