"""Carving the free space the depth views saw out of the column solid (`primitives.free_space`)."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.spatial import ConvexHull, Delaunay

from drake_grasp.funnel.observed_shape import MIN_THICKNESS, observed_shape
from drake_grasp.primitives import free_space
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.free_space import LEVEL, carve, column_intervals
from drake_grasp.primitives.table_top import HeightMap

INTRINSICS = CameraIntrinsics.from_fov_y(320, 240, math.radians(60.0))
CENTRE = np.array([0.55, 0.0])


def _look_at(eye, target) -> tuple[np.ndarray, np.ndarray]:
    """R_WC, p_WC of a camera at `eye` whose optical axis (z) points at `target`."""
    z = np.asarray(target, float) - np.asarray(eye, float)
    z /= np.linalg.norm(z)
    x = np.cross(z, [0.0, 0.0, 1.0])
    x = x / np.linalg.norm(x) if np.linalg.norm(x) > 1e-9 else np.array([0.0, 1.0, 0.0])
    return np.column_stack([x, np.cross(z, x), z]), np.asarray(eye, float)


def _depth_of_scene(R_WC, p_WC, box_half, box_height) -> np.ndarray:
    """The depth image (along the optical axis, m) of the table z = 0 with a box of half-sides
    `box_half` (x, y) and height `box_height` centred on CENTRE: each pixel's ray, cast exactly."""
    v, u = np.mgrid[0:INTRINSICS.height, 0:INTRINSICS.width]
    d_C = np.stack([(u - INTRINSICS.cx) / INTRINSICS.fx, (v - INTRINSICS.cy) / INTRINSICS.fy,
                    np.ones_like(u, float)], axis=-1)  # a ray per pixel, z = 1 in the camera frame
    d_W = d_C @ R_WC.T
    lo = np.array([CENTRE[0] - box_half[0], CENTRE[1] - box_half[1], 0.0])
    hi = np.array([CENTRE[0] + box_half[0], CENTRE[1] + box_half[1], box_height])
    with np.errstate(divide="ignore", invalid="ignore"):
        t0, t1 = (lo - p_WC) / d_W, (hi - p_WC) / d_W
        near = np.nanmax(np.minimum(t0, t1), axis=-1)
        far = np.nanmin(np.maximum(t0, t1), axis=-1)
        table = -p_WC[2] / d_W[..., 2]
    depth = np.where(table > 0, table, np.inf)
    return np.where((near <= far) & (near > 0), np.minimum(near, depth), depth)


def _map_of_box(box_half, box_height) -> HeightMap:
    m = HeightMap.around(CENTRE, 0.003, 64)
    ij = np.indices(m.heights.shape).reshape(2, -1).T
    xy = m.origin + (ij + 0.5) * m.cell
    on = np.all(np.abs(xy - CENTRE) < box_half, axis=1)
    m.heights[:] = np.where(on, box_height, np.nan).reshape(m.heights.shape)
    return m


def test_a_view_from_above_carves_beside_an_object_and_nothing_under_its_top():
    m = _map_of_box((0.03, 0.02), 0.05)
    R, p = _look_at([CENTRE[0], CENTRE[1], 0.45], [CENTRE[0], CENTRE[1], 0.0])
    bits = carve(np.zeros_like(m.heights), m.heights, m.origin, m.cell, 0.0, _depth_of_scene(R, p, (0.03, 0.02), 0.05),
                 INTRINSICS, R, p).astype(np.int64)
    on = np.isfinite(m.heights)
    under_top = (1 << (int(0.05 / LEVEL) - 1)) - 1  # the levels a level or more under the top
    assert np.all(bits[on] & under_top == 0)  # the box's top hides what is under it
    i, j = np.nonzero(on)
    beside = bits[i.min() - 3, j.min() + 2]  # 9 mm off the box's side, within the carved margin
    levels = int(0.05 / LEVEL) + 2
    # Every level judged is free but the first: its centre is nearer the table than the tolerance.
    assert beside == (1 << levels) - 2
    assert bits[0, 0] == 0  # beyond the margin around the seen cells: not judged


def test_a_slanted_view_carves_under_an_overhang_it_looks_under():
    # A slab 2 cm thick whose underside is 3 cm above the table (an overhang: no support is modelled,
    # the depth image is cast against the slab alone) seen from the side at 45 deg.
    half, top = (0.03, 0.02), 0.05
    R, p = _look_at([CENTRE[0] - 0.3, CENTRE[1], 0.3], [CENTRE[0], CENTRE[1], 0.0])
    v, u = np.mgrid[0:INTRINSICS.height, 0:INTRINSICS.width]
    d_W = np.stack([(u - INTRINSICS.cx) / INTRINSICS.fx, (v - INTRINSICS.cy) / INTRINSICS.fy,
                    np.ones_like(u, float)], axis=-1) @ R.T
    lo = np.array([CENTRE[0] - half[0], CENTRE[1] - half[1], 0.03])
    hi = np.array([CENTRE[0] + half[0], CENTRE[1] + half[1], top])
    with np.errstate(divide="ignore", invalid="ignore"):
        t0, t1 = (lo - p) / d_W, (hi - p) / d_W
        near, far = np.nanmax(np.minimum(t0, t1), axis=-1), np.nanmin(np.maximum(t0, t1), axis=-1)
    table = -p[2] / d_W[..., 2]
    depth = np.where((near <= far) & (near > 0), near, table)
    m = _map_of_box(half, top)
    bits = carve(np.zeros_like(m.heights), m.heights, m.origin, m.cell, 0.0, depth, INTRINSICS, R, p)
    lower, floor = column_intervals(bits, np.nan_to_num(m.heights), MIN_THICKNESS)
    near_edge = (np.nonzero(np.isfinite(m.heights))[0].min(), m.heights.shape[1] // 2)
    assert lower[near_edge] == 0.0  # free from the table up, under the slab's near edge
    assert floor[near_edge] == pytest.approx(0.03, abs=LEVEL)  # the slab's underside, within a level


def test_column_intervals_split_a_column_at_the_free_space_it_crosses():
    h = np.array([[0.05, 0.05, 0.04, 0.006]])
    bits = np.array([[sum(1 << k for k in range(2, 6)),  # 1-3 cm free: a base below, a head above
                      0,  # nothing free: the whole column
                      sum(1 << k for k in range(1, 4)),  # 0.5-2 cm free (and so the first level): an overhang
                      1]], float)  # a 6 mm top: no level lies a level under it, nothing is split
    lower, floor = column_intervals(bits, h, MIN_THICKNESS)
    np.testing.assert_allclose(lower, [[2 * LEVEL, 0.05, 0.0, 0.006]])
    np.testing.assert_allclose(floor[0, [0, 2]], [6 * LEVEL, 4 * LEVEL])
    assert np.isnan(floor[0, 1]) and np.isnan(floor[0, 3])


def _mushroom(carved: bool) -> HeightMap:
    """A 6 cm disk 5 cm tall on a 2 cm stem: the views saw free space from the table to 4 cm outside the
    stem (when `carved`)."""
    m = HeightMap.around(CENTRE, 0.003, 128)
    ij = np.indices(m.heights.shape).reshape(2, -1).T
    r = np.hypot(*(m.origin + (ij + 0.5) * m.cell - CENTRE).T).reshape(m.heights.shape)
    m.heights[:] = np.where(r < 0.03, 0.05, np.nan)
    if carved:
        m.carved = np.where((r < 0.03) & (r > 0.01), float(sum(1 << k for k in range(8))), 0.0)
    return m


def _inside(shape, point) -> bool:
    return any(Delaunay(p).find_simplex(point) >= 0 for p in shape.pieces)


def test_the_observed_shape_keeps_the_stem_and_the_cap_and_drops_the_free_space_under_it():
    column, carved = observed_shape(_mushroom(False)), observed_shape(_mushroom(True))
    under_cap = [CENTRE[0] + 0.022, CENTRE[1], 0.015]
    assert _inside(column, under_cap) and not _inside(carved, under_cap)
    assert _inside(carved, [CENTRE[0], CENTRE[1], 0.015])  # the stem
    assert _inside(carved, [CENTRE[0] + 0.022, CENTRE[1], 0.045])  # the cap
    volume = lambda s: sum(ConvexHull(p).volume for p in s.pieces)  # noqa: E731
    assert volume(carved) < 0.8 * volume(column)
    assert carved.carved and not column.carved
    assert carved.height == pytest.approx(column.height)
    assert np.allclose(carved.centre, column.centre)  # the estimate's centre of mass is the map's


def test_carving_is_off_without_it_and_merging_keeps_the_bits():
    first, second = _mushroom(True), _mushroom(False)
    plain, column = observed_shape(dataclasses.replace(first, carved=None)), observed_shape(second)
    assert len(plain.pieces) == len(column.pieces)
    assert all(np.array_equal(a, b) for a, b in zip(plain.pieces, column.pieces))
    merged = second.merged(first)
    np.testing.assert_array_equal(merged.carved, first.carved)
    assert free_space.LEVELS * LEVEL >= 0.25  # 26 cm of levels: the novel objects' largest size


def test_an_exploration_carves_a_pawns_waist_out_of_its_column_solid(tmp_path):
    """Real rendering and simulation: a pawn 10.5 cm tall (a 6 cm base, a 2.4 cm waist, a 4.4 cm head)
    explored with the depth views. The views' carved levels reach the height map, and the observed shape
    drops the space beside the waist under the head, where the column solid fills it, while keeping the
    waist and the head."""
    import trimesh

    from drake_grasp.objects import resolve_object
    from drake_grasp.perception import explore
    from drake_grasp.station import load_scenario
    from test_perception import short_config

    profile = [[0, 0], [0.03, 0], [0.03, 0.01], [0.015, 0.03], [0.012, 0.06], [0.022, 0.08], [0.018, 0.10],
               [0, 0.105]]
    path = tmp_path / "pawn.obj"
    trimesh.creation.revolve(np.array(profile), sections=48).export(path)
    config = short_config()
    config.table_top = load_scenario(scenario_name="funnel").perception.table_top
    seen = {}

    def keep_map(exploration, root):
        views = exploration.primitives.depth_views
        seen["map"] = views.GetOutputPort("height_map").Eval(views.GetMyContextFromRoot(root))

    result = explore(load_scenario(), config, resolve_object(str(path)), on_finish=keep_map)
    height_map = seen["map"]
    assert height_map.carved is not None and np.count_nonzero(height_map.carved) > 100
    carved, column = observed_shape(height_map), observed_shape(dataclasses.replace(height_map, carved=None))
    x, y, z0 = result.X_WO_end.translation() - [0.0, 0.0, 0.0423]  # the pawn's foot, on its axis
    beside_waist = [x + 0.018, y, z0 + 0.05]
    assert _inside(column, beside_waist) and not _inside(carved, beside_waist)
    assert _inside(carved, [x, y, z0 + 0.05]) and _inside(carved, [x + 0.018, y, z0 + 0.09])


def test_a_carved_ball_stays_within_the_piece_budget_and_near_its_volume():
    """A 12 cm ball on the table, carved where it curves in under its equator (every level whose centre
    lies below its lower surface): at most MAX_CARVED_PIECES pieces, and a volume near the ball's, where
    the column solid is a cylinder under the equator."""
    from drake_grasp.funnel.observed_shape import MAX_CARVED_PIECES

    radius = 0.06
    m = HeightMap.around(CENTRE, 0.003, 128)
    ij = np.indices(m.heights.shape).reshape(2, -1).T
    r = np.hypot(*(m.origin + (ij + 0.5) * m.cell - CENTRE).T).reshape(m.heights.shape)
    half_chord = np.sqrt(np.clip(radius**2 - r**2, 0.0, None))
    m.heights[:] = np.where(r < radius, radius + half_chord, np.nan)
    bottom = radius - half_chord  # the ball's lower surface over each cell
    levels = np.arange(free_space.LEVELS)
    free = (levels + 0.5) * LEVEL < bottom[..., None]
    m.carved = np.where(r < radius, (free * (1 << levels)).sum(axis=-1), 0).astype(float)
    carved, column = observed_shape(m), observed_shape(dataclasses.replace(m, carved=None))
    volume = lambda s: sum(ConvexHull(p).volume for p in s.pieces)  # noqa: E731
    ball = 4.0 / 3.0 * math.pi * radius**3
    assert len(carved.pieces) <= MAX_CARVED_PIECES
    assert volume(column) > 1.2 * ball
    assert volume(carved) == pytest.approx(ball, rel=0.2)


def test_a_carved_ring_keeps_its_hole_whatever_its_blocks():
    """A 5.2 cm ring 1.8 cm tall whose tube curves in under it (carved ideally): its hole, seen down to the
    table, stays open; blocks twice as large would close it, so the shape never takes them."""
    from drake_grasp.funnel.observed_shape import _holes, block_factor

    outer, inner, tube = 0.026, 0.012, 0.009
    m = HeightMap.around(CENTRE, 0.003, 128)
    ij = np.indices(m.heights.shape).reshape(2, -1).T
    r = np.hypot(*(m.origin + (ij + 0.5) * m.cell - CENTRE).T).reshape(m.heights.shape)
    across = np.clip(tube**2 - (r - (outer + inner) / 2) ** 2, 0.0, None) ** 0.5  # the tube's half-height
    on = (r > inner) & (r < outer) & (across > 0)
    m.heights[:] = np.where(on, tube + across, np.nan)
    levels = np.arange(free_space.LEVELS)
    free = (levels + 0.5) * LEVEL < (tube - across)[..., None]
    m.carved = np.where(on, (free * (1 << levels)).sum(axis=-1), 0).astype(float)
    f = block_factor(m, np.nan_to_num(m.heights) > 0)
    assert _holes(np.nan_to_num(m.heights) > 0, f) == 1
    shape = observed_shape(m)
    assert not _inside(shape, [CENTRE[0], CENTRE[1], 0.005])  # the hole
    assert _inside(shape, [CENTRE[0] + (outer + inner) / 2, CENTRE[1], tube])  # the tube
