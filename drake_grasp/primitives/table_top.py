"""The table-top estimate: an object's centre, axes and size from the wrist camera's depth images.

The paper's primitives measure the object from silhouettes alone (a monocular camera): the centre
from the drift of the silhouette's centroid, the principal axis from the interpretation planes of
the blob's axis, the size from tangent planes fitted by a box-like model. That is exact for the
primitives it models and fragile for shapes it does not (an irregular blob: its axis tilted 14° out of
the table plane, its length 12 cm too long). A table-top scene offers more: the object rests on a
known plane, and a wrist camera that renders depth (the station's RgbdSensor does; so do today's
wrist RGB-D cameras) sees its upper surface from every view of the exploration.

**The height map.** Every depth image's object pixels (the silhouette's mask) are back-projected to
world points (`back_project`); each point raises the cell of a horizontal grid it falls in to its
height (`HeightMap.add`): the map keeps, per cell, the highest surface point seen above it. Views
from the exploration's arcs fill in what one view hides.

**The column solid.** Under a resting object there is nothing but the object down to the table, as
far as a camera above can tell: the estimate takes the object to be the union of the columns from
the table up to the height map (a visual hull for the views from above, made exact in height by
depth). It is exact for prisms lying on a face (plates, T and L shapes, boxes) and over-fills what
hangs over the table (the lower half of a ball, the space under a handle). From it (`estimate`):

* centre: horizontally, the solid's centroid (the centre of mass of a prism; of any shape without
  overhang). Vertically, two models bracket the centre of mass of a resting object: the solid's own
  centroid is right for a shape without overhang and too low under one (15 % of a ball's radius),
  half the top height is right for a shape symmetric about its mid-plane and too high for one whose
  mass sits low (a blob resting on its flat side: 9 mm on a 12 cm one). The estimate takes the middle
  of the two, and half their distance counts in its uncertainty;
* principal axis: the solid's axis of least inertia (its longest direction, in 3-D: a tilted object
  gives a tilted axis);
* horizontal sides: the smallest-area rectangle around the footprint (`min_area_rectangle`), for the
  axes of an object that is not elongated, or of an upright one, whose sides its axis does not name;
* extents: the solid's spans along the estimate's axes, trimmed to the points' own outline (the
  cells' centres stand up to half a cell's diagonal outside a slanted edge: `HeightMap.support`); the
  footprint's rectangle is fitted to that outline too.

**Uncertainty.** The depth views are dealt, alternately, to two half maps; each half gives its own
estimate, and half their difference (with the grid's quantisation, a cell / √12) is the estimate's
spread (`Spread`). It measures what the views disagree on; a bias they share (the over-filled space
under an overhang) it cannot see, which is why the estimate checks (scripts/estimate_check.py)
compare it with the true errors.
"""

import dataclasses
import math

import numpy as np

from drake_grasp.primitives.camera_model import CameraIntrinsics

_UP = np.array([0.0, 0.0, 1.0])

# The footprint's outline is kept as the points' own extremes along this many horizontal directions
# (every 2 degrees): their hull lies within 0.02 % of the points' hull, where the cells' centres stand
# up to half a cell's diagonal beyond it (`HeightMap.support`).
SUPPORT_DIRECTIONS = 180
_DIRECTIONS = np.column_stack([np.cos(np.arange(SUPPORT_DIRECTIONS) * 2.0 * math.pi / SUPPORT_DIRECTIONS),
                               np.sin(np.arange(SUPPORT_DIRECTIONS) * 2.0 * math.pi / SUPPORT_DIRECTIONS)])


def empty_support() -> np.ndarray:
    """A support with no point yet (SUPPORT_DIRECTIONS × 2, NaN)."""
    return np.full((SUPPORT_DIRECTIONS, 2), np.nan)


def raised_support(support: np.ndarray, points_xy: np.ndarray) -> np.ndarray:
    """`support` with each direction's extreme point replaced by one of `points_xy` (N × 2, m) that
    reaches further along it."""
    from scipy.spatial import ConvexHull, QhullError

    support = np.array(support, float, copy=True)
    points = np.asarray(points_xy, float).reshape(-1, 2)
    if len(points) == 0:
        return support
    try:
        points = points[ConvexHull(points).vertices]  # only a hull vertex can be extreme
    except (QhullError, ValueError):
        pass
    reach = points @ _DIRECTIONS.T
    best = np.argmax(reach, axis=0)
    best_reach = reach[best, np.arange(SUPPORT_DIRECTIONS)]
    current = np.nan_to_num(np.einsum("kj,kj->k", support, _DIRECTIONS), nan=-np.inf)
    raise_ = best_reach > current
    support[raise_] = points[best[raise_]]
    return support


@dataclasses.dataclass
class TableTopParams:
    """Choices of the table-top estimate (a scenario's `perception.table_top`; absent: not used).

    Attributes:
        view_period: s between depth views (a multiple of the camera period: the label image is then
            the one the silhouette camera rendered).
        cell: the height map's cell, m.
        cells: the map's cells along x and along y (a square around the first view's object).
        pixel_stride: every `pixel_stride`-th pixel of the mask along u and v is back-projected.
        min_cells: fewer occupied cells than this is no estimate (the object barely seen).
        carve: carve the free space the views saw under the object out of the column solid the funnel
            search closes the hand on (`free_space`; docs/design.md §5.4r); the scenario `funnel` does.
            Nothing else reads it, so it is off by default. The estimate itself (centre, axes, extents)
            is the height map's either way.
    """

    view_period: float = 0.5
    cell: float = 0.003
    cells: int = 128
    pixel_stride: int = 2
    min_cells: int = 12
    carve: bool = False

    def validate(self) -> None:
        if not (math.isfinite(self.view_period) and self.view_period > 0):
            raise ValueError(f"table_top.view_period must be positive, got {self.view_period}")
        if not (math.isfinite(self.cell) and 0.0005 <= self.cell <= 0.02):
            raise ValueError(f"table_top.cell must be in [0.0005, 0.02] m, got {self.cell}")
        if not 16 <= self.cells <= 1024:
            raise ValueError(f"table_top.cells must be in [16, 1024], got {self.cells}")
        if not 1 <= self.pixel_stride <= 16:
            raise ValueError(f"table_top.pixel_stride must be in [1, 16], got {self.pixel_stride}")
        if self.min_cells < 3:
            raise ValueError(f"table_top.min_cells must be at least 3, got {self.min_cells}")


def back_project(depth: np.ndarray, mask: np.ndarray, intrinsics: CameraIntrinsics, R_WC: np.ndarray,
                 p_WC: np.ndarray, stride: int = 1) -> np.ndarray:
    """World points (N×3, m) of the masked pixels with a finite, positive depth.

    Args:
        depth: (H, W) or (H, W, 1) depth along the optical axis, m (Drake's ImageDepth32F: inf beyond
            the range, 0 nearer than it).
        mask: (H, W) boolean object mask.
        intrinsics: the camera's pinhole model (pixel centres at integer u, v).
        R_WC, p_WC: the camera's pose in the world (z along the optical axis).
        stride: every stride-th row and column.
    """
    z = np.asarray(depth, float).reshape(mask.shape)[::stride, ::stride]
    keep = np.asarray(mask, bool)[::stride, ::stride] & np.isfinite(z) & (z > 0)
    v, u = np.nonzero(keep)
    u, v, z = u * stride, v * stride, z[keep]
    p_C = np.column_stack([(u - intrinsics.cx) / intrinsics.fx * z, (v - intrinsics.cy) / intrinsics.fy * z, z])
    return p_C @ np.asarray(R_WC, float).T + np.asarray(p_WC, float)


@dataclasses.dataclass
class HeightMap:
    """The highest surface point seen above each cell of a horizontal grid (world frame; m).

    Attributes:
        origin: (x, y) of the corner of cell (0, 0).
        cell: cell size.
        heights: (n, n) height above the table of the highest point seen in each cell, NaN if none.
        table_height: the table top's z.
        clipped: points fell outside the grid (the object is larger than the map, or moved off it).
        support: the points' own extreme (x, y) along each of SUPPORT_DIRECTIONS horizontal directions
            (NaN where none yet), or None (a map made of heights alone: its cells' centres stand for
            the outline). A cell is raised by any point in it, so along an edge slanted to the grid the
            extreme cells' centres stand up to half a cell's diagonal outside the object (a 2.3 cm
            domino yawed 9 degrees read 2.63 cm); the support points do not.
        carved: (n, n) per cell, the levels the views saw free (`free_space.carve`: bits held in floats),
            or None (nothing carved).
    """

    origin: np.ndarray
    cell: float
    heights: np.ndarray
    table_height: float = 0.0
    clipped: bool = False
    support: np.ndarray | None = None
    carved: np.ndarray | None = None

    @classmethod
    def around(cls, centre_xy, cell: float, cells: int, table_height: float = 0.0) -> "HeightMap":
        """An empty map of cells × cells centred on `centre_xy` (its corner on the cell lattice)."""
        corner = np.floor(np.asarray(centre_xy, float)[:2] / cell - cells / 2.0) * cell
        return cls(corner, cell, np.full((cells, cells), np.nan), table_height, support=empty_support())

    def add(self, points_W: np.ndarray) -> None:
        """Raises each cell to the highest of its points (points below the table top are ignored)."""
        points = np.asarray(points_W, float).reshape(-1, 3)
        h = points[:, 2] - self.table_height
        ij = np.floor((points[:, :2] - self.origin) / self.cell).astype(int)
        n = self.heights.shape[0]
        inside = np.all((ij >= 0) & (ij < n), axis=1)
        self.clipped = self.clipped or bool(np.any(~inside & (h > 0)))
        keep = inside & (h > 0)
        flat = ij[keep, 0] * n + ij[keep, 1]
        top = np.full(n * n, -np.inf)
        np.maximum.at(top, flat, h[keep])
        current = self.heights.reshape(-1)
        raised = top > np.where(np.isnan(current), -np.inf, current)
        current[raised] = top[raised]
        if self.support is not None:
            self.support = raised_support(self.support, points[keep, :2])

    def merged(self, other: "HeightMap") -> "HeightMap":
        """The map of both maps' points (same grid)."""
        heights = np.fmax(self.heights, other.heights)
        support = None
        if self.support is not None and other.support is not None:
            both = np.vstack([self.support, other.support])
            support = raised_support(empty_support(), both[np.all(np.isfinite(both), axis=1)])
        carved = self.carved if other.carved is None else (other.carved if self.carved is None else (
            self.carved.astype(np.int64) | other.carved.astype(np.int64)).astype(float))
        return HeightMap(self.origin.copy(), self.cell, heights, self.table_height, self.clipped or other.clipped,
                         support, carved)

    def outline(self) -> np.ndarray | None:
        """The support's distinct points (K × 2, m), or None where it has fewer than 3 (or none)."""
        if self.support is None:
            return None
        points = self.support[np.all(np.isfinite(self.support), axis=1)]
        points = np.unique(points, axis=0) if len(points) else points
        return points if len(points) >= 3 else None

    def filled_heights(self) -> np.ndarray:
        """The heights (n × n, 0 where empty) after closing the map's small gaps: a cell no point fell in,
        between seen cells, takes the height its neighbours give it (a grey closing over 3 × 3 cells),
        so that sparse views do not leave holes in the solid."""
        from scipy import ndimage

        h = np.nan_to_num(self.heights, nan=0.0)
        return np.where(h > 0, h, ndimage.grey_closing(h, size=(3, 3)))

    def columns(self) -> tuple[np.ndarray, np.ndarray]:
        """(xy (N×2) of the occupied cells' centres, their heights (N)) of `filled_heights`."""
        filled = self.filled_heights()
        i, j = np.nonzero(filled > 0)
        xy = self.origin + (np.column_stack([i, j]) + 0.5) * self.cell
        return xy, filled[i, j]


@dataclasses.dataclass
class TableTopEstimate:
    """What the column solid gives (world frame; m).

    Attributes:
        centre: the solid's horizontal centroid, at half its top height.
        principal_axis: its axis of least inertia (unit; the largest component positive).
        sides: horizontal unit direction of the longer side of the footprint's smallest rectangle.
        extents_axis: spans along (principal axis, horizontal across it, their cross product).
        extents_sides: spans along (sides, horizontal across them, up).
        height: the highest point's height above the table.
        cells: occupied cells.
        centre_bracket: half the distance between the two vertical centres (the solid's centroid and
            half the height), m: the vertical centre's model uncertainty.
        edge_rise: how much the map rises just inside the footprint's edge (`edge_rise`), m: about 0
            for vertical sides (a box, a mug, a polycube), a centimetre for a round solid's.
        grip_width: the footprint's width across `grip_axis` where the box grasp's fingers close
            (`grip_width`), m.
        grip_axis: the horizontal unit direction the grip is measured along: the principal axis, or
            the footprint's sides where the principal axis stands within 30° of the vertical.
        grip_reach: how far the footprint reaches across `grip_axis` from the centre, either way, in
            the same band (`grip_reach`), m.
    """

    centre: np.ndarray
    principal_axis: np.ndarray
    sides: np.ndarray
    extents_axis: np.ndarray
    extents_sides: np.ndarray
    height: float
    cells: int
    centre_bracket: float = 0.0
    edge_rise: float = math.nan
    grip_width: float = math.nan
    grip_axis: np.ndarray | None = None
    grip_reach: float = math.nan


# How far inside the footprint's edge the edge rise looks, in cells (3 mm: 6 mm in).
EDGE_REACH = 2


def edge_rise(heights: np.ndarray, reach: int = EDGE_REACH) -> float:
    """How much the height map rises just inside the footprint's edge, m: over the footprint's boundary
    cells (an occupied cell with an empty one of its four neighbours), the median of the highest cell
    within `reach` cells of it less its own height. NaN with no occupied cell.

    Seen from above, a side that stands vertical ends in a top that is level at the edge (a box, a mug's
    rim, each tier of a polycube: 0-1 mm over 6 mm); a round side curves away below the top (a ball,
    fruit, a scan: 7-17 mm for solids 3-10 cm tall). It says whether the widest part of the object is at
    the top of its sides or lower down, where a grasp from above cannot see it (`primitives.round_sides`).
    The median keeps a handle or a step from deciding it."""
    from scipy import ndimage

    h = np.asarray(heights, float)
    occupied = h > 0
    if not np.any(occupied):
        return math.nan
    boundary = occupied & ~ndimage.binary_erosion(occupied)
    near = ndimage.maximum_filter(h, size=2 * reach + 1, mode="constant", cval=0.0)
    return float(np.median((near - h)[boundary]))


# Half the length, along the principal axis, of the band the box grasp's fingers close in: F3 on the
# centre line, F1 and F2's 23 mm pads from 13.5 to 36.5 mm either side of it (`hand.AW`, `hand.DISTAL_WIDTH`).
GRIP_BAND = 0.0365  # m


def grip_offsets(xy: np.ndarray, centre_xy, axis, band: float = GRIP_BAND) -> np.ndarray | None:
    """The signed distances (m) across the horizontal `axis` from `centre_xy` of the occupied cells'
    centres (`xy`, N × 2, m) that lie within `band` of it along the axis: where fingers closing across
    the axis at the centre meet the footprint. None without such a cell or a horizontal axis."""
    axis = np.asarray(axis, float)[:2]
    if np.linalg.norm(axis) < 1e-9 or len(xy) == 0:
        return None
    axis = axis / np.linalg.norm(axis)
    d = np.asarray(xy, float) - np.asarray(centre_xy, float)[:2]
    near = np.abs(d @ axis) <= band
    if not np.any(near):
        return None
    return d[near] @ np.array([-axis[1], axis[0]])


def grip_width(xy: np.ndarray, centre_xy, axis, band: float = GRIP_BAND) -> float:
    """The footprint's width across the horizontal `axis` among the occupied cells (centres `xy`, N × 2,
    m) within `band` of `centre_xy` along it, m: the span of their centres (an edge lies anywhere in its
    boundary cell, on average at the centre, so the centres' span is the unbiased one, as for the column
    ends). NaN without such a cell or a horizontal axis.

    It is the width the box grasp's fingers meet when they close across the axis at the centre: a
    hammer's handle (2-3 cm), not its head's length, which the footprint's own spans give
    (`primitives.narrow`)."""
    offsets = grip_offsets(xy, centre_xy, axis, band)
    return math.nan if offsets is None else float(np.ptp(offsets))


def grip_reach(xy: np.ndarray, centre_xy, axis, band: float = GRIP_BAND) -> float:
    """How far the footprint reaches across the horizontal `axis` from `centre_xy` within `band` of it
    along the axis, either way, m: the largest distance of an occupied cell's centre (`grip_offsets`;
    unbiased as `grip_width` is). NaN without such a cell or a horizontal axis.

    It is where fingertips closing across the axis at the centre must land outside of: on a hammer the
    handle's half width (1-1.5 cm) rather than half its head's length. Where the centroid is off the
    footprint rectangle's middle (a T, an L) it can exceed half the footprint's span; the flower grasp
    takes it only where it is the smaller (`grasps.ObjectEstimate.reach_across`)."""
    offsets = grip_offsets(xy, centre_xy, axis, band)
    return math.nan if offsets is None else float(np.max(np.abs(offsets)))


def min_area_rectangle(points_xy: np.ndarray) -> tuple[float, np.ndarray]:
    """(angle, (length, width)): the smallest-area rectangle around 2-D points, its longer side's
    direction angle (rad, in [0, π)) and its sides (length ≥ width). One side of it lies along an edge
    of the points' convex hull (qhull), so only those directions are tried."""
    from scipy.spatial import ConvexHull, QhullError

    points = np.asarray(points_xy, float)
    try:
        hull = points[ConvexHull(points).vertices]
    except (QhullError, ValueError):  # collinear or too few: the points' own span
        hull = points
    edges = np.diff(np.vstack([hull, hull[:1]]), axis=0)
    angles = np.unique(np.mod(np.arctan2(edges[:, 1], edges[:, 0]), math.pi / 2.0))
    best = None
    for angle in angles if len(angles) else [0.0]:
        u = np.array([math.cos(angle), math.sin(angle)])
        v = np.array([-u[1], u[0]])
        spans = np.ptp(hull @ u), np.ptp(hull @ v)
        if best is None or spans[0] * spans[1] < best[1][0] * best[1][1] - 1e-15:
            best = (angle, spans)
    angle, (su, sv) = best
    if sv > su:
        angle, (su, sv) = angle + math.pi / 2.0, (sv, su)
    return float(np.mod(angle, math.pi)), np.array([su, sv])


def _spans(points: np.ndarray, directions) -> np.ndarray:
    return np.array([np.ptp(points @ d) for d in directions])


def estimate(height_map: HeightMap, min_cells: int = 3) -> TableTopEstimate | None:
    """The column solid's estimate (see the module docstring), or None below `min_cells` cells."""
    xy, h = height_map.columns()
    if len(h) < min_cells:
        return None
    cell = height_map.cell
    weights = h / np.sum(h)  # each column's share of the volume
    centroid_xy = weights @ xy
    top = float(np.max(h))
    # Second moments of the columns (uniform density): x, y per column; z uniform on [0, h].
    d = xy - centroid_xy
    z_mean = float(weights @ (h / 2.0))
    cov = np.zeros((3, 3))
    cov[:2, :2] = (weights[:, None] * d).T @ d + np.eye(2) * cell**2 / 12.0
    cov[:2, 2] = cov[2, :2] = weights @ (d * (h / 2.0 - z_mean)[:, None])
    cov[2, 2] = float(weights @ (h**2 / 3.0)) - z_mean**2
    _, vectors = np.linalg.eigh(cov)
    axis = vectors[:, 2]
    axis = axis * np.sign(axis[np.argmax(np.abs(axis))])
    outline = height_map.outline()
    angle, _ = min_area_rectangle(xy if outline is None else outline)
    sides = np.array([math.cos(angle), math.sin(angle), 0.0])
    ends = _column_ends(xy, h, height_map.table_height)
    across = np.cross(_UP, axis)
    across = across / np.linalg.norm(across) if np.linalg.norm(across) > 1e-9 else np.cross(_UP, sides)
    axis_frame = (axis, across, np.cross(axis, across))
    side_frame = (sides, np.cross(_UP, sides), _UP)
    grip_axis = np.append(axis[:2], 0.0) if np.linalg.norm(axis[:2]) > 0.5 else sides
    grip_axis = grip_axis / np.linalg.norm(grip_axis)
    z_low, z_high = sorted((z_mean, top / 2.0))  # the solid's centroid, half the height (above the table)
    centre = np.array([centroid_xy[0], centroid_xy[1], height_map.table_height + 0.5 * (z_low + z_high)])
    return TableTopEstimate(
        centre=centre, principal_axis=axis, sides=sides,
        extents_axis=_outline_spans(ends, axis_frame, xy, outline),
        extents_sides=_outline_spans(ends, side_frame, xy, outline), height=top, cells=len(h),
        centre_bracket=0.5 * (z_high - z_low), edge_rise=edge_rise(height_map.filled_heights()),
        grip_width=grip_width(xy, centroid_xy, grip_axis), grip_axis=grip_axis,
        grip_reach=grip_reach(xy, centroid_xy, grip_axis))


def _outline_spans(ends: np.ndarray, directions, xy: np.ndarray, outline: np.ndarray | None) -> np.ndarray:
    """The column ends' spans along `directions`, each less what the cells' footprint stands beyond the
    points' outline along its horizontal part, both ways (`HeightMap.support`; more where the cells'
    centres fall short of it; none without an outline). For a horizontal direction this is the
    outline's own span; for a tilted one, right to first order in its horizontal part."""
    spans = _spans(ends, directions)
    if outline is None:
        return spans
    trimmed = []
    for span, d in zip(spans, directions):
        horizontal = np.asarray(d, float)[:2]
        length = float(np.linalg.norm(horizontal))
        if length < 1e-9:
            trimmed.append(span)
            continue
        u = horizontal / length
        beyond = sum(float(np.max(xy @ v)) - float(np.max(outline @ v)) for v in (u, -u))
        trimmed.append(max(span - length * beyond, 0.0))
    return np.array(trimmed)


def _column_ends(xy: np.ndarray, h: np.ndarray, table_height: float) -> np.ndarray:
    """Each column's axis ends (the cell's centre on the table and at its height), 2N × 3.

    Spans of the cells' centres, not of their corners: an edge of the object lies anywhere in its
    boundary cell, on average at the centre, so the centres' span is the unbiased one (the corners'
    is a cell too long)."""
    bottom = np.column_stack([xy, np.full(len(xy), table_height)])
    return np.vstack([bottom, np.column_stack([xy, table_height + h])])


@dataclasses.dataclass
class Spread:
    """How far two halves of the views disagree (half their difference, plus quantisation; m, deg).

    Attributes:
        centre: distance between the halves' centres / 2, m.
        axis_deg: angle between their principal axes / 2, degrees.
        extents: |difference of their spans along the principal axis's frame| / 2, m (3).
    """

    centre: float
    axis_deg: float
    extents: np.ndarray


def spread(first: TableTopEstimate | None, second: TableTopEstimate | None, cell: float,
           centre_bracket: float = 0.0) -> Spread | None:
    """The halves' disagreement (None if either half has no estimate); the grid's quantisation, a
    cell / √12 per coordinate, and the vertical centre's model bracket (`TableTopEstimate.centre_bracket`,
    m) are added in quadrature."""
    if first is None or second is None:
        return None
    q = cell / math.sqrt(12.0)
    centre = math.sqrt((0.5 * float(np.linalg.norm(first.centre - second.centre))) ** 2 + 3.0 * q * q
                       + centre_bracket ** 2)
    cosine = min(1.0, abs(float(first.principal_axis @ second.principal_axis)))
    extents = np.hypot(0.5 * np.abs(first.extents_axis - second.extents_axis), q)
    return Spread(centre, 0.5 * math.degrees(math.acos(cosine)), extents)
