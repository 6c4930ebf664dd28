"""SDFormat and URDF object files whose meshes Drake's parser cannot read (STL, PLY): the meshes are
converted to OBJs in the cache and the model loads with the mesh's size, the file's scale and mass,
while the user's folder is left as it was. Every file is written by the test; Drake parses them."""

import warnings

import numpy as np
import pytest
import trimesh

from drake_grasp import cli
from drake_grasp.objects import InertiaWarning
from drake_grasp.objects.check import check_object
from drake_grasp.objects.names import resolve_user_object

SIZE_MM = (60.0, 40.0, 90.0)  # the box's sides in the mesh file's units (millimetres)


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    """Converted meshes, solids and pieces go to a fresh cache outside the user's folder."""
    monkeypatch.setenv("DRAKE_GRASP_CACHE", str(tmp_path / "cache"))


def _urdf(mesh_reference: str, scale: str = "0.001 0.001 0.001") -> str:
    """A URDF of one link: a 1 kg placeholder inertial and one mesh as its visual and collision."""
    return f"""<?xml version="1.0"?>
<robot name="mug">
  <link name="mug">
    <inertial><origin xyz="0 0 0"/><mass value="1.0"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <visual><geometry><mesh filename="{mesh_reference}" scale="{scale}"/></geometry></visual>
    <collision><geometry><mesh filename="{mesh_reference}" scale="{scale}"/></geometry></collision>
  </link>
</robot>
"""


def _files(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def _load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InertiaWarning)  # the placeholder inertia is replaced; not the point here
        return resolve_user_object(str(path))


@pytest.mark.parametrize("suffix", ["stl", "ply"])
def test_a_urdf_naming_an_stl_or_ply_mesh_loads_with_its_size_and_mass(tmp_path, suffix):
    user = tmp_path / "user"
    (user / "meshes").mkdir(parents=True)
    trimesh.creation.box(SIZE_MM).export(user / "meshes" / f"mug.{suffix}")
    path = user / "mug.urdf"
    path.write_text(_urdf(f"meshes/mug.{suffix}"))  # a relative path, in millimetres with scale 0.001
    before = _files(user)
    spec = _load(path)
    assert spec.mass == pytest.approx(1.0)
    assert sorted(spec.extents) == pytest.approx(sorted(np.array(SIZE_MM) / 1000), abs=1e-3)
    assert _files(user) == before  # nothing written beside the user's files
    converted = list((tmp_path / "cache" / "converted").glob("*.obj"))
    assert len(converted) == 1  # one OBJ for the visual and collision, named by the mesh's content
    _load(path)
    assert list((tmp_path / "cache" / "converted").glob("*.obj")) == converted  # a second load reuses it


def test_an_sdf_with_a_package_uri_to_an_stl_beside_a_relative_obj_loads(tmp_path):
    user = tmp_path / "user"
    (user / "my_mugs" / "meshes").mkdir(parents=True)
    (user / "my_mugs" / "package.xml").write_text("<package><name>my_mugs</name></package>")
    box = trimesh.creation.box(np.array(SIZE_MM) / 1000)
    box.export(user / "my_mugs" / "meshes" / "mug.stl")
    box.export(user / "my_mugs" / "meshes" / "mug.obj")
    path = user / "my_mugs" / "mug.sdf"
    path.write_text("""<?xml version="1.0"?>
<sdf version="1.7" xmlns:drake="drake.mit.edu">
  <model name="mug_sdf">
    <link name="mug">
      <inertial><mass>0.25</mass><inertia><ixx>1e-3</ixx><ixy>0</ixy><ixz>0</ixz><iyy>1e-3</iyy><iyz>0</iyz>
        <izz>1e-3</izz></inertia></inertial>
      <visual name="visual"><geometry><mesh><uri>meshes/mug.obj</uri></mesh></geometry></visual>
      <collision name="collision"><geometry><mesh><uri>package://my_mugs/meshes/mug.stl</uri></mesh></geometry>
        <drake:proximity_properties><drake:mu_dynamic>0.5</drake:mu_dynamic></drake:proximity_properties>
      </collision>
    </link>
  </model>
</sdf>
""")
    before = _files(user)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InertiaWarning)
        spec, report = check_object(str(path))
    assert spec.name == "mug_sdf" and spec.mass == pytest.approx(0.25)
    assert sorted(spec.extents) == pytest.approx(sorted(np.array(SIZE_MM) / 1000), abs=1e-3)
    assert _files(user) == before


@pytest.mark.parametrize("mesh, content, message", [
    ("missing.stl", None, "mesh meshes/missing.stl: file not found"),
    ("missing.obj", None, "mesh meshes/missing.obj: file not found (looked for "),  # the error is Drake's parser's
    ("garbage.stl", "solid garbage\n not a facet\nendsolid\n", "mesh meshes/garbage.stl: "),
])
def test_a_mesh_that_cannot_be_read_is_refused_in_one_line(tmp_path, capsys, mesh, content, message):
    (tmp_path / "meshes").mkdir()
    if content is not None:
        (tmp_path / "meshes" / mesh).write_text(content)
    path = tmp_path / "mug.urdf"
    path.write_text(_urdf(f"meshes/{mesh}"))
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert message in line and str(path) in line and "MakeConvexHull" not in line, line


def _two_boxes_apart(gap_mm: float) -> trimesh.Trimesh:
    """Two 30 mm cubes `gap_mm` apart along x, in millimetres: one mesh of two separate parts."""
    a = trimesh.creation.box((30.0, 30.0, 30.0))
    b = trimesh.creation.box((30.0, 30.0, 30.0)).apply_translation([30.0 + gap_mm, 0.0, 0.0])
    return trimesh.util.concatenate([a, b])


def test_parts_apart_in_one_link_are_one_rigid_body_and_in_a_bare_mesh_an_error(tmp_path):
    """A URDF link declares its collision mesh one rigid body: parts farther apart than the join gap
    (pybullet's random_urdfs ship such meshes) load as that body, with a note; the same mesh bare,
    which declares nothing, is refused in one line as before."""
    user = tmp_path / "user"
    user.mkdir()
    _two_boxes_apart(5.0).export(user / "pair.obj")
    path = user / "pair.urdf"
    path.write_text(_urdf("pair.obj"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = resolve_user_object(str(path))
    notes = [str(w.message) for w in caught]
    assert any("2 separate parts" in n and "one rigid body" in n for n in notes), notes
    assert sorted(spec.extents) == pytest.approx([0.03, 0.03, 0.065], abs=1e-3)
    assert spec.mass == pytest.approx(1.0)
    with pytest.raises(Exception, match="2 separate parts farther apart than the join gap"):
        resolve_user_object(str(user / "pair.obj"), scale=0.001)


def test_a_shell_of_thin_convex_slivers_loads_as_its_merged_solid(tmp_path):
    """A 1.2 × 6 cm tube built of 24 flat strips 0.3 mm thick, each a closed convex sliver (pybullet's
    random_urdfs/292 is such a shell). Merging the slivers makes a solid for contact ten times the
    material's volume, and the vertex budget shrinks it by a few per cent of that: measured against
    the material, cleaning refused it ("would remove 4.0 % of the volume"). It loads, saying so, with
    the material's mass."""
    strips = []
    for i in range(24):
        a0, a1 = 2 * np.pi * i / 24, 2 * np.pi * (i + 1) / 24
        corners = [[r * np.cos(a), y, r * np.sin(a)] for a in (a0, a1) for r in (5.7, 6.0) for y in (-30.0, 30.0)]
        strips.append(trimesh.convex.convex_hull(np.array(corners)))
    tube = trimesh.util.concatenate(strips)
    path = tmp_path / "tube.obj"
    tube.export(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = resolve_user_object(str(path), scale=0.001)
    notes = [str(w.message) for w in caught]
    assert any("a shell of thin parts" in n for n in notes), notes
    assert sorted(spec.extents) == pytest.approx([0.012, 0.012, 0.06], abs=5e-4)
    assert spec.mass == pytest.approx(200.0 * tube.volume * 1e-9, rel=0.02)  # the material's, at 200 kg/m³
