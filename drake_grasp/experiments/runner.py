"""Runs many trials in a local process pool, writing each record as soon as it finishes.

A trial is described by plain data (a `TrialSpec`): the worker builds its own station and Diagram
(Drake Diagrams and Contexts do not pickle), runs it, and returns the record as a plain dict. Records
go to a resumable CSV (`results.ResultsTable`) keyed by (object, method, grasp, seed): rerunning the
same sweep after an interruption computes only the missing trials.
"""

import concurrent.futures
import dataclasses
import json
import math
import multiprocessing
import os
import pathlib
import sys
import time

from drake_grasp.experiments.results import ResultsTable

TRIAL_FIELDS = [
    "object", "method", "grasp", "seed", "success", "failure", "lift", "slip_distance", "slip_angle",
    "contacts_after_close", "contacts_at_end", "approach_stopped_on_contact", "estimate_source",
    "finger_angles", "breakaway", "breakaway_angles", "variation", "sim_time", "wall_time", "detail", "extra",
]
TRIAL_KEY = ["object", "method", "grasp", "seed"]


@dataclasses.dataclass(frozen=True)
class TrialSpec:
    """One trial as plain data.

    Attributes:
        object: catalogue name, primitive or mesh path.
        method: "oracle" (compliant grasp from ground truth), "compliant" (from the camera), or
            "eigengrasp" (a planned grasp, given in `planned`).
        grasp: "spherical" | "cylindrical" | "box" for compliant methods; a label for planned grasps.
        seed: the trial's seed (its variation; shared by every method).
        scenario_file, scenario_name: the station scenario.
        planned: for planned grasps: {"X_OH": 4x4 list, "joint_angles": 8 floats}.
    """

    object: str
    method: str
    grasp: str
    seed: int
    scenario_file: str = ""
    scenario_name: str = "default"
    planned: dict | None = None


def run_one(spec: TrialSpec) -> dict:
    """Runs one trial in this process; returns its record as a dict of CSV-ready values."""
    from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp, planned_grasp
    from drake_grasp.objects import resolve_object
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario
    from drake_grasp.trial import run_compliant_trial, run_trial

    scenario = load_scenario(spec.scenario_file or DEFAULT_SCENARIO_FILE, spec.scenario_name)
    obj = resolve_object(spec.object)
    if spec.method == "compliant":
        record = run_compliant_trial(scenario, obj, seed=spec.seed, grasp=spec.grasp)
        return _row(spec, record, {"resemblance": record.resemblances, "chosen": record.chosen_grasp,
                                   "estimate_errors": record.estimate_errors})
    if spec.method == "oracle":
        def plan(X_WO, object_spec):
            return plan_compliant_grasp(spec.grasp, oracle_estimate(X_WO, object_spec))

        extra = {"truth_class": obj.closest_primitive}
    elif spec.method == "eigengrasp":
        import numpy as np
        from pydrake.math import RigidTransform

        X_OH = RigidTransform(np.asarray(spec.planned["X_OH"], float))
        q = np.asarray(spec.planned["joint_angles"], float)

        def plan(X_WO, object_spec):
            return planned_grasp(X_OH, q, X_WO)

        extra = dict(spec.planned)
    else:
        raise ValueError(f"unknown method '{spec.method}'")
    record = run_trial(scenario, obj, plan, seed=spec.seed, method=spec.method, grasp=spec.grasp)
    return _row(spec, record, extra)


def _row(spec: TrialSpec, record, extra: dict) -> dict:
    """A record as CSV-ready values; lists and dicts as JSON."""
    row = {k: v for k, v in dataclasses.asdict(record).items() if k in TRIAL_FIELDS}
    row["object"] = spec.object  # the name the sweep asked for (a path stays a path)
    for key in ("finger_angles", "breakaway", "breakaway_angles", "variation"):
        row[key] = json.dumps(_finite(row[key]))
    row["extra"] = json.dumps(_finite(extra))
    return row


def _finite(value):
    """NaN and inf as None, so that the JSON cells are standard JSON."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def run_trials(specs: list[TrialSpec], csv_path: pathlib.Path, workers: int | None = None,
               progress=sys.stderr, label: str = "trials") -> ResultsTable:
    """Runs the specs not yet in csv_path (resumable), `workers` at a time; returns the table."""
    table = ResultsTable(csv_path, TRIAL_FIELDS, TRIAL_KEY)
    todo = [s for s in specs if (s.object, s.method, s.grasp, s.seed) not in table]
    total = len(specs)
    done = total - len(todo)
    if done:
        print(f"{label}: resuming, {done}/{total} trials already in {csv_path}", file=progress)
    workers = max(1, min(workers or os.cpu_count() or 1, len(todo) or 1))
    start = time.perf_counter()
    successes = 0

    def report(row: dict):
        nonlocal done, successes
        done += 1
        successes += row["success"] in (True, "1", 1)
        elapsed = time.perf_counter() - start
        verdict = "ok" if row["success"] in (True, "1", 1) else row["failure"]
        print(f"{label}: {done}/{total} {row['object']} {row['method']}/{row['grasp']} seed {row['seed']}: "
              f"{verdict} ({elapsed:.0f} s)", file=progress, flush=True)

    if workers == 1:
        for spec in todo:
            row = run_one(spec)
            table.append([row])
            report(row)
    else:
        context = multiprocessing.get_context("spawn")
        with concurrent.futures.ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
            futures = {pool.submit(run_one, spec): spec for spec in todo}
            for future in concurrent.futures.as_completed(futures):
                row = future.result()
                table.append([row])
                report(row)
    return table
