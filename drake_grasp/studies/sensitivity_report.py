"""The sensitivity sweep's analysis: per-condition cells and totals, the paper's claims, the report.

The sweep (`studies/sensitivity.py`) runs the algorithm's chosen grasps under one base condition
and one factor changed at a time, and records every trial in ``sensitivity.csv``. This module turns
those rows, grouped by condition, into results: per condition and object the successes, the grasps
chosen and the failure reasons (`tabulate`, `Cell`, `totals`); the paper's claims that chosen-grasp
trials can decide, judged per condition as holds or flips, marked unsure when the 95 % Wilson
interval does not decide them (`claims`, `Verdict`, `ClaimResult`); summary.md's text
(`summary_lines`, with the cost line `cost_note`), conditions.csv (`write_conditions_csv`) and the
figure (`plot`).

Kept apart from the sweep because it is a different concept (reading records, not making them) and
is pure apart from the files it writes: it imports nothing from the sweep, so the sweep can import
it. It reads a condition and the sweep's configuration by their attributes only.
"""

import collections
import csv
import dataclasses
import io
import json
import pathlib

from drake_grasp.sweeps.stats import format_rate, wilson_interval

PAPER_CHOSEN_SUCCESS = (86, 90)  # the paper's Fig. 6: 95.6 % for the grasps the algorithm chose
CLAIM_MARGIN = 0.10  # "within 10 points of the paper" (reproduce.fig6_claims' rule)
OBJECT_HOLDS = 0.70  # a chosen grasp "holds" an object at >= 70 % (reproduce's annulus rule)
# The sun-ray objects and the one grasp that works on each in the paper's Fig. 6 (the grasp of its shape).
SUN_RAY_GRASP = {"soccer_ball": "spherical", "game_box": "box", "bottle_case": "cylindrical"}
HAND_FRICTION = 0.5  # the hand's and the table's coefficient (models/*.sdf); for the pair coefficient


def number_label(value: float) -> str:
    """A number as conditions' names and labels write it (mass x2, noise 10)."""
    return f"{value:g}"


def friction_label(value: float) -> str:
    """A friction coefficient as names and labels write it, always with a decimal point (1.0)."""
    text = f"{value:g}"
    return text if "." in text or "e" in text else text + ".0"


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
    """(successes, trials) over the cells of one condition."""
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


def summary_lines(table: dict[str, dict[str, Cell]], config, base_friction: float,
                  cpu_note: str = "", base_segmentation: str = "label") -> list[str]:
    """summary.md's text (Markdown). `config` is the sweep's `sensitivity.SensitivityConfig` (read by
    its attributes: conditions, objects, trials, seed, scenario_file, scenario_name)."""
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
            seg += f" + noise σ {number_label(c.noise_sigma)}"
        lines.append(f"| {c.label} | {friction_label(mu)} ({pair_friction(mu):.3g}) | "
                     f"{'x' + number_label(c.mass_scale) if c.mass_scale is not None else 'x1'} | {seg} | "
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
    from drake_grasp.sweeps.results import write_atomically

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

    from drake_grasp.sweeps.results import save_figure

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
