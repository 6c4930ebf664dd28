"""ε against physics, on the trials of a study: the static score of each trial's hand pose beside the
trial's dynamic outcome.

For a trial whose grasp is computed before anything moves (oracle and planner trials, with or without
an estimate error), the hand pose is a pure function of its spec: the seed's placement of the object
and the plan. `static_grasp` rebuilds that pose in the object's frame and grasps quasi-statically, as
Fig. 4 does (`quasistatic.QuasiStaticHand`, with the table the object rests on as an obstacle): the
hand comes in along its palm normal as the executor's approach does (a compliant grasp stops at the
first contact or at its target; a planned grasp goes to its target), closes with breakaway, and the
contacts are scored with the ε metric (`quality.grasp_quality`, μ = 0.5 and 8 cone edges, torques
about the centre of mass scaled by the object's largest radius: docs/design.md §4.4-4.5).

The pairs (ε, held) then go to `calibration`: the reliability curve, the ROC area, and the trials
where ε and physics disagree. Scores are cached in ``epsilon.csv`` beside the trials, keyed like them
(fingerprint, object, method, grasp, seed), so a rerun scores only new trials.

The experiment:
    objects and grasps: those of a study's trials whose grasp is fixed before anything moves
        (oracle and planner trials, with or without an estimate error);
    seeds: the trials' own (the hand pose is rebuilt from each trial's spec);
    writes: epsilon.csv beside the trials (one ε per trial), epsilon.png and epsilon.svg (the
        reliability curve), epsilon.json, and replays of the trials where ε and physics disagree.
"""

import dataclasses
import functools
import json
import pathlib
import sys

import numpy as np

from drake_grasp.studies import calibration
from drake_grasp.sweeps.results import ResultsTable, save_figure, write_atomically
from drake_grasp.quality import CONE_EDGES, FRICTION  # the ε convention (docs/design.md §4.4-4.5)
from drake_grasp.sweeps.stats import short_rate

FIELDS = ["fingerprint", "object", "method", "grasp", "seed", "epsilon", "contacts", "links"]
KEY = ["fingerprint", "object", "method", "grasp", "seed"]
TYPES = {"fingerprint": "hex", "seed": "int", "epsilon": "float", "contacts": "int"}


@dataclasses.dataclass(frozen=True)
class StaticGrasp:
    """A trial's hand pose grasped quasi-statically: ε (dimensionless) and the links touching."""

    epsilon: float
    links: tuple[str, ...]


@functools.lru_cache(maxsize=8)
def _hand_for(object_name: str, options: tuple):
    """A quasi-static hand with the object (its frame the world) and its table, built once per object."""
    from drake_grasp.objects import resolve_user_object
    from drake_grasp.quasistatic import QuasiStaticHand

    obj = resolve_user_object(object_name, **dict(options))
    return QuasiStaticHand(obj, table=True), obj


def static_grasp(spec) -> StaticGrasp:
    """The quasi-static grasp of the hand pose a trial spec (method oracle or eigengrasp) executes.

    Raises:
        ValueError: a camera-driven spec (its hand pose is decided during the simulation).
    """
    from drake_grasp.protocol import TrialVariation
    from drake_grasp.quality import grasp_quality
    from drake_grasp.station import MakeStation
    from drake_grasp.trial import apply_variation, oracle_plan, resolve
    from drake_grasp.trial.eigengrasp import planned_plan

    if spec.method not in ("oracle", "eigengrasp"):
        raise ValueError(f"a {spec.method} trial decides its hand pose in the simulation: no static pose to score")
    scenario, obj = resolve(spec)
    variation = TrialVariation.draw(spec.seed, scenario.protocol)
    scenario, obj = apply_variation(scenario, obj, variation)
    X_WO = MakeStation(scenario, obj, camera=False).X_WO_nominal()
    error = spec.estimate_error if spec.has_estimate_error else None
    if spec.method == "oracle":
        plan = oracle_plan(spec.grasp, error)(X_WO, obj)
    else:
        plan = planned_plan({"X_OH": spec.planned["X_OH"], "joint_angles": spec.planned["joint_angles"]}, error)(X_WO, obj)
    sim, spec_object = _hand_for(spec.object, tuple(sorted(spec.object_options().items())))
    grasp = sim.grasp_plan(plan, X_WO)
    points, normals = grasp.contact_arrays()
    quality = grasp_quality(points, normals, FRICTION, np.zeros(3), spec_object.max_radius, CONE_EDGES)
    return StaticGrasp(float(quality.epsilon), tuple(grasp.touching_links))


def score_trials(pairs: list, csv_path: pathlib.Path, progress=sys.stderr) -> list[float]:
    """ε of each (spec, fingerprint) pair, computed once and kept in `csv_path`."""
    table = ResultsTable(csv_path, FIELDS, KEY, TYPES)
    have = {tuple(str(r[k]) for k in KEY): float(r["epsilon"]) for r in table.rows()}
    out = []
    for i, (spec, fingerprint) in enumerate(pairs):
        key = (fingerprint, spec.object, spec.method, spec.grasp, str(spec.seed))
        if key not in have:
            grasp = static_grasp(spec)
            table.append([{"fingerprint": fingerprint, "object": spec.object, "method": spec.method,
                           "grasp": spec.grasp, "seed": spec.seed, "epsilon": grasp.epsilon,
                           "contacts": len(grasp.links), "links": " ".join(grasp.links)}])
            have[key] = grasp.epsilon
            if (i + 1) % 20 == 0 or i + 1 == len(pairs):
                print(f"epsilon: {i + 1}/{len(pairs)} hand poses scored", file=progress, flush=True)
        out.append(have[key])
    return out


@dataclasses.dataclass
class Calibration:
    """ε against the dynamic outcome over a set of trials."""

    epsilons: list[float]
    held: list[bool]
    bins: list
    auc: calibration.AreaUnderCurve
    closure_fell: list[int]  # indices: ε > 0 but the object fell
    no_closure_held: list[int]  # ε = 0 but it held


def calibrate(epsilons: list[float], held: list[bool]) -> Calibration:
    edges = calibration.zero_and_quantile_edges(epsilons, bins=4)
    if len(edges) < 2:
        edges = [0.0, 1.0]
    bins = calibration.reliability_curve(epsilons, held, edges)
    closure_fell, no_closure_held = calibration.disagreements(epsilons, held)
    return Calibration(list(epsilons), list(held), bins, calibration.roc_auc(epsilons, held), closure_fell,
                       no_closure_held)


def summary_lines(result: Calibration, label: str) -> list[str]:
    """The calibration as Markdown: AUC with its interval, the reliability table, the disagreements."""
    auc = result.auc
    auc_text = "n/a (every trial had the same outcome)" if not np.isfinite(auc.value) else (
        f"{auc.value:.2f} (95 % CI {auc.lo:.2f}-{auc.hi:.2f}; {auc.positives} held, {auc.negatives} failed)")
    lines = [f"ε as a predictor of success ({label}, {len(result.epsilons)} trials): area under the ROC curve "
             f"{auc_text}; 0.5 is chance.", "",
             "| ε bin | trials | held |", "|---|---|---|"]
    for i, b in enumerate(result.bins):
        last = "≤" if i == len(result.bins) - 1 else "<"  # bins are [lo, hi), the last one closed
        span = ("ε = 0 (no force closure)" if b.hi <= 1e-12 else
                f"0 < ε {last} {b.hi:.3f}" if b.lo <= 1e-12 else f"{b.lo:.3f} ≤ ε {last} {b.hi:.3f}")
        lines.append(f"| {span} | {b.trials} | {short_rate(b.successes, b.trials)} |")
    lines += ["", f"Force closure (ε > 0) but the object fell: {len(result.closure_fell)} trials; no force closure "
              f"(ε = 0) but it held: {len(result.no_closure_held)} trials."]
    return lines


def plot(result: Calibration, out_dir: pathlib.Path, name: str = "epsilon") -> list[pathlib.Path]:
    """The reliability curve (P(success) per ε bin, Wilson bars) and the ROC curve side by side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.6))
    bins = [b for b in result.bins if b.trials]
    centres = [0.0 if b.hi <= 1e-12 else 0.5 * (b.lo + b.hi) for b in bins]
    rates = [100 * b.rate for b in bins]
    lows = [max(0.0, r - 100 * b.interval[0]) for r, b in zip(rates, bins)]
    highs = [max(0.0, 100 * b.interval[1] - r) for r, b in zip(rates, bins)]
    left.errorbar(centres, rates, yerr=[lows, highs], fmt="o-", capsize=3, color="tab:blue")
    for c, r, b in zip(centres, rates, bins):
        left.annotate(f"{b.successes}/{b.trials}", (c, r), textcoords="offset points", xytext=(4, 4), fontsize=7)
    left.set_xlabel("ε of the hand pose (quasi-static)")
    left.set_ylabel("held in full dynamics (%)")
    left.set_ylim(-5, 105)
    left.grid(alpha=0.3)
    left.set_title("reliability (error bars: 95 % Wilson)", fontsize=9)
    fpr, tpr = calibration.roc_curve(result.epsilons, result.held)
    right.plot(fpr, tpr, "-", color="tab:orange")  # ties between outcomes give the diagonal pieces
    right.plot([0, 1], [0, 1], ":", color="gray")
    auc = result.auc
    right.set_title(f"ROC of ε: area {auc.value:.2f}" if np.isfinite(auc.value) else "ROC of ε: n/a", fontsize=9)
    right.set_xlabel("false-positive rate")
    right.set_ylabel("true-positive rate")
    right.set_aspect("equal")
    fig.tight_layout()
    paths = save_figure(fig, out_dir, name, dpi=110)
    plt.close(fig)
    return paths


def write_replays(cases: list, out_dir: pathlib.Path, progress=sys.stderr) -> list[pathlib.Path]:
    """Meshcat replays of the given (label, spec) disagreement cases (each trial run again, with the
    same record), written as out_dir/replays/<label>.html; existing files are kept (a label names one
    trial: callers put its fingerprint in it)."""
    import logging

    from drake_grasp.trial import run

    logging.getLogger("drake").setLevel(logging.WARNING)  # not Meshcat's "listening at" per replay

    folder = out_dir / "replays"
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for label, spec in cases:
        path = folder / f"{label}.html"
        if not path.exists():
            print(f"epsilon: replay {path.name}", file=progress, flush=True)
            run(spec, replay_html=str(path))
        paths.append(path)
    return paths


def save(result: Calibration, out_dir: pathlib.Path) -> None:
    """epsilon.json: the numbers behind the figure (for the results page)."""
    data = {"auc": dataclasses.asdict(result.auc),
            "bins": [dict(dataclasses.asdict(b), rate=b.rate, interval=list(b.interval)) for b in result.bins],
            "closure_fell": len(result.closure_fell), "no_closure_held": len(result.no_closure_held),
            "trials": len(result.epsilons)}
    write_atomically(out_dir / "epsilon.json", json.dumps(data, indent=1, default=float))
