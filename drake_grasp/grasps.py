"""The compliant grasps: a compliance mode plus a hand pose, from an object estimate (the paper's three,
and the precision grasp of its future work).

A *compliant grasp* (paper, Sec. 2) = a hand pose (where the palm goes, and from which direction it
comes) + a compliance mode (the pre-grasp hand shape and torque close with breakaway). The pose is
computed only from a coarse *estimate* of the object — its centre, its axes and its size along them
— which the visual primitives provide (or, for oracle trials, the ground truth does). No object
model and no contact planning: the hand's compliance does the rest.

* **spherical grasp**: spherical mode; the palm centre approaches the object's centre from above
  until contact (or until it reaches the estimated top).
* **cylindrical grasp**: cylindrical mode; the hand is centred on the principal axis, its fingers
  closing perpendicular to it; it approaches perpendicular to the axis, from as high above as the
  axis allows, until contact.
* **precision grasp**, the flower grasp (the paper's future work: the "flower", small and flat
  objects): cylindrical mode with the arm compliant (`control.palm_impedance`). The palm is level above
  the object's centre, its fingers closing across the shorter side of the footprint. The fingers are
  bent before the approach (a preshape) to the largest angle at which their tips land clear of the
  object (`FLOWER_MARGIN` beyond its half-width, for the estimate's and the placement's errors), and
  the palm lands them on the table, guarded. The hand then closes while the arm presses
  `FLOWER_FORCE` along the palm normal and follows the tips down as they rise, so that they slide
  along the table into the object's foot (Kazemi et al., RSS 2012; Autonomous Robots 2014: the same
  WAM and BarrettHand, a guarded landing of the fingertips and a close under a light force on the
  table; Eppner et al., IJRR 2015: the table as the environmental constraint). What it holds and
  misses, and what else was tried: docs/design.md §5.4f, docs/results/flower.md. On an object too
  small for F1 and F2 to meet at that spread (a 2-3 cm cube, a domino standing on end), F1 and F2 turn
  to a 90 degree spread and pinch it from opposite sides while F3 stays open; a slender one lying down
  (a stick) they pinch so end to end (`flower_pinch_axis`).
* **box grasp**: cylindrical mode; the hand is aligned with the box's axes: it approaches along the
  box axis closest to the vertical (onto the top face), and its fingers close across the shorter side
  of that face. A face wider than the fingers' knuckles are apart would catch the open proximal links
  flat on it (they break away at once and the distal links close beside the box): the palm then stops
  short of the face, so that the proximal links meet the top edges at about 45 degrees and the distal
  links wrap down the sides.

The object rests on a table whose height the estimate gives (`ObjectEstimate.table_height`: the
table-top estimate's reference plane where it has one, else the object's estimated bottom). Closing from
above, the BarrettHand's bent fingertips sweep about 10 cm beyond the palm: a palm brought lower
would drive the fingertips into the table before they reach a small object (they would stall there
and break away). So a top-down grasp never brings the palm closer to the table than that sweep plus
a small clearance: on objects lower than that, the fingertips pass just above the table and close on
the object from below its middle, and the palm stops above it.

All poses are palm poses X_WP (P = ``bh_palm``: the palm centre, z along the palm normal); the
approach runs along +z_P.
"""

import dataclasses
import enum
import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from drake_grasp.flower_facing import thumb_to_the_right
from drake_grasp.robot import hand
from drake_grasp.robot.hand import ComplianceMode

# Height of the finger knuckles' axes behind the palm surface, m (hand.PALM_HEIGHT - hand.DW).
_KNUCKLE_BEHIND_PALM = hand.PALM_HEIGHT - hand.DW
# Distance of the proximal axes from the palm centre across the closing direction, m.
_KNUCKLE_SPACING_HALF = hand.A1
# Fingertips pass this far above the table at the bottom of their sweep (a choice), m.
TABLE_CLEARANCE = 0.005
# The flower grasp (docs/design.md §5.4f; measured on plates, cubes and sticks, oracle, two seeds):
# its fingertips land this far beyond the object's half-width across the closing direction (m: the
# placement's +-1 cm plus the estimate's error), their deepest point this far below the table (m: the
# landing's target, so that the guarded approach ends on the table, not above it), and the arm presses
# this hard along the palm normal while the hand closes (N: 6 N let the tips ride over 8-12 mm plates).
FLOWER_MARGIN = 0.012
FLOWER_SINK = 0.006
FLOWER_FORCE = 15.0
# The flower grasp lands outside the footprint's measured reach across its closing direction
# (`ObjectEstimate.reach_across`) where the grip was measured along the fingers' row within this, rad.
GRIP_ALIGNMENT = math.radians(15.0)
# The range of the preshape's proximal angle, rad: from where the tips still point down (below 40 deg
# they would land flat) to where they nearly meet under the palm.
FLOWER_PRESHAPE_RANGE = (math.radians(40.0), math.radians(85.0))
# The flower grasp's two-finger pinch (docs/design.md §5.4f). At the cylindrical spread F1 and F2 sit
# 25 mm either side of the closing plane (hand.AW) and their 23 mm pads cover 13.5-36.5 mm from it: an
# object whose footprint is shorter than PINCH_MAX_LENGTH along that line passes between them, and only
# F3 touches it (flower seed 11: 2-3 cm cubes held 7/15, standing dominoes 4-6/15). At a 90 deg
# spread F1 and F2 face each other on one line through the palm centre; F3 stays open and they pinch
# the object's sides. The tips' rounded ends meet a side lower than PINCH_MIN_HEIGHT with a contact
# normal pointing down into it, and ride over it (oracle, seeds 1-2: 2.5 cm squares 12 and 15 mm tall
# dropped, 18 and 22 mm held; the three-finger flower, which holds low objects, is kept for those).
PINCH_SPREAD = math.pi / 2
PINCH_MAX_LENGTH = 0.035
PINCH_MIN_HEIGHT = 0.018
# Its preshape range: the pinching tips start 25 mm further out than at the cylindrical spread
# (their knuckles are 75 mm from the centre), so they reach an object's sides at larger angles.
PINCH_PRESHAPE_RANGE = (math.radians(40.0), math.radians(100.0))
# Two fingertips let the object turn about the line through them. The WAM lifts with joints whose axes
# lie across its reach (shoulder, elbow and wrist pitch), so the palm pitches about that direction as
# it lifts: a pinch across the reach lets the object swing, one along it does not. On a footprint
# whose sides are within this ratio, the pinch runs along the reach (a 2 cm cube pinched across the
# reach turned 0.5 rad and fell at two of three seeds; along it, held at all three).
PINCH_SQUARE = 1.25
# A slender object lying down (a stick, a marker, a chopstick) is pinched end to end instead, along its
# long side: F1 and F2 meet its end faces, whose edges stand as high as the stick is thick, and the
# tips reach them at shallow angles (60-77° at the proximal joints). Across it, the three-finger
# flower meets a round stick's side below its top with the contact normal pointing down into it, and
# drops round sticks under about 1.6 cm (docs/design.md §5.4f). Measured from the true pose, seeds 1-2:
# round and square sticks 1-2 cm across and 8-14 cm long held end to end in 25 of 26 trials; shorter
# ones need taller ends (6-7 cm: a 1.2 cm one dropped, a 1.5 cm one held), as the tips meet the ends
# more steeply; a 9 mm one was dropped. A conical end (a pen's point) lets a tip ride over it either way.
# End to end has almost no funnel across the stick: in Fig. 4's flower (round sticks 12 cm long, the true
# pose shifted, seeds 1-2) every shift across of 5 mm or more failed, where the three-finger flower across
# held 20 mm sticks over ±1.5 cm (38/50 points against 10/50 end to end). So only sticks thinner than
# PINCH_MAX_STICK_WIDTH, which the flower across drops, are pinched end to end (12 mm: 0/50 across,
# 10/50 end to end; 16 mm: 11/50 both).
PINCH_SLENDER = 4.0  # the footprint's long side at least this many times its short side
PINCH_LENGTH_RANGE = (0.08, 0.16)  # m: the long side (the longest tried: 14 cm; the tips reach 20 cm)
PINCH_MIN_END_HEIGHT = 0.010  # m
PINCH_MAX_STICK_WIDTH = 0.015  # m
# The three-finger flower grasp closes across the footprint's shorter side. On a footprint whose sides
# are within this ratio the camera cannot tell which side is shorter (a ring's or a round blob's reads
# 1-6 % apart), and it closes across the arm's reach instead (docs/design.md §5.4k: small rings 2/10
# held with the estimate's longer side, 5/10 across the reach). Beyond it the shorter side is measured,
# and closing across it is §5.4f's rule (a first version used the pinch's 1.25).
FLOWER_SQUARE = 1.1
# A thin object (standing lower than FLOWER_THIN above the table: a plate, a tile, a lying domino) is
# closed across its longer side instead, where the tips land and meet it at shallower proximal angles
# than across the shorter one. Sliding along the table, a tip meets an edge with the part of its
# rounded end that faces the object at the angle it arrives at; the steeper it arrives, the higher
# that part sits, and on an edge lower than it the tip meets the top corner, presses the object into
# the table and lifts off it. Measured from the true pose (flower seed 37, a development seed, trial
# seeds 1-2): plates and tiles 6.4-8.9 mm thick held 5/16 across the shorter side and 11/16 across the
# longer; lying dominoes under 9 mm 0/8 and 2/8; 9-11.4 mm plates and tiles 12/12 across the shorter
# side and 10/12 across the longer, and L and T shapes 6/8 and 5/8, so thicker objects keep the rule
# above (docs/design.md §5.4p). Only where the tips land outside the longer side at the preshape's
# widest (FLOWER_PRESHAPE_RANGE[0]): a ruler longer than that keeps the shorter side.
FLOWER_THIN = 0.009  # m
# Approaches within this angle of the vertical are "from above" for the table clearance.
_FROM_ABOVE = math.radians(45.0)
_DOWN = np.array([0.0, 0.0, -1.0])
# The WAM's base in the world's x-y plane (models/wam_barrett.dmd.yaml welds it at the origin): a grasp
# from the side comes from there, where the arm reaches without wrapping round the object.
ARM_BASE_XY = np.zeros(2)
# The cylindrical grasp of an upright object (a bottle standing): its approach dips this far below the
# level (a level approach puts the pre-grasp low beside the arm's base, out of the WAM's reach: every
# level pose tried on 14-23 cm bottles 55 cm out was), aimed at this fraction of the object's height
# (below a bottle's shoulder, above the palm's reach of the table). Measured, oracle, three bottles x
# three seeds: 45° at 0.6-0.7 held the two of ordinary mass 6/6 each; 0.5 missed a 23 cm one.
UPRIGHT_APPROACH_DIP = math.radians(45.0)
UPRIGHT_AIM_HEIGHT = 0.65
# The upright wrap's palm stops this far short of the object's near side, along the approach. Driven
# into contact with the palm, a 5.5-7.5 cm bottle meets the proximal links so close to the palm that the
# distal links close to their 48° limit before they touch its far side: their stall torque presses on
# the limit, the object is held by position alone and turns 10-16° in the hand whatever its mass
# (docs/results/payload.md). Standing off, the proximal links meet it further out and the distal links
# press its far side at 15-35°, under the motor's torque. Measured from the true pose, nine standing
# cylinders 4.5-9 cm across, 13-23 cm tall and 0.2-1 kg, trial seeds 1-2: in contact 3 of 6 held (seed
# 1); 5 or 6 cm short, 18/18 each; 7.5-9 cm short the wider ones are barely reached (dropped or
# missed). The approach starts as far out as before (`GraspPlan.approach_distance` shortened by it), so
# the pre-grasp keeps its reach (a pre-grasp further back was out of the WAM's reach at 4 of 9).
UPRIGHT_STANDOFF = 0.055


class GraspType(enum.Enum):
    SPHERICAL = "spherical"
    CYLINDRICAL = "cylindrical"
    BOX = "box"
    PRECISION = "precision"

    @classmethod
    def parse(cls, name: str) -> "GraspType":
        try:
            return cls(name.strip().lower())
        except ValueError:
            choices = ", ".join(g.value for g in cls)
            raise ValueError(f"unknown grasp '{name}' (choose from {choices})") from None


@dataclasses.dataclass(frozen=True)
class ObjectEstimate:
    """What a grasp needs to know about an object, in the world frame W.

    Attributes:
        center: the object's centre, m.
        R_WB: the object's axes (columns), e.g. its principal axes or a box's edges.
        size: the object's extent along each of those axes, m.
        principal_axis: unit vector of the elongation (None for objects with no long axis).
        source: where the estimate came from ("oracle", "camera").
        table_z: the height of the table the object rests on, m, where it is known (the table-top
            estimate measures heights from it); None: the object's bottom, the centre less its half
            extent along the vertical (`table_height`).
        grip_axis, grip_reach: where the table-top estimate measured it, how far the footprint reaches
            either way (m) across the horizontal unit direction `grip_axis` from the centre, within the
            band fingers closing across it meet (`primitives.table_top.grip_reach`); None and NaN where
            it was not measured (`reach_across`).
    """

    center: np.ndarray
    R_WB: np.ndarray
    size: np.ndarray
    principal_axis: np.ndarray | None = None
    source: str = "oracle"
    table_z: float | None = None
    grip_axis: np.ndarray | None = None
    grip_reach: float = math.nan

    def __post_init__(self):
        for name in ("center", "R_WB", "size"):
            value = np.asarray(getattr(self, name), dtype=float)
            if not np.all(np.isfinite(value)):
                raise ValueError(f"object estimate: {name} has a non-finite value")
        if np.any(np.asarray(self.size) <= 0):
            raise ValueError("object estimate: size must be positive along every axis")

    def half_extent_along(self, direction_W: np.ndarray) -> float:
        """Half the object's (box) extent along a world direction, m."""
        d = np.asarray(direction_W, float)
        return 0.5 * float(np.abs(np.asarray(self.R_WB).T @ d) @ np.asarray(self.size))

    def reach_across(self, along_W: np.ndarray) -> float:
        """How far from the centre, m, the object reaches across the horizontal direction `along_W`,
        where fingers closing across it at the centre meet it: half the box's extent across it, or the
        measured `grip_reach` where that is less and the grip was measured along (within
        GRIP_ALIGNMENT of) that direction. On a hammer the first is half the head's length and the
        second the handle's half width.

        Only ever less (behaviour 0.30.0): a reach beyond the box's half extent (an L or a T whose
        centroid is off its footprint rectangle's middle, a claw hammer's claw in the band) widened
        the landing by 1-7 degrees, and on flower seed 31 the trials it changed lost 4 and gained 1
        (docs/design.md §5.4n)."""
        along = np.asarray(along_W, float)
        across = np.cross([0.0, 0.0, 1.0], along)
        half = self.half_extent_along(across / max(np.linalg.norm(across), 1e-12))
        if self.grip_axis is not None and math.isfinite(self.grip_reach) and np.linalg.norm(across) > 1e-9:
            if abs(float(np.asarray(self.grip_axis, float) @ along)) >= math.cos(GRIP_ALIGNMENT) * np.linalg.norm(along):
                return min(half, float(self.grip_reach))
        return half

    @property
    def table_height(self) -> float:
        """The table's height, m: `table_z` where it is known, else the object's estimated bottom.

        Why both: a from-above grasp stops its palm a fixed sweep above the table, so an error in the
        table's height is an error in where the fingertips pass. The bottom of an estimate carries the
        estimate's errors in centre and height (2.7 mm low on the apple with the table-top estimate:
        the spherical grasp then lifted without it, docs/results/fig6_table_top/summary.md).
        """
        if self.table_z is not None:
            return float(self.table_z)
        return float(np.asarray(self.center)[2]) - self.half_extent_along(_DOWN)


@dataclasses.dataclass(frozen=True)
class GraspPlan:
    """Where the palm goes and how the hand closes.

    Attributes:
        grasp: the compliant grasp (or None for a planned grasp from another method).
        spread: the spread angle of F1 and F2, rad (the compliance mode's, or a planner's).
        X_WP_target: the palm pose at the end of the approach, if nothing is touched first.
        approach_distance: the palm starts this far back along -z_P from the target, m.
        stop_on_contact: end the approach early when the hand touches something.
        finger_preshape: proximal and distal angles (6, rad) to take before the approach (planned grasps).
        palm_force: the force the arm keeps along the palm normal while the hand closes, N. Above
            zero, the arm is compliant (`control.palm_impedance`) from the approach to the end of the
            close: the approach is a guarded landing (it ends when the hand touches), and the close
            holds the palm in place across and in tilt while pressing this hard along its normal,
            soft along it, so that fingertips that landed on the table stay on it as they close
            (the flower grasp). Zero: the arm is held by position throughout, as in the paper.
        breakaway: the hand's close. True: torque close with the clutch's breakaway, closing on
            through the lift and the hold (the paper's). False: a gentle close under the breakaway
            torque, each finger stopping at its first contact, then held there through the lift and
            the hold (the flower grasp: `control.grasp_executor`, docs/design.md §5.4f).
        thumb_closes: whether F3 closes with F1 and F2. False only for a gentle close (`breakaway`
            False): F3 then stays at its preshape while F1 and F2 close (the flower grasp's two-finger
            pinch, `PINCH_SPREAD`).
    """

    grasp: GraspType | None
    spread: float
    X_WP_target: RigidTransform
    approach_distance: float = 0.12
    stop_on_contact: bool = True
    finger_preshape: tuple[float, ...] = (0.0,) * 6
    palm_force: float = 0.0
    breakaway: bool = True
    thumb_closes: bool = True

    def __post_init__(self):
        if not self.thumb_closes and self.breakaway:
            raise ValueError("grasp plan: only a gentle close (breakaway False) can leave F3 open")

    @property
    def compliant_arm(self) -> bool:
        """Whether the arm complies (palm impedance) during the approach and the close."""
        return self.palm_force > 0.0

    @property
    def X_WP_pregrasp(self) -> RigidTransform:
        z = self.X_WP_target.rotation().col(2)
        return RigidTransform(self.X_WP_target.rotation(), self.X_WP_target.translation() - self.approach_distance * z)


def _palm_rotation(approach_W: np.ndarray, x_hint_W: np.ndarray) -> RotationMatrix:
    """R_WP with z_P = approach direction and x_P as close to x_hint as possible."""
    z = np.asarray(approach_W, float)
    z = z / np.linalg.norm(z)
    x = np.asarray(x_hint_W, float) - np.dot(x_hint_W, z) * z
    if np.linalg.norm(x) < 1e-6:
        x = np.cross(z, [0.0, 1.0, 0.0]) if abs(z[1]) < 0.9 else np.cross(z, [1.0, 0.0, 0.0])
    x = x / np.linalg.norm(x)
    return RotationMatrix(np.column_stack([x, np.cross(z, x), z]))


def _clear_of_table(estimate: ObjectEstimate, R_WP: RotationMatrix, target: np.ndarray, spread: float) -> np.ndarray:
    """Raises a from-above palm target so that the closing fingertips pass above the table."""
    approach = R_WP.col(2)
    if np.dot(approach, _DOWN) < math.cos(_FROM_ABOVE):
        return target
    sweep = hand.fingertip_sweep_depth(spread) + TABLE_CLEARANCE
    lowest_palm = estimate.table_height + sweep / np.dot(approach, _DOWN)
    if target[2] >= lowest_palm:
        return target
    return target + (lowest_palm - target[2]) / np.dot(-approach, [0.0, 0.0, 1.0]) * -approach


def _from_the_arm(center: np.ndarray) -> np.ndarray:
    """The level direction from the arm's base to `center` (unit, world)."""
    d = np.asarray(center, float)[:2] - ARM_BASE_XY
    d = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-9 else np.array([1.0, 0.0])
    return np.array([d[0], d[1], 0.0])


def _upright_cylindrical_grasp(estimate: ObjectEstimate) -> GraspPlan:
    """The cylindrical grasp of an upright object: the palm comes from the arm's side,
    `UPRIGHT_APPROACH_DIP` below the level, towards the axis at `UPRIGHT_AIM_HEIGHT` of the object's
    height, and stops `UPRIGHT_STANDOFF` short of its near side (the half-width along the level
    direction, measured along the approach); its x axis (the fingers' spread line) leans the same way
    from the vertical, so the fingers close around the axis. The approach is shortened by the standoff,
    so that it starts where an approach to the near side would."""
    level = _from_the_arm(estimate.center)
    approach = math.cos(UPRIGHT_APPROACH_DIP) * level + math.sin(UPRIGHT_APPROACH_DIP) * _DOWN
    R_WP = _palm_rotation(approach, np.array([0.0, 0.0, 1.0]))
    height = 2.0 * (float(np.asarray(estimate.center)[2]) - estimate.table_height)
    aim = np.array([estimate.center[0], estimate.center[1], estimate.table_height + UPRIGHT_AIM_HEIGHT * height])
    target = aim - (estimate.half_extent_along(level) + UPRIGHT_STANDOFF) * approach
    approach_distance = GraspPlan.approach_distance - UPRIGHT_STANDOFF
    return GraspPlan(GraspType.CYLINDRICAL, ComplianceMode.CYLINDRICAL.spread, RigidTransform(R_WP, target),
                     approach_distance=approach_distance)


def spherical_grasp(estimate: ObjectEstimate) -> GraspPlan:
    """Spherical mode; the palm centre approaches the object's centre from above."""
    x_hint = estimate.principal_axis if estimate.principal_axis is not None else np.asarray(estimate.R_WB)[:, 0]
    R_WP = _palm_rotation(_DOWN, x_hint)
    top = estimate.half_extent_along(_DOWN)
    spread = ComplianceMode.SPHERICAL.spread
    target = _clear_of_table(estimate, R_WP, np.asarray(estimate.center) + [0.0, 0.0, top], spread)
    return GraspPlan(GraspType.SPHERICAL, spread, RigidTransform(R_WP, target))


def cylindrical_grasp(estimate: ObjectEstimate) -> GraspPlan:
    """Cylindrical mode; centred on the principal axis, fingers closing perpendicular to it."""
    axis = estimate.principal_axis
    if axis is None:  # no long axis: any horizontal axis of the object will do
        R = np.asarray(estimate.R_WB)
        axis = R[:, int(np.argmin(np.abs(R[2, :])))]
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    # The approach direction perpendicular to the axis that points down the most.
    approach = _DOWN - np.dot(_DOWN, axis) * axis
    spread = ComplianceMode.CYLINDRICAL.spread
    if np.linalg.norm(approach) < 1e-6:  # an upright axis: from the arm's side
        return _upright_cylindrical_grasp(estimate)
    approach = approach / np.linalg.norm(approach)
    R_WP = _palm_rotation(approach, axis)
    target = np.asarray(estimate.center) - estimate.half_extent_along(approach) * approach
    target = _clear_of_table(estimate, R_WP, target, spread)
    return GraspPlan(GraspType.CYLINDRICAL, spread, RigidTransform(R_WP, target))


def _top_face_axes(R: np.ndarray, size: np.ndarray) -> tuple[int, int, int]:
    """(up, long, short): the index of the object axis closest to the vertical, and of the longer and
    shorter of the other two (the top face's sides)."""
    up = int(np.argmax(np.abs(R[2, :])))
    long_axis, short_axis = sorted((i for i in range(3) if i != up), key=lambda i: -size[i])
    return up, long_axis, short_axis


def box_grasp(estimate: ObjectEstimate) -> GraspPlan:
    """Cylindrical mode, aligned with the box: onto the face that looks up, fingers across its shorter side."""
    R = np.asarray(estimate.R_WB, float)
    size = np.asarray(estimate.size, float)
    up, long_axis, short_axis = _top_face_axes(R, size)
    approach = -R[:, up] * np.sign(R[2, up])  # into the top face
    R_WP = _palm_rotation(approach, R[:, long_axis])  # fingers close along the short side
    half_width = size[short_axis] / 2
    # Stand off when the face is wider than the knuckles: the proximal links then meet the top
    # edges at ~45 deg instead of landing flat on the face.
    standoff = max(0.0, half_width - _KNUCKLE_SPACING_HALF - _KNUCKLE_BEHIND_PALM)
    spread = ComplianceMode.CYLINDRICAL.spread
    target = np.asarray(estimate.center) - (size[up] / 2 + standoff) * approach
    target = _clear_of_table(estimate, R_WP, target, spread)
    return GraspPlan(GraspType.BOX, spread, RigidTransform(R_WP, target))


def flower_landing_angle(half_width: float, spread: float, fingers: tuple = hand.FINGERS,
                         preshape_range: tuple = FLOWER_PRESHAPE_RANGE) -> float:
    """The largest coupled proximal angle (rad, whole degrees within `preshape_range`) at which the
    closing `fingers`' tips' lowest centimetre lands at least `half_width` + FLOWER_MARGIN from the
    palm's centre line (`hand.fingertip_reach`); the range's low end if none does (a wide object)."""
    low, high = (round(math.degrees(a)) for a in preshape_range)
    for degrees in range(high, low - 1, -1):
        angle = math.radians(degrees)
        if hand.fingertip_reach(angle, spread, fingers=fingers) >= half_width + FLOWER_MARGIN:
            return angle
    return math.radians(low)


def _flower_height(estimate: ObjectEstimate) -> float:
    """How high the object stands above the table, m: its estimated top less the table's height."""
    return float(np.asarray(estimate.center)[2]) + estimate.half_extent_along(-_DOWN) - estimate.table_height


def flower_pinch_axis(estimate: ObjectEstimate) -> int | None:
    """The estimate's axis along which the flower grasp pinches with two fingers (`PINCH_SPREAD`), or
    None for the three-finger flower:

    * a small object (its footprint shorter than PINCH_MAX_LENGTH, standing at least PINCH_MIN_HEIGHT
      above the table) is pinched across the footprint's shorter side, or on a near-square footprint
      (`PINCH_SQUARE`) along the side nearer the arm's reach (from `ARM_BASE_XY`);
    * a thin, slender one lying down (`PINCH_SLENDER`, `PINCH_LENGTH_RANGE`, `PINCH_MAX_STICK_WIDTH`,
      `PINCH_MIN_END_HEIGHT`) end to end, along its long side.
    """
    R = np.asarray(estimate.R_WB, float)
    size = np.asarray(estimate.size, float)
    _, long_axis, short_axis = _top_face_axes(R, size)
    height = _flower_height(estimate)
    length, width = size[long_axis], size[short_axis]
    if length < PINCH_MAX_LENGTH and height >= PINCH_MIN_HEIGHT:
        if length > PINCH_SQUARE * width:
            return short_axis
        reach = np.asarray(estimate.center, float)[:2] - ARM_BASE_XY
        return max((short_axis, long_axis), key=lambda i: abs(float(R[:2, i] @ reach)))
    low, high = PINCH_LENGTH_RANGE
    if (low <= length <= high and length >= PINCH_SLENDER * width and width < PINCH_MAX_STICK_WIDTH
            and height >= PINCH_MIN_END_HEIGHT):
        return long_axis
    return None


def precision_grasp(estimate: ObjectEstimate) -> GraspPlan:
    """The flower grasp: fingertips landed on the table around the object, closed under a light force
    of the compliant arm (module docstring).

    The palm faces down above the object's centre, its fingers closing across the shorter horizontal
    side (on a square footprint, `FLOWER_SQUARE`, across the arm's reach: F1 and F2 on one side of
    the reach, F3 on the other; docs/design.md §5.4k; on a thin object, `FLOWER_THIN`, across the
    longer side where the tips can land outside it: §5.4p), F3 to the right of the arm's reach
    (`flower_facing.thumb_to_the_right`; where the camera saw the footprint, `funnel.planning` may turn
    it so that F1 and F2 meet its fuller side). The fingers
    are preshaped to `flower_landing_angle`, and the palm's target puts their deepest point
    `FLOWER_SINK` below the table, whatever the object's height: the guarded approach ends when the
    tips touch the table (or the object's top, if it is wider than the hand opens).

    On a small object with sides to pinch, or a slender one lying down (`flower_pinch_axis`), F1 and
    F2 at `PINCH_SPREAD` face each other across it (the small one) or at its ends (the slender one) and
    close on it; F3 stays open (its preshape 0), to the right of the arm's reach as in the three-finger
    flower.
    """
    R, size = np.asarray(estimate.R_WB, float), np.asarray(estimate.size, float)
    _, long_axis, short_axis = _top_face_axes(R, size)
    pinch_axis = flower_pinch_axis(estimate)
    if pinch_axis is not None:
        R_WP = _palm_rotation(_DOWN, R[:, pinch_axis])  # F1 and F2 close along x_P
        spread, thumb_closes = PINCH_SPREAD, False
        angle = flower_landing_angle(estimate.half_extent_along(R_WP.col(0)), spread, (1, 2), PINCH_PRESHAPE_RANGE)
        preshape = (angle, angle, 0.0) + (angle * hand.DISTAL_PER_PROXIMAL,) * 2 + (0.0,)
    else:
        spread, thumb_closes = ComplianceMode.CYLINDRICAL.spread, True
        closing_side = long_axis  # x_P along it: the fingers close across the shorter side
        if size[long_axis] <= FLOWER_SQUARE * size[short_axis]:  # square: across the reach
            reach = np.asarray(estimate.center, float)[:2] - ARM_BASE_XY
            closing_side = max((long_axis, short_axis), key=lambda i: abs(float(R[:2, i] @ reach)))
        elif _flower_height(estimate) < FLOWER_THIN and hand.fingertip_reach(
                FLOWER_PRESHAPE_RANGE[0], spread) >= 0.5 * size[long_axis] + FLOWER_MARGIN:
            closing_side = short_axis  # thin: the fingers close across the longer side
        R_WP = _palm_rotation(_DOWN, R[:, closing_side])
        angle = flower_landing_angle(estimate.reach_across(R_WP.col(0)), spread)
        preshape = (angle,) * 3 + (angle * hand.DISTAL_PER_PROXIMAL,) * 3
    # F3 (closing or open) to the right of the arm's reach: a half-turn changes neither the preshape nor
    # the target (`flower_facing`).
    R_WP = thumb_to_the_right(R_WP, np.asarray(estimate.center, float)[:2] - ARM_BASE_XY)
    palm_z = estimate.table_height + hand.fingertip_depth(angle, spread) - FLOWER_SINK
    target = np.array([estimate.center[0], estimate.center[1], palm_z], float)
    return GraspPlan(GraspType.PRECISION, spread, RigidTransform(R_WP, target), finger_preshape=preshape,
                     palm_force=FLOWER_FORCE, breakaway=False, thumb_closes=thumb_closes)


COMPLIANT_GRASPS = {
    GraspType.SPHERICAL: spherical_grasp,
    GraspType.CYLINDRICAL: cylindrical_grasp,
    GraspType.BOX: box_grasp,
    GraspType.PRECISION: precision_grasp,
}


# The compliant grasps of each shape the decision chooses (`primitives.decision`), in the order they are
# tried on one object (`funnel.planning.grasp_of`: the next when the one before has used up its tries).
# The paper's three shapes and the flat one have one grasp each. An upright object (a bottle, a
# carton on end) takes the box grasp from above first: the palm on its top, the fingers down its sides
# and, on a bottle, under its shoulder; then the cylindrical wrap from the arm's side, which let 1 kg
# bottles turn out of it (docs/design.md §5.4q, behaviour 0.44.0).
GRASPS_OF_SHAPE = {"sphere": (GraspType.SPHERICAL.value,), "cylinder": (GraspType.CYLINDRICAL.value,),
                   "box": (GraspType.BOX.value,), "flat": (GraspType.PRECISION.value,),
                   "upright": (GraspType.BOX.value, GraspType.CYLINDRICAL.value)}
# The compliant grasp of each shape at a first attempt (the decision: the grasp of the most resembling shape).
GRASP_OF_SHAPE = {shape: grasps[0] for shape, grasps in GRASPS_OF_SHAPE.items()}


def plan_compliant_grasp(grasp: GraspType | str, estimate: ObjectEstimate) -> GraspPlan:
    """The compliant grasp of the given type for the estimate."""
    grasp = GraspType.parse(grasp) if isinstance(grasp, str) else grasp
    return COMPLIANT_GRASPS[grasp](estimate)


# Each compliant grasp's near-symmetries: turns of the palm about its approach axis (rad) that give
# nearly the same grasp. The box, cylindrical and precision grasps close two sides of the object
# against each other, so a half-turn swaps F3 with F1 and F2; the spherical grasp's three fingers sit
# 120° apart, so thirds of a turn move each finger onto the next's place. Not exact: F3 opposes F1 and
# F2, which sit 25 mm off its closing plane (hand.AW), so an equivalent is a different grasp that is
# tried only when the grasp's own pose cannot be reached (GraspExecutor).
NEAR_SYMMETRIES = {GraspType.SPHERICAL: (2 * math.pi / 3, -2 * math.pi / 3), GraspType.CYLINDRICAL: (math.pi,),
                   GraspType.BOX: (math.pi,), GraspType.PRECISION: (math.pi,)}


def turned_about_approach(plan: GraspPlan, turn: float) -> GraspPlan:
    """`plan` with the palm turned by `turn` rad about its approach axis (z_P) through the palm centre."""
    X = plan.X_WP_target
    return dataclasses.replace(plan, X_WP_target=RigidTransform(X.rotation() @ RotationMatrix.MakeZRotation(turn),
                                                                  X.translation()))


def near_symmetric_plans(plan: GraspPlan) -> list[tuple[float, GraspPlan]]:
    """(turn, plan) for `plan` itself (turn 0) and then each of its grasp's near-symmetric
    equivalents, the smallest turn first; a plan of no compliant grasp (a planner's) has none."""
    turns = sorted(NEAR_SYMMETRIES.get(plan.grasp, ()), key=lambda a: (abs(a), a))
    return [(0.0, plan)] + [(turn, turned_about_approach(plan, turn)) for turn in turns]


def near_symmetric_alternatives(plan: GraspPlan) -> list[tuple[str, GraspPlan]]:
    """(what it is, plan) of each of `plan`'s near-symmetric equivalents, the smallest turn first: the
    alternatives the executor tries when the arm cannot reach `plan` (`GraspExecutor.plan_reachable_motion`)."""
    return [(f"{TURNED} {math.degrees(turn):+.0f}° {ABOUT_APPROACH}", p) for turn, p in near_symmetric_plans(plan)[1:]]


TURNED, ABOUT_APPROACH = "the grasp turned", "about the approach"  # the words of a near-symmetric alternative


def oracle_estimate(X_WO: RigidTransform, spec) -> ObjectEstimate:
    """The ground-truth estimate of an object (for oracle trials and tests): its axes and extents."""
    R_WO = X_WO.rotation().matrix()
    axis = None if spec.principal_axis is None else R_WO @ np.asarray(spec.principal_axis, float)
    return ObjectEstimate(center=X_WO.translation().copy(), R_WB=R_WO, size=np.asarray(spec.extents, float),
                          principal_axis=axis, source="oracle")


def planned_grasp(X_OH: RigidTransform, joint_angles: np.ndarray, X_WO: RigidTransform,
                  approach_distance: float = 0.12) -> GraspPlan:
    """A grasp planned by another method (hand base pose X_OH in the object frame, 8 joint angles in
    the controller order), executed through the same runner: the palm comes from a retreat along its
    normal to the planned pose with the planned finger posture, then the hand closes."""
    X_HP = RigidTransform([0.0, 0.0, hand.PALM_HEIGHT])
    X_WP = X_WO @ X_OH @ X_HP
    q = np.asarray(joint_angles, float)
    return GraspPlan(None, float(q[0]), X_WP, approach_distance=approach_distance, stop_on_contact=False,
                     finger_preshape=tuple(float(a) for a in q[2:8]))
