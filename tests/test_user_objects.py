"""Honest physics and units for a user's mesh: the enclosed solid (drake_grasp.objects.solid),
separate components, --scale, the size refusal and units warning, simplification, and spheres that do
not tip."""

import time
import warnings

import pytest
import trimesh

from drake_grasp import cli, objects
from drake_grasp.file_formats import MESH_FORMATS
from drake_grasp.objects import solid


def _two_boxes(offset):
    a = trimesh.creation.box((0.06, 0.06, 0.03))
    b = trimesh.creation.box((0.06, 0.06, 0.03))
    b.apply_translation([offset, 0.0, 0.0])
    return trimesh.util.concatenate([a, b])


def test_overlapping_shells_are_one_solid_with_the_union_s_mass(tmp_path):
    path = tmp_path / "overlap.stl"
    _two_boxes(0.03).export(path)  # two 6x6x3 cm boxes, one moved 3 cm: a 9x6x3 cm box
    assert trimesh.load(path).volume == pytest.approx(216e-6)  # what summing the shells counts
    spec = objects.object_from_mesh(path)
    true = trimesh.creation.box((0.09, 0.06, 0.03))
    assert spec.volume == pytest.approx(162e-6, rel=1e-5)
    assert spec.mass == pytest.approx(objects.DEFAULT_DENSITY * 162e-6, rel=1e-5)  # 0.0324 kg, not 0.0432
    expected = true.moment_inertia / true.mass * spec.mass
    assert spec.inertia_matrix() == pytest.approx(expected, rel=1e-4, abs=1e-12)


def test_separate_components_are_an_error_unless_the_largest_is_kept(tmp_path):
    path = tmp_path / "apart.stl"
    parts = _two_boxes(0.2)
    parts = trimesh.util.concatenate([parts, trimesh.creation.box((0.02, 0.02, 0.02)).apply_translation([0, 0.2, 0])])
    parts.export(path)
    # The boxes are 14 cm apart, the cube 16 cm from the first box: the smallest gap is named.
    with pytest.raises(objects.ObjectError,
                       match=r"apart.stl: 3 separate parts farther apart than the join gap \(5.2 mm; the smallest "
                             r"gap is 140.0 mm\)"):
        objects.object_from_mesh(path)
    kept = objects.object_from_mesh(path, largest_component=True)
    assert kept.volume == pytest.approx(108e-6, rel=1e-5)
    assert len(solid.solid_of_shells([trimesh.creation.box((0.1, 0.1, 0.1))]).components) == 1
    # A join gap wider than the gaps makes them one object (mass from the three solids).
    joined = objects.object_from_mesh(path, join_gap=0.17)
    assert joined.volume == pytest.approx(2 * 108e-6 + 8e-6, rel=1e-5)


def test_a_box_in_millimetres_is_refused_and_scale_fixes_it(tmp_path):
    path = tmp_path / "box_mm.stl"
    trimesh.creation.box((100.0, 60.0, 40.0)).export(path)
    with pytest.raises(objects.ObjectError, match=r"largest extent 100 m: more than the 50 cm a grasp here can take "
                                                  r".*is the file in millimetres \(--scale 0.001\)\?"):
        objects.object_from_mesh(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error", objects.UnitsWarning)
        spec = objects.object_from_mesh(path, scale=0.001)
    assert spec.extents == pytest.approx((0.1, 0.06, 0.04))
    tiny = tmp_path / "tiny.stl"
    trimesh.creation.box((0.005, 0.004, 0.003)).export(tiny)
    with pytest.warns(objects.UnitsWarning, match=r"largest extent 5 mm"):
        objects.object_from_mesh(tiny)


@pytest.mark.parametrize("sphere", [trimesh.creation.icosphere(subdivisions=3, radius=0.05),
                                    trimesh.creation.uv_sphere(radius=0.05)])
def test_a_sphere_mesh_does_not_warn_that_it_would_tip(tmp_path, sphere):
    path = tmp_path / "ball.stl"
    sphere.export(path)
    with warnings.catch_warnings():
        warnings.simplefilter("error", objects.UnstablePoseWarning)
        spec = objects.object_from_mesh(path)
    assert spec.rpy_TO == (0.0, 0.0, 0.0)


def test_a_dense_mesh_is_simplified_with_a_note_and_keeps_its_mass(tmp_path):
    path = tmp_path / "dense.stl"
    dense = trimesh.creation.icosphere(subdivisions=6, radius=0.05)  # 81,920 faces
    dense.export(path)
    start = time.perf_counter()
    with pytest.warns(objects.MeshNote, match=r"81,920 faces; simplifying to 20,000"):
        spec = objects.object_from_mesh(path)
    assert time.perf_counter() - start < 60.0
    assert spec.mass == pytest.approx(objects.DEFAULT_DENSITY * dense.volume, rel=1e-6)  # from the full mesh
    assert len(spec.pieces) == 1


def test_cli_scale_is_for_object_files_only(tmp_path, capsys):
    assert cli.main(["trial", "--object", "cube:0.05", "--scale", "0.001", "--oracle"]) == 2
    assert capsys.readouterr().err.strip().splitlines() == [
        f"drake-grasp trial: error: cube:0.05: --scale applies to mesh files ({MESH_FORMATS}) and model files (SDF, URDF, MJCF) only"]
    assert "OpenUSD" in MESH_FORMATS and "3MF" in MESH_FORMATS  # the formats the readers take are named
    path = tmp_path / "box.stl"
    trimesh.creation.box((0.1, 0.06, 0.04)).export(path)
    assert cli.main(["resemble", "--object", str(path), "--scale", "-1"]) == 2
    assert capsys.readouterr().err.strip().splitlines() == ["drake-grasp resemble: error: --scale must be positive, got -1.0"]
    apart = tmp_path / "apart.stl"
    _two_boxes(0.2).export(apart)
    assert cli.main(["plan-eigengrasp", "--object", str(apart)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "2 separate parts farther apart than the join gap" in err[0]
