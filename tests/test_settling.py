"""Where a body set down on the table comes to rest (drake_grasp/objects/settling.py): the quasi-static
roll of its hull as plain functions, and the settle in the station's own simulator for model files."""

import math
import warnings

import numpy as np
import pytest
import trimesh

from drake_grasp import objects
from drake_grasp.objects.settling import base_margin_deg, resting_rotation, roll_to_rest, stays


def _box(size, rotation=None):
    box = trimesh.creation.box(size)
    if rotation is not None:
        box.apply_transform(rotation)
    return np.asarray(box.vertices)


def test_a_box_on_its_face_stays_and_its_margin_is_the_tipping_angle():
    vertices = _box((0.04, 0.06, 0.02))
    rest = roll_to_rest(vertices, np.zeros(3))
    assert rest.turned_deg < 0.1
    assert rest.height == pytest.approx(0.01, abs=1e-6)
    # Tipped about its shorter half-width: atan(0.02 / 0.01).
    assert rest.margin_deg == pytest.approx(math.degrees(math.atan2(0.02, 0.01)), abs=0.5)
    assert stays(vertices, np.zeros(3))


def test_a_box_set_down_on_its_edge_rolls_onto_the_nearer_face():
    # Turned 30° about x: the face it is nearer (30° away) is where it falls, not the other (60°).
    vertices = _box((0.04, 0.06, 0.02), trimesh.transformations.rotation_matrix(math.radians(30.0), [1, 0, 0]))
    rest = roll_to_rest(vertices, np.zeros(3))
    assert rest.turned_deg == pytest.approx(30.0, abs=0.3)
    assert rest.height == pytest.approx(0.01, abs=2e-4)
    assert rest.margin_deg > 40.0
    assert not stays(vertices, np.zeros(3))


def test_a_centre_of_mass_over_the_corner_side_rolls_over_two_edges():
    # A 4 cm cube set down on a corner (its diagonal vertical): it turns about the corner, then an edge,
    # and rests on a face, its centre 2 cm up.
    cube = trimesh.creation.box((0.04, 0.04, 0.04))
    axis = np.cross([1.0, 1.0, 1.0], [0.0, 0.0, 1.0])
    angle = math.acos(1.0 / math.sqrt(3.0)) - 0.05  # not quite balanced on the corner
    cube.apply_transform(trimesh.transformations.rotation_matrix(angle, axis))
    rest = roll_to_rest(np.asarray(cube.vertices), np.zeros(3))
    assert rest.height == pytest.approx(0.02, abs=3e-4)
    assert rest.margin_deg == pytest.approx(45.0, abs=1.0)


def test_a_base_of_one_edge_has_no_margin():
    offsets = np.array([[0.0, -0.01, -0.02], [0.0, 0.01, -0.02], [0.0, 0.0, 0.03]])
    assert base_margin_deg(offsets, np.array([0.0, 0.0, -1.0]), 0.02) == 0.0


@pytest.mark.parametrize("down", [(0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.3, -0.4, 0.5), (0.0, 0.0, 1.0)])
def test_the_resting_rotation_turns_down_to_the_table(down):
    d = np.asarray(down) / np.linalg.norm(down)
    np.testing.assert_allclose(resting_rotation(d) @ d, [0.0, 0.0, -1.0], atol=1e-12)


def _post_on_a_blunt_point(tmp_path, drop: float):
    """A URDF post 3 × 3 × 12 cm whose bottom is a shallow pyramid `drop` (m) deep: its base corners stand
    within the old test's tolerance of its apex, so that test took it to stand."""
    top = [[x, y, z] for x in (-0.015, 0.015) for y in (-0.015, 0.015) for z in (drop, 0.12)]
    post = trimesh.convex.convex_hull(np.array(top + [[0.003, 0.002, 0.0]]))
    post.export(tmp_path / "post.obj")
    (tmp_path / "post.urdf").write_text("""<robot name="post"><link name="post">
  <inertial><origin xyz="0 0 0.062"/><mass value="0.1"/>
    <inertia ixx="1.3e-4" ixy="0" ixz="0" iyy="1.3e-4" iyz="0" izz="1.5e-5"/></inertial>
  <collision><geometry><mesh filename="post.obj"/></geometry></collision></link></robot>""")
    return str(tmp_path / "post.urdf")


def test_a_urdf_standing_on_a_blunt_point_rests_as_it_falls_in_the_simulator(tmp_path):
    """A post on a 4 mm deep pyramid falls (as pybullet's random object 306 did, while the camera looked);
    its rest is where the station's simulator lets it fall, lying on a long side, with a warning."""
    with pytest.warns(objects.UnstablePoseWarning, match="would tip over .* in the simulator"):
        spec = objects.resolve_user_object(_post_on_a_blunt_point(tmp_path, 0.004))
    assert spec.rest_height < 0.025  # lying: about 1.5 cm, where it stood 6 cm


def test_a_urdf_on_a_flat_base_stays_without_the_simulator(tmp_path, monkeypatch, recwarn):
    from drake_grasp.objects import settling

    def refuse(*args, **kwargs):
        raise AssertionError("a flat-based body needs no settle")

    monkeypatch.setattr(settling, "settle_in_simulator", refuse)
    spec = objects.resolve_user_object(_post_on_a_blunt_point(tmp_path, 0.0))
    assert spec.R_TO.IsExactlyIdentity()
    assert not [w for w in recwarn if issubclass(w.category, objects.UnstablePoseWarning)]


def test_a_body_the_simulator_cannot_settle_stands_as_its_file_has_it(tmp_path, monkeypatch):
    from drake_grasp.objects import settling

    def diverge(*args, **kwargs):
        raise RuntimeError("the discrete solver failed to converge\nat time 0.005")

    monkeypatch.setattr(settling, "settle_in_simulator", diverge)
    with pytest.warns(objects.UnstablePoseWarning, match="could not settle it in the simulator .*converge"):
        spec = objects.resolve_user_object(_post_on_a_blunt_point(tmp_path, 0.004))
    assert spec.R_TO.IsExactlyIdentity()


def _can_on_a_bulge(bulge: float) -> trimesh.Trimesh:
    """A can 6.6 cm across and 10 cm tall whose bottom bulges `bulge` (m) below its rim at the centre,
    as YCB's scanned cans stand."""
    angles = np.linspace(0.0, 2.0 * math.pi, 48, endpoint=False)
    rim = [[0.033 * math.cos(a), 0.033 * math.sin(a), z] for a in angles for z in (0.0, 0.1)]
    return trimesh.convex.convex_hull(np.array(rim + [[0.0, 0.0, -bulge]]))


def test_a_mesh_can_on_a_bulge_stands_as_it_settles_and_a_steep_one_lies_down(tmp_path):
    # The lowest-face test sees a point under the can; the simulator, a can that rocks onto its rim.
    from drake_grasp.objects.mesh_files import _rests_stably_upright

    for bulge, stands in ((0.001, True), (0.012, False)):
        can = _can_on_a_bulge(bulge)
        assert not _rests_stably_upright(can.convex_hull, can.center_mass)
        path = tmp_path / f"can_{bulge}.obj"
        can.export(path)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            spec = objects.object_from_mesh(path)
        tipped = [w for w in caught if issubclass(w.category, objects.UnstablePoseWarning)]
        assert (not tipped) is stands
        z_up = abs(float((spec.R_TO.matrix() @ np.array([0.0, 0.0, 1.0]))[2]))
        assert (z_up > 0.999) is stands
