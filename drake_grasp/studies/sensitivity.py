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

This module is the sweep: the conditions (`Condition`, `default_conditions`, `SensitivityConfig`),
their scenarios and conditions.yaml, the trial specs, and `run_sensitivity`, the public entry. What
the records mean (cells, totals, the claims' verdicts, the summary, conditions.csv, the figure) is
`studies/sensitivity_report.py`, a separate concept that imports nothing from here.

The experiment:
    objects: the paper's nine (or --objects);
    grasps: the algorithm's own choice (camera-driven), under each condition (friction, mass,
        perception), one factor changed at a time;
    seeds: trial i of every object and condition uses seed + i, i < trials (default 4);
    writes: conditions.yaml, sensitivity.csv (one row per trial), conditions.csv, cost.json,
        sensitivity.png and sensitivity.svg, summary.md.
"""

import dataclasses
import io
import json
import math
import pathlib
import sys

from drake_grasp.studies.sensitivity_report import (
    claims, cost_note, friction_label, number_label, plot, summary_lines, tabulate, write_conditions_csv)

QUICK_OBJECTS = ("apple", "banana", "soccer_ball")  # the two that failed at friction 0.3, and a sun ray
DEFAULT_NOISE_SIGMA = 10.0  # 8-bit counts


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
    conditions += [Condition(f"friction_{friction_label(f)}", "friction", f"friction {friction_label(f)}",
                             friction=f) for f in frictions]
    conditions += [Condition(f"mass_x{number_label(m)}", "mass", f"mass x{number_label(m)}", mass_scale=m)
                   for m in mass_scales]
    conditions += [Condition("color", "perception", "colour segm.", segmentation="color"),
                   Condition(f"color_noise_{number_label(noise_sigma)}", "perception",
                             f"colour + noise {number_label(noise_sigma)}", segmentation="color",
                             noise_sigma=noise_sigma)]
    return tuple(conditions)



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

    header = ("# The sensitivity sweep's conditions (drake_grasp/studies/sensitivity.py), one named\n"
              "# scenario each, written from the base scenario; rewritten by every run of the sweep.\n")
    parts = [header]
    for c in conditions:
        parts.append(f"# {c.label}\n")
        parts.append(yaml_dump_typed(condition_scenario(base, c, color_segmentation), child_name=c.name))
    return "".join(parts)


def write_conditions(path: pathlib.Path, config: SensitivityConfig) -> None:
    """Writes conditions.yaml for `config` (base scenario, conditions) and checks that each condition
    loads back as a valid scenario (ValueError, one line, if not)."""
    from drake_grasp.sweeps.results import write_atomically
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
    from drake_grasp.sweeps.runner import TrialSpec

    return [TrialSpec(o, "compliant", "", config.seed + i, conditions_file, c.name)
            for i in range(config.trials) for c in config.conditions for o in config.objects]


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
    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.results import check_results_file, write_atomically
    from drake_grasp.sweeps.runner import TRIAL_FIELDS, fingerprints, run_trials, select
    from drake_grasp.objects import resolve_user_object
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    import time

    from drake_grasp.sweeps.executors import LocalExecutor
    from drake_grasp.sweeps.results import ResultsTable
    from drake_grasp.sweeps.runner import TRIAL_KEY, TRIAL_TYPES, spec_key

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
