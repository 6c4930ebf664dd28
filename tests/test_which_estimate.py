"""Which estimate a run uses when no scenario is named: the best (table-top) for object files and
generated objects, the paper's silhouettes for its objects and primitives (docs/trials.md)."""

import pytest

from drake_grasp.cli import _parser
from drake_grasp.cli.common import load_scenario_arg
from drake_grasp.station import BEST_SCENARIO_NAME, PAPER_SCENARIO_NAME, default_scenario_name
from drake_grasp.trial import TrialSpec


@pytest.mark.parametrize("name, expected", [
    ("apple", PAPER_SCENARIO_NAME), ("sphere:0.12", PAPER_SCENARIO_NAME), ("cylinder:0.1x0.3", PAPER_SCENARIO_NAME),
    ("my_mug.stl", BEST_SCENARIO_NAME), ("scans/bunny.OBJ", BEST_SCENARIO_NAME), ("robot/mug.urdf", BEST_SCENARIO_NAME),
    ("model.sdf", BEST_SCENARIO_NAME), ("out/novel/objects/novel_000_blob.obj", BEST_SCENARIO_NAME),
])
def test_object_files_get_the_best_estimate_and_the_paper_s_objects_the_paper_s(name, expected):
    assert default_scenario_name(name) == expected


def test_a_scenario_file_of_the_user_s_own_is_read_as_it_is(tmp_path):
    mine = tmp_path / "mine.yaml"
    mine.write_text("default: {}\n")
    assert default_scenario_name("my_mug.stl", mine) == PAPER_SCENARIO_NAME


def test_a_spec_without_a_scenario_name_resolves_it_when_made_and_a_named_one_is_kept():
    assert TrialSpec("my_mug.stl", "compliant", "", 0).scenario_name == BEST_SCENARIO_NAME
    assert TrialSpec("apple", "compliant", "", 0).scenario_name == PAPER_SCENARIO_NAME
    assert TrialSpec("my_mug.stl", "compliant", "", 0, scenario_name="default").scenario_name == "default"
    # Resolved, so that a spec's fingerprint never depends on a default that could change later.
    assert TrialSpec("my_mug.stl", "oracle", "box", 0) == TrialSpec("my_mug.stl", "oracle", "box", 0,
                                                                     scenario_name=BEST_SCENARIO_NAME)


@pytest.mark.parametrize("argv, expected", [
    (["trial", "--object", "my_mug.stl"], BEST_SCENARIO_NAME),
    (["trial", "--object", "apple"], PAPER_SCENARIO_NAME),
    (["trial", "--object", "my_mug.stl", "--scenario-name", "default"], PAPER_SCENARIO_NAME),
    (["resemble", "--object", "mug.urdf"], BEST_SCENARIO_NAME),
    (["fig6", "--objects", "apple,my_mug.stl"], BEST_SCENARIO_NAME),
    (["fig6", "--objects", "apple,banana"], PAPER_SCENARIO_NAME),
    (["fig6"], PAPER_SCENARIO_NAME),  # the paper's figure keeps the paper's algorithm
    (["fig7"], PAPER_SCENARIO_NAME),
    (["novel"], BEST_SCENARIO_NAME),
])
def test_the_commands_choose_as_documented(argv, expected):
    args = _parser().parse_args(argv)
    scenario = load_scenario_arg(args)
    assert args.scenario_name == expected
    assert (scenario.perception.table_top is not None) == (expected == BEST_SCENARIO_NAME)
