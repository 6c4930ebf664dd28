"""The standing objects' generator (drake_grasp.objects.standing): pegs, pencils, markers, vials and sticks
on their end, as meshes and as URDFs with a real mass; and the slender resemblance they are made for."""

import json

import numpy as np
import pytest
import trimesh

from drake_grasp import cli
from drake_grasp.objects import standing
from drake_grasp.primitives.upright import SLENDER_SPAN, slender_resemblance


def test_same_seed_gives_byte_identical_files_whatever_the_count(tmp_path):
    standing.generate(7, 3, tmp_path / "a")
    for row in standing.generate(2, 3, tmp_path / "b"):
        for name in [row["file"], *row["assets"]]:
            assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()


def test_standing_objects_are_closed_slender_solids_on_their_end(tmp_path):
    rows = standing.generate(20, 1, tmp_path)
    assert json.loads((tmp_path / "manifest.json").read_text()) == rows
    assert [r["class"] for r in rows] == list(standing.CLASSES) * 4
    assert [r["format"] for r in rows] == (["mesh"] * 5 + ["urdf"] * 5) * 2
    slender = 0
    for row in rows:
        mesh = trimesh.load(tmp_path / (row["assets"][0] if row["assets"] else row["file"]), process=True)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.volume > 0, row["file"]
        assert mesh.bounds[0, 2] == pytest.approx(0.0, abs=1e-6)
        footprint, height = mesh.extents[:2], mesh.extents[2]
        assert 0.06 <= height <= 0.19 and max(footprint) <= 0.045 and height >= 1.8 * max(footprint), row["file"]
        slender += slender_resemblance(height, footprint) >= 0.5
    assert 0 < slender < len(rows)  # both sides of the rule's 3.2 cm: pegs and sticks reach past it


def test_the_slender_step_lies_between_the_wrap_s_misses_and_the_pinch_s_reach():
    from drake_grasp.grasps import PINCH_MAX_LENGTH

    assert 0.027 < SLENDER_SPAN < PINCH_MAX_LENGTH  # F1 and F2's pads start 13.5 mm out; the pinch takes < 35 mm
    assert slender_resemblance(0.12, [0.026, 0.026]) > 0.99 and slender_resemblance(0.12, [0.035, 0.036]) < 0.1
    # The step is in the footprint's shorter side: thin one way is enough (a sauce bottle, a juice box).
    assert slender_resemblance(0.12, [0.03, 0.05]) > 0.8
    assert slender_resemblance(0.12, [SLENDER_SPAN, 0.05]) == pytest.approx(0.5, abs=0.01)


def test_cli_generates_standing_objects(tmp_path, capsys):
    assert cli.main(["objects", "generate", "--kind", "standing", "--count", "5", "--seed", "2", "--out",
                     str(tmp_path)]) == 0
    assert "5 standing objects (marker, peg, pencil, stick, vial)" in capsys.readouterr().out
