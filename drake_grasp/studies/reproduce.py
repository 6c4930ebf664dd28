"""The whole paper in one command: Fig. 4, Fig. 6 and Fig. 7, a report of claim against result, and
beyond the paper, both methods on novel objects.

`run` runs (or resumes) the three experiments into one output folder and writes ``report.md``: for each
claim of the paper, the paper's number or statement, ours, and whether ours agrees. The verdicts are
computed from the measured results with the rules stated beside each claim; nothing is tuned to agree.
The same text is also written as ``report.html``, the results page (`report_page`): figures inline, and
one Meshcat replay per object and method (`replays`), all of it openable offline in a browser.

The experiment:
    objects, grasps and seeds: Fig. 4's, Fig. 6's and Fig. 7's (the paper's), then the novel-object
        study's (--quick: fewer of each);
    writes: fig4/, fig6/, fig7/ and novel/ (each study's own files), replays/ (one Meshcat replay
        per object and method), report.md and report.html.
"""

import dataclasses
import json
import pathlib
import re
import time

import numpy as np

from drake_grasp.studies import fig4, fig4_flower, fig6, fig7, novel
from drake_grasp.station import PAPER_SCENARIO_NAME
from drake_grasp.studies.replays import ensure_replays
from drake_grasp.studies.report_page import write_report_html
from drake_grasp.sweeps.results import write_atomically
from drake_grasp.sweeps.stats import format_rate, short_rate

# Written by scripts/bench_scaling.py; quoted in the report when present.
SCALING_FILE = pathlib.Path(__file__).resolve().parents[2] / "docs" / "results" / "scaling.json"
ANNULUS = ("banana", "apple", "bell_pepper", "sponge", "spectacle_case", "toy_bridge")


@dataclasses.dataclass
class Claim:
    claim: str
    paper: str
    ours: str
    agrees: str  # "yes", "no", "partly", "n/a"
    rule: str


def fig4_claims(summaries: dict) -> list[Claim]:
    claims = []
    for shape in ("sphere", "cylinder"):
        s = summaries.get(shape)
        if s is None:
            continue
        both = (s.mean("x") + s.mean("y")) / 2
        peak = int(np.argmax(both))
        interior = 0 < peak < len(both) - 1
        falls = both[-1] < 0.1 * both[peak]
        claims.append(Claim(
            f"Fig. 4 ({shape}s): success peaks at medium sizes (the annulus) and declines past it",
            "peak at medium sizes, decline for larger ones",
            f"eps_mean peaks at {s.sizes[peak] * 100:.1f} cm ({both[peak]:.3f}); at {s.sizes[-1] * 100:.0f} cm "
            f"{both[-1]:.3f}",
            "yes" if interior and falls else "no",
            "peak not at the smallest or largest size, and eps_mean at the largest size < 10 % of the peak"))
    cube = summaries.get("cube")
    if cube is not None:
        both = (cube.mean("x") + cube.mean("y")) / 2
        peak = int(np.argmax(both))
        drop = [j for j in range(peak + 1, len(both)) if both[j] < 0.1 * both[peak]]
        claims.append(Claim(
            "Fig. 4 (cubes): a sudden drop for large cubes", "sudden drop (only two fingers touch)",
            (f"eps_mean falls from {both[peak]:.3f} at {cube.sizes[peak] * 100:.1f} cm to below 10 % of it at "
             f"{cube.sizes[drop[0]] * 100:.1f} cm (open proximal links land flat on the top face)")
            if drop else "no drop",
            "partly" if drop else "no",
            "a size past the peak with eps_mean < 10 % of the peak; the paper's cause (two fingers) differs"))
    return claims


def fig6_claims(stats: dict) -> list[Claim]:
    claims = []
    ok = n = 0
    for per_grasp in stats.values():
        choice = fig6.chosen_grasp(per_grasp)
        if choice:
            ok += per_grasp[choice].successes
            n += per_grasp[choice].trials
    if n:
        rate = ok / n
        claims.append(Claim("Fig. 6: the chosen grasps succeed", format_rate(86, 90), format_rate(ok, n),
                            "yes" if abs(rate - 86 / 90) <= 0.10 else "no", "within 10 points of the paper"))
    annulus = [o for o in ANNULUS if o in stats]
    if annulus:
        low, lowest = min((s.rate, (s.successes, s.trials)) for o in annulus for s in stats[o].values() if s.trials)
        claims.append(Claim("Fig. 6: in the annulus all three grasps do about equally well",
                            "all grasps high in the annulus",
                            "lowest success of any grasp on an annulus object: " + short_rate(*lowest),
                            "yes" if low >= 0.7 else "no", "every grasp on every annulus object >= 70 %"))
    ball = stats.get("soccer_ball")
    if ball:
        rates = {g: s.rate for g, s in ball.items()}
        only = rates["spherical"] >= 0.8 and max(rates["cylindrical"], rates["box"]) <= 0.2
        claims.append(Claim("Fig. 6: on the soccer ball only the spherical grasp works", "only spherical",
                            ", ".join(f"{g} {short_rate(s.successes, s.trials)}" for g, s in ball.items()),
                            "yes" if only else ("partly" if rates["spherical"] >= 0.8 else "no"),
                            "spherical >= 80 % and the others <= 20 %"))
    rays = [o for o in ("soccer_ball", "game_box", "bottle_case") if o in stats]
    for o in rays:
        rates = sorted((s.rate for s in stats[o].values()), reverse=True)
        clear = rates[0] - rates[-1] >= 0.5
        claims.append(Claim(f"Fig. 6: on the {o} (a sun ray) one grasp is clearly better", "one grasp clearly best",
                            ", ".join(f"{g} {short_rate(s.successes, s.trials)}" for g, s in stats[o].items()),
                            "yes" if clear else "no", "best minus worst grasp >= 50 points"))
    return claims


def fig7_claims(comparison: list) -> list[Claim]:
    claims = []
    by = {c.object: c for c in comparison}
    for o in ("bottle_case", "soccer_ball"):
        if o in by:
            c = by[o]
            claims.append(Claim(f"Fig. 7: the planner fails every attempt on the {o}", "0 %",
                                f"planner average {short_rate(*c.eigengrasp_counts)}, best {short_rate(*c.best_counts)}",
                                "yes" if c.eigengrasp_average == 0 else "no", "planner average = 0"))
    if "game_box" in by:
        c = by["game_box"]
        claims.append(Claim("Fig. 7: game box 100 % for both methods", "100 % / 100 %",
                            f"compliance-centric {short_rate(*c.compliant_counts)}, planner best "
                            f"{short_rate(*c.best_counts)}",
                            "yes" if c.compliant >= 0.9 and c.eigengrasp_best >= 0.9 else "no", "both >= 90 %"))
    for o in ("sponge", "toy_bridge", "spectacle_case"):
        if o in by:
            c = by[o]
            equal = abs(c.compliant - c.eigengrasp_best) <= 0.2
            paper = "not equal" if o == "spectacle_case" else "equal"
            agrees = (not equal) if o == "spectacle_case" else equal
            claims.append(Claim(f"Fig. 7: annulus object {o}: the two methods are {paper}", paper,
                                f"compliance-centric {short_rate(*c.compliant_counts)}, planner best "
                                f"{short_rate(*c.best_counts)}",
                                "yes" if agrees else "no", "equal = within 20 points (planner's best grasp)"))
    return claims


def scaling_lines(path: pathlib.Path = SCALING_FILE) -> list[str]:
    """The report's "Scaling" section: the measured benchmark (scripts/bench_scaling.py) if its JSON
    file exists, else how to measure it."""
    how = ("`.venv/bin/python scripts/bench_scaling.py` runs the same trials with 1 and 2 local workers and "
           "with Ray, and writes docs/results/scaling.md and scaling.json.")
    lines = ["## Scaling", ""]
    if not path.exists():
        return lines + [f"Not measured yet: {how}", ""]
    try:
        data = json.loads(path.read_text())
        base = data["runs"][0]["trials_per_second"]
        rows = [f"| {r['executor']} | {r['workers']} | {r['trials_per_second']:.3f} | "
                f"{r['trials_per_second'] / base:.2f}x |" for r in data["runs"]]
        load = ", ".join(f"{v:.2f}" for v in data["load_average_before"])
        lines += [f"Measured by scripts/bench_scaling.py on {data['date']} ({data['machine']}; load average "
                  f"{load} before the run): {data['workload']}. Start-up (worker processes, a local Ray "
                  "instance) is included.", "",
                  "| executor | workers | trials/s | speedup |", "|---|---|---|---|", *rows, "",
                  f"Records identical across executors: {'yes' if data['identical_records'] else 'NO'}. "
                  f"To measure again: {how}", ""]
    except (ValueError, KeyError, IndexError, TypeError, ZeroDivisionError) as e:
        lines += [f"{path} could not be read ({type(e).__name__}: {e}). {how}", ""]
    return lines


# The studies beyond the paper a report includes when their results are in its folder: (subfolder,
# title, the command that makes them there).
STUDIES = (
    ("capture", "capture regions and ε against physics", "drake-grasp capture --out {out}/capture"),
    ("sensitivity", "sensitivity of the chosen grasps", "drake-grasp sensitivity --out {out}/sensitivity"),
    ("near_primitives", "shape resemblance on near-primitives",
     "drake-grasp near-primitives --out {out}/near_primitives"),
    ("exploration", "the paper's proposed minimal exploration", "drake-grasp exploration --out {out}/exploration"),
)


def study_sections(out_dir: pathlib.Path) -> list[str]:
    """The report's sections for the studies beyond the paper whose summary.md is in `out_dir` (their
    headings one level down, their relative links rebased onto the report's folder), and a line on
    how to add the missing ones."""
    lines, missing = [], []
    for folder, title, command in STUDIES:
        summary = out_dir / folder / "summary.md"
        if not summary.is_file():
            missing.append(f"`{command.format(out=out_dir)}` ({title})")
            continue
        text = summary.read_text()
        # Links relative to the study's folder become relative to the report's.
        text = re.sub(r"\]\((?![a-z]+:|/|#)([^)]+)\)", lambda m: f"]({folder}/{m.group(1)})", text)
        body = text.splitlines()
        if body and body[0].startswith("# "):
            body = body[1:]  # the study's own title: this section has one
        # Its headings one level down, under this section's.
        body = [("#" + line) if line.startswith("#") else line for line in body]
        lines += [f"## Beyond the paper: {title}", "", f"From [{folder}/summary.md]({folder}/summary.md).",
                  *body, ""]
    if missing:
        lines += ["Further studies add their sections here when run into this folder: " + "; ".join(missing) + ".", ""]
    return lines


def write_report(path: pathlib.Path, claims: list[Claim], wall_time: float, quick: bool, energy: str,
                 figures: list[pathlib.Path], resumed: dict | None = None, executor: str = "local",
                 scaling_file: pathlib.Path = SCALING_FILE, novel_lines: list[str] | None = None,
                 flower_lines: list[str] | None = None) -> None:
    agree = sum(c.agrees == "yes" for c in claims)
    reuse = ""
    if resumed:
        reuse = " Results already on disk and reused: " + ", ".join(f"{k} {v}" for k, v in resumed.items()) + "."
    lines = [
        "# drake-grasp: the paper's claims against this reproduction",
        "",
        f"Run: {'quick' if quick else 'full'}; wall time {wall_time:.0f} s; executor: {executor}; Fig. 7 planner "
        f"energy: {energy}. {agree} of {len(claims)} claims agree.{reuse}",
        "",
        "Every experiment here runs the paper's algorithm: its visual primitives' silhouette estimate (scenario "
        f"`{PAPER_SCENARIO_NAME}`), the novel objects included. A single `drake-grasp trial` on an object file "
        "uses the best estimate the project has, the table-top one (docs/trials.md).",
        "",
        "| claim | paper | ours | agrees | rule |",
        "|---|---|---|---|---|",
    ]
    lines += [f"| {c.claim} | {c.paper} | {c.ours} | {c.agrees} | {c.rule} |" for c in claims]
    lines += ["", "Figures: " + ", ".join(f"[{p.name}]({p.parent.name}/{p.name})" for p in figures), ""]
    if quick:
        lines += ["A quick run uses few sizes, objects and trials: its verdicts are indicative only.", ""]
    if flower_lines:
        lines += ["## Beyond the paper: the flower", "",
                  "The paper's Fig. 4 names small and flat objects as a region its three grasps cannot reach. "
                  "Fig. 4's flower family: first plates on a table under the precision grasp that the flower "
                  "grasp replaced (palm held by position), quasi-static, the same pose errors (docs/design.md "
                  "§5.4b); then the flower grasp (fingertips landed on the table by a compliant arm, §5.4f) on "
                  "plates, sticks and cubes in full dynamics, one trial per point ([fig4_flower.png]"
                  "(fig4/fig4_flower.png)):", "", *[f"- {line}" for line in flower_lines],
                  "", "The same objects in full dynamics, camera-driven: `scripts/flower_check.py` "
                  "(docs/results/flower.md).", ""]
    if novel_lines:
        lines += ["## Beyond the paper: novel objects", "",
                  "Both methods on generated objects neither has seen (`drake-grasp novel`; details in "
                  "[novel/summary.md](novel/summary.md)), through the runner, seeds and success test of Fig. 6 "
                  "and Fig. 7.", "", *novel_lines, ""]
    lines += study_sections(path.parent)
    lines += scaling_lines(scaling_file)
    write_atomically(path, "\n".join(lines))


def run(out_dir: pathlib.Path, quick: bool, workers: int | None = None, seed: int = 0,
        energy: str = "contact-quality", executor=None) -> tuple[pathlib.Path, list[Claim], float]:
    """Runs (or resumes) Fig. 4, 6 and 7 under out_dir and writes out_dir/report.md. Everything runs on
    `executor` (`executors.make_executor`), or with none on a local executor of `workers` processes."""
    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.results import check_results_file
    from drake_grasp.sweeps.runner import TRIAL_FIELDS

    with results_lock(out_dir):
        # Every results file this run will use, checked before the first sweep starts.
        check_results_file(out_dir / "fig4" / "fig4.csv", fig4.FIELDS)
        for path in ("fig4/fig4_flower.csv", "fig6/fig6.csv", "fig7/fig7.csv", "fig7/fig7_compliant.csv"):
            check_results_file(out_dir / path, TRIAL_FIELDS)
        return _run(out_dir, quick, workers, seed, energy, executor)


def _run(out_dir, quick, workers, seed, energy, executor):
    from drake_grasp.sweeps.executors import LocalExecutor
    from drake_grasp.objects import PAPER_OBJECTS

    executor = executor or LocalExecutor(workers)
    start = time.perf_counter()
    resumed = {name: _rows_on_disk(out_dir / name / f"{name}.csv") for name in ("fig4", "fig6", "fig7")}
    config4 = fig4.Fig4Config.quick() if quick else fig4.Fig4Config.full()
    rows4 = fig4.run_fig4(config4, out_dir / "fig4", executor=executor)
    summaries4 = fig4.summarise(rows4)
    figures = list(fig4.plot(summaries4, out_dir / "fig4"))
    flower_config = fig4_flower.FlowerConfig.quick() if quick else fig4_flower.FlowerConfig.full()
    flower_results = fig4_flower.run_flower(flower_config, out_dir / "fig4", executor=executor)
    flower_maps = fig4_flower.summarise(flower_results)
    figures += fig4_flower.plot(flower_maps, out_dir / "fig4")
    trials = 2 if quick else 10
    config6 = fig6.Fig6Config(objects=fig6.QUICK_OBJECTS if quick else PAPER_OBJECTS, trials=trials, seed=seed)
    stats6, f6, _, _ = fig6.run_sweep(config6, out_dir / "fig6", executor=executor)
    figures += f6
    config7 = fig7.Fig7Config(objects=fig7.QUICK_OBJECTS if quick else fig7.OBJECTS, trials=trials, seed=seed,
                              energy=energy)
    comparison, f7, _ = fig7.run_comparison(config7, out_dir / "fig7", out_dir / "fig6", executor=executor)
    figures += f7
    claims = fig4_claims(summaries4) + fig6_claims(stats6) + fig7_claims(comparison)
    # Beyond the paper: one novel object of each class in the full run (2 trials per grasp), three in
    # the quick one; `drake-grasp novel --count N --trials K` runs a larger study on its own.
    novel_config = novel.NovelConfig.quick(seed=seed, energy=energy) if quick else novel.NovelConfig(
        count=7, trials=2, seed=seed, energy=energy)
    novel_objects = novel.ensure_objects(out_dir / "novel" / "objects", novel_config.count, novel_config.object_seed)
    # The paper's algorithm (its silhouettes), as in the paper's figures, not the best estimate.
    _, novel_figures, novel_lines = novel.run_study(novel_config, out_dir / "novel", novel_objects, executor,
                                                    scenario_name=PAPER_SCENARIO_NAME)
    figures += novel_figures
    wall = time.perf_counter() - start
    report = out_dir / "report.md"
    write_report(report, claims, wall, quick, energy, figures, {k: f"{v} rows" for k, v in resumed.items() if v},
                 executor.describe(), novel_lines=novel_lines,
                 flower_lines=([fig4.flower_line(summaries4[fig4.FLOWER])] if fig4.FLOWER in summaries4 else [])
                 + fig4_flower.summary_lines(flower_maps, flower_results))
    replays = ensure_replays(out_dir / "replays", replay_specs(config6, config7, out_dir / "fig7", executor),
                             executor)
    write_report_html(out_dir / "report.html", report.read_text(), replays)
    return report, claims, wall


def replay_specs(config6, config7, fig7_dir: pathlib.Path, executor) -> list:
    """One trial per object and method for the results page (the first trial's seed): the
    compliance-centric algorithm's own choice on each Fig. 6 object, the planner's best reachable
    grasp on each Fig. 7 object."""
    from drake_grasp.sweeps.runner import TrialSpec

    specs = [TrialSpec(obj, "compliant", "", config6.seed) for obj in config6.objects]
    plans = fig7.ensure_plans(fig7_dir, config7, executor)  # read back: planned by the comparison
    first = {}
    for spec in fig7.eigengrasp_specs(plans, config7):
        first.setdefault(spec.object, spec)
    return specs + list(first.values())


def _rows_on_disk(csv_path: pathlib.Path) -> int:
    """Rows a results file already holds (of any fingerprint: a figure uses those of its inputs)."""
    if not csv_path.is_file():
        return 0
    with open(csv_path, "rb") as f:
        return max(0, sum(1 for _ in f) - 1)
