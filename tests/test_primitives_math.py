"""The visual primitives' pure math on plain arrays: camera model, silhouette, estimators, scores."""

import math

import numpy as np
import pytest

from drake_grasp.primitives import estimators, scores
from drake_grasp.primitives.camera_model import (
    CameraIntrinsics,
    arc_angle,
    arc_command,
    arc_profile,
    centring_twist,
    orbit_twist,
    wrap_angle,
)
from drake_grasp.primitives.silhouette import CameraSample, Rectangle, measure_silhouette, min_area_rectangle

K = CameraIntrinsics.from_fov_y(320, 240, math.radians(60.0))
R_DOWN = np.diag([1.0, -1.0, -1.0])  # camera looking straight down, x along the world's x


def _grid():
    v, u = np.mgrid[0:240, 0:320]
    return u.astype(float), v.astype(float)


def _rectangle_mask(centre, length, width, angle):
    u, v = _grid()
    du, dv = u - centre[0], v - centre[1]
    x = math.cos(angle) * du + math.sin(angle) * dv
    y = -math.sin(angle) * du + math.cos(angle) * dv
    return (np.abs(x) <= length / 2) & (np.abs(y) <= width / 2)


# --- camera model -----------------------------------------------------------------------------------


def test_intrinsics_match_drakes_camera_config():
    from drake_grasp.station import load_scenario

    k = CameraIntrinsics.from_camera_config(load_scenario().camera)
    assert (k.width, k.height) == (320, 240)
    assert k.fx == pytest.approx(K.fx) and k.cx == pytest.approx(159.5) and k.cy == pytest.approx(119.5)


def test_ray_and_projection_are_inverse():
    p_C = np.array([0.05, -0.03, 0.4])
    u, v = K.project(p_C)
    assert K.ray(u, v) == pytest.approx(p_C / np.linalg.norm(p_C))
    assert K.ray(K.cx, K.cy) == pytest.approx([0.0, 0.0, 1.0])


def test_line_plane_normal_contains_the_line_and_points_to_its_positive_side():
    e = np.array([math.cos(0.3), math.sin(0.3)])
    s = 150.0
    n = K.line_plane_normal(e, s)
    for t in (-40.0, 0.0, 25.0):  # points on the image line back-project into the plane
        uv = s * e + t * np.array([-e[1], e[0]])
        assert np.dot(n, K.ray(*uv)) == pytest.approx(0.0, abs=1e-12)
    inside = (s + 10.0) * e
    assert np.dot(n, K.ray(*inside)) > 0


def test_orbit_twist_keeps_the_pivot_fixed_in_the_camera():
    omega = np.array([0.1, -0.4, 0.2])
    p_CO = np.array([0.02, -0.01, 0.35])
    twist = orbit_twist(omega, p_CO)
    # Velocity of the pivot seen from the camera: −v − ω × p_CO = 0.
    assert -twist[3:] - np.cross(twist[:3], p_CO) == pytest.approx(np.zeros(3))


def test_centring_twist_turns_the_optical_axis_toward_the_target():
    twist = centring_twist(0.1, 0.0, 2.0)  # target to the right (+x): rotate about +y
    assert twist[1] > 0 and twist[0] == 0
    twist = centring_twist(0.0, 0.1, 2.0)  # target below (+y): rotate about −x
    assert twist[0] < 0 and twist[1] == 0


def test_arc_profile_sweeps_both_ways_and_starts_and_ends_at_rest():
    s = np.linspace(0.0, 1.0, 2001)
    phi, dphi = np.array([arc_profile(x) for x in s]).T
    assert phi.max() == pytest.approx(1.0) and phi.min() == pytest.approx(-1.0)
    assert phi[0] == pytest.approx(0.0) and phi[-1] == pytest.approx(0.0, abs=1e-12)
    assert dphi[0] == pytest.approx(0.0) and dphi[-1] == pytest.approx(0.0, abs=1e-9)
    # dφ/ds integrates to φ; the peak rate is 2π.
    assert np.cumsum(dphi)[-1] * (s[1] - s[0]) == pytest.approx(0.0, abs=1e-2)
    assert np.abs(dphi).max() == pytest.approx(2 * math.pi, rel=1e-3)
    assert arc_command(-1.0, 0.5, 2.0) == (0.0, 0.0) and arc_command(5.0, 0.5, 2.0) == (0.0, 0.0)
    assert arc_command(0.5, 0.5, 2.0)[0] == pytest.approx(0.5)


def test_arc_angle_and_wrap_angle():
    axis = np.array([1.0, 0.0, 0.0])
    reference = np.array([0.0, 0.0, 1.0])
    view = np.array([0.0, -math.sin(0.3), math.cos(0.3)])  # reference turned by +0.3 about +x
    assert arc_angle(view, reference, axis) == pytest.approx(0.3)
    assert wrap_angle(3.0, math.pi) == pytest.approx(3.0 - math.pi)
    assert wrap_angle(-math.pi / 2, math.pi) == pytest.approx(math.pi / 2)


# --- silhouette -----------------------------------------------------------------------------------


@pytest.mark.parametrize("angle", [0.0, 0.4, -1.0, math.pi / 2])
def test_min_area_rectangle_of_a_rotated_rectangle(angle):
    mask = _rectangle_mask((160.0, 120.0), 100.0, 40.0, angle)
    rectangle = min_area_rectangle(mask)
    assert wrap_angle(rectangle.angle - angle, math.pi) == pytest.approx(0.0, abs=0.02)
    assert rectangle.length == pytest.approx(101.0, abs=1.5) and rectangle.width == pytest.approx(41.0, abs=1.5)
    points = np.argwhere(mask)[:, ::-1].astype(float)
    assert (points @ rectangle.e1).min() >= rectangle.s1[0] and (points @ rectangle.e1).max() <= rectangle.s1[1]
    assert (points @ rectangle.e2).min() >= rectangle.s2[0] and (points @ rectangle.e2).max() <= rectangle.s2[1]


def test_empty_mask_is_no_silhouette_and_samples_round_trip():
    assert measure_silhouette(np.zeros((240, 320), bool)) is None
    assert min_area_rectangle(np.zeros((240, 320), bool)) is None
    silhouette = measure_silhouette(_rectangle_mask((100.0, 80.0), 60.0, 20.0, 0.2))
    assert silhouette.eccentricity == pytest.approx(3.0, rel=0.05) and not silhouette.touches_border
    sample = CameraSample(2.5, silhouette, np.array([0.5, 0.0, 0.4]), R_DOWN)
    back = CameraSample.from_vector(sample.to_vector())
    assert back.time == 2.5 and back.usable
    assert back.silhouette.rectangle.angle == pytest.approx(silhouette.rectangle.angle)
    assert back.R_WC == pytest.approx(R_DOWN)
    assert not CameraSample.from_vector(CameraSample.empty().to_vector()).visible


# --- estimators -----------------------------------------------------------------------------------


def test_rays_meet_at_the_point_they_see():
    target = np.array([0.55, 0.02, 0.05])
    A, b = np.zeros((3, 3)), np.zeros(3)
    for angle in np.linspace(-0.4, 0.4, 9):
        p = target + 0.4 * np.array([math.sin(angle), 0.3 * math.sin(2 * angle), math.cos(angle)])
        r = (target - p) / np.linalg.norm(target - p)
        estimators.add_ray(A, b, p, r, 1.0, np.array([1.0, 0.0, 0.0]), 0.1)
    assert estimators.solve_point(A, b) == pytest.approx(target, abs=1e-9)
    assert estimators.ray_spread(A, 9) > 0


def test_axis_from_interpretation_planes():
    axis = np.array([math.cos(0.3), math.sin(0.3), 0.0])
    M = np.zeros((3, 3))
    for tilt in np.linspace(-0.35, 0.35, 7):  # views around the axis: planes containing it
        across = np.cross([0.0, 0.0, 1.0], axis)
        view = math.cos(tilt) * np.array([0.0, 0.0, 1.0]) + math.sin(tilt) * across
        estimators.add_plane(M, np.cross(axis, view) / np.linalg.norm(np.cross(axis, view)))
    found, eigenvalues = estimators.axis_from_planes(M)
    assert abs(np.dot(found, axis)) == pytest.approx(1.0, abs=1e-9)
    # Constrained across the vertical, the answer is the same horizontal axis.
    found, _ = estimators.axis_from_planes(M, perpendicular_to=np.array([0.0, 0.0, 1.0]))
    assert abs(np.dot(found, axis)) == pytest.approx(1.0, abs=1e-9)


def _box_support(half, centre):
    return lambda n: float(n @ centre + np.abs(n) @ half)


def _views(centre, radius, count=12):
    """Camera poses on two arcs (about x and about y) around `centre`, looking at it."""
    poses = []
    for angle in np.linspace(-0.6, 0.6, count):
        for axis in ("x", "y"):
            c, s = math.cos(angle), math.sin(angle)
            R = np.array([[1, 0, 0], [0, c, -s], [0, s, c]]) if axis == "x" else \
                np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
            R_WC = R @ R_DOWN
            poses.append((R_WC, centre - radius * R_WC[:, 2]))
    return poses


def _silhouette_rectangle(points_W, R_WC, p_WC):
    """The exact bounding rectangle, along the image axes, of the projections of points (u, v)."""
    uv = np.array([K.project(R_WC.T @ (p - p_WC)) for p in points_W])
    return Rectangle(0.0, (uv[:, 0].min(), uv[:, 0].max()), (uv[:, 1].min(), uv[:, 1].max()))


def test_tangent_planes_are_tangent_to_a_box():
    half = np.array([0.08, 0.05, 0.03])
    centre = np.array([0.55, 0.0, 0.03])
    corners = np.array([centre + half * (2 * np.array(s) - 1) for s in np.ndindex(2, 2, 2)])
    h = _box_support(half, centre)
    for R_WC, p_WC in _views(centre, 0.4, 5):
        planes = estimators.tangent_planes(K, R_WC, p_WC, _silhouette_rectangle(corners, R_WC, p_WC))
        for nu, o in zip(planes[:, :3], planes[:, 3]):
            assert o == pytest.approx(h(nu), abs=1e-9)


@pytest.mark.parametrize("shape", ["box", "sphere", "cylinder"])
def test_support_fit_recovers_centre_and_extents(shape):
    centre = np.array([0.55, 0.01, 0.0])
    rng = np.random.default_rng(0)
    normals = rng.normal(size=(300, 3))
    normals[:, 2] = np.abs(normals[:, 2]) * 0.5 + 0.1  # seen from above: normals tilted up
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    if shape == "box":
        half = np.array([0.1, 0.04, 0.03])
        h0 = np.abs(normals) @ half
        extents = 2 * half
    elif shape == "sphere":
        h0 = np.full(len(normals), 0.06)
        extents = np.full(3, 0.12)
    else:  # lying along x: half-length 0.15, radius 0.05
        h0 = 0.15 * np.abs(normals[:, 0]) + 0.05 * np.sqrt(1 - normals[:, 0] ** 2)
        extents = np.array([0.3, 0.1, 0.1])
    centre[2] = extents[2] / 2  # resting on the table at z = 0
    planes = np.column_stack([normals, normals @ centre + h0])
    fit = estimators.fit_support(planes, np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]), table_height=0.0)
    assert fit.centre == pytest.approx(centre, abs=1e-6)
    assert fit.extents() == pytest.approx(extents, abs=1e-6)
    assert fit.rms < 1e-6


def _upright_box_planes(yaw: float, half=(0.05, 0.015, 0.075), centre=(0.55, 0.0, 0.075)) -> np.ndarray:
    """Tangent planes of an upright box (10 x 3 x 15 cm, yawed) as the silhouettes' rectangles give
    them: normals along its four side faces' normals, tilted up and down as the views go round."""
    e1 = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    e2 = np.array([-math.sin(yaw), math.cos(yaw), 0.0])
    up = np.array([0.0, 0.0, 1.0])
    rows = []
    for face in (e1, -e1, e2, -e2):
        for tilt in np.linspace(-0.3, 0.6, 10):
            n = face * math.cos(tilt) + up * math.sin(tilt)
            h = n @ np.asarray(centre) + half[0] * abs(n @ e1) + half[1] * abs(n @ e2) + half[2] * abs(n @ up)
            rows.append(np.concatenate([n, [h]]))
    return np.array(rows)


def test_an_upright_box_is_sized_in_the_frame_of_its_sides():
    """An upright box's principal axis is vertical: made horizontal, it is the direction of its tilt
    error, unrelated to the box's sides. Fitted 30 degrees off them, the box model puts the width at
    its bound, 0 (to rounding here; 1e-21 m in a real trial, and exactly 0.0 gave an estimate whose
    size is not positive: the camera-driven trial ended in a simulation error). Fitted in the frame
    of its side faces, its sizes are exact."""
    yaw = math.radians(20.0)
    planes = _upright_box_planes(yaw)
    up = np.array([0.0, 0.0, 1.0])
    off = yaw + math.radians(30.0)
    skewed = estimators.fit_support(planes, np.array([math.cos(off), math.sin(off), 0.0]), up, table_height=0.0)
    assert skewed.extents()[1] < 1e-12
    sides = estimators.face_direction(planes)
    assert abs(np.dot(sides, [math.cos(yaw), math.sin(yaw), 0.0])) == pytest.approx(1.0, abs=1e-12)
    fit = estimators.fit_support(planes, sides, up, table_height=0.0)
    assert fit.extents() == pytest.approx([0.1, 0.03, 0.15], abs=1e-6)
    # The planes of the other two faces alone (normals 90 degrees away) give the same direction.
    assert abs(np.dot(estimators.face_direction(planes[20:40]), sides)) == pytest.approx(1.0, abs=1e-9)
    # A round section (normals evenly all round) shows no face direction.
    angles = np.radians(np.arange(0.0, 360.0, 10.0))
    round_planes = np.column_stack([np.cos(angles), np.sin(angles), np.zeros_like(angles), np.full_like(angles, 0.05)])
    assert estimators.face_direction(round_planes) is None
    assert estimators.is_upright(np.array([0.1, 0.0, 0.99])) and not estimators.is_upright(np.array([1.0, 0.0, 0.9]))


def test_view_angles_and_exploration_frame():
    a, b = estimators.exploration_frame(np.array([1.0, 0.1, 0.2]), np.array([0.0, 0.0, 1.0]))
    assert a == pytest.approx(np.array([1.0, 0.1, 0.0]) / math.hypot(1.0, 0.1))
    assert np.cross(a, b) == pytest.approx([0.0, 0.0, 1.0])
    centre = np.zeros(3)
    camera = 0.4 * np.array([0.0, math.sin(0.3), math.cos(0.3)])  # turned about x toward +y
    phi_a, phi_b = estimators.view_angles(camera, centre, np.array([1.0, 0, 0]), np.array([0, 1.0, 0]))
    assert abs(phi_a) == pytest.approx(0.3) and phi_b == pytest.approx(0.0, abs=1e-12)


# --- scores ---------------------------------------------------------------------------------------


def _statistics(area, eccentricity, amplitude=0.7):
    """Samples on the two arcs (about a, then about b) of features given as functions of (φa, φb)."""
    stats = scores.FeatureStatistics()
    for phi in np.linspace(-amplitude, amplitude, 41):
        stats.add(phi, 0.0, area(phi, 0.0), eccentricity(phi, 0.0))
        stats.add(0.0, phi, area(0.0, phi), eccentricity(0.0, phi))
    return stats


def test_a_sphere_scores_sphere():
    evidence = scores.evaluate(_statistics(lambda a, b: 0.01, lambda a, b: 1.0), scores.ScoreParams())
    assert evidence.sphere == pytest.approx(1.0)
    assert evidence.cylinder == pytest.approx(0.0) and evidence.box == pytest.approx(0.0)


def test_a_cylinder_scores_cylinder():
    # Lying along a: invariant about a; tilting along it shortens the silhouette; eccentricity 3.
    stats = _statistics(lambda a, b: 0.03 * math.cos(b) + 0.008 * abs(math.sin(b)),
                        lambda a, b: 3.0 * math.cos(b) + 0.3 * abs(math.sin(b)))
    evidence = scores.evaluate(stats, scores.ScoreParams())
    assert evidence.cylinder > 0.95 and evidence.sphere < 0.01 and evidence.box < 0.05


def test_a_box_scores_box():
    # A cube: the silhouette grows as cos φ + |sin φ| about either axis.
    grow = lambda phi: math.cos(phi) + abs(math.sin(phi))  # noqa: E731
    stats = _statistics(lambda a, b: 0.01 * grow(a) * grow(b), lambda a, b: max(grow(a), grow(b)))
    evidence = scores.evaluate(stats, scores.ScoreParams())
    assert evidence.box > 0.95 and evidence.sphere < 0.05 and evidence.cylinder < 0.05


def test_resemblances_stay_in_the_unit_interval_and_need_samples():
    rng = np.random.default_rng(1)
    for _ in range(20):
        stats = _statistics(lambda a, b: float(np.exp(rng.normal(-4, 0.5))), lambda a, b: 1 + float(rng.exponential()))
        evidence = scores.evaluate(stats, scores.ScoreParams())
        for shape in scores.SHAPES:
            assert 0.0 <= evidence.resemblance(shape) <= 1.0
    few = scores.FeatureStatistics()
    few.add(0.0, 0.0, 0.01, 1.0)
    assert scores.evaluate(few, scores.ScoreParams()).sphere == 0.0
    assert scores.FeatureStatistics.from_vector(few.to_vector()).count == 1.0
    assert len(few.to_vector()) == scores.FeatureStatistics.SIZE
