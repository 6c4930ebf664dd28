"""GraspIt!'s object files as they ship: Open Inventor and VRML geometry (read as triangles, transforms
applied as Coin applies them) and GraspIt body files (mm and grams, inertia per unit mass). Every file
is written by the test; none is GraspIt's own."""

import re

import numpy as np
import pytest
import trimesh

from drake_grasp import cli
from drake_grasp.objects import ObjectError
from drake_grasp.objects.inventor_mesh import read_inventor
from drake_grasp.objects.names import resolve_user_object

IV = "#Inventor V2.1 ascii\n"
VRML = "#VRML V2.0 utf8\n"


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    """Repaired solids and pieces go to a fresh cache: a load here never reads another test's."""
    monkeypatch.setenv("DRAKE_GRASP_CACHE", str(tmp_path / "cache"))


def _mesh(text: str, label: str = "test.iv") -> trimesh.Trimesh:
    vertices, faces = read_inventor(text.encode(), label)
    return trimesh.Trimesh(vertices, faces, process=False)


def _refusal(capsys, argv) -> str:
    """The one line a refused command prints (exit code 2)."""
    assert cli.main(argv) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    return line


# --- Open Inventor and VRML as triangles --------------------------------------------------------


def test_a_separator_with_a_transform_and_a_cube_is_the_exact_box_where_it_is_put():
    mesh = _mesh(IV + """
        Separator {  # a comment, { not a brace }
          Transform { translation 10 0 0  rotation 0 0 1 1.5707963267948966 }
          Material { diffuseColor 1 0 0 }
          Cube { width 20 height 40 depth 60 }
        }""")
    assert len(mesh.vertices) == 8 and len(mesh.faces) == 12 and mesh.is_watertight
    assert mesh.volume == pytest.approx(20 * 40 * 60)
    # turned 90° about z: its 20 along x now along y, its 40 along y now along x; then moved
    assert mesh.bounds == pytest.approx(np.array([[-10.0, -10.0, -30.0], [30.0, 10.0, 30.0]]))


def test_an_indexed_face_set_tetrahedron_with_commas_and_a_quad_fan():
    mesh = _mesh(IV + """
        Separator {
          ShapeHints { vertexOrdering COUNTERCLOCKWISE shapeType SOLID }
          Coordinate3 { point [ 0 0 0, 30 0 0, 0 30 0, 0 0 30, ] }
          IndexedFaceSet { coordIndex [ 0, 2, 1, -1, 0, 1, 3, -1, 0, 3, 2, -1, 1, 2, 3, -1 ] }
        }""")
    assert len(mesh.faces) == 4 and mesh.is_watertight
    assert mesh.volume == pytest.approx(30**3 / 6)  # wound outward: positive
    quad = _mesh(IV + "Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] } IndexedFaceSet { coordIndex [0, 1, 2, 3] }")
    assert quad.faces.tolist() == [[0, 1, 2], [0, 2, 3]]  # a fan; the last polygon needs no -1
    clockwise = _mesh(IV + "ShapeHints { vertexOrdering CLOCKWISE } Coordinate3 { point [0 0 0, 1 0 0, 1 1 0] }"
                      " FaceSet { numVertices 3 }")
    assert clockwise.face_normals[0] == pytest.approx([0, 0, -1])  # turned: its front is outward


def test_triangle_strips_alternate_their_turn():
    points = "Coordinate3 { point [0 0 0, 0 1 0, 1 0 0, 1 1 0, 2 0 0, 2 1 0] }"
    strip = _mesh(IV + points + " TriangleStripSet { numVertices [ 6 ] }")
    indexed = _mesh(IV + points + " IndexedTriangleStripSet { coordIndex [ 0, 1, 2, 3, -1, 2, 3, 4, 5 ] }")
    for mesh in (strip, indexed):
        assert len(mesh.faces) == 4
        assert np.allclose(mesh.face_normals, [0.0, 0.0, -1.0])  # every triangle the same way round
    vertex_property = _mesh(IV + "IndexedTriangleStripSet { vertexProperty VertexProperty { vertex [0 0 0, 0 1 0, "
                            "1 0 0, 1 1 0] orderedRGBA 0xff0000ff } coordIndex [0, 1, 2, 3, -1] }")
    assert len(vertex_property.faces) == 2


def test_a_vrml_transform_with_a_box_used_twice_and_an_inventor_cube_among_its_children():
    mesh = _mesh(VRML + """
        Viewpoint { position 0 0 10 description "a \\"quoted\\" view" }
        Transform {
          translation 100 0 0
          children [
            DEF B Shape { appearance Appearance { material Material { } } geometry Box { size 10 20 30 } }
            Transform { translation 0 50 0 scale 2 1 1 children [ USE B ] }
            Cube { width 4 height 4 depth 4 }
          ]
        }
        ROUTE a.b TO c.d""", "test.wrl")
    assert len(mesh.faces) == 36
    bodies = mesh.split(only_watertight=False)
    centres = sorted(tuple(np.round(b.bounds.mean(axis=0), 6)) for b in bodies)
    assert centres == [(100.0, 0.0, 0.0), (100.0, 0.0, 0.0), (100.0, 50.0, 0.0)]
    assert sorted(tuple(b.extents) for b in bodies) == [(4, 4, 4), (10, 20, 30), (20, 20, 30)]


def test_a_vrml_indexed_face_set_names_its_coordinates_and_winding():
    mesh = _mesh(VRML + """
        Shape { geometry IndexedFaceSet { ccw FALSE coord DEF C Coordinate { point [0 0 0, 1 0 0, 1 1 0] }
                                          coordIndex [0 1 2 -1] } }""", "test.wrl")
    assert mesh.face_normals[0] == pytest.approx([0, 0, -1])


def test_a_cylinder_stands_along_y_with_its_volume_and_a_cone_points_up():
    mesh = _mesh(IV + "Cylinder { radius 10 height 50 }")
    assert mesh.is_watertight
    assert mesh.extents == pytest.approx([20, 50, 20], rel=1e-3)
    assert mesh.bounds[:, 1] == pytest.approx([-25, 25])
    assert mesh.volume == pytest.approx(np.pi * 10**2 * 50, rel=0.01)  # 32 sides: 0.6 % short
    cone = _mesh(IV + "Cone { bottomRadius 10 height 30 }")
    assert cone.volume == pytest.approx(np.pi * 10**2 * 30 / 3, rel=0.01)
    apex = cone.vertices[np.argmax(cone.vertices[:, 1])]
    assert apex == pytest.approx([0, 15, 0])
    sphere = _mesh(VRML + "Shape { geometry Sphere { radius 5 } }", "test.wrl")
    assert sphere.volume == pytest.approx(4 / 3 * np.pi * 125, rel=0.02)


def test_nested_separators_scope_transforms_and_transforms_apply_nearest_first():
    mesh = _mesh(IV + """
        Separator {
          Translation { translation 10 0 0 }
          Separator { Translation { translation 0 5 0 } Cube { width 1 height 1 depth 1 } }
          Cube { width 1 height 1 depth 1 }
          Separator { Scale { scaleFactor 2 2 2 } Translation { translation 0 0 3 } Cube { width 1 height 1 depth 1 } }
          RotationXYZ { axis Z angle 1.5707963267948966 }
          MatrixTransform { matrix 1 0 0 0  0 1 0 0  0 0 1 0  7 0 0 1 }
          Sphere { radius 0.5 }
        }
        Cube { width 1 height 1 depth 1 }""")
    centres = sorted(tuple(np.round(b.bounds.mean(axis=0), 6)) for b in mesh.split(only_watertight=False))
    # (10, 5, 0) and (10, 0, 0); the scaled cube's translation is scaled too: 2 wide at z = 6; the
    # sphere: moved 7 along x by the matrix, then turned onto y; the last cube outside the separator
    assert centres == [(0, 0, 0), (10, 0, 0), (10, 0, 6), (10, 5, 0), (10, 7, 0)]


def test_switch_draws_only_its_chosen_child_and_lines_draw_no_surface():
    mesh = _mesh(IV + """
        Switch { whichChild 1 Cube { } Sphere { radius 3 } Cone { } }
        Switch { Cube { width 100 } }
        Coordinate3 { point [0 0 0, 1 1 1] } LineSet { numVertices 2 }""")
    assert mesh.extents == pytest.approx([6, 6, 6], rel=0.01)


@pytest.mark.parametrize("text, message", [
    ("#Inventor V2.1 binary\n\x00\x00", r"binary Open Inventor .* is not read"),
    ("solid cube\nfacet normal 0 0 1\n", r"not an Open Inventor or VRML file"),
    (IV + "Translation { translation 0 4x 0 } Cube { }", r"Translation \(line 2\): translation holds '4x', not a number"),
    (IV + "Separator { Cube { width 2 }", r"line 2: the file ends inside Separator \(line 2\)"),
    (IV + "Separator { USE missing }", r"line 2: USE 'missing': no node was DEF'd"),
    (IV + 'Info { string "never closed }', r"line 2: a quoted string is never closed"),
    (IV + "Separator {\n NurbsSurface { numUControlPoints 4 } }", r"NurbsSurface \(line 3\): a NURBS surface is not read"),
    (IV + "Text3 { string \"hi\" }", r"Text3 \(line 2\): 3D text is not read"),
    (IV + "Coordinate3 { point [0 0 0, 1 0 0, 1 1 0] } IndexedFaceSet { coordIndex [0, 1, 5] }",
     r"coordIndex 5 is out of range \(the coordinates are 0 to 2\)"),
    (IV + "IndexedFaceSet { coordIndex [0, 1, 2] }", r"no coordinates to index"),
    (IV + "Material { } DirectionalLight { }", r"no surface: the file draws no shape that is read \(not read: "
                                               r"DirectionalLight, Material\)"),
])
def test_a_bad_inventor_file_is_refused_in_one_line(tmp_path, capsys, text, message):
    path = tmp_path / "thing.iv"
    path.write_text(text)
    line = _refusal(capsys, ["objects", "check", str(path), "--scale", "0.001"])
    assert line.startswith(f"drake-grasp objects: error: {path}: ")
    assert re.search(message, line), line


def test_an_inventor_mesh_in_millimetres_loads_with_scale_like_any_mesh_file(tmp_path, capsys):
    path = tmp_path / "block.IV"  # GraspIt names some of its files in capitals; the header decides
    path.write_text(IV + "Separator { Cube { width 60 height 40 depth 30 } }")
    spec = resolve_user_object(str(path), scale=0.001)
    assert sorted(spec.extents) == pytest.approx([0.03, 0.04, 0.06])
    assert spec.volume == pytest.approx(60 * 40 * 30 * 1e-9)
    line = _refusal(capsys, ["trial", "--object", str(path), "--out", str(tmp_path / "out")])
    assert "largest extent 60 m" in line and "--scale 0.001" in line
    assert not (tmp_path / "out").exists()
