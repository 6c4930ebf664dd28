"""The vertex budget of decomposed pieces (drake_grasp/piece_budget.py)."""

import numpy as np
import pytest
import trimesh
from scipy.spatial import ConvexHull

from drake_grasp import objects
from drake_grasp.objects import piece_budget
from drake_grasp.objects.piece_budget import hull_deviations, simplify_hull


def _is_subset(rows, of):
    return all(np.any(np.all(of == row, axis=1)) for row in rows)


def test_a_fine_sphere_keeps_its_budget_of_vertices_inside_and_close():
    points = trimesh.creation.icosphere(subdivisions=4, radius=0.05).vertices  # 2,562 vertices
    kept = simplify_hull(points, max_vertices=64)
    assert len(kept) == 64 and _is_subset(kept, points)
    # Greedy farthest-point: within 3 mm of a 5 cm sphere, about 1 mm from the sag of its
    # 64-vertex tessellation (a random subset of 64 is several times worse).
    deviation = hull_deviations(points, kept).max()
    assert 0.0 < deviation < 0.003
    random_subset = points[np.random.default_rng(0).choice(len(points), 64, replace=False)]
    assert hull_deviations(points, random_subset).max() > 2.0 * deviation
    # A larger budget is closer; the tolerance stops it early.
    finer = simplify_hull(points, max_vertices=400, tolerance=0.001)
    assert 64 < len(finer) < 400
    assert hull_deviations(points, finer).max() <= 0.001


def test_a_hull_within_the_budget_is_kept_whole():
    box = trimesh.creation.box((0.1, 0.05, 0.02))
    points = np.vstack([box.vertices, box.sample(200, seed=0) * 0.5])  # corners and inner points
    kept = simplify_hull(points)
    assert len(kept) == 8
    assert ConvexHull(kept).volume == pytest.approx(1e-4, rel=1e-9)


def test_budget_needs_a_tetrahedron():
    with pytest.raises(ValueError):
        simplify_hull(np.eye(3), max_vertices=3)


@pytest.mark.filterwarnings("ignore:.*would tip over")
def test_mesh_pieces_are_within_the_budget(tmp_path):
    path = tmp_path / "ball.stl"
    trimesh.creation.icosphere(subdivisions=4, radius=0.05).export(path)
    spec = objects.object_from_mesh(path)
    (piece,) = spec.pieces
    assert len(objects._convex_vertices(piece.mesh_path)) <= piece_budget.MAX_PIECE_VERTICES
