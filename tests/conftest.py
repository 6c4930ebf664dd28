"""Fixtures shared by the test modules."""

import pytest

from drake_grasp.station import load_scenario

# The default suite's trials hold the object 0.5 s instead of the protocol's 10 s: everything before
# the hold is the real sequence, and a slip shows within half a second as well as within ten.
SHORT_HOLD_TIME = 0.5  # s
SHORT_SCENARIO_YAML = f"default:\n  protocol:\n    execution:\n      hold_time: {SHORT_HOLD_TIME}\n"


@pytest.fixture
def short_scenario():
    """The default scenario with the short hold."""
    scenario = load_scenario()
    scenario.protocol.execution.hold_time = SHORT_HOLD_TIME
    return scenario


@pytest.fixture
def short_scenario_file(tmp_path):
    """The short scenario as a user's scenario file (for the command line and sweeps): it overrides
    only the hold, on top of the default scenario."""
    path = tmp_path / "short.yaml"
    path.write_text(SHORT_SCENARIO_YAML)
    return path
