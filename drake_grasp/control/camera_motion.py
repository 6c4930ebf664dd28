"""Camera motion: a desired wrist-camera twist becomes the WAM's desired state (differential IK).

`CameraTwistController` integrates differential inverse kinematics at a fixed rate: each step it
takes the desired twist of the camera frame C (expressed in C, as the visual primitives produce it),
maps it to the world, and asks pydrake's `DoDifferentialInverseKinematics` (a small QP) for the arm's
joint velocities that realise it within joint position, velocity and acceleration limits, with the
redundant degree of freedom pulled toward a nominal posture. It integrates the joint positions (open
loop, like pydrake's `DifferentialInverseKinematicsIntegrator` without its robot-state input) and
outputs [q; v] for the station's `wam.desired_state` (implicit PD with gravity compensation).

Why not `DifferentialInverseKinematicsIntegrator` itself: it takes a desired *pose* and works on all
the plant's positions (here also the hand's joints and the object's free body); the twist interface
and an arm-only Jacobian are what the primitives need. The QP is the same.
"""


import dataclasses

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.inverse_kinematics import (
    DifferentialInverseKinematicsParameters,
    DifferentialInverseKinematicsStatus,
    DoDifferentialInverseKinematics,
)
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame, JacobianWrtVariable, ModelInstanceIndex
from pydrake.systems.framework import Context, LeafSystem

from drake_grasp.robot import arm


@dataclasses.dataclass
class CameraMotionParams:
    """Choices of the camera motion controller (the scenario's `perception:`, diagrams/station.scenarios.yaml).

    Attributes:
        time_step: integration step of the differential IK, s.
        joint_velocity_limit: |q̇| limit of every arm joint, rad/s.
        joint_acceleration_limit: |q̈| limit of every arm joint, rad/s².
        joint_centering_gain: 1/s, pull of the redundant degree of freedom toward the nominal posture.
        max_angular_speed: limit on the camera's angular speed, rad/s.
        max_linear_speed: limit on the camera's linear speed, m/s.
    """

    time_step: float = 0.02
    joint_velocity_limit: float = 1.5
    joint_acceleration_limit: float = 15.0
    joint_centering_gain: float = 1.0
    max_angular_speed: float = 2.0
    max_linear_speed: float = 0.8


_STATUS_CODES = {
    DifferentialInverseKinematicsStatus.kSolutionFound: 0,
    DifferentialInverseKinematicsStatus.kNoSolutionFound: 1,
    DifferentialInverseKinematicsStatus.kStuck: 2,
}


class CameraTwistController(LeafSystem):
    """Desired camera twist → WAM desired state, through differential inverse kinematics.

    Input ports:
        V_C_desired (6): desired twist of the camera frame C: [ω; v] (rad/s, m/s), expressed in C.
        active (1, optional): 0 stops the integration (the state is held; nothing is computed), e.g.
            once the grasp supervisor drives the arm itself and this output goes nowhere; unconnected,
            the controller always runs.
    Output ports:
        wam.desired_state (14): [q; v] of the arm's 7 joints (rad, rad/s).
        status (1): the last DifferentialInverseKinematicsStatus (0 found, 1 none found, 2 stuck).
    """

    def __init__(self, plant: MultibodyPlant, wam: ModelInstanceIndex, camera_frame: Frame,
                 X_FC: RigidTransform | None = None, params: CameraMotionParams | None = None):
        """
        Args:
            plant: the station's finalized plant (only its kinematics are used, on a private context).
            wam: the arm's model instance.
            camera_frame: the plant frame F the camera is fixed to (the hand's `wrist_camera`).
            X_FC: the camera's pose in F (the camera config's X_PB; identity by default).
            params: limits and gains.
        """
        super().__init__()
        self.params = params or CameraMotionParams()
        self._plant = plant
        self._plant_context = plant.CreateDefaultContext()
        self._frame = camera_frame
        self._X_FC = X_FC or RigidTransform()
        rows = np.arange(plant.num_velocities())
        self._arm_velocities = plant.GetVelocitiesFromArray(wam, rows).astype(int)
        self._wam = wam
        n = arm.NUM_JOINTS
        p = self.params
        ik = DifferentialInverseKinematicsParameters(n, n)
        ik.set_time_step(p.time_step)
        ik.set_joint_position_limits((arm.LOWER_LIMITS, arm.UPPER_LIMITS))
        ik.set_joint_velocity_limits((-p.joint_velocity_limit * np.ones(n), p.joint_velocity_limit * np.ones(n)))
        ik.set_joint_acceleration_limits((-p.joint_acceleration_limit * np.ones(n),
                                          p.joint_acceleration_limit * np.ones(n)))
        ik.set_joint_centering_gain(p.joint_centering_gain * np.eye(n))
        ik.set_end_effector_angular_speed_limit(p.max_angular_speed)
        ik.set_end_effector_translational_velocity_limits(-p.max_linear_speed * np.ones(3),
                                                         p.max_linear_speed * np.ones(3))
        self._ik = ik
        self._V_C_desired_port = self.DeclareVectorInputPort("V_C_desired", 6)
        self._active_port = self.DeclareVectorInputPort("active", 1)
        self._state = self.DeclareDiscreteState(2 * n)
        self._status = self.DeclareDiscreteState(1)
        self.DeclareStateOutputPort("wam.desired_state", self._state)
        self.DeclareStateOutputPort("status", self._status)
        self.DeclarePeriodicDiscreteUpdateEvent(p.time_step, 0.0, self._Step)

    def SetInitialPositions(self, context: Context, q: np.ndarray) -> None:
        """Starts the integration at arm joint angles q (at rest); also the nominal posture."""
        q = np.asarray(q, float)
        context.get_mutable_discrete_state(self._state).SetFromVector(np.concatenate([q, np.zeros(len(q))]))
        self._ik.set_nominal_joint_position(q)

    def camera_pose(self, q: np.ndarray) -> RigidTransform:
        """X_WC at arm joint angles q (forward kinematics)."""
        self._plant.SetPositions(self._plant_context, self._wam, q)
        return self._frame.CalcPoseInWorld(self._plant_context) @ self._X_FC

    def _Step(self, context: Context, discrete_state) -> None:
        if self._active_port.HasValue(context) and self._active_port.Eval(context)[0] < 0.5:
            return  # the discrete state is left as it is
        n = arm.NUM_JOINTS
        x = context.get_discrete_state(self._state).get_value()
        q, v = x[:n].copy(), x[n:].copy()
        V_C = self._V_C_desired_port.Eval(context)
        X_WC = self.camera_pose(q)
        R_WC = X_WC.rotation().matrix()
        V_W = np.concatenate([R_WC @ V_C[:3], R_WC @ V_C[3:]])
        J = self._plant.CalcJacobianSpatialVelocity(
            self._plant_context, JacobianWrtVariable.kV, self._frame, self._X_FC.translation(),
            self._plant.world_frame(), self._plant.world_frame())[:, self._arm_velocities]
        result = DoDifferentialInverseKinematics(q, v, V_W, J, self._ik)
        if result.status != DifferentialInverseKinematicsStatus.kNoSolutionFound and result.joint_velocities is not None:
            # A solution, possibly slowed down along the desired direction (kStuck when nearly 0).
            v_next = np.asarray(result.joint_velocities).reshape(n)
        else:
            v_next = np.zeros(n)
        q_next = np.clip(q + self.params.time_step * v_next, arm.LOWER_LIMITS, arm.UPPER_LIMITS)
        discrete_state.get_mutable_vector(self._state).SetFromVector(np.concatenate([q_next, v_next]))
        discrete_state.get_mutable_vector(self._status).SetFromVector([float(_STATUS_CODES[result.status])])
