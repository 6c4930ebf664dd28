"""The table-top estimate's pure functions: back-projection, the height map, the column solid."""

import dataclasses
import math

import numpy as np
import pytest

from drake_grasp.primitives import table_top
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.depth_views import TableTopVector
from drake_grasp.primitives.estimate import ExplorationPhase, gather_estimate


def _surface_points(top_z, xs, ys):
    """A grid of points of a height function top_z(x, y) (NaN: no surface there)."""
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    Z = top_z(X, Y)
    keep = np.isfinite(Z)
    return np.column_stack([X[keep], Y[keep], Z[keep]])


def _map_of(points, cell=0.003, centre=(0.5, 0.0)):
    height_map = table_top.HeightMap.around(centre, cell, 128)
    height_map.add(points)
    return height_map


def _rotated_box_top(centre, length, width, height, yaw):
    c, s = math.cos(yaw), math.sin(yaw)

    def top(X, Y):
        u = c * (X - centre[0]) + s * (Y - centre[1])
        v = -s * (X - centre[0]) + c * (Y - centre[1])
        inside = (np.abs(u) <= length / 2) & (np.abs(v) <= width / 2)
        return np.where(inside, height, np.nan)

    return top


def test_back_projection_of_a_plane_seen_from_above():
    intrinsics = CameraIntrinsics.from_fov_y(64, 48, math.radians(60))
    R_WC = np.diag([1.0, -1.0, -1.0])  # looking straight down
    p_WC = np.array([0.5, 0.0, 0.4])
    depth = np.full((48, 64), 0.3)  # a plane 0.1 m above the table
    mask = np.zeros((48, 64), bool)
    mask[10:30, 20:40] = True
    points = table_top.back_project(depth, mask, intrinsics, R_WC, p_WC)
    assert points.shape == (400, 3)
    np.testing.assert_allclose(points[:, 2], 0.1, atol=1e-12)
    # The pixel at the principal point lies straight below the camera.
    centre = table_top.back_project(depth, _at(48, 64, 24, 32), intrinsics, R_WC, p_WC)
    assert np.linalg.norm(centre[0, :2] - p_WC[:2]) < 0.3 / intrinsics.fx  # within a pixel
    # Masked-out, infinite and zero depths give no point.
    depth[12, 22], depth[13, 23] = np.inf, 0.0
    assert len(table_top.back_project(depth, mask, intrinsics, R_WC, p_WC)) == 398


def _at(h, w, v, u):
    mask = np.zeros((h, w), bool)
    mask[v, u] = True
    return mask


def test_a_lying_box_gives_its_centre_axis_and_size():
    yaw = math.radians(30)
    top = _rotated_box_top((0.52, 0.01), 0.12, 0.05, 0.04, yaw)
    points = _surface_points(top, np.arange(0.40, 0.65, 0.001), np.arange(-0.12, 0.13, 0.001))
    estimate = table_top.estimate(_map_of(points))
    np.testing.assert_allclose(estimate.centre, [0.52, 0.01, 0.02], atol=0.002)
    axis = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    assert math.degrees(math.acos(abs(estimate.principal_axis @ axis))) < 2.0
    assert math.degrees(math.acos(abs(estimate.sides @ axis))) < 2.0
    np.testing.assert_allclose(estimate.extents_axis, [0.12, 0.05, 0.04], atol=0.004)
    np.testing.assert_allclose(estimate.extents_sides, [0.12, 0.05, 0.04], atol=0.004)


def test_a_flat_T_has_its_centroid_not_its_box_centre():
    # A T of two 2 cm thick bars: the stem 10 x 2 cm along x, the bar 2 x 8 cm across its end.
    def top(X, Y):
        stem = (np.abs(Y) <= 0.01) & (X >= 0.45) & (X <= 0.55)
        bar = (np.abs(Y) <= 0.04) & (X >= 0.55) & (X <= 0.57)
        return np.where(stem | bar, 0.02, np.nan)

    points = _surface_points(top, np.arange(0.40, 0.60, 0.001), np.arange(-0.06, 0.06, 0.001))
    estimate = table_top.estimate(_map_of(points))
    # Areas 20 cm^2 at x = 0.50 and 16 cm^2 at x = 0.56: the centroid at x = 0.5267.
    assert estimate.centre[0] == pytest.approx(0.5267, abs=0.002)
    assert estimate.centre[1] == pytest.approx(0.0, abs=0.002)
    assert estimate.height == pytest.approx(0.02, abs=1e-9)


def test_a_tilted_rod_gives_a_tilted_axis():
    # A rod resting on something at one end: its top rises 1 cm per 10 cm (5.7 deg).
    def top(X, Y):
        inside = (np.abs(Y) <= 0.01) & (X >= 0.45) & (X <= 0.60)
        return np.where(inside, 0.02 + 0.1 * (X - 0.45), np.nan)

    points = _surface_points(top, np.arange(0.40, 0.65, 0.001), np.arange(-0.03, 0.03, 0.001))
    estimate = table_top.estimate(_map_of(points))
    tilt = math.degrees(math.asin(abs(estimate.principal_axis[2])))
    assert 2.0 < tilt < 10.0


@pytest.mark.parametrize("yaw_deg", [0.0, 9.0, 20.0, 45.0])
def test_the_extents_are_the_points_not_the_cells_they_fell_in(yaw_deg):
    # A domino 5.07 x 2.28 cm seen at 0.5 mm: along an edge slanted to the 3 mm grid, the cells' centres
    # stand up to half a cell's diagonal outside it (about +2 mm per span at 9-20 degrees); the
    # points' outline does not, so the spans come within the points' own spacing.
    yaw = math.radians(yaw_deg)
    top = _rotated_box_top((0.5, 0.003), 0.0507, 0.0228, 0.011, yaw)
    points = _surface_points(top, np.arange(0.46, 0.54, 0.0005), np.arange(-0.04, 0.04, 0.0005))
    height_map = _map_of(points)
    estimate = table_top.estimate(height_map)
    np.testing.assert_allclose(estimate.extents_sides[:2], [0.0507, 0.0228], atol=0.0008)
    np.testing.assert_allclose(estimate.extents_axis[:2], [0.0507, 0.0228], atol=0.0008)
    cells_only = table_top.estimate(dataclasses.replace(height_map, support=None))  # the cells' centres
    if yaw_deg in (9.0, 20.0):
        assert np.all(cells_only.extents_sides[:2] - np.array([0.0507, 0.0228]) > 0.0012)


def test_halves_merge_their_outlines():
    top = _rotated_box_top((0.5, 0.0), 0.10, 0.04, 0.03, math.radians(15))
    points = _surface_points(top, np.arange(0.43, 0.57, 0.0005), np.arange(-0.05, 0.05, 0.0005))
    left, right = points[points[:, 0] < 0.5], points[points[:, 0] >= 0.5]
    first, second = _map_of(left), _map_of(right)
    both = first.merged(second)
    whole = _map_of(points)
    np.testing.assert_allclose(table_top.estimate(both).extents_sides, table_top.estimate(whole).extents_sides,
                               atol=1e-9)
    assert table_top.HeightMap(np.zeros(2), 0.003, np.full((4, 4), np.nan)).outline() is None


def test_gaps_between_views_are_closed_and_the_map_knows_when_it_overflows():
    top = _rotated_box_top((0.5, 0.0), 0.08, 0.08, 0.05, 0.0)
    sparse = _surface_points(top, np.arange(0.46, 0.54, 0.004), np.arange(-0.04, 0.04, 0.004))
    height_map = _map_of(sparse)
    xy, h = height_map.columns()
    assert np.sum(~np.isnan(height_map.heights)) < len(h)  # holes filled
    assert not height_map.clipped
    height_map.add(np.array([[2.0, 0.0, 0.05]]))
    assert height_map.clipped


def test_too_few_cells_give_no_estimate_and_the_halves_give_a_spread():
    assert table_top.estimate(_map_of(np.array([[0.5, 0.0, 0.01]])), min_cells=12) is None
    top = _rotated_box_top((0.5, 0.0), 0.10, 0.04, 0.03, 0.0)
    a = table_top.estimate(_map_of(_surface_points(top, np.arange(0.44, 0.56, 0.002), np.arange(-0.03, 0.03, 0.002))))
    b = table_top.estimate(_map_of(_surface_points(top, np.arange(0.44, 0.56, 0.002) + 0.004,
                                                   np.arange(-0.03, 0.03, 0.002))))
    spread = table_top.spread(a, b, 0.003)
    assert spread.centre == pytest.approx(math.hypot(0.002, 0.003 / 2), abs=0.001)
    assert table_top.spread(a, None, 0.003) is None


def test_the_flat_resemblance_is_thin_or_small():
    from drake_grasp.primitives.flat import flat_resemblance

    plate, evidence = flat_resemblance(0.008, np.array([0.10, 0.07, 0.008]))
    assert plate > 0.95 and evidence["thin"] == plate
    ball, evidence = flat_resemblance(0.05, np.array([0.05, 0.05, 0.05]))
    assert ball > 0.9 and evidence["thin"] < 0.01
    sponge, _ = flat_resemblance(0.035, np.array([0.11, 0.07, 0.035]))  # the paper's: not flat
    apple, _ = flat_resemblance(0.072, np.array([0.075, 0.075, 0.072]))
    assert sponge < 0.1 and apple < 0.4
    assert math.isnan(flat_resemblance(math.nan, np.zeros(3))[0])


def test_min_area_rectangle_of_a_rotated_rectangle():
    angle = math.radians(20)
    corners = np.array([[0, 0], [0.1, 0], [0.1, 0.03], [0, 0.03]])
    R = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    found, spans = table_top.min_area_rectangle(corners @ R.T)
    assert found == pytest.approx(angle, abs=1e-9)
    np.testing.assert_allclose(spans, [0.1, 0.03], atol=1e-12)


def test_the_estimate_takes_the_table_top_centre_axes_and_extents():
    top = _rotated_box_top((0.52, 0.01), 0.12, 0.05, 0.04, math.radians(30))
    t = table_top.estimate(_map_of(_surface_points(top, np.arange(0.40, 0.65, 0.001), np.arange(-0.12, 0.13, 0.001))))
    vector = TableTopVector(t, table_top.Spread(0.001, 0.5, np.full(3, 0.001)), False, 24, 0.002)
    again = TableTopVector.from_vector(vector.to_vector())
    np.testing.assert_allclose(again.estimate.centre, t.centre)
    assert again.views == 24 and again.spread.axis_deg == 0.5 and again.table_height == 0.002
    args = (ExplorationPhase.DONE, np.array([0.5, 0.0, 0.02]), np.array([0.5, 0.0, 0.35]),
            np.array([1.0, 0.0, 0.0]), np.array([1.0, 1.5, 0.0]), np.array([0.1, 0.06, 0.05]),
            {"sphere": 0.1, "cylinder": 0.2, "box": 0.9}, np.zeros(9), np.array([1.0, 0.0, 0.0]))
    silhouettes = gather_estimate(*args)
    assert silhouettes.table_top is None and "table_top" not in silhouettes.to_dict()
    estimate = gather_estimate(*args, again)
    np.testing.assert_allclose(estimate.centre, t.centre)
    assert abs(estimate.principal_axis @ t.principal_axis) > 0.999  # elongated: the solid's axis
    np.testing.assert_allclose(estimate.extents, t.extents_axis)
    assert estimate.table_top["views"] == 24 and estimate.table_top["table_z"] == 0.002
    assert estimate.as_grasp_estimate().table_z == 0.002 and silhouettes.as_grasp_estimate().table_z is None
    np.testing.assert_allclose(estimate.table_top["silhouettes"]["centre"], [0.5, 0.0, 0.02])
    assert {s: estimate.resemblances[s] for s in silhouettes.resemblances} == silhouettes.resemblances
    # 4 cm tall and 12 cm long: neither thin nor small, so the flat resemblance stays low.
    assert estimate.resemblances["flat"] < 0.1 and estimate.best_shape == "box"


def test_a_short_exploration_with_depth_views_places_an_L_by_its_mass(tmp_path):
    """Real rendering and simulation: an L lying flat (2 cm thick) explored with the table-top
    estimate. The depth views leave the exploration as it was (same resemblances and silhouettes'
    estimate as without them), and the table-top centre is within 5 mm of the centre of mass, where
    the silhouettes' box-like model puts it at the L's bounding-box centre (about 2 cm away)."""
    import dataclasses as dc

    import trimesh

    from drake_grasp.objects import resolve_object
    from drake_grasp.perception import explore
    from drake_grasp.perception.evaluation import ground_truth
    from drake_grasp.station import load_scenario
    from test_perception import short_config

    bars = [trimesh.creation.box([0.12, 0.03, 0.02]), trimesh.creation.box([0.03, 0.09, 0.02])]
    bars[0].apply_translation([0.0, -0.03, 0.0])
    bars[1].apply_translation([-0.045, 0.0, 0.0])
    path = tmp_path / "L.obj"
    trimesh.boolean.union(bars).export(path)
    spec = resolve_object(str(path))
    scenario = load_scenario()
    plain = explore(scenario, short_config(), spec).estimate
    config = short_config()
    config.table_top = load_scenario(scenario_name="table_top").perception.table_top
    result = explore(scenario, config, spec)
    estimate = result.estimate
    assert {s: estimate.resemblances[s] for s in plain.resemblances} == plain.resemblances
    assert estimate.resemblances["flat"] > 0.5  # 2 cm thick: thin (the step is at 2.5 cm)
    own = estimate.table_top["silhouettes"]
    np.testing.assert_allclose(own["centre"], plain.centre)
    truth = ground_truth(spec, result.X_WO_end)
    assert np.linalg.norm(estimate.centre - truth.centre) < 0.005
    assert np.linalg.norm(np.asarray(own["centre"]) - truth.centre) > np.linalg.norm(estimate.centre - truth.centre)
    assert estimate.extents[2] == pytest.approx(0.02, abs=0.004)  # not elongated: (sides, across, up)
    u = estimate.table_top["uncertainty"]
    assert 0 < u["centre"] < 0.01 and estimate.table_top["views"] >= 8
    assert dc.asdict(config.table_top)["cell"] == 0.003


def _ball_top(centre, radius):
    def top(X, Y):
        r2 = (X - centre[0]) ** 2 + (Y - centre[1]) ** 2
        return np.where(r2 <= radius**2, radius + np.sqrt(np.maximum(radius**2 - r2, 0.0)), np.nan)

    return top


def test_the_edge_rise_tells_vertical_sides_from_round_ones():
    xs, ys = np.arange(0.40, 0.65, 0.001), np.arange(-0.12, 0.13, 0.001)
    box = table_top.estimate(_map_of(_surface_points(_rotated_box_top((0.52, 0.01), 0.09, 0.07, 0.05, 0.3), xs, ys)))
    ball = table_top.estimate(_map_of(_surface_points(_ball_top((0.52, 0.01), 0.035), xs, ys)))
    assert box.edge_rise < 0.001  # a level top at a vertical side
    assert ball.edge_rise > 0.006  # the top curves up from a round side
    assert math.isnan(table_top.edge_rise(np.zeros((4, 4))))
    again = TableTopVector.from_vector(TableTopVector(ball, None, False, 3).to_vector())
    assert again.estimate.edge_rise == pytest.approx(ball.edge_rise)


def test_the_grip_width_is_the_handle_s_not_the_head_s():
    """A hammer lying down: a 24 × 2.4 cm handle along x and a 10 × 2.8 cm head across its end. The
    footprint is 10 cm wide; where the box grasp's fingers close, about the centroid, it is the handle's
    2.4 cm. A 12 × 8 cm box is 8 cm wide there."""
    def hammer(X, Y):
        handle = (np.abs(Y) <= 0.012) & (X >= 0.40) & (X <= 0.64)
        head = (np.abs(Y) <= 0.05) & (X >= 0.612) & (X <= 0.64)
        return np.where(handle | head, 0.026, np.nan)

    xs, ys = np.arange(0.38, 0.66, 0.001), np.arange(-0.07, 0.07, 0.001)
    estimate = table_top.estimate(_map_of(_surface_points(hammer, xs, ys)))
    assert max(estimate.extents_sides[:2]) == pytest.approx(0.24, abs=0.004)
    assert min(estimate.extents_sides[:2]) == pytest.approx(0.10, abs=0.004)
    assert estimate.grip_width == pytest.approx(0.024, abs=0.004)
    box = table_top.estimate(_map_of(_surface_points(_rotated_box_top((0.52, 0.01), 0.12, 0.08, 0.03, 0.4), xs, ys)))
    assert box.grip_width == pytest.approx(0.08, abs=0.004)
    again = TableTopVector.from_vector(TableTopVector(estimate, None, False, 3).to_vector())
    assert again.estimate.grip_width == pytest.approx(estimate.grip_width)
    assert math.isnan(table_top.grip_width(np.zeros((0, 2)), (0.5, 0.0), (1.0, 0.0)))
    assert math.isnan(table_top.grip_width(np.zeros((3, 2)), (0.5, 0.0), (0.0, 0.0)))  # a vertical axis
    assert estimate.grip_reach == pytest.approx(0.012, abs=0.003)  # the handle's half width
    np.testing.assert_allclose(np.abs(estimate.grip_axis), [1, 0, 0], atol=0.02)
    np.testing.assert_allclose(again.estimate.grip_axis, estimate.grip_axis)
    assert again.estimate.grip_reach == pytest.approx(estimate.grip_reach)


def test_the_grip_reach_is_the_far_edge_s_on_a_footprint_off_its_centroid():
    """Offsets across the axis of cells within the band: a T-like section whose stem reaches 3 cm on one
    side of the centre and 1 cm on the other reaches 3 cm (its width, 4 cm, halved would say 2 cm);
    cells beyond the band along the axis do not count."""
    y = np.arange(-0.01, 0.0301, 0.002)
    xy = np.column_stack([np.full(len(y), 0.5), y])
    far = np.array([[0.5 + 0.05, 0.08]])  # 5 cm along the axis: outside the 3.65 cm band
    points = np.vstack([xy, far])
    assert table_top.grip_reach(points, (0.5, 0.0), (1.0, 0.0)) == pytest.approx(0.03)
    assert table_top.grip_width(points, (0.5, 0.0), (1.0, 0.0)) == pytest.approx(0.04)
    assert math.isnan(table_top.grip_reach(points, (0.5, 0.0), (0.0, 0.0)))
