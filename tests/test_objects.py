"""Tests of the object catalogue (drake_grasp.objects) and its contact snippets (.contact).

(a) the nine paper objects and the primitive families have the sizes and masses of docs/design.md §4.3;
(b) each paper object, dropped a few mm onto a rigid table in its nominal pose, comes to rest and
    then stays put (no creep) at both the 5 ms and 10 ms time steps the station may use, with no
    parser or simulation warnings;
(c) user meshes: convex and non-convex files, the decomposition cache, and one-line errors.
"""

import logging
import math

import numpy as np
import pytest
import trimesh
from pydrake.common.yaml import yaml_load_typed
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from drake_grasp import objects
from drake_grasp.robot.contact import ContactParameters, rigid_proximity_sdf
from drake_grasp.objects import ObjectError

# docs/design.md §4.3's table: extents (x, y, z) in O (m; the banana's y, its sagitta plus diameter, is not
# given), mass (kg), class, and the grasp whose shape it resembles.
PAPER_TABLE = {
    "banana": ((0.18, None, 0.036), 0.12, "annulus", "cylinder"),
    "apple": ((0.075, 0.075, 0.072), 0.15, "annulus", "sphere"),
    "bell_pepper": ((0.085, 0.085, 0.09), 0.16, "annulus", "sphere"),
    "sponge": ((0.11, 0.07, 0.035), 0.012, "annulus", "box"),
    "spectacle_case": ((0.16, 0.06, 0.04), 0.06, "annulus", "box"),
    "toy_bridge": ((0.15, 0.05, 0.06), 0.10, "annulus", "box"),
    "soccer_ball": ((0.20, 0.20, 0.20), 0.30, "sun_ray_sphere", "sphere"),
    "game_box": ((0.26, 0.18, 0.08), 0.40, "sun_ray_box", "box"),
    "bottle_case": ((0.35, 0.10, 0.10), 0.35, "sun_ray_cylinder", "cylinder"),
}

# The settling protocol: drop from DROP above the rest height with a yaw, settle, then hold.
SETTLE_TIME = 0.5  # s
HOLD_TIME = 2.0  # s
DROP = 0.005  # m
YAW = 0.3  # rad
MAX_CREEP = 0.002  # m, during the hold
MAX_CREEP_ANGLE = math.radians(1.0)  # during the hold


@pytest.fixture(autouse=True, scope="module")
def _private_cache(tmp_path_factory):
    """Generated meshes go to a fresh cache, not the user's."""
    patch = pytest.MonkeyPatch()
    patch.setenv("DRAKE_GRASP_CACHE", str(tmp_path_factory.mktemp("cache")))
    objects._paper_object_cached.cache_clear()
    yield
    objects._paper_object_cached.cache_clear()
    patch.undo()


# --- (a) sizes, masses, ground truth -------------------------------------------------------------


def test_paper_objects_are_designs_table_in_order():
    assert objects.PAPER_OBJECTS == tuple(PAPER_TABLE)


@pytest.mark.parametrize("name", list(PAPER_TABLE))
def test_paper_object_sizes_and_masses(name):
    extents, mass, paper_class, primitive = PAPER_TABLE[name]
    spec = objects.paper_object(name)
    assert spec.name == name
    assert spec.mass == pytest.approx(mass)
    for actual, expected in zip(spec.extents, extents):
        if expected is not None:
            assert actual == pytest.approx(expected, abs=1e-6)
    assert spec.paper_class == paper_class
    assert spec.closest_primitive == primitive
    # O (the centre of mass) lies above the table top and below the object's top.
    assert 0.0 < spec.rest_height < spec.extents[2]
    assert spec.R_TO.IsExactlyIdentity()
    # A physically valid inertia about the centre of mass.
    moments = np.linalg.eigvalsh(spec.inertia_matrix())
    assert np.all(moments > 0.0)
    assert moments[0] + moments[1] >= moments[2] * (1.0 - 1e-9)
    assert max(spec.extents) / 2.0 <= spec.max_radius <= np.linalg.norm(spec.extents)


def test_paper_object_ground_truth_details():
    ball = objects.paper_object("soccer_ball")
    assert ball.rest_height == pytest.approx(0.10)
    assert ball.max_radius == pytest.approx(0.10)
    assert ball.inertia[:3] == pytest.approx([0.4 * 0.30 * 0.10**2] * 3)
    assert ball.principal_axis is None
    box = objects.paper_object("game_box")
    assert box.max_radius == pytest.approx(math.sqrt(0.13**2 + 0.09**2 + 0.04**2))
    assert box.inertia[0] == pytest.approx(0.40 / 12.0 * (0.18**2 + 0.08**2))
    bottle = objects.paper_object("bottle_case")
    assert bottle.principal_axis == pytest.approx((1.0, 0.0, 0.0))
    assert bottle.rest_height == pytest.approx(0.05)
    assert bottle.max_radius == pytest.approx(math.hypot(0.175, 0.05))
    assert objects.paper_object("banana").rest_height == pytest.approx(0.018)
    assert objects.paper_object("banana").principal_axis == pytest.approx((1.0, 0.0, 0.0), abs=1e-9)
    # The bridge's centre of mass: beam (0.15×0.05×0.02 at z = 0.05) on two legs (0.03×0.05×0.04
    # at z = 0.02): z = (1.5e-4·0.05 + 1.2e-4·0.02) / 2.7e-4.
    assert objects.paper_object("toy_bridge").rest_height == pytest.approx(9.9e-6 / 2.7e-4)
    for name in ("apple", "bell_pepper"):
        assert objects.paper_object(name).principal_axis is None
    for name in ("sponge", "spectacle_case", "toy_bridge", "game_box"):
        assert objects.paper_object(name).principal_axis == pytest.approx((1.0, 0.0, 0.0), abs=1e-9)


def test_default_density_is_about_the_paper_objects_median():
    specs = [objects.paper_object(name) for name in PAPER_TABLE]
    densities = [spec.mass / spec.volume for spec in specs]
    assert np.median(densities) == pytest.approx(objects.DEFAULT_DENSITY, rel=0.1)


def test_primitive_families():
    sphere = objects.sphere_object(0.12)
    assert sphere.extents == pytest.approx((0.12, 0.12, 0.12))
    assert sphere.mass == pytest.approx(objects.DEFAULT_DENSITY * math.pi / 6.0 * 0.12**3)
    assert sphere.closest_primitive == "sphere" and sphere.paper_class is None
    cube = objects.cube_object(0.08, mass=0.2)
    assert cube.extents == pytest.approx((0.08, 0.08, 0.08))
    assert cube.mass == 0.2 and cube.rest_height == pytest.approx(0.04)
    assert cube.principal_axis is None and cube.closest_primitive == "box"
    cylinder = objects.cylinder_object(0.1)
    assert cylinder.extents == pytest.approx((objects.CYLINDER_FAMILY_LENGTH, 0.1, 0.1))
    assert cylinder.principal_axis == pytest.approx((1.0, 0.0, 0.0))
    assert cylinder.rest_height == pytest.approx(0.05)
    assert objects.cylinder_object(0.05, 0.2).extents == pytest.approx((0.2, 0.05, 0.05))
    assert objects.resolve_object("sphere:0.12") == sphere
    assert objects.resolve_object("cube:0.08", mass=0.2) == cube
    assert objects.resolve_object("cylinder:0.1") == cylinder
    assert objects.resolve_object("cylinder:0.1x0.3") == cylinder
    assert objects.resolve_object("bottle_case") == objects.paper_object("bottle_case")
    domino = objects.resolve_object("box:0.05x0.025x0.01")
    assert domino.extents == pytest.approx((0.05, 0.025, 0.01)) and domino.rest_height == pytest.approx(0.005)
    assert domino.mass == pytest.approx(objects.DEFAULT_DENSITY * 0.05 * 0.025 * 0.01)
    assert domino.principal_axis == pytest.approx((1.0, 0.0, 0.0)) and domino.closest_primitive == "box"


def test_contact_parameters_load_from_yaml():
    data = "friction: 0.8\nhydroelastic_modulus: 2.0e6\n"
    contact = yaml_load_typed(schema=ContactParameters, data=data)
    assert contact.friction == 0.8 and contact.hydroelastic_modulus == 2.0e6
    assert contact.hunt_crossley_dissipation == ContactParameters().hunt_crossley_dissipation
    assert contact.resolution_hint(1.0) == contact.mesh_resolution_max
    assert contact.resolution_hint(1e-4) == contact.mesh_resolution_min


# --- (b) settling on a table ---------------------------------------------------------------------


def _table_sdf(contact: ContactParameters) -> str:
    return (
        '<?xml version="1.0"?><sdf version="1.9" xmlns:drake="http://drake.mit.edu">'
        '<model name="table"><link name="table"><collision name="top"><pose>0 0 -0.025 0 0 0</pose>'
        f"<geometry><box><size>1 1 0.05</size></box></geometry>{rigid_proximity_sdf(contact)}"
        "</collision></link></model></sdf>"
    )


def _drop_and_hold(spec, time_step: float, contact: ContactParameters | None = None):
    """Drops the object onto a rigid table (top at z = 0, so W = T) in its nominal pose.

    Returns:
        (X_WO after SETTLE_TIME, X_WO after another HOLD_TIME). Also checks that the contact with
        the table is hydroelastic (not the point-contact fallback).
    """
    contact = ContactParameters() if contact is None else contact
    builder = DiagramBuilder()
    config = MultibodyPlantConfig(
        time_step=time_step,
        contact_model="hydroelastic_with_fallback",
        discrete_contact_approximation="lagged",
    )
    plant, _ = AddMultibodyPlant(config, builder)
    parser = Parser(plant)
    parser.SetStrictParsing()
    (table,) = parser.AddModelsFromString(_table_sdf(contact), "sdf")
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("table", table))
    model = objects.AddObject(plant, spec, contact)
    plant.Finalize()
    diagram = builder.Build()
    simulator = Simulator(diagram)
    plant_context = plant.GetMyMutableContextFromRoot(simulator.get_mutable_context())
    body = plant.GetBodyByName(spec.name, model)
    X_WO = spec.nominal_X_TO(yaw=YAW)
    X_WO_start = RigidTransform(X_WO.rotation(), X_WO.translation() + [0.0, 0.0, DROP])
    plant.SetFreeBodyPose(plant_context, body, X_WO_start)
    simulator.AdvanceTo(SETTLE_TIME)
    X_WO_settled = plant.EvalBodyPoseInWorld(plant_context, body)
    simulator.AdvanceTo(SETTLE_TIME + HOLD_TIME)
    contact_results = plant.get_contact_results_output_port().Eval(plant_context)
    assert contact_results.num_hydroelastic_contacts() >= 1
    assert contact_results.num_point_pair_contacts() == 0
    return X_WO_settled, plant.EvalBodyPoseInWorld(plant_context, body)


def _angle(R_a: RotationMatrix, R_b: RotationMatrix) -> float:
    return R_a.inverse().multiply(R_b).ToAngleAxis().angle()


def _assert_rests(spec, X_WO_settled, X_WO_final):
    creep = np.linalg.norm(X_WO_final.translation() - X_WO_settled.translation())
    assert creep < MAX_CREEP, f"{spec.name} crept {creep * 1e3:.2f} mm"
    assert _angle(X_WO_settled.rotation(), X_WO_final.rotation()) < MAX_CREEP_ANGLE
    # It rests where the spec says: at rest_height (less a little compliant penetration), not
    # tilted from its nominal pose (landing may turn it a little about the vertical).
    assert X_WO_settled.translation()[2] == pytest.approx(spec.rest_height, abs=0.003)
    nominal = spec.nominal_X_TO(yaw=YAW)
    assert np.linalg.norm(X_WO_settled.translation()[:2] - nominal.translation()[:2]) < 0.005
    up_settled = X_WO_settled.rotation().matrix() @ spec.R_TO.matrix().T[:, 2]
    assert math.acos(min(up_settled[2], 1.0)) < math.radians(2.0)


@pytest.mark.parametrize("time_step", [0.005, 0.01])
@pytest.mark.parametrize("name", list(PAPER_TABLE))
def test_paper_object_rests_on_table(name, time_step, caplog):
    spec = objects.paper_object(name)
    with caplog.at_level(logging.WARNING):
        X_WO_settled, X_WO_final = _drop_and_hold(spec, time_step)
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING], caplog.text
    _assert_rests(spec, X_WO_settled, X_WO_final)


@pytest.mark.parametrize(
    "name", ["sphere:0.03", "cube:0.02", "cube:0.3", "cylinder:0.03", "cylinder:0.3", "box:0.05x0.025x0.01"]
)
def test_primitive_family_rests_on_table(name):
    spec = objects.resolve_object(name)
    _assert_rests(spec, *_drop_and_hold(spec, 0.01))


def test_contact_properties_reach_drake():
    """Drake 1.51 silently ignores unknown <drake:...> proximity elements: check the values."""
    contact = ContactParameters(
        friction=0.7, hydroelastic_modulus=2.0e6, hunt_crossley_dissipation=30.0
    )
    spec = objects.paper_object("banana", friction=0.6)
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=0.01), builder)
    model = objects.AddObject(plant, spec, contact)
    plant.Finalize()
    inspector = scene_graph.model_inspector()
    geometries = plant.GetCollisionGeometriesForBody(plant.GetBodyByName("banana", model))
    assert len(geometries) == len(spec.pieces)
    for geometry, piece in zip(geometries, spec.pieces):
        properties = inspector.GetProximityProperties(geometry)
        friction = properties.GetProperty("material", "coulomb_friction")
        assert friction.static_friction() == friction.dynamic_friction() == 0.6
        assert properties.GetProperty("material", "hunt_crossley_dissipation") == 30.0
        assert properties.GetProperty("hydroelastic", "hydroelastic_modulus") == 2.0e6
        hint = properties.GetProperty("hydroelastic", "resolution_hint")
        assert hint == pytest.approx(contact.resolution_hint(piece.characteristic_size()))
        assert properties.HasProperty("hydroelastic", "compliance_type")


def test_object_sdf_names_and_uris():
    sdf = objects.object_sdf(objects.paper_object("bell_pepper"))
    assert '<model name="bell_pepper">' in sdf and '<link name="bell_pepper">' in sdf
    assert "<uri>file:///" in sdf and "<drake:declare_convex/>" in sdf
    assert "<drake:compliant_hydroelastic/>" in sdf
    assert "<diffuse>0.95 0.8 0.1 1</diffuse>" in sdf


# --- (c) user meshes -----------------------------------------------------------------------------


def _l_prism(long=0.12, short=0.08, thickness=0.03, height=0.03) -> trimesh.Trimesh:
    """A closed L-shaped prism (non-convex), the L in the xy plane, extruded along z."""
    outline = np.array(
        [[0, 0], [long, 0], [long, thickness], [thickness, thickness], [thickness, short],
         [0, short]],
        float,
    )
    cap = [(0, 1, 2), (0, 2, 3), (0, 3, 5), (3, 4, 5)]  # Counter-clockwise seen from +z.
    n = len(outline)
    vertices = np.vstack(
        [np.column_stack([outline, np.zeros(n)]), np.column_stack([outline, np.full(n, height)])]
    )
    faces = [(c, b, a) for a, b, c in cap] + [(a + n, b + n, c + n) for a, b, c in cap]
    for i in range(n):
        j = (i + 1) % n
        faces += [(i, j, j + n), (i, j + n, i + n)]
    return trimesh.Trimesh(vertices, np.array(faces), process=False)


def _assert_one_line_error(call, path, *words):
    with pytest.raises(ObjectError) as info:
        call()
    message = str(info.value)
    assert "\n" not in message
    assert str(path) in message
    for word in words:
        assert word in message
    return message


def test_convex_box_mesh_is_one_piece(tmp_path):
    path = tmp_path / "box.stl"
    trimesh.creation.box((0.1, 0.05, 0.02)).export(path)
    spec = objects.object_from_mesh(path)
    assert spec.name == "box" and len(spec.pieces) == 1 and spec.pieces[0].kind == "convex"
    assert spec.extents == pytest.approx((0.1, 0.05, 0.02), abs=1e-6)
    assert spec.mass == pytest.approx(objects.DEFAULT_DENSITY * 1e-4, rel=1e-6)
    assert spec.rest_height == pytest.approx(0.01, abs=1e-6)
    assert spec.principal_axis == pytest.approx((1.0, 0.0, 0.0))
    assert spec.closest_primitive is None and spec.paper_class is None
    assert objects.resolve_object(str(path), mass=0.5).mass == 0.5


def test_stable_pose_lays_a_tall_cylinder_down(tmp_path):
    path = tmp_path / "can.stl"
    trimesh.creation.cylinder(radius=0.03, height=0.2, sections=32).export(path)
    upright = objects.object_from_mesh(path)
    assert upright.rest_height == pytest.approx(0.1, abs=1e-6)
    assert upright.principal_axis == pytest.approx((0.0, 0.0, 1.0))
    lying = objects.object_from_mesh(path, stable_pose=True)
    assert lying.rest_height == pytest.approx(0.03 * math.cos(math.pi / 32), abs=1e-6)
    assert abs((lying.R_TO.matrix() @ np.array(lying.principal_axis))[2]) < 1e-9
    _assert_rests(lying, *_drop_and_hold(lying, 0.01))


def test_a_mesh_that_would_tip_over_is_rested_on_a_stable_face(tmp_path):
    # A capsule given standing on its round end would fall over: by default it is laid down, saying so.
    path = tmp_path / "capsule.stl"
    trimesh.creation.capsule(height=0.12, radius=0.035).export(path)
    with pytest.warns(objects.UnstablePoseWarning, match="capsule.stl: with its z up the object would tip over"):
        lying = objects.object_from_mesh(path)
    assert lying.rest_height < 0.04 and abs((lying.R_TO.matrix() @ np.array(lying.principal_axis))[2]) < 1e-6
    assert objects.object_from_mesh(path, stable_pose=False).rest_height == pytest.approx(0.095, abs=1e-6)
    # A box tilted in its file so that its centre of mass is off its lowest face tips over too.
    tilted = trimesh.creation.box((0.02, 0.02, 0.2))
    tilted.apply_transform(trimesh.transformations.rotation_matrix(math.radians(30), [1, 0, 0]))
    tilted.export(tmp_path / "tilted.stl")
    with pytest.warns(objects.UnstablePoseWarning):
        objects.object_from_mesh(tmp_path / "tilted.stl")


def _standing_on_a_ridge(ridge: float) -> trimesh.Trimesh:
    """A 3 × 3 × 9 cm post whose lowest centimetre narrows to a ridge `ridge` wide (m), along y."""
    top = [[x, y, z] for x in (-0.015, 0.015) for y in (-0.015, 0.015) for z in (0.01, 0.09)]
    bottom = [[x, y, 0.0] for x in (-ridge / 2, ridge / 2) for y in (-0.015, 0.015)]
    return trimesh.convex.convex_hull(np.array(top + bottom))


def test_a_balance_on_a_ridge_is_not_a_rest_and_a_standing_pencil_is():
    """An object stands only where its centre of mass lies at least MIN_TIP_ANGLE inside its base:
    on a 1 mm ridge a 9 cm post's centre lies 0.5 mm inside (0.6°), and the simulation's compliant
    table tips it (pybullet's random_urdfs/372 fell so); on a 6 mm one (3.8°) it stands. A pencil
    0.9 cm across and 18.5 cm tall (2.8°, the standing generator's slenderest) stands."""
    from drake_grasp.objects.mesh_files import _rests_stably_upright

    for ridge, stands in ((0.001, False), (0.006, True)):
        post = _standing_on_a_ridge(ridge)
        assert _rests_stably_upright(post.convex_hull, post.center_mass) is stands
    pencil = trimesh.creation.cylinder(radius=0.0045, height=0.185, sections=24)
    pencil.apply_translation([0.0, 0.0, 0.0925])
    assert _rests_stably_upright(pencil.convex_hull, pencil.center_mass)


def test_a_urdf_that_would_tip_over_is_rested_on_a_stable_face(tmp_path):
    """A model file's frame is not always how its body rests: a URDF of the post on its 1 mm ridge is
    laid on a stable face, saying so, as a mesh file is (it stood z up before, and fell as a trial began)."""
    _standing_on_a_ridge(0.001).export(tmp_path / "post.obj")
    (tmp_path / "post.urdf").write_text("""<robot name="post"><link name="post">
  <inertial><origin xyz="0 0 0.048"/><mass value="0.1"/>
    <inertia ixx="7e-5" ixy="0" ixz="0" iyy="7e-5" iyz="0" izz="1.5e-5"/></inertial>
  <collision><geometry><mesh filename="post.obj"/></geometry></collision></link></robot>""")
    with pytest.warns(objects.UnstablePoseWarning, match="post.urdf: with its z up the object would tip over"):
        spec = objects.resolve_user_object(str(tmp_path / "post.urdf"))
    assert spec.rest_height < 0.02  # lying on a long side: 1.5 cm, where it stood 4.8 cm
    _standing_on_a_ridge(0.006).export(tmp_path / "post.obj")
    assert objects.resolve_user_object(str(tmp_path / "post.urdf")).rest_height > 0.04


def test_a_urdf_can_on_a_scanned_bulge_keeps_its_z_up(tmp_path, recwarn):
    """A scanned base is not one plane: YCB's tuna can stands on a bulge 4 mm below its rim. A URDF body
    is laid down only where it clearly tips over, so such a can (here a bulge 3 mm below the rim)
    stands as its file has it; the lowest-face test of a mesh file would turn it upside down."""
    can = trimesh.creation.cylinder(radius=0.042, height=0.033, sections=32)
    bulge = trimesh.creation.icosphere(radius=0.006).apply_translation([0.0, 0.0, -0.0165 + 0.003])
    trimesh.util.concatenate([can, bulge]).convex_hull.export(tmp_path / "can.obj")
    (tmp_path / "can.urdf").write_text("""<robot name="can"><link name="can">
  <inertial><mass value="0.2"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1.7e-4"/></inertial>
  <collision><geometry><mesh filename="can.obj"/></geometry></collision></link></robot>""")
    spec = objects.resolve_user_object(str(tmp_path / "can.urdf"))
    assert spec.R_TO.IsExactlyIdentity()
    assert not [w for w in recwarn if issubclass(w.category, objects.UnstablePoseWarning)]


def test_a_urdf_whose_centre_of_mass_lies_outside_its_geometry_keeps_its_z_up(tmp_path):
    """OCRTOC's plastic lemon gives its centre of mass as the origin, outside its mesh (here beside it):
    how it rests cannot be told from that, so it stands as its file has it (0.39.0's first rest rule
    stopped on it with "attempt to get argmax of an empty sequence")."""
    trimesh.creation.icosphere(radius=0.03).apply_translation([0.04, 0.0, 0.03]).export(tmp_path / "lemon.obj")
    (tmp_path / "lemon.urdf").write_text("""<robot name="lemon"><link name="lemon">
  <inertial><mass value="0.1"/><inertia ixx="4e-5" ixy="0" ixz="0" iyy="4e-5" iyz="0" izz="4e-5"/></inertial>
  <collision><geometry><mesh filename="lemon.obj"/></geometry></collision></link></robot>""")
    assert objects.resolve_user_object(str(tmp_path / "lemon.urdf")).R_TO.IsExactlyIdentity()


def test_a_mesh_that_rests_stably_keeps_its_orientation(tmp_path, recwarn):
    trimesh.creation.cylinder(radius=0.03, height=0.2, sections=32).export(tmp_path / "can.stl")
    assert objects.object_from_mesh(tmp_path / "can.stl").R_TO.IsExactlyIdentity()
    assert not [w for w in recwarn if issubclass(w.category, objects.UnstablePoseWarning)]


def test_inverted_mesh_is_flipped(tmp_path):
    mesh = trimesh.creation.box((0.1, 0.1, 0.1))
    mesh.invert()
    path = tmp_path / "inside_out.obj"
    mesh.export(path)
    assert objects.object_from_mesh(path).volume == pytest.approx(1e-3)


def test_non_convex_mesh_is_decomposed_once_and_rests(tmp_path, monkeypatch):
    path = tmp_path / "ell.stl"
    _l_prism().export(path)
    spec = objects.object_from_mesh(path)
    assert len(spec.pieces) >= 2
    assert spec.volume == pytest.approx(0.12 * 0.03 * 0.03 + 0.05 * 0.03 * 0.03, rel=1e-5)
    assert spec.extents == pytest.approx((0.12, 0.08, 0.03), abs=1e-6)
    # A second call reads the cache instead of decomposing again.
    import coacd

    def fail(*args, **kwargs):
        raise AssertionError("decomposed twice")

    monkeypatch.setattr(coacd, "run_coacd", fail)
    assert objects.object_from_mesh(path, mass=0.05).pieces == spec.pieces
    _assert_rests(spec, *_drop_and_hold(spec, 0.01))


def test_bad_meshes_give_one_line_errors(tmp_path):
    sheet = trimesh.Trimesh([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0.01], [0, 0.1, 0]], [[0, 1, 2], [0, 2, 3]])
    path = tmp_path / "sheet.stl"
    sheet.export(path)
    _assert_one_line_error(lambda: objects.object_from_mesh(path), path, "encloses no volume")

    flat = trimesh.creation.box((0.1, 0.1, 0.1))
    flat.vertices[:, 2] = 0.0
    path = tmp_path / "flat.stl"
    flat.export(path)
    _assert_one_line_error(lambda: objects.object_from_mesh(path), path, "zero volume")

    box = trimesh.creation.box((0.1, 0.1, 0.1))
    vertices = box.vertices.copy()
    vertices[0] = np.nan
    path = tmp_path / "nan.ply"
    trimesh.Trimesh(vertices, box.faces, process=False).export(path)
    _assert_one_line_error(lambda: objects.object_from_mesh(path), path, "not finite")

    path = tmp_path / "garbage.stl"
    path.write_text("not a mesh")
    _assert_one_line_error(lambda: objects.object_from_mesh(path), path)

    path = tmp_path / "missing.stl"
    _assert_one_line_error(lambda: objects.resolve_object(str(path)), path, "not found")


def test_unknown_names_and_bad_primitives():
    message = _assert_one_line_error(
        lambda: objects.resolve_object("teapot"), "teapot", "valid names"
    )
    assert all(name in message for name in objects.PAPER_OBJECTS)
    _assert_one_line_error(
        lambda: objects.resolve_object("sphere:big"), "sphere:big", "sphere:DIAMETER"
    )
    _assert_one_line_error(lambda: objects.resolve_object("box:0.05x0.02"), "box:0.05x0.02", "box:LENGTHxWIDTHxHEIGHT")
    _assert_one_line_error(lambda: objects.paper_object("teapot"), "teapot", "banana")


def test_object_from_sdf(tmp_path):
    path = tmp_path / "brick.sdf"
    path.write_text(
        '<?xml version="1.0"?><sdf version="1.9"><model name="brick"><link name="body">'
        "<inertial><pose>0 0 0.01 0 0 0</pose><mass>0.3</mass>"
        "<inertia><ixx>2e-4</ixx><iyy>3e-4</iyy>"
        "<izz>4e-4</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial>"
        '<collision name="c"><pose>0 0 0.01 0 0 0</pose>'
        "<geometry><box><size>0.1 0.08 0.06</size></box>"
        "</geometry></collision></link></model></sdf>"
    )
    spec = objects.resolve_object(str(path))
    assert spec.name == "brick" and spec.mass == 0.3
    assert spec.pieces[0].kind == "box" and spec.pieces[0].p_OP == pytest.approx((0, 0, 0))
    assert spec.inertia == pytest.approx((2e-4, 3e-4, 4e-4, 0, 0, 0))
    assert spec.rest_height == pytest.approx(0.03)


def test_the_cli_says_in_one_line_that_it_rested_a_mesh_on_a_stable_face(tmp_path, capsys):
    from drake_grasp import cli

    path = tmp_path / "capsule.stl"
    trimesh.creation.capsule(height=0.12, radius=0.035).export(path)
    assert cli.main(["plan-eigengrasp", "--object", str(path), "--steps", "30001", "--json"]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("drake-grasp plan-eigengrasp: warning: ") and "tip over" in err[0]


def test_a_decomposition_that_stops_with_an_error_falls_back_to_the_convex_hull(monkeypatch, tmp_path):
    """CoACD runs in a child process: when it aborts (it does on some meshes, taking its process with
    it), the user's command goes on with the part's convex hull for contact, and says so."""
    from drake_grasp.objects import pieces

    monkeypatch.setattr(pieces, "_COACD_CHILD", "import os; os.abort()")
    monkeypatch.setattr(pieces, "cache_dir", lambda: tmp_path)
    l_shape = trimesh.boolean.union([trimesh.creation.box((0.06, 0.02, 0.02)),
                                     trimesh.creation.box((0.02, 0.06, 0.02)).apply_translation([-0.02, 0.02, 0])],
                                    engine="manifold")
    assert l_shape.is_watertight and l_shape.volume < 0.9 * l_shape.convex_hull.volume
    with pytest.warns(Warning, match="CoACD could not decompose this part"):
        files = pieces._decompose(l_shape, "abort-test", 8, label="l.obj")
    assert len(files) == 1
    piece = trimesh.load(files[0], force="mesh")
    assert piece.volume == pytest.approx(l_shape.convex_hull.volume, rel=0.05)
