"""The capture-region study: its planes, its specs, and a tiny real run that resumes."""

import io
import math

import pytest

from drake_grasp.experiments import capture
from drake_grasp.experiments.executors import LocalExecutor


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


@pytest.mark.parametrize("bad", [dict(grasps=("fist",)), dict(planes=("roll",)), dict(methods=("magic",)),
                                 dict(base=0), dict(depth=9)])
def test_bad_configurations_are_refused(bad):
    with pytest.raises(ValueError):
        capture.CaptureConfig(objects=("sphere:0.1",), **bad)


def test_a_tiny_study_runs_refines_and_resumes(tmp_path, short_scenario_file):
    # One cell from no error to 6 cm along and across a 10 cm sphere, refined once where its corners
    # disagree (measured: the oracle's spherical grasp holds at no error and misses 6 cm off along one
    # of the axes).
    config = capture.CaptureConfig(objects=("sphere:0.1",), grasps=("spherical",), planes=("position",),
                                   methods=("oracle",), offset_cm=(0.0, 6.0), base=1, depth=1)
    maps, lines = capture.run(config, tmp_path, LocalExecutor(2), 2, scenario_file=str(short_scenario_file))
    ((cell, (tree, results)),) = maps.items()
    assert results[(0, 0)]  # no error: the grasp holds
    corners = [results[p] for p in ((0, 0), (0, 2), (2, 0), (2, 2))]
    # 4 corners; if they disagree, the centre and the 4 edge midpoints of the split cell.
    assert len(results) == (9 if len(set(corners)) > 1 else 4)
    area = capture.areas(maps)[cell]
    assert 0 < area.lower <= area.estimate <= area.upper <= area.total == 36.0
    rounds = 2 if len(results) == 9 else 1
    assert (tmp_path / "summary.md").exists() and (tmp_path / "capture.png").exists()
    assert any("sphere:0.1" in line for line in lines)
    progress = io.StringIO()
    again, _ = capture.run(config, tmp_path, LocalExecutor(2), 2, progress, scenario_file=str(short_scenario_file))
    assert again == maps  # read back, nothing run again
    assert "resuming, 4/4" in progress.getvalue() and (rounds == 1 or "resuming, 5/5" in progress.getvalue())
    assert ": ok (" not in progress.getvalue() and "missed" not in progress.getvalue()
