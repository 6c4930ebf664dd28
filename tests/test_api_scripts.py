"""The Python API's example scripts (scripts/simulate_grasp.py, simulate_exploration.py,
compare_fig7.py) run as a user runs them, each short (a 0.5 s hold, a short planner run), and use
only the names drake_grasp.api documents."""

import ast

import pytest

from drake_grasp import api
from script_loader import SCRIPTS, load_script


def _main(name: str):
    return load_script(name).main


@pytest.mark.parametrize("name", ["simulate_grasp", "simulate_exploration", "compare_fig7"])
def test_the_scripts_use_only_the_documented_api(name):
    tree = ast.parse((SCRIPTS / f"{name}.py").read_text())
    used = {node.attr for node in ast.walk(tree)
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "api"}
    project = {(node.module, alias.name) for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
               and node.module and node.module.startswith("drake_grasp") for alias in node.names}
    assert used and used <= set(api.__all__), used - set(api.__all__)
    assert project == {("drake_grasp", "api")}, project  # the one import of the project a script needs


def test_simulate_exploration_prints_the_estimate_and_its_errors(capsys):
    assert _main("simulate_exploration")(["--object", "soccer_ball"]) == 0
    out = capsys.readouterr().out
    assert "soccer_ball: ok" in out and "resembles a sphere" in out and "against the truth" in out


def test_simulate_grasp_decides_grasps_and_judges(capsys, tmp_path):
    replay = tmp_path / "grasp.html"
    assert _main("simulate_grasp")(["--object", "soccer_ball", "--hold", "0.5", "--replay", str(replay)]) == 0
    out = capsys.readouterr().out
    assert "soccer_ball compliant/spherical" in out and '"chosen_grasp": "spherical"' in out
    assert replay.stat().st_size > 100_000


def test_compare_fig7_runs_the_planner_and_the_algorithm_on_one_object(capsys):
    assert _main("compare_fig7")(["--object", "sponge", "--steps", "31000", "--hold", "0.5"]) == 0
    out = capsys.readouterr().out
    assert "Eigengrasp planner" in out and "compliance-centric (" in out
