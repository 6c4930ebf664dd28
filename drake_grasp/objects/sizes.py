"""The sizes of object the hand can grasp: a user's object file outside them is refused before any
trial runs, with one line that names its size and the unit its file is likely in.

Why: a file in millimetres read as metres is a 100 m object; it used to draw a warning and then a
whole trial that ended in "simulation diverged" with exit code 0. The range comes from the robot:

* the largest extent of a graspable object is at most GRASPABLE_EXTENTS[1] = 0.5 m. The open hand
  spans at most :func:`hand_span` (0.37 m between the fingertips of F1 and F2 spread apart, from
  the D-H table in ``robot/hand.py``), so every grasp closes across a dimension of the object below
  that; and the exploration's first view (the wrist camera 0.45 m above the table, 60° vertical
  field of view) sees 0.52 m of the table across, so a longer object is not seen whole. 0.5 m
  leaves a stick of 45 cm graspable across its middle;
* an object whose *smallest* width exceeds the hand's span cannot be closed around in any direction
  (a 40 cm cube): refused too;
* the smallest: GRASPABLE_EXTENTS[0] = 3 mm of largest extent. The table-top estimate's height map
  has 3 mm cells (scenario ``table_top.cell``), and a convex piece thinner than 2 mm carries no contact
  (``objects/cleaning.py``, MIN_THICKNESS): a smaller object has nothing the hand or the camera can
  resolve. The flower's sticks (9 mm across, centimetres long) and plates (6 mm thick) are far above it.

Between 3 mm and 1 cm (PLAUSIBLE_EXTENTS[0]) the object is loaded with a UnitsWarning: small enough
to be a file in metres read with a wrong ``--scale``, large enough to be a real bead. ``--scale`` is
always the way out: the refusal names the factors (0.001 for millimetres, 0.01 for centimetres,
0.0254 for inches) that bring the object into the range where objects usually are.

Only objects a user names by file are checked: the catalogue and Fig. 4's primitives (``sphere:D``
and the like, 2-34 cm in Fig. 4) have sizes of their own. The largest extent is the object's
largest width along the file's axes and its principal axes (a box's longest edge, a rod's length
however it lies); the smallest width is taken over those and 400 directions spread over the sphere.
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np

from drake_grasp.objects.spec import ObjectError, PLAUSIBLE_EXTENTS, UnitsWarning

GRASPABLE_EXTENTS = (0.003, 0.5)  # m: largest extent of an object file's object (module docstring)
UNITS = (("millimetres", 0.001), ("centimetres", 0.01), ("inches", 0.0254))
_DIRECTIONS = 400


@functools.lru_cache(maxsize=1)
def hand_span() -> float:
    """The widest opening of the open hand, m: fingertip to fingertip (the rounded tips' farthest
    points, `hand.DISTAL_TIP_REACH`) of F1 and F2 spread apart (spread 90°), or of F1 and F3 (spread
    0), proximal joints at 0."""
    from drake_grasp.robot.hand import DISTAL_NOSE_CENTRE_Y, DISTAL_TIP_REACH, distal_points_in_base

    def tip(finger, spread):
        return distal_points_in_base(finger, spread, 0.0, 0.0, [[DISTAL_TIP_REACH, DISTAL_NOSE_CENTRE_Y, 0.0]])[0]

    return float(max(np.linalg.norm(tip(1, math.pi / 2) - tip(2, math.pi / 2)),
                     np.linalg.norm(tip(1, 0.0) - tip(3, 0.0))))


@functools.lru_cache(maxsize=1)
def _sphere_directions() -> np.ndarray:
    """Unit vectors spread over a half sphere (a Fibonacci lattice; a width is the same both ways)."""
    i = np.arange(_DIRECTIONS) + 0.5
    z = 1.0 - i / _DIRECTIONS
    angle = math.pi * (1.0 + 5**0.5) * i
    r = np.sqrt(1.0 - z**2)
    return np.column_stack([r * np.cos(angle), r * np.sin(angle), z])


def widths(points: np.ndarray) -> tuple[float, float]:
    """(smallest, largest) width of a point set (m). The largest is its largest extent along the
    file's axes and its principal axes (a box's longest edge, a rod's length however it lies); the
    smallest, its thinnest extent along those and a spread of directions (a plate's thickness, a
    tilted cube's edge). NaN if a point is not finite."""
    points = np.asarray(points, float).reshape(-1, 3)
    if len(points) == 0 or not np.all(np.isfinite(points)):
        return math.nan, math.nan
    centred = points - points.mean(axis=0)
    try:
        principal = np.linalg.eigh(centred.T @ centred)[1].T
    except np.linalg.LinAlgError:
        principal = np.eye(3)
    directions = np.vstack([np.eye(3), principal, _sphere_directions()])
    projections = centred @ directions.T
    spans = projections.max(axis=0) - projections.min(axis=0)
    return float(spans.min()), float(spans[:6].max())


def likely_units(extent: float, scale: float = 1.0) -> list[tuple[str, float]]:
    """The (unit, --scale) pairs that would bring an object of largest extent `extent` (m, read with
    `scale`) into PLAUSIBLE_EXTENTS, the range where objects for this hand usually are."""
    low, high = PLAUSIBLE_EXTENTS
    return [(unit, factor) for unit, factor in UNITS if low <= extent / scale * factor <= high]


def _hint(extent: float, scale: float) -> str:
    """What to do about a size in the wrong unit: `--scale` (mesh and model files take it)."""
    units = likely_units(extent, scale)
    if scale != 1.0 and PLAUSIBLE_EXTENTS[0] <= extent / scale <= PLAUSIBLE_EXTENTS[1]:
        return f"is the file in metres already? drop --scale {scale:g}"
    way = "--scale"
    if extent < PLAUSIBLE_EXTENTS[0]:
        return f"is the file in metres? ({way} multiplies its coordinates)"
    if not units:
        return f"no unit ({way} 0.001, 0.01, 0.0254) brings it into range"
    options = " or ".join(f"{unit} ({way} {factor:g})" for unit, factor in units)
    return f"is the file in {options}?"


def _length(metres: float) -> str:
    if metres >= 1.0:
        return f"{metres:.3g} m"
    if metres >= 0.01:
        return f"{metres * 100:.3g} cm"
    return f"{metres * 1000:.3g} mm"


def size_problem(smallest: float, largest: float, scale: float = 1.0) -> str | None:
    """Why an object file's object, of these widths (m, read with `scale`), cannot be grasped, or
    None: a size that is not finite, a largest extent outside GRASPABLE_EXTENTS, or a smallest width
    above the hand's span."""
    if not (math.isfinite(smallest) and math.isfinite(largest)):
        return "its size is not finite (a coordinate is NaN or inf)"
    low, high = GRASPABLE_EXTENTS
    if largest > high:
        return (f"largest extent {_length(largest)}: more than the {_length(high)} a grasp here can take (the open "
                f"hand spans {_length(hand_span())}); {_hint(largest, scale)}")
    if largest < low:
        return (f"largest extent {_length(largest)}: less than the {_length(low)} the hand and camera resolve; "
                f"{_hint(largest, scale)}")
    if smallest > hand_span():
        return (f"smallest width {_length(smallest)}: wider in every direction than the open hand "
                f"({_length(hand_span())}), no grasp closes around it; {_hint(largest, scale)}")
    return None


def size_warning(largest: float, scale: float = 1.0) -> str | None:
    """A warning for a graspable object whose size still suggests the wrong unit (largest extent
    below PLAUSIBLE_EXTENTS[0]), or None."""
    if largest < PLAUSIBLE_EXTENTS[0]:
        return (f"largest extent {_length(largest)}, smaller than the hand grasps reliably; "
                f"{_hint(largest, scale)}")
    return None


def check_size(points: np.ndarray, label: str, scale: float = 1.0, warn: bool = True) -> None:
    """ObjectError (one line starting with `label`) for an object file whose points (m) make an
    object no hand can grasp (:func:`size_problem`); a UnitsWarning (:func:`size_warning`) for one
    that is small enough to be in the wrong unit, when `warn`."""
    smallest, largest = widths(points)
    problem = size_problem(smallest, largest, scale)
    if problem:
        raise ObjectError(f"{label}: {problem}")
    message = size_warning(largest, scale) if warn else None
    if message:
        warnings.warn(f"{label}: {message}", UnitsWarning, stacklevel=3)
