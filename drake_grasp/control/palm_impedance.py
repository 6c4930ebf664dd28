"""A task-space impedance controller for the WAM: the palm as a spring, with a force along its normal.

Why: the paper's compliance is the hand's (torque close, breakaway clutch), and the arm that carries it
is held by position. A position-held palm cannot keep the fingertips on a table while they close: the
tips' arcs leave the table, or the palm strikes it and the clutches break away (docs/design.md §5.4b).
Kazemi et al. (RSS 2012; Autonomous Robots 2014) grasp pens and phones from a table with the same WAM
and BarrettHand by landing the fingertips on it and closing while the arm keeps a light force on the
table. The paper admits such compliance "irrespective of whether it is achieved passively or
actively"; this system is the active one, a compliance mode of the arm.

The law (Hogan's impedance control, gravity compensated by the station's `GravityCompensation`):

    F_P = K (x_d - x)_P - D V_P + [0, 0, 0, 0, 0, f]          (palm frame P; rotational rows first)
    tau = J_W^T R_WP F_P + N (K_n (q_ref - q) - D_n v)

* x_d is `palm_target` (X_WPd); the pose error is expressed in P: the position error R_WP^T (p_d - p)
  and the rotation error as the axis-angle vector of R_WP^T R_WPd. K and D are diagonal, per axis of P
  (`stiffness`, `damping`: N*m/rad and N/m, N*m*s/rad and N*s/m).
* f is `normal_force`, N, along +z_P: the palm normal, which points from the palm into what it grasps,
  so a palm facing down presses f newtons down.
* N = I - J^T (J^T)^+ projects the null-space posture torque (the WAM has 7 joints for 6 task
  coordinates: its elbow) so that it exerts no force on the palm; q_ref is the joint command's q.
* tau is clipped to the WAM's peak efforts (`robot.arm.EFFORT_LIMITS`).

How it shares the arm with the joint PD. The station's joint PD is implicit in the plant (its gains
are the plant's; the physics stays as it is). While this controller is active it hands the PD the
measured state as its desired state, so the PD's torque is -K_p h v - K_d (v' - v) (h the 5 ms step): a
small extra joint damping and inertia, and zero at rest. The static force and stiffness are this
law's alone (tests/test_palm_impedance.py measures both). Inactive, it passes the joint command
through and adds no torque, so a station that never activates it behaves bit for bit as before.
Handing over costs no jump when the target is the palm's pose at the switch (the executor sets it so)
and the force ramps from zero (the executor's job too).

Explicit in time: the torque is computed from the state at the start of each plant step. With the
default gains the highest frequency, a rotation of the wrist about the palm normal, is about 40 rad/s
(< 2/h = 400 rad/s), and its damping ratio is about 0.5.
"""

import dataclasses

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import JacobianWrtVariable, ModelInstanceIndex
from pydrake.systems.framework import BasicVector, Context, LeafSystem

from drake_grasp.robot import arm
from drake_grasp.robot.hand import HAND_JOINTS


@dataclasses.dataclass
class PalmImpedanceParams:
    """The controller's default gains (its `stiffness` and `damping` ports override them when connected).

    Attributes:
        stiffness: [k_rx, k_ry, k_rz, k_x, k_y, k_z] about and along the palm frame's axes,
            N*m/rad and N/m. Along the normal (z) soft, so that a force setpoint of a few newtons
            holds the fingertips on a table over the centimetres their arcs rise and fall; across
            it stiff enough to keep the grasp's place against the tips' friction on the table.
        damping: the same axes, N*m*s/rad and N*s/m: about half of critical for the WAM's palm
            (about 4 kg effective across, 0.02 kg*m^2 about the normal), and within explicit
            stability at the 5 ms step.
        nullspace_stiffness, nullspace_damping: the elbow's posture gains, N*m/rad and N*m*s/rad.
    """

    stiffness: list[float] = dataclasses.field(default_factory=lambda: [30.0, 30.0, 30.0, 1500.0, 1500.0, 400.0])
    damping: list[float] = dataclasses.field(default_factory=lambda: [1.0, 1.0, 1.0, 80.0, 80.0, 40.0])
    nullspace_stiffness: float = 20.0
    nullspace_damping: float = 2.0

    def validate(self) -> None:
        """Raises ValueError (one line) for a gain that is not a finite number >= 0."""
        for name in ("stiffness", "damping"):
            values = getattr(self, name)
            if len(values) != 6 or not all(np.isfinite(v) and v >= 0 for v in values):
                raise ValueError(f"{name} needs 6 finite gains >= 0 (rotational x, y, z, then translational), got {values}")
        for name in ("nullspace_stiffness", "nullspace_damping"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value >= 0):
                raise ValueError(f"{name} must be a finite number >= 0, got {value}")


def rotation_error(R_WP: RotationMatrix, R_WPd: RotationMatrix) -> np.ndarray:
    """The axis-angle vector (rad) of the rotation that takes P to Pd, expressed in P."""
    aa = (R_WP.inverse() @ R_WPd).ToAngleAxis()
    return aa.axis() * aa.angle()


def palm_wrench(X_WP: RigidTransform, V_WP: np.ndarray, X_WPd: RigidTransform, stiffness: np.ndarray,
                damping: np.ndarray, normal_force: float) -> np.ndarray:
    """The spatial force on the palm, [torque; force] in the world frame (N*m, N), of the impedance law.

    Args:
        X_WP: the palm's pose; V_WP: its spatial velocity [w; v] in the world frame (rad/s, m/s).
        X_WPd: the target pose.
        stiffness, damping: per axis of P, rotational first (module docstring).
        normal_force: the force setpoint along +z_P, N.
    """
    R_WP = X_WP.rotation()
    R_PW = R_WP.inverse().matrix()
    error = np.concatenate([rotation_error(R_WP, X_WPd.rotation()),
                            R_PW @ (X_WPd.translation() - X_WP.translation())])
    V_P = np.concatenate([R_PW @ V_WP[:3], R_PW @ V_WP[3:]])
    F_P = stiffness * error - damping * V_P
    F_P[5] += normal_force
    R = R_WP.matrix()
    return np.concatenate([R @ F_P[:3], R @ F_P[3:]])


class PalmImpedanceController(LeafSystem):
    """The WAM's palm as a spring and damper with a force along its normal (module docstring).

    Input ports:
        wam.state (14): the WAM's measured [q; v].
        joint_command (14): the joint PD's desired [q; v] (what drives the arm while inactive; its q is
            the null-space posture while active).
        active (1): > 0.5: this law drives the arm; else the joint PD does. Unconnected: inactive.
        palm_target: the target pose X_WPd (abstract RigidTransform). Unconnected: the palm's pose
            at the joint command's q.
        normal_force (1): the force setpoint along +z_P, N. Unconnected: 0.
        stiffness (6), damping (6): per axis of the palm frame, rotational first. Unconnected: the
            params' defaults.
    Output ports:
        wam.desired_state (14): for the plant's joint PD: the joint command while inactive, the
            measured state while active.
        wam.actuation (7): the law's torque while active (0 while inactive), N*m, to be added to the
            gravity compensation.
    """

    def __init__(self, plant: MultibodyPlant, wam: ModelInstanceIndex, params: PalmImpedanceParams | None = None):
        super().__init__()
        self._params = params or PalmImpedanceParams()
        self._params.validate()
        self._plant = plant
        self._wam = wam
        self._plant_context = plant.CreateDefaultContext()
        self._palm = plant.GetFrameByName(HAND_JOINTS.palm_frame)
        self._world = plant.world_frame()
        rows = plant.GetVelocitiesFromArray(wam, np.arange(plant.num_velocities())).astype(int)
        self._arm_columns = rows
        self._state_port = self.DeclareVectorInputPort("wam.state", 14)
        self._command_port = self.DeclareVectorInputPort("joint_command", 14)
        self._active_port = self.DeclareVectorInputPort("active", 1)
        self._target_port = self.DeclareAbstractInputPort("palm_target", AbstractValue.Make(RigidTransform()))
        self._force_port = self.DeclareVectorInputPort("normal_force", 1)
        self._stiffness_port = self.DeclareVectorInputPort("stiffness", 6)
        self._damping_port = self.DeclareVectorInputPort("damping", 6)
        self.DeclareVectorOutputPort("wam.desired_state", 14, self._CalcDesiredState)
        self.DeclareVectorOutputPort("wam.actuation", arm.NUM_JOINTS, self._CalcActuation)

    @property
    def params(self) -> PalmImpedanceParams:
        return self._params

    def is_active(self, context: Context) -> bool:
        return self._active_port.HasValue(context) and self._active_port.Eval(context)[0] > 0.5

    def palm_pose(self, q: np.ndarray) -> RigidTransform:
        """The palm's pose at arm joint angles q."""
        self._plant.SetPositions(self._plant_context, self._wam, q)
        return self._palm.CalcPoseInWorld(self._plant_context)

    def _CalcDesiredState(self, context: Context, output: BasicVector) -> None:
        source = self._state_port if self.is_active(context) else self._command_port
        output.SetFromVector(source.Eval(context))

    def _gains(self, context: Context) -> tuple[np.ndarray, np.ndarray]:
        k = self._stiffness_port.Eval(context) if self._stiffness_port.HasValue(context) else self._params.stiffness
        d = self._damping_port.Eval(context) if self._damping_port.HasValue(context) else self._params.damping
        return np.asarray(k, float), np.asarray(d, float)

    def _CalcActuation(self, context: Context, output: BasicVector) -> None:
        if not self.is_active(context):
            output.SetFromVector(np.zeros(arm.NUM_JOINTS))
            return
        output.SetFromVector(self.torque(context))

    def torque(self, context: Context) -> np.ndarray:
        """The law's joint torques at the context's inputs, N*m (clipped to the WAM's peak efforts)."""
        x = np.asarray(self._state_port.Eval(context), float)
        q, v = x[:7], x[7:]
        q_ref = np.asarray(self._command_port.Eval(context), float)[:7]
        plant, pc = self._plant, self._plant_context
        plant.SetPositions(pc, self._wam, q)
        plant.SetVelocities(pc, self._wam, v)
        X_WP = self._palm.CalcPoseInWorld(pc)
        J = plant.CalcJacobianSpatialVelocity(pc, JacobianWrtVariable.kV, self._palm, np.zeros(3),
                                              self._world, self._world)[:, self._arm_columns]
        X_WPd = self._target_port.Eval(context) if self._target_port.HasValue(context) else self.palm_pose(q_ref)
        force = float(self._force_port.Eval(context)[0]) if self._force_port.HasValue(context) else 0.0
        stiffness, damping = self._gains(context)
        F_W = palm_wrench(X_WP, J @ v, X_WPd, stiffness, damping, force)
        tau = J.T @ F_W
        # The elbow's posture, projected so that it pushes nothing at the palm.
        N = np.eye(7) - J.T @ np.linalg.pinv(J.T, rcond=1e-4)
        tau += N @ (self._params.nullspace_stiffness * (q_ref - q) - self._params.nullspace_damping * v)
        return np.clip(tau, -arm.EFFORT_LIMITS, arm.EFFORT_LIMITS)
