"""Real object files as users bring them: every case of the defect zoo (drake_grasp.objects.mesh_zoo)
is accepted (with its note), repaired, or refused for its stated reason; model files' inertias are
checked; `objects check` says what it did; and a grasp on such objects ends in no simulation error."""

import json
import warnings

import numpy as np
import pytest
import trimesh

from drake_grasp import cli, trial
from drake_grasp.objects import mesh_zoo, repair, solid
from drake_grasp.objects.model_files import InertiaWarning, inertia_problem
from drake_grasp.objects import ObjectError
from drake_grasp.objects.spec import DEFAULT_DENSITY
from drake_grasp.objects.mass_properties import _piece_points
from drake_grasp.trial import SIMULATION_ERROR, TrialSpec
from drake_grasp.objects.names import resolve_user_object


@pytest.fixture(scope="module")
def zoo(tmp_path_factory):
    return mesh_zoo.generate(tmp_path_factory.mktemp("zoo"), seeds=(0,))


def _load(case):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = resolve_user_object(str(case.path), **({"scale": case.scale} if case.scale != 1.0 else {}))
    return spec, [str(w.message) for w in caught]


def _one_body_mjcf(path, geoms: str, compiler: str = ""):
    """`path`, written as an MJCF file of one body made of `geoms` (MJCF text), after `compiler`."""
    path.write_text(f"<mujoco>{compiler}<worldbody><body>{geoms}</body></worldbody></mujoco>")
    return path


@pytest.mark.parametrize("defect", mesh_zoo.CLASSES)
def test_every_zoo_case_is_accepted_repaired_or_refused_for_its_reason(zoo, defect):
    (case,) = [c for c in zoo if c.defect == defect]
    if case.verdict == "refused":
        with pytest.raises(ObjectError) as error:
            _load(case)
        message = str(error.value)
        assert case.reason in message and "\n" not in message and message.startswith(str(case.path))
        return
    spec, notes = _load(case)
    if case.verdict == "repaired":
        assert any(("repaired" in n or "inertia" in n or "shells" in n) for n in notes), notes
    if case.reason:
        assert any(case.reason in n for n in notes), notes
    assert case.volume is not None
    assert spec.volume == pytest.approx(case.volume, rel=case.volume_tolerance)  # the solid the file describes
    assert spec.mass > 0 and np.all(np.linalg.eigvalsh(spec.inertia_matrix()) > 0)
    assert inertia_problem(spec.mass, spec.inertia_matrix(), spec.volume) is None
    assert 1 <= len(spec.pieces) <= 16


def test_cells_that_share_faces_are_one_object_with_the_exact_volume():
    a = trimesh.creation.box((0.04, 0.04, 0.04))
    b = trimesh.creation.box((0.04, 0.04, 0.04)).apply_translation([0.04, 0.0, 0.0])  # shares a face
    shells, _ = repair.closed_shells(trimesh.util.concatenate([a, b]))
    result = solid.solid_of_shells(shells)
    assert len(result.components) == 1 and result.components[0].volume == pytest.approx(2 * 0.04**3, rel=1e-6)


# A 4 × 3 × 2 cm box whose top is fanned through vertex 8, the midpoint of its edge with the front
# face: the front face does not have that vertex (a T-junction).
_BOX = (0.04, 0.03, 0.02)
_BOX_T_VERTICES = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1),
                            (0.5, 0, 1)], float) * _BOX
_BOX_T_FACES = [(0, 2, 1), (0, 3, 2), (0, 1, 5), (0, 5, 4), (3, 7, 6), (3, 6, 2), (0, 4, 7), (0, 7, 3),
                (1, 2, 6), (1, 6, 5),
                (4, 8, 7), (8, 5, 6), (8, 6, 7)]  # the top, through the front edge's midpoint 8


def test_a_closed_mesh_with_a_t_junction_sliver_keeps_its_volume():
    """A box whose top has a vertex on its edge with the front, closed by a zero-area triangle (a
    T-junction sliver, as a boolean union rounded to micrometres leaves): dropping the sliver would
    open a slit, so it is kept, and the solid is the box."""
    a, b, c = _BOX
    faces = _BOX_T_FACES + [(4, 5, 8)]  # the sliver: the front's edge 4-5 against the top's 4-8-5
    mesh = trimesh.Trimesh(_BOX_T_VERTICES, np.array(faces), process=False)
    assert mesh.is_watertight and min(mesh.area_faces) == 0.0
    shells, report = repair.closed_shells(mesh)
    assert sum(s.volume for s in shells) == pytest.approx(a * b * c, rel=1e-9)
    assert report.degenerate_faces == 0


def test_a_t_junction_left_open_is_split_and_the_box_closes():
    """The same box without the sliver: the top's vertex 8 lies on the front face's edge 4-5, which no
    face of the top shares, so the seam is open (as where a CAD export subdivided one part and not
    the part it meets). The front face is split at 8 and the box is closed, with its volume."""
    a, b, c = _BOX
    faces = _BOX_T_FACES
    mesh = trimesh.Trimesh(_BOX_T_VERTICES, np.array(faces), process=False)
    assert not mesh.is_watertight
    split_faces, split = repair.split_t_junctions(mesh.vertices, mesh.faces, 1e-9)
    assert split == 1 and len(split_faces) == len(faces) + 1
    assert trimesh.Trimesh(mesh.vertices, split_faces, process=False).is_watertight
    shells, report = repair.closed_shells(mesh)
    assert report.t_junctions == 1 and report.open_edges == 0 and "split at T-junctions" in report.describe()
    assert sum(s.volume for s in shells) == pytest.approx(a * b * c, rel=1e-9)
    # A real hole is left to the hole filler: a box without its top has no vertex on another's edge.
    open_box = trimesh.Trimesh(_BOX_T_VERTICES[:8], np.array(faces[:10]), process=False)
    assert repair.split_t_junctions(open_box.vertices, open_box.faces, 1e-9)[1] == 0


def test_a_generated_letter_with_a_sliver_loads():
    from drake_grasp.objects.novel import novel_object

    mesh = novel_object(2718, 24).mesh  # an L whose union left a zero-area triangle
    assert min(mesh.area_faces) < 1e-12
    shells, _ = repair.closed_shells(mesh)
    assert sum(s.volume for s in shells) == pytest.approx(mesh.volume, rel=1e-6)


def test_the_join_gap_decides_connectivity_and_the_error_names_the_smallest_gap():
    a = trimesh.creation.box((0.05, 0.05, 0.05))
    b = trimesh.creation.box((0.05, 0.05, 0.05)).apply_translation([0.053, 0.0, 0.0])  # a 3 mm gap
    assert solid.join_gap(0.05) == pytest.approx(0.002)
    assert solid.join_gap(0.5) == pytest.approx(0.01)
    apart = solid.solid_of_shells([a, b])
    assert len(apart.components) == 2 and apart.smallest_gap == pytest.approx(0.003, abs=0.0005)
    joined = solid.solid_of_shells([a, b], gap=0.004)
    assert len(joined.components) == 1 and joined.components[0].volume == pytest.approx(2 * 0.05**3, rel=1e-6)
    inner = trimesh.creation.icosphere(radius=0.01)  # wholly inside a: part of it, counted once
    assert solid.solid_of_shells([a, inner]).components[0].volume == pytest.approx(0.05**3, rel=1e-6)


def test_inertia_checks():
    box = np.diag([1.0, 1.0, 1.5]) * 1e-4
    assert inertia_problem(0.1, box, volume=1e-4, radius=0.06) is None
    assert "positive-definite" in inertia_problem(0.1, np.diag([1e-4, 1e-4, 0.0]))
    assert "triangle inequality" in inertia_problem(0.1, np.diag([1e-4, 1e-4, 3e-4]))
    assert "density" in inertia_problem(100.0, box, volume=1e-4)
    assert "exceeds" in inertia_problem(0.1, np.eye(3), volume=1e-4, radius=0.06)  # 1 kg·m² on 0.1 kg
    assert "non-finite" in inertia_problem(0.1, np.full((3, 3), np.nan))


def test_a_placeholder_inertia_is_replaced_or_with_inertia_file_refused(zoo, capsys):
    (urdf,) = [c for c in zoo if c.defect == "urdf_placeholder_inertia"]  # izz = 0 (seed 0)
    with pytest.warns(InertiaWarning, match=r"not positive-definite \(principal moments 0, 0.1, 0.1"):
        spec = resolve_user_object(str(urdf.path))
    assert spec.mass == pytest.approx(0.1) and np.all(np.linalg.eigvalsh(spec.inertia_matrix()) > 0)
    assert cli.main(["objects", "check", str(urdf.path), "--inertia", "file"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "the file's inertia cannot be simulated" in err[0]


def test_objects_check_reports_and_refuses(zoo, capsys, tmp_path):
    (gaps,) = [c for c in zoo if c.defect == "hull_gaps"]
    replay = tmp_path / "check.html"
    assert cli.main(["objects", "check", str(gaps.path), "--json", "--replay", str(replay)]) == 0
    report = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert any("closed shells within" in n for n in report["notes"])
    assert report["volume"] == pytest.approx(gaps.volume, rel=0.01) and report["pieces"] >= 2
    assert replay.stat().st_size > 10_000
    (apart,) = [c for c in zoo if c.defect == "separate"]
    assert cli.main(["objects", "check", str(apart.path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "2 separate parts" in err[0] and "smallest gap is" in err[0]


def test_an_mjcf_object_with_a_placeholder_inertia_is_grasped_without_a_simulation_error(zoo, short_scenario):
    (case,) = [c for c in zoo if c.defect == "mjcf_placeholder_inertia"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        record = trial.run(TrialSpec(str(case.path), "oracle", "box", 0), scenario=short_scenario)
    assert record.failure != SIMULATION_ERROR, record.detail


@pytest.mark.slow
def test_an_oracle_grasp_on_each_accepted_class_ends_in_no_simulation_error(zoo, short_scenario):
    failures = {}
    for case in zoo:
        if case.verdict == "refused":
            continue
        spec = TrialSpec(str(case.path), "oracle", "box", 0, **({"scale": case.scale} if case.scale != 1.0 else {}))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            record = trial.run(spec, scenario=short_scenario)
        if record.failure == SIMULATION_ERROR:
            failures[case.name] = record.detail
    assert not failures


def test_a_gltf_file_is_turned_z_up(tmp_path):
    tall = trimesh.creation.box((0.04, 0.12, 0.06))  # tall along y: up, in glTF's convention
    path = tmp_path / "tall.glb"
    tall.export(path)
    spec = resolve_user_object(str(path))
    assert sorted(spec.extents) == pytest.approx([0.04, 0.06, 0.12])
    assert spec.extents[2] == pytest.approx(0.12)  # its up is z on the table


def test_an_articulated_mjcf_model_is_held_rigid_where_the_file_puts_it(tmp_path):
    """A hinged lid is held at the file's pose (a note names the joint); the two bodies' <inertial>s
    are one rigid body's: masses added, the centre of mass between them."""
    inertial = '<inertial pos="0 0 0" mass="{}" diaginertia="1e-5 1e-5 1e-5"/>'
    path = tmp_path / "hinged.xml"
    path.write_text(f'<mujoco><worldbody><body>{inertial.format(0.1)}<geom type="box" size="0.02 0.02 0.02"/>'
                    f'<body pos="0.04 0 0"><joint name="lid" type="hinge"/>{inertial.format(0.3)}'
                    '<geom type="box" size="0.02 0.02 0.02"/></body></body></worldbody></mujoco>')
    spec, notes = _load(type("Case", (), {"path": path, "scale": 1.0}))
    assert any("articulated" in note and "hinge joint 'lid'" in note for note in notes)
    np.testing.assert_allclose(sorted(spec.extents), [0.04, 0.04, 0.08], atol=1e-6)
    assert spec.mass == pytest.approx(0.4)
    # The centre of mass sits 3/4 of the way to the lid: 1 cm from the object's middle.
    middle = (np.min(_points(spec), axis=0) + np.max(_points(spec), axis=0)) / 2
    assert np.linalg.norm(middle[:2]) == pytest.approx(0.01, abs=1e-4)


def _points(spec):
    """The object's piece vertices in its frame O (m; O at the centre of mass)."""
    return np.vstack([_piece_points(piece) for piece in spec.pieces])


def _write_urdf(path, body: str) -> str:
    path.write_text(f'<?xml version="1.0"?><robot name="thing">{body}</robot>')
    return str(path)


def _link(name: str, size: str, mass: float | None = None) -> str:
    inertial = (f'<inertial><mass value="{mass}"/><inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" '
                'iyz="0"/></inertial>') if mass else ""
    return (f'<link name="{name}">{inertial}<collision><geometry><box size="{size}"/></geometry></collision>'
            "</link>")


def _joint(kind: str, parent: str, child: str, xyz: str) -> str:
    return (f'<joint name="{child}_joint" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{xyz}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')


def test_urdf_links_joined_by_fixed_joints_are_one_rigid_body(tmp_path):
    """A ROS export's empty base_link above the object, and a mug's handle welded to its body: one
    body, its inertia the links' together (masses added, the centre of mass between them)."""
    path = _write_urdf(tmp_path / "mug.urdf", '<link name="base_link"/>' + _link("body", "0.06 0.06 0.1", 0.2)
                       + _link("handle", "0.02 0.01 0.06", 0.05) + _joint("fixed", "base_link", "body", "0 0 0.05")
                       + _joint("fixed", "body", "handle", "0.04 0 0"))
    spec, notes = _load(type("Case", (), {"path": path, "scale": 1.0}))
    assert not any("articulated" in note for note in notes)
    np.testing.assert_allclose(sorted(spec.extents), [0.06, 0.08, 0.1], atol=1e-6)
    assert spec.mass == pytest.approx(0.25)
    # The centre of mass is 0.05 * 0.04 / 0.25 = 8 mm from the body's axis towards the handle.
    middle_x = (_points(spec)[:, 0].min() + _points(spec)[:, 0].max()) / 2  # the box's middle: 1 cm out
    assert abs(middle_x) == pytest.approx(0.01 - 0.008, abs=1e-4)


def test_an_articulated_urdf_is_held_where_the_file_puts_it_and_two_objects_are_refused(tmp_path):
    """A lid on a revolute joint (PartNet-Mobility's objects) is held at its default position, with a note
    naming the joint; a model fixed to the world loads free; two links joined to nothing are refused."""
    lidded = _write_urdf(tmp_path / "box.urdf", _link("base", "0.08 0.06 0.05", 0.2) + _link("lid", "0.08 0.06 0.01", 0.02)
                         + _joint("revolute", "base", "lid", "0 0 0.03"))
    spec, notes = _load(type("Case", (), {"path": lidded, "scale": 1.0}))
    assert any("articulated" in note and "revolute joint 'lid_joint'" in note for note in notes)
    np.testing.assert_allclose(sorted(spec.extents), [0.06, 0.06, 0.08], atol=1e-6)
    fixed = _write_urdf(tmp_path / "fixed.urdf", '<link name="world"/>' + _link("block", "0.04 0.05 0.06", 0.1)
                        + _joint("fixed", "world", "block", "0 0 0.5"))
    spec, notes = _load(type("Case", (), {"path": fixed, "scale": 1.0}))
    assert any("fixed to the world" in note for note in notes) and spec.mass == pytest.approx(0.1)
    two = _write_urdf(tmp_path / "two.urdf", _link("a", "0.04 0.04 0.04", 0.1) + _link("b", "0.04 0.04 0.04", 0.1))
    assert cli.main(["objects", "check", two]) == 2
    stray = _write_urdf(tmp_path / "stray.urdf", _link("a", "0.04 0.04 0.04", 0.1) + '<link name="tool_frame"/>')
    spec, notes = _load(type("Case", (), {"path": stray, "scale": 1.0}))  # an empty frame joined to nothing
    assert spec.mass == pytest.approx(0.1)


def test_a_urdf_floating_joint_is_held_where_the_file_puts_it_or_to_the_world_means_free(tmp_path):
    """MultibodyPlant does not support URDF's floating joint (it would leave the child free at the world's
    origin): between two links it is held at its origin like a moving joint (a note); from the world it
    means a free body, as loaded, without a note."""
    lidded = _write_urdf(tmp_path / "box.urdf", _link("base", "0.08 0.06 0.05", 0.2) + _link("lid", "0.08 0.06 0.01", 0.05)
                         + _joint("floating", "base", "lid", "0 0 0.03"))
    spec, notes = _load(type("Case", (), {"path": lidded, "scale": 1.0}))
    assert any("articulated" in note and "floating joint 'lid_joint'" in note for note in notes)
    np.testing.assert_allclose(sorted(spec.extents), [0.06, 0.06, 0.08], atol=1e-6)
    assert spec.mass == pytest.approx(0.25)
    free = _write_urdf(tmp_path / "free.urdf", '<link name="world"/>' + _link("block", "0.04 0.05 0.06", 0.1)
                       + _joint("floating", "world", "block", "0 0 0.5"))
    spec, notes = _load(type("Case", (), {"path": free, "scale": 1.0}))
    assert not any("fixed to the world" in note or "articulated" in note for note in notes) and spec.mass == pytest.approx(0.1)


def test_a_mesh_path_one_folder_short_is_found_from_the_folder_above_with_a_note(tmp_path):
    """furniture-bench's lamp parts sit in urdf/lamp/ but name ``../mesh/lamp/...``, a path written for
    urdf/: the same path from one folder higher names the mesh, which is used (a note says so). A mesh
    found nowhere is still refused in one line."""
    mesh_dir = tmp_path / "mesh" / "lamp"
    mesh_dir.mkdir(parents=True)
    trimesh.creation.box((0.04, 0.05, 0.06)).export(mesh_dir / "bulb.obj")
    (tmp_path / "urdf" / "lamp").mkdir(parents=True)
    geometry = '<geometry><mesh filename="../mesh/lamp/{}"/></geometry>'
    body = ('<link name="bulb"><visual>{g}</visual><collision>{g}</collision></link>')
    path = _write_urdf(tmp_path / "urdf" / "lamp" / "bulb.urdf", body.format(g=geometry.format("bulb.obj")))
    spec, notes = _load(type("Case", (), {"path": path, "scale": 1.0}))
    assert any("not where the file says" in note and "1 folder higher" in note for note in notes)
    np.testing.assert_allclose(sorted(spec.extents), [0.04, 0.05, 0.06], atol=1e-6)
    missing = _write_urdf(tmp_path / "urdf" / "lamp" / "hood.urdf", body.format(g=geometry.format("hood.obj")))
    assert cli.main(["objects", "check", missing]) == 2


def test_a_urdf_collision_mesh_that_encloses_nothing_is_its_hull(tmp_path):
    """SAPIEN's PartNet-Mobility parts are open surfaces (a bottle's wall without thickness). As the engines a
    model file is made for collide a mesh, the URDF's collision mesh is its convex hull (a note); the
    same mesh file alone is still refused (a sheet)."""
    n = 13  # a corrugated sheet 6 × 6 cm, 3 cm from crest to trough: no thickness, not a convex piece
    x, y = np.meshgrid(np.linspace(0.0, 0.06, n), np.linspace(0.0, 0.06, n))
    vertices = np.c_[x.ravel(), y.ravel(), 0.015 * np.sin(x.ravel() / 0.06 * 2 * np.pi)]
    corners = [i * n + j for i in range(n - 1) for j in range(n - 1)]
    faces = [[a, a + 1, a + n] for a in corners] + [[a + 1, a + n + 1, a + n] for a in corners]
    trimesh.Trimesh(vertices, faces).export(tmp_path / "wall.obj")
    urdf = _write_urdf(tmp_path / "cup.urdf", '<link name="cup"><collision><geometry><mesh filename="wall.obj"/>'
                       "</geometry></collision></link>")
    spec, notes = _load(type("Case", (), {"path": urdf, "scale": 1.0}))
    assert any("an open surface" in note and "convex hull" in note for note in notes)
    assert sorted(spec.extents)[1:] == pytest.approx([0.06, 0.06], abs=1e-3)
    with pytest.raises(ObjectError, match="sheet"):
        resolve_user_object(str(tmp_path / "wall.obj"))


def test_an_mjcf_object_beside_its_scene_is_the_free_body(tmp_path):
    """Meta-World's object files include a scene (a table, a wall: bodies without joints, welded to the
    world) beside the object's body, which has a <freejoint>: the object is that body, with a note."""
    scene = ('<body name="tablelink" pos="0 0 -0.1"><geom type="box" size="0.5 0.5 0.05"/></body>'
             '<body name="wall" pos="0 0.6 0.2"><geom type="box" size="0.5 0.01 0.2"/></body>')
    cube = '<body pos="0 0 0.02"><freejoint/><geom type="box" size="0.03 0.02 0.01" mass="0.05"/></body>'
    path = tmp_path / "with_scene.xml"
    path.write_text(f"<mujoco><worldbody>{scene}{cube}</worldbody></mujoco>")
    spec, notes = _load(type("Case", (), {"path": path, "scale": 1.0}))
    np.testing.assert_allclose(sorted(spec.extents), [0.02, 0.04, 0.06], atol=1e-6)
    assert spec.mass == pytest.approx(0.05)
    assert any("free body" in note and "'tablelink', 'wall'" in note for note in notes)
    fixed = tmp_path / "fixed.xml"  # no body moves: which one is the object cannot be told
    fixed.write_text(f"<mujoco><worldbody>{scene}</worldbody></mujoco>")
    with pytest.raises(ObjectError, match="found 2 .none free."):
        resolve_user_object(str(fixed))
    two = tmp_path / "two.xml"
    two.write_text(f"<mujoco><worldbody>{cube}{cube}</worldbody></mujoco>")
    with pytest.raises(ObjectError, match="found 2 .2 free"):
        resolve_user_object(str(two))


def test_an_mjcf_object_of_rotated_geoms_loads_without_its_visual_mesh(tmp_path):
    """LIBERO's and robosuite's object files build the collision body of boxes turned by ``quat``
    (MuJoCo's w, x, y, z) and name a visual-only mesh (``contype="0" conaffinity="0"``) that
    collections often ship apart: the quats turn the boxes, the missing visual mesh is not needed,
    and a quat of zero is refused in one line."""
    turned = '<geom type="box" size="0.05 0.01 0.02" quat="0.70711 0 0 0.70711" pos="0 0 0"/>'
    plain = '<geom type="box" size="0.01 0.01 0.01" pos="0 0.06 0"/>'
    visual = '<geom type="mesh" mesh="look" contype="0" conaffinity="0" group="1"/>'
    body = f'<body name="object">{visual}{turned}{plain}</body>'
    path = tmp_path / "libero_like.xml"
    path.write_text(f'<mujoco><asset><mesh file="visual/missing.msh" name="look"/></asset>'
                    f'<worldbody><body>{body}</body></worldbody></mujoco>')
    spec = resolve_user_object(str(path))
    # Turned a quarter about z, the 10 × 2 × 4 cm box runs along y, from -5 to +5 cm; the cube's far
    # side is at 7 cm: 12 cm along y, 2 cm across, 4 cm tall.
    np.testing.assert_allclose(sorted(spec.extents), [0.02, 0.04, 0.12], atol=1e-4)
    zero = _one_body_mjcf(tmp_path / "zero_quat.xml", turned.replace("0.70711 0 0 0.70711", "0 0 0 0"))
    with pytest.raises(ObjectError, match="quat .* is zero"):
        resolve_user_object(str(zero))
    # A body's geoms 2 cm apart (a bottle's cap boxed apart from its body, LIBERO's salad dressing) are
    # one rigid body, as the file declares, where a bare mesh of two parts is refused.
    apart = _one_body_mjcf(tmp_path / "apart.xml", '<geom type="box" size="0.02 0.02 0.02"/>'
                           '<geom type="box" size="0.01 0.01 0.01" pos="0.05 0 -0.01"/>')
    spec, notes = _load(type("Case", (), {"path": apart, "scale": 1.0}))
    np.testing.assert_allclose(sorted(spec.extents), [0.04, 0.04, 0.08], atol=1e-4)
    assert any("one rigid body" in note for note in notes)


def test_mjcf_geoms_given_by_fromto_are_placed_as_mujoco_places_them(tmp_path):
    """A capsule along x from 0 to 10 cm (radius 1 cm) and a cylinder up z from 0 to 5 cm (radius 2
    cm): their union spans -2..11 cm in x, ±2 cm in y and -1..5 cm in z. 'fromto' on a sphere, which
    MuJoCo refuses too, is one line."""
    path = _one_body_mjcf(tmp_path / "fromto.xml", '<geom type="capsule" size="0.01" fromto="0 0 0 0.1 0 0"/>'
                          '<geom type="cylinder" size="0.02" fromto="0 0 0 0 0 0.05"/>')
    spec = resolve_user_object(str(path))
    np.testing.assert_allclose(sorted(spec.extents), [0.04, 0.06, 0.13], atol=2e-3)
    sphere = _one_body_mjcf(tmp_path / "sphere_fromto.xml", '<geom type="sphere" size="0.02" fromto="0 0 0 0 0 0.05"/>')
    with pytest.raises(ObjectError, match="'fromto' is for capsules"):
        resolve_user_object(str(sphere))


def test_model_files_in_millimetres_take_scale(tmp_path, capsys):
    """robogym's chess pieces are MJCF over STL meshes in millimetres: the size check says --scale
    0.001, and --scale applies to MJCF (its geoms' density × volume scaling as the cube, a geom's
    given mass not at all). A URDF over a millimetre mesh takes --scale the same way."""
    path = _one_body_mjcf(tmp_path / "pawn.xml", '<geom type="box" size="10 10 20"/>'
                          '<geom type="sphere" size="5" pos="0 0 25" mass="0.002"/>')
    assert cli.main(["objects", "check", str(path)]) == 2
    assert "--scale 0.001" in capsys.readouterr().err
    spec = resolve_user_object(str(path), scale=0.001)
    assert spec.mass == pytest.approx(1000 * 0.02 * 0.02 * 0.04 + 0.002, rel=1e-6)
    np.testing.assert_allclose(sorted(spec.extents), [0.02, 0.02, 0.05], atol=1e-4)
    trimesh.creation.box((20.0, 30.0, 40.0)).export(tmp_path / "block.stl")
    urdf = tmp_path / "block.urdf"
    urdf.write_text('<robot name="r"><link name="l"><collision><geometry><mesh filename="block.stl"/></geometry>'
                    "</collision></link></robot>")
    assert cli.main(["objects", "check", str(urdf)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "--scale 0.001" in line
    spec = resolve_user_object(str(urdf), scale=0.001)
    np.testing.assert_allclose(sorted(spec.extents), [0.02, 0.03, 0.04], atol=1e-4)
    assert spec.mass == pytest.approx(DEFAULT_DENSITY * 0.02 * 0.03 * 0.04, rel=1e-3)


def test_mjcf_euler_follows_the_compilers_eulerseq_and_xyaxes_and_frames_turn_a_geom(tmp_path):
    """A 10 × 2 × 1 cm box turned by euler="90 0 0": about x by default (its long side stays along x),
    about z where the compiler's eulerseq starts with z (it then runs along y); xyaxes="0 1 0 -1 0 0"
    turns it a quarter about z too. Told apart by a 1 cm cube beside it at x = 8 cm."""
    def extents(compiler: str, orientation: str) -> list:
        path = _one_body_mjcf(tmp_path / f"turned{len(list(tmp_path.iterdir()))}.xml",
                              f'<geom type="box" size="0.05 0.01 0.005" {orientation}/>'
                              '<geom type="box" size="0.005 0.005 0.005" pos="0.08 0 0"/>', compiler)
        return sorted(np.round(resolve_user_object(str(path), join_gap=0.1).extents, 4))

    assert extents("", 'euler="90 0 0"') == pytest.approx([0.01, 0.02, 0.135])
    assert extents('<compiler eulerseq="zyx"/>', 'euler="90 0 0"') == pytest.approx([0.01, 0.095, 0.1])
    assert extents("", 'xyaxes="0 1 0 -1 0 0"') == pytest.approx([0.01, 0.095, 0.1])
    # A MuJoCo 3 <frame> places what it holds: the same quarter turn about z, through a frame.
    framed = tmp_path / "framed.xml"
    framed.write_text('<mujoco><worldbody><frame pos="1 0 0"><body><frame euler="0 0 90">'
                      '<geom type="box" size="0.05 0.01 0.005"/></frame>'
                      '<geom type="box" size="0.005 0.005 0.005" pos="0.08 0 0"/></body></frame></worldbody></mujoco>')
    assert sorted(np.round(resolve_user_object(str(framed), join_gap=0.1).extents, 4)) == pytest.approx([0.01, 0.095, 0.1])
    bad = _one_body_mjcf(tmp_path / "bad_seq.xml", '<geom type="box" size="0.05 0.01 0.01"/>',
                         '<compiler eulerseq="xyw"/>')
    with pytest.raises(ObjectError, match="eulerseq 'xyw'"):
        resolve_user_object(str(bad))


def test_an_mjcf_mesh_named_relative_to_a_folder_its_project_sets_is_found_for_the_hint(tmp_path, capsys):
    """robogym loads its MJCF files from code that sets the mesh folder (assets/stls); the files name
    their meshes relative to it. As MuJoCo would, the file is refused, in one line that says where the
    mesh is and what to add; with that added, it loads."""
    stls, xmls = tmp_path / "assets" / "stls" / "parts", tmp_path / "assets" / "xmls" / "things"
    stls.mkdir(parents=True)
    xmls.mkdir(parents=True)
    trimesh.creation.box((0.04, 0.03, 0.02)).export(stls / "box.stl")
    body = '<asset><mesh file="parts/box.stl" name="b"/></asset><worldbody><body><geom type="mesh" mesh="b"/></body></worldbody>'
    path = xmls / "thing.xml"
    path.write_text(f"<mujoco>{body}</mujoco>")
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    hint = f'<compiler meshdir="{tmp_path / "assets" / "stls"}"/>'
    assert "not found" in line and hint in line
    path.write_text(f"<mujoco>{hint}{body}</mujoco>")
    assert sorted(resolve_user_object(str(path)).extents) == pytest.approx([0.02, 0.03, 0.04])


def test_a_model_files_convex_piece_whose_triangles_close_nothing_is_its_hull(tmp_path):
    """pybullet's dinnerware (a plate, a pan) gives its rim as 8-vertex convex pieces whose 16
    triangles overlap and close nothing. Bullet, MuJoCo and Drake's point contact collide a mesh as
    its convex hull, so in a model file such a piece is its hull; a bare mesh file of it declares no
    engine and is still refused, and so is a flat piece whose hull has no volume."""
    import itertools

    corners = trimesh.creation.box((0.04, 0.03, 0.02)).vertices
    fan = [(0, i, j) for i, j in itertools.combinations(range(1, 8), 2)][:16]
    piece = tmp_path / "piece.obj"
    piece.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in corners) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in fan))

    def urdf(mesh_name: str) -> str:
        return (f'<robot name="r"><link name="l"><collision><geometry><mesh filename="{mesh_name}"/></geometry>'
                "</collision></link></robot>")

    (tmp_path / "plate.urdf").write_text(urdf("piece.obj"))
    spec, notes = _load(type("Case", (), {"path": tmp_path / "plate.urdf", "scale": 1.0}))
    np.testing.assert_allclose(sorted(spec.extents), [0.02, 0.03, 0.04], atol=1e-6)
    assert any("convex hull: a convex piece" in note for note in notes)
    with pytest.raises(ObjectError, match="sheet"):
        resolve_user_object(str(piece))
    flat = tmp_path / "flat.obj"
    flat.write_text("v 0 0 0\nv 0.05 0 0\nv 0.05 0.05 0\nv 0 0.05 0\nf 1 2 3\nf 1 3 4\n")
    (tmp_path / "flat.urdf").write_text(urdf("flat.obj"))
    with pytest.raises(ObjectError):
        resolve_user_object(str(tmp_path / "flat.urdf"))


def test_the_note_of_a_joined_hull_set_gives_the_widest_gap_it_bridged(zoo):
    (gaps,) = [c for c in zoo if c.defect == "hull_gaps"]
    _, notes = _load(gaps)
    (note,) = [n for n in notes if "closed shells within the join gap" in n]
    bridged = float(note.split("gaps up to ")[1].split(" mm")[0])
    assert 0.1 < bridged <= 2.0  # the zoo moves its cells 0.25-1 mm apart each


def test_a_thin_solid_open_by_a_few_edges_is_closed_and_kept_and_a_wavy_sheet_is_not():
    """A 40 × 30 × 1 cm slab missing one small triangle (a model airplane's airframe open by three
    edges) is thin for its extent, yet its hole is a speck: it is a solid and is kept. A curved sheet,
    whose boundary is its whole rim, is dropped as before."""
    slab = trimesh.creation.box((0.4, 0.3, 0.01))
    for _ in range(5):
        slab = slab.subdivide()
    top = np.flatnonzero(slab.triangles_center[:, 2] > 0.004)[0]
    holed = trimesh.Trimesh(slab.vertices, np.delete(slab.faces, top, axis=0), process=False)
    assert not holed.is_watertight
    shells, report = repair.closed_shells(holed)
    assert len(shells) == 1 and shells[0].volume == pytest.approx(slab.volume, rel=1e-3)
    assert report.closed_patches == 1 and report.open_edges == 3
    x, y = np.meshgrid(np.linspace(0, 0.1, 11), np.linspace(0, 0.1, 11))
    z = 0.02 * np.sin(x * 60.0)
    grid = np.arange(121).reshape(11, 11)
    faces = [[grid[i, j], grid[i, j + 1], grid[i + 1, j + 1]] for i in range(10) for j in range(10)] + \
            [[grid[i, j], grid[i + 1, j + 1], grid[i + 1, j]] for i in range(10) for j in range(10)]
    wavy = trimesh.Trimesh(np.c_[x.ravel(), y.ravel(), z.ravel()], np.array(faces), process=False)
    with pytest.raises(repair.RepairError):
        repair.closed_shells(wavy)


def test_a_urdf_whose_visuals_drake_cannot_parse_loads_without_them(tmp_path):
    """VIMA-Bench's Hanoi stand writes a colour as "r, g, b a" (pybullet takes it; Drake's parser wants
    four numbers). The visuals are replaced by ours: the object loads without them, with a note."""
    visual = ('<visual><geometry><box size="0.04 0.05 0.06"/></geometry><material name="wood">'
              '<color rgba="0.61, 0.45, 0.37 1"/></material></visual>')
    path = _write_urdf(tmp_path / "block.urdf", f'<link name="block">{visual}<collision><geometry>'
                       '<box size="0.04 0.05 0.06"/></geometry></collision></link>')
    spec, notes = _load(type("Case", (), {"path": path, "scale": 1.0}))
    assert any("visual elements left out" in note and "rgba" in note for note in notes)
    np.testing.assert_allclose(sorted(spec.extents), [0.04, 0.05, 0.06], atol=1e-6)


def test_a_urdf_still_in_xacro_is_told_to_expand_it(tmp_path, capsys):
    """A ROS description saved as .urdf before xacro ran: the parse error says what to do."""
    path = tmp_path / "thing.urdf"
    path.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="thing"><xacro:property name="s" '
                    'value="0.05"/><link name="box"><collision><geometry><box size="${s} ${s} ${s}"/></geometry>'
                    "</collision></link></robot>")
    assert cli.main(["objects", "check", str(path)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "cannot parse" in line and "xacro FILE > object.urdf" in line


def test_an_sdf_world_is_read_as_its_one_free_model_beside_a_static_scene(tmp_path, capsys):
    """An SDFormat world with a static ground and one free model: the object is that model, the scene
    left out with a note, as for MJCF. Two free models are refused in one line naming them."""
    inertial = ("<inertial><mass>0.2</mass><inertia><ixx>1e-4</ixx><iyy>1e-4</iyy><izz>1e-4</izz><ixy>0</ixy>"
                "<ixz>0</ixz><iyz>0</iyz></inertia></inertial>")

    def model(name: str, static: bool, size: str) -> str:
        return (f'<model name="{name}"><static>{str(static).lower()}</static><pose>0.5 0 0.05 0 0 0</pose>'
                f'<link name="link">{inertial}<collision name="c"><geometry><box><size>{size}</size></box>'
                "</geometry></collision></link></model>")

    world = tmp_path / "scene.sdf"
    world.write_text(f'<sdf version="1.7"><world name="w">{model("ground", True, "2 2 0.01")}'
                     f'{model("block", False, "0.04 0.05 0.06")}</world></sdf>')
    spec, notes = _load(type("Case", (), {"path": world, "scale": 1.0}))
    assert any("the free model 'block'" in note and "'ground'" in note for note in notes)
    np.testing.assert_allclose(sorted(spec.extents), [0.04, 0.05, 0.06], atol=1e-6)
    two = tmp_path / "two.sdf"
    two.write_text(f'<sdf version="1.7"><world name="w">{model("a", False, "0.04 0.04 0.04")}'
                   f'{model("b", False, "0.04 0.04 0.04")}</world></sdf>')
    assert cli.main(["objects", "check", str(two)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert "expected one model, found 2 (2 free: 'a', 'b')" in line


def test_the_check_says_what_its_pieces_are(tmp_path, capsys):
    """A model file of Drake's primitives has no mesh vertices to count: the check names its shapes
    (it said "(0 vertices)")."""
    path = _write_urdf(tmp_path / "block.urdf", _link("block", "0.05 0.05 0.05", 0.1))
    assert cli.main(["objects", "check", path]) == 0
    assert "1 convex piece for contact (a box)" in capsys.readouterr().out


def test_a_mesh_standing_on_its_lowest_face_only_just_is_laid_on_its_most_stable_face(tmp_path):
    """A plank 5.8 mm thick and 22 cm tall on its end has its centre of mass 1.5° inside its base: over
    the lowest-face test's 1°, but set down 2° from upright, as a hand sets it, it falls (BulletArm's
    3DNet zucchini fell so in the trial's first second). It is laid down, with the warning; a 2.7 cm
    board as tall, 7° inside, still stands."""
    trimesh.creation.box((0.06, 0.0058, 0.22)).export(tmp_path / "plank.obj")
    spec, notes = _load(type("Case", (), {"path": tmp_path / "plank.obj", "scale": 1.0}))
    assert any("only just inside its base" in note for note in notes)
    assert spec.rest_height < 0.04
    trimesh.creation.box((0.06, 0.027, 0.22)).export(tmp_path / "board.obj")
    spec, notes = _load(type("Case", (), {"path": tmp_path / "board.obj", "scale": 1.0}))
    assert not any("tip over" in note for note in notes) and spec.rest_height == pytest.approx(0.11, abs=1e-3)
