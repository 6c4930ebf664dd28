#!/usr/bin/env python3
"""Benchmark: wall time of one full grasp trial (move, approach, close, lift 10 cm, hold 10 s).

    .venv/bin/python scripts/bench_trial.py [--scenario-name default] [--method oracle|compliant]
    .venv/bin/python scripts/bench_trial.py --ref main [--method both] [--repeats 2] \\
        [--out docs/results/bench_trial]

Runs on one core (the trial itself is single-threaded). `oracle` (default) times the grasp alone,
from ground-truth estimates: target at most 5 s per trial, with a time step and contact model that
hold a grasped object honestly (the slip is printed beside the time). `compliant` times the whole
algorithm, the wrist camera's 12.5 s exploration included, in one simulation.

With `--ref GITREV`, it measures the code of that revision ("before", exported with `git archive`
into a temporary directory) against the working tree ("after") in one run on the same machine: two
worker processes, one per version, each with its imports done once, run the same trials one at a
time, alternating which version goes first from trial to trial so that a drift of the machine's
load falls on both alike. It also compares the two versions' records field by field (all but
`wall_time`), and writes a table (`--out` + .md) and every measurement (`--out` + .json).
"""

import argparse
import json
import math
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile
import time

CASES = [("soccer_ball", "spherical"), ("bottle_case", "cylindrical"), ("sponge", "box"), ("apple", "box")]
REPO = pathlib.Path(__file__).resolve().parents[1]


def run_one(name: str, method: str, grasp: str, seed: int, scenario) -> tuple[dict, float, float]:
    """One trial: its record (plain data), its wall time and its process CPU time, s (the trial
    alone, imports done). On a shared machine the CPU time is the steadier of the two."""
    from drake_grasp import trial

    start, start_cpu = time.perf_counter(), time.process_time()
    record = trial.run(trial.TrialSpec(name, method, grasp, seed), scenario=scenario)
    return record.to_dict(), time.perf_counter() - start, time.process_time() - start_cpu


def serve() -> None:
    """The worker: reads one trial per line (JSON) on stdin, answers its record and wall time."""
    import drake_grasp.perception  # noqa: F401  (imports done before the first trial is timed)
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    scenarios = {}
    for line in sys.stdin:
        job = json.loads(line)
        name = job["scenario_name"]
        if name not in scenarios:
            scenarios[name] = load_scenario(DEFAULT_SCENARIO_FILE, name)
        record, wall, cpu = run_one(job["object"], job["method"], job["grasp"], job["seed"], scenarios[name])
        print(json.dumps({"record": record, "wall": wall, "cpu": cpu}), flush=True)


class Worker:
    """A worker process that imports `drake_grasp` from `tree`."""

    def __init__(self, tree: pathlib.Path):
        env = dict(os.environ, PYTHONPATH=str(tree))
        self.process = subprocess.Popen([sys.executable, str(pathlib.Path(__file__).resolve()), "--serve"],
                                        cwd=tree, env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def run(self, job: dict) -> dict:
        self.process.stdin.write(json.dumps(job) + "\n")
        self.process.stdin.flush()
        line = self.process.stdout.readline()
        if not line:
            raise RuntimeError("the benchmark worker ended unexpectedly")
        return json.loads(line)

    def close(self) -> None:
        self.process.stdin.close()
        self.process.wait()


def compare(args) -> None:
    """Before (`args.ref`) against after (the working tree), alternating, one trial at a time."""
    sys.path.insert(0, str(REPO / "scripts"))
    from record_check import differences

    revision = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", args.ref], check=True,
                              capture_output=True, text=True).stdout.strip()
    head = subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", "HEAD"], check=True,
                          capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", str(REPO), "status", "--porcelain", "--untracked-files=no"],
                           check=True, capture_output=True, text=True).stdout.strip()
    methods = ["oracle", "compliant"] if args.method == "both" else [args.method]
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_ref_") as temp:
        before_tree = pathlib.Path(temp)
        archive = subprocess.run(["git", "-C", str(REPO), "archive", args.ref], check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(before_tree)], input=archive, check=True)
        workers = {"before": Worker(before_tree), "after": Worker(REPO)}
        try:
            turn = 0
            for method in methods:
                for name, grasp in cases(args):
                    for repeat in range(args.repeats):
                        job = {"object": name, "method": method, "grasp": grasp if method == "oracle" else "",
                               "seed": args.seed, "scenario_name": args.scenario_name}
                        order = ("before", "after") if turn % 2 == 0 else ("after", "before")
                        turn += 1
                        results = {version: workers[version].run(job) for version in order}
                        diffs = differences(results["before"]["record"], results["after"]["record"])
                        for version in ("before", "after"):
                            record = results[version]["record"]
                            rows.append({"version": version, "object": name, "method": method, "repeat": repeat,
                                         "first": version == order[0], "wall": results[version]["wall"],
                                         "cpu": results[version]["cpu"],
                                         "sim_time": record["sim_time"], "success": record["success"],
                                         "failure": record["failure"],
                                         "slip_distance": record["slip_distance"]
                                         if math.isfinite(record["slip_distance"]) else None,
                                         "records_identical": not diffs})
                        print(f"  {method:9s} {name:12s} before {results['before']['wall']:6.2f} s "
                              f"({results['before']['cpu']:6.2f} s CPU)  after {results['after']['wall']:6.2f} s "
                              f"({results['after']['cpu']:6.2f} s CPU)  "
                              f"{'records identical' if not diffs else f'{len(diffs)} fields differ'}", flush=True)
                        for field, what in diffs:
                            print(f"      {field}: {what}")
        finally:
            for worker in workers.values():
                worker.close()
    summary = summarize(rows, methods)
    meta = {"ref": f"{args.ref} ({revision})", "after": f"working tree at {head}" + (" with changes" if dirty else ""),
            "scenario": args.scenario_name, "seed": args.seed, "repeats": args.repeats,
            "machine": f"{platform.node()}, {os.cpu_count()} CPUs, {platform.processor() or platform.machine()}",
            "date": time.strftime("%Y-%m-%d %H:%M")}
    for line in table(summary, meta):
        print(line)
    if args.out:
        out = pathlib.Path(args.out)
        out.parent.mkdir(parents=True, exist_ok=True)
        out.with_suffix(".json").write_text(json.dumps({"meta": meta, "summary": summary, "trials": rows}, indent=1,
                                                       allow_nan=False) + "\n")
        out.with_suffix(".md").write_text("\n".join(table(summary, meta)) + "\n")


def summarize(rows: list[dict], methods: list[str]) -> list[dict]:
    """Mean wall per trial before and after, per object and method, then per method over the objects."""
    out = []
    for method in methods:
        for name in sorted({r["object"] for r in rows}, key=[c[0] for c in CASES].index) + ["all objects"]:
            pick = [r for r in rows if r["method"] == method and (name == "all objects" or r["object"] == name)]
            row = {"method": method, "object": name}
            for measure in ("wall", "cpu"):
                before = statistics.mean(r[measure] for r in pick if r["version"] == "before")
                after = statistics.mean(r[measure] for r in pick if r["version"] == "after")
                row.update({f"{measure}_before": before, f"{measure}_after": after, f"{measure}_ratio": after / before})
            row["trials"] = len(pick) // 2
            row["records_identical"] = all(r["records_identical"] for r in pick)
            out.append(row)
    return out


def table(summary: list[dict], meta: dict) -> list[str]:
    lines = ["# bench_trial: wall time per trial, before against after", "",
             f"Before: {meta['ref']}; after: {meta['after']}. Scenario `{meta['scenario']}`, seed {meta['seed']}, "
             f"{meta['repeats']} trial(s) per object and version, one process at a time, the versions alternating. "
             f"{meta['machine']}; {meta['date']}. Produced by `scripts/bench_trial.py --ref`.", "",
             "Mean per trial; wall time (the target: at most half of before), and the worker's CPU time (steadier "
             "when another process shares the machine).", "",
             "| method | object | wall before (s) | wall after (s) | after / before | CPU before (s) | CPU after (s) "
             "| after / before | records identical |",
             "|---|---|---:|---:|---:|---:|---:|---:|---|"]
    for s in summary:
        b = "**" if s["object"] == "all objects" else ""
        lines.append(f"| {s['method']} | {b}{s['object']}{b} | {s['wall_before']:.2f} | {s['wall_after']:.2f} | "
                     f"{b}{s['wall_ratio']:.2f}{b} | {s['cpu_before']:.2f} | {s['cpu_after']:.2f} | "
                     f"{b}{s['cpu_ratio']:.2f}{b} | {'yes' if s['records_identical'] else 'NO'} |")
    return lines


def single(args) -> None:
    """Today's code alone: each case once, with its outcome and slip."""
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    scenario = load_scenario(DEFAULT_SCENARIO_FILE, args.scenario_name)
    config = scenario.plant_config
    print(f"scenario '{args.scenario_name}': time step {config.time_step * 1000:.1f} ms, {config.contact_model}, "
          f"{config.discrete_contact_approximation}")
    for method in (["oracle", "compliant"] if args.method == "both" else [args.method]):
        walls = []
        for name, grasp in cases(args):
            record, wall, _ = run_one(name, method, grasp if method == "oracle" else "", args.seed, scenario)
            walls.append(wall)
            slip = (f"slip {record['slip_distance'] * 1000:.2f} mm / {math.degrees(record['slip_angle']):.2f} deg"
                    if math.isfinite(record["slip_distance"]) else "no hold")
            print(f"  {name:12s} {grasp:12s} {'held' if record['success'] else record['failure']:20s} {slip:28s} "
                  f"{record['sim_time']:5.1f} s simulated, {wall:5.2f} s wall "
                  f"({record['sim_time'] / wall:4.1f}x real time)")
        target = " (target <= 5 s)" if method == "oracle" else ""
        print(f"mean wall time per {method} trial: {sum(walls) / len(walls):.2f} s{target}")


def cases(args) -> list[tuple[str, str]]:
    """The (object, oracle grasp) cases to run: all of CASES, or those `--objects` names."""
    return [c for c in CASES if not args.objects or c[0] in args.objects.split(",")]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenario-name", default="default")
    parser.add_argument("--method", choices=["oracle", "compliant", "both"], default="oracle")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--ref", metavar="GITREV", help="measure this revision (before) against the working tree")
    parser.add_argument("--repeats", type=int, default=1, help="with --ref: trials per object and version")
    parser.add_argument("--out", help="with --ref: write the table to OUT.md and the measurements to OUT.json")
    parser.add_argument("--objects", help="a comma-separated subset of the four objects (default: all)")
    parser.add_argument("--serve", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.serve:
        serve()
    elif args.ref:
        compare(args)
    else:
        single(args)


if __name__ == "__main__":
    main()
