"""Beyond the paper: the compliance-centric algorithm and the Eigengrasp planner on novel objects.

The paper tests nine household objects. Here both methods meet objects neither has seen, made by
the novel-object generator (`drake_grasp.objects.novel`: blobs, unions of primitives, plates, L and
T shapes, rings and handles, 3-25 cm), through exactly the runner, seeds and success test of Fig. 6
and Fig. 7:

- the compliance-centric algorithm explores each object with the wrist camera and executes each of
  the three compliant grasps `trials` times (Fig. 6's sweep; with a scenario that measures flatness,
  such as `table_top`, the precision grasp too); the grasp it would choose (the decision on its mean
  resemblances, `primitives.decision`) is marked, and run again from the true estimate;
- the Eigengrasp planner gets each object's exact model, and its three best grasps the arm can reach
  are each executed `trials` times (Fig. 7's comparison).

Everything is written under one folder as it finishes and resumes like the figures do:
``objects/`` (the meshes and their manifest), ``compliant/fig6.csv``, ``eigengrasp/fig7.csv`` and
its plans, and then ``novel.csv`` (one row per object), ``novel.png``/``.svg`` and ``summary.md``:
chosen-grasp success overall and per object class with 95 % Wilson intervals, the planner's average
and best, and why the failed trials failed.

The experiment:
    objects: `count` generated novel objects (default 20, generator seed `object_seed`), every class;
    grasps: Fig. 6's compliant grasps after the camera's exploration, the chosen one from the true
        estimate, and Fig. 7's planner's three best reachable grasps;
    seeds: trial i uses seed + i, i < trials (default 5), for both methods;
    writes: objects/, compliant/fig6.csv, oracle/fig6.csv (each chosen grasp from the true estimate:
        `novel_checks`), eigengrasp/fig7.csv and plans, novel.csv (one row per object), novel.png and
        novel.svg, summary.md (with the camera against the true estimate, and when nothing fits).
"""

import collections
import csv
import dataclasses
import io
import json
import pathlib

import numpy as np

from drake_grasp.studies import fig6, fig7, novel_checks
from drake_grasp.sweeps.results import save_figure
from drake_grasp.sweeps.stats import error_bars, format_rate, short_rate, wilson_interval

GOAL = 0.90  # chosen-grasp success the study aims for on novel objects (reported as measured)


@dataclasses.dataclass(frozen=True)
class NovelConfig:
    """Attributes:
        count: novel objects to generate (or reuse).
        object_seed: the generator's seed.
        trials: executions of each grasp (both methods), trial i with seed `seed + i`.
        seed: the first trial seed; the planner's seed too.
        steps: the Eigengrasp planner's step limit.
        energy: the planner's energy ("contact" or "contact-quality").
    """

    count: int = 20
    object_seed: int = 0
    trials: int = 5
    seed: int = 0
    steps: int = 70_000
    energy: str = "contact-quality"

    def __post_init__(self):
        if self.count < 1:
            raise ValueError(f"novel: --count must be >= 1, got {self.count}")
        if self.trials < 1:
            raise ValueError(f"novel: --trials must be >= 1, got {self.trials}")

    @classmethod
    def quick(cls, **overrides) -> "NovelConfig":
        """A few objects, one trial each, a shorter plan: minutes on 2 cores, indicative only."""
        return cls(**{"count": 3, "trials": 1, "steps": 40_000, **overrides})


@dataclasses.dataclass
class NovelRow:
    """One object's line of the study (rates over trials; nan when nothing ran)."""

    object: str
    object_class: str
    chosen_grasp: str
    chosen_successes: int
    chosen_trials: int
    grasp_successes: dict  # grasp -> (successes, trials), all three compliant grasps
    planner_successes: int
    planner_trials: int
    planner_best: float
    planner_best_counts: tuple = (0, 0)  # (successes, trials) of the planner's best grasp

    @property
    def chosen_rate(self) -> float:
        return self.chosen_successes / self.chosen_trials if self.chosen_trials else float("nan")

    @property
    def planner_average(self) -> float:
        return self.planner_successes / self.planner_trials if self.planner_trials else float("nan")


def study_rows(objects: list[dict], stats6: dict, comparison: list) -> list[NovelRow]:
    """Joins the manifest (file, class), Fig. 6's per-grasp stats and Fig. 7's comparison per object."""
    by_object = {c.object: c for c in comparison}
    rows = []
    for entry in objects:
        name = entry["file"]
        per_grasp = stats6.get(name, {})
        choice = fig6.chosen_grasp(per_grasp) if per_grasp else None
        c = by_object.get(name)
        planner_ok = sum(ok for ok, _ in c.per_grasp.values()) if c else 0
        planner_n = sum(n for _, n in c.per_grasp.values()) if c else 0
        rows.append(NovelRow(
            object=name, object_class=entry["class"], chosen_grasp=choice or "-",
            chosen_successes=per_grasp[choice].successes if choice else 0,
            chosen_trials=per_grasp[choice].trials if choice else 0,
            grasp_successes={g: (s.successes, s.trials) for g, s in per_grasp.items()},
            planner_successes=planner_ok, planner_trials=planner_n,
            planner_best=c.eigengrasp_best if c else float("nan"),
            planner_best_counts=c.best_counts if c else (0, 0)))
    return rows


def failure_reasons(trial_rows: list[dict]) -> collections.Counter:
    """How many failed trials failed for each reason (the `failure` field of their records)."""
    return collections.Counter(r["failure"] or "unknown" for r in trial_rows
                               if str(r["success"]) not in ("1", "True"))


def chosen_trial_rows(compliant_rows: list[dict], rows: list[NovelRow]) -> list[dict]:
    """The compliant trials of each object's chosen grasp."""
    chosen = {r.object: r.chosen_grasp for r in rows}
    return [r for r in compliant_rows if chosen.get(r["object"]) == r["grasp"]]


def summary_lines(rows: list[NovelRow], chosen_rows: list[dict], planner_rows: list[dict],
                  config: NovelConfig) -> list[str]:
    """The study's summary in Markdown: overall, per class, per object, failure reasons."""
    ok = sum(r.chosen_successes for r in rows)
    n = sum(r.chosen_trials for r in rows)
    p_ok = sum(r.planner_successes for r in rows)
    p_n = sum(r.planner_trials for r in rows)
    lines = [
        f"Chosen-grasp success on {len(rows)} novel objects (compliance-centric, camera only): "
        f"**{format_rate(ok, n)}** (goal >= {100 * GOAL:.0f} %); Eigengrasp planner ({config.energy}, "
        f"{config.steps} steps, 3 best reachable grasps): {format_rate(p_ok, p_n)}.",
        "",
        "| class | objects | compliance-centric (chosen grasp) | Eigengrasp average |",
        "|---|---|---|---|",
    ]
    for cls in sorted({r.object_class for r in rows}):
        mine = [r for r in rows if r.object_class == cls]
        lines.append(f"| {cls} | {len(mine)} | "
                     f"{format_rate(sum(r.chosen_successes for r in mine), sum(r.chosen_trials for r in mine))} | "
                     f"{format_rate(sum(r.planner_successes for r in mine), sum(r.planner_trials for r in mine))} |")
    lines += ["", "| object | class | chosen grasp | chosen success | all grasps | Eigengrasp average | "
              "Eigengrasp best |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        grasps = ", ".join(f"{g} {k}/{m}" for g, (k, m) in r.grasp_successes.items())
        best = short_rate(*r.planner_best_counts)
        lines.append(f"| {pathlib.Path(r.object).stem} | {r.object_class} | {r.chosen_grasp} | "
                     f"{format_rate(r.chosen_successes, r.chosen_trials)} | {grasps} | "
                     f"{format_rate(r.planner_successes, r.planner_trials)} | {best} |")
    for title, trial_rows in (("compliance-centric (chosen grasps)", chosen_rows),
                              ("Eigengrasp planner", planner_rows)):
        reasons = failure_reasons(trial_rows)
        text = ", ".join(f"{why}: {count}" for why, count in reasons.most_common()) or "none"
        lines += ["", f"Failed trials, {title}: {text}."]
    return lines


def write_csv(path: pathlib.Path, rows: list[NovelRow]) -> None:
    """novel.csv: one row per object (derived from the trial records, so rewritten whole)."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["object", "class", "chosen_grasp", "chosen_successes", "chosen_trials", "chosen_ci_lo",
                     "chosen_ci_hi", "planner_successes", "planner_trials", "planner_best", "grasps"])
    for r in rows:
        lo, hi = wilson_interval(r.chosen_successes, r.chosen_trials)
        writer.writerow([r.object, r.object_class, r.chosen_grasp, r.chosen_successes, r.chosen_trials,
                         f"{lo:.4f}", f"{hi:.4f}", r.planner_successes, r.planner_trials,
                         f"{r.planner_best:.4f}", json.dumps(r.grasp_successes)])
    from drake_grasp.sweeps.results import write_atomically

    write_atomically(path, buffer.getvalue())


def plot(rows: list[NovelRow], out_dir: pathlib.Path) -> list[pathlib.Path]:
    """Per object (grouped by class): the chosen grasp's success with its 95 % interval, the planner's
    average and best. Writes novel.png and novel.svg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = sorted(rows, key=lambda r: (r.object_class, r.object))
    x = np.arange(len(rows))
    width = 0.27
    fig, ax = plt.subplots(figsize=(max(7.5, 0.55 * len(rows) + 4), 4.2))
    series = [("compliance-centric (chosen grasp)", [(r.chosen_successes, r.chosen_trials) for r in rows],
               "tab:orange"),
              ("Eigengrasp average", [(r.planner_successes, r.planner_trials) for r in rows], "tab:gray"),
              ("Eigengrasp best", [r.planner_best_counts for r in rows], "tab:blue")]
    for k, (label, counts, colour) in enumerate(series):
        heights, whiskers = error_bars(counts)
        ax.bar(x + (k - 1) * width, heights, width, color=colour, label=label, yerr=whiskers, capsize=2,
               error_kw={"linewidth": 0.8})
    ax.set_xticks(x)
    ax.set_xticklabels([pathlib.Path(r.object).stem for r in rows], fontsize=7, rotation=60, ha="right")
    ax.set_ylim(0, 105)
    ax.set_ylabel("success (%)")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False,
              title="error bars: 95 % Wilson", title_fontsize=7)
    ax.set_title("Novel objects: compliance-centric grasps vs. the Eigengrasp planner", fontsize=9)
    fig.tight_layout()
    paths = save_figure(fig, out_dir, "novel", dpi=120)
    plt.close(fig)
    return paths


def ensure_objects(directory: pathlib.Path, count: int, seed: int) -> list[dict]:
    """The novel objects of generator seed `seed`, indices 0..count-1, in `directory`: generated once,
    reused on a rerun. Returns manifest entries {"file": path, "class": name, ...}.

    The generator is deterministic (object i of seed s is the same bytes whatever `count` is), so a
    manifest of the same seed and count is reused as it is. Files are generated in a private folder
    and moved into place one by one, the manifest last: an interrupted generation leaves no torn file
    and no manifest that promises a missing one.
    """
    from drake_grasp.sweeps.results import ensure_generated
    from drake_grasp.objects.novel import generate

    return ensure_generated(directory, lambda staging: generate(count, seed, staging), count, (seed,))


def _estimator_words(scenario_file: str, scenario_name: str) -> str:
    """Which estimate placed the camera's grasps, in words, from the scenario's perception."""
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    scenario = load_scenario(scenario_file or DEFAULT_SCENARIO_FILE, scenario_name)
    if scenario.perception.table_top is not None:
        return "the camera's grasps are placed by the table-top estimate (the best the project has)"
    return "the camera's grasps are placed by the paper's silhouette estimate"


def run_study(config: NovelConfig, out_dir: pathlib.Path, objects: list[dict], executor, scenario_file: str = "",
              scenario_name: str = "default"):
    """Runs (or resumes) both methods on `objects` (manifest entries: {"file": path, "class": name}) and
    writes novel.csv, novel.png/svg and summary.md under out_dir (whose lock it holds meanwhile).

    Returns (rows, figure paths, summary lines).
    """
    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.results import check_results_file, write_atomically
    from drake_grasp.sweeps.runner import TRIAL_FIELDS, fingerprints, run_trials, select, trial_table

    out_dir.mkdir(parents=True, exist_ok=True)
    with results_lock(out_dir):
        for path in ("compliant/fig6.csv", "oracle/fig6.csv", "eigengrasp/fig7.csv", "eigengrasp/fig7_compliant.csv"):
            check_results_file(out_dir / path, TRIAL_FIELDS)  # before any work
        names = tuple(entry["file"] for entry in objects)
        config6 = fig6.Fig6Config(objects=names, trials=config.trials, seed=config.seed, method="compliant")
        stats6, _, _, _ = fig6.run_sweep(config6, out_dir / "compliant", scenario_file=scenario_file,
                                         scenario_name=scenario_name, executor=executor)
        # The camera against the true estimate: each object's chosen grasp, from the ground truth.
        chosen = {o: fig6.chosen_grasp(per_grasp) for o, per_grasp in stats6.items()}
        oracle = novel_checks.oracle_specs(chosen, config.trials, config.seed, scenario_file, scenario_name)
        oracle_rows = run_trials(oracle, out_dir / "oracle" / "fig6.csv", label="novel, true estimate",
                                 executor=executor)
        config7 = fig7.Fig7Config(objects=names, trials=config.trials, seed=config.seed, steps=config.steps,
                                  energy=config.energy)
        comparison, _, _ = fig7.run_comparison(config7, out_dir / "eigengrasp", out_dir / "compliant",
                                               scenario_file=scenario_file, scenario_name=scenario_name,
                                               executor=executor)
        rows = study_rows(objects, stats6, comparison)
        # The trials' own records (this run's fingerprints only), for the failure reasons.
        specs6 = fig6.trial_specs(config6, scenario_file, scenario_name)
        compliant_rows = select(trial_table(out_dir / "compliant" / "fig6.csv", read_only=True).rows(), specs6,
                                fingerprints(specs6))
        plans = fig7.ensure_plans(out_dir / "eigengrasp", config7, executor, scenario_file=scenario_file,
                                  scenario_name=scenario_name)  # read back: planned above
        specs7 = fig7.eigengrasp_specs(plans, config7, scenario_file, scenario_name)
        planner_rows = select(trial_table(out_dir / "eigengrasp" / "fig7.csv", read_only=True).rows(), specs7,
                              fingerprints(specs7))
        lines = summary_lines(rows, chosen_trial_rows(compliant_rows, rows), planner_rows, config)
        lines += ["", f"Scenario `{scenario_name}`" + (f" of {scenario_file}" if scenario_file else "") + ": "
                  + _estimator_words(scenario_file, scenario_name) + "."]
        grasps = fig6.sweep_grasps(scenario_file, scenario_name)
        lines += ["", "## The camera against the true estimate", "",
                  "Each object's chosen grasp again from the ground-truth estimate (the same seeds):", ""]
        lines += novel_checks.truth_lines(rows, oracle_rows)
        lines += ["", "## When nothing fits", "",
                  "Objects by their mean decision margin (docs/design.md §5.4b), every grasp's success:", ""]
        lines += novel_checks.margin_lines(rows, compliant_rows, grasps)
        write_csv(out_dir / "novel.csv", rows)
        figures = plot(rows, out_dir)
        write_atomically(out_dir / "summary.md", "# Novel objects\n\n" + "\n".join(lines) + "\n")
        return rows, figures, lines
