"""scripts/compare_records.py: matching records, ignoring run fields and added `extra` keys."""

import csv
import json
import math

from script_loader import load_script

compare_records = load_script("compare_records")

FIELDS = ["object", "method", "grasp", "seed", "success", "failure", "lift", "wall_time", "extra"]


def _write(path, rows, fields=FIELDS):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    return str(path)


def _row(seed, lift="0.11", wall=1.0, extra=None, success="1", failure=""):
    return {"object": "apple", "method": "oracle", "grasp": "spherical", "seed": seed, "success": success,
            "failure": failure, "lift": lift, "wall_time": wall, "extra": json.dumps(extra or {"chosen": "box"})}


def test_identical_files_but_wall_time_and_an_added_extra_key_pass(tmp_path, capsys):
    before = _write(tmp_path / "a.csv", [_row(0), _row(1)])
    after = _write(tmp_path / "b.csv", [_row(1, wall=9.0, extra={"chosen": "box", "scenario": "default"}),
                                        _row(0, wall=3.0)])
    assert compare_records.main([before, after]) == 0
    assert "keys added to extra (ignored): scenario" in capsys.readouterr().out


def test_a_changed_number_is_reported_with_its_relative_size(tmp_path, capsys):
    before = _write(tmp_path / "a.csv", [_row(0, lift="0.100")])
    after = _write(tmp_path / "b.csv", [_row(0, lift="0.101")])
    assert compare_records.main([before, after]) == 1
    assert "lift (9.9e-03)" in capsys.readouterr().out
    assert compare_records.main([before, after, "--outcomes-only"]) == 0


def test_a_changed_outcome_or_a_missing_record_fails(tmp_path):
    before = _write(tmp_path / "a.csv", [_row(0), _row(1)])
    assert compare_records.main([before, _write(tmp_path / "b.csv", [_row(0), _row(1, success="0",
                                                                                      failure="slipped")])]) == 1
    assert compare_records.main([before, _write(tmp_path / "c.csv", [_row(0)]), "--outcomes-only"]) == 1


def test_relative_difference_of_texts():
    assert compare_records.relative_difference("[1.0, 2.0]", "[1.0, 2.0]") == 0.0
    assert math.isclose(compare_records.relative_difference("[1.0, 2.0]", "[1.0, 2.2]"), 0.2 / 2.2)
    assert compare_records.relative_difference("dropped during lift", "slipped during hold") == math.inf


def test_a_doubled_record_is_an_error(tmp_path, capsys):
    doubled = _write(tmp_path / "a.csv", [_row(0), _row(0)])
    assert compare_records.main([doubled, doubled]) == 2
    assert "appears twice" in capsys.readouterr().err
