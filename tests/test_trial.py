"""Grasp trials in real simulation: the executor, the success test, failure reasons, the CLI."""

import dataclasses
import json
import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from drake_grasp import cli, trial
from drake_grasp.objects import paper_object
from drake_grasp.trial import MISSED, UNREACHABLE, TrialSpec, oracle_plan, run_trial


def test_spherical_grasp_of_the_soccer_ball_succeeds(short_scenario):
    record = trial.run(TrialSpec("soccer_ball", "oracle", "spherical", 1), scenario=short_scenario)
    assert record.success, record.summary()
    assert record.lift > 0.08
    assert record.slip_distance < 0.01
    assert {"bh_finger_1_distal", "bh_finger_2_distal", "bh_finger_3_distal"} <= set(record.contacts_at_end.split())


def test_a_grasp_beside_the_object_misses(short_scenario):
    def beside(X_WO, spec):
        plan = oracle_plan("spherical")(X_WO, spec)
        X = plan.X_WP_target
        return dataclasses.replace(plan, X_WP_target=RigidTransform(X.rotation(), X.translation() + [0, 0.3, 0]))

    record = run_trial(short_scenario, paper_object("apple"), beside, seed=0, method="oracle", grasp="spherical")
    assert not record.success
    assert record.failure == MISSED
    assert record.contacts_after_close == ""


def test_an_unreachable_grasp_is_a_failed_trial_not_a_crash(short_scenario):
    def far(X_WO, spec):
        plan = oracle_plan("spherical")(X_WO, spec)
        return dataclasses.replace(plan, X_WP_target=RigidTransform(plan.X_WP_target.rotation(), [3.0, 0.0, 0.2]))

    record = run_trial(short_scenario, paper_object("apple"), far, seed=0, method="oracle", grasp="spherical")
    assert record.failure == UNREACHABLE and not record.success


def test_same_seed_same_trial(short_scenario):
    """A trial is deterministic: every field of its record but the wall time, to the bit (a speed
    change that alters a number shows here first; scripts/record_check.py compares whole trials)."""
    a, b = (trial.run(TrialSpec("sponge", "oracle", "box", 3), scenario=short_scenario).to_dict() for _ in range(2))
    del a["wall_time"], b["wall_time"]
    assert json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)  # NaN equal to NaN
    assert math.isfinite(a["slip_distance"])


def test_trial_cli_json_and_errors(capsys, tmp_path, monkeypatch, short_scenario_file):
    # A user's scenario file overrides only what it says, on top of the default scenario.
    scenario_file = short_scenario_file
    assert cli.main(["trial", "--object", "bottle_case", "--grasp", "cylindrical", "--oracle", "--seed", "2",
                     "--json", "--scenario", str(scenario_file)]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["object"] == "bottle_case" and record["seed"] == 2 and "success" in record
    assert cli.main(["trial", "--object", "apple", "--oracle"]) == 2
    assert "--grasp" in capsys.readouterr().err
    assert cli.main(["trial", "--object", "nope", "--grasp", "box", "--oracle"]) == 2
    assert "unknown object" in capsys.readouterr().err
    scenario_file.write_text("default:\n  protocol:\n    slip_distance: .nan\n")
    assert cli.main(["trial", "--object", "apple", "--grasp", "box", "--oracle", "--scenario", str(scenario_file)]) == 2
    assert "slip_distance" in capsys.readouterr().err


def test_a_planned_grasp_runs_through_the_same_runner(short_scenario):
    # A grasp "planned" in the object frame (hand base 0.3 m above the ball's centre, palm down, spread
    # at 60 deg, fingers preshaped to 20 deg): the arm approaches from a retreat along the palm normal
    # to exactly that pose (no contact guard), preshapes, closes, lifts and holds like any trial.
    from drake_grasp.robot import hand

    X_OH = RigidTransform(RotationMatrix.MakeXRotation(math.pi), [0, 0, 0.10 + hand.PALM_HEIGHT + 0.002])
    q = np.array([math.radians(60)] * 2 + [math.radians(20)] * 3 + [math.radians(20) / 3] * 3)
    planned = {"X_OH": X_OH.GetAsMatrix4().tolist(), "joint_angles": q.tolist()}
    record = trial.run(TrialSpec("soccer_ball", "eigengrasp", "planned", 0, planned=planned), scenario=short_scenario)
    assert record.success, record.summary()
    assert not record.approach_stopped_on_contact
    assert record.planned_grasp == planned


def test_trial_cli_runs_the_eigengrasp_planner_through_the_same_runner(capsys, tmp_path, short_scenario_file):
    # Plan (a short annealing, table loaded), execute the best grasp the arm can reach, judge.
    scenario_file = short_scenario_file
    assert cli.main(["trial", "--object", "sponge", "--method", "eigengrasp", "--steps", "35000", "--seed", "1",
                     "--json", "--scenario", str(scenario_file)]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["method"] == "eigengrasp" and record["grasp"] == "contact-quality/35000/seed0#1"
    assert record["planned_grasp"]["planner_rank"] >= 1 and len(record["planned_grasp"]["X_OH"]) == 4
    assert record["success"] == (record["failure"] == "")  # a verdict from the same success test
    for bad, message in ((["--grasp", "box"], "--method compliant"), (["--rank", "0"], "--rank"),
                         (["--energy", "joy"], "unknown --energy"), (["--steps", "10"], "--steps")):
        assert cli.main(["trial", "--object", "sponge", "--method", "eigengrasp"] + bad) == 2
        assert message in capsys.readouterr().err
    assert cli.main(["trial", "--object", "sponge", "--rank", "2"]) == 2
    assert "only with --method eigengrasp" in capsys.readouterr().err
