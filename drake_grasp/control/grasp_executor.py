"""Executes one grasp plan with the WAM and the hand: move, preshape, approach, close, lift, hold.

The executor is a LeafSystem state machine (phase in abstract state, advanced by a periodic
unrestricted update) that outputs the WAM's desired joint state and the hand's command. The approach
is *guarded*: the palm moves along its normal at a constant speed and stops as soon as the contact
force on the hand exceeds a threshold (the palm touched the object), or at the plan's target (the
estimated surface). The same executor runs the compliant grasps and the grasps planned by other
methods, so every method is executed by the same arm, controller and timings. Given no plan, it
starts in GraspPhase.EXPLORE: the compliant-grasp supervisor (`control.supervisor`) is such a subclass,
which decides the plan while the simulation runs.

The arm has two modes. Held by position (the paper's, and every plan with `palm_force` 0), the
executor's joint trajectory drives the station's joint PD throughout. A plan with a `palm_force`
(the flower grasp) hands the arm to the palm's impedance law (`control.palm_impedance`) for the
approach and the close: the approach's target pose slides down the approach line at the approach
speed and the landing ends when the hand touches (the fingertips on the table); the close then holds
the palm where it landed, across and in tilt, soft along its normal, and presses along it with the
plan's force, ramped up over `FORCE_RAMP`. The lift takes the arm back to the joint PD from where it
is (its measured joint angles), so the lift and the hold are the same as every other grasp's.

The hand has two closes. Torque close with breakaway (the paper's, and every plan with `breakaway`)
closes through the close, the lift and the hold, so that a finger re-squeezes when the object settles.
A plan without breakaway (the flower grasp) closes gently (HandAction.GENTLE_CLOSE: each finger stops
at its first contact, its clutch engaged) and then holds its fingers where they stopped through the lift
and the hold: the BH8's worm drives are not back-driven, so a squeeze on a thin edge keeps its shape
when the lift loads it. During the lift the fingers that squeeze squeeze harder (HandAction.SQUEEZE:
the motor's torque rises, still under the clutch's), so that the squeeze carries the object's weight;
the hold keeps their commands where the lift left them (HandAction.HOLD). A plan whose thumb does not close (the flower grasp's
two-finger pinch, `GraspPlan.thumb_closes`) closes F1 and F2 so and leaves F3 at its preshape
(HandAction.GENTLE_PINCH).
"""

import dataclasses
import enum

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.plant import ContactResults, MultibodyPlant
from pydrake.geometry import SceneGraph
from pydrake.multibody.tree import ModelInstanceIndex
from pydrake.systems.framework import BasicVector, Context, DiagramBuilder, LeafSystem, State

from drake_grasp.control.arm_motion import ArmKinematics, JointPath, ReachError
from drake_grasp.control.hand_controller import HandIndexing
from drake_grasp.grasps import ABOUT_APPROACH, TURNED, GraspPlan, near_symmetric_alternatives
from drake_grasp.robot import hand
from drake_grasp.robot.hand import HAND_JOINTS, HandAction
from drake_grasp.protocol import ExecutionTimes


# How long the palm's force takes to rise from zero to the plan's at the start of the close, s: a step
# in force would kick the palm off the table it just landed on.
FORCE_RAMP = 0.2


def fingertips_rise(plan: GraspPlan, proximal: list[float]) -> float:
    """How far the closing fingertips have risen towards the palm since they landed, m (never
    negative): `hand.fingertip_depth` at the angle they landed at (`plan.finger_preshape`) less at
    the closing fingers' mean proximal angle now (`proximal`, rad, F1-F3), at the plan's spread.

    Only the fingers that close count: in the two-finger pinch (`plan.thumb_closes` False) F3 stays
    open at 0, and counting it (behaviour before 0.35.0) took the mean a third short, so the palm
    followed the pinching tips down by a fraction of their rise: on a 3 cm lump they left the table
    by 10-20 mm as they closed and passed over it (docs/design.md §5.4f)."""
    closing = 3 if plan.thumb_closes else 2
    landed = float(np.mean(plan.finger_preshape[:closing]))
    now = float(np.mean(proximal[:closing]))
    rise = hand.fingertip_depth(landed, plan.spread) - hand.fingertip_depth(max(now, landed), plan.spread)
    return max(rise, 0.0)


class GraspPhase(enum.IntEnum):
    EXPLORE = 0  # no plan yet: the camera explores (the compliant-grasp supervisor only)
    MOVE = 1  # to the pre-grasp pose, hand opening to the mode's spread
    PRESHAPE = 2  # fingers to a planned posture (planned grasps only)
    APPROACH = 3  # along the palm normal, until contact or the target
    CLOSE = 4  # torque close with breakaway
    LIFT = 5
    HOLD = 6
    DONE = 7


@dataclasses.dataclass(frozen=True)
class GraspMotion:
    """The arm's motion for one plan, planned before anything moves (an unreachable plan fails first).

    Attributes:
        plan: the grasp.
        q_pregrasp: arm joint angles at the pre-grasp pose, rad.
        approach_path: joint angles along the straight approach line, from q_pregrasp to the target.
        move_time: duration of the move from the start configuration to q_pregrasp, s.
        approach_duration: duration of the whole approach at the approach speed, s.
    """

    plan: GraspPlan
    q_pregrasp: np.ndarray
    approach_path: list
    move_time: float
    approach_duration: float
    fallback: str = ""  # what `plan` is instead of the requested one when that was out of reach ("": itself)
    unreachable: str = ""  # why the requested pose could not be reached

    @property
    def has_preshape(self) -> bool:
        """Whether the plan sets the fingers to a posture before the approach (planned grasps)."""
        return any(abs(a) > 1e-9 for a in self.plan.finger_preshape)


@dataclasses.dataclass(frozen=True)
class _Progress:
    """The executor's abstract state (immutable: every update that changes it builds a new one).

    Attributes:
        phase, phase_start: the current GraspPhase and when it began, s.
        trajectory: PiecewisePolynomial of the arm's joint angles that the phase follows.
        motion: the plan's arm motion (None until a plan is known).
        stopped_on_contact: the approach ended on touch, not at its target.
        approach_travel: how far the palm went along the approach, m.
        phase_times: start time of every phase entered, s.
        outcome: why the sequence ended before grasping (a trial's failure reason), or "".
        detail: more about the outcome (e.g. the pose the arm could not reach).
        decision: what the supervisor decided (see `supervisor.Decision`), or None.
        palm_hold: the palm's pose where a compliant arm landed (the close's impedance target), or None.
    """

    phase: GraspPhase
    phase_start: float
    trajectory: object
    motion: GraspMotion | None = None
    stopped_on_contact: bool = False
    approach_travel: float = 0.0
    phase_times: dict = dataclasses.field(default_factory=dict)
    outcome: str = ""
    detail: str = ""
    decision: object = None
    palm_hold: RigidTransform | None = None

    def __deepcopy__(self, memo) -> "_Progress":
        """Itself. Drake copies the whole state at every plant step (unrestricted updates); an
        immutable value needs no copy, and deep-copying the trajectory and plan each time cost about
        a tenth of a trial's wall time (docs/performance.md)."""
        return self


class GraspExecutor(LeafSystem):
    """Runs a GraspPlan from a start configuration of the arm.

    Input ports:
        wam.state: the WAM's [q; v] (7 + 7).
        contact_results: the plant's ContactResults.
    Output ports:
        wam.desired_state: [q; v] for the station's ``wam.desired_state``.
        hand.command: [spread, HandAction] for ``hand.command``.
        hand.finger_preshape: proximal angles (3) for ``hand.finger_preshape``.
        phase: the current GraspPhase, as a number.
        wam.arm_mode (1): 1 while the palm's impedance law drives the arm (a plan with a palm force,
            from the approach to the end of the close), else 0.
        wam.palm_target: the impedance law's target pose X_WPd (RigidTransform).
        wam.palm_force (1): its force along the palm normal, N.

    Raises (at construction): ReachError if the arm cannot reach the whole path (pre-grasp, approach,
    lift) of the plan nor of any of its near-symmetric equivalents (`plan_reachable_motion`).
    """

    def __init__(self, plant: MultibodyPlant, scene_graph: SceneGraph, wam: ModelInstanceIndex, hand_bodies: list,
                 plan: GraspPlan | None, q_start: np.ndarray, times: ExecutionTimes):
        """
        Args:
            plant, scene_graph, wam: the station's.
            hand_bodies: the hand's body indices (contact on them ends the approach).
            plan: the grasp to run from time 0; None for a subclass that decides it later (it starts
                in GraspPhase.EXPLORE, holding the arm at q_start, until it calls `_start_grasp`).
            q_start: the arm's joint angles at time 0, rad.
            times: the sequence's timings.
        """
        super().__init__()
        self._inspector = scene_graph.model_inspector()
        self._body_of_geometry = {}  # GeometryId -> body index, filled as contacts come
        self._times = times
        self._kinematics = ArmKinematics(plant, wam)
        self._hand_bodies = set(int(b) for b in hand_bodies)
        self._plant = plant
        q_start = np.asarray(q_start, float)
        initial = _Progress(GraspPhase.EXPLORE, 0.0, _hold(q_start, 0.0), phase_times={GraspPhase.EXPLORE: 0.0})
        if plan is not None:
            initial = self._start_grasp(initial, plan, q_start, 0.0)

        self._wam_state_port = self.DeclareVectorInputPort("wam.state", 14)
        self._hand_state_port = self.DeclareVectorInputPort("hand.state", 2 * len(HAND_JOINTS.all))
        self._hand_index = HandIndexing(plant, plant.GetJointByName(HAND_JOINTS.proximal[0]).model_instance())
        self._contact_results_port = self.DeclareAbstractInputPort(
            "contact_results", AbstractValue.Make(ContactResults()))
        self._progress_index = self.DeclareAbstractState(AbstractValue.Make(initial))
        self.DeclarePeriodicUnrestrictedUpdateEvent(times.update_period, 0.0, self._Update)
        self.DeclareVectorOutputPort("wam.desired_state", 14, self._CalcDesiredState,
                                     {self.abstract_state_ticket(self._progress_index), self.time_ticket()})
        self.DeclareVectorOutputPort("hand.command", 2, self._CalcHandCommand,
                                     {self.abstract_state_ticket(self._progress_index)})
        self.DeclareVectorOutputPort("hand.finger_preshape", 3, self._CalcPreshape,
                                     {self.abstract_state_ticket(self._progress_index)})
        self.DeclareVectorOutputPort("phase", 1, self._CalcPhase, {self.abstract_state_ticket(self._progress_index)})
        progress_ticket = {self.abstract_state_ticket(self._progress_index)}
        self.DeclareVectorOutputPort("wam.arm_mode", 1, self._CalcArmMode, progress_ticket)
        self.DeclareAbstractOutputPort("wam.palm_target", lambda: AbstractValue.Make(RigidTransform()),
                                       self._CalcPalmTarget, progress_ticket | {self.time_ticket(),
                                                                              self._hand_state_port.ticket()})
        self.DeclareVectorOutputPort("wam.palm_force", 1, self._CalcPalmForce, progress_ticket | {self.time_ticket()})

    def plan_motion(self, plan: GraspPlan, q_start: np.ndarray) -> GraspMotion:
        """The arm's motion for `plan` from joint angles q_start (raises ReachError if unreachable).

        The whole path must be reachable: the pre-grasp pose, the straight approach to the target and
        a lift straight up from the target by the protocol's lift height (the lift itself is planned
        again from where the approach stops), with the arm's shell and the hand base clear of the
        table (`ArmKinematics.check_table_clearance`)."""
        q_pregrasp = self._kinematics.solve(plan.X_WP_pregrasp, q_start)
        approach_path = self._kinematics.straight_line(plan.X_WP_pregrasp, plan.X_WP_target, q_pregrasp, step=0.01)
        X_up = RigidTransform(plan.X_WP_target.rotation(),
                              plan.X_WP_target.translation() + [0.0, 0.0, self._times.lift_height])
        lift_path = self._kinematics.straight_line(plan.X_WP_target, X_up, approach_path[-1], step=0.02)
        self._kinematics.check_table_clearance([q_pregrasp, *approach_path, *lift_path])
        move_time = max(1.0, float(np.max(np.abs(q_pregrasp - q_start))) / self._times.joint_speed)
        return GraspMotion(plan, q_pregrasp, approach_path, move_time, plan.approach_distance / self._times.approach_speed)

    def plan_reachable_motion(self, plan: GraspPlan, q_start: np.ndarray,
                              alternatives: list[tuple[str, GraspPlan]] | None = None) -> GraspMotion:
        """The motion of `plan`, or, when the arm cannot reach its whole path, of the first of the
        `alternatives` it can reach.

        Args:
            alternatives: (what it is, plan) to try after `plan`, in order: the funnel search's next
                candidates (`funnel.planning`); default: the grasp's near-symmetric equivalents
                (`grasps.near_symmetric_plans`: the same grasp turned about the approach, the
                smallest turn first).

        Raises:
            ReachError: none is reachable; its message says what was tried.
        """
        if alternatives is None:
            alternatives = near_symmetric_alternatives(plan)
        tried = []
        for label, candidate in [("", plan)] + list(alternatives):
            try:
                motion = self.plan_motion(candidate, q_start)
            except ReachError as e:
                tried.append((label, str(e)))
                continue
            return dataclasses.replace(motion, fallback=label, unreachable=tried[0][1] if tried else "")
        if len(tried) == 1:
            raise ReachError(tried[0][1])
        turns = [label.removeprefix(f"{TURNED} ").removesuffix(f" {ABOUT_APPROACH}") for label, _ in tried[1:]]
        if all(label.startswith(TURNED) for label, _ in tried[1:]):
            raise ReachError(f"{tried[0][1]}, nor {TURNED} {', '.join(turns)} {ABOUT_APPROACH}")
        raise ReachError(f"{tried[0][1]}, nor any of {len(tried) - 1} other poses ({tried[1][0]}, ...)")

    def _start_grasp(self, progress: _Progress, plan: GraspPlan, q_start: np.ndarray, t: float,
                     alternatives: list[tuple[str, GraspPlan]] | None = None) -> _Progress:
        """Plans the motion of `plan` (or of the first reachable of its alternatives:
        `plan_reachable_motion`) from q_start and enters GraspPhase.MOVE at time t (raises ReachError)."""
        motion = self.plan_reachable_motion(plan, q_start, alternatives)
        path = JointPath()
        path.add(t, q_start)
        path.add(t + motion.move_time, motion.q_pregrasp)
        phase_times = dict(progress.phase_times)
        phase_times[GraspPhase.MOVE] = t
        return dataclasses.replace(progress, phase=GraspPhase.MOVE, phase_start=t, trajectory=path.ToTrajectory(),
                                   motion=motion, phase_times=phase_times)

    # --- Reading the state. -----------------------------------------------------------------------

    def progress(self, context: Context) -> _Progress:
        return context.get_abstract_state(self._progress_index).get_value()

    def phase(self, context: Context) -> GraspPhase:
        return self.progress(context).phase

    # --- Outputs. ---------------------------------------------------------------------------------

    def _CalcDesiredState(self, context: Context, output: BasicVector) -> None:
        # Read at every plant step: the trajectory's end holds still (no derivative to evaluate).
        trajectory = self.progress(context).trajectory
        t, t_end = context.get_time(), trajectory.end_time()
        if t >= t_end:
            q, v = trajectory.value(t_end), np.zeros(trajectory.rows())
        else:
            t = max(t, trajectory.start_time())
            q, v = trajectory.value(t), trajectory.EvalDerivative(t, 1)
        output.SetFromVector(np.concatenate([q.ravel(), v.ravel()]))

    def _CalcHandCommand(self, context: Context, output: BasicVector) -> None:
        progress = self.progress(context)
        phase, motion = progress.phase, progress.motion
        if motion is None:  # exploring, or ended before a grasp: the hand open, fingers together
            output.SetFromVector([0.0, float(HandAction.OPEN)])
            return
        if phase <= GraspPhase.MOVE:
            action = HandAction.OPEN
        elif phase == GraspPhase.PRESHAPE or (phase == GraspPhase.APPROACH and motion.has_preshape):
            action = HandAction.PRESHAPE
        elif phase == GraspPhase.APPROACH:
            action = HandAction.OPEN
        elif motion.plan.breakaway:
            action = HandAction.CLOSE
        else:
            gentle = HandAction.GENTLE_CLOSE if motion.plan.thumb_closes else HandAction.GENTLE_PINCH
            action = {GraspPhase.CLOSE: gentle, GraspPhase.LIFT: HandAction.SQUEEZE}.get(phase, HandAction.HOLD)
        output.SetFromVector([motion.plan.spread, float(action)])

    def _CalcPreshape(self, context: Context, output: BasicVector) -> None:
        motion = self.progress(context).motion
        preshape = motion.plan.finger_preshape[:3] if motion is not None else np.zeros(3)
        output.SetFromVector(np.asarray(preshape, float))

    def _CalcPhase(self, context: Context, output: BasicVector) -> None:
        output.SetFromVector([float(self.progress(context).phase)])

    @staticmethod
    def _compliant(progress: _Progress) -> bool:
        """Whether the palm's impedance law drives the arm now."""
        motion = progress.motion
        return (motion is not None and motion.plan.compliant_arm
                and progress.phase in (GraspPhase.APPROACH, GraspPhase.CLOSE))

    def _CalcArmMode(self, context: Context, output: BasicVector) -> None:
        output.SetFromVector([1.0 if self._compliant(self.progress(context)) else 0.0])

    def _CalcPalmTarget(self, context: Context, output: AbstractValue) -> None:
        progress = self.progress(context)
        motion = progress.motion
        if progress.palm_hold is not None:
            output.set_value(self._following_fingertips(context, progress))
        elif motion is not None and progress.phase == GraspPhase.APPROACH:
            # Down the approach line at the approach speed, from the pre-grasp pose to the target.
            plan = motion.plan
            travel = (context.get_time() - progress.phase_start) * self._times.approach_speed
            s = min(1.0, travel / plan.approach_distance) if plan.approach_distance > 0 else 1.0
            p = (1 - s) * plan.X_WP_pregrasp.translation() + s * plan.X_WP_target.translation()
            output.set_value(RigidTransform(plan.X_WP_target.rotation(), p))
        else:
            output.set_value(self._kinematics.palm_pose(progress.trajectory.value(
                min(context.get_time(), progress.trajectory.end_time())).ravel()))

    def _following_fingertips(self, context: Context, progress: _Progress) -> RigidTransform:
        """The close's palm target: where the palm landed, moved along its normal by as much as the
        closing fingertips rise (`fingertips_rise`), so that tips that landed on the table stay on
        it. Without the hand's state (an unconnected `hand.state`), where it landed."""
        X = progress.palm_hold
        if not self._hand_state_port.HasValue(context):
            return X
        angles = self._hand_index.joint_positions(self._hand_state_port.Eval(context))
        proximal = [angles[HAND_JOINTS.all.index(name)] for name in HAND_JOINTS.proximal]
        rise = fingertips_rise(progress.motion.plan, proximal)
        return RigidTransform(X.rotation(), X.translation() + rise * X.rotation().col(2))

    def _CalcPalmForce(self, context: Context, output: BasicVector) -> None:
        progress = self.progress(context)
        force = 0.0
        if self._compliant(progress) and progress.phase == GraspPhase.CLOSE:
            ramp = min(1.0, (context.get_time() - progress.phase_start) / FORCE_RAMP)
            force = ramp * progress.motion.plan.palm_force
        output.SetFromVector([force])

    # --- The state machine. -----------------------------------------------------------------------

    def _hand_contact_force(self, context: Context) -> float:
        """Magnitude of the total contact force on the hand's bodies from other bodies, N."""
        results: ContactResults = self._contact_results_port.Eval(context)
        total = np.zeros(3)
        for i in range(results.num_hydroelastic_contacts()):
            info = results.hydroelastic_contact_info(i)
            surface = info.contact_surface()
            body_m = self._body_of(surface.id_M())
            body_n = self._body_of(surface.id_N())
            force = info.F_Ac_W().translational()  # on the body of geometry M
            if body_m in self._hand_bodies and body_n not in self._hand_bodies:
                total += force
            elif body_n in self._hand_bodies and body_m not in self._hand_bodies:
                total -= force
        for i in range(results.num_point_pair_contacts()):
            info = results.point_pair_contact_info(i)
            a, b = int(info.bodyA_index()), int(info.bodyB_index())
            if a in self._hand_bodies and b not in self._hand_bodies:
                total -= info.contact_force()  # contact_force is on B
            elif b in self._hand_bodies and a not in self._hand_bodies:
                total += info.contact_force()
        return float(np.linalg.norm(total))

    def _body_of(self, geometry_id) -> int:
        """The index of the plant body that owns a geometry (looked up once per geometry)."""
        body = self._body_of_geometry.get(geometry_id)
        if body is None:
            body = int(self._plant.GetBodyFromFrameId(self._inspector.GetFrameId(geometry_id)).index())
            self._body_of_geometry[geometry_id] = body
        return body

    def _Update(self, context: Context, state: State) -> None:
        progress = self.progress(context)
        t = context.get_time()
        elapsed = t - progress.phase_start
        times = self._times
        motion = progress.motion
        if progress.phase == GraspPhase.EXPLORE:
            progress = self._Explore(context, progress)
        elif progress.phase == GraspPhase.MOVE and elapsed >= motion.move_time:
            progress = self._enter(progress, GraspPhase.PRESHAPE if motion.has_preshape else GraspPhase.APPROACH, t)
        elif progress.phase == GraspPhase.PRESHAPE and elapsed >= times.preshape_time:
            progress = self._enter(progress, GraspPhase.APPROACH, t)
        elif progress.phase == GraspPhase.APPROACH:
            done = t >= progress.trajectory.end_time()
            if motion.plan.stop_on_contact and self._hand_contact_force(context) > times.touch_force:
                progress = dataclasses.replace(progress, stopped_on_contact=True)
                done = True
            if done:
                progress = dataclasses.replace(
                    progress, approach_travel=times.approach_speed * min(elapsed, motion.approach_duration))
                if motion.plan.compliant_arm:  # hold the palm where it landed
                    X_WP = self._kinematics.palm_pose(self._measured_q(context))
                    progress = dataclasses.replace(progress, palm_hold=X_WP, approach_travel=float(np.dot(
                        X_WP.translation() - motion.plan.X_WP_pregrasp.translation(),
                        motion.plan.X_WP_target.rotation().col(2))))
                progress = self._enter(progress, GraspPhase.CLOSE, t)
        elif progress.phase == GraspPhase.CLOSE and elapsed >= times.close_time:
            # A compliant arm hands back to the joint PD where it is.
            q_now = self._measured_q(context) if motion.plan.compliant_arm else None
            progress = self._enter(dataclasses.replace(progress, palm_hold=None), GraspPhase.LIFT, t, q_now)
        elif progress.phase == GraspPhase.LIFT and elapsed >= times.lift_time:
            progress = self._enter(progress, GraspPhase.HOLD, t)
        elif progress.phase == GraspPhase.HOLD and elapsed >= times.hold_time:
            progress = self._enter(progress, GraspPhase.DONE, t)
        state.get_mutable_abstract_state(self._progress_index).set_value(progress)

    def _measured_q(self, context: Context) -> np.ndarray:
        """The arm's measured joint angles, rad."""
        return np.asarray(self._wam_state_port.Eval(context), float)[:7].copy()

    def _Explore(self, context: Context, progress: _Progress) -> _Progress:
        """GraspPhase.EXPLORE's update: a subclass that decides the grasp while running overrides it."""
        raise RuntimeError("GraspExecutor was built without a plan")

    def _end(self, progress: _Progress, t: float, outcome: str, detail: str = "") -> _Progress:
        """Ends the sequence at time t without grasping, saying why; the arm holds still."""
        return dataclasses.replace(self._enter(progress, GraspPhase.DONE, t), outcome=outcome, detail=detail)

    def _enter(self, progress: _Progress, phase: GraspPhase, t: float, q_now: np.ndarray | None = None) -> _Progress:
        """Switches to `phase` at time t, with the arm trajectory that phase follows (from q_now, rad:
        where the arm is; default: where the last trajectory left it)."""
        if q_now is None:
            q_now = progress.trajectory.value(min(t, progress.trajectory.end_time())).ravel()
        path = JointPath()
        motion = progress.motion
        if phase == GraspPhase.APPROACH:
            path.add(t, q_now)
            path.add_segment(t, motion.approach_duration, [q_now] + list(motion.approach_path[1:]))
        elif phase == GraspPhase.LIFT:
            X_WP = self._kinematics.palm_pose(q_now)
            X_up = RigidTransform(X_WP.rotation(), X_WP.translation() + [0.0, 0.0, self._times.lift_height])
            lift = self._kinematics.straight_line(X_WP, X_up, q_now, step=0.02)
            path.add(t, q_now)
            path.add_segment(t, self._times.lift_time, lift)
        else:  # hold still where the arm is
            return dataclasses.replace(progress, phase=phase, phase_start=t, trajectory=_hold(q_now, t),
                                       phase_times={**progress.phase_times, phase: t})
        return dataclasses.replace(progress, phase=phase, phase_start=t, trajectory=path.ToTrajectory(),
                                   phase_times={**progress.phase_times, phase: t})


def ConnectGraspExecutor(builder: DiagramBuilder, station_system, executor: GraspExecutor, *, arm: bool = True
                         ) -> None:
    """Connects an executor in `builder` to the station's Diagram `station_system` (both added to it):
    the arm's and the contacts' feedback in, the hand's commands out, and (with `arm`) the arm command."""
    builder.Connect(station_system.GetOutputPort("wam.state"), executor.GetInputPort("wam.state"))
    builder.Connect(station_system.GetOutputPort("contact_results"), executor.GetInputPort("contact_results"))
    builder.Connect(station_system.GetOutputPort("hand.state"), executor.GetInputPort("hand.state"))
    builder.Connect(executor.GetOutputPort("hand.command"), station_system.GetInputPort("hand.command"))
    builder.Connect(executor.GetOutputPort("hand.finger_preshape"), station_system.GetInputPort("hand.finger_preshape"))
    for name in ("wam.arm_mode", "wam.palm_target", "wam.palm_force"):
        builder.Connect(executor.GetOutputPort(name), station_system.GetInputPort(name))
    if arm:
        builder.Connect(executor.GetOutputPort("wam.desired_state"), station_system.GetInputPort("wam.desired_state"))


def _hold(q: np.ndarray, t: float):
    """A trajectory that holds joint angles q from time t on."""
    path = JointPath()
    path.add(t, q)
    path.add(t + 1.0, q)
    return path.ToTrajectory()
