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
    (IV + "Translation { translation 0 4x 0 } Cube { }",
     r"Translation \(line 2\): translation holds '4x', not a number"),
    (IV + "Separator { Cube { width 2 }", r"line 2: the file ends inside Separator \(line 2\)"),
    (IV + "Separator { USE missing }", r"line 2: USE 'missing': no node was DEF'd"),
    (IV + 'Info { string "never closed }', r"line 2: a quoted string is never closed"),
    (IV + "Separator {\n NurbsSurface { numUControlPoints 4 } }",
     r"NurbsSurface \(line 3\): a NURBS surface is not read"),
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


# --- GraspIt! body files -------------------------------------------------------------------------

CUBE_IV = IV + "Separator { Cube { width 50 height 50 depth 50 } }"


def _body(folder, xml: str, geometry: str | None = CUBE_IV, name: str = "cube.iv", body: str = "cube.xml"):
    """A body file (and its geometry) in `folder`, GraspIt's layout."""
    if geometry is not None:
        (folder / name).write_text(geometry)
    path = folder / body
    path.write_text('<?xml version="1.0" ?>\n<root>\n' + xml + "\n</root>\n")
    return path


def test_a_body_files_grams_millimetres_and_unit_mass_inertia_become_si(tmp_path):
    # GraspIt's inertia is per unit mass, in mm², about the centre of gravity: for a 50 mm cube a²/6.
    path = _body(tmp_path, """<material>plastic</material><mass>300</mass><cog>0 0 3</cog>
        <inertia_matrix>400 10 0 10 420 0 0 0 430</inertia_matrix>
        <geometryFile type="Inventor">cube.iv</geometryFile>""")
    spec = resolve_user_object(str(path))
    assert spec.mass == pytest.approx(0.300)
    assert spec.inertia == pytest.approx(tuple(0.3 * 1e-6 * np.array([400, 420, 430, 10, 0, 0])))
    assert spec.extents == pytest.approx([0.05, 0.05, 0.05])
    assert spec.rest_height == pytest.approx(0.025 + 0.003)  # its centre of mass is the file's <cog>, 3 mm up
    assert spec.source == str(path.resolve())
    again = resolve_user_object(str(path), inertia="geometry")  # a 50 mm cube's own: m a²/6
    assert again.inertia[:3] == pytest.approx([0.3 * 0.05**2 / 6] * 3)
    # The plant takes it as it takes any object: its mass and inertia reach the body.
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    from drake_grasp.objects.drake_model import AddObject

    plant, _ = AddMultibodyPlantSceneGraph(DiagramBuilder(), 0.001)
    model = AddObject(plant, spec)
    plant.Finalize()
    (index,) = plant.GetBodyIndices(model)
    body = plant.get_body(index)
    assert body.default_mass() == pytest.approx(0.3)
    assert body.default_rotational_inertia().get_moments() == pytest.approx(0.3e-6 * np.array([400, 420, 430]))


def test_without_mass_cog_or_inertia_the_geometry_and_density_give_them(tmp_path):
    path = _body(tmp_path, '<geometryFile>cube.iv</geometryFile>')  # type Inventor is the default
    spec = resolve_user_object(str(path))
    assert spec.mass == pytest.approx(spec.volume * __import__("drake_grasp").objects.DEFAULT_DENSITY)
    assert spec.inertia[:3] == pytest.approx([spec.mass * 0.05**2 / 6] * 3)
    assert resolve_user_object(str(path)).mass == pytest.approx(spec.mass)


def test_geometry_scaling_then_offset_place_the_geometry_in_millimetres(tmp_path):
    block = IV + "Cube { width 10 height 20 depth 30 }"
    uniform = _body(tmp_path, "<geometryScaling>2</geometryScaling><geometryFile>block.iv</geometryFile>", block,
                    "block.iv", "uniform.xml")
    assert resolve_user_object(str(uniform)).extents == pytest.approx([0.02, 0.04, 0.06])
    per_axis = _body(tmp_path, "<geometryScalingX>3</geometryScalingX><geometryScalingZ>0.5</geometryScalingZ>"
                     "<geometryFile>block.iv</geometryFile>", None, body="per_axis.xml")
    assert resolve_user_object(str(per_axis)).extents == pytest.approx([0.03, 0.02, 0.015])
    # turned 90° about z after scaling (x 10 → 20 mm, now along y), moved 5 mm: the offset is in mm
    offset = _body(tmp_path, "<geometryScaling>2</geometryScaling><geometryOffset><transform>"
                   "<translation>0 0 5</translation><rotation>90 z</rotation></transform></geometryOffset>"
                   "<cog>0 0 5</cog><geometryFile>block.iv</geometryFile>", None, body="offset.xml")
    spec = resolve_user_object(str(offset))
    assert spec.extents == pytest.approx([0.04, 0.02, 0.06])
    assert spec.rest_height == pytest.approx(0.030)  # the <cog> at the moved centre: nothing to tip


def test_an_implausible_inertia_is_replaced_and_a_cog_outside_the_geometry_too(tmp_path):
    from drake_grasp.objects.spec import InertiaWarning

    zeros = _body(tmp_path, "<mass>200</mass><inertia_matrix>0 0 0 0 0 0 0 0 0</inertia_matrix>"
                  "<geometryFile>cube.iv</geometryFile>", body="zeros.xml")
    with pytest.warns(InertiaWarning, match="implausible inertia in the file .*not positive-definite"):
        spec = resolve_user_object(str(zeros))
    assert spec.mass == pytest.approx(0.2) and spec.inertia[0] == pytest.approx(0.2 * 0.05**2 / 6)
    outside = _body(tmp_path, "<mass>200</mass><cog>0 0 80</cog><geometryFile>cube.iv</geometryFile>",
                    None, body="outside.xml")
    with pytest.warns(InertiaWarning, match=r"implausible <cog> in the file \(55 mm outside"):
        assert resolve_user_object(str(outside)).rest_height == pytest.approx(0.025)


def test_a_geometry_name_that_differs_in_case_only_is_found_with_a_note(tmp_path):
    from drake_grasp.objects.spec import MeshNote

    path = _body(tmp_path, "<mass>300</mass><geometryFile>soap.iv</geometryFile>", CUBE_IV, "soap.IV", "soap.xml")
    with pytest.warns(MeshNote, match="names soap.iv; read soap.IV"):
        assert resolve_user_object(str(path)).mass == pytest.approx(0.3)


def test_vrml_off_and_ply_geometry_types(tmp_path):
    _body(tmp_path, "", VRML + "Shape { geometry Box { size 40 40 40 } }", "box.wrl", "unused.xml")
    wrl = _body(tmp_path, '<geometryFile type="Inventor">box.wrl</geometryFile>', None, body="wrl.xml")
    assert resolve_user_object(str(wrl)).extents == pytest.approx([0.04, 0.04, 0.04])
    for kind in ("off", "ply"):
        trimesh.creation.box((30, 30, 30)).export(tmp_path / f"box.{kind}")
        body = _body(tmp_path, f'<geometryFile type="{kind}">box.{kind}</geometryFile>', None, body=f"{kind}.xml")
        assert resolve_user_object(str(body)).extents == pytest.approx([0.03, 0.03, 0.03])


@pytest.mark.parametrize("xml, geometry, message", [
    ("<mass>300</mass><geometryFile>missing.iv</geometryFile>", None,
     r"geometry file 'missing.iv' not found \(looked for .*missing.iv\)"),
    ("<geometryFile>cube.iv</geometryFile>", "#Inventor V2.1 binary\n\x00",
     r"cube.xml: cube.iv: binary Open Inventor .* is not read"),
    ("<mass>3OO</mass><geometryFile>cube.iv</geometryFile>", CUBE_IV, r"<mass> '3OO' is not a number"),
    ("<cog>0 0</cog><geometryFile>cube.iv</geometryFile>", CUBE_IV, r"<cog> needs 3 numbers, got 2"),
    ("<inertia_matrix>1 0 0 0 1 0 0 0</inertia_matrix><geometryFile>cube.iv</geometryFile>", CUBE_IV,
     r"<inertia_matrix> needs 9 numbers, got 8"),
    ("<mass>0</mass><geometryFile>cube.iv</geometryFile>", CUBE_IV, r"<mass> must be positive \(grams\), got 0"),
    ("<geometryScaling>-1</geometryScaling><geometryFile>cube.iv</geometryFile>", CUBE_IV,
     r"geometry scaling must be positive, got -1 -1 -1"),
    ('<geometryFile type="obj">cube.iv</geometryFile>', CUBE_IV,
     r"geometry type 'obj' is not one GraspIt! reads \(Inventor, off, ply\)"),
    ("<geometryOffset><translation>1 2 3</translation></geometryOffset><geometryFile>cube.iv</geometryFile>",
     CUBE_IV, r"<geometryOffset> without a <transform>"),
    ("<mass>300</mass>", None, r"a GraspIt! body file without a <geometryFile>"),
    ("<geometryFile>cube.iv</geometryFile>", IV + "Cube { width 1 height 1 depth 1 }",
     r"largest extent 1.\d+ mm: less than the 3 mm .* \(GraspIt! files are in millimetres"),
    ("<geometryFile>cube.iv</geometryFile>", IV + "Separator { Translation { translation 1 2 } Cube { } }",
     r"cube.iv: Translation \(line 2\): translation needs 3 numbers, got 2"),
])
def test_a_bad_body_file_is_refused_in_one_line_before_any_work(tmp_path, capsys, xml, geometry, message):
    path = _body(tmp_path, xml, geometry)
    line = _refusal(capsys, ["objects", "check", str(path)])
    assert line.startswith(f"drake-grasp objects: error: {path}: "), line
    assert re.search(message, line), line
    line = _refusal(capsys, ["trial", "--object", str(path), "--out", str(tmp_path / "out")])
    assert re.search(message, line), line
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("text, message", [
    ('<robot type="Hand"><palm>palm.xml</palm><dof type="r"/></robot>',
     r"a GraspIt! robot file \(<robot>\): only GraspIt object body files .* are read"),
    ("<world><graspableBody><filename>models/objects/mug.xml</filename></graspableBody></world>",
     r"a GraspIt! world file \(<world>\): only GraspIt object body files"),
    ("<root><geometryFile>cube.iv</geometryFile>", r"thing.xml: cannot parse \(no element found: line 1"),
])
def test_a_graspit_robot_world_or_broken_xml_is_refused_in_one_line(tmp_path, capsys, text, message):
    path = tmp_path / "thing.xml"
    path.write_text(text)
    assert re.search(message, _refusal(capsys, ["objects", "check", str(path)]))


def test_a_body_file_takes_the_inertia_and_join_options_but_not_scale(tmp_path, capsys):
    path = _body(tmp_path, "<mass>300</mass><geometryFile>cube.iv</geometryFile>")
    line = _refusal(capsys, ["objects", "check", str(path), "--scale", "0.001"])
    assert "a GraspIt! body's unit is fixed (millimetres): --scale does not apply" in line
    assert cli.main(["objects", "check", str(path), "--inertia", "geometry", "--join-gap", "0.001"]) == 0
    out = capsys.readouterr().out
    assert "size 5.0 x 5.0 x 5.0 cm" in out and "mass 300.0 g" in out
    assert cli.main(["objects", "check", str(path)]) == 0
    assert "inertia from the solid at uniform density (the GraspIt! file gives no <inertia_matrix>)" in \
        capsys.readouterr().out
    with pytest.raises(ObjectError, match="not an MJCF file"):  # other .xml files still go to the MJCF reader
        (tmp_path / "other.xml").write_text("<sdf/>")
        resolve_user_object(str(tmp_path / "other.xml"))


def test_vrml_1_is_read_as_inventor_and_a_gzipped_file_too(tmp_path):
    import gzip

    text = "#VRML V1.0 ascii\nSeparator { Transform { translation 0 0 5 scaleFactor 2 1 1 } Cube { } }"
    mesh = _mesh(text, "old.wrl")
    assert mesh.bounds == pytest.approx(np.array([[-2.0, -1.0, 4.0], [2.0, 1.0, 6.0]]))
    vertices, faces = read_inventor(gzip.compress(text.encode()), "old.wrl")
    assert np.allclose(vertices, mesh.vertices) and len(faces) == 12
