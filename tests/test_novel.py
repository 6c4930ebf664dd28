"""The novel-objects study's bookkeeping (pure functions; the runs are Fig. 6's and Fig. 7's)."""

import math

from drake_grasp.studies import novel
from drake_grasp.studies.fig6 import GraspStats
from drake_grasp.studies.fig7 import Comparison


def _stats(res, ok, n=2):
    return {g: GraspStats(n, k, r) for g, r, k in zip(("spherical", "cylindrical", "box"), res, ok)}


def _comparison(obj, per_grasp):
    best = max(k / n for k, n in per_grasp.values())
    return Comparison(obj, math.nan, 0, "-", math.nan, best, sum(n for _, n in per_grasp.values()), per_grasp)


OBJECTS = [{"file": "o/blob_000.obj", "class": "blob"}, {"file": "o/ring_001.obj", "class": "ring"},
           {"file": "o/blob_002.obj", "class": "blob"}]
STATS = {"o/blob_000.obj": _stats((0.9, 0.2, 0.5), (2, 0, 1)),
         "o/ring_001.obj": _stats((0.1, 0.3, 0.8), (2, 2, 0)),
         "o/blob_002.obj": _stats((0.7, 0.6, 0.1), (1, 2, 2))}
COMPARISON = [_comparison("o/blob_000.obj", {"t#1": (0, 2), "t#2": (2, 2)}),
              _comparison("o/ring_001.obj", {"t#1": (1, 2)})]


def test_rows_mark_the_chosen_grasp_and_join_the_planner():
    rows = novel.study_rows(OBJECTS, STATS, COMPARISON)
    assert [r.chosen_grasp for r in rows] == ["spherical", "box", "spherical"]
    assert [(r.chosen_successes, r.chosen_trials) for r in rows] == [(2, 2), (0, 2), (1, 2)]
    assert (rows[0].planner_successes, rows[0].planner_trials, rows[0].planner_best) == (2, 4, 1.0)
    assert rows[2].planner_trials == 0 and math.isnan(rows[2].planner_average)


def test_summary_breaks_down_by_class_with_intervals_and_reasons():
    rows = novel.study_rows(OBJECTS, STATS, COMPARISON)
    trials = [{"object": "o/blob_000.obj", "grasp": "spherical", "success": "1", "failure": ""},
              {"object": "o/ring_001.obj", "grasp": "box", "success": "0", "failure": "dropped during lift"},
              {"object": "o/ring_001.obj", "grasp": "box", "success": "0", "failure": "dropped during lift"},
              {"object": "o/ring_001.obj", "grasp": "spherical", "success": "0", "failure": "not chosen"}]
    chosen = novel.chosen_trial_rows(trials, rows)
    assert len(chosen) == 3  # the ring's spherical trial is not its chosen grasp
    text = "\n".join(novel.summary_lines(rows, chosen, [], novel.NovelConfig()))
    assert "50 % (3/6, 95 % CI" in text  # overall chosen-grasp success
    assert "| blob | 2 | 75 % (3/4" in text
    assert "| ring | 1 | 0 % (0/2" in text
    assert "dropped during lift: 2" in text and "not chosen" not in text


def test_csv_and_figure_are_written(tmp_path):
    rows = novel.study_rows(OBJECTS, STATS, COMPARISON)
    novel.write_csv(tmp_path / "novel.csv", rows)
    lines = (tmp_path / "novel.csv").read_text().splitlines()
    assert len(lines) == 4 and lines[1].startswith("o/blob_000.obj,blob,spherical,2,2,")
    paths = novel.plot(rows, tmp_path)
    assert all(p.stat().st_size > 1000 for p in paths)


def test_objects_are_generated_once_and_reused(tmp_path):
    first = novel.ensure_objects(tmp_path / "objects", 3, 7)
    assert [e["class"] for e in first] == ["blob", "union", "plate"]
    stamps = {e["file"]: __import__("os").stat(e["file"]).st_mtime_ns for e in first}
    again = novel.ensure_objects(tmp_path / "objects", 3, 7)
    assert again == first and all(__import__("os").stat(f).st_mtime_ns == t for f, t in stamps.items())
    assert not list((tmp_path / "objects").glob(".generating.*"))  # no staging folder left behind
    other = novel.ensure_objects(tmp_path / "objects", 2, 8)  # another seed: its own files
    assert {e["file"] for e in other}.isdisjoint(stamps)


def test_the_camera_is_compared_with_the_true_estimate_per_class():
    from drake_grasp.studies import novel_checks

    rows = novel.study_rows(OBJECTS, STATS, COMPARISON)
    specs = novel_checks.oracle_specs({r.object: r.chosen_grasp for r in rows}, 2, 5, scenario_name="table_top")
    assert [(s.object, s.method, s.grasp, s.seed) for s in specs[:2]] == [
        ("o/blob_000.obj", "oracle", "spherical", 5), ("o/blob_000.obj", "oracle", "spherical", 6)]
    assert len(specs) == 6 and all(s.scenario_name == "table_top" for s in specs)
    oracle = [{"object": "o/blob_000.obj", "grasp": "spherical", "success": "1"},
              {"object": "o/blob_000.obj", "grasp": "spherical", "success": "1"},
              {"object": "o/blob_002.obj", "grasp": "spherical", "success": "0"},
              {"object": "o/blob_002.obj", "grasp": "spherical", "success": "1"},
              {"object": "o/ring_001.obj", "grasp": "box", "success": "1"},
              {"object": "o/ring_001.obj", "grasp": "box", "success": "1"}]
    text = "\n".join(novel_checks.truth_lines(rows, oracle))
    assert "| blob | 75 % (3/4" in text and "| 75 % (3/4" in text.split("| blob |")[1]  # camera as truth
    assert text.rstrip().endswith("| -33 |")  # all: camera 3/6 against 5/6
    assert "| ring | 0 % (0/2" in text and "| -100 |" in text


def test_close_calls_are_reported_with_every_grasp():
    import json

    from drake_grasp.studies import novel_checks

    rows = novel.study_rows(OBJECTS, STATS, COMPARISON)

    def trial(obj, seed, res):
        return {"object": obj, "seed": seed, "extra": json.dumps({"resemblance": res})}

    trials = [trial("o/blob_000.obj", 0, {"sphere": 0.9, "cylinder": 0.2, "box": 0.5}),  # margin 0.4
              trial("o/blob_002.obj", 0, {"sphere": 0.7, "cylinder": 0.6, "box": 0.1}),  # 0.1
              trial("o/blob_002.obj", 1, {"sphere": 0.7, "cylinder": 0.5, "box": 0.1})]  # 0.2
    margins = novel_checks.object_margins(trials)
    assert margins["o/blob_000.obj"] == 0.4 and abs(margins["o/blob_002.obj"] - 0.15) < 1e-12
    text = "\n".join(novel_checks.margin_lines(rows, trials, ("spherical", "cylindrical", "box")))
    close = [line for line in text.splitlines() if line.startswith("| margin < 0.2")][0]
    assert "| 1 | 50 % (1/2" in close and close.endswith("| 50 % (1/2, 95 % CI 9-91 %) | 100 % (2/2, 95 % CI 34-100 %) | 100 % (2/2, 95 % CI 34-100 %) |")
    assert "Close calls: blob_002 (0.15, chose spherical)." in text
