"""The Eigengrasp planner baseline (baselines/eigengrasp; docs/design.md §4.6)."""

import json
import math

import numpy as np
import trimesh
import trimesh.triangles
import pytest
from pydrake.math import RigidTransform, RotationMatrix

from baselines.eigengrasp import annealing, convex_regions, eigengrasps, energy, search_space
from baselines.eigengrasp import virtual_contacts as vc
from baselines.eigengrasp.object_distance import ConvexPiecesDistance, PrimitiveDistance
from baselines.eigengrasp.planner import EigengraspPlanner, _add_unique
from baselines.eigengrasp.scene import HandObjectScene
from drake_grasp import cli
from drake_grasp.robot import hand
from drake_grasp.objects import ShapePiece, _cached_hull_obj, paper_object, resolve_object, sphere_object
from drake_grasp.quality import friction_cone_edges, wrench_space_quality

# The palm on top of a 10 cm sphere, facing down, 0.5 mm above it.
X_OP_ON_SPHERE = RigidTransform(RotationMatrix.MakeXRotation(math.pi), [0.0, 0.0, 0.0505])


@pytest.fixture(scope="module")
def sphere_planner():
    return EigengraspPlanner(sphere_object(0.10))


# --- Annealing: schedule, neighbours, acceptance. -------------------------------------------------

def test_temperature_follows_graspits_schedule():
    for k in (1, 30_000, 50_000, 70_000):
        assert annealing.temperature(k) == pytest.approx(1.0e6 * math.exp(-7.0 * k ** (1.0 / 8.0)), rel=1e-12)
    # The step counter starts at 30,000: T(30,000) ≈ 9.3e-6 and T(70,000) ≈ 5.5e-7.
    assert annealing.temperature(annealing.K0) == pytest.approx(9.27e-6, rel=1e-2)
    assert annealing.temperature(annealing.DEFAULT_MAX_STEPS) == pytest.approx(5.54e-7, rel=1e-2)
    ts = [annealing.temperature(k) for k in range(30_000, 70_001, 5_000)]
    assert all(a > b for a, b in zip(ts, ts[1:]))


def test_neighbor_offset_is_ingbers_distribution():
    T = 1e-5
    assert annealing.neighbor_offset(0.5, T) == 0.0
    assert annealing.neighbor_offset(1.0, T) == pytest.approx(1.0)
    assert annealing.neighbor_offset(0.0, T) == pytest.approx(-1.0)
    assert annealing.neighbor_offset(0.25, T) == pytest.approx(-annealing.neighbor_offset(0.75, T))
    # |2u - 1| = 1/2 gives T((1 + 1/T)^0.5 - 1).
    assert annealing.neighbor_offset(0.75, T) == pytest.approx(T * (math.sqrt(1 + 1 / T) - 1))


def test_acceptance_rule():
    T = 1e-5
    assert annealing.acceptance_probability(10.0, 9.0, T) == 1.0
    assert annealing.acceptance_probability(10.0, 11.0, T) == pytest.approx(math.exp(-1e-6 / T))
    assert annealing.acceptance_probability(10.0, 10.0, T) == pytest.approx(1.0)


class _Fixed:
    """A uniform stream that replays given numbers."""

    def __init__(self, values):
        self.values = list(values)

    def next(self):
        return self.values.pop(0)


def test_neighbors_stay_in_range_and_phi_wraps():
    rng = np.random.default_rng(3)
    uniforms = annealing.UniformStream(rng)
    for T in (1e3, 1.0, annealing.temperature(annealing.K0)):
        for start in (search_space.LOWER, search_space.UPPER, search_space.RESET_STATE):
            for _ in range(300):
                n = annealing.neighbor(list(start), T, uniforms)
                assert search_space.in_range(n), (T, n)
    # u = 1 is the largest step up: +max jump. φ at π - 0.1 steps by +π/2 and wraps to -π/2 - 0.1.
    state = list(search_space.RESET_STATE)
    state[search_space.PHI] = math.pi - 0.1
    n = annealing.neighbor(state, 1e-5, _Fixed([0.5] * 4 + [1.0] + [0.5] * 3))
    assert n[search_space.PHI] == pytest.approx(-math.pi / 2 - 0.1)
    assert n[:search_space.PHI] == pytest.approx(state[:search_space.PHI])
    # θ (not circular) at its top: a step up is out of range and is drawn again (here: a step down).
    state[search_space.THETA] = math.pi
    n = annealing.neighbor(state, 1e-5, _Fixed([0.5] * 3 + [1.0, 0.0] + [0.5] * 4))
    assert n[search_space.THETA] == pytest.approx(math.pi - math.pi / 5)


def test_uniform_stream_is_deterministic():
    a = annealing.UniformStream(np.random.default_rng(7), block=5)
    b = annealing.UniformStream(np.random.default_rng(7), block=3)
    assert [a.next() for _ in range(11)] == [b.next() for _ in range(11)]


# --- Search space, eigengrasps, virtual contacts. --------------------------------------------------

def test_eigengrasps_origin_limits_and_coupling():
    q = eigengrasps.joint_angles([0.0, 0.0])
    np.testing.assert_allclose(q, [1.13, 1.13, 0.79, 0.79, 0.79] + [0.79 / 3] * 3)
    np.testing.assert_allclose(eigengrasps.joint_angles(eigengrasps.RESET_AMPLITUDES), 0.0)
    q = eigengrasps.joint_angles([4.0, 4.0])
    assert q[0] == pytest.approx(math.pi)  # 1.13 + 4 clamped to the spread limit
    np.testing.assert_allclose(q[2:5], hand.PROXIMAL_LIMITS[1])
    np.testing.assert_allclose(q[5:8], hand.PROXIMAL_LIMITS[1] / 3)
    assert eigengrasps.spread_and_flex(1.0, -1.0) == pytest.approx((2.13, 0.79 - 1 / math.sqrt(3)))


def test_axis_angle_pose_round_trip_and_state_distance():
    rng = np.random.default_rng(0)
    for _ in range(20):
        s = search_space.LOWER + rng.random(8) * (search_space.UPPER - search_space.LOWER)
        X = search_space.palm_pose(s)
        back = search_space.state_from_palm_pose(X, s[6:])
        assert search_space.palm_pose(back).IsNearlyEqualTo(X, 1e-9)
        assert search_space.hand_pose(s).IsNearlyEqualTo(X @ RigidTransform([0, 0, -hand.PALM_HEIGHT]), 1e-12)
    a = np.array(search_space.RESET_STATE)
    b = a.copy()
    b[search_space.TX] += 0.05
    assert search_space.state_distance(a, a, 0.1) == 0.0
    assert search_space.state_distance(a, b, 0.1) == pytest.approx(0.5)
    c = a.copy()
    c[search_space.ALPHA] += math.pi / 5  # 36 deg about the same axis: 0.5 * 0.2
    assert search_space.state_distance(a, c, 0.1) == pytest.approx(0.1)


def test_virtual_contacts_sit_on_the_links_and_follow_the_joints():
    assert len(vc.VIRTUAL_CONTACTS) == 19
    assert sum(c.link == "bh_base" for c in vc.VIRTUAL_CONTACTS) == 4
    for f in hand.FINGERS:
        for link, count in (("proximal", 2), ("distal", 3)):
            assert sum(c.link == f"bh_finger_{f}_{link}" for c in vc.VIRTUAL_CONTACTS) == count
    np.testing.assert_allclose(vc.FRICTION[[c.friction == 1.0 for c in vc.VIRTUAL_CONTACTS]], 1.0)
    assert np.count_nonzero(vc.FRICTION == 1.0) == 3  # the fingertips
    # Positions and normals match Drake's forward kinematics of our model.
    scene = HandObjectScene(sphere_object(0.05))
    plant, context = scene._plant, scene._plant_context
    rng = np.random.default_rng(2)
    for _ in range(3):
        q = np.concatenate([rng.uniform(0, math.pi, 2), rng.uniform(0, 2.4, 3), rng.uniform(0, 0.8, 3)])
        scene.set_hand(RigidTransform(), q)
        points, normals = vc.contact_frames_in_hand(q)
        for i, c in enumerate(vc.VIRTUAL_CONTACTS):
            X_HL = plant.EvalBodyPoseInWorld(context, plant.GetBodyByName(c.link))
            np.testing.assert_allclose(points[i], X_HL @ np.array(c.point), atol=1e-7)
            np.testing.assert_allclose(normals[i], X_HL.rotation() @ np.array(c.normal), atol=1e-7)
        p2, n2 = vc.contact_frames_for_posture(q[0], q[2], q[5])
        q_same = np.array([q[0], q[0], q[2], q[2], q[2], q[5], q[5], q[5]])
        p1, n1 = vc.contact_frames_in_hand(q_same)
        np.testing.assert_allclose(p2, p1, atol=1e-12)
        np.testing.assert_allclose(n2, n1, atol=1e-12)


def test_primitive_distances_match_drake():
    rng = np.random.default_rng(4)
    for name in ("toy_bridge", "bottle_case", "soccer_ball", "banana"):
        spec = resolve_object(name)
        scene = HandObjectScene(spec)
        query = scene._query_port.Eval(scene._sg_context)
        object_ids = set(scene._plant.GetCollisionGeometriesForBody(scene._plant.GetBodyByName(spec.name)))
        points = rng.uniform(-0.2, 0.2, (60, 3))
        points[:20] *= 0.2  # some inside
        d, g = PrimitiveDistance(spec.pieces)(points)
        for i, p in enumerate(points):
            best = min((r for r in query.ComputeSignedDistanceToPoint(p) if r.id_G in object_ids),
                       key=lambda r: r.distance)
            assert d[i] == pytest.approx(best.distance, abs=1e-9), name
            np.testing.assert_allclose(g[i], np.asarray(best.grad_W).ravel(), atol=1e-6)


def _brute_force_distances(pieces, points):
    """Signed distance to a union of convex pieces over every triangle of every piece (reference)."""
    best = np.full(len(points), np.inf)
    for piece in pieces:
        vertices = trimesh.load(piece.mesh_path, force="mesh", process=False).vertices
        hull = trimesh.convex.convex_hull(vertices @ piece.X_OP.rotation().matrix().T + piece.X_OP.translation())
        triangles = hull.triangles
        closest = np.array([trimesh.triangles.closest_point(triangles, np.tile(p, (len(triangles), 1)))
                            for p in points])  # (N, F, 3)
        unsigned = np.linalg.norm(closest - points[:, None, :], axis=2).min(axis=1)
        inside = np.all(points @ hull.face_normals.T < np.einsum('fj,fj->f', hull.face_normals, triangles[:, 0]), axis=1)
        best = np.minimum(best, np.where(inside, -unsigned, unsigned))
    return best


def test_convex_piece_distances_are_exact(monkeypatch):
    rng = np.random.default_rng(5)
    directions = rng.normal(size=(150, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    points = directions * rng.uniform(0.0, 0.15, (150, 1))
    # One piece (the spectacle case), against Drake.
    spec = paper_object("spectacle_case")
    scene = HandObjectScene(spec)
    query = scene._query_port.Eval(scene._sg_context)
    (case_id,) = scene._plant.GetCollisionGeometriesForBody(scene._plant.GetBodyByName(spec.name))
    d, g = ConvexPiecesDistance(spec.pieces)(points)
    for i, p in enumerate(points):
        r = next(r for r in query.ComputeSignedDistanceToPoint(p) if r.id_G == case_id)
        assert d[i] == pytest.approx(r.distance, abs=1e-7)
        np.testing.assert_allclose(g[i], np.asarray(r.grad_W).ravel(), atol=1e-5)
    # Three posed, overlapping pieces of different facet counts, against every triangle. Coarse
    # hulls put many closest points on edges and vertices.
    rng = np.random.default_rng(5)
    pieces = []
    for k, n in enumerate((6, 20, 40)):
        path = _cached_hull_obj(f"test_piece{k}", rng.normal(scale=0.03, size=(n, 3)))
        pieces.append(ShapePiece("convex", (), p_OP=tuple(rng.uniform(-0.03, 0.03, 3)),
                                 rpy_OP=tuple(rng.uniform(-1, 1, 3)), mesh_path=path))
    points = rng.uniform(-0.15, 0.15, (600, 3))
    reference = _brute_force_distances(pieces, points)
    d, g = ConvexPiecesDistance(pieces)(points)
    np.testing.assert_allclose(d, reference, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(g, axis=1), 1.0, atol=1e-9)
    # The gradient points from the closest point to the point: stepping back along it lands on
    # the surface.
    outside = d > 1e-4
    np.testing.assert_allclose(_brute_force_distances(pieces, points[outside] - d[outside, None] * g[outside]),
                               0.0, atol=1e-9)
    # Points near the surface too (within 5 mm), where edges and vertices are often the closest.
    near = points[outside][:200] - d[outside][:200, None] * g[outside][:200] * rng.uniform(-0.5, 1.0, (200, 1))
    near += rng.normal(scale=0.005, size=near.shape)
    d_near, g_near = ConvexPiecesDistance(pieces)(near)
    np.testing.assert_allclose(d_near, _brute_force_distances(pieces, near), atol=1e-9)
    # The second stage (all visible facets) alone, where the first never accepts: exact too (spied
    # on to be sure it ran).
    distance = ConvexPiecesDistance(pieces)
    distance._tolerance = -np.inf
    stage_two = []
    closest_of_facets = distance._closest_of_facets
    monkeypatch.setattr(distance, "_closest_of_facets",
                        lambda *a: stage_two.append(len(a) == 7) or closest_of_facets(*a))
    d2, g2 = distance(points)
    assert any(stage_two)
    np.testing.assert_allclose(d2, reference, atol=1e-9)
    np.testing.assert_allclose(g2, g, atol=1e-6)


def test_strip_triangulation_of_a_polygon_has_no_fan():
    for m in (3, 4, 5, 8, 25):
        cycle = list(range(10, 10 + m))
        triangles = convex_regions.strip_triangles(cycle)
        assert len(triangles) == m - 2
        assert all(len(set(t)) == 3 and set(t) <= set(cycle) for t in triangles)
        # A convex polygon (regular, in the plane): the triangles tile it.
        angle = 2 * np.pi * np.arange(m) / m
        xy = dict(zip(cycle, np.column_stack([np.cos(angle), np.sin(angle)])))
        area = sum(0.5 * abs(np.linalg.det(np.array([xy[b] - xy[a], xy[c] - xy[a]]))) for a, b, c in triangles)
        assert area == pytest.approx(0.5 * m * np.sin(2 * np.pi / m))
        counts = np.bincount([v - 10 for t in triangles for v in t])
        assert counts.max() <= 4  # a fan would put one vertex in all m − 2


def test_flat_faces_of_a_hull_group_its_coplanar_triangles():
    from scipy.spatial import ConvexHull
    # A 20-sided prism: two 20-gon caps (fans in qhull) and 20 rectangles.
    angle = 2 * np.pi * np.arange(20) / 20
    ring = np.column_stack([np.cos(angle), np.sin(angle)])
    hull = ConvexHull(np.vstack([np.column_stack([ring, np.zeros(20)]), np.column_stack([ring, np.ones(20)])]))
    faces = convex_regions.flat_faces(hull)
    assert sorted(len(cycle) for _, cycle in faces) == [4] * 20 + [20, 20]
    for equation, cycle in faces:
        np.testing.assert_allclose(hull.points[cycle] @ equation[:3] + equation[3], 0.0, atol=1e-12)
        # Consecutive cycle vertices are neighbours on the boundary (a side, not a diagonal).
        sides = np.linalg.norm(np.diff(hull.points[cycle + cycle[:1]], axis=0), axis=1)
        assert sides.max() < 1.01  # 20-gon sides 0.31, rectangle sides 0.31 and 1


def _region_test_pieces(rng):
    """Posed convex pieces with flat faces of many vertices (fans in qhull) and random ones."""
    pieces = []
    angle = 2 * np.pi * np.arange(24) / 24
    ring = np.column_stack([np.cos(angle), np.sin(angle)])
    prism = np.vstack([np.column_stack([0.03 * ring, np.full(24, -0.02)]),
                       np.column_stack([0.02 * ring, np.full(24, 0.03)])])
    for k, points in enumerate((prism, rng.normal(scale=0.03, size=(40, 3)), rng.normal(scale=0.02, size=(12, 3)))):
        path = _cached_hull_obj(f"region_piece{k}", points)
        pieces.append(ShapePiece("convex", (), p_OP=tuple(rng.uniform(-0.03, 0.03, 3)),
                                 rpy_OP=tuple(rng.uniform(-1, 1, 3)), mesh_path=path))
    return pieces


def test_convex_distances_by_regions_match_the_general_path_and_brute_force():
    rng = np.random.default_rng(11)
    pieces = _region_test_pieces(rng)
    distance = ConvexPiecesDistance(pieces)
    points = rng.uniform(-0.2, 0.2, (4000, 3))
    exact = _brute_force_distances(pieces, points)
    points, exact = points[exact > 1e-4][:1900], exact[exact > 1e-4][:1900]  # outside every piece
    assert len(points) == 1900
    # Near the surface too, where edges and vertices are the closest features.
    _, g = distance(points[:399])
    near = points[:399] - exact[:399, None] * g * rng.uniform(0.9, 0.999, (399, 1))
    points = np.vstack([points, near])
    exact = np.concatenate([exact, _brute_force_distances(pieces, near)])
    for batch in np.split(np.arange(len(points)), len(points) // 19):  # the planner's 19 contacts
        d, g = distance(points[batch])
        d_ref, g_ref = distance._general(points[batch], *_products_and_lower(distance, points[batch]))
        np.testing.assert_allclose(d, exact[batch], atol=1e-9)
        np.testing.assert_allclose(d, d_ref, rtol=0.0, atol=1e-14)  # the previous algorithm's
        np.testing.assert_allclose(g, g_ref, rtol=0.0, atol=1e-9)
    assert distance.general_calls <= 2  # the regions settle (almost) every call
    # A point inside a piece takes the general path: a negative distance.
    inside = np.vstack([points[:18], [pieces[0].X_OP.translation()]])
    calls = distance.general_calls
    d, g = distance(inside)
    assert d[-1] < 0.0 and distance.general_calls == calls
    np.testing.assert_array_equal(d, distance._general(inside, *_products_and_lower(distance, inside))[0])
    # A star cut short (no edge, no triangle) falls back where it must and stays exact.
    short = ConvexPiecesDistance(pieces, max_star=1)
    for batch in points[:380].reshape(-1, 19, 3):
        np.testing.assert_allclose(short(batch)[0], distance(batch)[0], rtol=0.0, atol=1e-14)
    assert short.general_calls > 0


def test_compiled_convex_distances_match_the_numpy_path():
    """The numba loop (convex_kernel.py) gives the numpy region path's distances and gradients to
    rounding, on points far, near the surface (edges and vertices closest) and inside; a call it
    cannot settle (a point inside) goes to the numpy general path, as before."""
    from baselines.eigengrasp.convex_kernel import region_distances
    rng = np.random.default_rng(13)
    coarse = []  # the posed pieces of test_convex_piece_distances_are_exact
    for k, n in enumerate((6, 20, 40)):
        path = _cached_hull_obj(f"test_piece{k}", np.random.default_rng(5 + k).normal(scale=0.03, size=(n, 3)))
        coarse.append(ShapePiece("convex", (), p_OP=tuple(rng.uniform(-0.03, 0.03, 3)),
                                 rpy_OP=tuple(rng.uniform(-1, 1, 3)), mesh_path=path))
    for pieces in (_region_test_pieces(np.random.default_rng(11)), coarse):
        compiled, reference = ConvexPiecesDistance(pieces), ConvexPiecesDistance(pieces, compiled=False)
        assert compiled.compiled and not reference.compiled
        far = rng.uniform(-0.2, 0.2, (1900, 3))
        d_far = _brute_force_distances(pieces, far)
        outside = far[d_far > 1e-4][:19 * 40]
        d_out, g_out = reference(outside)
        # Near the surface, both sides of it (some points inside a piece).
        near = outside - d_out[:, None] * g_out * rng.uniform(0.95, 1.05, (len(outside), 1))
        near += rng.normal(scale=1e-4, size=near.shape)
        close = rng.uniform(-0.06, 0.06, (1900, 3))
        inside = close[_brute_force_distances(pieces, close) < -1e-4][:19 * 5]
        assert len(outside) == 19 * 40 and len(inside) == 19 * 5
        points = np.vstack([outside, near, inside])
        points = points[rng.permutation(len(points))]
        points = np.vstack([outside[:19 * 20], points])  # whole calls outside, then mixed ones
        settled = 0
        for batch in points[:len(points) // 19 * 19].reshape(-1, 19, 3):
            d, g = compiled(batch)
            d_ref, g_ref = reference(batch)
            np.testing.assert_allclose(d, d_ref, rtol=0.0, atol=1e-12)
            np.testing.assert_allclose(g, g_ref, rtol=0.0, atol=1e-12)
            # The kernel alone, where it settles the call: the numpy region path's values. It
            # settles every call of points outside every piece and none with a point inside.
            d_k, g_k = np.empty(19), np.empty((19, 3))
            ok = region_distances(np.ascontiguousarray(batch), *compiled._kernel_arguments, d_k, g_k)
            products, lower = _products_and_lower(reference, batch)
            if lower.min() <= 0.0:
                assert not ok
            elif ok:
                settled += 1
                found = reference._from_regions(batch, products, lower)
                if found is not None:
                    np.testing.assert_allclose(d_k, found[0], rtol=0.0, atol=1e-12)
                    np.testing.assert_allclose(g_k, found[1], rtol=0.0, atol=1e-12)
                np.testing.assert_allclose(d_k, d_ref, rtol=0.0, atol=1e-12)
        assert settled >= 20  # the calls of outside points at least


def test_convex_piece_regions_cover_the_exterior_of_one_piece():
    """Each point outside a piece lies in the region of one of its features: the star of its nearest
    vertex or the maximising facet almost always; the projector gives the closest point."""
    rng = np.random.default_rng(12)
    path = _cached_hull_obj("region_single", rng.normal(scale=0.03, size=(64, 3)))
    piece = ShapePiece("convex", (), p_OP=(0.0, 0.0, 0.0), rpy_OP=(0.0, 0.0, 0.0), mesh_path=path)
    distance = ConvexPiecesDistance([piece])
    points = rng.normal(scale=0.08, size=(1900, 3))
    points = points[_brute_force_distances([piece], points) > 1e-5][:19 * 80]
    for batch in points.reshape(-1, 19, 3):
        found = distance._from_regions(batch, *_products_and_lower(distance, batch))
        assert found is not None
        np.testing.assert_allclose(found[0], _brute_force_distances([piece], batch), atol=1e-12)


def _products_and_lower(distance, q):
    P, F, V = distance._shape
    products = q @ distance._rows_T + distance._row_offsets
    return products, products[:, :P * F].reshape(len(q), P, F).max(axis=2)


def test_scene_collision_test_and_distances_for_a_convex_object():
    spec = paper_object("spectacle_case")
    scene = HandObjectScene(spec)
    assert not scene.uses_drake_distances
    q = eigengrasps.joint_angles([0.0, 0.0])
    scene.set_hand(RigidTransform([0.0, 0.0, -0.05]), q)  # the palm cuts through the case
    assert scene.in_collision()
    X_OH = search_space.hand_pose(search_space.state_from_palm_pose(RigidTransform(
        RotationMatrix.MakeXRotation(math.pi), [0.0, 0.0, 0.06])))
    scene.set_hand(X_OH, q)
    assert not scene.in_collision()
    points_H, _ = vc.contact_frames_in_hand(q)
    points = np.array([X_OH @ p for p in points_H])
    d, g = scene.contact_distances(points)
    query = scene._query_port.Eval(scene._sg_context)
    (case_id,) = scene._plant.GetCollisionGeometriesForBody(scene._plant.GetBodyByName(spec.name))
    for i, p in enumerate(points):
        r = next(r for r in query.ComputeSignedDistanceToPoint(p) if r.id_G == case_id)
        assert d[i] == pytest.approx(r.distance, abs=1e-6)
        np.testing.assert_allclose(g[i], np.asarray(r.grad_W).ravel(), atol=1e-4)


# --- Energies. -----------------------------------------------------------------------------------

def test_contact_energy_on_plain_arrays():
    normals = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])
    # Both contacts 10 mm from the object, the first facing it, the second at 90 degrees.
    directions = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]])
    assert energy.contact_energy(normals, np.array([0.01, 0.01]), directions) == pytest.approx((10 + 10 + 50) / 2)
    points = np.zeros((2, 3))
    closest = np.array([[0.0, 0.0, 0.01], [0.0, 0.01, 0.0]])
    assert energy.contact_energy_from_points(points, normals, closest) == pytest.approx(35.0)


def test_contact_quality_energy_on_plain_arrays():
    assert energy.quality_scale([0.0, 0.025, 0.05, 0.051, 0.0], [1.0, 1.0, 1.0, 1.0, 0.6]) == pytest.approx(
        [2.0, math.cos(math.pi / 2) + 1, math.cos(math.pi) + 1, 0.0, 0.0])
    # Three fingertips touching a sphere 120 degrees apart, pushing 30 degrees below the horizon.
    angles = np.radians([90.0, 210.0, 330.0])
    normals = -np.stack([np.cos(angles), np.sin(angles), -0.5 * np.ones(3)], axis=1)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.vstack([normals, [[0.0, 0.0, -1.0]]])  # and the palm, on top
    distances = np.zeros(4)
    e = energy.contact_quality_energy(normals, distances, normals, [1.0, 1.0, 1.0, 0.2])
    assert e < 0.0
    edges = friction_cone_edges(normals, [1.0, 1.0, 1.0, 0.2], 8)
    assert e == pytest.approx(-energy.force_space_epsilon(edges, [2.0] * 4))
    assert e == pytest.approx(-wrench_space_quality(2.0 * edges.reshape(-1, 3)).epsilon)
    # The cones may come in any frame: turning every cone together changes nothing.
    R = (RotationMatrix.MakeXRotation(0.3) @ RotationMatrix.MakeZRotation(0.7)).matrix()
    assert -energy.force_space_epsilon(edges @ R.T, [2.0] * 4) == pytest.approx(e)
    assert energy.contact_quality_energy(normals, distances, normals, [1.0] * 4, lambda: edges @ R.T) == pytest.approx(e)
    # With two close contacts the energy is the contact energy.
    far = np.array([0.0, 0.0, 0.2, 0.2])
    assert energy.contact_quality_energy(normals, far, normals, [1.0] * 4) == pytest.approx(
        energy.contact_energy(normals, far, normals))
    # Three close contacts that cannot resist every force score 0.
    same = np.tile([0.0, 0.0, -1.0], (4, 1))
    assert energy.contact_quality_energy(same, distances, same, [0.2] * 4) == 0.0


def test_a_hand_conforming_to_a_sphere_has_lower_energy_than_far_or_misaligned(sphere_planner):
    # The palm on top of the sphere with the fingers curled as far as they go without touching.
    legal = [a1 for a1 in np.arange(-4.0, 4.01, 0.25)
             if sphere_planner.evaluate(search_space.state_from_palm_pose(X_OP_ON_SPHERE, (0.0, a1))) is not None]
    conform = search_space.state_from_palm_pose(X_OP_ON_SPHERE, (0.0, max(legal)))
    far = search_space.state_from_palm_pose(RigidTransform(X_OP_ON_SPHERE.rotation(), [0, 0, 0.25]), (0.0, max(legal)))
    # Misaligned: the same posture with the palm facing away, the hand's back on the sphere.
    away = search_space.state_from_palm_pose(RigidTransform([0.0, 0.0, 0.0505 + hand.PALM_HEIGHT + 0.001]),
                                             (0.0, max(legal)))
    e_conform, e_far, e_away = (sphere_planner.evaluate(s) for s in (conform, far, away))
    assert None not in (e_conform, e_far, e_away)
    assert e_conform < 0.5 * e_far
    assert e_conform < 0.5 * e_away
    # The open hand on the sphere scores worse than the curled one.
    open_hand = search_space.state_from_palm_pose(X_OP_ON_SPHERE, eigengrasps.RESET_AMPLITUDES)
    assert e_conform < sphere_planner.evaluate(open_hand)
    # A state through the object is illegal.
    inside = search_space.state_from_palm_pose(RigidTransform(X_OP_ON_SPHERE.rotation(), [0, 0, 0.02]))
    assert sphere_planner.evaluate(inside) is None


# --- The planner. ---------------------------------------------------------------------------------

def test_best_list_merges_close_states_and_keeps_twenty():
    best = []

    def entry(energy_, x):
        s = list(search_space.RESET_STATE)
        s[search_space.TX] = x
        return (energy_, s, 0, search_space.palm_position_and_quaternion(s))

    _add_unique(best, entry(5.0, 0.0), 0.1)
    _add_unique(best, entry(6.0, 0.01), 0.1)  # within 0.2 * 0.1 m of a better state: not added
    assert [e[0] for e in best] == [5.0]
    _add_unique(best, entry(4.0, 0.01), 0.1)  # better: replaces it
    assert [(e[0], e[1][0]) for e in best] == [(4.0, 0.01)]
    for i in range(30):
        _add_unique(best, entry(10.0 + i, 0.1 * (i + 1)), 0.1)
    assert len(best) == annealing.BEST_LIST_SIZE
    assert [e[0] for e in best] == sorted(e[0] for e in best)


def test_planning_a_sphere_finds_grasps_touching_with_all_three_fingers(sphere_planner):
    plan = sphere_planner.plan(max_steps=annealing.K0 + 1500, seed=1)
    assert plan.iterations == 1500
    assert len(plan.grasps) == 3
    assert len(plan.candidates) <= annealing.BEST_LIST_SIZE
    epsilons = [g.epsilon for g in plan.candidates]
    assert epsilons == sorted(epsilons, reverse=True)
    for g in plan.grasps:
        assert g.fingers_touching == [1, 2, 3]
        # Autograsp closes from the planned posture, in place, with the spread fixed.
        assert g.X_OH.IsNearlyEqualTo(search_space.hand_pose(g.state), 1e-12)
        assert g.joint_angles[0] == g.pregrasp_joint_angles[0]
        assert np.all(g.joint_angles[2:] >= g.pregrasp_joint_angles[2:] - 1e-12)


def test_same_seed_same_plan(sphere_planner):
    a = sphere_planner.anneal(annealing.K0 + 400, seed=5)
    b = sphere_planner.anneal(annealing.K0 + 400, seed=5)
    c = sphere_planner.anneal(annealing.K0 + 400, seed=6)
    assert [(e, s, k) for e, s, k in a["best"]] == [(e, s, k) for e, s, k in b["best"]]
    assert a["evaluations"] == b["evaluations"]
    assert [s for _, s, _ in a["best"]] != [s for _, s, _ in c["best"]]


def test_contact_quality_energy_plans(sphere_planner):
    planner = EigengraspPlanner(sphere_planner.spec, "contact-quality")
    result = planner.anneal(annealing.K0 + 300, seed=0)
    assert result["iterations"] == 300 and result["best"]
    with pytest.raises(ValueError, match="unknown energy"):
        EigengraspPlanner(sphere_planner.spec, "hand+object")
    with pytest.raises(ValueError, match="30000"):
        planner.anneal(annealing.K0)


# --- Command line. --------------------------------------------------------------------------------

def test_cli_prints_and_writes_the_plan(capsys, tmp_path):
    assert cli.main(["plan-eigengrasp", "--object", "sphere:0.1", "--steps", "30300", "--seed", "2",
                     "--json", "--out", str(tmp_path)]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["iterations"] == 300 and record["first_step"] == 30000
    assert len(record["grasps"]) == 3
    for g in record["grasps"]:
        assert {"position_mm", "axis", "angle_rad", "pregrasp_joint_angles", "energy", "epsilon"} <= set(g)
    files = list(tmp_path.glob("eigengrasp_*.json"))
    assert len(files) == 1 and json.loads(files[0].read_text())["grasps"] == record["grasps"]
    assert cli.main(["plan-eigengrasp", "--object", "sphere:0.1", "--steps", "30100"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("plan-eigengrasp") and out[-1].startswith("planning time")
    assert len(out) == 5


@pytest.mark.parametrize("args, message", [
    (["--object", "no_such_object"], "unknown object"),
    (["--object", "sphere:0.1", "--steps", "nan"], "--steps"),
    (["--object", "sphere:0.1", "--steps", "-70000"], "--steps"),
    (["--object", "sphere:0.1", "--steps", "0"], "--steps"),
    (["--object", "sphere:0.1", "--energy", "hand+object"], "--energy"),
])
def test_cli_bad_input_is_one_line_and_exit_2(capsys, args, message):
    assert cli.main(["plan-eigengrasp", *args]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and message in err


def test_planning_with_the_table_keeps_the_hand_above_it():
    from baselines.eigengrasp.planner import plan_eigengrasp
    from drake_grasp.objects import paper_object
    from drake_grasp.quasistatic import QuasiStaticHand

    spec = paper_object("sponge")
    plan = plan_eigengrasp(spec, max_steps=32_000, seed=1, table=True)
    check = QuasiStaticHand(spec, table=True)
    for grasp in plan.grasps:
        check.set_hand(grasp.X_OH, grasp.pregrasp_joint_angles)
        assert check.hand_distance()[0] >= 0.0
