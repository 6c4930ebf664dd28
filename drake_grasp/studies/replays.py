"""One replay per object and method, for the results page: a trial run again with a Meshcat recording.

The studies' trials run without recording (a replay is about 5 MB). For the page, each object's first
trial is run once more, with the same seed, scenario and success test, recording a Meshcat replay: for
the compliance-centric algorithm its own choice of grasp from the camera, for the Eigengrasp planner
its best reachable grasp. Each replay is written beside a small JSON file naming the trial it shows
(its fingerprint) and how it ended, so a rerun reuses a replay only if it shows the same trial.
"""

import json
import pathlib
import sys

from drake_grasp.studies.report_page import Replay
from drake_grasp.sweeps.results import write_atomically


def _record_replay(spec, path: str) -> dict:
    """A worker task: runs `spec` (a runner.TrialSpec; method "compliant" runs the algorithm's own
    choice) with a replay written to `path`; returns how it ended."""
    import logging

    from drake_grasp.sweeps.runner import run_one

    logging.getLogger("drake").setLevel(logging.WARNING)  # not Meshcat's "listening at" per replay
    row = run_one(spec, replay_html=path)
    return {"success": str(row["success"]) in ("1", "True"), "failure": row["failure"]}


def ensure_replays(out_dir: pathlib.Path, specs: list, executor, progress=sys.stderr) -> list[Replay]:
    """The replays of `specs` (runner.TrialSpec) under out_dir, run on `executor` where missing or
    stale; returned with paths relative to out_dir's parent (the report's folder)."""
    from drake_grasp.sweeps.runner import fingerprints

    out_dir.mkdir(parents=True, exist_ok=True)
    todo, replays = [], {}
    for spec, fingerprint in zip(specs, fingerprints(specs)):
        stem = f"{pathlib.Path(spec.object).stem if '/' in spec.object else spec.object.replace(':', '_')}_{spec.method}"
        html_path, info_path = out_dir / f"{stem}.html", out_dir / f"{stem}.json"
        info = json.loads(info_path.read_text()) if info_path.exists() else {}
        if html_path.exists() and info.get("fingerprint") == fingerprint:
            replays[stem] = (spec, info)
        else:
            todo.append((spec, fingerprint, stem))
    tasks = [(spec, str(out_dir / f"{stem}.html")) for spec, _, stem in todo]
    for index, outcome in executor.imap_unordered(_record_replay, tasks):
        spec, fingerprint, stem = todo[index]
        info = {"fingerprint": fingerprint, **outcome}
        write_atomically(out_dir / f"{stem}.json", json.dumps(info))
        replays[stem] = (spec, info)
        print(f"replay: {spec.object} {spec.method}: {'held' if outcome['success'] else outcome['failure']}",
              file=progress, flush=True)
    return [Replay(spec.object, spec.method, f"{out_dir.name}/{stem}.html",
                   "held" if info["success"] else info["failure"])
            for stem, (spec, info) in sorted(replays.items(), key=lambda kv: specs.index(kv[1][0]))]
