"""The planner's search space: hand pose in axis-angle form relative to the object, plus posture.

GraspIt!'s default "Axis-angle" space (src/EGPlanner/searchStateImpl.cpp, ``PositionStateAA``;
docs/design.md §4.6) places the hand's *approach frame* relative to the object with 6 variables: a
translation (Tx, Ty, Tz) and a rotation by α about the axis (sin θ cos φ, sin θ sin φ, cos θ). With
the Barrett's two eigengrasp amplitudes that makes the 8 variables annealed. The Barrett's approach
frame is its palm frame (GraspIt!'s Barrett.xml: approach direction +z from the palm origin, which
sits on the palm surface): here, our ``bh_palm`` frame P, ``PALM_HEIGHT`` along the palm normal from
the hand base H, with the same axes. So the state gives X_OP, and X_OH = X_OP · X_PH.

A state is a plain (8,) array in the order of ``SEARCH_VARIABLES``: [Tx, Ty, Tz, θ, φ, α, a0, a1]
(GraspIt!'s neighbour function also visits the position variables first). Translations are in
metres here; GraspIt!'s ranges and jumps are in mm and converted once, below.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.math import RigidTransform, RotationMatrix

from baselines.eigengrasp import eigengrasps
from drake_grasp.robot import hand

M_PER_MM = 1e-3


@dataclasses.dataclass(frozen=True)
class SearchVariable:
    """One annealed variable.

    Attributes:
        name: GraspIt!'s name ("Tx", "theta", "EG 0", ...).
        lower, upper: Range (m for translations, rad for angles, dimensionless amplitudes).
        max_jump: Scale of a neighbour step, in the variable's unit (a step is at most this).
        circular: Whether the variable wraps around at its ends (φ).
    """

    name: str
    lower: float
    upper: float
    max_jump: float
    circular: bool = False

    @property
    def span(self) -> float:
        """upper − lower (GraspIt!'s getRange)."""
        return self.upper - self.lower


# --- docs/design.md §4.6 (searchStateImpl.cpp PositionStateAA, mm and rad; PostureStateEigen). ----
TRANSLATION_XY_RANGE_MM = (-250.0, 250.0)
TRANSLATION_Z_RANGE_MM = (-250.0, 350.0)
TRANSLATION_MAX_JUMP_MM = 150.0

SEARCH_VARIABLES: tuple[SearchVariable, ...] = (
    SearchVariable("Tx", *(v * M_PER_MM for v in TRANSLATION_XY_RANGE_MM), TRANSLATION_MAX_JUMP_MM * M_PER_MM),
    SearchVariable("Ty", *(v * M_PER_MM for v in TRANSLATION_XY_RANGE_MM), TRANSLATION_MAX_JUMP_MM * M_PER_MM),
    SearchVariable("Tz", *(v * M_PER_MM for v in TRANSLATION_Z_RANGE_MM), TRANSLATION_MAX_JUMP_MM * M_PER_MM),
    SearchVariable("theta", 0.0, math.pi, math.pi / 5.0),
    SearchVariable("phi", -math.pi, math.pi, math.pi / 2.0, circular=True),
    SearchVariable("alpha", 0.0, math.pi, math.pi / 2.0),
    SearchVariable("EG 0", *eigengrasps.AMPLITUDE_RANGE, eigengrasps.AMPLITUDE_MAX_JUMP),
    SearchVariable("EG 1", *eigengrasps.AMPLITUDE_RANGE, eigengrasps.AMPLITUDE_MAX_JUMP),
)
NUM_VARIABLES = len(SEARCH_VARIABLES)
LOWER = np.array([v.lower for v in SEARCH_VARIABLES])
UPPER = np.array([v.upper for v in SEARCH_VARIABLES])
MAX_JUMP = np.array([v.max_jump for v in SEARCH_VARIABLES])
CIRCULAR = np.array([v.circular for v in SEARCH_VARIABLES])
TX, TY, TZ, THETA, PHI, ALPHA, EG0, EG1 = range(NUM_VARIABLES)

# Reset state (docs/design.md §4.6): the palm 350 mm along the object's z, α = π/2 (θ = φ = 0: about the
# object's z), amplitudes at −4 (hand open).
RESET_TZ_MM = 350.0
RESET_STATE = np.array([0.0, 0.0, RESET_TZ_MM * M_PER_MM, 0.0, 0.0, math.pi / 2.0,
                        *eigengrasps.RESET_AMPLITUDES])

X_PH = RigidTransform([0.0, 0.0, -hand.PALM_HEIGHT])
"""Pose of the hand base H in the palm (approach) frame P."""

# --- docs/design.md §4.6 (searchState.cpp HandObjectState::distance, simAnnPlanner.cpp). ----------
ANGLE_DISTANCE_WEIGHT = 0.5  # GraspIt!: "0.5 weight out of thin air".


def in_range(state) -> bool:
    """Whether every variable of a state lies in its range."""
    state = np.asarray(state, dtype=float)
    return bool(np.all((state >= LOWER) & (state <= UPPER)))


def axis_angle_quaternion(theta: float, phi: float, alpha: float) -> tuple[float, float, float, float]:
    """Unit quaternion (w, x, y, z) of the rotation by α about (sinθ cosφ, sinθ sinφ, cosθ)."""
    s = math.sin(0.5 * alpha)
    sin_theta = math.sin(theta)
    return (math.cos(0.5 * alpha), s * sin_theta * math.cos(phi), s * sin_theta * math.sin(phi),
            s * math.cos(theta))


def palm_pose(state) -> RigidTransform:
    """X_OP: the palm (approach) frame in the object frame for a state."""
    w, x, y, z = axis_angle_quaternion(state[THETA], state[PHI], state[ALPHA])
    return RigidTransform(RotationMatrix(Quaternion(w, x, y, z)), np.asarray(state[TX:TZ + 1], dtype=float))


def hand_pose(state) -> RigidTransform:
    """X_OH: the hand base frame in the object frame for a state."""
    return palm_pose(state) @ X_PH


def amplitudes(state) -> np.ndarray:
    """The eigengrasp amplitudes (a0, a1) of a state."""
    return np.asarray(state[EG0:EG1 + 1], dtype=float)


def state_from_palm_pose(X_OP: RigidTransform, amplitudes_=(0.0, 0.0)) -> np.ndarray:
    """The state whose palm pose is X_OP (GraspIt!'s PositionStateAA::setTran), with amplitudes.

    The rotation angle is put in [0, π] (flipping the axis), and an axis along ±z gets φ = 0.
    """
    p = X_OP.translation()
    q = X_OP.rotation().ToQuaternion()
    w, v = q.w(), np.array([q.x(), q.y(), q.z()])
    if w < 0.0:
        w, v = -w, -v
    s = float(np.linalg.norm(v))
    alpha = 2.0 * math.atan2(s, w)  # in [0, π] since w ≥ 0
    axis = v / s if s > 1e-12 else np.array([0.0, 0.0, 1.0])
    if abs(axis[0]) > 1e-7 or abs(axis[1]) > 1e-7:
        phi = math.atan2(axis[1], axis[0])
        theta = math.atan2(math.hypot(axis[0], axis[1]), axis[2])
    else:
        phi, theta = 0.0, (0.0 if axis[2] > 0 else math.pi)
    return np.array([p[0], p[1], p[2], theta, phi, alpha, *amplitudes_], dtype=float)


def palm_position_and_quaternion(state) -> tuple[tuple[float, float, float], tuple[float, float, float, float]]:
    """The palm frame's origin in O (m) and orientation quaternion (w, x, y, z) for a state."""
    return (state[TX], state[TY], state[TZ]), axis_angle_quaternion(state[THETA], state[PHI], state[ALPHA])


def pose_distance(pose_a, pose_b, max_radius: float) -> float:
    """:func:`state_distance` between two (position, quaternion) pairs of palm_position_and_quaternion."""
    dp = math.dist(pose_a[0], pose_b[0]) / max_radius
    dot = min(1.0, abs(sum(x * y for x, y in zip(pose_a[1], pose_b[1]))))
    angle = 2.0 * math.acos(dot)
    return max(dp, ANGLE_DISTANCE_WEIGHT * angle / math.pi)


def state_distance(a, b, max_radius: float) -> float:
    """GraspIt!'s distance between two states, used to merge near-duplicates in the best list.

    max(|Δp| / ρ, 0.5 |Δangle| / π): Δp between the palm (approach) frame origins, ρ the object's
    max radius (m), Δangle the angle of the rotation between the two palm frames. The posture is
    ignored. GraspIt! takes the angle of the relative quaternion as stored (up to 2π); the minimal
    angle (≤ π) is used here, so two poses 10° apart always count as close.

    Args:
        a, b: States (8,).
        max_radius: The object's largest distance from its centre of mass to its surface, m.
    """
    return pose_distance(palm_position_and_quaternion(a), palm_position_and_quaternion(b), max_radius)
