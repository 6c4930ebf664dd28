"""ε of a trial's hand pose (Fig. 4's quasi-static grasp and metric on the pose a trial executes)."""

import pytest

from drake_grasp.estimate_error import EstimateError
from drake_grasp.studies import epsilon_physics
from drake_grasp.trial import TrialSpec


def test_a_centred_box_grasp_of_the_sponge_is_force_closure_and_a_far_miss_is_not():
    centred = epsilon_physics.static_grasp(TrialSpec("sponge", "oracle", "box", 0))
    assert centred.epsilon > 0.0 and len(centred.links) >= 3
    missed = epsilon_physics.static_grasp(TrialSpec("sponge", "oracle", "box", 0,
                                                    estimate_error=EstimateError(across=0.12)))
    assert missed.epsilon == 0.0


def test_camera_trials_have_no_static_pose():
    with pytest.raises(ValueError, match="decides its hand pose"):
        epsilon_physics.static_grasp(TrialSpec("sponge", "compliant", "", 0))


def test_scores_are_cached_by_the_trial_key(tmp_path):
    spec = TrialSpec("sponge", "oracle", "box", 0)
    pairs = [(spec, "0123456789abcdef")]
    first = epsilon_physics.score_trials(pairs, tmp_path / "epsilon.csv")
    text = (tmp_path / "epsilon.csv").read_text()
    assert epsilon_physics.score_trials(pairs, tmp_path / "epsilon.csv") == first
    assert (tmp_path / "epsilon.csv").read_text() == text  # nothing scored twice


def test_calibration_summary_and_figure(tmp_path):
    result = epsilon_physics.calibrate([0.0, 0.0, 0.05, 0.1, 0.2], [False, True, False, True, True])
    lines = epsilon_physics.summary_lines(result, "test")
    assert "area under the ROC curve" in lines[0] and "| ε = 0 (no force closure) | 2 |" in "\n".join(lines)
    assert result.closure_fell == [2] and result.no_closure_held == [1]
    assert all(p.exists() for p in epsilon_physics.plot(result, tmp_path))
