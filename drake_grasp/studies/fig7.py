"""Fig. 7 of the paper: the compliance-centric algorithm against a compliance-agnostic planner.

For the six modelled objects, GraspIt!'s Eigengrasp planner (our reimplementation,
`baselines.eigengrasp`) gets the exact object model and pose (the object resting on the table, which
the planner treats as an obstacle, as a GraspIt! world with the table loaded would), anneals for 70,000 steps and closes
its best states with autograsp; its three best grasps are each executed N times (default 10) by the
same trial runner as the compliance-centric trials: same arm, hand controller, timings, per-trial
seeds and success test. Reported per object: the compliance-centric success (the chosen grasp's, from
Fig. 6's results when they exist, else run here), the Eigengrasp *average* over all 3N attempts, and
its *best* grasp's success (chosen in hindsight).

Plans are stored as JSON (``plans/``) and trials in ``fig7.csv`` as they finish: rerunning resumes.

The experiment:
    objects: the six modelled objects of the paper's Fig. 7 (or --objects);
    grasps: the planner's three best grasps the arm can reach (one plan per object), against the
        compliance-centric algorithm's chosen grasp;
    seeds: trial i of every grasp uses seed + i, i < trials (default 10), as Fig. 6;
    writes: plans/ (one JSON per object), fig7.csv (planner trials), fig7_compliant.csv (the
        algorithm's trials not found in Fig. 6's results), fig7.png and fig7.svg.
"""

import contextlib
import dataclasses
import json
import pathlib
import sys
import time

import numpy as np

from drake_grasp.sweeps.results import axis_label, save_figure
from drake_grasp.sweeps.stats import error_bars, short_rate

from drake_grasp.studies import fig6

OBJECTS = ("sponge", "spectacle_case", "toy_bridge", "soccer_ball", "game_box", "bottle_case")
QUICK_OBJECTS = ("sponge", "soccer_ball")
PAPER_FINDINGS = (
    "paper: equal success in the annulus except the spectacle case; the planner failed every attempt "
    "on the bottle case and the soccer ball; game box 100% for both"
)


@dataclasses.dataclass
class Fig7Config:
    """Attributes:
        objects: objects to compare.
        trials: executions of each planned grasp (and compliance-centric trials per grasp).
        seed: trial i uses seed + i; the planner uses `seed` too.
        steps: the planner's step limit (GraspIt!'s counter: 70,000 = 40,000 iterations).
        energy: "contact" or "contact-quality".
        compliant_method: "compliant" (camera) or "oracle" (ground-truth estimates) for the
            compliance-centric side, when Fig. 6's results are not reused.
        scale, largest_component: options of the mesh files among the objects.
    """

    objects: tuple[str, ...] = OBJECTS
    trials: int = 10
    seed: int = 0
    steps: int = 70_000
    energy: str = "contact-quality"
    compliant_method: str = "compliant"
    scale: float = 1.0
    largest_component: bool = False
    join_gap: float | None = None
    inertia: str = "check"
    package_path: tuple[str, ...] = ()  # --package-path: where SDF/URDF files' package:// URIs resolve

    def object_options(self, obj: str) -> dict:
        """The keyword arguments that resolve `obj` as this comparison does (`--scale`,
        `--largest-component` for a mesh file; none for anything else)."""
        from drake_grasp.objects.names import mesh_options, options_for

        return options_for(obj, **mesh_options(self.scale, self.largest_component, self.join_gap, self.inertia,
                                               self.package_path))

    @property
    def plan_tag(self) -> str:
        """Names the plan in trial records, so that trials of another plan are never mixed in."""
        return f"{self.energy}/{self.steps}/seed{self.seed}"

    def __post_init__(self):
        if self.trials < 1:
            raise ValueError(f"fig7: --trials must be >= 1, got {self.trials}")
        if self.energy not in ("contact", "contact-quality"):
            raise ValueError(f"fig7: unknown energy '{self.energy}' (contact, contact-quality)")


def plan_path(out_dir: pathlib.Path, obj: str, config: Fig7Config, fingerprint: str) -> pathlib.Path:
    """Where an object's plan is kept: named by the object (a file by its stem), the planner's
    settings and the fingerprint of its inputs (object content, scenario, version)."""
    return out_dir / "plans" / f"{pathlib.Path(obj).stem if '/' in obj else obj}_{config.energy}_{config.steps}" \
        f"_seed{config.seed}_table_{fingerprint}.json"


def plan_fingerprint(obj: str, scenario_file: str = "", scenario_name: str = "default",
                     object_options: dict | None = None) -> str:
    """The fingerprint of a plan's inputs other than the planner's settings: the object's content (with
    its mesh options) and the scenario (whose arm decides which grasps are reachable)."""
    from drake_grasp.sweeps.fingerprint import digest, object_fingerprint, scenario_fingerprint

    return digest("plan", object_fingerprint(obj, **(object_options or {})),
                  scenario_fingerprint(scenario_file, scenario_name))


def plan_object(obj: str, config: Fig7Config, scenario_file: str = "", scenario_name: str = "default"):
    """Plans one object (a worker task: plain data in and out); returns (plan dict with the grasps to
    execute under "executed": the three best the arm can reach, planning wall time in s)."""
    from baselines.eigengrasp.planner import plan_eigengrasp
    from drake_grasp.objects import pose_warnings_announced, resolve_user_object

    start = time.perf_counter()
    with pose_warnings_announced():
        options = config.object_options(obj)
        plan = plan_eigengrasp(resolve_user_object(obj, **options), max_steps=config.steps, seed=config.seed,
                               energy_name=config.energy, table=True).to_dict()
        plan["executed"] = reachable_grasps(plan, obj, scenario_file, scenario_name, object_options=options)
    return plan, time.perf_counter() - start


def ensure_plans(out_dir: pathlib.Path, config: Fig7Config, executor, progress=sys.stderr,
                 scenario_file: str = "", scenario_name: str = "default", label: str = "fig7") -> dict[str, dict]:
    """The planner's result for each object: read back from its JSON file, or planned on `executor`
    (objects in parallel) and written as each plan arrives (a line to `progress`, named `label`)."""
    from drake_grasp.sweeps.results import write_atomically

    plans = {}
    todo = []
    paths = {obj: plan_path(out_dir, obj, config, plan_fingerprint(obj, scenario_file, scenario_name,
                                                                   config.object_options(obj)))
             for obj in config.objects}
    for obj in config.objects:
        plan = _read_plan(paths[obj], progress)
        if plan is not None:
            plans[obj] = plan
        else:
            todo.append((obj, config, scenario_file, scenario_name))
    with contextlib.closing(executor.imap_unordered(plan_object, todo)) as results:
        for index, (plan, seconds) in results:
            obj = todo[index][0]
            path = paths[obj]
            path.parent.mkdir(parents=True, exist_ok=True)
            write_atomically(path, json.dumps(plan, indent=1))
            plans[obj] = plan
            eps = ", ".join(f"{g['epsilon']:.3f}" for g in plan["grasps"])
            ranks = ", ".join(str(g["planner_rank"]) for g in plan["executed"])
            print(f"{label}: planned {obj} ({config.energy}, {config.steps} steps) in {seconds:.0f} s; "
                  f"eps of the top 3 after autograsp [{eps}]; executing ranks [{ranks}] of "
                  f"{len(plan['candidates'])} (the best the arm can reach)", file=progress, flush=True)
    return {obj: plans[obj] for obj in config.objects}


def _read_plan(path: pathlib.Path, progress) -> dict | None:
    """A plan written earlier, or None if there is none or it is damaged (then it is planned again)."""
    if not path.exists():
        return None
    try:
        plan = json.loads(path.read_text())
        if isinstance(plan, dict) and {"grasps", "executed", "candidates"} <= plan.keys():
            return plan
    except (OSError, ValueError):
        pass
    print(f"{path}: damaged plan, planning again", file=progress, flush=True)
    return None


def reachable_grasps(plan: dict, obj: str, scenario_file: str = "", scenario_name: str = "default",
                     count: int = 3, object_options: dict | None = None) -> list[dict]:
    """The `count` best of the plan's ranked candidates that the WAM can execute, with their
    "planner_rank" (`trial.reachable_grasps`, for the object and scenario named here)."""
    from drake_grasp.objects import resolve_user_object
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario
    from drake_grasp.trial import reachable_grasps as reachable

    scenario = load_scenario(scenario_file or DEFAULT_SCENARIO_FILE, scenario_name)
    return reachable(plan, scenario, resolve_user_object(obj, **(object_options or {})), count)


def eigengrasp_specs(plans: dict, config: Fig7Config, scenario_file="", scenario_name="default"):
    from drake_grasp.sweeps.runner import TrialSpec

    specs = []
    for obj, plan in plans.items():
        for rank, grasp in enumerate(plan["executed"], start=1):
            planned = {"X_OH": grasp["X_OH"], "joint_angles": grasp["pregrasp_joint_angles"],
                       "epsilon": grasp["epsilon"], "energy": config.energy, "planner_rank": grasp["planner_rank"]}
            for i in range(config.trials):
                specs.append(TrialSpec(obj, "eigengrasp", f"{config.plan_tag}#{rank}", config.seed + i,
                                       scenario_file, scenario_name, planned, **config.object_options(obj)))
    return specs


@dataclasses.dataclass
class Comparison:
    """One object's row of Fig. 7 (rates in [0, 1], nan when nothing was run)."""

    object: str
    compliant: float
    compliant_trials: int
    compliant_grasp: str
    eigengrasp_average: float
    eigengrasp_best: float
    eigengrasp_trials: int
    per_grasp: dict

    @property
    def compliant_counts(self) -> tuple[int, int]:
        """(successes, trials) of the compliance-centric side."""
        if not self.compliant_trials or not np.isfinite(self.compliant):
            return 0, 0
        return round(self.compliant * self.compliant_trials), self.compliant_trials

    @property
    def eigengrasp_counts(self) -> tuple[int, int]:
        """(successes, trials) over all of the planner's executed grasps."""
        return sum(ok for ok, _ in self.per_grasp.values()), sum(n for _, n in self.per_grasp.values())

    @property
    def best_counts(self) -> tuple[int, int]:
        """(successes, trials) of the planner's best grasp (chosen in hindsight: its interval is that
        grasp's own, and the choice makes it optimistic)."""
        return max(self.per_grasp.values(), key=lambda c: (c[0] / c[1] if c[1] else -1.0, c[1]), default=(0, 0))


def compare(objects, eigen_rows: list[dict], compliant_stats: dict, plan_tag: str) -> list[Comparison]:
    out = []
    for obj in objects:
        mine = [r for r in eigen_rows if r["object"] == obj and r["grasp"].startswith(plan_tag + "#")]
        per_grasp = {}
        for r in mine:
            ok, n = per_grasp.get(r["grasp"], (0, 0))
            per_grasp[r["grasp"]] = (ok + (str(r["success"]) in ("1", "True")), n + 1)
        total_ok = sum(ok for ok, _ in per_grasp.values())
        total = sum(n for _, n in per_grasp.values())
        best = max((ok / n for ok, n in per_grasp.values() if n), default=float("nan"))
        stats = compliant_stats.get(obj, {})
        choice = fig6.chosen_grasp(stats) if stats else None
        c_rate = stats[choice].rate if choice else float("nan")
        c_trials = stats[choice].trials if choice else 0
        out.append(Comparison(obj, c_rate, c_trials, choice or "-", total_ok / total if total else float("nan"),
                              best, total, per_grasp))
    return out


def summary_lines(rows: list[Comparison], energy: str, compliant_source: str) -> list[str]:
    lines = []
    for c in rows:
        grasps = ", ".join(f"{g.split('#')[1]}: {ok}/{n}" for g, (ok, n) in sorted(c.per_grasp.items()))
        lines.append(
            f"{c.object}: compliance-centric {_rate(c.compliant, c.compliant_trials)} ({c.compliant_grasp}); "
            f"Eigengrasp ({energy}) average {_rate(c.eigengrasp_average, c.eigengrasp_trials)}, "
            f"best {short_rate(*c.best_counts)} [{grasps}]")
    lines.append(f"compliance-centric side: {compliant_source}")
    lines.append(PAPER_FINDINGS)
    return lines


def _rate(rate: float, trials: int) -> str:
    """A rate over `trials` with its 95 % interval (`stats.format_rate`)."""
    from drake_grasp.sweeps.stats import format_rate

    return format_rate(round(rate * trials), trials) if trials and np.isfinite(rate) else "n/a"


def plot(rows: list[Comparison], out_dir: pathlib.Path, energy: str) -> list[pathlib.Path]:
    """Per object: compliance-centric success, Eigengrasp average and best. Writes fig7.png/svg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(max(7.5, 1.5 * len(rows) + 4), 4))
    x = np.arange(len(rows))
    width = 0.26
    series = [("compliance-centric", [c.compliant_counts for c in rows], "tab:orange"),
              (f"Eigengrasp average ({energy})", [c.eigengrasp_counts for c in rows], "tab:gray"),
              (f"Eigengrasp best ({energy})", [c.best_counts for c in rows], "tab:blue")]
    for k, (label, counts, colour) in enumerate(series):
        heights, whiskers = error_bars(counts)
        ax.bar(x + (k - 1) * width, heights, width, label=label, color=colour, yerr=whiskers, capsize=2,
               error_kw={"linewidth": 0.8})
    ax.set_xticks(x)
    ax.set_xticklabels([axis_label(c.object) for c in rows], fontsize=8)
    ax.set_ylim(0, 105)
    ax.set_ylabel("success (%)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False,
              title="error bars: 95 % Wilson", title_fontsize=7)
    ax.grid(alpha=0.3, axis="y")
    ax.set_title("Fig. 7: compliance-centric grasps vs. the Eigengrasp planner\n(same arm, controller, seeds and success test)",
                 fontsize=9)
    fig.tight_layout()
    paths = save_figure(fig, out_dir, "fig7", dpi=120)
    plt.close(fig)
    return paths


def run_comparison(config: Fig7Config, out_dir: pathlib.Path, fig6_dir: pathlib.Path, workers: int | None = None,
                   scenario_file: str = "", scenario_name: str = "default", executor=None):
    """Plans, executes (or resumes) the planned grasps, gathers the compliance-centric trials (Fig. 6's
    where they exist, else run here), plots and summarises. Plans and trials run on `executor`
    (`executors.make_executor`), or with none on a local executor of `workers` processes.

    Returns (list of Comparison, figure paths, summary lines).
    """
    from drake_grasp.sweeps.executors import LocalExecutor
    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.results import check_results_file
    from drake_grasp.sweeps.runner import TRIAL_FIELDS, fingerprints, run_trials, select, trial_table

    fig6_csv = pathlib.Path(fig6_dir) / "fig6.csv"
    with results_lock(out_dir):
        for path in (out_dir / "fig7.csv", out_dir / "fig7_compliant.csv", fig6_csv):  # before planning
            check_results_file(path, TRIAL_FIELDS)
        executor = executor or LocalExecutor(workers)
        plans = ensure_plans(out_dir, config, executor, scenario_file=scenario_file, scenario_name=scenario_name)
        eigen_rows = run_trials(eigengrasp_specs(plans, config, scenario_file, scenario_name), out_dir / "fig7.csv",
                                label="fig7", executor=executor)
        f6_config = fig6.Fig6Config(objects=config.objects, trials=config.trials, seed=config.seed,
                                    method=config.compliant_method, scale=config.scale,
                                    largest_component=config.largest_component, join_gap=config.join_gap,
                                    inertia=config.inertia, package_path=config.package_path)
        f6_specs = fig6.trial_specs(f6_config, scenario_file, scenario_name)
        f6_prints = fingerprints(f6_specs)
        # Fig. 6's records of the same inputs (same fingerprints) are reused; its file is only read.
        reused = select(trial_table(fig6_csv, read_only=True).rows(), f6_specs, f6_prints) \
            if fig6_csv.is_file() else []
        have = {tuple(r[k] for k in ("object", "method", "grasp", "seed")) for r in reused}
        missing = [s for s in f6_specs if (s.object, s.method, s.grasp, str(s.seed)) not in have]
        own = run_trials(missing, out_dir / "fig7_compliant.csv", label="fig7 compliant", executor=executor)
        compliant_rows = reused + own
        source = (f"{len(reused)} trials reused from {fig6_csv}, {len(missing)} run here"
                  f" (method {config.compliant_method})")
        comparison = compare(config.objects, eigen_rows, fig6.grasp_stats(compliant_rows, config.objects),
                             config.plan_tag)
        return comparison, plot(comparison, out_dir, config.energy), summary_lines(comparison, config.energy, source)
