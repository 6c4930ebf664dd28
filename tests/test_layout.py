"""The layout's promises: studies apart from the sweep machinery, and the old import paths of the
moved modules still working for one release, with a DeprecationWarning."""

import ast
import importlib
import pathlib
import sys

import pytest

import drake_grasp


@pytest.mark.parametrize("old, new", [("drake_grasp.experiments.fig6", "drake_grasp.studies.fig6"),
                                      ("drake_grasp.experiments.runner", "drake_grasp.sweeps.runner"),
                                      ("drake_grasp.experiments.results", "drake_grasp.sweeps.results")])
def test_the_experiments_paths_forward_to_studies_and_sweeps_with_a_deprecation_warning(old, new):
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=new.replace(".", r"\.")):
        module = importlib.import_module(old)
    assert module is importlib.import_module(new)


def test_the_sweep_machinery_imports_no_study():
    """The machinery serves every study and knows none of them."""
    root = pathlib.Path(drake_grasp.__file__).parent
    for path in sorted((root / "sweeps").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            modules = ([node.module] if isinstance(node, ast.ImportFrom) and node.module else
                       [a.name for a in node.names] if isinstance(node, ast.Import) else [])
            for module in modules:
                assert not module.startswith(("drake_grasp.studies", "drake_grasp.experiments")), (path.name, module)


# A study module (one experiment) against its helpers: pure analysis, reports, the results page.
STUDY_MODULES = ("fig4", "fig6", "fig7", "novel", "sensitivity", "capture", "epsilon_physics", "near_primitives", "estimates",
                 "exploration",
                 "reproduce")
HELPERS = ("calibration", "capture_region", "replays", "report_page", "near_primitives_report", "sensitivity_report",
           "novel_checks")


def test_every_study_says_what_it_runs_and_writes():
    """Each study's docstring ends with 'The experiment:': its objects, grasps, seeds and what it writes,
    so the module reads as a description of its experiment before any code."""
    root = pathlib.Path(drake_grasp.__file__).parent / "studies"
    found = {p.stem for p in root.glob("*.py")} - {"__init__"}
    assert found == set(STUDY_MODULES) | set(HELPERS), "a new module in studies/: list it above"
    for name in STUDY_MODULES:
        doc = ast.get_docstring(ast.parse((root / f"{name}.py").read_text()))
        assert "\nThe experiment:\n" in doc, name
        block = doc.split("\nThe experiment:\n")[1]
        labels = " ".join(line.split(":")[0].strip() for line in block.splitlines() if line.startswith("    ")
                          and not line.startswith("     "))
        for word in ("objects", "grasps", "seeds", "writes"):
            assert word in labels, (name, word)
