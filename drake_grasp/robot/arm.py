"""Facts about the 7-DoF Barrett WAM.

Sources (docs/design.md §4.2): WAM Arm User's Manual, D-H table 5 and joint-limit table 6; libbarrett's
config wam7w.conf for masses. The WAM table uses the classical D-H convention: the transform from
frame i-1 to frame i is RotZ(theta_i) TransZ(d_i) TransX(a_i) RotX(alpha_i), theta_i = q_i.
At q = 0 the arm stands straight up.
"""

from __future__ import annotations

import math

import numpy as np

NUM_JOINTS = 7
JOINT_NAMES = tuple(f"wam_joint_{i}" for i in range(1, NUM_JOINTS + 1))
BASE_FRAME = "wam_base"
FLANGE_FRAME = "wam_flange"  # the J7 flange, where the hand mounts.

# Classical D-H rows (a_i, alpha_i, d_i), metres and rad (WAM manual table 5).
DH_ROWS = (
    (0.0, -math.pi / 2, 0.0),
    (0.0, math.pi / 2, 0.0),
    (0.045, -math.pi / 2, 0.55),
    (-0.045, math.pi / 2, 0.0),
    (0.0, -math.pi / 2, 0.30),
    (0.0, math.pi / 2, 0.0),
    (0.0, 0.0, 0.06),
)
BASE_TO_JOINT1 = 0.346  # first joint axis above the base plate, m.

# Joint limits (manual table 6), rad.
LOWER_LIMITS = np.array([-2.6, -2.0, -2.8, -0.9, -4.76, -1.6, -3.0])
UPPER_LIMITS = np.array([2.6, 2.0, 2.8, 3.1, 1.24, 1.6, 3.0])
# Peak joint efforts (manual), N*m.
EFFORT_LIMITS = np.array([60.0, 60.0, 45.0, 30.0, 10.0, 10.0, 10.0])
# Link masses (libbarrett wam7w.conf), kg, for links 1..7.
LINK_MASSES = (10.77, 3.87, 1.80, 2.17, 0.357, 0.409, 0.075)
BASE_MASS = 9.97  # the base casing; it is welded to the world, so it never matters dynamically.

# Radius of the shell around each link's joint (i = 1..7), m: the model's visual cylinders (modelgen)
# and the arm's clearance from the table (control.arm_motion). Assumed, to match the WAM's look: the
# shoulder and upper arm are about 12 cm across, the wrist about 8 cm.
def link_radius(i: int) -> float:
    return 0.06 if i <= 4 else 0.04


HOME = np.array([0.0, -2.0, 0.0, 3.13, 0.0, 0.0, 0.0])

# The hand mounts on the J7 flange rotated by pi about the flange's z axis (docs/design.md §4.2).
HAND_MOUNT_YAW = math.pi
