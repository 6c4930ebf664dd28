#!/usr/bin/env python3
"""The sensitivity sweep (drake_grasp/experiments/sensitivity.py) from the command line.

    .venv/bin/python scripts/sensitivity.py --quick                       # 3 objects x 8 conditions x 1 trial
    .venv/bin/python scripts/sensitivity.py                               # 9 objects x 8 conditions x 4 trials
    .venv/bin/python scripts/sensitivity.py --trials 1 --out docs/results/sensitivity
    .venv/bin/python scripts/sensitivity.py --conditions base,friction_0.3 --objects apple,banana

Resumable (rerun the same command), one writer per folder, progress lines on stderr, one-line errors
with exit code 2 for bad input before any work (1: a run that could not be carried out; 130/143:
interrupted). Writes conditions.yaml, sensitivity.csv, conditions.csv, cost.json, summary.md and
sensitivity.png/.svg under --out.
"""

import argparse
import os
import pathlib
import signal
import sys
import time


class UsageError(ValueError):
    pass


class Terminated(KeyboardInterrupt):
    pass


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="sensitivity", description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="3 objects (apple, banana, soccer ball), 1 trial each")
    p.add_argument("--objects", help="comma-separated objects (default: the paper's nine)")
    p.add_argument("--trials", type=int, help="trials per object and condition (default 4; --quick: 1)")
    p.add_argument("--seed", type=int, default=0, help="trial i uses seed + i (default 0)")
    p.add_argument("--conditions", help="comma-separated condition names to run (default: all; see --list)")
    p.add_argument("--noise-sigma", type=float, default=None, help="image noise of the noisy colour condition, "
                   "8-bit counts (default 10)")
    p.add_argument("--list", action="store_true", help="list the conditions and exit")
    p.add_argument("--scenario", help="the base scenario file (default: the repository's)")
    p.add_argument("--scenario-name", default="default", help="the base scenario's name (default: default)")
    p.add_argument("--out", help="output folder (default out/sensitivity, or out/sensitivity-quick)")
    p.add_argument("--workers", type=int, help="local worker processes (default: every core)")
    p.add_argument("--executor", default="local", help="local or ray")
    p.add_argument("--ray-address", help="join a running Ray cluster (with --executor ray)")
    return p


def check_out_dir(path: str) -> pathlib.Path:
    p = pathlib.Path(path)
    if p.exists():
        if not p.is_dir():
            raise UsageError(f"--out {path}: exists and is not a directory")
        if not os.access(p, os.W_OK | os.X_OK):
            raise UsageError(f"--out {path}: directory is not writable")
        return p
    parent = p.absolute().parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir() or not os.access(parent, os.W_OK | os.X_OK):
        raise UsageError(f"--out {path}: cannot create it ({parent} is not a writable directory)")
    return p


def config_from_args(args):
    """The SensitivityConfig the arguments ask for (UsageError / ValueError, one line, if bad)."""
    from drake_grasp.experiments import sensitivity
    from drake_grasp.objects import resolve_user_object

    if args.trials is not None and args.trials < 1:
        raise UsageError(f"--trials must be >= 1, got {args.trials}")
    trials = args.trials or (1 if args.quick else 4)
    if not 0 <= args.seed or args.seed + trials - 1 >= 2**32:
        raise UsageError(f"--seed must be in [0, 2^32 - trials], got {args.seed}")
    sigma = sensitivity.DEFAULT_NOISE_SIGMA if args.noise_sigma is None else args.noise_sigma
    if not sigma >= 0 or sigma == float("inf"):
        raise UsageError(f"--noise-sigma must be a finite number >= 0, got {args.noise_sigma}")
    conditions = sensitivity.default_conditions(noise_sigma=sigma)
    if args.conditions is not None:
        names = [n.strip() for n in args.conditions.split(",") if n.strip()]
        known = {c.name: c for c in conditions}
        unknown = [n for n in names if n not in known]
        if not names or unknown:
            raise UsageError(f"--conditions: unknown {', '.join(unknown) or '(none given)'} "
                             f"(choose from {', '.join(known)})")
        conditions = tuple(known[n] for n in dict.fromkeys(names))
    objects = sensitivity.QUICK_OBJECTS if args.quick else ()
    if args.objects is not None:
        objects = tuple(o.strip() for o in args.objects.split(",") if o.strip())
        if not objects:
            raise UsageError("--objects needs at least one object")
        if len(set(objects)) != len(objects):
            raise UsageError(f"--objects names an object twice: {args.objects}")
        for o in objects:
            resolve_user_object(o)
    scenario_file = str(pathlib.Path(args.scenario).resolve()) if args.scenario else ""
    return sensitivity.SensitivityConfig(objects=objects, trials=trials, seed=args.seed, conditions=conditions,
                                         scenario_file=scenario_file, scenario_name=args.scenario_name)


def run(args) -> int:
    from drake_grasp.experiments import sensitivity
    from drake_grasp.experiments.executors import make_executor
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers must be >= 1, got {args.workers}")
    cores = os.cpu_count() or 1
    if args.workers is not None and args.workers > cores:
        print(f"sensitivity: note: --workers {args.workers} is more than this machine's {cores} cores; using "
              f"{cores}", file=sys.stderr)
        args.workers = cores
    config = config_from_args(args)
    if args.list:
        for c in config.conditions:
            print(f"{c.name}: {c.label}")
        return 0
    load_scenario(config.scenario_file or DEFAULT_SCENARIO_FILE, config.scenario_name)  # a bad one: exit 2
    out = check_out_dir(args.out or ("out/sensitivity-quick" if args.quick else "out/sensitivity"))
    executor = make_executor(args.executor, args.workers, args.ray_address)
    start = time.perf_counter()
    with executor:
        result = sensitivity.run_sensitivity(config, out, args.workers, executor)
    from drake_grasp.experiments.stats import format_rate

    for c in config.conditions:
        print(f"{c.label}: chosen grasps {format_rate(*sensitivity.totals(result.table[c.name]))}")
    for r in result.claims:
        print(f"{r.claim}: {r.across(config.conditions)}")
    print(f"sensitivity: {result.trials} trials, {time.perf_counter() - start:.0f} s; {result.summary}, "
          f"{result.figures[0]}")
    return 0


def main(argv=None) -> int:
    args = parser().parse_args(argv)

    def terminate(signum, frame):
        raise Terminated()

    previous = signal.signal(signal.SIGTERM, terminate)
    try:
        return run(args)
    except ValueError as e:  # UsageError, ObjectError, scenario and results-file errors, a held lock
        message = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        print(f"sensitivity: error: {message}", file=sys.stderr)
        return 2
    except FileNotFoundError as e:
        print(f"sensitivity: error: {e}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        message = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        print(f"sensitivity: failed: {message}", file=sys.stderr)
        return 1
    except KeyboardInterrupt as e:
        terminated = isinstance(e, Terminated)
        print(f"sensitivity: {'terminated' if terminated else 'interrupted'}", file=sys.stderr)
        return 143 if terminated else 130
    finally:
        signal.signal(signal.SIGTERM, previous)


if __name__ == "__main__":
    sys.exit(main())
