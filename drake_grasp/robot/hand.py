"""Facts about the BarrettHand BH8-280, and its compliance modes.

Every number here is a fact about the hardware, with its source (docs/design.md §4.1 collects them):

* Barrett BH8 manual, D-H table of the fingers, and the Barrett support wiki;
* libbarrett (include/barrett/products/hand.h, src/products/hand.cpp) for the transmission ratios;
* GraspIt! (models/robots/BarrettBH8_280) for the breakaway torque;
* jhu-lcsr/barrett_model for per-link masses.

Numbers that are *choices* (controller gains, closing speed of the simulated motor) live in the
scenario YAML files under ``diagrams/``, not here.

Geometry follows the manual's modified (Craig) Denavit-Hartenberg convention: the transform from
frame i-1 to frame i is RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i) TransZ(d_i). Frame W is the
hand base (``bh_base``): z along the palm normal (out of the palm, toward the object), F3 on +y,
F1 and F2 on -y. A finger at joint angle 0 lies flat, radially outward, in the palm plane.
"""

from __future__ import annotations

import dataclasses
import enum
import functools
import math

# --- Kinematics (BH8 manual D-H table; docs/design.md §4.1). Lengths in metres. -------------------
AW = 0.025  # Aw: offset of the F1/F2 spread axes from the palm centre, along x.
A1 = 0.050  # A1: spread axis to proximal axis (knuckle length).
A2 = 0.070  # A2: proximal axis to distal axis (proximal link length).
A3 = 0.050  # A3: distal axis to fingertip (distal link length).
D3 = 0.0095  # D3: fingertip offset toward the inner (grasping) side of the distal link.
DW = 0.0754  # Dw: height of the finger knuckles above the hand base for the BH8-280.
PHI2 = 0.0  # Phi2: built-in offset of the proximal joint, rad.
PHI3 = math.radians(42.0)  # Phi3: built-in bend of the distal link, rad.

FINGERS = (1, 2, 3)
# Per finger: r (direction of the spread rotation, 0 = no spread joint) and j (quarter turns).
FINGER_R = {1: -1, 2: 1, 3: 0}
FINGER_J = {1: 1, 2: 1, 3: -1}

# --- Joint ranges (BH8 manual; docs/design.md §4.1), rad. -----------------------------------------
SPREAD_LIMITS = (0.0, math.pi)  # 0-180 deg, F1 and F2 each.
PROXIMAL_LIMITS = (0.0, math.radians(140.0))  # 2.44 rad.
DISTAL_LIMITS = (0.0, math.radians(48.0))  # 0.84 rad, relative to the proximal link.

# --- Transmission (libbarrett hand.cpp; docs/design.md §4.1). -------------------------------------
MOTOR_TO_PROXIMAL = 125.0  # motor turns per proximal-joint turn.
MOTOR_TO_DISTAL = 375.0  # motor turns per distal-joint turn, clutch engaged.
# After breakaway libbarrett computes outer = motor / 93.75 - inner_frozen: 375 / 93.75 = 4 times
# faster per motor turn than in the coupled phase.
MOTOR_TO_DISTAL_AFTER_BREAKAWAY = 93.75
DISTAL_PER_PROXIMAL = MOTOR_TO_PROXIMAL / MOTOR_TO_DISTAL  # = 1/3 in free motion.
BREAKAWAY_SPEEDUP = MOTOR_TO_DISTAL / MOTOR_TO_DISTAL_AFTER_BREAKAWAY  # = 4.

# Breakaway torque at the proximal joint (GraspIt! BarrettBH8_280 model), N*m.
BREAKAWAY_TORQUE = 0.5

# --- Masses (docs/design.md §4.1), kg. ------------------------------------------------------------
BASE_MASS = 0.664  # hand base, BH8-280, measured by Barrett.
KNUCKLE_MASS = 0.141  # jhu-lcsr/barrett_model.
PROXIMAL_MASS = 0.062
DISTAL_MASS = 0.041
FINGER_LOAD_LIMIT = 2.0  # kg per finger (manual).

# --- Geometry of the shell (docs/design.md §4.1: primitives are fine). ----------------------------
BASE_RADIUS = 0.0445  # hand base is a cylinder of about 89 mm diameter.
PALM_HEIGHT = 0.080  # palm surface above the hand base frame.
FINGER_WIDTH = 0.025  # width of a finger link, across the closing plane (assumed).
PROXIMAL_THICKNESS = 0.020  # thickness of the proximal link, in the closing plane (assumed).
# The open finger's inner face is flush with the palm (assumed; the real links are rounded about the
# joint axis): the proximal box's inner face is PALM_HEIGHT - DW = 4.6 mm off the D-H line.
PROXIMAL_BEHIND_AXIS = 0.005  # the proximal box starts this far behind the joint axis (assumed).
# The distal pad surface holds the fingertip frame, D3 from the D-H line: thickness 2*D3 at the joint.
DISTAL_THICKNESS = 2.0 * D3

# --- The distal link as the BH8-280 has it (docs/design.md §4.1a). --------------------------------
# Not a box: a flat inner pad, a back that tapers toward the tip, and a tip rounded both in the
# closing plane and across the finger's width. Numbers measured on Barrett's CAD model of the
# BH8-280 distal link (jhu-lcsr/barrett_model, models/sw_meshes/bhand/bhand_finger_dist_link_fine.stl,
# exported from Barrett's SolidWorks parts) by cutting it along the link; in the distal link's D-H
# frame: x along the link from the distal joint, y toward the inner (grasping) side, z across.
DISTAL_PAD_Y = D3  # the flat inner pad, on which the fingertip frame lies (measured 8-9.5 mm).
DISTAL_BACK_Y_ROOT = -0.0094  # the back face at the distal joint (x = 0).
DISTAL_BACK_Y_END = -0.0048  # the back face at x = A3: the link tapers from 18.9 to 14.3 mm.
DISTAL_TIP_REACH = 0.0585  # the rounded tip's farthest point along the link (8.5 mm past A3).
DISTAL_NOSE_RADIUS = 0.0115  # the tip's rounding in the closing plane, from the back up to the pad.
DISTAL_NOSE_CENTRE_Y = 0.0060  # where that rounding is centred across the link (its farthest point's y).
DISTAL_WIDTH = 0.023  # across the closing plane (measured 23.0 mm; the proximal link's is assumed).
DISTAL_TIP_WIDTH_RADIUS = 0.022  # the tip's rounding across the width (seen from the pad).

# --- Finger force (docs/design.md §4.1, assumed from the manual's force plot). --------------------
FINGERTIP_STALL_FORCE = 15.0  # N, lower end of the 15-25 N range.


class ComplianceMode(enum.Enum):
    """A pre-grasp hand shape, closed compliantly by torque close with breakaway.

    The value is the spread angle of each of F1 and F2 (rad).
    """

    # Each spread joint at 60 deg: F1 and F2 are 120 deg apart, and 120 deg from F3.
    SPHERICAL = math.radians(60.0)
    # Spread 0: F1 and F2 side by side, opposing F3.
    CYLINDRICAL = 0.0

    @property
    def spread(self) -> float:
        """Spread angle of each of F1 and F2, rad."""
        return float(self.value)

    @classmethod
    def parse(cls, name: str) -> "ComplianceMode":
        """Returns the mode called `name` (case-insensitive), or raises ValueError naming the choices."""
        try:
            return cls[name.strip().upper()]
        except KeyError:
            choices = ", ".join(m.name.lower() for m in cls)
            raise ValueError(f"unknown compliance mode '{name}' (choose from {choices})") from None


class HandAction(enum.IntEnum):
    """What the hand controller is told to do with the fingers."""

    OPEN = 0  # drive every finger to 0 and re-engage the clutches.
    CLOSE = 1  # torque close with breakaway.
    HOLD = 2  # keep the fingers where they are (and keep squeezing if they squeeze).
    PRESHAPE = 3  # move each finger (coupled, clutch engaged) to a given proximal angle and stop.
    GENTLE_CLOSE = 4  # close with the motor's torque held under the clutch's breakaway: no breakaway.
    GENTLE_PINCH = 5  # F1 and F2 close as GENTLE_CLOSE; F3 keeps its place (the flower's two-finger pinch).
    SQUEEZE = 6  # a finger that squeezes squeezes harder, still under the breakaway (a gentle close's lift).


@dataclasses.dataclass(frozen=True)
class JointNames:
    """Names of the hand's joints and frames in the model (models/barrett_hand)."""

    spread = ("bh_spread_1", "bh_spread_2")
    proximal = ("bh_proximal_1", "bh_proximal_2", "bh_proximal_3")
    distal = ("bh_distal_1", "bh_distal_2", "bh_distal_3")
    base_frame = "bh_base"
    tips = ("bh_tip_1", "bh_tip_2", "bh_tip_3")
    palm_frame = "bh_palm"

    @property
    def all(self) -> tuple[str, ...]:
        """The eight joints, in the order the hand controller uses: spreads, proximals, distals."""
        return self.spread + self.proximal + self.distal


HAND_JOINTS = JointNames()


def finger_dh_table(finger: int, spread: float = 0.0, proximal: float = 0.0, distal: float = 0.0):
    """Rows (a_{i-1}, alpha_{i-1}, d_i, theta_i) of one finger's modified D-H chain, W to tip.

    Args:
        finger: 1, 2 or 3.
        spread, proximal, distal: joint angles Theta1, Theta2, Theta3 in rad (Theta1 is ignored for
            F3, which has no spread joint).

    Returns:
        Four tuples, for the spread joint, the proximal joint, the distal joint and the tip frame.
    """
    r, j = FINGER_R[finger], FINGER_J[finger]
    return (
        (r * AW, 0.0, DW, r * spread - j * math.pi / 2),
        (A1, math.pi / 2, 0.0, proximal + PHI2),
        (A2, 0.0, 0.0, distal + PHI3),
        (A3, -math.pi / 2, D3, 0.0),
    )


def _modified_dh_matrix(a: float, alpha: float, d: float, theta: float):
    import numpy as np

    ca, sa, ct, st = math.cos(alpha), math.sin(alpha), math.cos(theta), math.sin(theta)
    # RotX(alpha) TransX(a) RotZ(theta) TransZ(d)
    return np.array([
        [ct, -st, 0.0, a],
        [ca * st, ca * ct, -sa, -sa * d],
        [sa * st, sa * ct, ca, ca * d],
        [0.0, 0.0, 0.0, 1.0],
    ])


def distal_points_in_base(finger: int, spread: float, proximal: float, distal: float, points_D):
    """Points given in a finger's distal-link frame, expressed in the hand base frame W (m).

    Pure numpy forward kinematics from the D-H table (`finger_dh_table`).
    """
    import numpy as np

    T = np.eye(4)
    for row in finger_dh_table(finger, spread, proximal, distal)[:3]:
        T = T @ _modified_dh_matrix(*row)
    P = np.asarray(points_D, float)
    return P @ T[:3, :3].T + T[:3, 3]


def distal_pad_end() -> float:
    """Where the flat pad ends and the rounded tip begins, along the distal link (m from its joint)."""
    rise = DISTAL_PAD_Y - DISTAL_NOSE_CENTRE_Y
    return DISTAL_TIP_REACH - DISTAL_NOSE_RADIUS + math.sqrt(DISTAL_NOSE_RADIUS**2 - rise**2)


@functools.lru_cache(maxsize=1)
def distal_link_points():
    """Vertices of the distal link's shape, in its D-H frame (m): an (N, 3) array whose convex hull
    is the link's collision and visual geometry (the model writes it as a mesh).

    Sections across the link follow the measured outline in the closing plane: the flat pad at
    ``DISTAL_PAD_Y``, the back tapering from ``DISTAL_BACK_Y_ROOT`` to ``DISTAL_BACK_Y_END`` at A3, and
    the nose, a circle of radius ``DISTAL_NOSE_RADIUS`` reaching ``DISTAL_TIP_REACH``. Each outline
    point is put at plus and minus the half-width at its x, which the tip's rounding across the width
    (``DISTAL_TIP_WIDTH_RADIUS``) narrows near the end. The shape is convex, as the real link is
    (apart from the pad's shallow recess).
    """
    import numpy as np

    cx = DISTAL_TIP_REACH - DISTAL_NOSE_RADIUS
    cy = DISTAL_NOSE_CENTRE_Y
    slope = (DISTAL_BACK_Y_END - DISTAL_BACK_Y_ROOT) / A3
    outline = [(0.0, DISTAL_PAD_Y), (0.0, DISTAL_BACK_Y_ROOT)]
    # The nose: from where the circle meets the back line up to where it meets the pad.
    top = math.asin((DISTAL_PAD_Y - cy) / DISTAL_NOSE_RADIUS)
    angles = np.linspace(-math.pi / 2, top, 25)
    for a in angles:
        x, y = cx + DISTAL_NOSE_RADIUS * math.cos(a), cy + DISTAL_NOSE_RADIUS * math.sin(a)
        if y >= DISTAL_BACK_Y_ROOT + slope * x:  # outside the back line: part of the nose
            outline.append((x, y))
    outline.append((outline[-1][0], DISTAL_PAD_Y))
    for x in np.linspace(0.0, cx, 8):  # the back line, up to the nose
        outline.append((float(x), DISTAL_BACK_Y_ROOT + slope * float(x)))
    width_centre = DISTAL_TIP_REACH - DISTAL_TIP_WIDTH_RADIUS
    points = []
    for x, y in outline:
        beyond = max(0.0, x - width_centre)
        half = min(DISTAL_WIDTH / 2, math.sqrt(max(DISTAL_TIP_WIDTH_RADIUS**2 - beyond**2, 0.0)))
        half = max(half, 0.002)  # the very end keeps a 4 mm wide edge (measured: a blunt dome)
        points += [(x, y, -half), (x, y, half)]
    return np.array(points)


def closing_distal_points(proximal: float, spread: float = 0.0) -> list:
    """Each finger's distal-link shape (`distal_link_points`) in the hand base frame at a free
    (coupled) closing, distal = proximal / 3 (m): one (N, 3) array per finger of FINGERS."""
    points = distal_link_points()
    return [distal_points_in_base(f, spread, proximal, proximal * DISTAL_PER_PROXIMAL, points) for f in FINGERS]


def _deepest(proximal: float, spread: float) -> float:
    """How far beyond the palm surface the distal links reach at this coupled proximal angle, m."""
    return max(float(p[:, 2].max()) for p in closing_distal_points(proximal, spread)) - PALM_HEIGHT


@functools.lru_cache(maxsize=32)
def fingertip_sweep_depth(spread: float = 0.0, samples: int = 141) -> float:
    """How far beyond the palm surface the fingers reach while closing in the coupled phase, m.

    The deepest point, along the palm normal, of the distal links' shape (`distal_link_points`: the
    sweep's deepest point is on the rounded tip's outer side) over a free closing (distal = proximal
    / 3) of every finger at the given spread. A grasp that brings the palm closer than this to a
    table lets the fingertips strike it.
    """
    import numpy as np

    return max(0.0, *(_deepest(p, spread) for p in np.linspace(PROXIMAL_LIMITS[0], PROXIMAL_LIMITS[1], samples)))


@functools.lru_cache(maxsize=4096)
def fingertip_depth(proximal: float, spread: float = 0.0) -> float:
    """How far beyond the palm surface the lowest fingertip reaches in a free (coupled) closing at this
    proximal angle (rad, rounded to a milliradian for the cache), m. The flower grasp keeps the palm
    this far above the table as its fingers close, so that the tips stay on the table."""
    return _deepest(round(float(proximal), 3), spread)


def closing_direction(finger: int, spread: float = 0.0) -> tuple[float, float]:
    """The unit direction (x, y in the hand base frame) in which a finger's knuckle link points, from
    its spread axis outward; the finger closes back along it, toward the palm's centre line. At spread
    0, F1 and F2 point along -y and F3 along +y; at 90 deg, F1 and F2 point along -x and +x, opposed on
    one line through the palm centre (the D-H table's spread row, `finger_dh_table`)."""
    theta = finger_dh_table(finger, spread)[0][3]
    return math.cos(theta), math.sin(theta)


@functools.lru_cache(maxsize=512)
def fingertip_reach(proximal: float, spread: float = 0.0, band: float = 0.010, fingers: tuple = FINGERS) -> float:
    """How near the palm's centre line the fingertips' lowest `band` m comes at this coupled proximal
    angle, m: the smallest distance, along each finger's closing direction (`closing_direction`; the
    palm's y at spread 0), of any of its distal-link points within `band` of the deepest one, over
    `fingers`. An object narrower than twice this along that direction, centred, is not under the
    fingertips when they land."""
    import numpy as np

    reach = np.inf
    for finger, p in zip(FINGERS, closing_distal_points(proximal, spread)):
        if finger not in fingers:
            continue
        low = p[p[:, 2] > p[:, 2].max() - band]
        u = np.array(closing_direction(finger, spread))
        reach = min(reach, float(np.min(np.abs(low[:, :2] @ u))))
    return reach
