"""Files users bring that are not read here are refused in one line that says what to give instead
(drake_grasp.objects.other_formats), before any work, with exit code 2."""

import pytest

from drake_grasp import cli
from drake_grasp.objects.other_formats import advice


@pytest.mark.parametrize("name, words", [
    ("arm.urdf.xacro", "xacro FILE > object.urdf"),
    ("part.STEP", "a CAD file (STEP)"),
    ("mug.skp", "a SketchUp model"),
    ("scene.blend", "a Blender file"),
    ("cloud.pcd", "reconstruct a surface"),
])
def test_each_format_names_what_to_give_instead(tmp_path, capsys, name, words):
    path = tmp_path / name
    path.write_bytes(b"not a mesh\n")
    assert words in advice(path)
    assert cli.main(["trial", "--object", str(path), "--method", "compliant"]) == 2
    err = capsys.readouterr().err
    assert words in err and err.strip().count("\n") == 0 and "Traceback" not in err


def test_formats_read_here_have_no_advice():
    assert advice("mug.obj") is None and advice("mug.3mf") is None and advice("model.urdf") is None
