"""ε against physics: the reliability curve, the ROC area and the disagreements (pure functions)."""

import math

import numpy as np
import pytest
from scipy.stats import mannwhitneyu

from drake_grasp.studies.calibration import (disagreements, reliability_curve, roc_auc, roc_curve,
                                                 zero_and_quantile_edges)


def test_reliability_bins_count_every_trial_once():
    eps = [0.0, 0.0, 0.05, 0.1, 0.2, 0.3, 0.9]
    ok = [False, True, False, True, True, True, True]
    bins = reliability_curve(eps, ok, [0.0, 1e-12, 0.15, 0.5])
    assert [b.trials for b in bins] == [2, 2, 3]
    assert [b.successes for b in bins] == [1, 1, 3]  # 0.9 is past the last edge: in the last bin
    lo, hi = bins[2].interval
    assert 0.0 < lo < 1.0 and hi == 1.0
    assert math.isnan(reliability_curve([], [], [0, 1])[0].rate)


def test_reliability_rejects_bad_edges_and_lengths():
    with pytest.raises(ValueError):
        reliability_curve([0.1], [True], [0.5, 0.1])
    with pytest.raises(ValueError):
        reliability_curve([0.1, 0.2], [True], [0.0, 1.0])


def test_quantile_edges_keep_zero_apart():
    edges = zero_and_quantile_edges([0, 0, 0, 0.1, 0.2, 0.3, 0.4], bins=2)
    assert edges[0] == 0.0 and edges[1] < 0.1 and edges[-1] == pytest.approx(0.4)
    assert zero_and_quantile_edges([0, 0]) == [0.0, 1e-12]


def test_auc_perfect_chance_and_inverse():
    assert roc_auc([0.1, 0.2, 0.3, 0.4], [False, False, True, True]).value == 1.0
    assert roc_auc([0.1, 0.2, 0.3, 0.4], [True, True, False, False]).value == 0.0
    assert roc_auc([0.5] * 4, [True, False, True, False]).value == 0.5  # all tied
    assert math.isnan(roc_auc([0.1, 0.2], [True, True]).value)  # one class: nothing to rank


def test_auc_equals_mann_whitney_and_its_interval_contains_it():
    rng = np.random.default_rng(0)
    ok = rng.random(80) < 0.5
    scores = np.round(rng.random(80) + 0.5 * ok, 1)  # ties on purpose
    auc = roc_auc(scores, ok)
    u = mannwhitneyu(scores[ok], scores[~ok]).statistic
    assert auc.value == pytest.approx(u / (ok.sum() * (~ok).sum()))
    assert auc.lo < auc.value < auc.hi
    assert (auc.positives, auc.negatives) == (ok.sum(), (~ok).sum())


def test_roc_curve_runs_from_origin_to_one_one():
    fpr, tpr = roc_curve([0.1, 0.4, 0.35, 0.8], [False, True, False, True])
    assert (fpr[0], tpr[0]) == (0.0, 0.0) and (fpr[-1], tpr[-1]) == (1.0, 1.0)
    assert np.all(np.diff(fpr) >= 0) and np.all(np.diff(tpr) >= 0)


def test_disagreements():
    closure_fell, no_closure_held = disagreements([0.0, 0.2, 0.0, 0.3], [True, False, False, True])
    assert closure_fell == [1] and no_closure_held == [0]
