"""Loads one of the repository's scripts (scripts/NAME.py, not a package) as a module, for its tests."""

import importlib.util
import pathlib
import types

SCRIPTS = pathlib.Path(__file__).resolve().parents[1] / "scripts"


def load_script(name: str, module_name: str | None = None) -> types.ModuleType:
    """scripts/`name`.py executed as a module named `module_name` (default: `name`)."""
    spec = importlib.util.spec_from_file_location(module_name or name, SCRIPTS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
