"""The hand tools' generator (drake_grasp.objects.tools): hammers, screwdrivers, clamps, markers and
wrenches lying down, as meshes and as URDFs with their parts' real masses, loaded as a user's file is."""

import json
import warnings

import numpy as np
import pytest
import trimesh

from drake_grasp import cli, objects
from drake_grasp.objects import tools


def test_same_seed_gives_byte_identical_files_whatever_the_count(tmp_path):
    a, b = tools.generate(7, 3, tmp_path / "a"), tools.generate(2, 3, tmp_path / "b")
    for row in b:
        for name in [row["file"], *row["assets"]]:
            assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    other = tools.generate(1, 4, tmp_path / "c")[0]
    assert (tmp_path / "c" / other["file"]).read_bytes() != (tmp_path / "a" / a[0]["file"]).read_bytes()


def test_tools_are_closed_solids_lying_low_on_the_table(tmp_path):
    rows = tools.generate(10, 1, tmp_path)
    assert json.loads((tmp_path / "manifest.json").read_text()) == rows
    assert [r["class"] for r in rows] == list(tools.CLASSES) * 2
    assert [r["format"] for r in rows] == ["mesh"] * 5 + ["urdf"] * 5
    for row in rows:
        mesh = trimesh.load(tmp_path / (row["assets"][0] if row["assets"] else row["file"]), process=True)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0, row["file"]
        assert mesh.bounds[0, 2] == pytest.approx(0.0, abs=1e-6)
        assert np.allclose(mesh.bounds[:, :2].sum(axis=0), 0.0, atol=1e-5)  # centred in x and y
        length = max(mesh.extents[:2])
        # Lying down: low and long (the longest side 7-32 cm, at most 5.5 cm tall: a fat handle and a tilt).
        assert 0.07 <= length <= 0.32 and mesh.extents[2] <= 0.055 and mesh.extents[2] < 0.4 * length, row["file"]


def test_resting_face_is_stable_and_lowest():
    """A 10 × 4 × 2 cm box set down on its end comes to rest on its largest face (its centre of mass
    lowest), whatever face it was generated on."""
    box = trimesh.creation.box(extents=[0.02, 0.04, 0.10])
    box.apply_transform(tools.resting_transform(box, box.center_mass))
    assert sorted(np.round(box.extents, 6)) == [0.02, 0.04, 0.10] and box.extents[2] == pytest.approx(0.02)


def test_a_hammer_s_mass_lies_towards_its_head_and_the_urdf_keeps_it(tmp_path):
    row = next(r for r in tools.generate(6, 2, tmp_path) if r["format"] == "urdf" and r["class"] == "hammer")
    with warnings.catch_warnings():
        warnings.simplefilter("error", objects.InertiaWarning)  # a plausible inertia: no warning, no replacement
        spec = objects.resolve_object(str(tmp_path / row["file"]))
    assert spec.mass == pytest.approx(row["mass_kg"], rel=1e-4)
    assert row["mass_kg"] > 1.5 * tools.HANDLE_DENSITY[1] * row["volume_m3"]  # the steel head weighs
    mesh = trimesh.load(tmp_path / row["assets"][0])
    com = np.array([float(v) for v in (tmp_path / row["file"]).read_text().split('origin xyz="')[1].split('"')[0].split()])
    # The centre of mass is nearer the head's end than the mesh's uniform centroid is.
    axis = np.linalg.svd(mesh.vertices[:, :2] - mesh.vertices[:, :2].mean(axis=0))[2][0]
    ends = sorted(mesh.vertices[:, :2] @ axis)
    along = lambda p: (p[:2] @ axis - ends[0]) / (ends[-1] - ends[0])  # noqa: E731
    assert abs(along(com) - 0.5) > abs(along(mesh.center_mass) - 0.5) + 0.05


def test_cli_generates_tools(tmp_path, capsys):
    assert cli.main(["objects", "generate", "--kind", "tools", "--count", "5", "--seed", "4",
                     "--out", str(tmp_path)]) == 0
    assert "5 tools objects (clamp, hammer, marker, screwdriver, wrench)" in capsys.readouterr().out
    assert len(list(tmp_path.glob("*.obj"))) == 5 and not list(tmp_path.glob("*.urdf"))
