"""Shape resemblance on near-primitives (issue 15, item 4): is an almost-sphere still a sphere?

For generated near-primitives (`drake_grasp.objects.near_primitives`: ellipsoids within 10 % of a
sphere, rounded boxes, tapered and rounded cylinders) and for perfect primitives, runs the wrist
camera's exploration exactly as `drake-grasp resemble` does (the default scenario's perception, the
object placed with the trial seed's variation, `perception.explore`), and records the three
resemblances, the chosen primitive (the highest resemblance) and the silhouette statistics the
resemblances are computed from (`scores.FeatureStatistics`: per arc, the regression's sums).

This module makes the records: the sets as tasks (`ensure_objects`, `near_tasks`, `perfect_tasks`,
`catalogue_tasks`), one exploration (`explore_one`, in a worker), the resumable results file
(`table`, `run`) and the whole study (`StudyConfig`, `run_study`: objects, explorations, then
summary.md). What the records mean (re-scoring, accuracy, confusion, the report and its figure) is
`near_primitives_report`; where the sphere score's tolerances come from is
`primitives/sphere_tolerances.py`.

The statistics do not depend on the scorer (the camera's motion never reads a resemblance), so a
record's fingerprint leaves the scorer out (`exploration_fingerprint`): a changed scorer re-scores
the recorded statistics (`near_primitives_report.rescore`) instead of simulating again, and the run's
own resemblances stay in the record with the scorer that made them
(`near_primitives_report.scorer_fingerprint`), so the report can show that re-scoring and running
agree.

Sets: ``near`` (the generated objects of one generator seed), ``perfect`` (Drake's exact sphere,
cube and cylinder, and the generator's own perfect meshes: no departure, tessellated and loaded like
the others) and ``catalogue`` (the paper's nine objects).

The experiment:
    objects: generated near-primitives (`count` per class, default 10, in a development set of
        generator seed `seed` and an evaluation set of `eval_seed`), perfect primitives and the
        paper's nine;
    grasps: none: the camera's exploration alone (the resemblances and the chosen primitive);
    seeds: trial seed 0 for the near-primitives; 0..reference_seeds-1 for the perfect primitives and
        the paper's objects;
    writes: objects-seed*/ and objects-perfect/, explorations.csv (one row per exploration),
        near_primitives.png, summary.md.
"""

from __future__ import annotations

import dataclasses
import json
import math
import pathlib
import sys
import time

import numpy as np

from drake_grasp.studies import near_primitives_report as analysis
from drake_grasp.sweeps.results import ResultsTable, json_finite

SETS = ("near", "perfect", "catalogue")
PERFECT_PRIMITIVES = {"sphere:0.09": "sphere", "cube:0.08": "box", "cylinder:0.065x0.18": "cylinder"}
"""Drake's exact shapes of sizes in the middle of the generator's ranges (argument -> primitive)."""

FIELDS = ["fingerprint", "set", "object", "class", "primitive", "seed", "found", "sphere", "cylinder", "box",
          "best", "scorer", "statistics", "evidence", "errors", "wall_time", "detail"]
KEY = ["fingerprint", "object", "seed"]
TYPES = {"fingerprint": "hex", "seed": "int", "found": "bool", "sphere": "float", "cylinder": "float",
         "box": "float", "scorer": "hex", "statistics": "json", "evidence": "json", "errors": "json",
         "wall_time": "float"}


def table(path: pathlib.Path, read_only: bool = False) -> ResultsTable:
    """The study's resumable results file."""
    return ResultsTable(path, FIELDS, KEY, TYPES, read_only=read_only)


@dataclasses.dataclass(frozen=True)
class Task:
    """One exploration as plain data (what a worker process gets).

    Attributes:
        object: a mesh path, a primitive (sphere:0.09) or a catalogue name.
        set: "near", "perfect" or "catalogue".
        shape_class: the generator's class (or "primitive", "catalogue").
        primitive: the primitive it should be classified as.
        seed: the trial seed (the object's placement variation, as `resemble --seed`).
        scenario_file, scenario_name: the station scenario ("" = the default file).
    """

    object: str
    set: str
    shape_class: str
    primitive: str
    seed: int
    scenario_file: str = ""
    scenario_name: str = "default"


# --- Fingerprints ------------------------------------------------------------------------------------


def _scenario(scenario_file: str, scenario_name: str):
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    return load_scenario(scenario_file or DEFAULT_SCENARIO_FILE, scenario_name)


def exploration_fingerprint(task: Task, scenario=None) -> str:
    """What decides an exploration's statistics: the resolved scenario with its perception but
    without the scorer's parameters (`perception.scores`: they only turn statistics into
    resemblances), the object's content and the package version."""
    import drake_grasp
    from drake_grasp.sweeps.fingerprint import digest, object_fingerprint, scenario_text

    scenario = scenario or _scenario(task.scenario_file, task.scenario_name)
    return digest("near_primitives", drake_grasp.BEHAVIOUR_VERSION, without_block(scenario_text(scenario), "scores"),
                  object_fingerprint(task.object))


def without_block(yaml_text: str, key: str) -> str:
    """YAML text without the mapping `key:` (the line and the lines indented under it)."""
    out, skip = [], None
    for line in yaml_text.splitlines(keepends=True):
        indent = len(line) - len(line.lstrip(" "))
        if skip is not None and (indent > skip or not line.strip()):
            continue
        skip = None
        if line.strip() == f"{key}:":
            skip = indent
            continue
        out.append(line)
    return "".join(out)


# --- One exploration (runs in a worker) --------------------------------------------------------------


def explore_one(task: Task) -> dict:
    """Runs one exploration as `drake-grasp resemble --object OBJECT --seed SEED` does, and returns its
    record (never raises: an error is recorded in `detail`)."""
    from drake_grasp.objects import pose_warnings_announced, resolve_object
    from drake_grasp.perception import comparison_record, explore, resemblance_statistics
    from drake_grasp.primitives import scores
    from drake_grasp.protocol import TrialVariation
    from drake_grasp.trial import apply_variation

    start = time.perf_counter()
    record = {"set": task.set, "object": task.object, "class": task.shape_class, "primitive": task.primitive,
              "seed": task.seed, "found": False, "sphere": math.nan, "cylinder": math.nan, "box": math.nan,
              "best": "", "statistics": [], "evidence": {}, "errors": {}, "detail": ""}
    try:
        scenario = _scenario(task.scenario_file, task.scenario_name)
        record["scorer"] = analysis.scorer_fingerprint(scenario)
        with pose_warnings_announced():
            spec = resolve_object(task.object)
        look_at = np.array([scenario.object.x, scenario.object.y, 0.0])
        scenario, spec = apply_variation(scenario, spec, TrialVariation.draw(task.seed, scenario.protocol))
        gathered = {}

        def keep_statistics(exploration, context):
            gathered["stats"] = resemblance_statistics(exploration, context)

        result = explore(scenario, None, spec, look_at=look_at, on_finish=keep_statistics)
        estimate = result.estimate
        record["found"] = estimate.found
        record["statistics"] = [float(x) for x in gathered["stats"].to_vector()]
        if estimate.found:
            record.update({s: float(estimate.resemblances[s]) for s in scores.SHAPES})
            record["best"] = estimate.best_shape
            record["evidence"] = estimate.evidence
            comparison = comparison_record(result, spec)
            errors = comparison.get("errors", {})
            record["errors"] = {k: errors.get(k) for k in ("centre", "depth", "axis_deg", "extents")}
            # A round mesh may roll a little while it is looked at (it is rendered as its 64-vertex hull).
            record["errors"]["object_moved"] = comparison["truth"]["object_moved"]
            R = result.X_WO_start.rotation().inverse() @ result.X_WO_end.rotation()
            record["errors"]["object_turned_deg"] = math.degrees(R.ToAngleAxis().angle())
        else:
            record["detail"] = estimate.status
    except Exception as error:  # noqa: BLE001 -- a study never stops for one object
        record["detail"] = f"{type(error).__name__}: {str(error).strip().splitlines()[0] if str(error).strip() else ''}"
        record.setdefault("scorer", "0")
    record["wall_time"] = time.perf_counter() - start
    return record


# --- The sets ----------------------------------------------------------------------------------------


def ensure_objects(directory: pathlib.Path, count: int, seed: int, perfect: bool = False) -> list[dict]:
    """The near-primitives of generator seed `seed`, indices 0..count-1 (and, with `perfect`, the
    generator's perfect meshes), in `directory`: generated once, reused on a rerun (the generator is
    deterministic). Files go through a private folder and are moved into place, the manifest last.
    Returns manifest rows, "file" as a path."""
    from drake_grasp.sweeps.results import ensure_generated
    from drake_grasp.objects import near_primitives as generator

    expected = count + (len(generator.PERFECT) if perfect else 0)
    return ensure_generated(directory, lambda staging: generator.generate(count, seed, staging, perfect=perfect),
                            expected, (seed, -1))  # the perfect meshes' seed is -1


def near_tasks(objects: list[dict], scenario_file: str = "", scenario_name: str = "default") -> list[Task]:
    """A task per generated object; object i of generator seed s is placed with trial seed 1000·s + i."""
    return [Task(o["file"], "near" if o["index"] >= 0 else "perfect", o["class"], o["primitive"],
                 1000 * max(o["seed"], 0) + max(o["index"], 0), scenario_file, scenario_name) for o in objects]


def perfect_tasks(perfect_meshes: list[dict], seeds: int = 1, scenario_file: str = "",
                  scenario_name: str = "default") -> list[Task]:
    """Drake's exact sphere, cube and cylinder (`PERFECT_PRIMITIVES`) and the generator's perfect
    meshes, each with trial seeds 0..seeds-1."""
    objects = [(name, "primitive", primitive) for name, primitive in PERFECT_PRIMITIVES.items()]
    objects += [(o["file"], o["class"], o["primitive"]) for o in perfect_meshes]
    return [Task(obj, "perfect", c, p, seed, scenario_file, scenario_name) for seed in range(seeds)
            for obj, c, p in objects]


def catalogue_tasks(seeds: int = 1, scenario_file: str = "", scenario_name: str = "default") -> list[Task]:
    """The paper's nine objects, each with trial seeds 0..seeds-1 (as `drake-grasp resemble --object
    NAME --seed K`)."""
    from drake_grasp.objects.catalogue import PAPER_OBJECTS, paper_object

    return [Task(name, "catalogue", "catalogue", paper_object(name).closest_primitive, seed, scenario_file,
                 scenario_name) for seed in range(seeds) for name in PAPER_OBJECTS]


# --- Running -----------------------------------------------------------------------------------------


def run(tasks: list[Task], csv_path: pathlib.Path, executor=None, progress=sys.stderr,
        label: str = "near-primitives", counts: dict | None = None) -> list[dict]:
    """Runs the tasks whose records are not yet in csv_path (resumable: each record is appended as it
    arrives); returns the tasks' records, as read back, in task order. With `counts`, adds how many
    it computed to counts["computed"]."""
    from drake_grasp.sweeps.executors import LocalExecutor

    scenarios = {}
    prints = []
    for task in tasks:
        where = (task.scenario_file, task.scenario_name)
        if where not in scenarios:
            scenarios[where] = _scenario(*where)
        prints.append(exploration_fingerprint(task, scenarios[where]))
    results = table(csv_path)
    todo = [(t, f) for t, f in zip(tasks, prints) if (f, t.object, t.seed) not in results]
    done, total = len(tasks) - len(todo), len(tasks)
    if done:
        print(f"{label}: resuming, {done}/{total} explorations already in {csv_path}", file=progress, flush=True)
    executor = executor or LocalExecutor(1)
    start = time.perf_counter()
    import contextlib

    with contextlib.closing(executor.imap_unordered(explore_one, [(t,) for t, _ in todo])) as stream:
        for index, record in stream:
            task, fingerprint = todo[index]
            record["fingerprint"] = fingerprint
            results.append([_csv_ready(record)])
            done += 1
            print(f"{label}: {done}/{total} {analysis.short_name(task.object)} ({task.primitive}): "
                  + _verdict(record) + f" ({time.perf_counter() - start:.0f} s)", file=progress, flush=True)
    by_key = {(r["fingerprint"], r["object"], r["seed"]): r for r in results.rows()}
    if counts is not None:
        counts["computed"] = counts.get("computed", 0) + len(todo)
    return [by_key[(f, t.object, str(t.seed))] for t, f in zip(tasks, prints) if (f, t.object, str(t.seed)) in by_key]


def _csv_ready(record: dict) -> dict:
    row = dict(record)
    for key in ("statistics", "evidence", "errors"):
        row[key] = json.dumps(json_finite(row[key]))
    return row


def _verdict(record: dict) -> str:
    if record.get("detail"):
        return f"no estimate ({record['detail']})"
    scores_text = " ".join(f"{s} {float(record[s]):.2f}" for s in ("sphere", "cylinder", "box"))
    mark = "right" if record["best"] == record["primitive"] else "WRONG"
    return f"{record['best']} ({scores_text}) {mark}"


# --- The whole study ---------------------------------------------------------------------------------


@dataclasses.dataclass
class StudyConfig:
    """Attributes:
        count: near-primitives per class in each of the two sets.
        seed: the development set's generator seed; eval_seed: the evaluation set's (must differ).
        reference_seeds: trial seeds 0..N-1 for the perfect primitives and the paper's objects.
        catalogue: include the paper's nine objects.
        development_only: leave out the evaluation set (while a scorer is being developed).
    """

    count: int = 10
    seed: int = 0
    eval_seed: int = 1
    reference_seeds: int = 3
    catalogue: bool = True
    development_only: bool = False

    def validate(self) -> None:
        """ValueError (one line) for a bad configuration."""
        if self.count < 1:
            raise ValueError(f"--count must be >= 1, got {self.count}")
        if self.seed < 0 or self.eval_seed < 0:
            raise ValueError("--seed and --eval-seed must be >= 0")
        if self.seed == self.eval_seed:
            raise ValueError(f"the evaluation seed must differ from the development seed ({self.seed}): the "
                             "evaluation set must be new objects")
        if self.reference_seeds < 1:
            raise ValueError(f"--reference-seeds must be >= 1, got {self.reference_seeds}")

    def command(self) -> str:
        return (f"scripts/near_primitives_check.py --count {self.count} --seed {self.seed} --eval-seed "
                f"{self.eval_seed} --reference-seeds {self.reference_seeds}"
                + ("" if self.catalogue else " --skip-catalogue")
                + (" --development-only" if self.development_only else ""))


FIGURE = "near_primitives.png"


def run_study(config: StudyConfig, out_dir: pathlib.Path, executor, progress=sys.stderr,
              label: str = "near-primitives", command: str | None = None) -> str:
    """Runs (or resumes) the study into out_dir (objects, explorations.csv) under its lock and writes
    out_dir/summary.md with its figure out_dir/near_primitives.png; returns the summary's text.

    Raises:
        ValueError: a bad configuration; ResultsFileError, LockHeld: an unusable results folder (one
            line each, before any work).
    """
    import os

    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.results import check_results_file, write_atomically

    config.validate()
    csv_path = out_dir / "explorations.csv"
    check_results_file(csv_path, FIELDS)
    out_dir.mkdir(parents=True, exist_ok=True)
    start, times = time.perf_counter(), os.times()
    cpu_start = times.user + times.system + times.children_user + times.children_system
    counts = {"computed": 0}
    with results_lock(out_dir):
        dev = ensure_objects(out_dir / f"objects-seed{config.seed}", 4 * config.count, config.seed)
        ev = [] if config.development_only else ensure_objects(
            out_dir / f"objects-seed{config.eval_seed}", 4 * config.count, config.eval_seed)
        perfect = ensure_objects(out_dir / "objects-perfect", 0, 0, perfect=True)
        groups = {
            "perfect": perfect_tasks(perfect, config.reference_seeds),
            "catalogue": catalogue_tasks(config.reference_seeds) if config.catalogue else [],
            "development": near_tasks(dev),
            "evaluation": near_tasks(ev),
        }
        records = {name: run(tasks, csv_path, executor=executor, progress=progress, label=f"{label} {name}",
                             counts=counts)
                   for name, tasks in groups.items() if tasks}
        times = os.times()
        cpu = times.user + times.system + times.children_user + times.children_system - cpu_start
        text = analysis.report(records, command=command or config.command(),
                               seeds=(config.seed, config.eval_seed), count=config.count, figure=out_dir / FIGURE,
                               wall=time.perf_counter() - start, cpu=cpu, workers=getattr(executor, "workers", 1),
                               computed=counts["computed"], baseline=analysis.main_scorer,
                               scorer_note=analysis.SCORER_NOTE)
        write_atomically(out_dir / "summary.md", text)
    return text
