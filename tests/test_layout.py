"""The layout's promises: studies apart from the sweep machinery, and the old import paths of the
moved modules still working for one release, with a DeprecationWarning."""

import ast
import importlib
import pathlib
import sys

import pytest

import drake_grasp


# Paths of the old layout, removed in release 0.3.0 (CHANGELOG.md): no forwarder is left behind.
REMOVED = ("drake_grasp.experiments", "drake_grasp.geometry", "drake_grasp.catalogue", "drake_grasp.object_model",
           "drake_grasp.piece_budget", "drake_grasp.user_objects", "drake_grasp.hand", "drake_grasp.arm",
           "drake_grasp.contact", "drake_grasp.modelgen", "drake_grasp.perception_config")


@pytest.mark.parametrize("old", REMOVED)
def test_the_old_layouts_paths_are_gone(old):
    sys.modules.pop(old, None)
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module(old)


def test_no_module_of_the_package_forwards_to_another():
    """A forwarder replaces itself in sys.modules; none is left in the package."""
    root = pathlib.Path(drake_grasp.__file__).parent
    for path in sorted(root.rglob("*.py")):
        assert "sys.modules[__name__]" not in path.read_text(), path


def test_the_robots_facts_are_one_package_and_the_perception_settings_live_in_perception():
    from drake_grasp.perception import PerceptionConfig
    from drake_grasp.robot import arm, contact, hand, modelgen

    assert PerceptionConfig.__module__ == "drake_grasp.perception.config"
    assert {m.__name__ for m in (arm, contact, hand, modelgen)} == {f"drake_grasp.robot.{n}" for n in
                                                                    ("arm", "contact", "hand", "modelgen")}
    root = pathlib.Path(drake_grasp.__file__).parent
    loose = sorted(p.stem for p in root.glob("*.py"))
    assert not set(loose) & {"hand", "arm", "contact", "modelgen", "perception_config"}, loose


def test_the_model_generator_runs_from_the_command_line(tmp_path, monkeypatch):
    """`python -m drake_grasp.modelgen` moved: `drake-grasp models` writes the same files."""
    from drake_grasp import cli
    from drake_grasp.robot import modelgen

    written = {}
    monkeypatch.setattr(modelgen, "write_models", lambda: [written.setdefault("hand", modelgen.HAND_SDF)])
    assert cli.main(["models"]) == 0
    assert written == {"hand": modelgen.HAND_SDF}


def test_the_module_map_names_every_module():
    """docs/design.md's module map lists every module of the package (its path), and no removed one."""
    design = (pathlib.Path(drake_grasp.__file__).parents[1] / "docs" / "design.md").read_text()
    module_map = design.split("## 1. Module map", 1)[1].split("\n## ", 1)[0]
    for old in ("drake_grasp/hand.py", "drake_grasp/modelgen.py", "perception_config", "experiments/", "geometry/"):
        assert old not in module_map, old
    for new in ("robot/hand.py", "robot/arm.py", "robot/contact.py", "robot/modelgen.py", "perception/config.py"):
        assert new in module_map, new
    root = pathlib.Path(drake_grasp.__file__).parent
    for path in sorted(root.rglob("*.py")):
        if path.name not in ("__init__.py", "__main__.py"):
            relative = path.relative_to(root).as_posix()
            assert relative in module_map or path.name in module_map, f"docs/design.md §1 does not list {relative}"


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
STUDY_MODULES = ("fig4", "fig4_flower", "fig6", "fig7", "novel", "sensitivity", "capture", "epsilon_physics", "near_primitives", "estimates",
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
