"""One exploration, several grasps: camera-driven trials that differ only in their forced grasp run as
one simulation that branches at the decision, and give the records they give one by one."""

import io
import json

import numpy as np
import pytest
from pydrake.multibody.plant import ContactResults
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import InputPortIndex

from drake_grasp.control.supervisor import CompliantGraspSupervisor
from drake_grasp.estimate_error import EstimateError
from drake_grasp.objects import paper_object
from drake_grasp.primitives.estimate import ObjectEstimate
from drake_grasp.primitives.sequencer import ExplorationPhase
from drake_grasp.station import MakeStation, load_scenario
from drake_grasp.sweeps.runner import group_specs, run_trials, trial_table
from drake_grasp.trial import TrialSpec, exploration_key


def _supervisor_on_a_finished_exploration(forced_grasp=None):
    scenario = load_scenario()
    station = MakeStation(scenario, paper_object("soccer_ball"), camera=False)
    plant = station.plant
    q_start = np.asarray(scenario.protocol.start_configuration, float)
    supervisor = CompliantGraspSupervisor(plant, station.scene_graph, station.wam, plant.GetBodyIndices(station.hand),
                                          q_start, scenario.protocol.execution, (InputPortIndex(1), InputPortIndex(2)),
                                          forced_grasp)
    context = supervisor.CreateDefaultContext()
    estimate = ObjectEstimate(status="ok", centre=np.array([0.55, 0.0, 0.10]), depth=0.35,
                              camera_position=np.array([0.55, 0, 0.45]), axes=np.eye(3),
                              extents=np.array([0.2, 0.2, 0.2]),
                              resemblances={"sphere": 0.9, "cylinder": 0.1, "box": 0.0})
    supervisor.GetInputPort("wam.state").FixValue(context, np.concatenate([q_start, np.zeros(7)]))
    supervisor.GetInputPort("contact_results").FixValue(context, ContactResults())
    supervisor.GetInputPort("exploration_phase").FixValue(context, [float(ExplorationPhase.DONE)])
    supervisor.GetInputPort("object_estimate").FixValue(context, estimate)
    return supervisor, context


def test_the_forced_grasp_is_a_parameter_of_the_context_and_a_clone_carries_it():
    supervisor, context = _supervisor_on_a_finished_exploration(forced_grasp="box")
    assert supervisor.forced_grasp(context) == "box"
    clone = context.Clone()
    supervisor.set_forced_grasp(clone, "Cylindrical")
    assert supervisor.forced_grasp(clone) == "cylindrical" and supervisor.forced_grasp(context) == "box"
    supervisor.set_forced_grasp(context, None)
    Simulator(supervisor, context).AdvanceTo(0.05)
    Simulator(supervisor, clone).AdvanceTo(0.05)
    assert supervisor.decision(context).executed == "spherical"  # the chosen grasp
    assert supervisor.decision(clone).executed == "cylindrical" and supervisor.decision(clone).chosen == "spherical"
    with pytest.raises(ValueError, match="unknown grasp"):
        supervisor.set_forced_grasp(context, "pinch")


def test_trials_are_grouped_by_their_exploration():
    a = [TrialSpec("apple", "compliant", g, 0) for g in ("spherical", "cylindrical", "box")]
    b = [TrialSpec("apple", "compliant", g, 1) for g in ("spherical", "box")]
    oracle = [TrialSpec("apple", "oracle", "box", 0), TrialSpec("apple", "oracle", "spherical", 0)]
    erred = TrialSpec("apple", "compliant", "box", 0, estimate_error=EstimateError(along=0.01))
    again = TrialSpec("apple", "compliant", "box", 0)  # the same trial twice: never one simulation
    specs = [a[0], b[0], oracle[0], a[1], erred, oracle[1], a[2], b[1], again]
    assert exploration_key(oracle[0]) is None
    assert exploration_key(a[0]) == exploration_key(a[2]) != exploration_key(b[0])
    assert group_specs(specs) == [[0, 3, 6], [1, 7], [2], [4], [5], [8]]
    # With more workers than tasks, groups are split rather than leave a worker idle.
    assert sorted(len(g) for g in group_specs(a, workers=2)) == [1, 2]
    assert sorted(len(g) for g in group_specs(a, workers=8)) == [1, 1, 1]


def _rows(csv_path) -> dict:
    """The trials of a results file by grasp, every field but the wall time."""
    return {r["grasp"]: {k: v for k, v in r.items() if k != "wall_time"}
            for r in trial_table(csv_path, read_only=True).rows()}


def test_one_exploration_gives_each_grasp_the_record_it_gives_alone(tmp_path, short_scenario_file):
    # Real simulations (the short hold): the sponge, seed 1, two forced grasps after one exploration,
    # through the sweeps' runner; then each trial alone (the second as a resumed sweep that finds the
    # first in its file). Field for field the same, wall time aside.
    specs = [TrialSpec("sponge", "compliant", g, 1, str(short_scenario_file)) for g in ("box", "cylindrical")]
    quiet = io.StringIO()
    run_trials(specs, tmp_path / "shared.csv", workers=1, progress=quiet)
    run_trials(specs[:1], tmp_path / "alone.csv", workers=1, progress=quiet)
    run_trials(specs, tmp_path / "alone.csv", workers=1, progress=quiet)
    assert "resuming, 1/2 trials already" in quiet.getvalue()
    shared, alone = _rows(tmp_path / "shared.csv"), _rows(tmp_path / "alone.csv")
    assert set(shared) == {"box", "cylindrical"}
    assert shared == alone
    assert all(json.loads(r["extra"])["resemblance"] for r in shared.values())
    # Every camera-driven row says how clear the choice was and what the exploration cost.
    extra = json.loads(shared["box"]["extra"])
    assert 0.0 <= extra["margin"] <= 1.0
    assert extra["exploration"]["kind"] == "full" and extra["exploration"]["images"] > 100
