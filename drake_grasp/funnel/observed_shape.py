"""The shape the camera saw: the table-top height map's column solid, as convex pieces a grasp can be closed on.

The table-top estimate (`primitives.table_top`) keeps, per 3 mm cell, the highest surface point the
wrist camera's depth views saw above it; under a resting object there is nothing but the object down
to the table, as far as a camera above can tell, so the object seen is the union of the columns from
the table up to that map (the *column solid*). It is what the funnel search closes the hand on
(`funnel.search`): never the object's file, which a real robot does not have.

For Drake's distance queries the solid must be a union of convex pieces, and few of them: a closing
asks each hand link's distance to every piece about a hundred times, so the cost of one grasp grows
with the pieces (about 0.2 ms per piece on one core). The solid is coarsened and cut into strips:

1. *blocks*: square blocks of `factor` × `factor` cells (a block edge of about a twelfth of the
   object's larger side, at least 6 mm, at most 15 mm); a block is occupied when at least half its
   cells are, and its height is the mean of theirs (the surface through the block's middle);
2. *strips*: each row of blocks (along the world's y) is cut where it is empty; each run of occupied
   blocks is one convex piece, the hull of its columns. The hull fills what dips between the run's
   two ends (a concavity along y); a gap the camera saw down to the table cuts the run (the hole of a
   ring, the space inside a handle, seen from above);
3. *merging*: consecutive rows whose runs span the same blocks at the same heights (within `LEVEL`)
   are one piece (a box lying on a face is one piece; a 9 cm ball fifteen).

Where the depth views saw free space under the object (`HeightMap.carved`: `primitives.free_space`,
docs/design.md §5.4r), a column is at most two intervals (`free_space.column_intervals`): a lower
block from the table and an upper shell over the free space. The blocks are made of each layer apart
(a block takes an interval that most of its object cells have; its mean top and bottom), the upper
shell at least `MIN_THICKNESS` thick, and each layer is cut into strips as above (rows merge only where
their bottoms agree too). So the hand closes on a ball's flank, a pawn's waist and head and a vase's
neck as the camera saw them, not on walls down to the table.

Frame: the observed shape's frame O has the world's axes and its origin at the table-top estimate's
centre (`table_top.estimate`: the solid's horizontal centroid, vertically between its centroid and
half its height), which is also the centre of mass the ε metric uses; the torque scale is the largest
distance from it to the solid's corners (GraspIt!'s "max radius", docs/design.md §4.5).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from pydrake.math import RigidTransform

from scipy.spatial import ConvexHull

from drake_grasp.objects.spec import ObjectError, ObjectSpec, ShapePiece, _cached_hull_obj
from drake_grasp.primitives import free_space, table_top

LEVEL = 0.002  # m: heights are rounded to this step before columns merge
MIN_BLOCK, MAX_BLOCK = 0.006, 0.015  # m: the block edge's bounds
BLOCKS_ACROSS = 12  # blocks along the solid's larger horizontal side (before the bounds)
DENSITY = 200.0  # kg/m³: for the spec's mass only (the quasi-static hand moves nothing)
MIN_THICKNESS = 0.005  # m: a carved column keeps at least this much under its top
BOTTOM_LEVEL = free_space.LEVEL  # m: bottoms within this merge (they are known to a carved level)
# A carved shape has two layers and more strips (a 12 cm ball: 24 against 9); a closing's cost grows with
# the pieces, so rows merge more coarsely (twice, four times LEVEL), then blocks grow (twice, three times)
# while they keep every hole the footprint has at its own blocks, until there are at most this many; if
# none does, the column solid is closed on (a 5 cm ring's hole closed at twice its blocks).
MAX_CARVED_PIECES = 24


@dataclasses.dataclass(frozen=True)
class ObservedShape:
    """The column solid as convex pieces, world frame (m).

    Attributes:
        pieces: each piece's corner points (K × 3; the piece is their convex hull).
        centre: the centre of mass the ε metric uses (module docstring).
        table_z: the table's height, m.
        block: the block edge, m.
        carved: the pieces are the carved columns' layers (the views saw free space under the object and
            the shape kept within its piece budget), not the plain column solid.
    """

    pieces: tuple[np.ndarray, ...]
    centre: np.ndarray
    table_z: float
    block: float
    carved: bool = False

    @property
    def X_WO(self) -> RigidTransform:
        """The observed shape's frame O in the world: the world's axes, at `centre`."""
        return RigidTransform(np.asarray(self.centre, float))

    @property
    def points(self) -> np.ndarray:
        return np.vstack(self.pieces)

    @property
    def max_radius(self) -> float:
        """Largest distance from `centre` to a piece's corner, m: the ε metric's torque scale."""
        return float(np.max(np.linalg.norm(self.points - self.centre, axis=1)))

    @property
    def height(self) -> float:
        """The solid's top above the table, m."""
        return float(np.max(self.points[:, 2]) - self.table_z)

    def as_object_spec(self, name: str = "observed") -> ObjectSpec:
        """The solid as an `ObjectSpec` in its frame O (resting in its nominal pose on the table), for
        `quasistatic.QuasiStaticHand`: one convex piece per strip (its hull, written once to the mesh
        cache). Mass and inertia are nominal (uniform density): quasi-static closing moves nothing,
        and ε takes its centre of mass from `centre`. A piece too thin to be a solid for contact (a
        sliver the carving left: a repaired 6 × 5 × 9 cm box with holes stopped its trial with an error
        there) carries no contact and is left out; ObjectError if none is left."""
        pieces, solids = [], []
        for corners in self.pieces:
            try:
                pieces.append(ShapePiece("convex", (), mesh_path=_cached_hull_obj("observed", corners - self.centre)))
            except ObjectError:
                continue
            solids.append(corners)
        if not pieces:
            raise ObjectError("observed: every piece of the observed shape is too thin to be a solid for contact")
        pieces = tuple(pieces)
        points = self.points - self.centre
        extents = np.ptp(points, axis=0)
        volume = float(sum(ConvexHull(p).volume for p in solids))
        mass = DENSITY * volume
        inertia = mass / 12.0 * np.array([extents[1] ** 2 + extents[2] ** 2, extents[0] ** 2 + extents[2] ** 2,
                                          extents[0] ** 2 + extents[1] ** 2])
        return ObjectSpec(name=name, pieces=pieces, mass=mass, inertia=(*map(float, inertia), 0.0, 0.0, 0.0),
                          volume=volume, extents=tuple(map(float, extents)),
                          rest_height=float(self.centre[2] - self.table_z), rpy_TO=(0.0, 0.0, 0.0),
                          principal_axis=None, max_radius=self.max_radius, paper_class=None, closest_primitive=None)


def block_factor(height_map: table_top.HeightMap, occupied: np.ndarray) -> int:
    """Cells per block edge for a map whose occupied cells are `occupied` (module docstring, step 1)."""
    i, j = np.nonzero(occupied)
    side = max(np.ptp(i), np.ptp(j)) + 1 if len(i) else 1
    block = min(MAX_BLOCK, max(MIN_BLOCK, side * height_map.cell / BLOCKS_ACROSS))
    return max(1, int(round(block / height_map.cell)))


def observed_shape(height_map: table_top.HeightMap, min_cells: int = 3) -> ObservedShape | None:
    """The column solid of a height map as boxes (module docstring); None without an estimate."""
    whole = table_top.estimate(height_map, min_cells)
    if whole is None:
        return None
    h = height_map.filled_heights()
    f = block_factor(height_map, h > 0)
    carved = height_map.carved is not None
    if not carved:
        layers = _layers(h, None, f)
        strips = _layer_strips(layers, LEVEL, BOTTOM_LEVEL)
    else:  # coarser merging, then larger blocks that keep every hole, until the closing's cost is bounded
        holes = _holes(h > 0, f)
        for f_times, coarsening in ((1, 1), (1, 2), (1, 4), (2, 2), (2, 4), (3, 4)):
            if f_times > 1 and _holes(h > 0, f * f_times) < holes:
                continue
            layers = _layers(h, height_map.carved, f * f_times)
            strips = _layer_strips(layers, coarsening * LEVEL, coarsening * BOTTOM_LEVEL)
            if len(strips) <= MAX_CARVED_PIECES:
                break
        else:  # no carved shape within the budget keeps the holes: the column solid
            f_times, layers, carved = 1, _layers(h, None, f), False
            strips = _layer_strips(layers, LEVEL, BOTTOM_LEVEL)
        f *= f_times
    block = f * height_map.cell
    origin = np.asarray(height_map.origin, float)
    pieces = []
    for tops_of, bottoms_of, (i0, i1, j0, j1) in strips:
        ii, jj = np.meshgrid(np.arange(i0, i1), np.arange(j0, j1), indexing="ij")
        tops, bottoms = tops_of[i0:i1, j0:j1].ravel(), bottoms_of[i0:i1, j0:j1].ravel()
        corners = []
        for di in (0, 1):
            for dj in (0, 1):
                x = origin[0] + (ii + di).ravel() * block
                y = origin[1] + (jj + dj).ravel() * block
                for z in (bottoms, tops):
                    corners.append(np.column_stack([x, y, height_map.table_height + z]))
        pieces.append(np.unique(np.vstack(corners), axis=0))
    if not pieces:
        return None
    return ObservedShape(tuple(pieces), np.asarray(whole.centre, float), float(height_map.table_height), block,
                         carved)


def _per_block(values: np.ndarray, present: np.ndarray, f: int) -> tuple[np.ndarray, np.ndarray]:
    """(cells present per block of f × f cells, the mean of `values` over them; 0 where none)."""
    n = values.shape[0]
    m = -(-n // f)  # blocks per side
    padded = np.zeros((2, m * f, m * f))
    padded[0, :n, :n] = np.where(present, values, 0.0)
    padded[1, :n, :n] = present
    sums = padded.reshape(2, m, f, m, f).transpose(0, 1, 3, 2, 4).reshape(2, m, m, f * f).sum(axis=3)
    return sums[1], np.where(sums[1] > 0, sums[0] / np.maximum(sums[1], 1), 0.0)


def _holes(occupied: np.ndarray, f: int) -> int:
    """How many holes the blocks of f × f cells leave in the footprint: empty regions that do not reach
    the map's edge (a ring's, a handle's, seen down to the table)."""
    from scipy import ndimage

    counts, _ = _per_block(occupied.astype(float), occupied, f)
    blocks = counts * 2 >= f * f
    labels, count = ndimage.label(~blocks)
    edge = set(np.unique(np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]])))
    return len(set(range(1, count + 1)) - edge)


def _layers(h: np.ndarray, carved: np.ndarray | None, f: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """The blocks' (tops, bottoms), m above the table, per layer: the column solid's one (bottoms at the
    table), or with `carved` levels the lower blocks' and the upper shells' (module docstring)."""
    counts, heights = _per_block(h, h > 0, f)
    occupied = counts * 2 >= f * f
    heights = np.where(occupied, heights, 0.0)
    if carved is None:
        return [(heights, np.zeros_like(heights))]
    lower, floor = free_space.column_intervals(carved, h, MIN_THICKNESS)
    lower_counts, lower_tops = _per_block(lower, lower > 0, f)
    upper = np.isfinite(floor)
    upper_counts, upper_tops = _per_block(h, upper, f)
    _, upper_floors = _per_block(np.nan_to_num(floor), upper, f)
    has_lower = occupied & (lower_counts * 2 >= counts)
    has_upper = occupied & (upper_counts * 2 >= counts)
    neither = occupied & ~has_lower & ~has_upper  # neither interval in most of its cells: the column
    upper_floors = np.clip(upper_floors, 0.0, np.maximum(upper_tops - MIN_THICKNESS, 0.0))
    return [(np.where(has_lower, lower_tops, np.where(neither, heights, 0.0)), np.zeros_like(heights)),
            (np.where(has_upper, upper_tops, 0.0), np.where(has_upper, upper_floors, 0.0))]


def _layer_strips(layers, level: float, bottom_level: float) -> list:
    """Every layer's strips, as (tops, bottoms, (i0, i1, j0, j1))."""
    return [(tops, bottoms, strip) for tops, bottoms in layers for strip in _strips(tops, bottoms, level, bottom_level)]


def _strips(heights: np.ndarray, bottoms: np.ndarray | None = None, level: float = LEVEL,
            bottom_level: float = BOTTOM_LEVEL) -> list[tuple[int, int, int, int]]:
    """Strips (i0, i1, j0, j1), ends exclusive, covering the blocks of positive height: each row's runs
    of occupied blocks along j, a run merged with the same run of the rows that follow while its heights
    stay within `level` of the first row's (and its `bottoms` within `bottom_level`)."""
    bottoms = np.zeros_like(heights) if bottoms is None else bottoms
    strips = []
    open_runs: dict[tuple[int, int], int] = {}  # (j0, j1) -> first row
    m = heights.shape[0]
    for i in range(m + 1):
        runs = set()
        if i < m:
            occupied = np.concatenate([[False], heights[i] > 0, [False]])
            edges = np.flatnonzero(np.diff(occupied.astype(int)))
            runs = {(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])}
        for run, first in list(open_runs.items()):
            same = (run in runs
                    and np.all(np.abs(heights[i, run[0]:run[1]] - heights[first, run[0]:run[1]]) <= level)
                    and np.all(np.abs(bottoms[i, run[0]:run[1]] - bottoms[first, run[0]:run[1]]) <= bottom_level))
            if not same:
                strips.append((first, i, *run))
                del open_runs[run]
        for run in runs:
            open_runs.setdefault(run, i)
    return sorted(strips)


def describe(shape: ObservedShape) -> str:
    """One line: pieces, block, height, for logs."""
    return f"{len(shape.pieces)} pieces of {shape.block * 1000:.0f} mm blocks, {shape.height * 100:.1f} cm tall"
