"""Opening pinched edges (drake_grasp.objects.edge_pairing): solids that meet along an edge."""

import numpy as np
import pytest
import trimesh

from drake_grasp.objects import repair, solid
from drake_grasp.objects.edge_pairing import open_pinched_edges

EDGE = 0.03


def _welded(meshes) -> trimesh.Trimesh:
    mesh = trimesh.util.concatenate(meshes)
    mesh.merge_vertices()
    return mesh


def _cube(cell) -> trimesh.Trimesh:
    return trimesh.creation.box([EDGE] * 3).apply_translation(EDGE * np.asarray(cell, float))


def test_two_cubes_meeting_along_an_edge_open_into_two_closed_cubes():
    mesh = _welded([_cube((0, 0, 0)), _cube((1, 1, 0))])
    assert not mesh.is_watertight  # the shared edge has four faces
    vertices, faces, opened = open_pinched_edges(mesh.vertices, mesh.faces)
    assert opened == 1
    assert len(faces) == len(mesh.faces) and len(vertices) == len(mesh.vertices) + 2  # the edge's two ends copied
    result = trimesh.Trimesh(vertices, faces, process=False)
    assert result.is_watertight and result.is_winding_consistent
    assert result.volume == pytest.approx(2 * EDGE**3, rel=1e-9)
    assert len(result.split(only_watertight=True)) == 2


def test_a_polycube_pinched_along_an_edge_is_one_closed_shell_with_its_volume():
    # Six cells; the top two touch each other along one vertical edge only. Their union, written as
    # STL (no shared vertices), is what an exporter leaves.
    cells = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (2, 1, 0), (1, 1, 1), (0, 0, 1)]
    union = trimesh.boolean.union([_cube(c) for c in cells])
    soup = trimesh.load(trimesh.util.wrap_as_stream(union.export(file_type="stl")), file_type="stl", process=False)
    shells, report = repair.closed_shells(soup, "polycube")
    assert report.non_manifold_edges == 1 and report.open_edges == 0 and report.dropped_faces == 0
    assert len(shells) == 1 and shells[0].is_watertight
    assert shells[0].volume == pytest.approx(6 * EDGE**3, rel=1e-6)


def test_cells_of_a_soup_that_share_faces_and_edges_keep_their_exact_volume():
    # Each cube a closed box of its own; the shared faces' triangles need not match, so no wall pairs
    # up as a duplicate: every edge around a shared face has four faces, two coplanar.
    cells = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 1), (0, 0, 1)]
    soup = trimesh.util.concatenate([_cube(c) for c in cells])
    shells, report = repair.closed_shells(soup, "soup")
    assert report.open_edges == 0 and report.dropped_faces == 0
    result = solid.solid_of_shells(shells)
    assert len(result.components) == 1
    assert sum(s.volume for s in shells) == pytest.approx(5 * EDGE**3, rel=1e-6)


def test_a_fin_and_an_inconsistently_wound_pinch_are_left_alone():
    # A fin: an edge of three faces.
    cube = _cube((0, 0, 0))
    a, b = cube.edges_unique[0]
    tip = cube.vertices[[a, b]].mean(axis=0) * 2.0
    vertices = np.vstack([cube.vertices, tip])
    faces = np.vstack([cube.faces, [[a, b, len(vertices) - 1]]])
    out_vertices, out_faces, opened = open_pinched_edges(vertices, faces)
    assert opened == 0 and out_faces is not None and len(out_vertices) == len(vertices)
    # Two cubes along an edge, one of them wound inside out against the other's faces at that edge:
    # the faces around the edge no longer alternate solid / empty, so no pairing is guessed.
    mesh = _welded([_cube((0, 0, 0)), _cube((1, 1, 0))])
    faces = mesh.faces.copy()
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    pinch = unique[counts == 4][0]
    at_pinch = np.flatnonzero(np.isin(faces, pinch).sum(axis=1) == 2)
    faces[at_pinch[0]] = faces[at_pinch[0]][::-1]
    _, _, opened = open_pinched_edges(mesh.vertices, faces)
    assert opened == 0


def test_a_manifold_mesh_comes_back_unchanged():
    sphere = trimesh.creation.icosphere(subdivisions=2)
    vertices, faces, opened = open_pinched_edges(sphere.vertices, sphere.faces)
    assert opened == 0 and np.array_equal(faces, sphere.faces) and np.array_equal(vertices, sphere.vertices)


def test_a_voxel_soup_opens_into_closed_cells_of_its_exact_volume():
    # 8 x 8 x 3 cells, about 60 % present, each a closed cube of its own (as a voxel exporter writes a
    # soup): edges of four, six and eight faces, faces shared in one plane with other triangulations.
    rng = np.random.default_rng(3)
    cells = [(i, j, k) for i in range(8) for j in range(8) for k in range(3) if rng.random() < 0.6]
    mesh = _welded([_cube(c) for c in cells])
    vertices, faces, opened = open_pinched_edges(mesh.vertices, mesh.faces)
    result = trimesh.Trimesh(vertices, faces, process=False)
    assert opened > len(cells) and result.is_watertight and result.is_winding_consistent
    assert result.volume == pytest.approx(len(cells) * EDGE**3, rel=1e-9)
