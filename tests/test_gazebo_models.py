"""Gazebo's model files as osrf/gazebo_models ships them: ``model://NAME/...`` URIs resolved as Gazebo
resolves them, COLLADA meshes read in the unit they declare, a static model loaded as a free body, and
one line (exit 2) for what cannot load. Every file is written by the test; Drake parses the models."""

import numpy as np
import pytest
import trimesh

from drake_grasp import cli
from drake_grasp.objects import ObjectError
from drake_grasp.objects.check import check_object
from drake_grasp.objects.collada_mesh import read_dae

CAN_MM = (66.0, 66.0, 122.0)  # the can's box in the COLLADA file's millimetres


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    """Converted meshes, solids and pieces go to a fresh cache; no model path from the environment."""
    monkeypatch.setenv("DRAKE_GRASP_CACHE", str(tmp_path / "cache"))
    for variable in ("GAZEBO_MODEL_PATH", "GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH"):
        monkeypatch.delenv(variable, raising=False)


def _collada(size, unit: float = 0.001, offset=(0.0, 0.0, 0.0), scene: bool = True, up: str = "Y_UP") -> str:
    """A COLLADA 1.4.1 document of one box (`size` in the file's unit), declaring `unit` metres per
    unit and the up axis `up`; with `scene`, a node puts it at `offset` (file units)."""
    box = trimesh.creation.box(size)
    positions = " ".join(f"{x:.6f}" for x in box.vertices.ravel())
    indices = " ".join(str(i) for i in box.faces.ravel())
    node = f"""
  <library_visual_scenes><visual_scene id="scene">
    <node id="can"><translate>{" ".join(str(o) for o in offset)}</translate>
      <instance_geometry url="#can-mesh"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>""" if scene else ""
    return f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="{unit}" name="unit"/><up_axis>{up}</up_axis></asset>
  <library_geometries><geometry id="can-mesh"><mesh>
    <source id="can-positions"><float_array id="can-array" count="{box.vertices.size}">{positions}</float_array>
      <technique_common><accessor source="#can-array" count="{len(box.vertices)}" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="can-vertices"><input semantic="POSITION" source="#can-positions"/></vertices>
    <triangles count="{len(box.faces)}"><input semantic="VERTEX" source="#can-vertices" offset="0"/>
      <p>{indices}</p></triangles>
  </mesh></geometry></library_geometries>{node}
</COLLADA>
"""


def _gazebo_model(folder, name: str, mesh_uri: str, static: bool = False, material_uri: str | None = None):
    """A Gazebo model folder `folder`/`name`: model.config and model.sdf naming `mesh_uri`."""
    model = folder / name
    (model / "meshes").mkdir(parents=True, exist_ok=True)
    (model / "model.config").write_text(f"<model><name>{name}</name><sdf version='1.5'>model.sdf</sdf></model>")
    material = (f"<material><script><uri>{material_uri}</uri><name>Gazebo/Red</name></script></material>"
                if material_uri else "")
    (model / "model.sdf").write_text(f"""<?xml version="1.0" ?>
<sdf version="1.5">
  <model name="{name}">
    <static>{'true' if static else 'false'}</static>
    <link name="link">
      <inertial><mass>0.39</mass><inertia><ixx>5e-4</ixx><ixy>0</ixy><ixz>0</ixz><iyy>5e-4</iyy><iyz>0</iyz>
        <izz>2e-4</izz></inertia></inertial>
      <collision name="collision"><geometry><mesh><uri>{mesh_uri}</uri></mesh></geometry></collision>
      <visual name="visual"><geometry><mesh><uri>{mesh_uri}</uri></mesh></geometry>{material}</visual>
    </link>
  </model>
</sdf>
""")
    return model / "model.sdf"


def _check(path):
    """The object a file loads as, and the notes and warnings `objects check` reports on it."""
    spec, report = check_object(str(path))
    return spec, report.notes


def test_a_collada_mesh_comes_in_metres_by_its_declared_unit_and_where_its_node_puts_it(tmp_path):
    path = tmp_path / "can.dae"
    path.write_text(_collada(CAN_MM, unit=0.001, offset=(100.0, 0.0, 200.0)))
    vertices, faces = read_dae(path.read_bytes(), str(path))
    assert len(faces) == 12
    assert np.ptp(vertices, axis=0) == pytest.approx(np.array(CAN_MM) / 1000)  # millimetres to metres
    assert vertices.mean(axis=0) == pytest.approx([0.1, 0.0, 0.2])  # the node's translation, in metres
    # Declared Y up, yet not turned (as Gazebo draws it): the tall side stays along z.
    inches = tmp_path / "inches.dae"
    inches.write_text(_collada((2.0, 3.0, 4.0), unit=0.0254, scene=False))
    vertices, _ = read_dae(inches.read_bytes(), str(inches))  # no scene: the geometry as stored
    assert np.ptp(vertices, axis=0) == pytest.approx(np.array([2.0, 3.0, 4.0]) * 0.0254)


def test_a_file_that_is_not_collada_is_refused_in_one_line(tmp_path, capsys):
    path = tmp_path / "broken.dae"
    path.write_text("<COLLADA><library_geometries><geometry id='g'><mesh>")
    with pytest.raises(ObjectError, match="broken.dae: cannot read COLLADA"):
        read_dae(path.read_bytes(), str(path))
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "cannot read COLLADA" in line and "Traceback" not in line


def test_a_gazebo_model_with_model_uris_and_a_collada_mesh_loads_at_its_size(tmp_path, caplog):
    models = tmp_path / "gazebo_models"
    # A material script from another model, as gear_part takes arm_part's: Drake reads no material
    # script, so that model need not be there.
    path = _gazebo_model(models, "tin_can", "model://tin_can/meshes/can.dae",
                         material_uri="model://arm_part/materials/scripts")
    (models / "tin_can" / "meshes" / "can.dae").write_text(_collada(CAN_MM, unit=0.001))
    spec, notes = _check(path)
    assert spec.mass == pytest.approx(0.39)
    assert sorted(spec.extents) == pytest.approx(sorted(np.array(CAN_MM) / 1000), abs=1e-3)
    assert not [note for note in notes if "static" in note]
    # Its OGRE material script, which Drake ignores, brings no warning on each load.
    assert not [r for r in caplog.records if "material" in r.getMessage()]


def test_a_model_uri_resolves_on_gazebo_model_path_and_a_missing_one_is_one_line(tmp_path, capsys, monkeypatch):
    elsewhere = tmp_path / "shared"
    (elsewhere / "can_meshes").mkdir(parents=True)
    (elsewhere / "can_meshes" / "can.dae").write_text(_collada(CAN_MM, unit=0.001))
    path = _gazebo_model(tmp_path / "mine", "tin_can", "model://can_meshes/can.dae")
    assert cli.main(["objects", "check", str(path)]) == 2  # not beside it, not on the model path
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "model://can_meshes/ is not known" in line and "--package-path" in line
    # As the line says: --package-path names the folder that holds it (no package.xml needed).
    assert cli.main(["objects", "check", str(path), "--package-path", str(elsewhere)]) == 0
    capsys.readouterr()
    monkeypatch.setenv("GAZEBO_MODEL_PATH", f"{tmp_path / 'nowhere'}:{elsewhere}")
    spec, _ = _check(path)
    assert sorted(spec.extents) == pytest.approx(sorted(np.array(CAN_MM) / 1000), abs=1e-3)


def test_a_static_model_is_loaded_free_with_a_note(tmp_path):
    path = _gazebo_model(tmp_path, "hammer_like", "model://hammer_like/meshes/block.obj", static=True)
    trimesh.creation.box((0.03, 0.2, 0.03)).export(tmp_path / "hammer_like" / "meshes" / "block.obj")
    spec, notes = _check(path)
    static = [note for note in notes if "static" in note]
    assert static == ["note: the model is static in its file (Gazebo holds it fixed); loaded as a free body"]
    assert sorted(spec.extents) == pytest.approx([0.03, 0.03, 0.2], abs=1e-3)


def test_a_model_in_gazebos_format_before_sdformat_1_3_is_read_as_1_3(tmp_path):
    """Gazebo's format up to 1.2 had the root <gazebo version="1.2">, which Drake's parser does not
    read; SDFormat 1.3 renamed only the root (pyrobosim ships its coke can in both)."""
    path = _gazebo_model(tmp_path, "old_can", "model://old_can/meshes/block.obj")
    trimesh.creation.box((0.03, 0.05, 0.12)).export(tmp_path / "old_can" / "meshes" / "block.obj")
    path.write_text(path.read_text().replace('<sdf version="1.5">', '<gazebo version="1.2">').replace("</sdf>", "</gazebo>"))
    spec, notes = _check(path)
    assert sorted(spec.extents) == pytest.approx([0.03, 0.05, 0.12], abs=1e-3)
    assert any("before SDFormat 1.3" in note for note in notes)


def test_a_gazebo_model_folder_names_its_sdf_and_a_folder_without_one_is_one_line(tmp_path, capsys):
    path = _gazebo_model(tmp_path, "tin_can", "model://tin_can/meshes/can.dae")
    (tmp_path / "tin_can" / "meshes" / "can.dae").write_text(_collada(CAN_MM, unit=0.001))
    assert cli.main(["objects", "check", str(tmp_path / "tin_can")]) == 0
    assert capsys.readouterr().out.startswith(f"{path}: accepted")  # the folder named its model.sdf
    (tmp_path / "tin_can" / "model.config").write_text("<model><name>tin_can</name></model>")
    assert cli.main(["trial", "--object", str(tmp_path / "tin_can")]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.endswith("tin_can: model.config names no <sdf> file")
    assert cli.main(["objects", "check", str(tmp_path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "a folder; give an object file, or a Gazebo model folder" in line
