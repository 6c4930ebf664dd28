"""The exploration study's bookkeeping (pure functions; its trials are the runner's compliant trials)."""

import json

import pytest

from drake_grasp import cli
from drake_grasp.studies import exploration


def _row(obj, seed, chosen, ok, time_s, path_m, kind="full", hypothesis=None, why=""):
    cost = {"kind": kind, "time_s": time_s, "path_m": path_m, "path_rad": 1.0, "images": int(20 * time_s)}
    if hypothesis:
        cost.update(hypothesis=hypothesis, why=why)
    return {"object": obj, "seed": seed, "success": "1" if ok else "0",
            "extra": json.dumps({"chosen": chosen, "exploration": cost})}


OBJECTS = [("apple", "paper", "apple"), ("o/blob_0_000.obj", "novel", "blob")]
FULL = [_row("apple", 0, "spherical", True, 12.45, 2.0), _row("apple", 1, "spherical", True, 12.45, 2.1),
        _row("o/blob_0_000.obj", 0, "box", False, 12.45, 3.0)]
MINIMAL = [_row("apple", 0, "spherical", True, 3.95, 0.5, "confirmed", "round", "round, invariant (sphere 0.9)"),
           _row("apple", 1, "spherical", True, 3.95, 0.6, "confirmed", "round", "round, invariant (sphere 0.8)"),
           _row("o/blob_0_000.obj", 0, "cylindrical", True, 14.95, 4.0, "fallback", "elongated",
                "elongated, between a cylinder and a box about its axis (I_a 0.50)")]


def test_pairs_join_the_two_explorations_by_object_and_seed():
    rows = exploration.pairs(OBJECTS, FULL, MINIMAL[:2])
    assert [(p.object, p.seed, p.set) for p in rows] == [("apple", 0, "paper"), ("apple", 1, "paper")]


def test_the_table_gives_agreement_success_cost_and_fallbacks_per_set():
    rows = exploration.pairs(OBJECTS, FULL, MINIMAL)
    text = "\n".join(exploration.table_lines(rows))
    assert "| paper | 2 | 100 % (2/2" in text
    assert "| novel | 1 | 0 % (0/1" in text  # the blob: box after the full, cylindrical after the minimal
    assert "| 12.45 / 12.45 | 3.95 / 14.95 |" in text.splitlines()[-1]  # all: time median / worst
    assert text.splitlines()[-1].endswith("| 33 % (1/3, 95 % CI 6-79 %) |")  # one fallback of three


def test_goals_and_fallback_reasons_are_reported_as_measured():
    rows = exploration.pairs(OBJECTS, FULL, MINIMAL)
    goals = "\n".join(exploration.goal_lines(rows))
    assert "median 3.95 s against 12.45 s, 0.32 of it (goal <= 0.33): met" in goals
    assert "67 % (2/3" in goals and "not met" in goals  # two of three chose the same grasp
    assert "Success: minimal 100 % (3/3" in goals
    text = "\n".join(exploration.fallback_lines(rows))
    assert "| elongated | 0 | 1 |" in text and "| round | 2 | 0 |" in text
    assert "elongated, between a cylinder and a box about its axis: 1" in text
    assert "blob_0_000 seed 0 (full box, minimal cylindrical, fallback)" in text


def test_the_command_refuses_bad_numbers_in_one_line(capsys):
    assert cli.main(["exploration", "--flower", "-2"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--flower must be >= 0" in err


@pytest.mark.slow
def test_the_study_runs_both_explorations_and_resumes(tmp_path):
    # Real trials: a ball, one seed, after the full and the minimal exploration (about a minute).
    from drake_grasp.sweeps.executors import LocalExecutor

    config = exploration.ExplorationConfig.quick(paper=("sphere:0.1",))
    rows, lines, figures = exploration.run_study(config, tmp_path, LocalExecutor(1))
    assert len(rows) == 1 and all(p.stat().st_size > 1000 for p in figures)
    pair = rows[0]
    assert exploration.cost(pair.full)["kind"] == "full" and exploration.cost(pair.minimal)["kind"] == "confirmed"
    assert exploration.chosen(pair.full) == exploration.chosen(pair.minimal) == "spherical"
    again, _, _ = exploration.run_study(config, tmp_path, LocalExecutor(1))  # resumes: nothing to run
    assert [(p.full, p.minimal) for p in again] == [(pair.full, pair.minimal)]
