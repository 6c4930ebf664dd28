"""Static checks of the package's source: no name is used that is never defined.

A module split can lose an import that only one code path needs; Python says so only when that path
runs, as a traceback in front of a user (an MJCF geom turned by ``quat`` did so from release 0.37.0
to 0.47.1). pyflakes reads every module without running it."""

from pathlib import Path

import pytest

pyflakes_api = pytest.importorskip("pyflakes.api")
from pyflakes import messages  # noqa: E402
from pyflakes.reporter import Reporter  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
UNDEFINED = (messages.UndefinedName, messages.UndefinedLocal, messages.UndefinedExport)


class _Collect(Reporter):
    def __init__(self):
        super().__init__(None, None)
        self.found = []

    def flake(self, message):
        if isinstance(message, UNDEFINED):
            self.found.append(str(message))

    def syntaxError(self, filename, msg, lineno, offset, text):
        self.found.append(f"{filename}:{lineno}: {msg}")

    def unexpectedError(self, filename, msg):
        self.found.append(f"{filename}: {msg}")


def test_no_module_uses_a_name_it_never_defines():
    reporter = _Collect()
    files = [p for folder in ("drake_grasp", "baselines", "scripts") for p in sorted((ROOT / folder).rglob("*.py"))]
    assert len(files) > 100
    for path in files:
        pyflakes_api.checkPath(str(path), reporter)
    assert reporter.found == []
