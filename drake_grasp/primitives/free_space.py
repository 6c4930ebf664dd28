"""The free space the depth views saw under an object: what carves the column solid's overhangs away.

The table-top estimate's column solid (`table_top`) fills every column from the table up to the
highest point seen above it. That is all a camera straight above can tell, but the exploration's
views are not all straight above: its arcs look down at 57-90° from the table, and a ray that passes
under a ball's bulge, a pawn's head or a vase's lip before it meets the table or the object's far
side shows that the space it crossed is empty. Space carving (the depth image's version of a visual
hull) keeps that knowledge: a point of space is *free* when some view's ray through it ran on past
it, its depth in that view more than `TOLERANCE` short of the depth the camera measured at its pixel.

The map keeps it per height-map cell as a column of `LEVELS` levels of `LEVEL` m from the table up,
one bit each (a level is carved when its centre was seen free), in a float that holds the integer
exactly (52 bits). A column is then the object as at most two intervals (`column_intervals`): a lower
block from the table up to the first carved level, and an upper shell over the highest carved level
(a ball's flank over the free space beside its foot; a pawn's head over its waist, above its base).
A level no view saw stays solid: carving can only remove what a view saw through, never add, and what
it removes is the over-fill the column solid knows it has (docs/design.md §5.4r).

Measured offline on 30 real object files (the 13 Dex-Net adversarial parts and 17 of its KIT scans,
the exploration's own 26 depth views at its nominal placement, 4 mm voxels): the column solid
over-fills the object by 16-51 % of its volume; carving removes 69 % of that over-fill, and carves
4.4 % of the object's own volume (voxels whose centre lies within a voxel of its surface).
"""

from __future__ import annotations

import numpy as np

from drake_grasp.primitives.camera_model import CameraIntrinsics

LEVEL = 0.005  # m: the height of one carved level
LEVELS = 52  # levels per column (a float64 holds 52 bits exactly): 26 cm above the table
TOLERANCE = 0.004  # m: a level is free when a ray ran on at least this much past its centre
MARGIN_CELLS = 6  # cells carved around the occupied cells' bounding box (views fill the map's edge in)
_NEAREST = 0.02  # m: levels nearer the camera than its range are not judged


def carve(bits: np.ndarray, heights: np.ndarray, origin, cell: float, table_height: float, depth: np.ndarray,
          intrinsics: CameraIntrinsics, R_WC: np.ndarray, p_WC: np.ndarray) -> np.ndarray:
    """The carved bits (n × n floats holding integers) after one depth view.

    Only the levels of the columns around the cells seen so far (`heights`, NaN where none;
    `MARGIN_CELLS` around their bounding box) and up to one level over the highest are judged: the rest
    cannot hold the object's underside.

    Args:
        bits: (n, n) carved levels so far, bit k for level k (from the table up).
        heights: (n, n) the height map's heights above the table, m (NaN where nothing was seen).
        origin, cell, table_height: the height map's grid (m).
        depth: (H, W) or (H, W, 1) depth along the optical axis, m (inf beyond the range, 0 nearer).
        intrinsics: the camera's pinhole model.
        R_WC, p_WC: the camera's pose in the world (z along the optical axis).
    """
    bits = np.asarray(bits, float)
    seen = np.isfinite(heights) & (heights > 0)
    if not np.any(seen):
        return bits
    n = bits.shape[0]
    i, j = np.nonzero(seen)
    i0, i1 = max(0, i.min() - MARGIN_CELLS), min(n, i.max() + MARGIN_CELLS + 1)
    j0, j1 = max(0, j.min() - MARGIN_CELLS), min(n, j.max() + MARGIN_CELLS + 1)
    levels = min(LEVELS, int(np.nanmax(heights[seen]) / LEVEL) + 2)
    ii, jj, kk = np.meshgrid(np.arange(i0, i1), np.arange(j0, j1), np.arange(levels), indexing="ij")
    ii, jj, kk = ii.ravel(), jj.ravel(), kk.ravel()
    origin = np.asarray(origin, float)
    points = np.column_stack([origin[0] + (ii + 0.5) * cell, origin[1] + (jj + 0.5) * cell,
                              table_height + (kk + 0.5) * LEVEL])
    p_C = (points - np.asarray(p_WC, float)) @ np.asarray(R_WC, float)
    z = p_C[:, 2]
    ahead = z > _NEAREST
    safe_z = np.where(ahead, z, 1.0)
    u = np.round(p_C[:, 0] / safe_z * intrinsics.fx + intrinsics.cx).astype(int)
    v = np.round(p_C[:, 1] / safe_z * intrinsics.fy + intrinsics.cy).astype(int)
    inside = ahead & (u >= 0) & (u < intrinsics.width) & (v >= 0) & (v < intrinsics.height)
    image = np.asarray(depth, float).reshape(intrinsics.height, intrinsics.width)
    measured = np.zeros(len(points))
    measured[inside] = image[v[inside], u[inside]]  # inf: the ray met nothing in range (free)
    free = (inside & (measured > z + TOLERANCE)).reshape(i1 - i0, j1 - j0, levels)
    carved = np.zeros((n, n), np.int64)
    carved[i0:i1, j0:j1] = free @ np.left_shift(np.int64(1), np.arange(levels, dtype=np.int64))
    return (bits.astype(np.int64) | carved).astype(float)


def column_intervals(bits: np.ndarray, heights: np.ndarray, min_thickness: float) -> tuple[np.ndarray, np.ndarray]:
    """The object in each column as at most two intervals, m above the table: a *lower block* from the
    table up to the first carved level, and an *upper shell* from just above the highest carved level
    below the top up to the top (what hangs over the free space: a ball's flank, a pawn's head).

    Returns (lower, floor), each (n, n): `lower` the lower block's top (the whole column's height
    where nothing under the top was carved; 0 where the free space starts at the table), `floor` the
    upper shell's bottom (NaN where nothing was carved), at least `min_thickness` under the top. A
    solid seen between two free gaps is left out: the views would have to see through a column twice.
    """
    bits = np.nan_to_num(np.asarray(bits, float), nan=0.0).astype(np.int64)
    h = np.nan_to_num(np.asarray(heights, float), nan=0.0)
    # Levels at least a level under the top: at an edge, a pixel's rounding lets a ray past the top's rim.
    below = np.clip(np.floor(h / LEVEL).astype(int) - 1, 0, LEVELS)
    # The first level's centre is closer to the table than TOLERANCE: no ray is seen past it by that much,
    # so it counts as free where the level above it is.
    bits = bits | ((bits >> 1) & 1)
    lowest = np.full(h.shape, -1)
    highest = np.full(h.shape, -1)
    for k in range(LEVELS):
        carved = (((bits >> k) & 1) == 1) & (k < below)
        lowest = np.where(carved & (lowest < 0), k, lowest)
        highest = np.where(carved, k, highest)
    gap = lowest >= 0
    lower = np.where(gap, lowest * LEVEL, h)
    floor = np.where(gap, np.minimum((highest + 1) * LEVEL, h - min_thickness), np.nan)
    return np.where(h > 0, lower, 0.0), np.where(h > 0, floor, np.nan)
