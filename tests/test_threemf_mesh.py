"""3MF packages as 3D-printing tools write them, read into triangles in metres
(drake_grasp.objects.threemf_mesh). Each test writes its own small package."""

from __future__ import annotations

import io
import zipfile

import numpy as np
import pytest
import trimesh

from drake_grasp.objects.spec import ObjectError
from drake_grasp.objects.threemf_mesh import is_3mf, read_3mf

CORE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
PRODUCTION = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06"
RELS = """<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0"
  Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>"""


def mesh_xml(mesh: trimesh.Trimesh) -> str:
    vertices = "".join(f'<vertex x="{x:.9g}" y="{y:.9g}" z="{z:.9g}"/>' for x, y, z in mesh.vertices)
    triangles = "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in mesh.faces)
    return f"<mesh><vertices>{vertices}</vertices><triangles>{triangles}</triangles></mesh>"


def model(resources: str, build: str, unit: str | None = "millimeter") -> str:
    unit_attribute = f' unit="{unit}"' if unit else ""
    return (f'<?xml version="1.0" encoding="UTF-8"?><model{unit_attribute} xml:lang="en-US" xmlns="{CORE}" '
            f'xmlns:p="{PRODUCTION}"><resources>{resources}</resources><build>{build}</build></model>')


def package(parts: dict[str, str], rels: str | None = RELS) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        archive.writestr("[Content_Types].xml", "<Types/>")
        if rels is not None:
            archive.writestr("_rels/.rels", rels)
        for name, text in parts.items():
            archive.writestr(name, text)
    return buffer.getvalue()


BOX = trimesh.creation.box((40.0, 20.0, 10.0))  # millimetres


def test_a_box_in_millimetres_comes_in_metres_moved_by_its_build_item():
    data = package({"3D/3dmodel.model": model(
        f'<object id="1" type="model">{mesh_xml(BOX)}</object>',
        '<item objectid="1" transform="1 0 0 0 1 0 0 0 1 100 0 5"/>')})
    assert is_3mf(data)
    vertices, faces = read_3mf(data, "box.3mf")
    mesh = trimesh.Trimesh(vertices, faces)
    assert mesh.is_watertight
    np.testing.assert_allclose(mesh.extents, [0.04, 0.02, 0.01])
    np.testing.assert_allclose(mesh.bounds.mean(axis=0), [0.1, 0.0, 0.005], atol=1e-12)
    assert mesh.volume == pytest.approx(8e-6)


def test_the_default_unit_is_millimetres_and_other_units_apply():
    build = '<item objectid="1"/>'
    resources = f'<object id="1">{mesh_xml(BOX)}</object>'
    default = read_3mf(package({"3D/3dmodel.model": model(resources, build, unit=None)}), "a.3mf")[0]
    inches = read_3mf(package({"3D/3dmodel.model": model(resources, build, unit="inch")}), "b.3mf")[0]
    np.testing.assert_allclose(np.ptp(default, axis=0), [0.04, 0.02, 0.01])
    np.testing.assert_allclose(np.ptp(inches, axis=0), np.array([40.0, 20.0, 10.0]) * 0.0254)


def test_the_transform_applies_to_row_vectors():
    """A quarter turn about z written as 3MF writes it: the matrix's rows are the images of x, y and z."""
    data = package({"3D/3dmodel.model": model(
        f'<object id="1">{mesh_xml(BOX)}</object>', '<item objectid="1" transform="0 1 0 -1 0 0 0 0 1 0 0 0"/>')})
    vertices, _ = read_3mf(data, "turned.3mf")
    np.testing.assert_allclose(np.ptp(vertices, axis=0), [0.02, 0.04, 0.01])  # x went to y


def test_a_slicer_project_with_components_in_another_part_and_a_support_left_out():
    """As PrusaSlicer and Bambu Studio save: the build names an assembly whose components live in
    /3D/Objects/object_1.model; a print support beside the object is not part of it."""
    cube = trimesh.creation.box((10.0, 10.0, 10.0))
    support = trimesh.creation.box((5.0, 5.0, 50.0))
    main = model(
        '<object id="2" type="model"><components>'
        '<component p:path="/3D/Objects/object_1.model" objectid="1" transform="1 0 0 0 1 0 0 0 1 -20 0 0"/>'
        '<component p:path="/3D/Objects/object_1.model" objectid="1" transform="1 0 0 0 1 0 0 0 1 20 0 0"/>'
        '</components></object>'
        f'<object id="3" type="support">{mesh_xml(support)}</object>',
        '<item objectid="2" transform="1 0 0 0 1 0 0 0 1 0 0 5"/><item objectid="3"/>')
    part = model(f'<object id="1" type="model">{mesh_xml(cube)}</object>', "")
    data = package({"3D/3dmodel.model": main, "3D/Objects/object_1.model": part})
    vertices, faces = read_3mf(data, "project.3mf")
    mesh = trimesh.Trimesh(vertices, faces)
    assert len(mesh.split(only_watertight=True)) == 2  # the two cubes, not the support
    np.testing.assert_allclose(mesh.bounds, [[-0.025, -0.005, 0.0], [0.025, 0.005, 0.01]], atol=1e-12)


def test_without_a_relationship_the_default_model_part_is_read():
    data = package({"3D/3dmodel.model": model(f'<object id="1">{mesh_xml(BOX)}</object>', '<item objectid="1"/>')},
                   rels=None)
    assert read_3mf(data, "plain.3mf")[1].shape == (12, 3)


@pytest.mark.parametrize("data, problem", [
    (b"solid box\nendsolid\n", "not a ZIP package"),
    (package({"3D/other.model": "<model/>"}, rels=None), "without a 3MF model part"),
    (package({"3D/3dmodel.model": model(f'<object id="1">{mesh_xml(BOX)}</object>', "")}), "builds nothing"),
    (package({"3D/3dmodel.model": model(f'<object id="1">{mesh_xml(BOX)}</object>', '<item objectid="7"/>')}),
     "names object 7 of /3D/3dmodel.model, which is not defined"),
    (package({"3D/3dmodel.model": model(
        '<object id="1"><mesh><vertices><vertex x="0" y="0" z="0"/></vertices>'
        '<triangles><triangle v1="0" v2="1" v3="2"/></triangles></mesh></object>', '<item objectid="1"/>')}),
     "triangle index out of range (0-0)"),
    (package({"3D/3dmodel.model": model(
        '<object id="1"><components><component objectid="1"/></components></object>', '<item objectid="1"/>')}),
     "components nest deeper"),
    (package({"3D/3dmodel.model": model(f'<object id="1">{mesh_xml(BOX)}</object>', '<item objectid="1"/>',
                                        unit="furlong")}), "unknown unit 'furlong'"),
    (package({"3D/3dmodel.model": model(f'<object id="1">{mesh_xml(BOX)}</object>',
                                        '<item objectid="1" transform="1 0 0"/>')}), "not 12 finite numbers"),
    (package({"3D/3dmodel.model": model('<object id="1"><mesh><vertices><vertex x="a" y="0" z="0"/>'
                                        '</vertices></mesh></object>', '<item objectid="1"/>')}),
     "not numbers"),
])
def test_a_damaged_package_is_one_line(data, problem):
    with pytest.raises(ObjectError) as raised:
        read_3mf(data, "bad.3mf")
    message = str(raised.value)
    assert message.startswith("bad.3mf: ") and problem in message and "\n" not in message


def test_a_3mf_file_loads_as_a_users_object_in_its_declared_unit(tmp_path, capsys):
    """`drake-grasp objects check box.3mf`: a 40 × 20 × 10 mm box, no --scale needed."""
    from drake_grasp import cli

    path = tmp_path / "box.3mf"
    path.write_bytes(package({"3D/3dmodel.model": model(f'<object id="1">{mesh_xml(BOX)}</object>',
                                                         '<item objectid="1"/>')}))
    assert cli.main(["objects", "check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "accepted" in out and "size 4.0 x 2.0 x 1.0 cm" in out


def test_a_beam_lattice_alone_is_refused_saying_so():
    lattice = ('<object id="1"><mesh><vertices><vertex x="0" y="0" z="0"/><vertex x="0" y="0" z="10"/></vertices>'
               '<beamlattice radius="1" minlength="0.1"><beams><beam v1="0" v2="1"/></beams></beamlattice>'
               '</mesh></object>')
    with pytest.raises(ObjectError, match="a beam lattice only"):
        read_3mf(package({"3D/3dmodel.model": model(lattice, '<item objectid="1"/>')}), "lattice.3mf")


SLICE = "http://schemas.microsoft.com/3dmanufacturing/slice/2015/07"


@pytest.mark.parametrize("resolution, loads", [(None, False), ("lowres", False), ("fullres", True)])
def test_an_object_of_slices_loads_only_with_a_full_resolution_mesh(resolution, loads):
    attribute = f' s:meshresolution="{resolution}"' if resolution else ""
    resources = (f'<s:slicestack id="9" zbottom="0"/><object id="1" s:slicestackid="9"{attribute}>'
                 f'{mesh_xml(BOX)}</object>')
    text = model(resources, '<item objectid="1"/>').replace("<model ", f'<model xmlns:s="{SLICE}" ', 1)
    data = package({"3D/3dmodel.model": text})
    if loads:
        assert read_3mf(data, "sliced.3mf")[1].shape == (12, 3)
    else:
        with pytest.raises(ObjectError, match="described by a stack of slices"):
            read_3mf(data, "sliced.3mf")
