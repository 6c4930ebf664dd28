"""The compliant-grasp supervisor: the decision as a single LeafSystem on fixed inputs, and the whole
algorithm (explore, decide, grasp) in one Diagram in real simulation."""

import json

import numpy as np
import pytest
from pydrake.multibody.plant import ContactResults
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import InputPortIndex

from drake_grasp import cli
from drake_grasp.control.arm_motion import UNREACHABLE
from drake_grasp.control.grasp_executor import GraspPhase
from drake_grasp.control.supervisor import CompliantGraspSupervisor
from drake_grasp.objects import paper_object
from drake_grasp.primitives.estimate import OBJECT_NOT_FOUND, PERCEPTION_FAILED, ObjectEstimate
from drake_grasp.primitives.sequencer import ExplorationPhase
from drake_grasp.station import MakeStation, load_scenario
from drake_grasp import trial
from drake_grasp.estimate_error import EstimateError

CAMERA, GRASP = InputPortIndex(1), InputPortIndex(2)


def _ball_estimate(centre=(0.55, 0.0, 0.10), resemblances=(0.9, 0.1, 0.0), extents=(0.2, 0.2, 0.2),
                   principal_axis=None) -> ObjectEstimate:
    return ObjectEstimate(status="ok", centre=np.array(centre), depth=0.35, camera_position=np.array([0.55, 0, 0.45]),
                          axes=np.eye(3), extents=np.array(extents), principal_axis=principal_axis,
                          resemblances=dict(zip(("sphere", "cylinder", "box"), resemblances)))


def _decide(estimate: ObjectEstimate, exploration_phase: ExplorationPhase, forced_grasp=None, until=0.05,
            estimate_error=None):
    """Runs the supervisor alone on fixed inputs for `until` seconds; returns it and its context."""
    scenario = load_scenario()
    station = MakeStation(scenario, paper_object("soccer_ball"), camera=False)
    plant = station.plant
    q_start = np.asarray(scenario.protocol.start_configuration, float)
    supervisor = CompliantGraspSupervisor(plant, station.scene_graph, station.wam, plant.GetBodyIndices(station.hand),
                                          q_start, scenario.protocol.execution, (CAMERA, GRASP), forced_grasp,
                                          estimate_error)
    context = supervisor.CreateDefaultContext()
    supervisor.GetInputPort("wam.state").FixValue(context, np.concatenate([q_start, np.zeros(7)]))
    supervisor.GetInputPort("contact_results").FixValue(context, ContactResults())
    supervisor.GetInputPort("exploration_phase").FixValue(context, [float(exploration_phase)])
    supervisor.GetInputPort("object_estimate").FixValue(context, estimate)
    Simulator(supervisor, context).AdvanceTo(until)
    return supervisor, context


def test_while_exploring_the_camera_drives_the_arm_and_the_hand_stays_open():
    supervisor, context = _decide(_ball_estimate(), ExplorationPhase.RESEMBLANCE)
    assert supervisor.phase(context) == GraspPhase.EXPLORE and supervisor.decision(context) is None
    assert supervisor.GetOutputPort("arm_source").Eval(context) == CAMERA
    spread, action = supervisor.GetOutputPort("hand.command").Eval(context)
    assert spread == 0.0 and action == 0.0  # HandAction.OPEN


def test_the_decision_is_the_grasp_of_the_most_resembling_shape():
    supervisor, context = _decide(_ball_estimate(), ExplorationPhase.DONE)
    decision = supervisor.decision(context)
    assert decision.chosen == decision.executed == "spherical"
    assert supervisor.phase(context) == GraspPhase.MOVE
    assert supervisor.GetOutputPort("arm_source").Eval(context) == GRASP
    # The plan comes from the estimate alone: the palm approaches the estimated centre from above.
    np.testing.assert_allclose(decision.plan.X_WP_target.translation()[:2], [0.55, 0.0], atol=1e-9)
    box, context = _decide(_ball_estimate(resemblances=(0.1, 0.3, 0.6)), ExplorationPhase.DONE)
    assert box.decision(context).chosen == "box"


def test_a_forced_grasp_is_executed_and_the_choice_still_recorded():
    supervisor, context = _decide(_ball_estimate(), ExplorationPhase.DONE, forced_grasp="cylindrical")
    decision = supervisor.decision(context)
    assert decision.chosen == "spherical" and decision.executed == "cylindrical"
    with pytest.raises(ValueError, match="unknown grasp"):
        _decide(_ball_estimate(), ExplorationPhase.DONE, forced_grasp="pinch")


def test_an_estimate_error_moves_the_grasp_not_the_decision():
    # The ball's estimate (no principal axis, axes = world): along is world x, across world y.
    error = EstimateError(along=0.02, across=-0.01)
    supervisor, context = _decide(_ball_estimate(), ExplorationPhase.DONE, estimate_error=error)
    decision = supervisor.decision(context)
    assert decision.chosen == decision.executed == "spherical"
    np.testing.assert_allclose(decision.estimate.centre, [0.55, 0.0, 0.10])  # the camera's, as it was
    np.testing.assert_allclose(decision.plan.X_WP_target.translation()[:2], [0.57, -0.01], atol=1e-9)


def test_no_object_or_no_reach_ends_the_sequence_with_the_reason():
    supervisor, context = _decide(ObjectEstimate(status=OBJECT_NOT_FOUND), ExplorationPhase.NOT_FOUND)
    assert supervisor.phase(context) == GraspPhase.DONE and supervisor.progress(context).outcome == OBJECT_NOT_FOUND
    assert supervisor.GetOutputPort("arm_source").Eval(context) == CAMERA
    far, context = _decide(_ball_estimate(centre=(3.0, 0.0, 0.1)), ExplorationPhase.DONE)
    assert far.phase(context) == GraspPhase.DONE and far.progress(context).outcome == UNREACHABLE
    assert far.decision(context).executed == "spherical"


def test_an_estimate_that_cannot_place_a_grasp_ends_the_sequence_as_perception_failed():
    """A size that is not positive, a value that is not finite, an axis that did not converge: the
    supervisor ends the sequence at the decision with PERCEPTION_FAILED and the reason, before any
    grasp is computed (it never reaches the grasp's own check, which would throw)."""
    cases = {"size not positive": _ball_estimate(extents=(0.04, 0.0, 0.144)),
             "extents not finite": _ball_estimate(extents=(0.04, np.nan, 0.144)),
             "centre not finite": _ball_estimate(centre=(0.55, np.inf, 0.1)),
             "principal axis did not converge": _ball_estimate(principal_axis=np.full(3, np.nan)),
             "resemblance not finite": _ball_estimate(resemblances=(np.nan, 0.1, 0.0)),
             "no usable silhouette": ObjectEstimate(status=PERCEPTION_FAILED)}
    for why, estimate in cases.items():
        supervisor, context = _decide(estimate, ExplorationPhase.DONE, forced_grasp="box")
        progress = supervisor.progress(context)
        assert supervisor.phase(context) == GraspPhase.DONE, why
        assert progress.outcome == PERCEPTION_FAILED and why in progress.detail, (why, progress.detail)
        decision = supervisor.decision(context)
        assert decision.plan is None and decision.chosen == "" and decision.executed == "box"
        assert supervisor.GetOutputPort("arm_source").Eval(context) == CAMERA  # the arm never left the camera
    # The trial's record: its own failure reason, the why as its detail, and both in the summary line.
    record = trial.TrialRecord("carton", "compliant", "", 1, False, PERCEPTION_FAILED,
                               detail=cases["size not positive"].problem())
    assert PERCEPTION_FAILED in trial.FAILURES and trial.SIMULATION_ERROR != PERCEPTION_FAILED
    assert "FAILED (perception failed: size not positive along every axis: extents [0.040, 0.000, 0.144] m" \
        in record.summary()
    # A width the fit left at its bound (1.25e-21 m, a real trial's) is no size either.
    assert "size not positive" in _ball_estimate(extents=(0.106, 1.25e-21, 0.146)).problem()


def test_the_whole_algorithm_grasps_the_soccer_ball_from_the_camera_alone(short_scenario):
    record = trial.run(trial.TrialSpec("soccer_ball", "compliant", "", 1), scenario=short_scenario)
    assert record.success, record.summary()
    assert record.estimate_source == "camera" and record.chosen_grasp == record.grasp == "spherical"
    assert record.resemblances["sphere"] > 0.5
    # The decision came when the exploration ended, in the same simulation as the grasp.
    assert 12.0 < record.estimate["decided_at"] < 13.0 < record.sim_time
    # The record and its summary line say which estimate placed the grasp (this scenario: the paper's).
    assert record.estimate["estimator"] == "silhouettes" and "(silhouettes estimate)" in record.summary()
    assert record.estimate_errors["centre"] < 0.01 and record.estimate_errors["shape_correct"]


def test_an_upright_carton_is_explored_and_grasped(tmp_path, short_scenario):
    """A 4 x 4 x 14.4 cm carton standing on the table: its principal axis is vertical. The estimate
    gives it its height along that axis (the depth primitive's vertical extent), a grasp is decided
    from it and attempted: the trial ends in the grasp's own outcome, never in a simulation error or
    a perception failure."""
    import trimesh

    path = tmp_path / "carton.stl"
    trimesh.creation.box((0.04, 0.04, 0.144)).export(path)
    record = trial.run(trial.TrialSpec(str(path), "compliant", "", 1), scenario=short_scenario)
    assert record.failure not in (trial.SIMULATION_ERROR, PERCEPTION_FAILED, OBJECT_NOT_FOUND, UNREACHABLE), \
        record.summary()
    assert record.chosen_grasp == record.grasp == "box" and record.contacts_after_close, record.summary()
    estimate = record.estimate
    assert abs(estimate["principal_axis"][2]) > 0.99
    assert estimate["extents"][0] == pytest.approx(0.144, rel=0.1)  # along the vertical axis: the height
    assert estimate["extents"][1] == pytest.approx(0.04, rel=0.3) and estimate["extents"][2] == pytest.approx(
        0.04, rel=0.3)
    assert all(abs(e) < 0.3 for e in record.estimate_errors["extents"])


@pytest.mark.slow
def test_the_cli_runs_a_forced_grasp_and_writes_its_record(tmp_path, capsys, short_scenario_file):
    scenario_file = short_scenario_file
    assert cli.main(["trial", "--object", "spectacle_case", "--method", "compliant", "--grasp", "cylindrical",
                     "--seed", "3", "--json", "--scenario", str(scenario_file), "--out", str(tmp_path)]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["grasp"] == "cylindrical" and record["chosen_grasp"] == "box"
    assert record["estimate_source"] == "camera" and record["estimate"]["status"] == "ok"
    assert (tmp_path / "trial_spectacle_case_cylindrical_3.json").exists()
