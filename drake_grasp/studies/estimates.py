"""How right is the camera's estimate? The silhouettes' and the table-top estimate, on every shape class.

One exploration gives both: with the `table_top` scenario the depth views ride along an exploration
that is otherwise the default one, and the estimate keeps the silhouettes' own centre, axes and
extents beside the table-top ones (`ObjectEstimate.table_top["silhouettes"]`). Each is compared
with the object's true pose and size (`perception.evaluation.compare`) when the exploration ends.

The experiment:
    objects: generated novel objects (`objects.novel`: blobs, unions, plates, L, T, rings, handles;
        COUNT of generator seed SEED), near-primitives (`objects.near_primitives`: ellipsoids, rounded
        boxes, tapered and rounded cylinders; NEAR per class of generator seed SEED) and the paper's
        nine objects.
    grasps: none (explorations only).
    seeds: object k of a set is placed with trial seed k's variation (the paper's nine: seed 0).
    writes: OUT/estimates.csv (one record per exploration, appended as it finishes; a rerun resumes)
        and OUT/summary.md: per class, the share of objects within 1 cm of the centre and 10° of the
        axis for each estimate, median and 95th-percentile errors, and how often the true error lay
        within twice the reported uncertainty.
"""

import dataclasses
import json
import pathlib
import sys
import time

import numpy as np

from drake_grasp.sweeps.results import ResultsTable, json_finite

SCENARIO = "table_top"
FIELDS = ["fingerprint", "set", "object", "class", "seed", "found", "best", "silhouettes", "table_top",
          "uncertainty", "wall_time", "detail"]
KEY = ["fingerprint", "object", "seed"]
TYPES = {"fingerprint": "hex", "seed": "int", "found": "bool", "silhouettes": "json", "table_top": "json",
         "uncertainty": "json", "wall_time": "float"}
CENTRE_TOL = 0.01  # m, the target
AXIS_TOL_DEG = 10.0


@dataclasses.dataclass(frozen=True)
class Task:
    """One exploration: an object (catalogue name or mesh file), its set and class, a trial seed."""

    object: str
    set: str
    shape_class: str
    seed: int


def table(path: pathlib.Path, read_only: bool = False) -> ResultsTable:
    return ResultsTable(path, FIELDS, KEY, TYPES, read_only=read_only)


def fingerprint(task: Task, scenario) -> str:
    """What decides the record: the resolved scenario, the object's content and the package version."""
    import drake_grasp
    from drake_grasp.sweeps.fingerprint import digest, object_fingerprint, scenario_text

    return digest("estimates", drake_grasp.BEHAVIOUR_VERSION, scenario_text(scenario), object_fingerprint(task.object))


def errors_record(estimate, truth) -> dict:
    """An estimate's errors against the truth, as plain data (centre m, axis degrees, relative extents)."""
    from drake_grasp.perception.evaluation import compare

    e = compare(estimate, truth)
    return {"centre": e.centre, "centre_xyz": [float(x) for x in np.asarray(estimate.centre) - truth.centre],
            "axis_deg": e.axis_deg, "extents": [float(x) for x in e.extents]}


def silhouettes_estimate(estimate):
    """The estimate the silhouettes alone gave (the table-top one replaced its centre, axes, extents)."""
    own = estimate.table_top["silhouettes"]
    centre = np.asarray(own["centre"], float)
    return dataclasses.replace(
        estimate, centre=centre, depth=float(np.linalg.norm(centre - estimate.camera_position)),
        axes=np.asarray(own["axes"], float), extents=np.asarray(own["extents"], float),
        principal_axis=None if own["principal_axis"] is None else np.asarray(own["principal_axis"], float),
        table_top=None)


def explore_one(task: Task) -> dict:
    """One exploration of the `table_top` scenario and both estimates' errors (never raises)."""
    from drake_grasp.objects import pose_warnings_announced, resolve_object
    from drake_grasp.perception import explore
    from drake_grasp.perception.evaluation import ground_truth
    from drake_grasp.protocol import TrialVariation
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario
    from drake_grasp.trial import apply_variation

    start = time.perf_counter()
    record = {"set": task.set, "object": task.object, "class": task.shape_class, "seed": task.seed,
              "found": False, "best": "", "silhouettes": {}, "table_top": {}, "uncertainty": {}, "detail": ""}
    try:
        scenario = load_scenario(DEFAULT_SCENARIO_FILE, SCENARIO)
        with pose_warnings_announced():
            spec = resolve_object(task.object)
        look_at = np.array([scenario.object.x, scenario.object.y, 0.0])
        scenario, spec = apply_variation(scenario, spec, TrialVariation.draw(task.seed, scenario.protocol))
        result = explore(scenario, None, spec, look_at=look_at)
        estimate = result.estimate
        record["found"] = estimate.found and not estimate.problem()
        if not record["found"]:
            record["detail"] = estimate.problem() or estimate.status
        else:
            truth = ground_truth(spec, result.X_WO_end)
            record["best"] = estimate.best_shape
            if estimate.table_top is None:  # the depth views saw too little: the silhouettes' estimate stands
                record["silhouettes"] = record["table_top"] = errors_record(estimate, truth)
                record["detail"] = "no table-top estimate"
            else:
                record["silhouettes"] = errors_record(silhouettes_estimate(estimate), truth)
                record["table_top"] = errors_record(estimate, truth)
                record["uncertainty"] = estimate.table_top["uncertainty"] or {}
    except Exception as error:  # noqa: BLE001 -- a study never stops for one object
        text = str(error).strip()
        record["detail"] = f"{type(error).__name__}: {text.splitlines()[0] if text else ''}"
    record["wall_time"] = time.perf_counter() - start
    return record


def tasks(out_dir: pathlib.Path, count: int, near: int, seed: int, catalogue: bool = True) -> list[Task]:
    """The sets: `count` novel objects and `near` near-primitives per class (generator seed `seed`),
    and the paper's nine objects."""
    from drake_grasp.objects.catalogue import PAPER_OBJECTS
    from drake_grasp.studies import near_primitives, novel

    found = []
    if count:
        for k, o in enumerate(novel.ensure_objects(out_dir / "novel_objects", count, seed)):
            found.append(Task(str(o["file"]), "novel", o["class"], k))
    if near:
        for o in near_primitives.ensure_objects(out_dir / "near_primitives", near * 4, seed):
            found.append(Task(str(o["file"]), "near", o["class"], int(o["index"])))
    if catalogue:
        found += [Task(name, "catalogue", "catalogue", 0) for name in PAPER_OBJECTS]
    return found


def run(task_list: list[Task], csv_path: pathlib.Path, executor, progress=sys.stderr) -> list[dict]:
    """Runs the explorations not yet in csv_path (each record appended as it arrives); returns all."""
    import contextlib

    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    scenario = load_scenario(DEFAULT_SCENARIO_FILE, SCENARIO)
    prints = [fingerprint(t, scenario) for t in task_list]
    results = table(csv_path)
    todo = [(t, f) for t, f in zip(task_list, prints) if (f, t.object, t.seed) not in results]
    done, total = len(task_list) - len(todo), len(task_list)
    if done:
        print(f"estimates: resuming, {done}/{total} explorations already in {csv_path}", file=progress, flush=True)
    start = time.perf_counter()
    with contextlib.closing(executor.imap_unordered(explore_one, [(t,) for t, _ in todo])) as stream:
        for index, record in stream:
            task, print_ = todo[index]
            record["fingerprint"] = print_
            row = dict(record)
            for key in ("silhouettes", "table_top", "uncertainty"):
                row[key] = json.dumps(json_finite(row[key]))
            results.append([row])
            done += 1
            print(f"estimates: {done}/{total} {pathlib.Path(task.object).name} ({task.shape_class}): "
                  f"{_verdict(record)} ({time.perf_counter() - start:.0f} s)", file=progress, flush=True)
    by_key = {(r["fingerprint"], r["object"], r["seed"]): r for r in results.rows()}
    return [by_key[(f, t.object, str(t.seed))] for t, f in zip(task_list, prints)
            if (f, t.object, str(t.seed)) in by_key]


def _verdict(record: dict) -> str:
    if not record["found"]:
        return f"no estimate ({record['detail']})"

    def short(e):
        axis = "-" if e.get("axis_deg") is None else f"{e['axis_deg']:.1f} deg"
        return f"{1000 * e['centre']:.1f} mm, {axis}"

    return f"silhouettes {short(record['silhouettes'])}; table-top {short(record['table_top'])}"


# --- Summary -----------------------------------------------------------------------------------------


def _loads(value):
    return json.loads(value) if isinstance(value, str) else value


def within(errors: dict) -> bool:
    """Centre within 1 cm and axis (where both have one) within 10°."""
    axis = errors.get("axis_deg")
    return errors["centre"] <= CENTRE_TOL and (axis is None or axis <= AXIS_TOL_DEG)


def summary_lines(rows: list[dict], command: str) -> list[str]:
    """The Markdown summary: per class and overall, for each estimate."""
    from drake_grasp.sweeps.stats import wilson_interval

    by_class: dict[str, list[dict]] = {}
    for r in rows:
        by_class.setdefault(f"{r['set']}: {r['class']}", []).append(r)
    lines = ["# The camera's estimate: silhouettes against the table-top estimate", "",
             f"Made by `{command}`. Each object explored once (scenario `{SCENARIO}`: the default exploration "
             "with depth views); both estimates come from that one exploration. Within: centre error ≤ 1 cm and "
             "axis error ≤ 10° (where the object has a principal axis). Errors at the end of the exploration, "
             "against the object's true pose. 95 % Wilson intervals.", "",
             "| class | objects | silhouettes within | table-top within | centre, mm (sil. / t-t, median; 95th) | "
             "axis, deg (sil. / t-t, median; 95th) | t-t centre within 2σ |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    groups = sorted(by_class.items()) + [("all", rows)]
    for name, group in groups:
        found = [r for r in group if _truthy(r["found"])]
        sil = [_loads(r["silhouettes"]) for r in found]
        tt = [_loads(r["table_top"]) for r in found]
        unc = [_loads(r["uncertainty"]) for r in found]

        def rate(errors):
            k = sum(within(e) for e in errors)
            lo, hi = wilson_interval(k, len(group))
            return f"{k}/{len(group)} ({100 * lo:.0f}-{100 * hi:.0f} %)"

        def stats(errors, key, scale):
            values = [scale * e[key] for e in errors if e.get(key) is not None]
            if not values:
                return "-"
            return f"{np.median(values):.1f}; {np.quantile(values, 0.95):.1f}"

        calibrated = [t["centre"] <= 2 * u["centre"] for t, u in zip(tt, unc) if u]
        cal = f"{sum(calibrated)}/{len(calibrated)}" if calibrated else "-"
        lines.append(f"| {name} | {len(group)} | {rate(sil)} | {rate(tt)} | {stats(sil, 'centre', 1000)} / "
                     f"{stats(tt, 'centre', 1000)} | {stats(sil, 'axis_deg', 1)} / {stats(tt, 'axis_deg', 1)} | {cal} |")
    missing = [r for r in rows if not _truthy(r["found"]) or r["detail"]]
    if missing:
        lines += ["", "Explorations without a (table-top) estimate:", ""]
        lines += [f"- {pathlib.Path(r['object']).name} (seed {r['seed']}): {r['detail']}" for r in missing]
    return lines


def _truthy(value) -> bool:
    return str(value) in ("1", "True", "true")
