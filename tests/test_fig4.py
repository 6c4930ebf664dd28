"""Fig. 4's sweep: a small real run, its files, and resuming after an interruption."""

import contextlib
import csv
import io

import numpy as np
import pytest

from drake_grasp import cli
from drake_grasp.studies import fig4
from drake_grasp.sweeps.results import ResultsTable


def _small():
    return fig4.Fig4Config(sizes=[0.06, 0.14, 0.30], errors=[-0.03, 0.0, 0.03], thicknesses=[0.006, 0.02])


def test_small_sweep_writes_rows_and_figures_and_resumes(tmp_path):
    config = _small()
    rows = fig4.run_fig4(config, tmp_path, workers=1)
    assert len(rows) == (3 * 3 + 2) * 2 * 3
    summaries = fig4.summarise(rows)
    paths = fig4.plot(summaries, tmp_path)
    assert all(p.exists() and p.stat().st_size > 1000 for p in paths)
    # The annulus: a medium sphere grasped dead centre beats one past the hand's envelope.
    sphere = summaries["sphere"]
    assert sphere.at_zero("x")[1] > 0.05
    assert sphere.at_zero("x")[2] < sphere.at_zero("x")[1]
    # The flower: the precision grasp's tilted pads pass over a 6 mm plate; a 2 cm one is held dead centre.
    plate = summaries["plate"]
    assert np.all(plate.epsilon["x"][:, 0] == 0) and np.all(plate.epsilon["y"][:, 0] == 0)
    assert plate.at_zero("y")[1] > 0.02
    assert any(line.startswith("plates (precision grasp): eps = 0 for every error below 20 mm")
               for line in fig4.summary_lines(summaries, rows))

    # Interrupt: drop the last 5 rows and tear the line before them, as kill -9 mid-write would.
    csv_path = tmp_path / "fig4.csv"
    lines = csv_path.read_text().splitlines(keepends=True)
    csv_path.write_text("".join(lines[:-6]) + lines[-6][:10])
    progress = io.StringIO()
    with contextlib.redirect_stderr(io.StringIO()) as report:
        again = fig4.run_fig4(config, tmp_path, workers=1, progress=progress)
    assert report.getvalue() == f"{csv_path}:{len(lines) - 5}: damaged record, recomputing\n"
    # Only the interrupted (shape, size) task is computed again.
    assert "resuming, 10/11" in progress.getvalue()
    assert len(again) == len(rows)
    with open(csv_path) as f:
        keys = [(r["shape"], r["size"], r["axis"], r["error"]) for r in csv.DictReader(f)]
    assert len(keys) == len(set(keys)) == len(rows)
    before = {(r["shape"], r["size"], r["axis"], r["error"]): r["epsilon"] for r in rows}
    after = {(r["shape"], r["size"], r["axis"], r["error"]): r["epsilon"] for r in again}
    assert before == after  # deterministic, and nothing lost or duplicated


def test_results_table_skips_known_keys_and_drops_a_torn_line(tmp_path):
    path = tmp_path / "t.csv"
    table = ResultsTable(path, ["a", "b", "value"], ["a", "b"], {"b": "float", "value": "float"})
    assert table.append([{"a": "x", "b": 0.1, "value": 1.0}, {"a": "x", "b": 0.2, "value": 2.0}]) == 2
    assert table.append([{"a": "x", "b": 0.1, "value": 9.0}]) == 0
    assert ("x", np.float64(0.2)) in table  # numpy scalars key like floats
    with open(path, "a") as f:
        f.write("x,0.3,3.")  # torn
    report = io.StringIO()
    table = ResultsTable(path, ["a", "b", "value"], ["a", "b"], report=report)
    assert len(table) == 2 and ("x", 0.2) in table and ("x", 0.3) not in table
    assert report.getvalue() == f"{path}:4: damaged record, recomputing\n"
    with pytest.raises(ValueError, match="columns do not match"):
        ResultsTable(path, ["a", "c"], ["a"])


def test_fig4_cli_quick_bad_workers(capsys):
    assert cli.main(["fig4", "--workers", "0"]) == 2
    assert "--workers" in capsys.readouterr().err


def test_flower_in_full_dynamics_small_sweep_and_resume(tmp_path):
    """Fig. 4's flower, a real (short) run: a 12 mm plate under the flower grasp, dead centre and 1 cm
    off across it; the zero error is one trial shared by both axes."""
    from drake_grasp.studies import fig4_flower

    config = fig4_flower.FlowerConfig(sizes={"plate": [0.012]}, errors=[0.0, 0.01], seeds=(1,))
    assert len(fig4_flower.points(config)) == 3
    results = fig4_flower.run_flower(config, tmp_path, workers=1, progress=io.StringIO())
    assert len(results) == 3
    assert all(r["grasp"] == "precision" and r["method"] == "oracle" for r in results.values())
    maps = fig4_flower.summarise(results)
    plate = maps["plate"]
    # Dead centre the flower grasp holds a 12 mm plate (docs/design.md §5.4f), on both axes' maps.
    assert plate.share["x"][0, 0] == 1.0 and plate.share["y"][0, 0] == 1.0
    (line,) = fig4_flower.summary_lines(maps, results)
    assert line.startswith("flower, plates (thickness; full dynamics") and "12 mm:" in line
    paths = fig4_flower.plot(maps, tmp_path)
    assert all(p.exists() and p.stat().st_size > 1000 for p in paths)
    progress = io.StringIO()
    again = fig4_flower.run_flower(config, tmp_path, workers=1, progress=progress)
    assert "resuming, 3/3" in progress.getvalue()
    assert {p: r["success"] for p, r in again.items()} == {p: r["success"] for p, r in results.items()}


def test_flower_object_names():
    from drake_grasp.objects import resolve_object
    from drake_grasp.studies import fig4_flower

    assert resolve_object(fig4_flower.object_name("plate", 0.008)).extents == pytest.approx((0.08, 0.05, 0.008))
    assert resolve_object(fig4_flower.object_name("stick", 0.012)).extents == pytest.approx((0.12, 0.012, 0.012))
    assert resolve_object(fig4_flower.object_name("cube", 0.025)).extents == pytest.approx((0.025,) * 3)
    with pytest.raises(ValueError, match="unknown family"):
        fig4_flower.FlowerConfig(sizes={"pen": [0.01]}, errors=[0.0])
