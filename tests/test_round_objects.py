"""The low round objects' generator (drake_grasp.objects.round): fruit and balls 4-11 cm, as meshes and as
URDFs with a real mass, loaded the way a user's file is."""

import json
import warnings

import pytest
import trimesh

from drake_grasp import cli, objects
from drake_grasp.objects import round as round_objects


def test_same_seed_gives_byte_identical_files_whatever_the_count(tmp_path):
    a, b = round_objects.generate(6, 3, tmp_path / "a"), round_objects.generate(3, 3, tmp_path / "b")
    for row in b:
        for name in [row["file"], *row["assets"]]:
            assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    other = round_objects.generate(1, 4, tmp_path / "c")[0]
    assert (tmp_path / "c" / other["file"]).read_bytes() != (tmp_path / "a" / a[0]["file"]).read_bytes()


def test_low_round_closed_solids_resting_on_the_table(tmp_path):
    rows = round_objects.generate(8, 1, tmp_path)
    assert json.loads((tmp_path / "manifest.json").read_text()) == rows
    assert [r["format"] for r in rows] == ["mesh", "urdf"] * 4
    for row in rows:
        mesh = trimesh.load(tmp_path / (row["assets"][0] if row["assets"] else row["file"]), process=True)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0, row["file"]
        assert mesh.bounds[0, 2] == pytest.approx(0.0, abs=1e-6)
        width, depth, height = sorted(mesh.extents[:2])[::-1] + [mesh.extents[2]]
        assert 0.04 * 0.94 <= width <= 0.11 * 1.4 * 1.06 and height <= width * 1.06, row["file"]
        assert mesh.volume > 0.6 * mesh.convex_hull.volume  # round: no hollow, a few lumps


def test_a_urdf_s_real_mass_and_inertia_are_kept(tmp_path):
    row = next(r for r in round_objects.generate(4, 2, tmp_path) if r["format"] == "urdf")
    with warnings.catch_warnings():
        warnings.simplefilter("error", objects.InertiaWarning)  # a plausible inertia: no warning, no replacement
        spec = objects.resolve_object(str(tmp_path / row["file"]))
    assert spec.mass == pytest.approx(row["mass_kg"], rel=1e-4)
    density = row["mass_kg"] / row["volume_m3"]
    assert round_objects.DENSITY_RANGE[0] <= density <= round_objects.DENSITY_RANGE[1]
    mesh = trimesh.load(tmp_path / row["assets"][0])
    expected = mesh.moment_inertia * (row["mass_kg"] / mesh.volume)  # kg·m², about the centre of mass
    assert spec.inertia_matrix() == pytest.approx(expected, rel=1e-2, abs=1e-9)


def test_cli_generates_round_objects(tmp_path, capsys):
    assert cli.main(["objects", "generate", "--kind", "round", "--count", "2", "--seed", "4",
                     "--out", str(tmp_path)]) == 0
    assert "2 round objects (round)" in capsys.readouterr().out
    assert len(list(tmp_path.glob("*.obj"))) == 2 and len(list(tmp_path.glob("*.urdf"))) == 1
