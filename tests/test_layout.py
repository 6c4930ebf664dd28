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
