"""Sensitivity of the paper's claims: the algorithm's chosen grasps under friction, mass and perception.

Fig. 6's chosen grasps succeed 36/36 in this repository's default setting (9 objects x 4 trials). How
much of that rests on the assumed numbers? This sweep runs the compliance-centric algorithm (camera
only, its own choice of grasp: `TrialSpec(method="compliant", grasp="")`) on the paper's nine objects
under one base condition and one factor changed at a time:

- friction: the object's Coulomb coefficient (`contact.friction`; the trial's seeded ±20 % applies on
  top, as always) 0.3, 0.8, 1.0 against the base's 0.5. The hand's and the table's own coefficients
  stay 0.5 (their model files): Drake combines two coefficients as 2·μ1·μ2/(μ1 + μ2), so the
  hand–object pair gets 0.375, 0.615, 0.667 against 0.5.
- object mass: x0.5 and x2 (`object.mass_scale`: mass and rotational inertia about the centre of
  mass; same shape).
- perception: colour segmentation (the paper's yellow paper: the repository's `color_segmentation`
  thresholds) instead of the label image, and colour segmentation with Gaussian image noise
  (`perception.segmentation.color_noise`, sigma in 8-bit counts, seeded per trial).

Every condition is a named scenario, derived from the base scenario and written into
``conditions.yaml`` in the output folder, so each trial is an ordinary `TrialSpec(scenario_file,
scenario_name)` and its record's fingerprint covers the whole resolved condition. Trial i of every
object and condition uses seed `seed + i` (as Fig. 6), so the conditions see the same placements.
All records go to one resumable ``sensitivity.csv``; then ``summary.md`` (success per condition with
95 % Wilson intervals, a condition x object table, and the paper's claims that these trials can
decide, judged per condition: holds or flips), ``conditions.csv`` and ``sensitivity.png``/``.svg``.
"""

import collections
import csv
import dataclasses
import io
import json
import math
import pathlib
import sys

from drake_grasp.experiments.stats import format_rate, wilson_interval

PAPER_CHOSEN_SUCCESS = (86, 90)  # the paper's Fig. 6: 95.6 % for the grasps the algorithm chose
CLAIM_MARGIN = 0.10  # "within 10 points of the paper" (reproduce.fig6_claims' rule)
OBJECT_HOLDS = 0.70  # a chosen grasp "holds" an object at >= 70 % (reproduce's annulus rule)
# The sun-ray objects and the one grasp that works on each in the paper's Fig. 6 (the grasp of its shape).
SUN_RAY_GRASP = {"soccer_ball": "spherical", "game_box": "box", "bottle_case": "cylindrical"}
QUICK_OBJECTS = ("apple", "banana", "soccer_ball")  # the two that failed at friction 0.3, and a sun ray
DEFAULT_NOISE_SIGMA = 10.0  # 8-bit counts
HAND_FRICTION = 0.5  # the hand's and the table's coefficient (models/*.sdf); for the pair coefficient


@dataclasses.dataclass(frozen=True)
class Condition:
    """One condition of the sweep: the base scenario with at most one factor changed.

    Attributes:
        name: its scenario's name in conditions.yaml (letters, digits, '_', '.').
        factor: "base", "friction", "mass" or "perception".
        label: how tables and figures name it.
        friction: the object's friction coefficient (`contact.friction`), or None: the base's.
        mass_scale: `object.mass_scale`, or None: the base's.
        segmentation: "color" for colour segmentation, or None: the base's.
        noise_sigma: with "color", image noise in 8-bit counts, or None: none.
    """

    name: str
    factor: str
    label: str
    friction: float | None = None
    mass_scale: float | None = None
    segmentation: str | None = None
    noise_sigma: float | None = None


def default_conditions(frictions=(0.3, 0.8, 1.0), mass_scales=(0.5, 2.0),
                       noise_sigma: float = DEFAULT_NOISE_SIGMA) -> tuple[Condition, ...]:
    """The base condition and one factor changed at a time (the issue's sweep)."""
    conditions = [Condition("base", "base", "base")]
    conditions += [Condition(f"friction_{_friction(f)}", "friction", f"friction {_friction(f)}", friction=f)
                   for f in frictions]
    conditions += [Condition(f"mass_x{_number(m)}", "mass", f"mass x{_number(m)}", mass_scale=m)
                   for m in mass_scales]
    conditions += [Condition("color", "perception", "colour segm.", segmentation="color"),
                   Condition(f"color_noise_{_number(noise_sigma)}", "perception",
                             f"colour + noise {_number(noise_sigma)}", segmentation="color",
                             noise_sigma=noise_sigma)]
    return tuple(conditions)


def _number(value: float) -> str:
    return f"{value:g}"


def _friction(value: float) -> str:
    text = f"{value:g}"
    return text if "." in text or "e" in text else text + ".0"


@dataclasses.dataclass(frozen=True)
class SensitivityConfig:
    """Attributes:
        objects: the objects (default: the paper's nine).
        trials: trials per object and condition (trial i with seed `seed + i`).
        seed: the first trial seed.
        conditions: the conditions (default: `default_conditions()`); the first is the base.
        scenario_file, scenario_name: the base scenario ("" = the repository's scenarios).
    """

    objects: tuple[str, ...] = ()
    trials: int = 4
    seed: int = 0
    conditions: tuple[Condition, ...] = ()
    scenario_file: str = ""
    scenario_name: str = "default"

    def __post_init__(self):
        if not self.objects:
            from drake_grasp.objects import PAPER_OBJECTS

            object.__setattr__(self, "objects", tuple(PAPER_OBJECTS))
        if not self.conditions:
            object.__setattr__(self, "conditions", default_conditions())
        if self.trials < 1:
            raise ValueError(f"sensitivity: trials must be >= 1, got {self.trials}")
        if not 0 <= self.seed or self.seed + self.trials - 1 >= 2**32:
            raise ValueError(f"sensitivity: seeds {self.seed}..{self.seed + self.trials - 1} must be in [0, 2^32)")
        if len(set(self.objects)) != len(self.objects):
            raise ValueError("sensitivity: an object is named twice")
        names = [c.name for c in self.conditions]
        if len(set(names)) != len(names):
            raise ValueError(f"sensitivity: two conditions share a name ({', '.join(names)})")
        for c in self.conditions:
            _check_condition(c)

    @classmethod
    def quick(cls, **overrides) -> "SensitivityConfig":
        """Every condition, the full protocol (10 s hold), 3 objects, 1 trial: 24 trials, minutes on
        2 cores; indicative only."""
        return cls(**{"objects": QUICK_OBJECTS, "trials": 1, **overrides})


def _check_condition(c: Condition) -> None:
    import re

    if not re.fullmatch(r"[A-Za-z0-9_.]+", c.name):
        raise ValueError(f"sensitivity: condition name {c.name!r} must be letters, digits, '_' or '.'")
    if c.factor not in ("base", "friction", "mass", "perception"):
        raise ValueError(f"sensitivity: condition {c.name}: unknown factor {c.factor!r}")
    if c.friction is not None and not (math.isfinite(c.friction) and c.friction > 0):
        raise ValueError(f"sensitivity: condition {c.name}: friction must be > 0, got {c.friction}")
    if c.mass_scale is not None and not (math.isfinite(c.mass_scale) and c.mass_scale > 0):
        raise ValueError(f"sensitivity: condition {c.name}: mass scale must be > 0, got {c.mass_scale}")
    if c.segmentation not in (None, "color", "label"):
        raise ValueError(f"sensitivity: condition {c.name}: segmentation must be 'color' or 'label'")
    if c.noise_sigma is not None and (c.segmentation != "color" or not (math.isfinite(c.noise_sigma)
                                                                         and c.noise_sigma >= 0)):
        raise ValueError(f"sensitivity: condition {c.name}: image noise needs colour segmentation and sigma >= 0")


# --- The conditions as scenarios ----------------------------------------------------------------------


def condition_scenario(base, condition: Condition, color_segmentation):
    """The scenario of `condition`: a copy of `base` (a station.Scenario) with its factor changed.

    Args:
        base: the base scenario.
        condition: the condition.
        color_segmentation: the colour segmentation's parameters (a SegmentationParams: the
            repository's `color_segmentation` scenario's), used when the condition asks for colour.
    """
    import copy

    scenario = copy.deepcopy(base)
    if condition.friction is not None:
        scenario.contact.friction = float(condition.friction)
    if condition.mass_scale is not None:
        scenario.object.mass_scale = float(condition.mass_scale)
    if condition.segmentation == "color":
        segmentation = copy.deepcopy(color_segmentation)
        segmentation.method = "color"
        segmentation.color_noise = None
        if condition.noise_sigma is not None:
            from drake_grasp.primitives.camera import ColorNoise

            segmentation.color_noise = ColorNoise(sigma=float(condition.noise_sigma))
        scenario.perception.segmentation = segmentation
    elif condition.segmentation == "label":
        scenario.perception.segmentation.method = "label"
        scenario.perception.segmentation.color_noise = None
    return scenario


def conditions_yaml(base, conditions: tuple[Condition, ...], color_segmentation) -> str:
    """conditions.yaml's text: each condition as a named scenario, every field written out (Drake's
    typed YAML dump), so that loading it (over the repository's default scenario, as any scenario file
    is) gives exactly the condition's scenario."""
    from pydrake.common.yaml import yaml_dump_typed

    header = ("# The sensitivity sweep's conditions (drake_grasp/experiments/sensitivity.py), one named\n"
              "# scenario each, written from the base scenario; rewritten by every run of the sweep.\n")
    parts = [header]
    for c in conditions:
        parts.append(f"# {c.label}\n")
        parts.append(yaml_dump_typed(condition_scenario(base, c, color_segmentation), child_name=c.name))
    return "".join(parts)


def write_conditions(path: pathlib.Path, config: SensitivityConfig) -> None:
    """Writes conditions.yaml for `config` (base scenario, conditions) and checks that each condition
    loads back as a valid scenario (ValueError, one line, if not)."""
    from drake_grasp.experiments.results import write_atomically
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    base = load_scenario(config.scenario_file or DEFAULT_SCENARIO_FILE, config.scenario_name)
    color = load_scenario(DEFAULT_SCENARIO_FILE, "color_segmentation").perception.segmentation
    text = conditions_yaml(base, config.conditions, color)
    if not path.is_file() or path.read_text() != text:
        write_atomically(path, text)
    for c in config.conditions:
        load_scenario(path, c.name)


def trial_specs(config: SensitivityConfig, conditions_file: str) -> list:
    """The sweep as TrialSpecs: trial index first, so that an interrupted run covers every condition
    and object evenly."""
    from drake_grasp.experiments.runner import TrialSpec

    return [TrialSpec(o, "compliant", "", config.seed + i, conditions_file, c.name)
            for i in range(config.trials) for c in config.conditions for o in config.objects]


# --- Analysis (pure: rows in, tables and verdicts out) --------------------------------------------------


def _ok(row: dict) -> bool:
    return str(row["success"]) in ("1", "True", "true")


def _chosen(row: dict) -> str:
    try:
        return json.loads(row.get("extra") or "{}").get("chosen") or ""
    except ValueError:
        return ""


@dataclasses.dataclass
class Cell:
    """One object under one condition: its trials."""

    successes: int = 0
    trials: int = 0
    chosen: collections.Counter = dataclasses.field(default_factory=collections.Counter)
    failures: collections.Counter = dataclasses.field(default_factory=collections.Counter)

    @property
    def rate(self) -> float:
        return self.successes / self.trials if self.trials else float("nan")


def tabulate(rows_by_condition: dict[str, list[dict]], objects) -> dict[str, dict[str, Cell]]:
    """Per condition and object: successes, trials, the grasps chosen, the failure reasons."""
    table = {}
    for name, rows in rows_by_condition.items():
        table[name] = {o: Cell() for o in objects}
        for r in rows:
            cell = table[name].setdefault(r["object"], Cell())
            cell.trials += 1
            cell.successes += _ok(r)
            cell.chosen[_chosen(r) or "-"] += 1
            if not _ok(r):
                cell.failures[r.get("failure") or "unknown"] += 1
    return table


def totals(cells: dict[str, Cell]) -> tuple[int, int]:
    return sum(c.successes for c in cells.values()), sum(c.trials for c in cells.values())


@dataclasses.dataclass
class Verdict:
    """A claim under one condition: "holds", "flips" or "n/a" (nothing measured), what was measured,
    and whether the 95 % interval alone decides it ("sure") or not ("unsure")."""

    verdict: str
    ours: str
    certainty: str = ""


@dataclasses.dataclass
class ClaimResult:
    claim: str
    paper: str
    rule: str
    per_condition: dict  # condition name -> Verdict

    def across(self, conditions) -> str:
        """'holds in every condition', 'flips under A, B', or 'not measured'."""
        measured = [c for c in conditions if self.per_condition[c.name].verdict != "n/a"]
        if not measured:
            return "not measured"
        flips = [c.label for c in measured if self.per_condition[c.name].verdict == "flips"]
        if not flips:
            return "holds in every condition"
        return "flips under " + ", ".join(flips)


def _threshold_verdict(successes: int, trials: int, threshold: float) -> Verdict:
    """holds when the rate >= threshold; "sure" when the whole Wilson interval is on that side."""
    if trials == 0:
        return Verdict("n/a", "no trials")
    lo, hi = wilson_interval(successes, trials)
    rate = successes / trials
    holds = rate >= threshold - 1e-12
    sure = lo >= threshold if holds else hi < threshold
    return Verdict("holds" if holds else "flips", f"{successes}/{trials}", "sure" if sure else "unsure")


def claims(table: dict[str, dict[str, Cell]], conditions, objects) -> list[ClaimResult]:
    """The paper's claims that the chosen-grasp trials can decide, judged per condition."""
    paper_ok, paper_n = PAPER_CHOSEN_SUCCESS
    threshold = paper_ok / paper_n - CLAIM_MARGIN
    overall = ClaimResult(
        "Fig. 6: the algorithm's chosen grasps succeed", format_rate(paper_ok, paper_n),
        f"success within {100 * CLAIM_MARGIN:.0f} points of the paper (>= {100 * threshold:.1f} %); "
        "'sure' when the whole 95 % interval is on that side",
        {c.name: _threshold_verdict(*totals(table[c.name]), threshold) for c in conditions})
    out = [overall]
    for o in objects:
        out.append(ClaimResult(
            f"{o}: the chosen grasp holds it", "held (Fig. 6)",
            f"chosen-grasp success >= {100 * OBJECT_HOLDS:.0f} %",
            {c.name: _threshold_verdict(table[c.name][o].successes, table[c.name][o].trials, OBJECT_HOLDS)
             for c in conditions}))
    for o, grasp in SUN_RAY_GRASP.items():
        if o not in objects:
            continue
        per = {}
        for c in conditions:
            cell = table[c.name][o]
            if cell.trials == 0:
                per[c.name] = Verdict("n/a", "no trials")
                continue
            right = cell.chosen.get(grasp, 0)
            per[c.name] = Verdict("holds" if right == cell.trials else "flips", f"{right}/{cell.trials} {grasp}")
        out.append(ClaimResult(f"{o} (a sun ray): the algorithm chooses the {grasp} grasp",
                               f"{grasp} (the one grasp that works)", "every trial chooses it", per))
    return out


def pair_friction(mu: float, other: float = HAND_FRICTION) -> float:
    """Drake's combined coefficient of two geometries: 2·μ1·μ2/(μ1 + μ2)."""
    return 2 * mu * other / (mu + other) if mu + other > 0 else 0.0


def summary_lines(table: dict[str, dict[str, Cell]], config: SensitivityConfig, base_friction: float,
                  cpu_note: str = "", base_segmentation: str = "label") -> list[str]:
    """summary.md's text (Markdown)."""
    conditions, objects = config.conditions, config.objects
    n_total = sum(totals(table[c.name])[1] for c in conditions)
    seeds = f"{config.seed}" if config.trials == 1 else f"{config.seed}..{config.seed + config.trials - 1}"
    lines = [
        f"Trials: **{n_total}** ({config.trials} per object and condition, seeds {seeds}; {len(objects)} objects x "
        f"{len(conditions)} conditions); base scenario `{config.scenario_name}`"
        f"{' of ' + config.scenario_file if config.scenario_file else ''}; the algorithm's own choice of grasp "
        "(camera only), the full protocol (10 s hold unless the base scenario says otherwise). "
        "Intervals: 95 % Wilson.",
        "",
        "## Success of the chosen grasps per condition",
        "",
        "| condition | object μ (hand–object pair μ) | mass | segmentation | chosen-grasp success | failures |",
        "|---|---|---|---|---|---|",
    ]
    for c in conditions:
        ok, n = totals(table[c.name])
        mu = c.friction if c.friction is not None else base_friction
        reasons = collections.Counter()
        for cell in table[c.name].values():
            reasons.update(cell.failures)
        why = ", ".join(f"{k} {v}" for k, v in reasons.most_common()) or "none"
        seg = {"label": "label image", "color": "colour"}.get(c.segmentation or base_segmentation, "?")
        if c.noise_sigma is not None:
            seg += f" + noise σ {_number(c.noise_sigma)}"
        lines.append(f"| {c.label} | {_friction(mu)} ({pair_friction(mu):.3g}) | "
                     f"{'x' + _number(c.mass_scale) if c.mass_scale is not None else 'x1'} | {seg} | "
                     f"{format_rate(ok, n)} | {why} |")
    lines += ["", "## Per object (successes / trials; the grasps chosen)", "",
              "| object | " + " | ".join(c.label for c in conditions) + " |",
              "|---|" + "---|" * len(conditions)]
    for o in objects:
        cells = []
        for c in conditions:
            cell = table[c.name][o]
            chosen = ", ".join(f"{g} {k}" for g, k in cell.chosen.most_common())
            cells.append(f"{cell.successes}/{cell.trials} ({chosen})" if cell.trials else "-")
        lines.append(f"| {pathlib.Path(o).stem if '/' in o else o} | " + " | ".join(cells) + " |")
    results = claims(table, conditions, objects)
    lines += ["", "## The paper's claims across the sweep", "",
              "Only claims about the chosen grasps can be decided here (the all-grasps claims of Fig. 6 need "
              "every grasp run, Fig. 7 the planner). A verdict is the stated rule on the measured rate; "
              "'(unsure)' marks a verdict that the 95 % interval does not decide (it reaches the other side "
              "of the threshold): more trials could turn it.", "",
              "| claim | paper | rule | " + " | ".join(c.label for c in conditions) + " | across the sweep |",
              "|---|---|---|" + "---|" * len(conditions) + "---|"]
    for r in results:
        cells = []
        for c in conditions:
            v = r.per_condition[c.name]
            mark = " (unsure)" if v.certainty == "unsure" else ""
            cells.append(f"{v.verdict}{mark}: {v.ours}" if v.verdict != "n/a" else "n/a")
        lines.append(f"| {r.claim} | {r.paper} | {r.rule} | " + " | ".join(cells) + f" | {r.across(conditions)} |")
    holds = [r.claim for r in results if r.across(conditions) == "holds in every condition"]
    flips = [f"{r.claim} ({r.across(conditions)})" for r in results if r.across(conditions).startswith("flips")]
    lines += ["", f"Hold in every condition: {'; '.join(holds) or 'none'}.", "",
              f"Flip somewhere: {'; '.join(flips) or 'none'}.", ""]
    lines += ["Friction is the object's coefficient (`contact.friction`; each trial's seeded variation scales it, "
              f"as always); the hand and the table keep {HAND_FRICTION}, and Drake combines two coefficients as "
              "2·μ1·μ2/(μ1 + μ2): the pair coefficient is in parentheses."]
    if cpu_note:
        lines += ["", cpu_note]
    return lines


def write_conditions_csv(path: pathlib.Path, table: dict[str, dict[str, Cell]], conditions) -> None:
    """conditions.csv: one row per condition (successes, trials, rate and its 95 % Wilson interval)."""
    from drake_grasp.experiments.results import write_atomically

    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["condition", "factor", "label", "successes", "trials", "rate", "ci_lo", "ci_hi", "per_object"])
    for c in conditions:
        ok, n = totals(table[c.name])
        lo, hi = wilson_interval(ok, n)
        writer.writerow([c.name, c.factor, c.label, ok, n, f"{ok / n:.4f}" if n else "nan", f"{lo:.4f}", f"{hi:.4f}",
                         json.dumps({o: [cell.successes, cell.trials] for o, cell in table[c.name].items()})])
    write_atomically(path, buffer.getvalue())


def plot(table: dict[str, dict[str, Cell]], conditions, out_dir: pathlib.Path, title: str = "") -> list[pathlib.Path]:
    """Chosen-grasp success per condition with its 95 % Wilson interval; the paper's 95.6 % and the
    claim's threshold as lines. Writes sensitivity.png and .svg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from drake_grasp.experiments.results import save_figure

    colours = {"base": "black", "friction": "tab:blue", "mass": "tab:green", "perception": "tab:orange"}
    fig, ax = plt.subplots(figsize=(max(6.5, 0.9 * len(conditions) + 2.5), 4.0))
    paper = PAPER_CHOSEN_SUCCESS[0] / PAPER_CHOSEN_SUCCESS[1]
    ax.axhline(100 * paper, color="tab:red", linewidth=1, label=f"paper {100 * paper:.1f} %")
    ax.axhline(100 * (paper - CLAIM_MARGIN), color="tab:red", linewidth=0.8, linestyle="--",
               label=f"claim threshold {100 * (paper - CLAIM_MARGIN):.1f} %")
    for x, c in enumerate(conditions):
        ok, n = totals(table[c.name])
        if not n:
            continue
        lo, hi = wilson_interval(ok, n)
        rate = ok / n
        ax.errorbar([x], [100 * rate], yerr=[[100 * (rate - lo)], [100 * (hi - rate)]], fmt="o",
                    color=colours.get(c.factor, "gray"), capsize=4)
        ax.annotate(f"{ok}/{n}", (x, 100 * rate), textcoords="offset points", xytext=(6, -10), fontsize=7)
    ax.set_xticks(np.arange(len(conditions)))
    ax.set_xticklabels([c.label.replace(" + ", "\n+ ") for c in conditions], fontsize=7, rotation=30, ha="right")
    ax.set_ylim(-3, 105)
    ax.set_ylabel("chosen-grasp success (%)")
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=7, loc="lower left", frameon=False, title="bars: 95 % Wilson", title_fontsize=7)
    ax.set_title(title or "Sensitivity: the algorithm's chosen grasps, one factor changed at a time", fontsize=9)
    fig.tight_layout()
    paths = save_figure(fig, out_dir, "sensitivity", dpi=120)
    plt.close(fig)
    return paths


def cost_note(cost: dict, conditions: int, objects: int = 9, trials: int = 4) -> str:
    """The summary's cost line from cost.json's totals ({"trials", "cpu_seconds", "wall_seconds"})."""
    if not cost.get("trials"):
        return ""
    per_trial = cost["cpu_seconds"] / cost["trials"]
    full = objects * conditions * trials
    return (f"Cost: {per_trial:.1f} CPU-seconds per trial (workers and the parent process together, measured over "
            f"the {cost['trials']} trials these runs computed on local workers); the full sweep ({objects} objects x "
            f"{conditions} conditions x {trials} trials = {full} trials) needs about "
            f"{full * per_trial / 3600:.1f} core-hours.")


def _cpu_seconds() -> float:
    """CPU time of this process and of its finished (waited-for) children, s."""
    import resource

    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


# --- The run ----------------------------------------------------------------------------------------------


@dataclasses.dataclass
class SensitivityResult:
    table: dict  # condition name -> object -> Cell
    claims: list  # ClaimResult
    figures: list
    summary: pathlib.Path
    lines: list
    trials: int


def run_sensitivity(config: SensitivityConfig, out_dir: pathlib.Path, workers: int | None = None, executor=None,
                    progress=sys.stderr) -> SensitivityResult:
    """Runs (or resumes) the sweep into out_dir: conditions.yaml, sensitivity.csv (every trial, as it
    finishes), then conditions.csv, sensitivity.png/.svg and summary.md. Holds out_dir's lock meanwhile.
    Trials run on `executor` (`executors.make_executor`), or with none on a local executor of
    `workers` processes. Bad input (a scenario, an object, a results file of another version) is a
    one-line ValueError before any trial starts."""
    from drake_grasp.experiments.lock import results_lock
    from drake_grasp.experiments.results import check_results_file, write_atomically
    from drake_grasp.experiments.runner import TRIAL_FIELDS, fingerprints, run_trials, select
    from drake_grasp.objects import resolve_user_object
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    import time

    from drake_grasp.experiments.executors import LocalExecutor
    from drake_grasp.experiments.results import ResultsTable
    from drake_grasp.experiments.runner import TRIAL_KEY, TRIAL_TYPES, spec_key

    out_dir = pathlib.Path(out_dir)
    base = load_scenario(config.scenario_file or DEFAULT_SCENARIO_FILE, config.scenario_name)  # before any work
    for o in config.objects:
        resolve_user_object(o)
    out_dir.mkdir(parents=True, exist_ok=True)
    csv_path = out_dir / "sensitivity.csv"
    with results_lock(out_dir):
        check_results_file(csv_path, TRIAL_FIELDS)
        conditions_file = out_dir / "conditions.yaml"
        write_conditions(conditions_file, config)
        specs = trial_specs(config, str(conditions_file.resolve()))
        prints = fingerprints(specs)
        # What is already there (read quietly: run_trials reports a damaged line itself).
        have = ResultsTable(csv_path, TRIAL_FIELDS, TRIAL_KEY, TRIAL_TYPES, read_only=True,
                            report=io.StringIO()) if csv_path.is_file() else {}
        todo = sum(spec_key(s, f) not in have for s, f in zip(specs, prints))
        executor = executor or LocalExecutor(workers)
        cpu_start, wall_start = _cpu_seconds(), time.perf_counter()
        rows = run_trials(specs, csv_path, workers=workers, progress=progress, label="sensitivity",
                          executor=executor)
        cost_path = out_dir / "cost.json"
        cost = json.loads(cost_path.read_text()) if cost_path.is_file() else {}
        if todo and isinstance(executor, LocalExecutor):  # Ray's workers are not this process's children
            cost = {"trials": cost.get("trials", 0) + todo,
                    "cpu_seconds": cost.get("cpu_seconds", 0.0) + _cpu_seconds() - cpu_start,
                    "wall_seconds": cost.get("wall_seconds", 0.0) + time.perf_counter() - wall_start}
            write_atomically(cost_path, json.dumps(cost, indent=1) + "\n")
        rows_by_condition = {}
        for c in config.conditions:
            mine = [(s, f) for s, f in zip(specs, prints) if s.scenario_name == c.name]
            rows_by_condition[c.name] = select(rows, [s for s, _ in mine], [f for _, f in mine])
        table = tabulate(rows_by_condition, config.objects)
        lines = summary_lines(table, config, base.contact.friction, cost_note(cost, len(config.conditions)),
                              base.perception.segmentation.method)
        write_conditions_csv(out_dir / "conditions.csv", table, config.conditions)
        figures = plot(table, config.conditions, out_dir, title=(
            f"The algorithm's chosen grasps, one factor changed at a time: {len(config.objects)} objects x "
            f"{config.trials} trial{'s' if config.trials > 1 else ''} per condition"))
        summary = out_dir / "summary.md"
        write_atomically(summary, "# Sensitivity of the chosen grasps (friction, mass, perception)\n\n"
                         + "\n".join(lines) + "\n")
        return SensitivityResult(table, claims(table, config.conditions, config.objects), figures, summary, lines,
                                 len(rows))
