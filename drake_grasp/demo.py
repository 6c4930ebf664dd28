"""The station demo: pick an object up with the hand's compliance, using its ground-truth pose.

The arm brings the open hand above the object (palm down), descends until the palm is just above the
object's top, closes the fingers with torque close and breakaway, lifts 10 cm and holds 10 s. The
result says whether the object was held and how much it slipped in the hand during the hold.

This is the smallest complete use of the station; the trial runner (`drake_grasp.trial`) does the
same with the paper's protocol, the three compliant grasps, and camera estimates instead of truth.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
from pydrake.geometry import Meshcat, MeshcatVisualizer, MeshcatVisualizerParams, Role
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from drake_grasp.control.arm_motion import ArmKinematics, JointPath
from drake_grasp.hand import ComplianceMode, HandAction
from drake_grasp.objects import ObjectSpec
from drake_grasp.station import MakeStation, Scenario, Station

LIFT_HEIGHT = 0.10  # m (the paper's protocol)
HOLD_TIME = 10.0  # s (the paper's protocol)
PREGRASP_CLEARANCE = 0.12  # m of free space between palm and object top before the descent (assumed)
APPROACH_GAP = 0.005  # m left between palm and the object's top at the end of the descent (assumed)


@dataclasses.dataclass
class DemoResult:
    """What happened. Distances in m, angles in rad, times in s."""

    object_name: str
    mode: str
    held: bool
    lift: float  # how far the object rose above its resting height at the end
    slip_distance: float  # object position change in the palm frame during the hold
    slip_angle: float  # object orientation change in the palm frame during the hold
    hold_time: float
    breakaway: list[bool]
    breakaway_angles: list[float]
    final_finger_angles: list[float]  # proximal 1..3, distal 1..3
    sim_time: float
    wall_time: float

    def summary(self) -> str:
        verdict = "held" if self.held else "NOT held"
        angles = ", ".join("-" if math.isnan(a) else f"{math.degrees(a):.0f}" for a in self.breakaway_angles)
        return (
            f"{self.object_name} ({self.mode} mode): {verdict}; lifted {self.lift * 100:.1f} cm; "
            f"slip over the {self.hold_time:.0f} s hold {self.slip_distance * 1000:.2f} mm, "
            f"{math.degrees(self.slip_angle):.2f} deg; breakaway at [{angles}] deg; "
            f"{self.sim_time:.1f} s simulated in {self.wall_time:.1f} s "
            f"({self.sim_time / max(self.wall_time, 1e-9):.1f}x real time)"
        )


def default_mode(spec: ObjectSpec) -> ComplianceMode:
    """Spherical mode for round objects, cylindrical for the rest (ground truth, for the demo only)."""
    return ComplianceMode.SPHERICAL if spec.closest_primitive == "sphere" else ComplianceMode.CYLINDRICAL


def top_down_palm_pose(X_WO: RigidTransform, spec: ObjectSpec, height_above_top: float) -> RigidTransform:
    """Palm pose X_WP above the object, palm normal down; hand x along the object's horizontal axis.

    In the cylindrical mode F1/F2 and F3 face each other across the hand's y axis, so the fingers
    close across the object's principal axis.
    """
    top = X_WO.translation()[2] + _half_height(X_WO, spec)
    axis_W = np.array([1.0, 0.0, 0.0])
    if spec.principal_axis is not None:
        axis_W = X_WO.rotation() @ np.asarray(spec.principal_axis)
        axis_W[2] = 0.0
        if np.linalg.norm(axis_W) < 1e-6:
            axis_W = np.array([1.0, 0.0, 0.0])
    x_P = axis_W / np.linalg.norm(axis_W)
    z_P = np.array([0.0, 0.0, -1.0])
    y_P = np.cross(z_P, x_P)
    R_WP = RotationMatrix(np.column_stack([x_P, y_P, z_P]))
    p = X_WO.translation().copy()
    p[2] = top + height_above_top
    return RigidTransform(R_WP, p)


def _half_height(X_WO: RigidTransform, spec: ObjectSpec) -> float:
    """Half of the object's vertical extent in the world (from its oriented bounding box)."""
    R = X_WO.rotation().matrix()
    return 0.5 * float(np.abs(R[2, :]) @ np.asarray(spec.extents))


def run_demo(scenario: Scenario, mode: ComplianceMode | None = None, replay_html: str | None = None,
             object_spec: ObjectSpec | None = None, hold_time: float = HOLD_TIME) -> DemoResult:
    """Builds the station for `scenario`, runs the pick-up, and judges it.

    Args:
        scenario: the station's scenario (its object placement says what to pick up).
        mode: the compliance mode (default: `default_mode` of the object).
        replay_html: if given, write a Meshcat replay there.
        object_spec: the object, if already resolved.
        hold_time: how long to hold after the lift, s (the paper's protocol: 10 s).
    """
    station = MakeStation(scenario, object_spec, camera=False)
    spec = station.object_spec
    mode = mode or default_mode(spec)
    plant = station.plant
    X_WO = station.X_WO_nominal()

    # Arm waypoints from inverse kinematics.
    kinematics = ArmKinematics(plant, station.wam)
    X_pre = top_down_palm_pose(X_WO, spec, PREGRASP_CLEARANCE)
    X_grasp = top_down_palm_pose(X_WO, spec, APPROACH_GAP)
    X_lift = RigidTransform(X_grasp.rotation(), X_grasp.translation() + [0, 0, LIFT_HEIGHT])
    q_ready = np.array([0.0, 0.6, 0.0, 1.6, 0.0, 0.9, 0.0])
    q_pre = kinematics.solve(X_pre, q_ready)
    descent = kinematics.straight_line(X_pre, X_grasp, q_pre)
    lift = kinematics.straight_line(X_grasp, X_lift, descent[-1])

    # Timeline (s): spread, descend, close, lift, hold.
    t_descend, t_close = 0.5, 2.0
    t_lift = t_close + 1.8
    t_hold = t_lift + 1.5
    t_end = t_hold + hold_time
    path = JointPath()
    path.add(0.0, q_pre)
    path.add(t_descend, q_pre)
    path.add_segment(t_descend, t_close - t_descend, descent)
    path.add(t_lift, descent[-1])
    path.add_segment(t_lift, t_hold - t_lift, lift)
    path.add(t_end, lift[-1])
    arm_trajectory = path.ToTrajectory()
    hand_commands = PiecewisePolynomial.ZeroOrderHold(
        [0.0, t_close, t_end], np.array([[mode.spread] * 3, [HandAction.OPEN, HandAction.CLOSE, HandAction.CLOSE]]))

    builder = DiagramBuilder()
    builder.AddNamedSystem("station", station.diagram)
    arm_source = builder.AddNamedSystem("arm_trajectory", TrajectorySource(arm_trajectory, output_derivative_order=1))
    hand_source = builder.AddNamedSystem("hand_commands", TrajectorySource(hand_commands))
    builder.Connect(arm_source.get_output_port(), station.diagram.GetInputPort("wam.desired_state"))
    builder.Connect(hand_source.get_output_port(), station.diagram.GetInputPort("hand.command"))
    meshcat = None
    if replay_html:
        meshcat = Meshcat()
        MeshcatVisualizer.AddToBuilder(builder, station.diagram.GetOutputPort("query_object"), meshcat,
                                       MeshcatVisualizerParams(role=Role.kIllustration))
    diagram = builder.Build()

    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    plant.SetPositions(plant_context, station.wam, q_pre)
    station.hand_controller.SetInitialFingers(station.hand_controller.GetMyMutableContextFromRoot(context))
    object_body = plant.get_body(plant.GetBodyIndices(station.object_instance)[0])
    palm = plant.GetFrameByName("bh_palm")

    def X_PO() -> RigidTransform:
        return palm.CalcPoseInWorld(plant_context).inverse() @ object_body.EvalPoseInWorld(plant_context)

    if meshcat is not None:
        p_WO = X_WO.translation()
        meshcat.SetCameraPose(p_WO + [0.45, -0.75, 0.45], p_WO)
        meshcat.StartRecording()
    wall_start = time.perf_counter()
    simulator.AdvanceTo(t_hold)
    X_PO_start = X_PO()
    simulator.AdvanceTo(t_end)
    wall = time.perf_counter() - wall_start
    X_PO_end = X_PO()
    if meshcat is not None:
        meshcat.StopRecording()
        meshcat.PublishRecording()
        with open(replay_html, "w") as f:
            f.write(meshcat.StaticHtml())

    X_WO_end = object_body.EvalPoseInWorld(plant_context)
    rise = X_WO_end.translation()[2] - X_WO.translation()[2]
    slip = X_PO_start.inverse() @ X_PO_end
    slip_distance = float(np.linalg.norm(X_PO_end.translation() - X_PO_start.translation()))
    slip_angle = float(slip.rotation().ToAngleAxis().angle())
    status = station.diagram.GetOutputPort("hand.finger_status").Eval(
        station.diagram.GetMyContextFromRoot(context))
    q_hand = station.hand_controller._index.joint_positions(
        plant.get_state_output_port(station.hand).Eval(plant_context))
    held = rise > 0.5 * LIFT_HEIGHT and slip_distance < 0.01 and slip_angle < math.radians(10)
    return DemoResult(
        object_name=spec.name, mode=mode.name.lower(), held=bool(held), lift=float(rise),
        slip_distance=slip_distance, slip_angle=slip_angle, hold_time=hold_time,
        breakaway=[bool(b > 0.5) for b in status[:3]], breakaway_angles=[float(a) for a in status[3:]],
        final_finger_angles=[float(a) for a in q_hand[2:8]], sim_time=t_end, wall_time=wall,
    )
