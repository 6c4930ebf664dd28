#!/usr/bin/env python3
"""Benchmark: trials per second with 1 and 2 local worker processes and with Ray, same workload.

    .venv/bin/python scripts/bench_scaling.py [--trials 8] [--object sponge] [--grasp box]
                                              [--ray-cpus 2] [--out docs/results/scaling.md]

The workload is N full oracle trials (default scenario: move, approach, close, lift 10 cm, hold 10 s)
of one object and grasp, seeds 0..N-1, run through `runner.run_trials` into a fresh results file per
executor. Wall times include the executor's start-up (spawning worker processes, starting a local
Ray instance) up to the last record, as a sweep would pay it; Ray's start-up is also given alone. The
records of the three runs are compared (all fields but wall_time): they must be identical.

Writes the table as Markdown to --out and the numbers as JSON beside it (same name, .json); the
reproduction report (`drake-grasp reproduce`) quotes that JSON. The machine's load average is recorded
before and after: other work on the machine slows the parallel runs most.
"""

import argparse
import csv
import datetime
import importlib.metadata
import json
import os
import pathlib
import platform
import sys
import tempfile
import time

from drake_grasp.sweeps.executors import make_executor, ray_available, RAY_INSTALL_HINT
from drake_grasp.sweeps.runner import TrialSpec, run_trials


def cpu_model() -> str:
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def git_commit() -> str:
    """The repository's commit, with "+ local changes" when the tree differs from it; "" outside git."""
    import subprocess

    root = pathlib.Path(__file__).resolve().parent.parent
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True, text=True,
                                check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=root,
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""
    return f"commit {commit}" + (" + local changes" if dirty else "")


def records(csv_path: pathlib.Path) -> dict:
    """Rows by key, without wall_time (the one field that depends on where and when a trial ran)."""
    with open(csv_path) as f:
        return {(r["object"], r["method"], r["grasp"], r["seed"]): {k: v for k, v in r.items() if k != "wall_time"}
                for r in csv.DictReader(f)}


def time_run(specs, kind: str, workers: int, csv_path: pathlib.Path) -> dict:
    """Runs the specs on one executor; returns its timings."""
    devnull = open(os.devnull, "w")
    start = time.perf_counter()
    with make_executor(kind, workers, progress=devnull) as executor:
        executor.start()
        startup = time.perf_counter() - start
        run_trials(specs, csv_path, progress=devnull, executor=executor)
        wall = time.perf_counter() - start
        description = executor.describe()
    return {"executor": kind, "workers": workers, "description": description, "wall_time": wall,
            "startup_time": startup if kind == "ray" else None, "trials_per_second": len(specs) / wall}


def scaling_statement(runs: list[dict]) -> str:
    base = runs[0]["trials_per_second"]
    parts = []
    for r in runs[1:]:
        parts.append(f"{r['description']}: {r['trials_per_second'] / base:.2f}x the throughput of 1 local worker")
    return "; ".join(parts) + "."


def markdown(data: dict) -> str:
    base = data["runs"][0]["trials_per_second"]
    lines = [
        "# Scaling: trials per second by executor",
        "",
        f"Measured {data['date']} with `{data['command']}` on {data['machine']} "
        f"(load average {', '.join(f'{v:.2f}' for v in data['load_average_before'])} before, "
        f"{', '.join(f'{v:.2f}' for v in data['load_average_after'])} after, over 1, 5, 15 min; the load after "
        "includes this benchmark's own processes).",
        "",
        f"Workload: {data['workload']}." + (f" Code: {data['code']}." if data.get("code") else ""),
        "",
        "| executor | workers | wall time (s) | of which start-up (s) | trials/s | speedup |",
        "|---|---|---|---|---|---|",
    ]
    for r in data["runs"]:
        startup = f"{r['startup_time']:.1f}" if r["startup_time"] is not None else "-"
        lines.append(f"| {r['executor']} | {r['workers']} | {r['wall_time']:.1f} | {startup} | "
                     f"{r['trials_per_second']:.3f} | {r['trials_per_second'] / base:.2f}x |")
    ray = [r for r in data["runs"] if r["startup_time"] is not None]
    lines += [
        "",
        f"Scaling: {data['scaling']}",
        "",
        "Wall times run from creating the executor to the last record: the local pool's process spawning "
        "and each worker's first import of Drake are inside them, as is starting the local Ray instance"
        + (f" ({ray[0]['startup_time']:.1f} s, the start-up column; without it Ray did "
           f"{data['trials'] / (ray[0]['wall_time'] - ray[0]['startup_time']):.3f} trials/s)" if ray else "")
        + ". Ray's shutdown is not.",
        "",
        f"Records identical across executors (every field but wall_time): "
        f"{'yes' if data['identical_records'] else 'NO'}.",
        "",
    ]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--trials", type=int, default=8, help="trials per run (seeds 0..N-1, default 8)")
    parser.add_argument("--object", default="sponge", help="object of every trial (default sponge)")
    parser.add_argument("--grasp", default="box", choices=["spherical", "cylindrical", "box"])
    parser.add_argument("--ray-cpus", type=int, default=2, help="CPUs of the local Ray instance (default 2)")
    parser.add_argument("--out", default="docs/results/scaling.md", help="Markdown table; JSON beside it")
    args = parser.parse_args()
    if args.trials < 1 or args.ray_cpus < 1:
        print("bench_scaling: error: --trials and --ray-cpus must be >= 1", file=sys.stderr)
        return 2
    if not ray_available():
        print(f"bench_scaling: error: the Ray run needs Ray: {RAY_INSTALL_HINT}", file=sys.stderr)
        return 2
    out = pathlib.Path(args.out)
    if not out.parent.is_dir():
        print(f"bench_scaling: error: directory {out.parent} does not exist", file=sys.stderr)
        return 2

    specs = [TrialSpec(args.object, "oracle", args.grasp, seed) for seed in range(args.trials)]
    load_before = os.getloadavg()
    print(f"load average before: {', '.join(f'{v:.2f}' for v in load_before)} ({os.cpu_count()} CPUs)")
    runs, rows = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for kind, workers in (("local", 1), ("local", 2), ("ray", args.ray_cpus)):
            csv_path = pathlib.Path(tmp) / f"{kind}_{workers}.csv"
            run = time_run(specs, kind, workers, csv_path)
            runs.append(run)
            rows.append(records(csv_path))
            print(f"{run['description']}: {args.trials} trials in {run['wall_time']:.1f} s, "
                  f"{run['trials_per_second']:.3f} trials/s", flush=True)
    successes = sum(r["success"] == "1" for r in rows[0].values())
    data = {
        "date": datetime.datetime.now().astimezone().isoformat(timespec="minutes"),
        "machine": f"{cpu_model()}, {os.cpu_count()} CPUs, {platform.system()} {platform.machine()}, "
                   f"Python {platform.python_version()}, Ray {importlib.metadata.version('ray')}",
        "command": f"scripts/bench_scaling.py --trials {args.trials} --object {args.object} --grasp {args.grasp} "
                   f"--ray-cpus {args.ray_cpus}",
        "load_average_before": list(load_before),
        "load_average_after": list(os.getloadavg()),
        "workload": f"{args.trials} oracle trials of the {args.object} with the {args.grasp} grasp, seeds "
                    f"0-{args.trials - 1}, default scenario (full 10 s hold), {successes}/{args.trials} held",
        "code": git_commit(),
        "trials": args.trials,
        "runs": runs,
        "identical_records": all(r == rows[0] for r in rows[1:]),
    }
    data["scaling"] = scaling_statement(runs)
    out.write_text(markdown(data))
    out.with_suffix(".json").write_text(json.dumps(data, indent=1) + "\n")
    print(f"scaling: {data['scaling']} Records identical: {data['identical_records']}. Wrote {out} and "
          f"{out.with_suffix('.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
