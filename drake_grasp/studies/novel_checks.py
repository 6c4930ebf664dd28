"""Two checks of the camera's side of the novel-objects study: against the true estimate, and when
nothing fits.

* **The camera against the true estimate.** For each object, its chosen grasp is run again from the
  ground-truth estimate (method "oracle", the same seeds and scenario): what the camera's estimate
  loses is the difference of the two success rates, per class and overall, in points.
* **When nothing fits.** Every camera-driven trial records its resemblances; their decision margin
  (`primitives.decision.decision_margin`: the best resemblance's lead, bounded by flatness's distance
  from its threshold) says how clear the choice was. Objects whose mean margin is below `LOW_MARGIN`
  are those no primitive clearly fits: the section gives every grasp's success on them, beside the
  clear ones, so that the choice rule is judged where it is closest.

Pure functions over trial rows (dicts as the runner writes them), apart from `oracle_specs`, which
only builds the trials' specs.
"""

import collections
import json

import numpy as np

from drake_grasp.primitives.decision import decision_margin
from drake_grasp.sweeps.runner import succeeded
from drake_grasp.sweeps.stats import format_rate

LOW_MARGIN = 0.2  # a decision margin below this is a close call (a choice)


def oracle_specs(chosen: dict, trials: int, seed: int, scenario_file: str = "", scenario_name: str = "default"):
    """The trials of each object's chosen grasp from the true estimate: `chosen` maps an object to its
    chosen grasp ("-" or None: skipped); trial i uses seed + i, as the camera's."""
    from drake_grasp.sweeps.runner import TrialSpec

    return [TrialSpec(o, "oracle", g, seed + i, scenario_file, scenario_name)
            for o, g in chosen.items() if g and g != "-" for i in range(trials)]


def truth_lines(rows, oracle_rows: list[dict]) -> list[str]:
    """Markdown: per class, the camera's chosen-grasp success against the same grasp from the true
    estimate (`rows`: the study's NovelRows), and the difference in points."""
    truth = collections.defaultdict(lambda: [0, 0])
    for r in oracle_rows:
        truth[(r["object"], r["grasp"])][0] += succeeded(r)
        truth[(r["object"], r["grasp"])][1] += 1

    def totals(mine):
        cam = [sum(r.chosen_successes for r in mine), sum(r.chosen_trials for r in mine)]
        true = [sum(truth[(r.object, r.chosen_grasp)][i] for r in mine) for i in (0, 1)]
        return cam, true

    lines = ["| class | camera (chosen grasp) | same grasp, true estimate | camera − true (points) |",
             "|---|---|---|---:|"]
    classes = sorted({r.object_class for r in rows})
    for label, mine in [(c, [r for r in rows if r.object_class == c]) for c in classes] + [("all", rows)]:
        (ck, cn), (tk, tn) = totals(mine)
        diff = f"{100 * (ck / cn - tk / tn):+.0f}" if cn and tn else "-"
        lines.append(f"| {label} | {format_rate(ck, cn)} | {format_rate(tk, tn)} | {diff} |")
    return lines


def object_margins(compliant_rows: list[dict]) -> dict[str, float]:
    """Per object, the mean decision margin over its camera-driven trials (one exploration per seed:
    a seed's trials share their resemblances, so each seed counts once)."""
    per_seed = {}
    for r in compliant_rows:
        extra = json.loads(r.get("extra") or "{}")
        margin = decision_margin(extra.get("resemblance") or {})
        if np.isfinite(margin):
            per_seed[(r["object"], str(r["seed"]))] = margin
    by_object = collections.defaultdict(list)
    for (o, _), m in per_seed.items():
        by_object[o].append(m)
    return {o: float(np.mean(ms)) for o, ms in by_object.items()}


def margin_lines(rows, compliant_rows: list[dict], grasps) -> list[str]:
    """Markdown: objects no primitive clearly fits (mean margin < LOW_MARGIN) against the rest: the
    chosen grasp's success, each grasp's, and the objects' names with their margins."""
    margins = object_margins(compliant_rows)
    bands = [(f"margin < {LOW_MARGIN:g} (nothing clearly fits)", lambda m: m < LOW_MARGIN),
             (f"margin >= {LOW_MARGIN:g}", lambda m: m >= LOW_MARGIN)]
    lines = ["| decision | objects | chosen grasp | " + " | ".join(grasps) + " |",
             "|---|---:|---|" + "---|" * len(grasps)]
    for label, inside in bands:
        mine = [r for r in rows if r.object in margins and inside(margins[r.object])]
        chosen = format_rate(sum(r.chosen_successes for r in mine), sum(r.chosen_trials for r in mine))
        cells = [format_rate(sum(r.grasp_successes.get(g, (0, 0))[0] for r in mine),
                             sum(r.grasp_successes.get(g, (0, 0))[1] for r in mine)) for g in grasps]
        lines.append(f"| {label} | {len(mine)} | {chosen} | " + " | ".join(cells) + " |")
    close = sorted((margins[r.object], r) for r in rows if r.object in margins and margins[r.object] < LOW_MARGIN)
    if close:
        lines += ["", "Close calls: " + ", ".join(
            f"{r.object.rsplit('/', 1)[-1].rsplit('.', 1)[0]} ({m:.2f}, chose {r.chosen_grasp})" for m, r in close) + "."]
    return lines
