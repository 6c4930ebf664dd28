"""Arm motion: inverse kinematics for a palm pose, and smooth joint trajectories through palm poses.

The WAM is position controlled (joint PD with gravity compensation in the station), so moving the
hand means handing the station a desired joint trajectory. These functions make one from palm poses
X_WP (P = the hand's ``bh_palm`` frame: origin at the palm centre, z along the palm normal).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex
from pydrake.solvers import Solve
from pydrake.trajectories import PiecewisePolynomial

from drake_grasp.robot import arm, hand
from drake_grasp.robot.hand import HAND_JOINTS

# How far above the table the arm's shell and the hand base must stay along a planned path, m (a
# choice: the fingers, not the arm or the palm's housing, are what may touch the table).
TABLE_MARGIN = 0.005


class ReachError(RuntimeError):
    """The arm cannot put the palm at the requested pose."""


UNREACHABLE = "arm could not reach"  # a trial's failure reason when a ReachError stops it


@dataclasses.dataclass
class ArmKinematics:
    """Inverse kinematics of the WAM for palm poses, on the station's plant.

    Attributes:
        plant: the station's (finalized) plant.
        wam: the WAM's model instance.
        position_tolerance: allowed palm position error, m.
        angle_tolerance: allowed palm orientation error, rad.
        table_z: the table top's height, m (the station's is the world's z = 0 plane:
            models/wam_barrett.dmd.yaml).
    """

    plant: MultibodyPlant
    wam: ModelInstanceIndex
    position_tolerance: float = 1e-3
    angle_tolerance: float = np.radians(1.0)
    table_z: float = 0.0

    def __post_init__(self):
        self._palm = self.plant.GetFrameByName(HAND_JOINTS.palm_frame)
        self._context = self.plant.CreateDefaultContext()
        q = np.arange(self.plant.num_positions())
        self._arm_rows = self.plant.GetPositionsFromArray(self.wam, q).astype(int)
        # The arm's shell as spheres in its links' frames: each joint (the previous D-H origin) with
        # the link's radius, and the middle of each link with 0.8 of it (modelgen's visual shell).
        self._shell = []
        for i in range(2, arm.NUM_JOINTS + 1):
            body = self.plant.GetBodyByName(f"wam_link_{i}", self.wam)
            X_prev_i = self.plant.GetFrameByName(f"wam_link_{i - 1}", self.wam).CalcPose(
                self._context, body.body_frame())  # at q = 0: where link i's joint is, in link i
            p_joint = X_prev_i.translation()
            self._shell.append((body.body_frame(), np.array([p_joint, p_joint / 2]),
                                np.array([1.0, 0.8]) * arm.link_radius(i)))
        self._hand_base = self.plant.GetFrameByName(HAND_JOINTS.base_frame)

    def lowest_point(self, q_arm: np.ndarray) -> tuple[float, str]:
        """The lowest point of the arm's shell and of the hand base's housing (a cylinder of the
        palm's radius and height) at arm joint angles q_arm: (its height, m; which part)."""
        self.plant.SetPositions(self._context, self.wam, q_arm)
        lowest = (np.inf, "")
        for frame, points_L, radii in self._shell:  # one pose per link
            z = (frame.CalcPoseInWorld(self._context) @ points_L.T)[2] - radii
            lowest = min(lowest, (float(z.min()), frame.body().name()))
        X_WH = self._hand_base.CalcPoseInWorld(self._context)
        axis = X_WH.rotation().col(2)
        centre = X_WH @ np.array([0.0, 0.0, hand.PALM_HEIGHT / 2])
        z = centre[2] - hand.PALM_HEIGHT / 2 * abs(axis[2]) - hand.BASE_RADIUS * np.sqrt(max(0.0, 1 - axis[2] ** 2))
        return min(lowest, (float(z), "hand base"))

    def check_table_clearance(self, q_path) -> None:
        """Raises ReachError if the arm's shell or the hand base comes within TABLE_MARGIN of the
        table anywhere along q_path (joint angles, each 7)."""
        for q in q_path:
            z, part = self.lowest_point(q)
            if z < self.table_z + TABLE_MARGIN:
                p = self.palm_pose(q).translation()
                raise ReachError(f"the arm would strike the table ({part} {1000 * (z - self.table_z):.0f} mm from it) "
                                 f"with the palm at ({p[0]:.3f}, {p[1]:.3f}, {p[2]:.3f}) m")

    def palm_pose(self, q_arm: np.ndarray) -> RigidTransform:
        """Forward kinematics: X_WP at arm joint angles q_arm."""
        self.plant.SetPositions(self._context, self.wam, q_arm)
        return self._palm.CalcPoseInWorld(self._context)

    def solve(self, X_WP: RigidTransform, q_seed: np.ndarray) -> np.ndarray:
        """Arm joint angles (7) that put the palm at X_WP, closest to q_seed.

        Raises:
            ReachError: if no solution within the tolerances and joint limits was found.
        """
        ik = InverseKinematics(self.plant, self._context, with_joint_limits=True)
        q = ik.q()
        prog = ik.get_mutable_prog()
        # Only the arm moves: every other position stays as it is in the context.
        q_now = self.plant.GetPositions(self._context)
        others = np.setdiff1d(np.arange(len(q_now)), self._arm_rows)
        q_now[self._arm_rows] = q_seed
        if len(others):
            prog.AddBoundingBoxConstraint(q_now[others], q_now[others], q[others])
        tol = self.position_tolerance
        ik.AddPositionConstraint(self._palm, np.zeros(3), self.plant.world_frame(),
                                 X_WP.translation() - tol, X_WP.translation() + tol)
        ik.AddOrientationConstraint(self._palm, RigidTransform().rotation(), self.plant.world_frame(),
                                    X_WP.rotation(), self.angle_tolerance)
        prog.AddQuadraticErrorCost(np.eye(len(self._arm_rows)), q_seed, q[self._arm_rows])
        prog.SetInitialGuess(q, q_now)
        result = Solve(prog)
        if not result.is_success():
            p = X_WP.translation()
            raise ReachError(f"the arm cannot reach a palm pose at ({p[0]:.3f}, {p[1]:.3f}, {p[2]:.3f}) m")
        return result.GetSolution(q)[self._arm_rows]

    def straight_line(self, X_WP_start: RigidTransform, X_WP_end: RigidTransform, q_start: np.ndarray,
                      step: float = 0.02) -> list[np.ndarray]:
        """Joint angles along a straight palm path (orientation interpolated), every `step` m or less.

        The first element is q_start (assumed to be at X_WP_start).
        """
        distance = np.linalg.norm(X_WP_end.translation() - X_WP_start.translation())
        n = max(1, int(np.ceil(distance / step)))
        q_path = [np.asarray(q_start, float)]
        R0 = X_WP_start.rotation().ToQuaternion()
        R1 = X_WP_end.rotation().ToQuaternion()
        from pydrake.common.eigen_geometry import Quaternion  # noqa: local import, used only here
        from pydrake.math import RotationMatrix

        for k in range(1, n + 1):
            s = k / n
            p = (1 - s) * X_WP_start.translation() + s * X_WP_end.translation()
            quat = R0.slerp(s, R1)
            X = RigidTransform(RotationMatrix(Quaternion(quat.wxyz())), p)
            q_path.append(self.solve(X, q_path[-1]))
        return q_path


@dataclasses.dataclass
class JointPath:
    """Arm waypoints with arrival times; becomes a smooth trajectory that stops at each segment's end."""

    times: list[float] = dataclasses.field(default_factory=list)
    positions: list[np.ndarray] = dataclasses.field(default_factory=list)
    stops: list[bool] = dataclasses.field(default_factory=list)

    def add(self, t: float, q: np.ndarray, stop: bool = True) -> None:
        """Arrive at q at time t (s); `stop` makes the arm come to rest there."""
        if self.times and t <= self.times[-1]:
            raise ValueError("JointPath times must increase")
        self.times.append(float(t))
        self.positions.append(np.asarray(q, float).copy())
        self.stops.append(stop)

    def add_segment(self, t_start: float, duration: float, q_path: list[np.ndarray]) -> float:
        """Move through q_path[1:] (q_path[0] is where the arm is) in `duration` s; returns the end time."""
        n = len(q_path) - 1
        for k in range(1, n + 1):
            self.add(t_start + duration * k / n, q_path[k], stop=(k == n))
        return t_start + duration

    def ToTrajectory(self) -> PiecewisePolynomial:
        """A C1 cubic (Hermite) through the waypoints: zero velocity at stops, finite differences elsewhere."""
        t = np.array(self.times)
        Q = np.array(self.positions).T
        V = np.zeros_like(Q)
        for k in range(1, len(t) - 1):
            if not self.stops[k]:
                V[:, k] = (Q[:, k + 1] - Q[:, k - 1]) / (t[k + 1] - t[k - 1])
        return PiecewisePolynomial.CubicHermite(t, Q, V)
