"""Did the grasp hold? What the robot itself can tell at the end of an attempt: the wrist camera's view.

A real WAM and BH8 do not know where the object is; the simulator's contact results and the object's
true pose are not sensors. What they can tell: the finger joint angles and motor efforts, the arm's
joint torques, and the wrist camera. The finger angles alone do not tell a hold from a miss (a plate
missed by an earlier precision grasp ended with its proximal joints at 0.95 rad, as a held ring did at
1.04 rad: the flower grasp's gentle close freezes a finger where it stopped, on the table or on the
object), so the test is the camera's:

* at the end of the attempt (after the lift and the hold), the wrist camera's depth image is taken;
  the object's pixels (the same segmentation the exploration uses: the label image) are back-projected
  to world points (`table_top.back_project`);
* the object is **held** when its lowest visible points stand at least half the lift height above the
  table (`LIFTED_FRACTION`): a lifted object rose with the hand, whole; one left behind, dropped or
  knocked over did not, and one out of view was not held either. Where the table's height is not
  known, its highest visible points must stand that much above the top the exploration measured. The
  bottom decides because a top can rise alone (behaviour 0.36.0): a hammer lifted by its handle, its
  head still on the table, pivots, and showed a top risen 7-9 cm over the test's threshold and a
  bottom 2-3 cm above the table, read as held (tools seeds 13 and 17). And the top cannot tell a tall
  object held from above: the palm hides its top from the wrist camera, which sees only its sides (a
  20 cm handle held by the box grasp and lifted 10 cm showed a top 8 mm under the threshold; its
  sides' lowest points were far above the table).

And it must have risen with the camera: the camera also looks as the lift begins (the hand closed on
it, still low). The camera rides on the palm, so an object that rose with the hand keeps its depth,
pixel by pixel, while one left on the table is as much deeper as the hand rose. An object whose depth
grew by `LIFTED_FRACTION` of the lift height or more was left behind, whatever its visible sides'
heights say (a 17.8 cm union that never rose showed sides whose lowest visible points stood 6.8 cm
above the table, over the bottom test's threshold: novel seed 31337). One whose depth shrank that much
did not rise with the hand either (behaviour 0.37.0): a held object cannot come nearer to a camera on
the palm holding it, and one that fell can show a nearer face (a 22 cm blob dropped in the lift,
standing on its end at the table, read -5.8 cm and was taken for held: novel seed 1201). Pixel by
pixel holds while the camera rises along its own axis, as it does with the palm level; with the palm
tilted (the upright grasp from the arm's side) the camera moves across its view as well, and a 16.5 cm
bottle that never rose measured -2 to -5 cm (everyday seed 8080): the -5 cm is now caught, a -2 cm
would not be (docs/design.md §5.4h says what was tried).

An object pressed against the palm fills the camera's view nearer than the camera ranges (2 cm): a
20 cm handle held from above filled all of it with the depth reading "too near", and with no point
seen it was taken for not held, opened on, and grasped again (novel seed 4096). A camera that is too
near to range still sees the object in its colour (here, its label) image, and an object that did not
rise with the hand lies 10 cm or more below the camera after the lift. So the object filling at least
`TOO_NEAR_SHARE` of the image nearer than the range rose with the hand (`too_near_share`), and a depth
that grew over the lift on the few pixels still in range (the rim of the pressed region, which a held
object's settling in the grasp moves onto its farther parts) is not taken for left behind.

And where the object shows no pixel in range at all, any share of it too near to range (at least
`TOO_NEAR_UNSEEN_SHARE`) is in the hand (behaviour 0.49.0): after the lift, an object left on the table
lies at least the lift height below the camera, well inside its range, so an object pixel nearer than
2 cm is one the hand carries. A plate held by the flower grasp filled 37 % of the image too near and
showed nothing in range, and a ring 6 %: both were held by the success test and let go (SimplerEnv's
plate, novel seed 2230's ring 026). Of the 124 attempts in the stored records with no object pixel in
range and some too near, every one had held.

An object the camera sees none of is not held, though the fingers can hide a small one whole (a
3.4 cm ring held by the flower grasp): the finger angles and motor torques were tried as the tie-break
and do not tell (docs/design.md §5.4h), so such an attempt is tried again and the object may be lost.

And the object must not have slid in the hand over the hold: the camera also looks as the hold
begins, and an object that moved `slip_distance` (the success test's obvious slip, 1 cm) or more
along the camera's axis by its end was not held, though it is still up. The camera rides on the palm,
so the object's depth, pixel by pixel where both images see it, changes only when it moves in the
hand. (A median over the visible points would not do: how much of a held object the camera sees can
change while it stays put, 200 pixels as one hold began and 942 at its end with 0.8 mm of slip; why
was not traced.) A 3 cm tall ring held by the box grasp slid 2.8-3.4 cm down through the fingers and
stayed in the hand (novel seed 5150); without this test the robot took it for held and did not try
again. Along the axis is not enough: a ring that slid 2.5 cm mostly across the view changed its depth
by 6 mm (novel seed 2718). So the two images' object pixels are also back-projected into the camera's
frame, which rides on the palm, and the shift that carries the first point set onto the second is
fitted (`in_hand_shift`: a trimmed ICP, translation only; the closest 70 % of the point pairs decide,
so what only one image sees is left out). That ring measured 20.6 mm. Against the true slip on 19 trials
of novel and everyday objects (docs/design.md §5.4h): within 1.4 mm on 17, from 0.2 to 101 mm; under
it on a bottle that slid 9.7 mm along its own axis, a surface that slides within itself (1.8 mm).
The success test also fails a turn of 10° in the hand, which can move the points little: a polycube
that turned 16° moved 6 mm (everyday seed 7919). So the rigid motion between the two point sets is
fitted too (`fit_motion`, `in_hand_turn`), and a turn of `slip_angle_deg` or more is not held
(docs/design.md §5.4h), unless the object fills `TOO_NEAR_SHARE` of the view too near to range: what
is left to fit a turn to is then its rim, and on fresh seed 6661 two objects held still read turns of
10.2° and 65.6° from 1134 and 166 pixels (81 % and 98 % too near). Every true turn read on the stored
studies came from a view at most 44 % too near.

It is evaluated once per attempt on the final state, so an attempt that missed still runs its lift
and hold (simulated seconds, not wall minutes) before the next attempt.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from scipy.spatial import cKDTree

from drake_grasp.primitives import table_top
from drake_grasp.primitives.camera_model import CameraIntrinsics

LIFTED_FRACTION = 0.5  # of the lift height: the object's top must have risen this much to count as held
TOP_PERCENTILE = 95  # the visible object's top: this percentile of its points' heights (robust to a stray pixel)
BOTTOM_PERCENTILE = 5  # the visible object's bottom, likewise
SLIP_DISTANCE = 0.01  # m: the success test's obvious slip (the scenario's protocol.slip_distance)
MIN_COMMON_PIXELS = 50  # pixels seeing the object both as the hold began and at its end, to compare them
TOO_NEAR_SHARE = 0.5  # of the image: the object filling this much nearer than the camera ranges is in the hand
TOO_NEAR_UNSEEN_SHARE = 0.01  # of the image: so is one this much too near, with no pixel in range
SHIFT_STRIDE = 2  # every second row and column of the in-hand depth images, for the shift's point sets
SHIFT_KEPT = 0.7  # the fraction of closest point pairs the shift is fitted to (the rest: seen only once)
SHIFT_ITERATIONS = 30  # at most, from each start (the fit stops when a step is under 0.01 mm)
TURN_STARTS = (-30.0, -15.0, 15.0, 30.0)  # degrees about the view's axis: `fit_motion`'s further starts
TURN_RESIDUAL_KEPT = 0.95  # the fraction of closest pairs whose residual tells `fit_motion`'s fits apart
TURN_EVIDENCE = 0.6  # a turn counts when it leaves at most this share of the shift's residual
# ... and when it explains at least this much of it (m²: a mean squared misfit of (1 mm)²). Below it the
# shift has already matched the points as closely as the pixels sample the surface: a held mug, round
# but for its handle, left 0.8 mm² after the shift, and a turn of 13.4° about its axis "explained" 0.43
# mm² of it (it turned 0.4°). A box turned 15° in the view's plane leaves 5.0 mm² to the shift and
# 1.8 to the turn; a polycube that turned 16.6° in the hand 18.3 and 1.2 (docs/design.md §5.4h).
TURN_MIN_EXPLAINED = 1e-6
SLIP_ANGLE_DEG = 10.0  # the success test's obvious turn in the hand (the scenario's protocol.slip_angle_deg)


@dataclasses.dataclass(frozen=True)
class Sensed:
    """What the camera told at the end of an attempt.

    Attributes:
        held: the object's top, or its bottom, rose with the hand.
        pixels: object pixels seen.
        top: the visible object's top height, m (NaN when unseen).
        expected_top: the exploration's top plus `LIFTED_FRACTION` of the lift height, m.
        bottom: the visible object's lowest height, m (NaN when unseen).
        expected_bottom: the table's height plus `LIFTED_FRACTION` of the lift height, m (NaN when
            the table's height was not given).
        slid: how far the object moved along the camera's axis over the hold (`depth_change`), m (NaN
            when the hold's start was not seen, or too few pixels saw it both times).
        rose_short: how much less than the hand the object rose from the lift's start to the end
            (`depth_change`: its depth in the camera's view grows by that much; negative: it came
            nearer), m (NaN likewise).
        moved: how far the object moved in the hand over the hold, in any direction (`in_hand_shift`),
            m (NaN when not measured).
        turned: how far the object turned in the hand over the hold (`in_hand_turn`), degrees (NaN
            when not measured).
        too_near: the share of the image the object fills nearer than the camera ranges
            (`too_near_share`).
    """

    held: bool
    pixels: int
    top: float
    expected_top: float
    bottom: float = float("nan")
    expected_bottom: float = float("nan")
    slid: float = float("nan")
    rose_short: float = float("nan")
    moved: float = float("nan")
    too_near: float = 0.0
    turned: float = float("nan")

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


def visible_object_points(station, root_context, stride: int = 2,
                          image: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """World points (N × 3, m) of the object's pixels in the wrist camera's depth image (`image`:
    `object_depth_image`'s, when the caller has it already)."""
    depth, mask = image if image is not None else object_depth_image(station, root_context)
    intrinsics = CameraIntrinsics.from_camera_config(station.scenario.camera)
    X_WC = station.diagram.GetOutputPort("camera.X_WC").Eval(station.diagram.GetMyContextFromRoot(root_context))
    return table_top.back_project(depth, mask, intrinsics, X_WC.rotation().matrix(), X_WC.translation(), stride)


def object_depth_image(station, root_context) -> tuple[np.ndarray, np.ndarray]:
    """The wrist camera's depth image (H × W, m along the optical axis) and the object's pixels in it
    (H × W booleans: the label image's, as the exploration segments)."""
    from drake_grasp.perception.wiring import object_labels

    station_context = station.diagram.GetMyContextFromRoot(root_context)
    depth = station.diagram.GetOutputPort("camera.depth_image").Eval(station_context).data
    labels = station.diagram.GetOutputPort("camera.label_image").Eval(station_context).data
    mask = np.isin(np.asarray(labels).reshape(labels.shape[:2]), object_labels(station))
    return np.array(depth, float).reshape(mask.shape), mask


def too_near_share(depth: np.ndarray, mask: np.ndarray) -> float:
    """The share of the image (0-1) whose pixels are the object's (`mask`) with the depth reading
    "nearer than the camera ranges" (Drake's depth images: 0; `depth` in m)."""
    depth = np.asarray(depth, float).reshape(mask.shape)
    return float(np.mean(np.asarray(mask, bool) & (depth == 0.0)))


def in_hand_depth(depth: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """The object's depth image: `depth` (m) where `mask` and the depth is finite and positive, NaN elsewhere."""
    return np.where(mask & np.isfinite(depth) & (depth > 0), depth, np.nan)


def lift_start_depth(depth: np.ndarray, mask: np.ndarray, near: float) -> np.ndarray:
    """The object's depth image as the lift begins (`in_hand_depth`), with its pixels nearer than the
    camera ranges at `near` (m, the camera's nearest range): their true depth is at most that.

    The hand has just closed on the object, and a palm on a large one presses the camera into it:
    a 3.8 kg piggy bank 13.7 cm tall, held by the spherical grasp, filled the view too near to range,
    so `depth_change` had no pixel to compare and the object, left on the table while the hand rose
    10 cm, was taken for held (its visible sides stood over the bottom test's 5 cm). Seen at the end
    10 cm below the camera, those pixels grew by at least 10 cm less the bound; an object that rose
    with the hand stays too near and drops out of the comparison."""
    bounded = np.where(mask & (np.asarray(depth, float) == 0.0), float(near), np.nan)
    seen = in_hand_depth(depth, mask)
    return np.where(np.isfinite(seen), seen, bounded)


def depth_change(start: np.ndarray, end: np.ndarray, min_pixels: int = MIN_COMMON_PIXELS) -> float:
    """How far the object moved along the camera's axis between two of its depth images (`in_hand_depth`,
    m; NaN off the object): the median change over the pixels that see it in both, m (NaN when fewer
    than `min_pixels` do). Pixel by pixel, so it does not depend on how much of the object each image
    sees; the camera rides on the palm, so a change is the object moving in the hand."""
    both = np.isfinite(start) & np.isfinite(end)
    if int(both.sum()) < min_pixels:
        return float("nan")
    return float(np.median(end[both] - start[both]))


def in_hand_points(depth: np.ndarray, intrinsics: CameraIntrinsics, stride: int = SHIFT_STRIDE) -> np.ndarray:
    """The object's points (N × 3, m) in the camera's frame, from its in-hand depth image
    (`in_hand_depth`: NaN off the object): the frame rides on the palm, so these are points of the
    object in the hand's frame (`table_top.back_project` with the camera at the origin)."""
    depth = np.asarray(depth, float)
    return table_top.back_project(depth, np.isfinite(depth), intrinsics, np.eye(3), np.zeros(3), stride)


def fit_shift(start: np.ndarray, end: np.ndarray, kept: float = SHIFT_KEPT,
              iterations: int = SHIFT_ITERATIONS) -> np.ndarray:
    """The translation (3,) that carries point set `start` onto `end` (N × 3 and M × 3, one frame, m):
    a trimmed ICP (translation only). The smaller set is matched into the larger, each point to its
    nearest neighbour, and the shift is fitted to the closest `kept` fraction of the pairs: what one
    image sees and the other does not (a finger's shadow moved, the object turned a face into view)
    is left out. Started from no shift and from the centroids' difference; the fit with the smaller
    trimmed residual wins. A surface that slides within itself (a flat face moving in its plane) gives
    no evidence of that motion, and the fit stays near its start: it can miss a slip, not invent one."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    flip = len(start) > len(end)
    source, target = (end, start) if flip else (start, end)
    tree = cKDTree(target)
    n_kept = max(3, int(kept * len(source)))

    def fit(t: np.ndarray) -> tuple[np.ndarray, float]:
        residual = float("inf")
        for _ in range(iterations):
            distance, index = tree.query(source + t)
            closest = np.argsort(distance)[:n_kept]
            step = np.mean(target[index[closest]] - (source[closest] + t), axis=0)
            t = t + step
            residual = float(np.mean(distance[closest] ** 2))
            if np.linalg.norm(step) < 1e-5:
                break
        return t, residual

    fits = [fit(np.zeros(3)), fit(target.mean(axis=0) - source.mean(axis=0))]
    t = min(fits, key=lambda f: f[1])[0]
    return -t if flip else t


def in_hand_shift(start: np.ndarray, end: np.ndarray, intrinsics: CameraIntrinsics,
                  min_pixels: int = MIN_COMMON_PIXELS) -> float:
    """How far the object moved in the hand between two of its in-hand depth images (`in_hand_depth`),
    in any direction, m: the length of `fit_shift` between their points in the camera's frame (NaN when
    either image sees fewer than `min_pixels` of its points). `depth_change` sees motion along the
    camera's axis only: a ring that slid 25 mm mostly across the view changed its depth by 6.4 mm, and
    was taken for held, where this reads 20.6 mm (novel seed 2718)."""
    points = _in_hand_point_sets(start, end, intrinsics, min_pixels)
    return float("nan") if points is None else float(np.linalg.norm(fit_shift(*points)))


def fit_motion(start: np.ndarray, end: np.ndarray, kept: float = SHIFT_KEPT,
               iterations: int = SHIFT_ITERATIONS, shift: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The rigid motion (R 3 × 3, t 3) that carries point set `start` onto `end` (m, one frame): a
    trimmed ICP as `fit_shift`'s, with the rotation fitted too (Kabsch on the closest `kept` fraction
    of the pairs).

    A face that turns in its own plane slides within itself, and a fit started from no turn stops
    short (a box face turned 15° about the view's axis read 4.5°), so fits start from `fit_shift`'s
    translation and from turns of `TURN_STARTS` about the view's axis; the one that leaves the
    smallest residual over the closest `TURN_RESIDUAL_KEPT` of its pairs wins (the fit's own trimmed
    pairs match a face's inside whatever its turn). A turn that does not bring that residual under
    `TURN_EVIDENCE` times the shift's alone, or that explains less than `TURN_MIN_EXPLAINED` of it,
    is not evidenced and is not reported: a ball turning about its centre shows nothing to fit, and its
    fit drifts 9° on the shadow of a finger; a round object's turn about its own axis shows only in
    how the pixels sample its surface, and in the few points of a handle. So the fit can
    miss a turn, as the shift can miss a slip, but not invent one. `shift`: `fit_shift`'s translation
    between the two sets, where the caller has it already."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    tree = cKDTree(end)
    n_kept = max(3, int(kept * len(start)))

    def residual(R: np.ndarray, t: np.ndarray) -> float:
        distance, _ = tree.query(start @ R.T + t)
        return float(np.mean(np.sort(distance)[:max(3, int(TURN_RESIDUAL_KEPT * len(start)))] ** 2))

    def fit(R: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        for _ in range(iterations):
            distance, index = tree.query(start @ R.T + t)
            closest = np.argsort(distance)[:n_kept]
            a, b = start[closest], end[index[closest]]
            ca, cb = a.mean(axis=0), b.mean(axis=0)
            u, _, vt = np.linalg.svd((a - ca).T @ (b - cb))
            d = np.sign(np.linalg.det(vt.T @ u.T))
            R_new = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
            t_new = cb - R_new @ ca
            step = np.linalg.norm(t_new - t) + np.linalg.norm(R_new - R)
            R, t = R_new, t_new
            if step < 1e-5:
                break
        return R, t

    if shift is None:
        shift = fit_shift(start, end, kept, iterations)
    fits = [fit(np.eye(3), shift)]
    c_start, c_end = start.mean(axis=0), end.mean(axis=0)
    for degrees in TURN_STARTS:
        a = math.radians(degrees)
        R0 = np.array([[math.cos(a), -math.sin(a), 0.0], [math.sin(a), math.cos(a), 0.0], [0.0, 0.0, 1.0]])
        fits.append(fit(R0, c_end - R0 @ c_start))
    R, t = min(fits, key=lambda f: residual(*f))
    left, by_shift = residual(R, t), residual(np.eye(3), shift)
    if left >= TURN_EVIDENCE * by_shift or by_shift - left < TURN_MIN_EXPLAINED:
        return np.eye(3), shift
    return R, t


def turn_angle(R: np.ndarray) -> float:
    """The angle of rotation `R`, degrees."""
    return float(np.degrees(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0))))


def in_hand_motion(start: np.ndarray, end: np.ndarray, intrinsics: CameraIntrinsics,
                   min_pixels: int = MIN_COMMON_PIXELS) -> tuple[float, float]:
    """(moved m, turned degrees): `in_hand_shift` and `in_hand_turn` from one back-projection of the two
    images and one shift fit (NaN, NaN when either image sees fewer than `min_pixels` of its points)."""
    points = _in_hand_point_sets(start, end, intrinsics, min_pixels)
    if points is None:
        return float("nan"), float("nan")
    shift = fit_shift(*points)
    return float(np.linalg.norm(shift)), turn_angle(fit_motion(*points, shift=shift)[0])


def _in_hand_point_sets(start: np.ndarray, end: np.ndarray, intrinsics: CameraIntrinsics,
                        min_pixels: int) -> tuple[np.ndarray, np.ndarray] | None:
    """The two in-hand depth images' points (`in_hand_points`), or None when either has fewer than
    `min_pixels`."""
    p_start, p_end = in_hand_points(start, intrinsics), in_hand_points(end, intrinsics)
    return None if min(len(p_start), len(p_end)) < min_pixels else (p_start, p_end)


def in_hand_turn(start: np.ndarray, end: np.ndarray, intrinsics: CameraIntrinsics,
                 min_pixels: int = MIN_COMMON_PIXELS) -> float:
    """How far the object turned in the hand between two of its in-hand depth images (`in_hand_depth`),
    degrees: the angle of `fit_motion` between their points in the camera's frame (NaN when either
    image sees fewer than `min_pixels` of its points). A turn moves the points near the turn's axis
    little: a 7 cm polycube that turned 17° in the hand moved 6 mm, under the obvious slip's 1 cm
    (everyday seed 7919)."""
    return in_hand_motion(start, end, intrinsics, min_pixels)[1]


def sense_hold(points_W: np.ndarray, top_before: float, lift_height: float,
               table_z: float | None = None, hold_depths: tuple[np.ndarray, np.ndarray] | None = None,
               slip_distance: float = SLIP_DISTANCE,
               lift_depths: tuple[np.ndarray, np.ndarray] | None = None,
               intrinsics: CameraIntrinsics | None = None, too_near: float = 0.0,
               slip_angle_deg: float = SLIP_ANGLE_DEG) -> Sensed:
    """Whether the object is held (module docstring): where the table's height `table_z` (m) is given,
    its visible points' bottom against the table and the lift height (m); else their top against the
    top the exploration measured before the grasp (m, world z); and where
    `hold_depths` gives the object's depth images (`in_hand_depth`) as the hold began and at its end,
    how far it moved in the hand along the camera's axis (`depth_change`), against `slip_distance` (m);
    and where `lift_depths` gives them as the lift began and at the end, whether it was left behind:
    its depth grew by `LIFTED_FRACTION` of the lift height or more. With the camera's `intrinsics`,
    `hold_depths` also give how far it moved in the hand in any direction (`in_hand_shift`), against
    `slip_distance`, and how far it turned there (`in_hand_turn`), against `slip_angle_deg`. An object filling `too_near` (a share of the image) of at least `TOO_NEAR_SHARE`
    nearer than the camera ranges rose with the hand, whatever the points seen say: its turn is
    recorded but not held against it, nor is a depth that grew over the lift (behaviour 0.48.0: a
    blob and a handle held by the box grasp, pressed into the view, read 5-10 cm "left behind" from
    the rim of the pressed region and were let go; novel seed 2230). So does one with no point in range
    and at least `TOO_NEAR_UNSEEN_SHARE` of the image too near (behaviour 0.49.0)."""
    expected = float(top_before) + LIFTED_FRACTION * float(lift_height)
    expected_bottom = float("nan") if table_z is None else float(table_z) + LIFTED_FRACTION * float(lift_height)
    pressed = too_near >= TOO_NEAR_SHARE or (len(points_W) == 0 and too_near >= TOO_NEAR_UNSEEN_SHARE)
    if len(points_W) == 0 and not pressed:
        return Sensed(False, 0, float("nan"), expected, float("nan"), expected_bottom, too_near=too_near)
    heights = np.asarray(points_W, float).reshape(-1, 3)[:, 2]
    top = float(np.percentile(heights, TOP_PERCENTILE)) if len(heights) else float("nan")
    bottom = float(np.percentile(heights, BOTTOM_PERCENTILE)) if len(heights) else float("nan")
    # With the table's height known, the bottom decides: an object that rose whole has its lowest
    # visible points up too, while one pivoting on the table (a hammer lifted by its handle, its head
    # still down) raises its top alone. Without it, the top.
    held = pressed or (bottom >= expected_bottom if table_z is not None else top >= expected)
    slid = float("nan")
    if hold_depths is not None:
        slid = depth_change(*hold_depths)
        held = held and not abs(slid) >= slip_distance
    moved = turned = float("nan")
    if hold_depths is not None and intrinsics is not None:
        moved, turned = in_hand_motion(*hold_depths, intrinsics)
        # A turn fitted to what is left of an object pressed into the view (its rim, or a few hundred
        # pixels) is not to be trusted (`TOO_NEAR_SHARE`): the shift still counts.
        held = held and not moved >= slip_distance and not (turned >= slip_angle_deg and not pressed)
    rose_short = float("nan")
    if lift_depths is not None:
        rose_short = depth_change(*lift_depths)
        # Grown: left behind, unless the object is still pressed into the view (then it is in the hand,
        # and its few pixels in range are the rim of the pressed region, which a millimetre's settling
        # in the grasp moves onto farther parts of the object). Shrunk: fallen, pressed or not.
        left_behind = rose_short >= LIFTED_FRACTION * float(lift_height) and not pressed
        fallen = rose_short <= -LIFTED_FRACTION * float(lift_height)
        held = held and not left_behind and not fallen
    return Sensed(bool(held), int(len(points_W)), top, expected, bottom, expected_bottom, slid, rose_short, moved,
                  too_near, turned)
