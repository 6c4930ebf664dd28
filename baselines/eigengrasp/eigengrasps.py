"""The BarrettHand's eigengrasps: two amplitudes -> the hand's joint angles (docs/design.md §4.6).

GraspIt! searches the Barrett's posture in a 2-D eigengrasp subspace of its 4 DOFs
``[spread, flex_1, flex_2, flex_3]`` (spread of each of F1 and F2, and the proximal flexion of each
finger; rad): DOF values = origin + Σ aᵢ eᵢ, clamped to the joint limits (GraspIt!
``PostureStateEigen::getHandDOF`` calls ``Hand::checkSetDOFVals``, which clamps). Sources:
GraspIt! models/robots/Barrett/eigen/barrett_eigen.xml and src/EGPlanner/searchStateImpl.cpp
(docs/design.md §4.6); Ciocarlie & Allen, IJRR 2009.

Our model has 8 joints. A GraspIt! flexion DOF drives both joints of a finger through the clutch in
free motion (distal = proximal / 3, docs/design.md §4.1), so a flexion f gives proximal = f and
distal = f / 3.
Joint limits are our model's (hand.py): proximal 0-140 deg (GraspIt!'s Barrett model allows 144),
distal 0-48 deg, spread 0-180 deg.

Pure numpy, no Drake.
"""

from __future__ import annotations

import numpy as np

from drake_grasp.robot import hand

# --- docs/design.md §4.6 (barrett_eigen.xml). DOF order: [spread, flex_1, flex_2, flex_3], rad. ---
EIGENGRASPS = np.array([
    [1.0, 0.0, 0.0, 0.0],  # EG0: spread alone.
    np.array([0.0, 1.0, 1.0, 1.0]) / np.sqrt(3.0),  # EG1: the three flexions together, unit length.
])
EIGENGRASP_ORIGIN = np.array([1.13, 0.79, 0.79, 0.79])  # spread 64.7 deg, fingers 45 deg.
# Amplitude range: GraspIt! hard-codes [-4, 4] when the eigengrasp file gives no limits, and the
# maximum jump of an amplitude is a quarter of its range (searchStateImpl.cpp,
# PostureStateEigen::createVariables).
AMPLITUDE_RANGE = (-4.0, 4.0)
AMPLITUDE_MAX_JUMP = (AMPLITUDE_RANGE[1] - AMPLITUDE_RANGE[0]) / 4.0
# The planner's reset posture: both amplitudes at their minimum (docs/design.md §4.6), i.e. the hand open.
RESET_AMPLITUDES = (AMPLITUDE_RANGE[0], AMPLITUDE_RANGE[0])

NUM_EIGENGRASPS = len(EIGENGRASPS)

# Limits of the 4 DOFs in our model, rad.
DOF_LOWER = np.array([hand.SPREAD_LIMITS[0]] + [hand.PROXIMAL_LIMITS[0]] * 3)
DOF_UPPER = np.array([hand.SPREAD_LIMITS[1]] + [hand.PROXIMAL_LIMITS[1]] * 3)


def dof_values(amplitudes) -> np.ndarray:
    """The hand's 4 DOF values for eigengrasp amplitudes, clamped to the joint limits.

    Args:
        amplitudes: (2,) amplitudes of EG0 (spread) and EG1 (flexion), dimensionless (rad per unit
            amplitude along the unit eigengrasp vectors).

    Returns:
        (4,) [spread, flex_1, flex_2, flex_3] in rad.
    """
    a = np.asarray(amplitudes, dtype=float)
    if a.shape != (NUM_EIGENGRASPS,):
        raise ValueError(f"expected {NUM_EIGENGRASPS} amplitudes, got shape {a.shape}")
    return np.clip(EIGENGRASP_ORIGIN + a @ EIGENGRASPS, DOF_LOWER, DOF_UPPER)


def spread_and_flex(a0: float, a1: float) -> tuple[float, float]:
    """Scalar fast path of :func:`dof_values`: (spread, flexion of every finger), rad.

    The three flexions are equal in the Barrett's eigengrasp space (EG1 moves them together and
    the origin has them equal), so two numbers describe the posture.
    """
    spread = _ORIGIN_SPREAD + a0
    flex = _ORIGIN_FLEX + a1 * _EG1_FLEX
    spread = min(max(spread, _SPREAD_LO), _SPREAD_HI)
    flex = min(max(flex, _FLEX_LO), _FLEX_HI)
    return spread, flex


_EG1_FLEX = float(EIGENGRASPS[1, 1])
_ORIGIN_SPREAD, _ORIGIN_FLEX = float(EIGENGRASP_ORIGIN[0]), float(EIGENGRASP_ORIGIN[1])
_SPREAD_LO, _SPREAD_HI = float(DOF_LOWER[0]), float(DOF_UPPER[0])
_FLEX_LO, _FLEX_HI = float(DOF_LOWER[1]), float(DOF_UPPER[1])


def joint_angles_from_dofs(dofs) -> np.ndarray:
    """Our 8 joint angles (controller order) from the 4 GraspIt! DOFs.

    Args:
        dofs: (4,) [spread, flex_1, flex_2, flex_3], rad.

    Returns:
        (8,) [spread_1, spread_2, proximal_1..3, distal_1..3], rad: proximal = flex and distal =
        flex / 3 (the clutch's free-motion coupling), each clamped to its limits.
    """
    dofs = np.asarray(dofs, dtype=float)
    spread, flex = dofs[0], dofs[1:4]
    proximal = np.clip(flex, *hand.PROXIMAL_LIMITS)
    distal = np.clip(flex * hand.DISTAL_PER_PROXIMAL, *hand.DISTAL_LIMITS)
    return np.concatenate([[spread, spread], proximal, distal])


def joint_angles(amplitudes) -> np.ndarray:
    """Our 8 joint angles (controller order, rad) for eigengrasp amplitudes (see dof_values)."""
    return joint_angles_from_dofs(dof_values(amplitudes))


def distal_angle(flex: float) -> float:
    """Distal joint angle (rad) that goes with a flexion (rad) in free motion, clamped."""
    return min(max(flex * hand.DISTAL_PER_PROXIMAL, hand.DISTAL_LIMITS[0]), hand.DISTAL_LIMITS[1])

