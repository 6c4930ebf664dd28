"""Tests of the ε metric (drake_grasp.quality), docs/design.md §4.5.

Expected values come from hand derivations (in the comments) or from references computed here
without qhull: a brute-force facet enumeration (every d-subset of the wrenches spans a hyperplane;
the facets are the supporting ones) and a linear program (scipy.optimize.linprog) that shoots rays
from the origin to the hull boundary.
"""

import itertools

import numpy as np
import pytest
from scipy.optimize import linprog
from scipy.spatial.transform import Rotation

from drake_grasp.quality import (
    GraspQuality,
    contact_tangent_frames,
    epsilon_l1,
    friction_cone_edges,
    grasp_quality,
    primitive_wrenches,
    wrench_space_quality,
)

SPHERE_RADIUS = 0.04  # m
SPHERE_CENTER = np.array([0.1, -0.2, 0.3])  # m, deliberately not the origin


def equator_grasp(num_contacts=3, first_angle=np.pi / 2):
    """Contacts evenly spaced on the equator of the sphere, normals towards its centre.

    The first contact is at 90° so that no normal is parallel to x (the frame's special case).
    """
    angles = first_angle + 2.0 * np.pi * np.arange(num_contacts) / num_contacts
    directions = np.stack((np.cos(angles), np.sin(angles), np.zeros_like(angles)), axis=1)
    return SPHERE_CENTER + SPHERE_RADIUS * directions, -directions


def random_force_closure_grasp(rng, num_contacts, mu=0.5, num_edges=8):
    """Random contacts on the sphere (normals inwards), resampled until ε > 0."""
    while True:
        directions = rng.normal(size=(num_contacts, 3))
        directions /= np.linalg.norm(directions, axis=1, keepdims=True)
        points, normals = SPHERE_CENTER + SPHERE_RADIUS * directions, -directions
        if epsilon_l1(points, normals, mu, SPHERE_CENTER, SPHERE_RADIUS, num_edges) > 0.05:
            return points, normals


def epsilon_by_facet_enumeration(wrenches):
    """Reference ε without qhull, for wrench sets whose hull contains the origin strictly.

    A facet of a d-dimensional polytope with the origin strictly inside lies on a hyperplane
    a·x = 1 through d affinely independent vertices, with a·w ≤ 1 for every wrench w; its distance
    from the origin is 1/|a|. Try every d-subset (affinely dependent subsets and subsets whose
    hyperplane passes through the origin give singular systems and are skipped).
    """
    dimension = wrenches.shape[1]
    subsets = np.array(list(itertools.combinations(range(len(wrenches)), dimension)))
    systems = wrenches[subsets]
    systems = systems[np.abs(np.linalg.det(systems)) > 1e-9]
    normals = np.linalg.solve(systems, np.ones(systems.shape[:2] + (1,)))[..., 0]
    supporting = (normals @ wrenches.T).max(axis=1) <= 1.0 + 1e-9
    return 1.0 / np.linalg.norm(normals[supporting], axis=1).max()


def boundary_distance_along(wrenches, direction):
    """Largest t with t·direction in conv(wrenches), by linear programming.

    Variables: convex weights λ (one per wrench) and t; maximise t subject to Σλ_k w_k = t·u,
    Σλ_k = 1, λ ≥ 0.
    """
    num_wrenches, dimension = wrenches.shape
    equality_matrix = np.zeros((dimension + 1, num_wrenches + 1))
    equality_matrix[:dimension, :num_wrenches] = wrenches.T
    equality_matrix[:dimension, num_wrenches] = -direction
    equality_matrix[dimension, :num_wrenches] = 1.0
    equality_rhs = np.zeros(dimension + 1)
    equality_rhs[dimension] = 1.0
    cost = np.zeros(num_wrenches + 1)
    cost[-1] = -1.0
    bounds = [(0.0, None)] * num_wrenches + [(None, None)]
    result = linprog(cost, A_eq=equality_matrix, b_eq=equality_rhs, bounds=bounds, method="highs")
    assert result.status == 0, result.message
    return -result.fun


# --- Building blocks: frames, edges, wrenches (worked by hand). ---


def test_tangent_frame_follows_the_convention():
    # n = z: t1 = z × x = y; t2 = z × y = −x.
    # n = −x (parallel to x): t1 = (−x) × z = y; t2 = (−x) × y = −z.
    normals = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]])
    t1, t2 = contact_tangent_frames(normals)
    np.testing.assert_allclose(t1, [[0, 1, 0], [0, 1, 0]], atol=1e-15)
    np.testing.assert_allclose(t2, [[-1, 0, 0], [0, 0, -1]], atol=1e-15)


def test_cone_edges_have_unit_normal_component_and_tangential_length_mu():
    rng = np.random.default_rng(0)
    normals = rng.normal(size=(5, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    edges = friction_cone_edges(normals, 0.7, num_edges=8)
    assert edges.shape == (5, 8, 3)
    normal_components = np.einsum("imk,ik->im", edges, normals)
    np.testing.assert_allclose(normal_components, 1.0, atol=1e-14)
    tangential = edges - normal_components[..., np.newaxis] * normals[:, np.newaxis, :]
    np.testing.assert_allclose(np.linalg.norm(tangential, axis=2), 0.7, atol=1e-14)


def test_primitive_wrenches_of_one_contact_by_hand():
    # Contact 5 cm below the centre, normal +z (into the object), μ = 0.5, ρ = 0.1 m, m = 4.
    # Frame: t1 = y, t2 = −x, so the edges (θ = 0, 90°, 180°, 270°) are
    # (0, .5, 1), (−.5, 0, 1), (0, −.5, 1), (.5, 0, 1).
    # Torque r × f / ρ with r = (0, 0, −0.05): (0.05 f_y, −0.05 f_x, 0) / 0.1 = (f_y, −f_x, 0) / 2.
    wrenches = primitive_wrenches(
        [[0.0, 0.0, -0.05]], [[0.0, 0.0, 1.0]], mu=0.5, center=[0, 0, 0], torque_scale=0.1,
        num_edges=4)
    expected = [
        [0.0, 0.5, 1.0, 0.25, 0.0, 0.0],
        [-0.5, 0.0, 1.0, 0.0, 0.25, 0.0],
        [0.0, -0.5, 1.0, -0.25, 0.0, 0.0],
        [0.5, 0.0, 1.0, 0.0, -0.25, 0.0],
    ]
    np.testing.assert_allclose(wrenches, expected, atol=1e-15)


# --- The hull step on polytopes known in closed form. ---


@pytest.mark.parametrize("dimension", [3, 6])
def test_cross_polytope(dimension):
    # Vertices ±e_k: facets Σ s_k x_k = 1 (s_k = ±1), at distance 1/√d; volume 2^d / d!.
    vertices = np.concatenate((np.eye(dimension), -np.eye(dimension)))
    quality = wrench_space_quality(vertices)
    assert quality.epsilon == pytest.approx(1.0 / np.sqrt(dimension), rel=1e-12)
    assert quality.volume == pytest.approx(2.0**dimension / np.prod(range(1, dimension + 1)))


def test_hypercube_shifted_off_centre():
    # The cube [−1, 1]^6 shifted by 0.25 along x: nearest facet x = −1 + 0.25, at distance 0.75.
    vertices = np.array(list(itertools.product([-1.0, 1.0], repeat=6)))
    vertices[:, 0] += 0.25
    quality = wrench_space_quality(vertices)
    assert quality.epsilon == pytest.approx(0.75, rel=1e-12)
    assert quality.volume == pytest.approx(64.0)


def test_origin_on_a_facet_or_outside_gives_zero():
    cube = np.array(list(itertools.product([0.0, 1.0], repeat=6)))
    assert wrench_space_quality(cube).epsilon == 0.0  # origin is a vertex
    assert wrench_space_quality(cube + 0.1).epsilon == 0.0  # origin outside
    assert wrench_space_quality(cube).volume == pytest.approx(1.0)


# --- Grasps with values derived by hand or by symmetry. ---


@pytest.mark.parametrize("mu, torque_scale", [(0.5, 1.0), (0.5, np.sqrt(3.0)), (1.0, np.sqrt(3.0))])
def test_four_contacts_on_cube_faces(mu, torque_scale):
    # Cube of half-side 1 m centred at the origin; contacts at the centres of the ±x and ±y faces,
    # normals inwards, m = 4. The frames make every cone edge axis-aligned: each primitive torque is
    # ±μ/ρ along a single axis (e.g. contact (1,0,0): edges (−1, ±μ, 0) and (−1, 0, ±μ), torques
    # (0, −f_z, f_y) / ρ). So in the pure-torque direction u = (0, 0, 0, ±1, ±1, ±1)/√3 no primitive
    # wrench reaches beyond μ/(√3 ρ): ε ≤ μ/(√3 ρ). The facet enumeration shows that no facet is
    # nearer, so ε = μ/(√3 ρ) (ρ = √3 is the cube's own torque scale, centre to corner).
    points = np.array([[1.0, 0, 0], [-1.0, 0, 0], [0, 1.0, 0], [0, -1.0, 0]])
    normals = -points
    wrenches = primitive_wrenches(points, normals, mu, np.zeros(3), torque_scale, num_edges=4)
    expected = mu / (np.sqrt(3.0) * torque_scale)
    assert epsilon_by_facet_enumeration(wrenches) == pytest.approx(expected, rel=1e-9)
    assert epsilon_l1(points, normals, mu, np.zeros(3), torque_scale, num_edges=4) == (
        pytest.approx(expected, rel=1e-12))


def test_three_contacts_on_equator():
    # Three contacts 120° apart on the equator, normals to the centre, μ = 0.5, ρ = R, m = 8.
    # With f = n + μ(a z + b h) (h = z × n; a, b on the octagon), torque = −n × f = μ(a h − b z).
    # Hand bounds: in the pure-torque direction of a horizontal axis e, the support (largest
    # projection of a primitive wrench) is μ max_k |h_k · e|, which is μ cos 30° for the worst e
    # (the h_k are 120° apart); in the force direction z it is μ. So ε ≤ μ cos 30°. The exact value
    # comes from the facet enumeration (no qhull).
    mu = 0.5
    points, normals = equator_grasp()
    wrenches = primitive_wrenches(points, normals, mu, SPHERE_CENTER, SPHERE_RADIUS)
    expected = epsilon_by_facet_enumeration(wrenches)
    assert 0.0 < expected < mu * np.cos(np.pi / 6)
    quality = grasp_quality(points, normals, mu, SPHERE_CENTER, SPHERE_RADIUS)
    assert quality.epsilon == pytest.approx(expected, rel=1e-9)
    assert quality.epsilon == pytest.approx(0.2759251556860989, rel=1e-9)  # regression value
    assert quality.volume > 0.0 and quality.is_force_closure


def test_equator_grasp_is_invariant_under_any_rotation_about_z():
    # On the equator t1 = n × x = ±z, so for m divisible by 4 the octagon {±z, ±h, (±z ± h)/√2}
    # does not depend on the contact's azimuth (nor on the n ∥ x branch): the linearised grasp
    # turns rigidly with the rotation and ε is exactly invariant.
    reference = epsilon_l1(*equator_grasp(), 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    for first_angle in (0.0, 0.3, 1.0, np.pi):  # 0 and π put a normal along ±x
        points, normals = equator_grasp(first_angle=first_angle)
        assert epsilon_l1(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS) == (
            pytest.approx(reference, rel=1e-9))


def test_two_antipodal_contacts_give_zero():
    # No wrench has a moment about the line through the two contacts: the wrenches span 5 of 6
    # dimensions, the hull is flat.
    points = SPHERE_CENTER + SPHERE_RADIUS * np.array([[1.0, 0.2, 0.1], [-1.0, -0.2, -0.1]])
    normals = SPHERE_CENTER - points
    for mu in (0.3, 2.0):
        quality = grasp_quality(points, normals, mu, SPHERE_CENTER, SPHERE_RADIUS)
        assert quality == GraspQuality(epsilon=0.0, volume=0.0)


def test_any_two_point_contacts_give_zero():
    rng = np.random.default_rng(3)
    for _ in range(5):
        points, normals = rng.normal(size=(2, 3)), rng.normal(size=(2, 3))
        assert epsilon_l1(points, normals, 1.0, [0, 0, 0], 1.0) == 0.0


def test_contacts_all_pushing_down_give_zero():
    # Four contacts within 20° of the north pole, normals inwards: n_z ≤ −cos 20° = −0.94 and the
    # tangential part of each edge has |z| ≤ μ sin 20° = 0.10, so every force pushes down and no
    # combination can be zero. The hull itself is full-dimensional (volume > 0): this exercises the
    # "origin outside" branch, not the degenerate one.
    polar = np.deg2rad([15.0, 20.0, 10.0, 18.0])
    azimuth = np.deg2rad([0.0, 100.0, 200.0, 290.0])
    directions = np.stack((np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth),
                           np.cos(polar)), axis=1)
    points = SPHERE_CENTER + SPHERE_RADIUS * directions
    quality = grasp_quality(points, -directions, 0.3, SPHERE_CENTER, SPHERE_RADIUS)
    assert quality.epsilon == 0.0
    assert quality.volume > 0.0
    assert not quality.is_force_closure


def test_frictionless_contacts_give_zero():
    # μ = 0: each contact contributes one wrench; three wrenches cannot span 6-D.
    points, normals = equator_grasp()
    assert epsilon_l1(points, normals, 0.0, SPHERE_CENTER, SPHERE_RADIUS) == 0.0


def test_zero_contacts_give_zero():
    assert grasp_quality(np.empty((0, 3)), np.empty((0, 3)), 0.5, [0, 0, 0], 1.0) == (
        GraspQuality(0.0, 0.0))
    assert epsilon_l1([], [], 0.5, [0, 0, 0], 1.0) == 0.0


# --- Invariances. ---


def test_translating_points_and_center_together():
    points, normals = random_force_closure_grasp(np.random.default_rng(4), 4)
    reference = epsilon_l1(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    shift = np.array([1.5, -0.7, 0.2])
    moved = epsilon_l1(points + shift, normals, 0.5, SPHERE_CENTER + shift, SPHERE_RADIUS)
    assert moved == pytest.approx(reference, rel=1e-9)


def test_permuting_contacts():
    points, normals = random_force_closure_grasp(np.random.default_rng(5), 5)
    reference = grasp_quality(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    order = np.array([3, 0, 4, 2, 1])
    permuted = grasp_quality(points[order], normals[order], 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    assert permuted.epsilon == pytest.approx(reference.epsilon, rel=1e-9)
    assert permuted.volume == pytest.approx(reference.volume, rel=1e-9)


def test_rotation_about_x_is_exact():
    # R x = x, so R(n × x) = (R n) × x: the tangent frames rotate with the grasp and the linearised
    # GWS is rotated rigidly (forces by R, torques R r × R f = R(r × f)): ε is exactly invariant.
    points, normals = random_force_closure_grasp(np.random.default_rng(6), 4)
    reference = epsilon_l1(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    rotation = Rotation.from_rotvec([0.9, 0.0, 0.0]).as_matrix()
    rotated = epsilon_l1(points @ rotation.T, normals @ rotation.T, 0.5,
                         rotation @ SPHERE_CENTER, SPHERE_RADIUS)
    assert rotated == pytest.approx(reference, rel=1e-9)


def test_arbitrary_rotation_stays_within_the_linearisation_bounds():
    # Other rotations also turn each linearised cone about its normal. A regular m-gon of
    # circumradius μ, however turned, contains the disc of radius μ cos(π/m) (which contains the
    # unturned m-gon of circumradius μ cos(π/m)) and is contained in the disc of radius μ (inside
    # the unturned m-gon of circumradius μ / cos(π/m)). The GWS grows with its cones, so
    # ε(μ cos(π/m)) ≤ ε_rotated(μ) ≤ ε(μ / cos(π/m)).
    rng = np.random.default_rng(7)
    mu, num_edges = 0.5, 8
    shrink = np.cos(np.pi / num_edges)
    for _ in range(3):
        points, normals = random_force_closure_grasp(rng, 4, mu, num_edges)
        rotation = Rotation.random(random_state=rng).as_matrix()
        rotated = epsilon_l1(points @ rotation.T, normals @ rotation.T, mu,
                             rotation @ SPHERE_CENTER, SPHERE_RADIUS, num_edges)
        lower = epsilon_l1(points, normals, mu * shrink, SPHERE_CENTER, SPHERE_RADIUS, num_edges)
        upper = epsilon_l1(points, normals, mu / shrink, SPHERE_CENTER, SPHERE_RADIUS, num_edges)
        assert lower - 1e-12 <= rotated <= upper + 1e-12


def test_epsilon_grows_with_mu():
    # Larger μ scales each cone section about its centre n: the new cones contain the old ones.
    points, normals = equator_grasp()
    values = [epsilon_l1(points, normals, mu, SPHERE_CENTER, SPHERE_RADIUS)
              for mu in (0.0, 0.1, 0.2, 0.4, 0.8, 1.6)]
    assert values[0] == 0.0
    assert all(later > earlier for earlier, later in zip(values[1:], values[2:]))


def test_normals_need_not_be_unit():
    points, normals = random_force_closure_grasp(np.random.default_rng(8), 3)
    scales = np.array([[0.5], [3.0], [1.0 + 1e-6]])
    reference = epsilon_l1(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    assert epsilon_l1(points, normals * scales, 0.5, SPHERE_CENTER, SPHERE_RADIUS) == (
        pytest.approx(reference, rel=1e-12))


def test_per_contact_mu_matches_scalar_mu():
    points, normals = random_force_closure_grasp(np.random.default_rng(9), 3)
    scalar = epsilon_l1(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    per_contact = epsilon_l1(points, normals, [0.5, 0.5, 0.5], SPHERE_CENTER, SPHERE_RADIUS)
    assert per_contact == scalar


# --- Independent cross-checks on random force-closure grasps. ---


@pytest.mark.parametrize("num_contacts", [3, 4])
def test_random_grasps_match_facet_enumeration(num_contacts):
    rng = np.random.default_rng(10 + num_contacts)
    for _ in range(2):
        points, normals = random_force_closure_grasp(rng, num_contacts, num_edges=4)
        wrenches = primitive_wrenches(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS, 4)
        assert epsilon_l1(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS, 4) == (
            pytest.approx(epsilon_by_facet_enumeration(wrenches), rel=1e-9))


def test_random_grasps_agree_with_linear_programming():
    # ε is the radius of the largest ball about the origin inside the hull: the boundary is at
    # distance ≥ ε in every direction (checked along random directions) and at exactly ε along
    # the normal of the nearest facet (taken from an independently built hull of the wrenches).
    from scipy.spatial import ConvexHull

    rng = np.random.default_rng(11)
    for num_contacts in (3, 5):
        points, normals = random_force_closure_grasp(rng, num_contacts)
        wrenches = primitive_wrenches(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
        epsilon = epsilon_l1(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
        directions = rng.normal(size=(15, 6))
        directions /= np.linalg.norm(directions, axis=1, keepdims=True)
        for direction in directions:
            assert boundary_distance_along(wrenches, direction) >= epsilon * (1.0 - 1e-7)
        equations = ConvexHull(wrenches, qhull_options="QJ").equations
        nearest_normal = equations[np.argmax(equations[:, -1]), :-1]
        assert boundary_distance_along(wrenches, nearest_normal) == pytest.approx(epsilon, rel=1e-6)


# --- Input validation. ---

GOOD = dict(points=[[0.0, 0.0, 0.0]] * 3, normals=[[0.0, 0.0, 1.0]] * 3, mu=0.5,
            center=[0.0, 0.0, 0.0], torque_scale=0.1)


@pytest.mark.parametrize("change, message", [
    (dict(points=[[0.0, np.nan, 0.0]] * 3), r"points contain NaN or inf \(row 0"),
    (dict(normals=[[0.0, 0.0, 1.0], [0.0, np.inf, 1.0], [0.0, 0.0, 1.0]]),
     r"normals contain NaN or inf \(row 1"),
    (dict(points=[[0.0, 0.0]] * 3), r"points must have shape \(N, 3\), got shape \(3, 2\)"),
    (dict(points=[0.0, 0.0, 0.0]), r"points must have shape \(N, 3\), got shape \(3,\)"),
    (dict(normals=[[0.0, 0.0, 1.0]] * 2),
     r"normals must have the same shape as points, got normals \(2, 3\) and points \(3, 3\)"),
    (dict(mu=-0.1), r"mu must be >= 0, got -0.1"),
    (dict(mu=np.nan), r"mu must be finite"),
    (dict(mu=[0.5, 0.5]), r"mu must be a scalar or have shape \(3,\)"),
    (dict(center=[0.0, 0.0]), r"center must have shape \(3,\), got shape \(2,\)"),
    (dict(center=[0.0, np.nan, 0.0]), r"center contains NaN or inf"),
    (dict(torque_scale=0.0), r"torque_scale must be finite and > 0 \(metres\), got 0.0"),
    (dict(torque_scale=-1.0), r"torque_scale must be finite and > 0"),
    (dict(torque_scale=np.inf), r"torque_scale must be finite and > 0"),
    (dict(torque_scale="big"), r"torque_scale must be a real number"),
    (dict(num_edges=2), r"num_edges must be an integer >= 3, got 2"),
    (dict(num_edges=8.0), r"num_edges must be an integer >= 3, got 8.0"),
    (dict(normals=[[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
     r"normals must be nonzero: normal 1 has length 0"),
    (dict(normals=[[0.0, 0.0, 1.0], [1e-12, 0.0, 0.0], [0.0, 0.0, 1.0]]),
     r"normals must be nonzero: normal 1 has length 1e-12"),
])
def test_invalid_input_is_reported(change, message):
    arguments = {**GOOD, **change}
    for function in (epsilon_l1, grasp_quality, primitive_wrenches):
        with pytest.raises(ValueError, match=message):
            function(**arguments)


def test_invalid_wrenches_are_reported():
    with pytest.raises(ValueError, match=r"wrenches must be a 2-D array"):
        wrench_space_quality(np.zeros(6))
    with pytest.raises(ValueError, match=r"wrenches contain NaN or inf"):
        wrench_space_quality(np.full((8, 6), np.nan))


def test_qhull_precision_error_falls_back_to_joggled_input(monkeypatch):
    # If the default qhull run fails on a set that is not flat, the joggled ("QJ") run is used; its
    # answer differs from the exact one by ~1e-10 only.
    import scipy.spatial

    from drake_grasp import quality

    def default_run_fails(points, qhull_options=None):
        if qhull_options is None:
            raise scipy.spatial.QhullError("simulated precision error")
        return scipy.spatial.ConvexHull(points, qhull_options=qhull_options)

    points, normals = equator_grasp()
    exact = grasp_quality(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    monkeypatch.setattr(quality, "ConvexHull", default_run_fails)
    joggled = grasp_quality(points, normals, 0.5, SPHERE_CENTER, SPHERE_RADIUS)
    assert joggled.epsilon == pytest.approx(exact.epsilon, abs=1e-8)
    assert joggled.volume == pytest.approx(exact.volume, rel=1e-6)
