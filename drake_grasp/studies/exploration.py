"""Beyond the paper: the minimal exploration the paper proposes, against the full one.

The paper (Sec. 4) calls its camera exploration a proof of concept and proposes a shape hypothesis from
2-D vision, confirmed by minimal camera motion, with the full exploration as the fallback. The scenario
`minimal_exploration` builds it (`primitives.hypothesis`, docs/design.md §5.4c); this study answers the
paper's question by running both on the same objects and seeds, each followed by the algorithm's own
grasp (a compliance-centric trial, `method="compliant"`): the full exploration with the `table_top`
scenario (the same estimate of the pose and size, the paper's twelve and a half seconds of motion),
the minimal one with `minimal_exploration`.

Per set of objects and overall, with 95 % Wilson intervals: how often the two choose the same grasp,
the success of each, the exploration's simulated time and camera path (median and worst), and how often
the minimal exploration fell back to the full one, and why. The goals (reported as measured): time at
most a third of the full exploration's median, the same grasp on at least 95 % of trials, success within
the full exploration's interval.

The experiment:
    objects: the paper's nine; near-primitives (`objects.near_primitives`, NEAR of generator seed
        OBJECT_SEED, classes in turn); novel objects (`objects.novel`, NOVEL, every class); the flower
        (`objects.flower`, FLOWER, its six classes). --quick: four of the paper's objects.
    grasps: the algorithm's own choice after each exploration.
    seeds: trial i uses seed + i, i < trials, for both explorations.
    writes: OUT/objects/ (the generated files), OUT/full/trials.csv and OUT/minimal/trials.csv (one
        record per trial, as they finish; a rerun resumes), OUT/exploration.png and OUT/summary.md.
"""

import collections
import dataclasses
import json
import pathlib

import numpy as np

from drake_grasp.sweeps.results import save_figure, write_atomically
from drake_grasp.sweeps.runner import succeeded
from drake_grasp.sweeps.stats import error_bars, format_rate, wilson_interval

FULL, MINIMAL = "table_top", "minimal_exploration"
EXPLORATIONS = {"full": FULL, "minimal": MINIMAL}
QUICK_OBJECTS = ("apple", "sponge", "soccer_ball", "bottle_case")
TIME_GOAL = 1.0 / 3.0  # of the full exploration's median time
AGREEMENT_GOAL = 0.95


@dataclasses.dataclass(frozen=True)
class ExplorationConfig:
    """Attributes:
        trials: trials per object and exploration (trial i with seed `seed + i`).
        seed: the first trial seed.
        near, novel, flower: generated objects of each set (0: none).
        object_seed: the generators' seed.
        paper: the paper's objects (names).
    """

    trials: int = 2
    seed: int = 0
    near: int = 4
    novel: int = 7
    flower: int = 6
    object_seed: int = 0
    paper: tuple = ()

    def __post_init__(self):
        if self.trials < 1:
            raise ValueError(f"exploration: --trials must be >= 1, got {self.trials}")
        for name in ("near", "novel", "flower", "object_seed", "seed"):
            if getattr(self, name) < 0:
                raise ValueError(f"exploration: --{name.replace('_', '-')} must be >= 0, got {getattr(self, name)}")

    @classmethod
    def quick(cls, **overrides) -> "ExplorationConfig":
        return cls(**{"trials": 1, "near": 0, "novel": 0, "flower": 0, "paper": QUICK_OBJECTS, **overrides})


def study_objects(config: ExplorationConfig, out_dir: pathlib.Path) -> list[tuple[str, str, str]]:
    """(object, set, class) of every object: the paper's by name, the generated ones as files under
    out_dir/objects/<set> (generated once, reused on a rerun)."""
    from drake_grasp.objects import PAPER_OBJECTS, flower, near_primitives, novel
    from drake_grasp.sweeps.results import ensure_generated

    objects = [(name, "paper", name) for name in (config.paper or PAPER_OBJECTS)]
    sets = (("near", config.near, lambda d: near_primitives.generate(config.near, config.object_seed, d)),
            ("novel", config.novel, lambda d: novel.generate(config.novel, config.object_seed, d)),
            # The flower's first six classes, as when this study's results were stored (behaviour 0.7.0).
            ("flower", config.flower, lambda d: flower.generate(config.flower, config.object_seed, d, flower.CLASSES_0_7)))
    for name, count, generate in sets:
        if count:
            rows = ensure_generated(out_dir / "objects" / name, generate, count, (config.object_seed,))
            objects += [(row["file"], name, row["class"]) for row in rows]
    return objects


def trial_specs(config: ExplorationConfig, objects, scenario_name: str, scenario_file: str = ""):
    """One exploration's trials: the algorithm's own choice on every object and seed."""
    from drake_grasp.sweeps.runner import TrialSpec

    return [TrialSpec(o, "compliant", "", config.seed + i, scenario_file, scenario_name)
            for o, _, _ in objects for i in range(config.trials)]


# --- Analysis (pure). -----------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Pair:
    """One object and seed under both explorations (their trial rows)."""

    object: str
    set: str
    seed: int
    full: dict
    minimal: dict


def _extra(row: dict) -> dict:
    return json.loads(row.get("extra") or "{}") if isinstance(row.get("extra"), str) else (row.get("extra") or {})


def chosen(row: dict) -> str:
    return _extra(row).get("chosen") or ""


def cost(row: dict) -> dict:
    return _extra(row).get("exploration") or {}


def pairs(objects, full_rows: list[dict], minimal_rows: list[dict]) -> list[Pair]:
    """The (object, seed)s both explorations have a record of."""
    set_of = {o: s for o, s, _ in objects}
    full = {(r["object"], int(r["seed"])): r for r in full_rows}
    minimal = {(r["object"], int(r["seed"])): r for r in minimal_rows}
    return [Pair(o, set_of.get(o, "-"), seed, full[(o, seed)], minimal[(o, seed)])
            for (o, seed) in full if (o, seed) in minimal]


def _median_worst(values) -> str:
    values = [v for v in values if np.isfinite(v)]
    return f"{np.median(values):.2f} / {max(values):.2f}" if values else "-"


def _reason(why: str) -> str:
    """A fallback's reason without its measured number (so that reasons can be counted)."""
    return why.split(" (")[0] if why else "unknown"


def table_lines(rows: list[Pair]) -> list[str]:
    """Per set and overall: agreement, success of each, time and path (median / worst), fallbacks."""
    lines = ["| objects | trials | same grasp | success, full | success, minimal | time s, full | "
             "time s, minimal | path m, full | path m, minimal | fallbacks |",
             "|---|---:|---|---|---|---|---|---|---|---|"]
    sets = list(dict.fromkeys(p.set for p in rows))
    for label, mine in [(s, [p for p in rows if p.set == s]) for s in sets] + [("all", rows)]:
        if not mine:
            continue
        same = sum(chosen(p.full) == chosen(p.minimal) and chosen(p.full) != "" for p in mine)
        fallback = sum(cost(p.minimal).get("kind") == "fallback" for p in mine)
        lines.append(
            f"| {label} | {len(mine)} | {format_rate(same, len(mine))} | "
            f"{format_rate(sum(succeeded(p.full) for p in mine), len(mine))} | "
            f"{format_rate(sum(succeeded(p.minimal) for p in mine), len(mine))} | "
            f"{_median_worst([cost(p.full).get('time_s', np.nan) for p in mine])} | "
            f"{_median_worst([cost(p.minimal).get('time_s', np.nan) for p in mine])} | "
            f"{_median_worst([cost(p.full).get('path_m', np.nan) for p in mine])} | "
            f"{_median_worst([cost(p.minimal).get('path_m', np.nan) for p in mine])} | "
            f"{format_rate(fallback, len(mine))} |")
    return lines


def goal_lines(rows: list[Pair]) -> list[str]:
    """The issue's three goals, as measured."""
    if not rows:
        return ["No trial pairs yet."]
    full_time = float(np.median([cost(p.full).get("time_s", np.nan) for p in rows]))
    minimal_time = float(np.median([cost(p.minimal).get("time_s", np.nan) for p in rows]))
    same = sum(chosen(p.full) == chosen(p.minimal) and chosen(p.full) != "" for p in rows)
    full_ok = sum(succeeded(p.full) for p in rows)
    minimal_ok = sum(succeeded(p.minimal) for p in rows)
    lo, hi = wilson_interval(full_ok, len(rows))
    rate = minimal_ok / len(rows)
    ratio = minimal_time / full_time if full_time > 0 else float("nan")
    return [
        f"- Exploration time: median {minimal_time:.2f} s against {full_time:.2f} s, {ratio:.2f} of it "
        f"(goal <= {TIME_GOAL:.2f}): {'met' if ratio <= TIME_GOAL else 'not met'}.",
        f"- The same chosen grasp: {format_rate(same, len(rows))} (goal >= {100 * AGREEMENT_GOAL:.0f} %): "
        f"{'met' if same / len(rows) >= AGREEMENT_GOAL else 'not met'}.",
        f"- Success: minimal {format_rate(minimal_ok, len(rows))}, full {format_rate(full_ok, len(rows))} "
        f"(goal: within the full exploration's interval): {'met' if lo <= rate <= hi else 'not met'}.",
    ]


def fallback_lines(rows: list[Pair]) -> list[str]:
    """How often each hypothesis was confirmed or fell back, and why."""
    outcomes = collections.Counter((cost(p.minimal).get("hypothesis", "-"), cost(p.minimal).get("kind", "-"))
                                   for p in rows)
    reasons = collections.Counter(_reason(cost(p.minimal).get("why", "")) for p in rows
                                  if cost(p.minimal).get("kind") == "fallback")
    lines = ["| hypothesis | confirmed | fell back |", "|---|---:|---:|"]
    for h in sorted({h for h, _ in outcomes}):
        lines.append(f"| {h} | {outcomes[(h, 'confirmed')]} | {outcomes[(h, 'fallback')]} |")
    lines += ["", "Why it fell back: " + ("; ".join(f"{why}: {n}" for why, n in reasons.most_common()) or "never") + "."]
    disagree = [p for p in rows if chosen(p.full) != chosen(p.minimal)]
    if disagree:
        lines += ["", "Where the two chose differently: " + "; ".join(
            f"{pathlib.Path(p.object).stem} seed {p.seed} (full {chosen(p.full) or '-'}, minimal "
            f"{chosen(p.minimal) or '-'}, {cost(p.minimal).get('kind', '-')})" for p in disagree) + "."]
    return lines


def summary_lines(rows: list[Pair], config: ExplorationConfig) -> list[str]:
    return ["# The paper's proposed minimal exploration against the full one", "",
            f"Made by `drake-grasp exploration` ({config.trials} trial(s) per object and exploration, seeds "
            f"{config.seed}..{config.seed + config.trials - 1}; full: the `{FULL}` scenario, minimal: "
            f"`{MINIMAL}`; docs/design.md §5.4c). 95 % Wilson intervals; times are simulated seconds of the "
            "exploration, paths the camera's, median / worst.", "",
            *table_lines(rows), "", "Against the goals:", "", *goal_lines(rows), "",
            "## Hypotheses and fallbacks", "", *fallback_lines(rows), "",
            "![exploration](exploration.png)"]


def plot(rows: list[Pair], out_dir: pathlib.Path) -> list[pathlib.Path]:
    """Left: each trial's exploration time, full against minimal (confirmed and fallback marked);
    right: success per set with 95 % intervals. Writes exploration.png and .svg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for kind, marker, colour in (("confirmed", "o", "tab:green"), ("fallback", "x", "tab:red")):
        mine = [p for p in rows if cost(p.minimal).get("kind") == kind]
        left.scatter([cost(p.full).get("time_s", np.nan) for p in mine],
                     [cost(p.minimal).get("time_s", np.nan) for p in mine], marker=marker, color=colour,
                     label=f"minimal: {kind} ({len(mine)})")
    top = max([cost(p.minimal).get("time_s", 0.0) for p in rows] + [cost(p.full).get("time_s", 0.0) for p in rows]
              + [1.0])
    left.plot([0, top], [0, top], color="grey", lw=0.8, label="same time")
    left.plot([0, top], [0, top * TIME_GOAL], color="grey", lw=0.8, ls="--", label="a third")
    left.set_xlabel("full exploration (s)")
    left.set_ylabel("minimal exploration (s)")
    left.legend(fontsize=7)
    left.grid(alpha=0.3)
    sets = list(dict.fromkeys(p.set for p in rows)) + ["all"]
    x = np.arange(len(sets))
    for k, (name, key) in enumerate((("full", "full"), ("minimal", "minimal"))):
        counts = [(sum(succeeded(getattr(p, key)) for p in rows if s in ("all", p.set)),
                   sum(1 for p in rows if s in ("all", p.set))) for s in sets]
        heights, whiskers = error_bars(counts)
        right.bar(x + (k - 0.5) * 0.35, heights, 0.35, yerr=whiskers, capsize=2, label=name)
    right.set_xticks(x)
    right.set_xticklabels(sets)
    right.set_ylim(0, 105)
    right.set_ylabel("success (%)")
    right.legend(fontsize=7, title="exploration (95 % Wilson)", title_fontsize=7, loc="lower right")
    right.grid(alpha=0.3, axis="y")
    fig.suptitle("The paper's proposed minimal exploration against the full one", fontsize=10)
    fig.tight_layout()
    paths = save_figure(fig, out_dir, "exploration", dpi=110)
    plt.close(fig)
    return paths


def run_study(config: ExplorationConfig, out_dir: pathlib.Path, executor, scenario_file: str = ""):
    """Runs (or resumes) both explorations into out_dir, then writes the figure and summary.md (under
    the folder's lock). Returns (pairs, summary lines, figure paths)."""
    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.results import check_results_file
    from drake_grasp.sweeps.runner import TRIAL_FIELDS, run_trials

    out_dir.mkdir(parents=True, exist_ok=True)
    with results_lock(out_dir):
        for name in EXPLORATIONS:
            check_results_file(out_dir / name / "trials.csv", TRIAL_FIELDS)  # before any work
        objects = study_objects(config, out_dir)
        results = {name: run_trials(trial_specs(config, objects, scenario, scenario_file),
                                    out_dir / name / "trials.csv", label=f"exploration, {name}", executor=executor)
                   for name, scenario in EXPLORATIONS.items()}
        rows = pairs(objects, results["full"], results["minimal"])
        lines = summary_lines(rows, config)
        figures = plot(rows, out_dir)
        write_atomically(out_dir / "summary.md", "\n".join(lines) + "\n")
        return rows, lines, figures
