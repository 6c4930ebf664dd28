"""scripts/time_step_check.py: pairing two scenarios' oracle trials (pure functions, no simulation)."""

import math

from script_loader import load_script

time_step_check = load_script("time_step_check")


def _row(success: bool, slip_mm: float, slip_deg: float, wall: float = 2.0, failure: str = "") -> dict:
    return {"success": "1" if success else "0", "failure": "" if success else (failure or "slipped during hold"),
            "slip_distance": str(slip_mm / 1e3), "slip_angle": str(math.radians(slip_deg)), "wall_time": str(wall)}


def test_compare_pairs_trials_and_names_the_grasps_held_in_one_scenario_only():
    a = {("banana", "box", 0): _row(True, 1.2, 0.1, wall=6.0), ("apple", "box", 0): _row(True, 0.5, 0.3, wall=4.0),
         ("sponge", "box", 0): _row(False, 30.0, 19.0, wall=5.0)}
    b = {("banana", "box", 0): _row(False, 118.0, 16.6, wall=3.0), ("apple", "box", 0): _row(True, 0.9, 0.2, wall=2.0),
         ("sponge", "box", 0): _row(True, 0.2, 1.0, wall=1.0)}
    summary = time_step_check.compare(a, b)
    assert summary["trials"] == 3
    assert summary["a"]["held"] == 2 and summary["b"]["held"] == 2
    assert summary["held_only_in_a"] == [["banana", "box", 0]]
    assert summary["held_only_in_b"] == [["sponge", "box", 0]]
    assert summary["held_in_both"] == 1
    # Slip statistics cover only the grasps held in both (the apple), so they compare like with like.
    assert summary["a"]["slip_mm_held_in_both"]["max"] == 0.5
    assert summary["b"]["slip_mm_held_in_both"]["median"] == 0.9
    assert summary["a"]["held_under_1mm"] == 1 and summary["b"]["held_under_1mm"] == 2
    assert summary["a"]["mean_wall_time_s"] == 5.0 and summary["b"]["mean_wall_time_s"] == 2.0
    low, high = summary["a"]["held_ci95"]
    assert 0.0 < low < 2 / 3 < high < 1.0


def test_report_marks_the_trials_whose_outcome_differs():
    a = {("banana", "box", 0): _row(True, 1.2, 0.1), ("apple", "box", 0): _row(True, 0.5, 0.3)}
    b = {("banana", "box", 0): _row(False, 118.0, 16.6), ("apple", "box", 0): _row(True, 0.9, 0.2)}
    text = time_step_check.report("default", "step_10ms", a, b, time_step_check.compare(a, b))
    assert "Held in `default` only: banana box seed 0." in text
    assert "Held in `step_10ms` only: none." in text
    differing = [line for line in text.splitlines() if "(differs)" in line]
    assert len(differing) == 1 and differing[0].startswith("| banana | box | 0 |")


def test_quantiles_use_the_nearest_rank():
    q = time_step_check.quantiles([float(v) for v in range(1, 11)])  # 1..10
    assert q == {"median": 5.5, "p90": 9.0, "max": 10.0}
    assert all(math.isnan(v) for v in time_step_check.quantiles([]).values())
