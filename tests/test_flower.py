"""The flower's generator: seeded, closed, and within the sizes of its classes."""

import numpy as np
import pytest

from drake_grasp.objects import flower


def test_the_flower_generator_is_seeded_and_its_objects_are_the_named_sizes(tmp_path):
    rows = flower.generate(22, 3, tmp_path)
    assert [r["class"] for r in rows] == list(flower.CLASSES) * 2
    again = flower.flower_object(3, 7)
    assert (tmp_path / rows[7]["file"]).read_text().count("\nv ") == len(again.mesh.vertices)
    for index in range(22):
        obj = flower.flower_object(3, index)
        assert obj.mesh.is_watertight and obj.mesh.volume > 0
        low, mid, high = sorted(obj.mesh.extents)
        if obj.shape_class == "plate":
            assert 0.006 - 1e-6 <= low <= 0.012 + 1e-6 and high <= 0.12 + 1e-6
        elif obj.shape_class in ("T", "L"):
            assert 0.015 - 1e-6 <= low <= 0.025 + 1e-6
        elif obj.shape_class == "stick":
            assert 0.01 - 1e-6 <= low and mid <= 0.02 + 1e-6 and 0.06 - 1e-6 <= high <= 0.14 + 1e-6
        elif obj.shape_class == "tile":
            assert 0.006 - 1e-6 <= low <= 0.012 + 1e-6 and 0.85 * high - 1e-6 <= mid and 0.04 * 0.85 <= mid and high <= 0.10 + 1e-6
        elif obj.shape_class == "pen":  # lying along x
            assert 0.009 * np.cos(np.pi / 6) - 1e-6 <= low and mid <= 0.013 + 1e-6 and 0.11 - 1e-6 <= obj.mesh.extents[0] <= 0.15 + 1e-6
        elif obj.shape_class in ("domino", "standing_domino"):
            assert 0.008 - 1e-6 <= low <= 0.012 + 1e-6 and 0.022 - 1e-6 <= mid <= 0.028 + 1e-6 and 0.044 - 1e-6 <= high <= 0.056 + 1e-6
            assert (obj.mesh.extents[2] == high) == (obj.shape_class == "standing_domino")  # on its end, or lying
        elif obj.shape_class == "cube":
            assert 0.02 - 1e-6 <= low and high <= 0.03 + 1e-6 and high - low < 1e-4
        else:  # ball, fruit
            assert 0.04 - 1e-3 <= high <= 0.08 + 1e-3
    np.testing.assert_array_equal(flower.flower_object(3, 4).mesh.vertices, flower.flower_object(3, 4).mesh.vertices)
    # The six-class cycle of the results stored up to behaviour 0.7.0 still regenerates.
    old = flower.flower_object(0, 7, flower.CLASSES_0_7)
    assert old.name == "T_0_007" and old.mesh.is_watertight


def test_flower_check_refuses_an_unknown_class_in_one_line(capsys):
    from script_loader import load_script

    module = load_script("flower_check")
    assert module.main(["--classes", "ball,pear"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--classes: choose from " + ", ".join(flower.CLASSES) in err
    assert module.main(["--classes", "cube", "--six-classes"]) == 2
    assert "--classes: choose from plate, T, L, stick, ball, fruit" in capsys.readouterr().err


def test_the_trial_command_takes_the_flower_grasp_by_its_name():
    from drake_grasp.cli import _parser

    args = _parser().parse_args(["trial", "--object", "box:0.05x0.025x0.01", "--grasp", "flower", "--oracle"])
    assert args.grasp == "precision"  # the records' name
    with pytest.raises(SystemExit) as exit_info:
        _parser().parse_args(["trial", "--object", "box:0.05x0.025x0.01", "--grasp", "petal"])
    assert exit_info.value.code == 2


def test_the_flower_grasp_holds_a_12_mm_plate_the_old_precision_grasp_missed():
    """The flower grasp in full dynamics (oracle pose, seed 1): the compliant arm lands the preshaped
    fingertips on the table, presses while the hand closes, and the plate is lifted and held. The
    precision grasp it replaced (fingertips swept 2 mm above the table, the arm held by position)
    missed this plate at seeds 1 and 2 (docs/results/flower.md)."""
    from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp
    from drake_grasp.objects.catalogue import plate_object
    from drake_grasp.station import load_scenario
    from drake_grasp.trial.given_plan import run_trial

    record = run_trial(load_scenario(), plate_object(0.012),
                       lambda X_WO, spec: plan_compliant_grasp("precision", oracle_estimate(X_WO, spec)),
                       seed=1, method="oracle", grasp="precision")
    assert record.success, (record.failure, record.detail)
    assert record.lift > 0.09 and "distal" in record.contacts_at_end


def test_the_gentle_close_holds_an_8_mm_plate_that_the_breakaway_close_drops(tmp_path):
    """The flower grasp closes under the clutch's breakaway torque and then holds its fingers: the
    tips stop on the plate's edges at the table and keep their squeeze through the lift. With the
    paper's close (breakaway, closing on through the lift) the same plan lifts the plate, then the
    fingers close past it and it falls (oracle pose, seed 1; docs/design.md §5.4f)."""
    import dataclasses

    import trimesh

    from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp
    from drake_grasp.objects.names import resolve_object
    from drake_grasp.station import load_scenario
    from drake_grasp.trial.given_plan import run_trial

    path = tmp_path / "plate.obj"
    trimesh.creation.box(extents=(0.12, 0.08, 0.008)).export(path)
    spec = resolve_object(str(path))

    def flower(breakaway):
        def plan(X_WO, spec):
            return dataclasses.replace(plan_compliant_grasp("precision", oracle_estimate(X_WO, spec)),
                                       breakaway=breakaway)
        return plan

    gentle = run_trial(load_scenario(), spec, flower(False), seed=1, method="oracle", grasp="precision")
    assert gentle.success, (gentle.failure, gentle.detail)
    assert not any(gentle.breakaway)
    paper = run_trial(load_scenario(), spec, flower(True), seed=1, method="oracle", grasp="precision")
    assert not paper.success



def test_the_lift_squeeze_carries_a_heavy_plate_that_the_gentle_squeeze_drops(tmp_path):
    """A 0.4 kg plate (7.3 x 4.8 x 1.1 cm, as a model file with its own mass): the gentle close's
    squeeze, kept through the lift, lets it fall; the lift's harder squeeze (HandAction.SQUEEZE,
    under the clutch's breakaway) carries it (oracle pose, seed 1; docs/design.md §5.4f)."""
    import dataclasses

    import trimesh

    from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp
    from drake_grasp.objects.names import resolve_object
    from drake_grasp.station import load_scenario
    from drake_grasp.trial.given_plan import run_trial

    mass, box = 0.4, trimesh.creation.box(extents=(0.073, 0.048, 0.0113))
    box.export(tmp_path / "plate.obj")
    inertia = box.moment_inertia / box.mass * mass
    (tmp_path / "plate.urdf").write_text(
        f'<?xml version="1.0"?><robot name="plate"><link name="plate"><inertial><mass value="{mass}"/>'
        f'<inertia ixx="{inertia[0, 0]}" ixy="0" ixz="0" iyy="{inertia[1, 1]}" iyz="0" izz="{inertia[2, 2]}"/>'
        '</inertial><visual><geometry><mesh filename="plate.obj"/></geometry></visual>'
        '<collision><geometry><mesh filename="plate.obj"/></geometry></collision></link></robot>')
    spec = resolve_object(str(tmp_path / "plate.urdf"))
    assert spec.mass == pytest.approx(mass)

    def trial(lift_squeeze_torque):
        scenario = load_scenario()
        scenario.hand = dataclasses.replace(scenario.hand, lift_squeeze_torque=lift_squeeze_torque)
        return run_trial(scenario, spec, lambda X_WO, s: plan_compliant_grasp("precision", oracle_estimate(X_WO, s)),
                         seed=1, method="oracle", grasp="precision")

    hand = load_scenario().hand
    gentle = trial(hand.gentle_close_torque)  # the lift squeezes no harder than the close
    assert not gentle.success
    squeezed = trial(hand.lift_squeeze_torque)
    assert squeezed.success, (squeezed.failure, squeezed.detail)
    assert not any(squeezed.breakaway)


def test_cli_generates_the_flower_objects(tmp_path, capsys):
    from drake_grasp.cli import main

    assert main(["objects", "generate", "--kind", "flower", "--count", "11", "--seed", "4", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "11 flower objects (" + ", ".join(sorted(flower.CLASSES)) + ")" in out
    assert len(list(tmp_path.glob("*.obj"))) == 11


def test_the_flower_grasp_pinches_a_2_cm_cube_that_f1_and_f2_would_straddle():
    """A 2 cm cube (oracle pose, seed 2) under the flower grasp: F1 and F2 at a 90 deg spread pinch
    it along the arm's reach, F3 stays open, and it is held. At the cylindrical spread F1's and F2's
    pads pass either side of it (docs/design.md §5.4f)."""
    from drake_grasp.grasps import PINCH_SPREAD, oracle_estimate, plan_compliant_grasp
    from drake_grasp.objects import cube_object
    from drake_grasp.station import load_scenario
    from drake_grasp.trial.given_plan import run_trial

    plans = []

    def plan(X_WO, spec):
        plans.append(plan_compliant_grasp("precision", oracle_estimate(X_WO, spec)))
        return plans[-1]

    record = run_trial(load_scenario(), cube_object(0.02), plan, seed=2, method="oracle", grasp="precision")
    assert plans[0].spread == PINCH_SPREAD and not plans[0].thumb_closes
    assert record.success, (record.failure, record.detail)
    assert record.finger_angles[3] == pytest.approx(0.0, abs=0.02)  # F3's proximal joint stayed open
    assert "bh_finger_1_distal" in record.contacts_at_end and "bh_finger_2_distal" in record.contacts_at_end


def test_the_flower_grasp_pinches_a_thin_round_stick_end_to_end():
    """A 1.2 cm round stick 12 cm long (oracle pose, seed 2): F1 and F2 meet its end faces and it is
    held; the three-finger flower across it drops round sticks this thin (docs/design.md §5.4f)."""
    from drake_grasp.grasps import PINCH_SPREAD, oracle_estimate, plan_compliant_grasp
    from drake_grasp.objects import cylinder_object
    from drake_grasp.station import load_scenario
    from drake_grasp.trial.given_plan import run_trial

    plans = []

    def plan(X_WO, spec):
        plans.append(plan_compliant_grasp("precision", oracle_estimate(X_WO, spec)))
        return plans[-1]

    record = run_trial(load_scenario(), cylinder_object(0.012, 0.12), plan, seed=2, method="oracle",
                       grasp="precision")
    assert plans[0].spread == PINCH_SPREAD and not plans[0].thumb_closes
    # F1 and F2 close along the palm's x, which lies along the stick's axis (the world's x, give or take
    # the placement's 10 degrees).
    assert abs(plans[0].X_WP_target.rotation().col(0)[0]) > 0.98
    assert record.success, (record.failure, record.detail)


def test_the_palm_follows_the_closing_fingertips_down_counting_only_the_fingers_that_close():
    """The compliant arm's target during the close moves down by as much as the closing tips rise
    (`fingertips_rise`). The two-finger pinch leaves F3 open at 0: its rise is F1's and F2's alone,
    not a mean that counts F3 (which let the pinching tips leave the table: docs/design.md §5.4f)."""
    import math

    from drake_grasp.control.grasp_executor import fingertips_rise
    from drake_grasp.grasps import ObjectEstimate, precision_grasp
    from drake_grasp.robot import hand

    cube = ObjectEstimate(center=np.array([0.5, 0.0, 0.0125]), R_WB=np.eye(3), size=np.array([0.025] * 3), table_z=0.0)
    pinch = precision_grasp(cube)
    assert not pinch.thumb_closes and pinch.finger_preshape[2] == 0.0
    landed, now = pinch.finger_preshape[0], pinch.finger_preshape[0] + math.radians(25)
    expected = hand.fingertip_depth(landed, pinch.spread) - hand.fingertip_depth(now, pinch.spread)
    assert expected > 0.01  # the tips rise centimetres over such a close
    assert fingertips_rise(pinch, [now, now, 0.0]) == pytest.approx(expected)
    assert fingertips_rise(pinch, [landed, landed, 0.0]) == 0.0
    assert fingertips_rise(pinch, [landed - 0.1, landed - 0.1, 0.0]) == 0.0  # never up from the landing

    plate = ObjectEstimate(center=np.array([0.5, 0.0, 0.006]), R_WB=np.eye(3), size=np.array([0.10, 0.06, 0.012]),
                           table_z=0.0)
    flower = precision_grasp(plate)
    assert flower.thumb_closes
    a = flower.finger_preshape[0]
    b = a + math.radians(20)
    expected = hand.fingertip_depth(a, flower.spread) - hand.fingertip_depth(b, flower.spread)
    assert fingertips_rise(flower, [b, b, b]) == pytest.approx(expected)
