"""The robot models: kinematics against the D-H tables, and model hygiene."""

import math

import numpy as np
import pytest
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from drake_grasp.robot import hand, modelgen
from drake_grasp.paths import RegisterPackage


def _rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _trans(x, y, z):
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def barrett_fingertip(finger, spread, proximal, distal):
    """Fingertip position in frame W, written from the BH8 manual's modified D-H table.

    The numbers are typed here again on purpose (not read from drake_grasp.robot.hand), so that a wrong
    constant in the package cannot hide behind the same wrong constant in the test.
    """
    Aw, A1, A2, A3, D3, Dw = 0.025, 0.050, 0.070, 0.050, 0.0095, 0.0754
    phi2, phi3 = 0.0, math.radians(42)
    r = {1: -1, 2: 1, 3: 0}[finger]
    j = {1: 1, 2: 1, 3: -1}[finger]
    rows = [  # (a_{i-1}, alpha_{i-1}, d_i, theta_i)
        (r * Aw, 0, Dw, r * spread - math.pi / 2 * j),
        (A1, math.pi / 2, 0, proximal + phi2),
        (A2, 0, 0, distal + phi3),
        (A3, -math.pi / 2, D3, 0),
    ]
    T = np.eye(4)
    for a, alpha, d, theta in rows:
        T = T @ _rot_x(alpha) @ _trans(a, 0, 0) @ _rot_z(theta) @ _trans(0, 0, d)
    return T[:3, 3]


def wam_flange(q):
    """Flange position in the WAM base frame, from the WAM manual's classical D-H table."""
    rows = [(0, -math.pi / 2, 0), (0, math.pi / 2, 0), (0.045, -math.pi / 2, 0.55),
            (-0.045, math.pi / 2, 0), (0, -math.pi / 2, 0.30), (0, math.pi / 2, 0), (0, 0, 0.06)]
    T = _trans(0, 0, 0.346)
    for (a, alpha, d), qi in zip(rows, q):
        T = T @ _rot_z(qi) @ _trans(0, 0, d) @ _trans(a, 0, 0) @ _rot_x(alpha)
    return T


def _load(path):
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.001)
    parser = RegisterPackage(Parser(plant))
    (model,) = parser.AddModels(str(path))
    return builder, plant, model


@pytest.mark.parametrize("finger", [1, 2, 3])
@pytest.mark.parametrize(
    "spread, proximal, distal",
    [(0, 0, 0), (math.radians(60), 1.0, 0.3), (math.radians(170), 2.4, 0.8), (0.5, 0.3, 0.84)],
)
def test_fingertip_matches_dh_table(finger, spread, proximal, distal):
    builder, plant, model = _load(modelgen.HAND_SDF)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("bh_base"))
    plant.Finalize()
    context = plant.CreateDefaultContext()
    for f in (1, 2):
        plant.GetJointByName(f"bh_spread_{f}").set_angle(context, spread)
    for f in (1, 2, 3):
        plant.GetJointByName(f"bh_proximal_{f}").set_angle(context, proximal)
        plant.GetJointByName(f"bh_distal_{f}").set_angle(context, distal)
    X_WT = plant.GetFrameByName(f"bh_tip_{finger}").CalcPoseInWorld(context)
    expected = barrett_fingertip(finger, spread, proximal, distal)
    np.testing.assert_allclose(X_WT.translation(), expected, atol=1e-4)
    # The package's own pure forward kinematics (used to keep fingertips off the table) agrees.
    from drake_grasp.robot import hand
    p = hand.distal_points_in_base(finger, spread, proximal, distal, [[hand.A3, hand.D3, 0.0]])[0]
    np.testing.assert_allclose(p, expected, atol=1e-9)


def test_open_hand_is_flat_and_spherical_mode_is_120_degrees_apart():
    # In the spherical mode (each spread joint at 60 deg) the three fingers point 120 deg apart
    # (docs/design.md §2): compare the directions in which the open fingers point, knuckle to tip.
    angles = []
    for finger in (1, 2, 3):
        knuckle = np.array([{1: -0.025, 2: 0.025, 3: 0.0}[finger], 0, 0])
        tip = barrett_fingertip(finger, math.radians(60), 0, 0)
        assert tip[2] > 0.0754  # the distal link's 42 deg bend lifts the tip above the knuckle.
        angles.append(math.atan2(tip[1] - knuckle[1], tip[0] - knuckle[0]))
    diffs = sorted((b - a) % (2 * math.pi) for a, b in zip(angles, angles[1:] + angles[:1]))
    np.testing.assert_allclose(diffs, [2 * math.pi / 3] * 3, atol=0.1)


@pytest.mark.parametrize(
    "q", [np.zeros(7), np.array([0.3, -1.0, 0.4, 2.0, -0.5, 0.7, 1.1]), np.array([-1, 1.5, -2, 0.5, 1, -1.2, 2.5])]
)
def test_wam_flange_matches_dh_table(q):
    builder, plant, model = _load(modelgen.WAM_SDF)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("wam_base"))
    plant.Finalize()
    context = plant.CreateDefaultContext()
    plant.SetPositions(context, model, q)
    X_WF = plant.GetFrameByName("wam_flange").CalcPoseInWorld(context)
    T = wam_flange(q)
    np.testing.assert_allclose(X_WF.translation(), T[:3, 3], atol=1e-4)
    np.testing.assert_allclose(X_WF.rotation().matrix(), T[:3, :3], atol=1e-6)


def test_model_files_are_generated_from_the_facts():
    assert modelgen.HAND_SDF.read_text() == modelgen.hand_sdf(), "run: drake-grasp models"
    assert modelgen.WAM_SDF.read_text() == modelgen.wam_sdf(), "run: drake-grasp models"
    assert modelgen.DISTAL_OBJ.read_text() == modelgen.distal_obj(), "run: drake-grasp models"


def test_the_bh8_280s_distal_link_shape_has_its_pad_taper_and_rounded_tip(tmp_path):
    """The BH8-280's distal link as measured (hand.py's numbers, design.md §4.1a): the tip frame lies on the flat pad, the back tapers, and the rounded tip reaches 8.5 mm
    past A3, narrower than the link and below the pad, so its leading point is not a square edge.
    Its mesh is a closed convex solid that Drake loads as a convex shape."""
    import trimesh
    from pydrake.geometry import Convex

    path = tmp_path / "distal.obj"
    path.write_text(modelgen.distal_obj())
    mesh = trimesh.load(path, force="mesh")
    assert mesh.is_watertight and mesh.is_convex and mesh.volume > 0
    lo, hi = mesh.bounds
    assert hi[0] == pytest.approx(hand.DISTAL_TIP_REACH, abs=1e-4)
    assert hi[1] == pytest.approx(hand.D3, abs=1e-6)  # the pad, on which the tip frame lies
    assert hi[2] - lo[2] == pytest.approx(hand.DISTAL_WIDTH, abs=1e-6)
    v = mesh.vertices
    root, end = v[v[:, 0] < 1e-6], v[np.abs(v[:, 0] - hand.A3) < 2e-3]
    assert root[:, 1].min() == pytest.approx(hand.DISTAL_BACK_Y_ROOT, abs=1e-6)
    assert end[:, 1].min() > hand.DISTAL_BACK_Y_ROOT + 0.003  # tapered: thinner at A3 than at the joint
    tip = v[v[:, 0] > hand.DISTAL_TIP_REACH - 1e-4]
    assert np.ptp(tip[:, 2]) < 0.5 * hand.DISTAL_WIDTH  # rounded across the width
    assert tip[:, 1].max() < hand.D3 - 0.002  # and in the closing plane: the nose lies below the pad
    assert hand.A3 < hand.distal_pad_end() < hand.DISTAL_TIP_REACH
    assert Convex(str(path)).GetConvexHull().num_vertices() == len(mesh.vertices)


def test_the_model_s_distal_links_are_that_shape_and_the_sweep_follows_their_tips():
    """The hand model uses the mesh (convex, so SceneGraph collides with its exact hull), and the
    fingertips' sweep below the palm, which sets every top-down grasp's height, is that shape's."""
    builder, plant, model = _load(modelgen.HAND_SDF)
    plant.Finalize()
    diagram = builder.Build()
    inspector = diagram.GetSubsystemByName("scene_graph").model_inspector()
    body = plant.GetBodyByName("bh_finger_1_distal", model)
    (geometry,) = plant.GetCollisionGeometriesForBody(body)
    hull = inspector.GetConvexHull(geometry)
    reach = max(hull.vertex(i)[0] for i in range(hull.num_vertices()))
    assert reach == pytest.approx(hand.DISTAL_TIP_REACH, abs=1e-6)
    assert body.default_mass() == pytest.approx(hand.DISTAL_MASS)
    # The sweep's deepest point over the shape lies deeper than the old box's square tip edge at A3.
    box_edge = np.array([[hand.A3, y, 0.0] for y in (-hand.D3, hand.D3)])
    box_depth = max(float(hand.distal_points_in_base(f, 0.0, q, q / 3, box_edge)[:, 2].max()) - hand.PALM_HEIGHT
                    for q in np.linspace(0, hand.PROXIMAL_LIMITS[1], 141) for f in hand.FINGERS)
    assert hand.fingertip_sweep_depth(0.0) > box_depth


def test_hand_joint_names_ranges_and_masses():
    builder, plant, model = _load(modelgen.HAND_SDF)
    plant.Finalize()
    names = {plant.get_joint(i).name() for i in plant.GetJointIndices(model)}
    for n in ["bh_spread_1", "bh_spread_2"] + [f"bh_{k}_{f}" for k in ("proximal", "distal") for f in (1, 2, 3)]:
        assert n in names
    assert "bh_spread_3" not in names
    assert plant.GetJointByName("bh_proximal_2").position_upper_limits()[0] == pytest.approx(math.radians(140))
    assert plant.GetJointByName("bh_distal_3").position_upper_limits()[0] == pytest.approx(math.radians(48))
    assert plant.GetJointByName("bh_spread_1").position_upper_limits()[0] == pytest.approx(math.pi)
    finger_mass = sum(plant.GetBodyByName(f"bh_finger_1_{p}").default_mass() for p in ("knuckle", "proximal", "distal"))
    assert finger_mass == pytest.approx(0.244, abs=1e-3)  # jhu per-link masses: 0.141 + 0.062 + 0.041
    assert plant.CalcTotalMass(plant.CreateDefaultContext()) == pytest.approx(0.664 + 3 * 0.244, abs=1e-3)


@pytest.mark.parametrize("path", [modelgen.HAND_SDF, modelgen.WAM_SDF, modelgen.MODELS_DIR / "table" / "table.sdf"])
def test_every_model_loads_finalizes_and_simulates_without_warnings(path, caplog):
    import logging

    caplog.set_level(logging.WARNING, logger="drake")
    builder, plant, model = _load(path)
    plant.Finalize()
    diagram = builder.Build()
    simulator = Simulator(diagram)
    simulator.AdvanceTo(0.1)
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING], caplog.text
    q = plant.GetPositions(plant.GetMyContextFromRoot(simulator.get_context()))
    assert np.all(np.isfinite(q))
