"""The 19 virtual contacts of the BarrettHand, and where they are for a finger posture.

GraspIt!'s contact energy (docs/design.md §4.6) measures how well a set of *virtual contacts* on the hand,
each a point with an outward normal, lies on the object. The Barrett's set
(models/robots/Barrett/virtual/all_16_contacts.xml) has 19: 4 on the palm, 2 on each of the 6 finger
links, 1 on each fingertip; links and palm carry friction 0.2, fingertips 1.0 (its ``sCof``). We
place the same set on *our* model's collision shapes (drake_grasp/robot/modelgen.py), on the surfaces that
face the object when grasping:

* palm: on the palm surface (``PALM_HEIGHT`` above the hand base), at ``PALM_CONTACT_RADIUS`` from
  its centre along ±x and ±y; normal +z (the palm normal).
* proximal links: on the inner face of the link box (``PALM_HEIGHT - DW`` along the link's +y), on its
  centre line, at the fractions ``PROXIMAL_CONTACT_FRACTIONS`` of A2 from the proximal axis (GraspIt!
  puts them 18 and 52 mm along its 70 mm link); normal +y.
* distal links: on the inner pad (``D3`` along the link's +y), at ``DISTAL_CONTACT_FRACTIONS`` of A3;
  normal +y.
* fingertips: where the flat pad ends and the rounded tip begins (``hand.distal_pad_end()``, 58 mm
  along the link, D3 along y: the BH8-280's fingertip, docs/design.md §4.1a), normal halfway between
  the link's direction and the pad normal, (1, 1, 0)/√2 in the distal frame (GraspIt!'s
  fingertips.xml has the same 45° normal; on the rounded tip's convex hull that edge is where a 45°
  normal meets it).

Link frames are the D-H frames of hand.py (x along the link, y toward the grasping side, z along the
joint axis), which are also our model's body frames. Forward kinematics here is pure numpy: every
finger moves in a plane through the palm normal, so a finger's contacts are 2-D points of a planar
2-link chain, turned about the palm normal by the finger's spread. Lengths in metres, angles in rad.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from drake_grasp.robot import hand

# --- Placement on our model (assumed unless marked). -----------------------------------------------
PALM_CONTACT_RADIUS = 0.020  # m from the palm centre (assumed; inside the 44.5 mm palm disc).
PROXIMAL_CONTACT_FRACTIONS = (0.25, 0.75)  # of A2 (GraspIt!'s Barrett: 18/70 and 52/70).
DISTAL_CONTACT_FRACTIONS = (0.25, 0.60)  # of A3 (assumed; the fingertip contact is at 1.0).
# Friction of the virtual contacts (GraspIt! all_16_contacts.xml / fingertips.xml sCof), used by the
# contact-quality energy only.
LINK_FRICTION = 0.2
FINGERTIP_FRICTION = 1.0

_PROXIMAL_INNER_Y = hand.PALM_HEIGHT - hand.DW  # inner face of the proximal box (modelgen.py).
_DISTAL_INNER_Y = hand.DISTAL_PAD_Y  # the distal link's flat inner pad (hand.distal_link_points).


@dataclasses.dataclass(frozen=True)
class VirtualContact:
    """A virtual contact on a hand link.

    Attributes:
        link: Body name in our model ("bh_base" for the palm, "bh_finger_2_distal", ...).
        point: Position in the link's body frame, m.
        normal: Unit outward normal (the direction the contact pushes an object) in that frame.
        friction: Friction coefficient of the contact (dimensionless).
    """

    link: str
    point: tuple[float, float, float]
    normal: tuple[float, float, float]
    friction: float

    @property
    def finger(self) -> int | None:
        """1, 2 or 3 for a finger contact, None for the palm."""
        return None if self.link == "bh_base" else int(self.link.split("_")[2])


def _finger_contacts(finger: int) -> list[VirtualContact]:
    proximal, distal = f"bh_finger_{finger}_proximal", f"bh_finger_{finger}_distal"
    contacts = [VirtualContact(proximal, (f * hand.A2, _PROXIMAL_INNER_Y, 0.0), (0.0, 1.0, 0.0), LINK_FRICTION)
                for f in PROXIMAL_CONTACT_FRACTIONS]
    contacts += [VirtualContact(distal, (f * hand.A3, _DISTAL_INNER_Y, 0.0), (0.0, 1.0, 0.0), LINK_FRICTION)
                 for f in DISTAL_CONTACT_FRACTIONS]
    half = math.sqrt(0.5)
    contacts.append(VirtualContact(distal, (hand.distal_pad_end(), _DISTAL_INNER_Y, 0.0), (half, half, 0.0),
                                   FINGERTIP_FRICTION))
    return contacts


def _palm_contacts() -> list[VirtualContact]:
    r, h = PALM_CONTACT_RADIUS, hand.PALM_HEIGHT
    return [VirtualContact("bh_base", (x, y, h), (0.0, 0.0, 1.0), LINK_FRICTION)
            for x, y in ((r, 0.0), (-r, 0.0), (0.0, r), (0.0, -r))]


VIRTUAL_CONTACTS: tuple[VirtualContact, ...] = tuple(
    _palm_contacts() + [c for finger in hand.FINGERS for c in _finger_contacts(finger)])
"""The 19 contacts: 4 palm, then per finger F1, F2, F3: 2 proximal, 2 distal, 1 fingertip."""

NUM_CONTACTS = len(VIRTUAL_CONTACTS)
NUM_PALM_CONTACTS = 4
CONTACTS_PER_FINGER = 5
FRICTION = np.array([c.friction for c in VIRTUAL_CONTACTS])
"""(19,) friction coefficient of each virtual contact."""

# Planar description of one finger's 5 contacts (the same on every finger): local x, y and normal
# components in their link frame, and whether the link is the distal one.
_LOCAL = np.array([c.point[:2] + c.normal[:2] for c in _finger_contacts(1)])  # (5, 4): x, y, nx, ny
_IS_DISTAL = np.array([c.link.endswith("distal") for c in _finger_contacts(1)], dtype=float)  # (5,)
_R = np.array([hand.FINGER_R[f] for f in hand.FINGERS], dtype=float)
_J = np.array([hand.FINGER_J[f] for f in hand.FINGERS], dtype=float)
_FINGER_ORIGINS = np.array([[hand.FINGER_R[f] * hand.AW, 0.0, hand.DW] for f in hand.FINGERS])  # knuckle axes
_PALM_POINTS = np.array([c.point for c in VIRTUAL_CONTACTS[:NUM_PALM_CONTACTS]])
_PALM_NORMALS = np.array([c.normal for c in VIRTUAL_CONTACTS[:NUM_PALM_CONTACTS]])
_Z = np.array([0.0, 0.0, 1.0])
_LOCAL_ROWS = [tuple(float(v) for v in row) + (bool(d),) for row, d in zip(_LOCAL, _IS_DISTAL)]


def contact_frames_in_hand(joint_angles) -> tuple[np.ndarray, np.ndarray]:
    """Positions and outward normals of the 19 virtual contacts in the hand base frame H.

    Args:
        joint_angles: (8,) [spread_1, spread_2, proximal_1..3, distal_1..3], rad (controller order).

    Returns:
        (points (19, 3) in m, unit normals (19, 3)), in H, in the order of ``VIRTUAL_CONTACTS``.
    """
    q = np.asarray(joint_angles, dtype=float)
    if q.shape != (8,):
        raise ValueError(f"expected 8 joint angles, got shape {q.shape}")
    spread = np.array([q[0], q[1], 0.0])
    theta2 = q[2:5] + hand.PHI2
    theta3 = q[5:8] + hand.PHI3
    # Angle of each contact's link in its finger plane, (3 fingers, 5 contacts).
    psi = theta2[:, None] + _IS_DISTAL[None, :] * theta3[:, None]
    c, s = np.cos(psi), np.sin(psi)
    x, y, nx, ny = _LOCAL.T
    # The link's origin in the finger plane: radial distance from the knuckle axis and height.
    base_rho = hand.A1 + _IS_DISTAL[None, :] * hand.A2 * np.cos(theta2)[:, None]
    base_h = _IS_DISTAL[None, :] * hand.A2 * np.sin(theta2)[:, None]
    rho = base_rho + x * c - y * s
    height = base_h + x * s + y * c
    n_rho = nx * c - ny * s
    n_h = nx * s + ny * c
    return _to_hand_frame(spread, rho, height, n_rho, n_h)


def contact_frames_for_posture(spread: float, flex: float, distal: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`contact_frames_in_hand` for a posture whose three fingers share one flexion.

    The planner's fast path (the Barrett's eigengrasps keep the fingers together): the planar
    coordinates (radial distance ρ, height h) of a finger's contacts are computed once with scalar
    math, and one matrix product [ρ, h, 1] · [u_f; z; o_f] places them on the three fingers (u_f is
    finger f's radial direction, o_f its knuckle axis).

    Args:
        spread: Spread of each of F1 and F2, rad.
        flex: Proximal angle of every finger, rad.
        distal: Distal angle of every finger, rad.
    """
    t2 = flex + hand.PHI2
    t23 = t2 + distal + hand.PHI3
    c2, s2, c23, s23 = math.cos(t2), math.sin(t2), math.cos(t23), math.sin(t23)
    rows = []
    normal_rows = []
    for x, y, nx, ny, is_distal in _LOCAL_ROWS:
        if is_distal:
            c, s, b_rho, b_h = c23, s23, hand.A1 + hand.A2 * c2, hand.A2 * s2
        else:
            c, s, b_rho, b_h = c2, s2, hand.A1, 0.0
        rows.append((b_rho + x * c - y * s, b_h + x * s + y * c, 1.0))
        normal_rows.append((nx * c - ny * s, nx * s + ny * c, 0.0))
    planar = np.array(rows + normal_rows)  # (10, 3)
    frames = planar @ _finger_bases(spread)  # (3 fingers, 10, 3)
    points = np.concatenate((_PALM_POINTS, frames[:, :CONTACTS_PER_FINGER].reshape(-1, 3)))
    normals = np.concatenate((_PALM_NORMALS, frames[:, CONTACTS_PER_FINGER:].reshape(-1, 3)))
    return points, normals


def _finger_bases(spread: float) -> np.ndarray:
    """(3, 3, 3): per finger, rows u_f (radial direction), z, o_f (knuckle axis point) in H."""
    bases = []
    for r, j, origin in _FINGER_CONSTANTS:
        theta1 = r * spread - j * (math.pi / 2.0)
        bases.append(((math.cos(theta1), math.sin(theta1), 0.0), (0.0, 0.0, 1.0), origin))
    return np.array(bases)


_FINGER_CONSTANTS = [(hand.FINGER_R[f], hand.FINGER_J[f], (hand.FINGER_R[f] * hand.AW, 0.0, hand.DW))
                     for f in hand.FINGERS]


def _to_hand_frame(spread, rho, height, n_rho, n_h):
    theta1 = _R * spread - _J * (math.pi / 2.0)
    u = np.stack([np.cos(theta1), np.sin(theta1), np.zeros(3)], axis=1)  # (3, 3): radial direction
    points = _FINGER_ORIGINS[:, None, :] + rho[..., None] * u[:, None, :] + height[..., None] * _Z
    normals = n_rho[..., None] * u[:, None, :] + n_h[..., None] * _Z
    return (np.concatenate([_PALM_POINTS, points.reshape(-1, 3)]),
            np.concatenate([_PALM_NORMALS, normals.reshape(-1, 3)]))
