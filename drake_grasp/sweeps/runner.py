"""Runs many trials through an executor (local processes or Ray), writing each record as it finishes.

A trial is described by plain data (a `trial.TrialSpec`): the worker runs it through the trial
layer's one entry point (`trial.run`, which builds its own station and Diagram: Drake Diagrams and
Contexts do not pickle) and turns its record into a CSV row, a plain dict. Records go to a
resumable CSV (`results.ResultsTable`) keyed by (fingerprint, object, method, grasp, seed):
rerunning the same sweep after an interruption computes only the missing trials, and a rerun with
other inputs (scenario, object file, ...: `fingerprint.trial_fingerprint`) computes its own.

Trials that can share work run together as one task (`group_specs`): the camera-driven trials of
one object, seed and scenario that differ only in their grasp explore once (`trial.run_shared`).
A task's records are written together when it finishes, each whole: a killed run loses at most
the tasks in flight, and progress still counts trials.
"""

import contextlib
import dataclasses
import json
import pathlib
import sys
import time

from drake_grasp.sweeps.executors import Executor, LocalExecutor
from drake_grasp.sweeps.results import ResultsTable, json_finite
from drake_grasp.trial.spec import TrialSpec  # re-exported: `runner.TrialSpec` keeps working

__all__ = ["TRIAL_FIELDS", "TRIAL_KEY", "TRIAL_TYPES", "TrialSpec", "fingerprints", "group_specs", "run_group",
           "run_one", "run_trials", "select", "spec_key", "succeeded", "trial_table"]

TRIAL_FIELDS = [
    "fingerprint", "object", "method", "grasp", "seed", "success", "failure", "lift", "slip_distance", "slip_angle",
    "contacts_after_close", "contacts_at_end", "approach_stopped_on_contact", "estimate_source",
    "finger_angles", "breakaway", "breakaway_angles", "variation", "sim_time", "wall_time", "detail", "extra",
]
TRIAL_KEY = ["fingerprint", "object", "method", "grasp", "seed"]
TRIAL_TYPES = {
    "fingerprint": "hex", "seed": "int", "success": "bool", "lift": "float", "slip_distance": "float",
    "slip_angle": "float", "approach_stopped_on_contact": "bool", "finger_angles": "json", "breakaway": "json",
    "breakaway_angles": "json", "variation": "json", "sim_time": "float", "wall_time": "float", "extra": "json",
}


def succeeded(row: dict) -> bool:
    """Whether a trial row held, as written (True) or as read back from the CSV ("1" or "True")."""
    return str(row["success"]) in ("1", "True")


def trial_table(csv_path: pathlib.Path, read_only: bool = False) -> ResultsTable:
    """The results file of trials at csv_path."""
    return ResultsTable(csv_path, TRIAL_FIELDS, TRIAL_KEY, TRIAL_TYPES, read_only=read_only)


def fingerprints(specs: list["TrialSpec"]) -> list[str]:
    """Each spec's fingerprint (`fingerprint.trial_fingerprint`), reading each scenario and object
    file once."""
    from drake_grasp.sweeps.fingerprint import object_fingerprint, scenario_fingerprint, trial_fingerprint

    scenarios, objects = {}, {}
    out = []
    for s in specs:
        where = (s.scenario_file, s.scenario_name)
        if where not in scenarios:
            scenarios[where] = scenario_fingerprint(*where)
        which = (s.object, s.scale, s.largest_component, s.join_gap, s.inertia, s.package_path)
        if which not in objects:
            objects[which] = object_fingerprint(s.object, **s.object_options())
        out.append(trial_fingerprint(s, scenarios[where], objects[which]))
    return out


def spec_key(spec: "TrialSpec", fingerprint: str) -> tuple:
    """A spec's row key in a trial table."""
    return (fingerprint, spec.object, spec.method, spec.grasp, spec.seed)


def run_one(spec: TrialSpec, replay_html: str | None = None) -> dict:
    """Runs one trial in this process; returns its record as a dict of CSV-ready values. With
    `replay_html`, the trial also writes a Meshcat replay there (the record is the same)."""
    from drake_grasp.objects import pose_warnings_announced

    with pose_warnings_announced():
        return _run_one(spec, replay_html)


def _run_one(spec: TrialSpec, replay_html: str | None = None) -> dict:
    from drake_grasp import trial

    scenario, obj = trial.resolve(spec)
    record = trial.run(spec, replay_html, scenario=scenario, obj=obj)
    return _row(spec, record, _extra(spec, record, scenario, obj))


def run_group(specs: list[TrialSpec]) -> list[dict]:
    """Runs trials that share work (one group of `group_specs`) in this process; returns their
    records as `run_one` does, in order."""
    from drake_grasp.objects import pose_warnings_announced

    with pose_warnings_announced():
        from drake_grasp import trial

        scenario, obj = trial.resolve(specs[0])
        records = trial.run_shared(specs, scenario=scenario, obj=obj)
        return [_row(spec, record, _extra(spec, record, scenario, obj)) for spec, record in zip(specs, records)]


def group_specs(specs: list[TrialSpec], workers: int = 1) -> list[list[int]]:
    """The specs' indices grouped into tasks: camera-driven trials with one exploration
    (`trial.exploration_key`), one per grasp, together, in the order of their first spec; every
    other spec alone. While there are fewer tasks than `workers`, groups are split (a worker with
    nothing to do is slower than one exploring again)."""
    from drake_grasp.trial.entry import exploration_key

    groups, open_groups = [], {}
    for index, spec in enumerate(specs):
        key = exploration_key(spec)
        group = open_groups.get(key) if key is not None else None
        if group is None or any(specs[i].grasp == spec.grasp for i in group):
            group = []
            groups.append(group)
            if key is not None:
                open_groups[key] = group
        group.append(index)
    while len(groups) < workers and any(len(g) > 1 for g in groups):
        largest = max(range(len(groups)), key=lambda i: len(groups[i]))
        groups.insert(largest + 1, [groups[largest].pop()])
    return groups


def _extra(spec: TrialSpec, record, scenario, obj) -> dict:
    """The row's `extra` cell: what the method adds to the record's common fields."""
    if spec.method == "compliant":
        return {"resemblance": record.resemblances, "chosen": record.chosen_grasp,
                "margin": (record.estimate or {}).get("resemblance_margin"),
                "estimate_errors": record.estimate_errors, "scenario": spec.scenario_name,
                "segmentation": scenario.perception.segmentation.method,
                "exploration": (record.estimate or {}).get("exploration"), "grasp_search": record.grasp_search,
                "sensed": record.sensed, "attempts": record.attempts}
    if spec.method == "oracle":
        return {"truth_class": obj.closest_primitive}
    return dict(record.planned_grasp or {})  # eigengrasp: the planned grasp executed


def _row(spec: TrialSpec, record, extra: dict) -> dict:
    """A record as CSV-ready values; lists and dicts as JSON."""
    row = {k: v for k, v in dataclasses.asdict(record).items() if k in TRIAL_FIELDS}
    row["object"] = spec.object  # the name the sweep asked for (a path stays a path)
    row["grasp"] = spec.grasp  # the key asked for ("" for the algorithm's own choice: see extra.chosen)
    for key in ("finger_angles", "breakaway", "breakaway_angles", "variation"):
        row[key] = json.dumps(json_finite(row[key]))
    row["extra"] = json.dumps(json_finite(extra))
    return row


def run_trials(specs: list[TrialSpec], csv_path: pathlib.Path, workers: int | None = None,
               progress=sys.stderr, label: str = "trials", executor: Executor | None = None) -> list[dict]:
    """Runs the specs not yet in csv_path (resumable); returns the rows of the specs, as read back.

    Args:
        specs: the sweep's trials.
        csv_path: the results file; each record is appended as soon as its trial finishes.
        workers: with no `executor`, a local executor of this many processes (default: every core).
        progress: where a line per finished trial goes.
        label: the sweep's name in those lines.
        executor: where trials run (`executors.make_executor`); its results are the same wherever
            they run.
    """
    prints = fingerprints(specs)
    table = trial_table(csv_path)
    todo = [(s, f) for s, f in zip(specs, prints) if spec_key(s, f) not in table]
    total = len(specs)
    done = total - len(todo)
    if done:
        print(f"{label}: resuming, {done}/{total} trials already in {csv_path}", file=progress)
    executor = executor or LocalExecutor(workers)
    groups = group_specs([spec for spec, _ in todo], executor.slots())
    tasks = [([todo[i][0] for i in group],) for group in groups]
    start = time.perf_counter()
    with contextlib.closing(executor.imap_unordered(run_group, tasks)) as results:
        for index, rows in results:
            for i, row in zip(groups[index], rows):
                row["fingerprint"] = todo[i][1]
            table.append(rows)
            for row in rows:
                done += 1
                verdict = "ok" if row["success"] in (True, "1", 1) else row["failure"]
                print(f"{label}: {done}/{total} {row['object']} {row['method']}/{row['grasp']} seed {row['seed']}: "
                      f"{verdict} ({time.perf_counter() - start:.0f} s)", file=progress, flush=True)
    return select(table.rows(), specs, prints)


def select(rows: list[dict], specs: list["TrialSpec"], prints: list[str]) -> list[dict]:
    """The rows (as read back) of these specs with these fingerprints: what a report may use."""
    wanted = {tuple(str(v) for v in spec_key(s, f)) for s, f in zip(specs, prints)}
    return [r for r in rows if tuple(r[k] for k in TRIAL_KEY) in wanted]
