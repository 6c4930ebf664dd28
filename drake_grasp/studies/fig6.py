"""Fig. 6 of the paper: shape resemblance predicts grasp success.

For each of the nine objects and each of the three compliant grasps, N trials of "explore with the
wrist camera, then execute that grasp" (`method="compliant"`). Every trial records the three
resemblances the visual primitives measured; the algorithm's choice for an object is the grasp with
the highest resemblance. The figure shows, per object, each grasp's mean resemblance (height) and
success rate (circle size), the chosen grasp marked; the summary gives the chosen grasps' success
per object and overall, beside the paper's 95.6 % (86/90).

Trials are independent, seeded (trial i of every object and grasp uses seed `seed + i`, the same
seeds as every other method), run in a local process pool, and written to ``fig6.csv`` as they
finish, each with the fingerprint of its inputs: rerunning the command after an interruption
resumes, and only records of the current inputs are counted.

The experiment:
    objects: the paper's nine (or --objects: catalogue names, primitives, mesh or model files);
    grasps: spherical, cylindrical and box, each after the camera's exploration (one exploration
        per object and seed, shared by its three grasps: `trial.run_shared`);
    seeds: trial i of every object and grasp uses seed + i, i < trials (default 10);
    writes: fig6.csv (one row per trial), fig6.png and fig6.svg, and the summary lines.
"""

import dataclasses
import json
import pathlib

import numpy as np

from drake_grasp.sweeps.results import axis_label, save_figure
from drake_grasp.sweeps.stats import error_bars, format_rate, short_rate

GRASPS = ("spherical", "cylindrical", "box")
# With the table-top estimate (a scenario's perception.table_top) the decision has a fourth choice, the
# precision grasp of flat objects (`primitives.decision`): the sweep then runs it too.
FLOWER_GRASPS = GRASPS + ("precision",)
RESEMBLANCE_OF = {"spherical": "sphere", "cylindrical": "cylinder", "box": "box", "precision": "flat"}
PAPER_CHOSEN_SUCCESS = (86, 90)  # the paper's Fig. 6: 95.6 % for the grasps the algorithm chose
QUICK_OBJECTS = ("apple", "sponge", "soccer_ball", "bottle_case")


@dataclasses.dataclass
class Fig6Config:
    """Attributes:
        objects: the objects (default: the paper's nine, annulus first).
        trials: trials per object and grasp (the paper: 10).
        seed: trial i uses seed + i.
        method: "compliant" (camera estimates, the paper's algorithm) or "oracle" (ground truth).
        scale, largest_component: options of the mesh files among the objects (`--scale`,
            `--largest-component`).
    """

    objects: tuple[str, ...]
    trials: int = 10
    seed: int = 0
    method: str = "compliant"
    scale: float = 1.0
    largest_component: bool = False
    join_gap: float | None = None
    inertia: str = "check"
    package_path: tuple[str, ...] = ()  # --package-path: where SDF/URDF files' package:// URIs resolve

    def object_options(self, obj: str) -> dict:
        """The keyword arguments that resolve `obj` as this sweep does (`--scale`,
        `--largest-component` for a mesh file; none for a catalogue object or a primitive)."""
        from drake_grasp.objects.names import mesh_options, options_for

        return options_for(obj, **mesh_options(self.scale, self.largest_component, self.join_gap, self.inertia,
                                               self.package_path))

    def __post_init__(self):
        if self.trials < 1:
            raise ValueError(f"fig6: --trials must be >= 1, got {self.trials}")
        if not self.objects:
            raise ValueError("fig6: no objects")


def sweep_grasps(scenario_file: str = "", scenario_name: str = "default") -> tuple[str, ...]:
    """The grasps a sweep runs under a scenario: the paper's three, and the precision grasp where the
    scenario's perception measures flatness (its table-top estimate)."""
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    scenario = load_scenario(scenario_file or DEFAULT_SCENARIO_FILE, scenario_name)
    return FLOWER_GRASPS if scenario.perception.table_top is not None else GRASPS


def trial_specs(config: Fig6Config, scenario_file: str = "", scenario_name: str = "default"):
    """The sweep as plain TrialSpecs."""
    from drake_grasp.sweeps.runner import TrialSpec

    grasps = sweep_grasps(scenario_file, scenario_name)
    return [TrialSpec(o, config.method, g, config.seed + i, scenario_file, scenario_name, **config.object_options(o))
            for o in config.objects for g in grasps for i in range(config.trials)]


@dataclasses.dataclass
class GraspStats:
    trials: int
    successes: int
    resemblance: float  # mean over trials (nan if none measured)
    truth_class: str | None = None  # the object's true primitive class (oracle trials record it)

    @property
    def rate(self) -> float:
        return self.successes / self.trials if self.trials else float("nan")


def _resemblance(row: dict, grasp: str) -> float:
    extra = json.loads(row.get("extra") or "{}")
    value = extra.get("resemblance", {}).get(RESEMBLANCE_OF[grasp])
    return float("nan") if value is None else float(value)


def grasp_stats(rows: list[dict], objects) -> dict[str, dict[str, GraspStats]]:
    """Per object and grasp: trials, successes, mean resemblance (the paper's three grasps, and the
    precision grasp where the rows have it)."""
    grasps = FLOWER_GRASPS if any(r["grasp"] == "precision" for r in rows) else GRASPS
    out = {}
    for o in objects:
        out[o] = {}
        for g in grasps:
            mine = [r for r in rows if r["object"] == o and r["grasp"] == g]
            res = [_resemblance(r, g) for r in mine]
            res = [x for x in res if np.isfinite(x)]
            truth = {json.loads(r.get("extra") or "{}").get("truth_class") for r in mine} - {None}
            out[o][g] = GraspStats(len(mine), sum(str(r["success"]) in ("1", "True") for r in mine),
                                   float(np.mean(res)) if res else float("nan"),
                                   truth.pop() if len(truth) == 1 else None)
    return out


def chosen_grasp(stats: dict[str, GraspStats]) -> str | None:
    """The algorithm's choice for an object: the decision (`primitives.decision`) on its mean
    resemblances, the paper's highest one unless the precision grasp's flat resemblance decides first.

    Oracle trials measure no resemblance: their choice is the grasp of the object's true class.
    """
    from drake_grasp.grasps import GRASP_OF_SHAPE
    from drake_grasp.primitives.decision import choose_shape

    measured = {RESEMBLANCE_OF[g]: s.resemblance for g, s in stats.items() if np.isfinite(s.resemblance)}
    if measured:
        return GRASP_OF_SHAPE[choose_shape(measured)]
    for g, s in stats.items():
        if s.truth_class is not None and RESEMBLANCE_OF[g] == s.truth_class:
            return g
    return None


def summary_lines(stats: dict[str, dict[str, GraspStats]]) -> list[str]:
    lines = []
    total_ok = total = 0
    for o, per_grasp in stats.items():
        choice = chosen_grasp(per_grasp)
        cells = ", ".join(f"{g} {short_rate(s.successes, s.trials)} (res {s.resemblance:.2f})"
                          for g, s in per_grasp.items())
        if choice is not None:
            total_ok += per_grasp[choice].successes
            total += per_grasp[choice].trials
        lines.append(f"{o}: chosen {choice or '-'}; {cells}")
    paper_ok, paper_n = PAPER_CHOSEN_SUCCESS
    lines.append(f"chosen grasps: {format_rate(total_ok, total)}; paper: {format_rate(paper_ok, paper_n)}")
    return lines


def plot(stats: dict[str, dict[str, GraspStats]], out_dir: pathlib.Path) -> list[pathlib.Path]:
    """Fig. 6's layout: per object, each grasp's mean resemblance (y) as a circle whose area is its
    success rate; the chosen grasp ringed. Below it, each grasp's success rate with its 95 % Wilson
    interval (the chosen grasp's bar outlined). Writes fig6.png and fig6.svg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colours = {"spherical": "tab:red", "cylindrical": "tab:blue", "box": "tab:green", "precision": "tab:purple"}
    fig, (ax, bars) = plt.subplots(2, 1, figsize=(1.3 * len(stats) + 3.5, 7.0), sharex=True,
                                   gridspec_kw={"height_ratios": [3, 2]})
    for x, (o, per_grasp) in enumerate(stats.items()):
        choice = chosen_grasp(per_grasp)
        for k, (g, s) in enumerate(per_grasp.items()):
            if not np.isfinite(s.resemblance):
                continue
            xx = x + (k - 1) * 0.18
            size = 30 + 600 * (s.rate if np.isfinite(s.rate) else 0)
            ax.scatter([xx], [s.resemblance], s=size, color=colours[g], alpha=0.6,
                       label=g if x == 0 else None, edgecolors="none")
            ax.annotate(f"{s.successes}/{s.trials}", (xx, s.resemblance), fontsize=6, ha="center", va="center")
            if g == choice:
                ax.scatter([xx], [s.resemblance], s=size + 120, facecolors="none", edgecolors="black", linewidths=1.5)
        for k, (g, s) in enumerate(per_grasp.items()):
            heights, whiskers = error_bars([(s.successes, s.trials)])
            bars.bar([x + (k - 1) * 0.22], heights, 0.22, color=colours[g], alpha=0.7, yerr=whiskers, capsize=2,
                     error_kw={"linewidth": 0.8}, edgecolor="black", linewidth=1.4 if g == choice else 0.0)
    bars.set_xticks(range(len(stats)))
    bars.set_xticklabels([axis_label(o) for o in stats], fontsize=8)
    bars.set_ylim(0, 105)
    bars.set_ylabel("success (%)")
    bars.grid(alpha=0.3, axis="y")
    bars.set_title("success per grasp (error bars: 95 % Wilson; outlined: the algorithm's choice)", fontsize=8)
    ax.set_ylim(-0.05, 1.1)
    ax.set_ylabel("shape resemblance")
    ax.grid(alpha=0.3, axis="y")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(title="grasp\n(circle area = success rate,\nring = the algorithm's choice)", fontsize=7,
                  title_fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), markerscale=0.35, frameon=False)
    else:  # oracle trials measure no resemblance
        ax.text(0.5, 0.5, "no resemblances measured (oracle trials)", transform=ax.transAxes, ha="center")
    ax.set_title("Fig. 6: resemblance of each compliant grasp's shape vs. its success", fontsize=9)
    fig.tight_layout()
    paths = save_figure(fig, out_dir, "fig6", dpi=120)
    plt.close(fig)
    return paths


def run_sweep(config: Fig6Config, out_dir: pathlib.Path, workers: int | None = None, scenario_file: str = "",
              scenario_name: str = "default", executor=None) -> tuple[dict, list[pathlib.Path], list[str], int]:
    """Runs (or resumes) the sweep into out_dir/fig6.csv, plots it and summarises it. Trials run on
    `executor` (`executors.make_executor`), or with none on a local executor of `workers` processes.

    Returns (per-object per-grasp stats, figure paths, summary lines, number of trials).
    """
    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.runner import run_trials

    with results_lock(out_dir):
        specs = trial_specs(config, scenario_file, scenario_name)
        rows = run_trials(specs, out_dir / "fig6.csv", workers=workers, label="fig6", executor=executor)
        stats = grasp_stats(rows, config.objects)
        return stats, plot(stats, out_dir), summary_lines(stats), len(rows)
