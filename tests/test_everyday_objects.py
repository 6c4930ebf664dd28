"""The everyday-object generator (drake_grasp.objects.everyday): polycubes, scans, mugs, bottles and
boxes, as meshes and as URDFs with a placeholder inertia, loaded the way a user's file is."""

import json

import numpy as np
import pytest
import trimesh

from drake_grasp import cli, objects
from drake_grasp.objects import everyday


def test_same_seed_gives_byte_identical_files_whatever_the_count(tmp_path):
    a, b = everyday.generate(10, 3, tmp_path / "a"), everyday.generate(4, 3, tmp_path / "b")
    for row in b:
        for name in [row["file"], *row["assets"]]:
            assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    other = everyday.generate(1, 4, tmp_path / "c")[0]
    assert (tmp_path / "c" / other["file"]).read_bytes() != (tmp_path / "a" / a[0]["file"]).read_bytes()


def test_every_class_in_both_formats_is_a_resting_closed_solid(tmp_path):
    rows = everyday.generate(2 * len(everyday.CLASSES), 1, tmp_path)
    assert json.loads((tmp_path / "manifest.json").read_text()) == rows
    assert {(r["class"], r["format"]) for r in rows} == {(c, f) for c in everyday.CLASSES for f in everyday.FORMATS}
    for row in rows:
        mesh_file = row["assets"][0] if row["format"] == "urdf" else row["file"]
        mesh = trimesh.load(tmp_path / mesh_file, process=True)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0, row["file"]
        assert mesh.bounds[0, 2] == pytest.approx(0.0, abs=1e-6)  # it rests on z = 0
        assert 0.03 <= max(mesh.extents) <= 0.25, row["file"]
    mugs = [r for r in rows if r["class"] == "mug"]
    hull = trimesh.load(tmp_path / mugs[0]["file"]).convex_hull.volume
    assert mugs[0]["volume_m3"] < 0.5 * hull  # hollow, not a cylinder


def test_polycubes_are_cells_and_boxes_fit_the_hand():
    for index in range(0, 200, len(everyday.CLASSES)):
        _, shape_class, mesh = everyday.everyday_object(7, index)
        assert shape_class == "polycube"
        up = np.abs(mesh.face_normals[:, 2])
        slanted = (up > 0.01) & (up < 0.99)  # only slivers from rounding to µm: cells, turned about z
        assert mesh.area_faces[slanted].sum() < 1e-4 * mesh.area
        _, _, box = everyday.everyday_object(7, index + 4)
        sides = sorted(box.bounding_box_oriented.primitive.extents)
        assert min(sides) <= everyday.HAND_SPAN + 1e-6


def test_a_urdf_with_a_placeholder_inertia_loads_with_the_geometry_s(tmp_path):
    row = next(r for r in everyday.generate(10, 2, tmp_path) if r["format"] == "urdf" and r["class"] == "box")
    with pytest.warns(objects.InertiaWarning, match="implausible inertia in the file"):
        spec = objects.resolve_object(str(tmp_path / row["file"]))
    assert spec.volume == pytest.approx(row["volume_m3"], rel=1e-3)
    assert spec.mass == pytest.approx(1.0)  # the file's mass is kept; its unit inertia matrix is not
    mesh = trimesh.load(tmp_path / row["assets"][0])
    expected = mesh.moment_inertia / mesh.mass  # per kg, about the centre of mass
    assert spec.inertia_matrix() == pytest.approx(expected, rel=1e-2, abs=1e-9)


def test_cli_generates_everyday_objects(tmp_path, capsys):
    assert cli.main(["objects", "generate", "--kind", "everyday", "--count", "5", "--seed", "4",
                     "--out", str(tmp_path)]) == 0
    assert "5 everyday objects (bottle, box, mug, polycube, scan)" in capsys.readouterr().out
    assert len(list(tmp_path.glob("*.obj"))) == 5
