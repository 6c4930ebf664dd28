"""Fig. 7's comparison: grasp selection by reachability, statistics, summary and figure."""

import json

import pytest

from drake_grasp.studies import fig6, fig7


def test_compare_counts_only_this_plans_trials_and_picks_the_best_grasp(tmp_path):
    config = fig7.Fig7Config(objects=("sponge",), trials=2)
    tag = config.plan_tag
    rows = [
        {"object": "sponge", "grasp": f"{tag}#1", "success": "1"},
        {"object": "sponge", "grasp": f"{tag}#1", "success": "1"},
        {"object": "sponge", "grasp": f"{tag}#2", "success": "0"},
        {"object": "sponge", "grasp": f"{tag}#2", "success": "1"},
        {"object": "sponge", "grasp": f"{tag}#3", "success": "0"},
        {"object": "sponge", "grasp": f"{tag}#3", "success": "0"},
        {"object": "sponge", "grasp": "contact/40000/seed9#1", "success": "1"},  # another plan's trial
    ]
    compliant = fig6.grasp_stats(
        [{"object": "sponge", "grasp": g, "success": "1", "extra": json.dumps({"resemblance": {"box": 0.9, "sphere": 0.1, "cylinder": 0.2}})}
         for g in fig6.GRASPS], ["sponge"])
    (row,) = fig7.compare(["sponge"], rows, compliant, tag)
    assert row.eigengrasp_average == pytest.approx(3 / 6)
    assert row.eigengrasp_best == pytest.approx(1.0)
    assert row.compliant == 1.0 and row.compliant_grasp == "box"
    lines = fig7.summary_lines([row], "contact", "test")
    assert "average 50 % (3/6, 95 % CI 19-81 %)" in lines[0] and "best 100 % (2/2; " in lines[0]
    assert row.best_counts == (2, 2) and row.eigengrasp_counts == (3, 6) and row.compliant_counts == (1, 1)
    assert all(p.exists() for p in fig7.plot([row], tmp_path, "contact"))


def test_only_reachable_grasps_are_executed():
    # Two candidates in the object frame: hand 0.2 m above the sponge, palm down (reachable), and
    # the same hand 1.5 m away (the WAM cannot get there).
    import numpy as np

    above = np.eye(4)
    above[:3, :3] = np.diag([1.0, -1.0, -1.0])
    above[:3, 3] = [0.0, 0.0, 0.2]
    away = above.copy()
    away[:3, 3] = [1.5, 0.0, 0.2]
    q = [0.0] * 8
    plan = {"candidates": [{"X_OH": away.tolist(), "joint_angles": q}, {"X_OH": above.tolist(), "joint_angles": q}]}
    chosen = fig7.reachable_grasps(plan, "sponge")
    assert [g["planner_rank"] for g in chosen] == [2]
