"""Object files in the formats Drake and MuJoCo users have (issue 34): MuJoCo's binary .msh (alone
and in an MJCF), Drake's model repository's layout (package:// URIs against a package.xml above the
file or on --package-path, the remote drake_models replaced by a local one, a tetrahedral .vtk for a
compliant hydroelastic geometry), sizes no hand can grasp refused with the likely unit, NaN sizes
and masses named, and the optional MeshFix (pymeshfix) missing. Every file is written by the test."""

import struct
import sys
import warnings

import numpy as np
import pytest
import trimesh

from drake_grasp import cli, trial
from drake_grasp.objects import MeshNote, ObjectError, UnitsWarning, mujoco_msh, packages, sizes, vtk_mesh
from drake_grasp.objects.check import check_object
from drake_grasp.objects.names import resolve_user_object
from drake_grasp.trial import TrialSpec


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    """Repaired solids and pieces go to a fresh cache: a load here never reads another test's."""
    monkeypatch.setenv("DRAKE_GRASP_CACHE", str(tmp_path / "cache"))


def _can():
    """A can 6.6 cm across and 10 cm tall (a closed 24-sided prism), centred at its origin."""
    return trimesh.creation.cylinder(radius=0.033, height=0.10, sections=24)


def _tetrahedra(size=(0.07, 0.06, 0.08)):
    """A box as 12 tetrahedra from its centre to its faces' triangles, bottom at z = 0: a valid mesh for
    Drake's compliant hydroelastic contact (which needs a vertex inside)."""
    box = trimesh.creation.box(size)
    points = np.vstack([box.vertices, [0.0, 0.0, 0.0]]) + [0.0, 0.0, size[2] / 2]
    # Each outward face turned inward, then the centre: positive volumes, as Drake requires.
    return points, np.column_stack([box.faces[:, ::-1], np.full(len(box.faces), len(box.vertices))])


# --- MuJoCo .msh ------------------------------------------------------------------------------


def test_a_msh_file_round_trips_and_becomes_the_object(tmp_path):
    can = _can()
    data = mujoco_msh.msh_bytes(can.vertices, can.faces, normals=can.vertex_normals,
                                texcoords=np.zeros((len(can.vertices), 2)))
    vertices, faces = mujoco_msh.read_msh(data, "can.msh")
    assert np.allclose(vertices, can.vertices, atol=1e-7) and np.array_equal(faces, can.faces)
    path = tmp_path / "can.msh"
    path.write_bytes(data)
    spec, report = check_object(str(path))
    assert spec.volume == pytest.approx(can.volume, rel=1e-5)
    assert sorted(spec.extents) == pytest.approx([0.066, 0.066, 0.10], abs=1e-4)
    # A point cloud (no faces) is its convex hull, as in MuJoCo.
    hull_vertices, hull_faces = mujoco_msh.read_msh(mujoco_msh.msh_bytes(can.vertices, np.zeros((0, 3))), "cloud")
    assert trimesh.Trimesh(hull_vertices, hull_faces).volume == pytest.approx(can.volume, rel=1e-5)


@pytest.mark.parametrize("damage, message", [
    (lambda d: d[:10], "shorter than its 16-byte header"),
    (lambda d: d[:-6], r"damaged .msh file \(truncated\): its counts \(nvertex 50, nnormal 0, ntexcoord 0, nface 96\) "
                       r"need 1,768 bytes, the file has 1,762"),
    (lambda d: d + b"\0\0\0\0", r"\(longer than its counts say\)"),
    (lambda d: struct.pack("<i", -3) + d[4:], "negative count"),
    (lambda d: d[:-4] + struct.pack("<i", 50), r"1 face indices out of range \(e.g. 50; vertices are 0 to 49\)"),
    (lambda d: d[:16] + struct.pack("<f", float("nan")) + d[20:], "1 of its 50 vertices are not finite"),
    (lambda d: struct.pack("<i", 3) + d[4:], "counts"),  # three vertices: the length disagrees first
    (lambda d: b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", "a Gmsh mesh"),
])
def test_a_damaged_msh_file_is_refused_in_one_line(tmp_path, capsys, damage, message):
    can = _can()
    assert len(can.vertices) == 50 and len(can.faces) == 96
    path = tmp_path / "can.msh"
    path.write_bytes(damage(mujoco_msh.msh_bytes(can.vertices, can.faces)))
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith(f"drake-grasp objects: error: {path}: ")
    assert __import__("re").search(message, line), line


def test_an_mjcf_naming_a_msh_mesh_loads_and_a_short_trial_runs(tmp_path, short_scenario):
    """robosuite's can.xml, as it names meshes/can.msh (the collision geom and two visual ones)."""
    (tmp_path / "meshes").mkdir()
    can = _can()
    (tmp_path / "meshes" / "can.msh").write_bytes(mujoco_msh.msh_bytes(can.vertices, can.faces))
    path = tmp_path / "can.xml"
    path.write_text("""<mujoco model="can">
  <asset>
    <mesh file="meshes/can.msh" name="can_mesh"/>
    <texture file="../textures/soda.png" name="tex-can" type="2d"/>
  </asset>
  <worldbody>
    <body>
      <body name="collision">
        <geom pos="0 0 0" mesh="can_mesh" type="mesh" density="100" friction="0.95 0.3 0.1" group="1" condim="4"/>
      </body>
      <body name="visual">
        <geom pos="0 0 0" mesh="can_mesh" type="mesh" conaffinity="0" contype="0" group="0" mass="0.0001"/>
      </body>
      <site rgba="0 0 0 0" size="0.005" pos="0 0 -0.06" name="bottom_site"/>
    </body>
  </worldbody>
</mujoco>
""")
    spec, report = check_object(str(path))
    assert spec.mass == pytest.approx(100 * can.volume, rel=1e-4)  # the collision geom's density
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        record = trial.run(TrialSpec(str(path), "oracle", "box", 0), scenario=short_scenario)
    assert record.success, record.summary()
    (tmp_path / "meshes" / "can.msh").write_bytes(b"\x10\0\0\0")
    with pytest.raises(ObjectError, match=r"can.xml: mesh 'can_mesh': can.msh: not a MuJoCo .msh file"):
        resolve_user_object(str(path))


def _included_collection(root, body_geoms=None):
    """An object as RoboHive's object_sim lays its objects out: ``cube/object.xml`` includes the
    collection's ``common.xml`` (the angle unit, default classes, a floor in its own worldbody) and the
    object's ``assets.xml`` and ``body.xml``; meshdir is the collection's folder, and mesh paths go
    up and down again through the collection's name. Returns the object file's path."""
    collection = root / "collection"
    (collection / "cube").mkdir(parents=True)
    trimesh.creation.box((0.05, 0.04, 0.03)).export(collection / "cube" / "cube.stl")
    (collection / "common.xml").write_text("""<mujoco>
  <compiler angle="radian"/>
  <default><default class="grab"><geom type="mesh"/>
    <default class="object_col"><geom type="mesh" density="1250" contype="1" conaffinity="1"/></default>
  </default></default>
  <worldbody><geom type="plane" size="4 4 .1"/></worldbody>
</mujoco>""")
    (collection / "cube" / "assets.xml").write_text(
        '<mujocoinclude><asset><mesh name="cube" file="../collection/cube/cube.stl"/></asset></mujocoinclude>')
    (collection / "cube" / "body.xml").write_text(body_geoms or """<mujocoinclude>
  <geom name="cube_visual" mesh="cube" contype="0" conaffinity="0"/>
  <geom name="cube_contact" mesh="cube" class="object_col"/>
</mujocoinclude>""")
    path = collection / "cube" / "object.xml"
    path.write_text("""<mujoco>
  <compiler meshdir=".."/>
  <include file="../common.xml"/>
  <include file="assets.xml"/>
  <worldbody><body name="object" pos="0 0 0.05" childclass="grab"><include file="body.xml"/></body></worldbody>
</mujoco>""")
    return path


def test_an_mjcf_object_split_across_included_files_loads(tmp_path):
    """Its compilers merge (radians from one, meshdir from the other), its worldbodies merge (the
    floor is the world's, not the object), and its body's geoms come from the included body file."""
    path = _included_collection(tmp_path)
    spec, _ = check_object(str(path))
    assert sorted(spec.extents) == pytest.approx([0.03, 0.04, 0.05], abs=1e-6)
    assert spec.mass == pytest.approx(1250 * 0.05 * 0.04 * 0.03, rel=1e-4)  # object_col's density


@pytest.mark.parametrize("body, message", [
    ('<mujocoinclude><include file="body.xml"/></mujocoinclude>', r"nests deeper than 16 files"),
    ('<mujocoinclude><include file="missing.xml"/></mujocoinclude>', r"included file 'missing.xml' not found"),
    ('<robot name="x"/>', r"included file 'body.xml' is not MJCF"),
])
def test_a_broken_include_is_refused_in_one_line(tmp_path, capsys, body, message):
    path = _included_collection(tmp_path, body_geoms=body)
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert __import__("re").search(message, line), line


# --- Drake's tetrahedral .vtk -----------------------------------------------------------------


def test_a_vtk_tetrahedral_mesh_is_read_as_its_outward_boundary():
    points, tets = _tetrahedra()
    read_points, read_tets = vtk_mesh.read_vtk(vtk_mesh.vtk_text(points, tets).encode(), "box.vtk")
    assert np.allclose(read_points, points) and np.array_equal(read_tets, tets)
    vertices, faces = vtk_mesh.boundary_surface(read_points, read_tets)
    surface = trimesh.Trimesh(vertices, faces, process=False)
    assert len(faces) == 12 and surface.is_watertight  # 48 tetrahedron faces, 36 inside (twice), 12 outside
    assert surface.volume == pytest.approx(0.07 * 0.06 * 0.08)  # positive: wound outward
    # VTK 5.1 (OFFSETS and CONNECTIVITY), as VTK 9 writes it, gives the same tetrahedra.
    offsets = " ".join(str(4 * i) for i in range(len(tets) + 1))
    text = ("# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\n"
            f"POINTS {len(points)} float\n" + " ".join(map(str, points.ravel())) + "\nMETADATA\nINFORMATION 0\n\n"
            f"CELLS {len(tets) + 1} {4 * len(tets)}\nOFFSETS vtktypeint64\n{offsets}\n"
            "CONNECTIVITY vtktypeint64\n" + " ".join(map(str, tets.ravel())) + f"\nCELL_TYPES {len(tets)}\n"
            + "10\n" * len(tets))
    assert np.array_equal(vtk_mesh.read_vtk(text.encode(), "v5.vtk")[1], tets)


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("ASCII", "BINARY"), "BINARY VTK unstructured grid; only ASCII ones are read"),
    (lambda t: t.replace("UNSTRUCTURED_GRID", "POLYDATA"), "not DATASET UNSTRUCTURED_GRID"),
    (lambda t: t[:t.index("CELLS")], "no CELLS section"),
    (lambda t: t[:t.index("CELL_TYPES") - 10], r"CELLS section is truncated"),
    (lambda t: t.replace(t.split("CELLS")[1].split("\n")[1], "4 90 1 2 8", 1),
     r"1 VTK cell indices out of range \(e.g. 90; points are 0 to 8\)"),
    (lambda t: t.replace("POINTS 9", "POINTS 8"), "where a section should start"),
    (lambda t: t.replace("\n10\n", "\n5\n", 1), "VTK cells of type 5"),
    (lambda t: "solid box\nendsolid\n", "not a legacy VTK file"),
])
def test_a_damaged_vtk_file_is_refused_in_one_line(edit, message):
    text = vtk_mesh.vtk_text(*_tetrahedra())
    with pytest.raises(ObjectError, match=message) as error:
        vtk_mesh.read_vtk(edit(text).encode(), "pepper.vtk")
    assert str(error.value).startswith("pepper.vtk: ") and "\n" not in str(error.value)


# --- Drake's model repository: package:// against a package.xml ---------------------------------


def _drake_models(root):
    """drake_models' layout: package.xml at the root, ycb/*.sdf naming package://drake_models/ycb/meshes/...,
    veggies/*.sdf with a compliant hydroelastic .vtk under veggies/assets/."""
    (root / "ycb" / "meshes").mkdir(parents=True)
    (root / "veggies" / "assets").mkdir(parents=True)
    (root / "package.xml").write_text('<?xml version="1.0"?>\n<package format="2">\n  <name>drake_models</name>\n'
                                      "  <version>0.0.0</version>\n</package>\n")
    trimesh.creation.box((0.06, 0.04, 0.09)).export(root / "ycb" / "meshes" / "box_textured.obj")
    (root / "ycb" / "009_box.sdf").write_text("""<?xml version="1.0"?>
<sdf version="1.7">
  <model name="009_box">
    <link name="base_link_box">
      <inertial><mass>0.1</mass><inertia><ixx>9.1e-5</ixx><ixy>0</ixy><ixz>0</ixz><iyy>9.75e-5</iyy><iyz>0</iyz>
        <izz>4.33e-5</izz></inertia></inertial>
      <visual name="visual"><geometry><mesh>
        <uri>package://drake_models/ycb/meshes/box_textured.obj</uri></mesh></geometry></visual>
      <collision name="collision"><geometry><mesh>
        <uri>package://drake_models/ycb/meshes/box_textured.obj</uri></mesh></geometry></collision>
    </link>
  </model>
</sdf>
""")
    (root / "veggies" / "assets" / "pepper.vtk").write_text(vtk_mesh.vtk_text(*_tetrahedra()))
    (root / "veggies" / "pepper.sdf").write_text("""<?xml version="1.0"?>
<sdf version="1.7" xmlns:drake="drake.mit.edu">
  <model name="pepper">
    <link name="pepper">
      <inertial><pose>0 0 0.04 0 0 0</pose><mass>0.159</mass><inertia><ixx>1.3e-4</ixx><ixy>0</ixy><ixz>0</ixz>
        <iyy>1.5e-4</iyy><iyz>0</iyz><izz>1.1e-4</izz></inertia></inertial>
      <collision name="collision">
        <geometry><mesh><uri>package://drake_models/veggies/assets/pepper.vtk</uri><scale>1 1 1</scale></mesh>
        </geometry>
        <drake:proximity_properties>
          <drake:compliant_hydroelastic/>
          <drake:hydroelastic_modulus>5.0e4</drake:hydroelastic_modulus>
        </drake:proximity_properties>
      </collision>
    </link>
  </model>
</sdf>
""")
    return root


def test_drake_models_layout_loads_with_its_package_xml_above_the_file(tmp_path, short_scenario):
    root = _drake_models(tmp_path / "models")
    box, _ = check_object(str(root / "ycb" / "009_box.sdf"))
    assert sorted(box.extents) == pytest.approx([0.04, 0.06, 0.09]) and box.mass == pytest.approx(0.1)
    pepper, report = check_object(str(root / "veggies" / "pepper.sdf"))
    # The tetrahedra's boundary is the solid: a 7 x 6 x 8 cm box, its inertia the file's.
    assert pepper.volume == pytest.approx(0.07 * 0.06 * 0.08, rel=1e-6) and pepper.mass == pytest.approx(0.159)
    assert report.inertia_source == "the file" and report.pieces == 1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        record = trial.run(TrialSpec(str(root / "veggies" / "pepper.sdf"), "oracle", "box", 0),
                           scenario=short_scenario)
    assert record.success, record.summary()  # the hand lifts the box its tetrahedra bound


def test_a_local_package_replaces_drakes_remote_one_and_package_path_finds_one_elsewhere(tmp_path, capsys):
    from pydrake.multibody.parsing import PackageMap

    root = _drake_models(tmp_path / "checkout")
    package_map = PackageMap()
    assert package_map.Contains("drake_models")  # Drake's default: remote, downloaded on first use
    registered = packages.register_packages(package_map, root / "ycb" / "009_box.sdf")
    assert registered == {"drake_models": root / "package.xml"}
    assert package_map.GetPath("drake_models") == str(root)  # no download: the local copy
    # An SDF of another package, away from its package.xml: --package-path names the folder above it.
    away = tmp_path / "elsewhere" / "cup.sdf"
    away.parent.mkdir()
    mine = tmp_path / "mine" / "my_models"
    mine.mkdir(parents=True)
    (mine / "package.xml").write_text("<package><name>my_models</name></package>")
    trimesh.creation.cylinder(radius=0.04, height=0.1).export(mine / "cup.obj")
    away.write_text((root / "ycb" / "009_box.sdf").read_text().replace("drake_models/ycb/meshes/box_textured.obj",
                                                                       "my_models/cup.obj"))
    assert cli.main(["objects", "check", str(away)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "package://my_models/ is not known" in line and "--package-path DIR" in line
    assert cli.main(["objects", "check", str(away), "--package-path", str(tmp_path / "mine")]) == 0
    assert "accepted" in capsys.readouterr().out
    assert cli.main(["objects", "check", str(away), "--package-path", str(tmp_path / "nothing")]) == 2
    assert "not a directory" in capsys.readouterr().err
    # Only SDF and URDF files take it; a sweep carries it in its specs and their fingerprints.
    with pytest.raises(ObjectError, match="--package-path applies to SDF and URDF model files only"):
        resolve_user_object("sphere:0.1", package_path=(str(mine),))
    spec = TrialSpec(str(away), "oracle", "box", 0, package_path=(str(tmp_path / "mine"),))
    assert spec.object_options() == {"package_path": (str(tmp_path / "mine"),)}


def test_a_package_uri_without_a_package_xml_resolves_to_the_folder_beside_the_file(tmp_path):
    """onshape-to-robot writes package://assets/part_1.stl beside an assets folder and no package.xml
    (Genesis' blue_box): the folder of that name beside the file is the package, with a note."""
    (tmp_path / "box" / "assets").mkdir(parents=True)
    trimesh.creation.box((0.05, 0.06, 0.07)).export(tmp_path / "box" / "assets" / "part_1.stl")
    urdf = tmp_path / "box" / "model.urdf"
    urdf.write_text('<robot name="blue_box"><link name="part_1"><collision><geometry>'
                    '<mesh filename="package://assets/part_1.stl"/></geometry></collision></link></robot>')
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = resolve_user_object(str(urdf))
    assert any("package://assets/ resolved to the folder" in str(w.message) for w in caught)
    np.testing.assert_allclose(sorted(spec.extents), [0.05, 0.06, 0.07], atol=1e-6)


# --- Sizes no hand can grasp, and NaN ----------------------------------------------------------


def test_the_graspable_range_comes_from_the_hand():
    assert sizes.hand_span() == pytest.approx(0.369, abs=0.001)  # F1 to F2 spread apart, from robot/hand.py
    assert sizes.GRASPABLE_EXTENTS[0] < 0.009 < 0.09 < sizes.hand_span() < sizes.GRASPABLE_EXTENTS[1]
    box = trimesh.creation.box((0.1, 0.06, 0.04))
    assert sizes.widths(box.vertices) == pytest.approx((0.04, 0.1))
    rod = trimesh.creation.cylinder(radius=0.01, height=0.6)
    rod.apply_transform(trimesh.transformations.rotation_matrix(0.9, [1, 1, 0]))  # tilted: its length still found
    assert sizes.widths(rod.vertices)[1] == pytest.approx(0.6, rel=1e-3)
    assert sizes.size_problem(0.009, 0.12) is None  # a 9 mm stick
    assert "is the file in millimetres (--scale 0.001)?" in sizes.size_problem(60.0, 100.0)
    assert "centimetres (--scale 0.01)" in sizes.size_problem(20.0, 40.0)
    assert "inches (--scale 0.0254)" in sizes.size_problem(2.0, 8.0)
    assert "drop --scale 0.001" in sizes.size_problem(0.00005, 0.0001, scale=0.001)
    assert "not finite" in sizes.size_problem(float("nan"), 0.1)


@pytest.mark.parametrize("size, scale, message", [
    ((1e9, 5e8, 3e8), 1.0, r"largest extent 1e\+09 m: more than the 50 cm a grasp here can take"),
    ((100.0, 60.0, 40.0), 1.0, r"largest extent 100 m: .* is the file in millimetres \(--scale 0.001\)\?"),
    ((0.40, 0.38, 0.40), 1.0, r"smallest width 38 cm: wider in every direction than the open hand \(36.9 cm\)"),
    ((0.002, 0.002, 0.001), 1.0, r"largest extent 2 mm: less than the 3 mm"),
    ((0.1, 0.06, 0.04), 0.001, r"largest extent 0.1 mm: .*is the file in metres already\? drop --scale 0.001"),
])
def test_an_object_no_hand_can_grasp_is_refused_before_any_work(tmp_path, capsys, size, scale, message):
    path = tmp_path / "thing.stl"
    trimesh.creation.box(size).export(path)
    argv = ["trial", "--object", str(path), "--out", str(tmp_path / "out")]
    argv += ["--scale", str(scale)] if scale != 1 else []
    assert cli.main(argv) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert __import__("re").search(message, line), line
    assert not (tmp_path / "out").exists()


def test_small_objects_warn_and_primitives_are_not_checked(tmp_path):
    bead = tmp_path / "bead.stl"
    trimesh.creation.box((0.009, 0.006, 0.004)).export(bead)
    with pytest.warns(UnitsWarning, match=r"largest extent 9 mm, smaller than the hand grasps reliably"):
        resolve_user_object(str(bead))
    stick = tmp_path / "stick.stl"
    trimesh.creation.cylinder(radius=0.0045, height=0.12).export(stick)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitsWarning)
        resolve_user_object(str(stick))  # a 9 mm stick: nothing to say
    for primitive in ("sphere:0.02", "cube:0.34", "cylinder:0.34x0.3"):  # Fig. 4's range is not a file's
        resolve_user_object(primitive)


@pytest.mark.parametrize("file, text, message", [
    ("nan.xml", '<mujoco><worldbody><body><geom name="block" type="box" size="nan 0.02 0.02"/></body></worldbody>'
                "</mujoco>", r"geom 'block' size 'nan 0.02 0.02' is not finite \(NaN or inf\)"),
    ("mass.xml", '<mujoco><worldbody><body><geom type="box" size="0.02 0.02 0.02" mass="inf"/></body></worldbody>'
                 "</mujoco>", r"box geom mass 'inf' is not finite"),
    ("inertial.xml", '<mujoco><worldbody><body><inertial pos="0 0 0" mass="nan" diaginertia="1e-4 1e-4 1e-4"/>'
                     '<geom type="box" size="0.02 0.02 0.02"/></body></worldbody></mujoco>',
     r"inertial mass 'nan' is not finite"),
    ("size.sdf", '<sdf version="1.7"><model name="m"><link name="l"><collision name="c"><geometry><box>'
                 "<size>nan 0.1 0.1</size></box></geometry></collision></link></model></sdf>",
     r"model 'm' link 'l' collision 'c' geometry box size 'nan 0.1 0.1' is not finite"),
    ("mass.sdf", '<sdf version="1.7"><model name="m"><link name="l"><inertial><mass>nan</mass></inertial>'
                 "<collision name='c'><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision></link>"
                 "</model></sdf>", r"model 'm' link 'l' inertial mass 'nan' is not finite"),
])
def test_a_nan_size_or_mass_names_itself(tmp_path, capsys, file, text, message):
    path = tmp_path / file
    path.write_text(text)
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert __import__("re").search(message, line) and "sheet" not in line, line


# --- MeshFix is optional ------------------------------------------------------------------------


def test_without_pymeshfix_an_open_mesh_says_how_to_enable_the_repair(tmp_path, monkeypatch, capsys):
    closed = tmp_path / "closed.stl"
    box = trimesh.creation.box((0.06, 0.05, 0.04))
    box.export(closed)
    holed = tmp_path / "holed.stl"
    trimesh.Trimesh(box.vertices, box.faces[1:], process=False).export(holed)  # one triangle missing
    monkeypatch.setitem(sys.modules, "pymeshfix", None)  # `import pymeshfix` now fails
    assert resolve_user_object(str(closed)).volume == pytest.approx(box.volume)  # closed meshes need no MeshFix
    assert cli.main(["objects", "check", str(holed)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert f"{holed}: open mesh" in line and "pip install 'drake-grasp[repair]'" in line
    monkeypatch.delitem(sys.modules, "pymeshfix")
    pytest.importorskip("pymeshfix")
    with pytest.warns(MeshNote, match="closed 1 open surface"):
        assert resolve_user_object(str(holed)).volume == pytest.approx(box.volume, rel=1e-6)  # with it: closed


# --- Non-uniform mesh scale in a model file ------------------------------------------------------


@pytest.mark.parametrize("scale", ["0.003 0.002 0.001", "-0.003 0.002 0.001"])
def test_a_urdf_mesh_scaled_unevenly_is_the_scaled_solid(tmp_path, scale):
    """Ravens fills its object template with ``scale="0.003 0.003 0.001"`` (a 20-unit shape made
    6 × 6 × 2 cm); a mirroring factor keeps the solid's volume positive."""
    trimesh.creation.box((20.0, 20.0, 20.0)).export(tmp_path / "shape.obj")
    path = tmp_path / "shape.urdf"
    path.write_text(f"""<robot name="shape"><link name="base">
  <inertial><mass value="0.1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  <collision><geometry><mesh filename="shape.obj" scale="{scale}"/></geometry></collision>
</link></robot>""")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the placeholder inertia, replaced
        spec = resolve_user_object(str(path))
    assert sorted(spec.extents) == pytest.approx([0.02, 0.04, 0.06], abs=1e-6)
    assert spec.mass == pytest.approx(0.1)
    # The inertia is the scaled box's at 0.1 kg, not the cube's: about its 6 cm side's axis, m (b² + c²)/12.
    xx, yy, zz, xy, xz, yz = spec.inertia
    moments = np.sort(np.linalg.eigvalsh(np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])))
    assert moments[0] == pytest.approx(0.1 * (0.04**2 + 0.02**2) / 12, rel=1e-3)
    # Its pieces are cached under a folder the scale names; Drake's parser must find them there.
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    from drake_grasp.objects.drake_model import AddObject

    plant, scene_graph = AddMultibodyPlantSceneGraph(DiagramBuilder(), 0.001)
    AddObject(plant, spec)
    plant.Finalize()
    assert scene_graph.model_inspector().num_geometries() >= len(spec.pieces)


# --- VTK surfaces (DATASET POLYDATA), and specks of scan noise -----------------------------------

from drake_grasp.objects import vtk_polydata  # noqa: E402


def _quad_cube(size: float):
    """A cube of `size` (file units) as 8 points and 6 outward quads, as PCL writes a scan's polygons."""
    points = np.array([[x, y, z] for z in (0, size) for y in (0, size) for x in (0, size)], float)
    quads = np.array([[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]])
    return points, quads


@pytest.mark.parametrize("binary", [True, False])
def test_a_vtk_surface_ascii_or_binary_in_millimetres_is_the_solid(tmp_path, binary):
    """PCL's binary POLYDATA in millimetres (the Columbia grasping group's scans): read, then --scale."""
    points, quads = _quad_cube(50.0)
    path = tmp_path / "block.vtk"
    path.write_bytes(vtk_polydata.polydata_bytes(points, quads, binary=binary))
    vertices, faces = vtk_polydata.read_polydata(path.read_bytes(), "block.vtk")
    assert len(faces) == 12 and trimesh.Trimesh(vertices, faces).volume == pytest.approx(50.0**3)
    spec = resolve_user_object(str(path), scale=0.001)
    assert sorted(spec.extents) == pytest.approx([0.05] * 3, abs=1e-6)


def test_a_vtk5_surface_with_offsets_and_triangle_strips_is_read():
    points, quads = _quad_cube(1.0)
    polygons = quads[:4]
    offsets = np.arange(0, 4 * len(polygons) + 1, 4)
    # The last two faces as one strip each: quad (a, b, c, d) is the strip a, b, d, c.
    strips = [[q[0], q[1], q[3], q[2]] for q in quads[4:]]
    text = "\n".join([
        "# vtk DataFile Version 5.1", "vtk output", "ASCII", "DATASET POLYDATA", f"POINTS {len(points)} float",
        " ".join(repr(float(v)) for v in points.ravel()),
        "METADATA", "INFORMATION 0", "",
        f"POLYGONS {len(offsets)} {polygons.size}", "OFFSETS vtktypeint64", " ".join(map(str, offsets)),
        "CONNECTIVITY vtktypeint64", " ".join(map(str, polygons.ravel())),
        f"TRIANGLE_STRIPS 3 8", "OFFSETS vtktypeint64", "0 4 8", "CONNECTIVITY vtktypeint64",
        " ".join(str(int(i)) for s in strips for i in s),
        f"POINT_DATA {len(points)}", "NORMALS Normals float", "0 0 1 " * len(points)]) + "\n"
    vertices, faces = vtk_polydata.read_polydata(text.encode(), "cube.vtk")
    mesh = trimesh.Trimesh(vertices, faces)
    assert len(faces) == 12 and mesh.is_watertight and mesh.volume == pytest.approx(1.0)


@pytest.mark.parametrize("edit, message", [
    (lambda b: b[:-60], r"POLYGONS section is truncated"),
    (lambda b: b.replace(b"DATASET POLYDATA", b"DATASET STRUCTURED_POINTS"), r"not a legacy VTK file|unstructured"),
    (lambda b: b.split(b"\nPOLYGONS")[0] + b"\n", r"no polygons or triangle strips"),
    (lambda b: b.replace(b"BINARY", b"HEX"), r"encoding 'HEX'"),
])
def test_a_damaged_vtk_surface_is_refused_in_one_line(tmp_path, capsys, edit, message):
    points, quads = _quad_cube(0.05)
    path = tmp_path / "bad.vtk"
    path.write_bytes(edit(vtk_polydata.polydata_bytes(points, quads, binary=True)))
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert __import__("re").search(message, line), line


def test_a_binary_tetrahedral_vtk_names_its_encoding_not_a_missing_header(tmp_path, capsys):
    path = tmp_path / "volume.vtk"
    path.write_bytes(b"# vtk DataFile Version 3.0\nvolume\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n"
                     + np.zeros(12, ">f4").tobytes() + b"\xff\xfe")
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "BINARY VTK unstructured grid" in line and "first line" not in line, line


def test_specks_of_scan_noise_are_left_out_but_a_second_part_is_not(tmp_path):
    body = trimesh.creation.icosphere(subdivisions=3, radius=0.04)
    specks = [trimesh.creation.box((0.002, 0.001, 0.001)).apply_translation((0.05 + 0.01 * i, 0.0, 0.0))
              for i in range(3)]
    path = tmp_path / "scan.stl"
    trimesh.util.concatenate([body, *specks]).export(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = resolve_user_object(str(path))
    assert max(spec.extents) == pytest.approx(0.08, abs=0.002)  # the sphere alone
    assert any("left out 3 specks" in str(w.message) for w in caught)
    # A 1.5 cm cube 2 cm away is a part (0.5 % of the volume or more), not noise: still refused.
    part = trimesh.creation.box((0.015, 0.015, 0.015)).apply_translation((0.07, 0.0, 0.0))
    trimesh.util.concatenate([body, part]).export(path)
    with pytest.raises(ObjectError, match="2 separate parts"):
        resolve_user_object(str(path))
