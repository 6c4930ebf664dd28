"""The capture-region study: its planes, its specs, and a tiny real run that resumes."""

import io
import math

import pytest

from drake_grasp.studies import capture
from drake_grasp.sweeps.executors import LocalExecutor
from drake_grasp.sweeps.runner import trial_table


def test_plane_points_become_estimate_errors_in_si_units():
    e = capture.error_of("position", (2.0, -4.0))
    assert (e.along, e.across, e.yaw, e.size_scale) == (0.02, -0.04, 0.0, 1.0)
    e = capture.error_of("yaw", (1.0, 30.0))
    assert e.across == 0.01 and e.yaw == pytest.approx(math.radians(30)) and e.along == 0.0
    e = capture.error_of("size", (0.0, -30.0))
    assert e.size_scale == pytest.approx(0.7) and e.across == 0.0


def test_cells_pick_the_resembled_grasp_and_skip_size_for_the_planner():
    config = capture.CaptureConfig(objects=("soccer_ball",), grasps=("chosen",), planes=("position", "size"))
    cells = capture.cells(config, "plan#1")
    assert capture.Cell("soccer_ball", "oracle", "spherical", "position") in cells
    assert capture.Cell("soccer_ball", "oracle", "spherical", "size") in cells
    assert capture.Cell("soccer_ball", "eigengrasp", "plan#1", "position") in cells
    assert all(not (c.method == "eigengrasp" and c.plane == "size") for c in cells)


def test_each_physical_trial_counts_once_in_the_epsilon_calibration():
    def trial(grasp, fingerprint, error, outcome="[1.0, 1.2]"):
        cell = capture.Cell("sponge", "oracle", grasp, "position")
        return capture.Trial(cell, (0, 0), None, fingerprint, True, ("sponge", 0, error, outcome, "0.1", "0.001"))

    shared = trial("box", "f1", "e0")
    same_in_another_plane = trial("box", "f1", "e0")
    twin_grasp = trial("cylindrical", "f1", "e0")  # the same hand pose planned under another grasp name
    other_grasp = trial("spherical", "f1", "e0", "[0.9, 1.1]")  # same fingerprint, another record
    miss_a, miss_b = trial("box", "f3", "e1", "[2.4, 2.4]"), trial("box", "f4", "e2", "[2.4, 2.4]")
    distinct = capture.distinct_trials([shared, same_in_another_plane, twin_grasp, other_grasp, miss_a, miss_b])
    assert distinct == [shared, other_grasp, miss_a, miss_b]  # two misses at different errors stay two


@pytest.mark.parametrize("bad", [dict(grasps=("fist",)), dict(planes=("roll",)), dict(methods=("magic",)),
                                 dict(base=0), dict(depth=9)])
def test_bad_configurations_are_refused(bad):
    with pytest.raises(ValueError):
        capture.CaptureConfig(objects=("sphere:0.1",), **bad)


def _tiny_study(tmp_path, scenario_file, depth, replays=0):
    # One cell from no error to 6 cm along and across a 10 cm sphere (measured: the oracle's box grasp
    # holds at no error and misses 6 cm off along both axes), refined `depth` times where its corners
    # disagree.
    config = capture.CaptureConfig(objects=("sphere:0.1",), grasps=("box",), planes=("position",),
                                   methods=("oracle",), offset_cm=(0.0, 6.0), base=1, depth=depth)
    maps, lines = capture.run(config, tmp_path, LocalExecutor(2), scenario_file=str(scenario_file),
                              replays_per_kind=replays)
    ((cell, (tree, results)),) = maps.items()
    assert results[(0, 0)]  # no error: the grasp holds
    records = trial_table(tmp_path / "capture.csv", read_only=True).rows()
    assert len(records) == len(results)
    assert sorted(results.values()) == sorted(r["success"] in ("1", "True") for r in records)
    area = capture.areas(maps)[cell]
    assert 0 <= area.lower <= area.estimate <= area.upper <= area.total == 36.0
    assert (tmp_path / "summary.md").exists() and (tmp_path / "capture.png").exists()
    assert any("sphere:0.1" in line for line in lines)
    progress = io.StringIO()
    again, _ = capture.run(config, tmp_path, LocalExecutor(2), progress, scenario_file=str(scenario_file),
                           replays_per_kind=replays)
    assert again == maps  # read back, nothing run again
    assert ": ok (" not in progress.getvalue() and "missed" not in progress.getvalue()
    return config, results


def test_a_tiny_study_runs_and_resumes(tmp_path, short_scenario_file):
    _, results = _tiny_study(tmp_path, short_scenario_file, depth=0)
    assert sorted(results) == [(0, 0), (0, 1), (1, 0), (1, 1)]


@pytest.mark.slow
def test_a_tiny_study_refines_where_the_corners_disagree(tmp_path, short_scenario_file):
    _, results = _tiny_study(tmp_path, short_scenario_file, depth=1, replays=1)
    assert (tmp_path / "epsilon.png").exists() and "ε against physics" in (tmp_path / "summary.md").read_text()
    corners = [results[p] for p in ((0, 0), (0, 2), (2, 0), (2, 2))]
    # 4 corners; if they disagree, the centre and the 4 edge midpoints of the split cell.
    assert len(results) == (9 if len(set(corners)) > 1 else 4)
