"""OpenUSD stages as Isaac Sim and Omniverse ship objects, read in metres with z up
(drake_grasp.objects.usd_mesh); without the optional usd-core, one line that says how to read them."""

import importlib.util

import numpy as np
import pytest

from drake_grasp import cli
from drake_grasp.objects.spec import ObjectError
from drake_grasp.objects.usd_mesh import read_usd

HAS_USD = importlib.util.find_spec("pxr") is not None

# A 10 × 4 × 6 cm box as a Mesh of quads in centimetres, Y up, moved 1 m along x; and beside it a
# cylinder of radius 2 and height 8 along Y, guide purpose (left out).
STAGE = """#usda 1.0
(
    metersPerUnit = 0.01
    upAxis = "Y"
)

def Xform "object"
{
    double3 xformOp:translate = (100, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]

    def Mesh "box"
    {
        int[] faceVertexCounts = [4, 4, 4, 4, 4, 4]
        int[] faceVertexIndices = [0, 1, 3, 2, 4, 6, 7, 5, 0, 4, 5, 1, 2, 3, 7, 6, 0, 2, 6, 4, 1, 5, 7, 3]
        point3f[] points = [(-5, -3, -2), (-5, -3, 2), (-5, 3, -2), (-5, 3, 2), (5, -3, -2), (5, -3, 2), (5, 3, -2), (5, 3, 2)]
    }

    def Cylinder "handle_guide"
    {
        uniform token purpose = "guide"
        double radius = 2
        double height = 8
        uniform token axis = "Y"
    }
}
"""


@pytest.mark.skipif(not HAS_USD, reason="the optional usd-core is not installed")
def test_a_y_up_stage_in_centimetres_comes_in_metres_with_z_up(tmp_path):
    path = tmp_path / "box.usda"
    path.write_text(STAGE)
    vertices, faces = read_usd(path, "box.usda")
    assert faces.shape == (12, 3)  # the box's six quads; the guide cylinder is left out
    np.testing.assert_allclose(np.ptp(vertices, axis=0), [0.10, 0.04, 0.06], atol=1e-9)  # y (6 cm) is now z
    np.testing.assert_allclose(vertices.mean(axis=0), [1.0, 0.0, 0.0], atol=1e-9)


@pytest.mark.skipif(not HAS_USD, reason="the optional usd-core is not installed")
def test_a_usd_object_loads_as_a_users_object(tmp_path, capsys):
    path = tmp_path / "box.usda"
    path.write_text(STAGE)
    assert cli.main(["objects", "check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "accepted" in out and "size 10.0 x 4.0 x 6.0 cm" in out and "volume 240.0 cm³" in out


@pytest.mark.skipif(not HAS_USD, reason="the optional usd-core is not installed")
def test_a_damaged_stage_is_one_line(tmp_path):
    path = tmp_path / "bad.usda"
    path.write_text("#usda 1.0\ndef Mesh \"m\" {\n  point3f[] points = [(0, 0\n")
    with pytest.raises(ObjectError) as raised:
        read_usd(path, "bad.usda")
    assert str(raised.value).startswith("bad.usda: USD could not open it") and "\n" not in str(raised.value)


@pytest.mark.skipif(HAS_USD, reason="usd-core is installed")
def test_without_usd_core_a_usd_file_is_one_line_naming_it(tmp_path, capsys):
    path = tmp_path / "box.usda"
    path.write_text(STAGE)
    assert cli.main(["objects", "check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "pip install usd-core" in err and err.strip().count("\n") == 0


@pytest.mark.skipif(not HAS_USD, reason="the optional usd-core is not installed")
def test_meshes_inside_an_instance_are_read(tmp_path):
    """Isaac Sim's assets make their meshes instanceable: the cube is inside an instance of an
    abstract prototype (a class, not drawn itself), moved 0.5 m along x; metres, z up."""
    path = tmp_path / "instanced.usda"
    path.write_text('#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = "Z"\n)\n\n'
                    'class Xform "prototype"\n{\n    def Cube "cube"\n    {\n        double size = 0.04\n    }\n}\n\n'
                    'def Xform "object" (\n    instanceable = true\n    references = </prototype>\n)\n{\n'
                    '    double3 xformOp:translate = (0.5, 0, 0)\n'
                    '    uniform token[] xformOpOrder = ["xformOp:translate"]\n}\n')
    vertices, faces = read_usd(path, "instanced.usda")
    assert len(faces) == 12
    np.testing.assert_allclose(np.ptp(vertices, axis=0), [0.04, 0.04, 0.04], atol=1e-9)
    np.testing.assert_allclose(vertices.mean(axis=0), [0.5, 0.0, 0.0], atol=1e-9)


@pytest.mark.skipif(not HAS_USD, reason="the optional usd-core is not installed")
def test_faces_of_fewer_than_three_vertices_are_skipped(tmp_path):
    """A point and a line among a mesh's faces (exporters write them for seams and markers) draw
    nothing; the box's quads are read, and a mesh of such faces alone is no solid."""
    stage = STAGE.replace("[4, 4, 4, 4, 4, 4]", "[4, 4, 1, 4, 2, 4, 4, 4]").replace(
        "[0, 1, 3, 2, 4, 6, 7, 5, 0, 4, 5, 1,", "[0, 1, 3, 2, 4, 6, 7, 5, 3, 0, 4, 5, 1, 6, 7,")
    path = tmp_path / "seams.usda"
    path.write_text(stage)
    vertices, faces = read_usd(path, "seams.usda")
    assert faces.shape == (12, 3)
    np.testing.assert_allclose(np.ptp(vertices, axis=0), [0.10, 0.04, 0.06], atol=1e-9)
    lines_only = STAGE.replace("[4, 4, 4, 4, 4, 4]", "[2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2]")
    path.write_text(lines_only)
    with pytest.raises(ObjectError):
        read_usd(path, "seams.usda")
