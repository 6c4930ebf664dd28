"""ε against physics: how well the quasi-static grasp quality predicts a grasp's dynamic outcome.

GraspIt! and Dex-Net rank grasps by a static score; the paper's Fig. 4 uses the ε metric (the
radius of the largest ball about the origin inside the grasp's L1 wrench-space hull, Ferrari &
Canny, ICRA 1992). Whether a higher ε means a grasp that holds in a full simulation is an empirical
question: Weisz & Allen (ICRA 2012) found the most robust grasp is usually not the highest-ε one.
This module answers it from pairs (ε of a hand pose, did the same hand pose hold in a trial):

* a reliability curve: P(success) per ε bin, each with its 95 % Wilson interval;
* the area under the ROC curve (ε as a classifier of success), with the Hanley-McNeil standard
  error (J. A. Hanley and B. J. McNeil, "The meaning and use of the area under a receiver operating
  characteristic (ROC) curve", Radiology 143(1), 1982) for a 95 % interval;
* the disagreements: ε > 0 (force closure) but the object fell, and ε = 0 but it held.

Everything here is pure (numpy and scipy): the studies that produce the pairs live elsewhere.
"""

import dataclasses
import math

import numpy as np
from scipy.stats import norm, rankdata

from drake_grasp.sweeps.stats import CONFIDENCE, wilson_interval

FORCE_CLOSURE = 0.0  # ε above this: the contacts resist every wrench (force closure)


@dataclasses.dataclass(frozen=True)
class ReliabilityBin:
    """Trials whose ε lies in [lo, hi): how many, how many held, and the 95 % interval of the rate."""

    lo: float
    hi: float
    trials: int
    successes: int

    @property
    def rate(self) -> float:
        return self.successes / self.trials if self.trials else float("nan")

    @property
    def interval(self) -> tuple[float, float]:
        return wilson_interval(self.successes, self.trials)


def reliability_curve(epsilons, successes, edges) -> list[ReliabilityBin]:
    """P(success) per ε bin.

    Args:
        epsilons: ε of each trial's hand pose (dimensionless, >= 0).
        successes: whether each trial held the object.
        edges: increasing bin edges; the last bin also takes ε equal to its upper edge, and ε outside
            [edges[0], edges[-1]] is counted in the first or last bin.

    Raises:
        ValueError: unequal lengths, fewer than two edges, or edges not increasing.
    """
    eps, ok = _pairs(epsilons, successes)
    edges = np.asarray(edges, float)
    if edges.ndim != 1 or len(edges) < 2 or np.any(np.diff(edges) <= 0):
        raise ValueError(f"bin edges must be at least two increasing numbers, got {edges.tolist()}")
    index = np.clip(np.searchsorted(edges, eps, side="right") - 1, 0, len(edges) - 2)
    return [ReliabilityBin(float(edges[i]), float(edges[i + 1]), int(np.sum(index == i)),
                           int(np.sum(ok[index == i]))) for i in range(len(edges) - 1)]


def zero_and_quantile_edges(epsilons, bins: int = 4) -> list[float]:
    """Bin edges for ε: one bin for ε = 0 (no force closure, often the largest group), then `bins`
    bins of about equal counts over the positive values (fewer if the values repeat)."""
    eps = np.asarray(epsilons, float)
    positive = eps[eps > FORCE_CLOSURE]
    edges = [0.0, 1e-12]
    if len(positive):
        quantiles = np.quantile(positive, np.linspace(0.0, 1.0, bins + 1)[1:])
        for q in quantiles:
            if q > edges[-1]:
                edges.append(float(q))
    return edges


@dataclasses.dataclass(frozen=True)
class AreaUnderCurve:
    """The ROC curve's area with its 95 % interval (Hanley-McNeil), from `positives` successes and
    `negatives` failures. nan when either class is empty (nothing to rank)."""

    value: float
    lo: float
    hi: float
    positives: int
    negatives: int


def roc_auc(scores, successes) -> AreaUnderCurve:
    """Area under the ROC curve of `scores` as a predictor of success: the probability that a random
    success scores higher than a random failure, ties counting one half (the Mann-Whitney U statistic
    divided by the number of pairs). 0.5 = no better than chance, 1 = perfect ranking."""
    s, ok = _pairs(scores, successes)
    n_pos, n_neg = int(ok.sum()), int((~ok).sum())
    if n_pos == 0 or n_neg == 0:
        return AreaUnderCurve(float("nan"), float("nan"), float("nan"), n_pos, n_neg)
    ranks = rankdata(s)  # average ranks for ties
    auc = (ranks[ok].sum() - n_pos * (n_pos + 1) / 2.0) / (n_pos * n_neg)
    q1, q2 = auc / (2.0 - auc), 2.0 * auc * auc / (1.0 + auc)
    variance = (auc * (1 - auc) + (n_pos - 1) * (q1 - auc * auc) + (n_neg - 1) * (q2 - auc * auc)) / (n_pos * n_neg)
    half = float(norm.ppf(0.5 + CONFIDENCE / 2.0)) * math.sqrt(max(variance, 0.0))
    return AreaUnderCurve(float(auc), max(0.0, auc - half), min(1.0, auc + half), n_pos, n_neg)


def roc_curve(scores, successes) -> tuple[np.ndarray, np.ndarray]:
    """The ROC curve's points (false-positive rate, true-positive rate), from (0, 0) to (1, 1), one
    point per distinct score (predict success when the score is at least that value)."""
    s, ok = _pairs(scores, successes)
    n_pos, n_neg = max(int(ok.sum()), 1), max(int((~ok).sum()), 1)
    thresholds = np.unique(s)[::-1]
    fpr = [0.0] + [float(np.sum((s >= t) & ~ok)) / n_neg for t in thresholds]
    tpr = [0.0] + [float(np.sum((s >= t) & ok)) / n_pos for t in thresholds]
    return np.array(fpr), np.array(tpr)


def disagreements(epsilons, successes) -> tuple[list[int], list[int]]:
    """Indices where ε and physics disagree: (force closure but the object fell, no force closure but
    it held)."""
    eps, ok = _pairs(epsilons, successes)
    closure = eps > FORCE_CLOSURE
    return np.flatnonzero(closure & ~ok).tolist(), np.flatnonzero(~closure & ok).tolist()


def _pairs(values, successes) -> tuple[np.ndarray, np.ndarray]:
    values = np.asarray(values, float).ravel()
    ok = np.asarray(successes, bool).ravel()
    if values.shape != ok.shape:
        raise ValueError(f"{len(values)} scores but {len(ok)} outcomes")
    if not np.all(np.isfinite(values)):
        raise ValueError("scores must be finite")
    return values, ok
