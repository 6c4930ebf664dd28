"""The novel-object generator (drake_grasp.objects.novel) and `drake-grasp objects generate`."""

import json

import numpy as np
import pytest
import trimesh

from drake_grasp import cli
from drake_grasp.objects import novel


def test_same_seed_gives_byte_identical_files(tmp_path):
    a, b, c = tmp_path / "a", tmp_path / "b", tmp_path / "c"
    novel.generate(8, 5, a)
    novel.generate(8, 5, b)
    novel.generate(8, 6, c)
    names = sorted(p.name for p in a.iterdir())
    assert names == sorted(p.name for p in b.iterdir()) and "manifest.json" in names and "manifest.csv" in names
    for name in names:
        assert (a / name).read_bytes() == (b / name).read_bytes()
    different = [n for n in names if n.endswith(".obj")]
    assert all((a / n).read_bytes() != (c / n.replace("_5_", "_6_")).read_bytes() for n in different)
    # An object depends on (seed, index) only, not on how many were generated.
    for row in novel.generate(3, 5, tmp_path / "d"):
        assert (tmp_path / "d" / row["file"]).read_bytes() == (a / row["file"]).read_bytes()


def test_every_class_is_watertight_in_size_and_listed(tmp_path):
    rows = novel.generate(len(novel.CLASSES) * 2, 1, tmp_path)
    assert {r["class"] for r in rows} == set(novel.CLASSES)
    assert json.loads((tmp_path / "manifest.json").read_text()) == rows
    for row in rows:
        mesh = trimesh.load(tmp_path / row["file"], process=True)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0, row["file"]
        assert novel.SIZE_RANGE[0] - 1e-6 <= np.max(mesh.extents) <= novel.SIZE_RANGE[1] + 1e-6
        assert mesh.volume == pytest.approx(row["volume_m3"], rel=1e-5)
    non_convex = [r["class"] for r in rows if not r["convex"]]
    assert {"union", "L", "T", "ring", "handle"} <= set(non_convex)


def test_cli_generate_and_bad_count(tmp_path, capsys):
    assert cli.main(["objects", "generate", "--count", "2", "--seed", "4", "--out", str(tmp_path)]) == 0
    assert len(list(tmp_path.glob("*.obj"))) == 2
    assert cli.main(["objects", "generate", "--count", "0", "--out", str(tmp_path)]) == 2
    assert capsys.readouterr().err.strip().splitlines() == [
        "drake-grasp objects: error: --count must be >= 1, got 0"]
