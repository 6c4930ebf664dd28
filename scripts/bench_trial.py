#!/usr/bin/env python3
"""Benchmark: wall time of one full grasp trial (move, approach, close, lift 10 cm, hold 10 s).

    .venv/bin/python scripts/bench_trial.py [--scenario-name default] [--method oracle|compliant]

Runs on one core (the trial itself is single-threaded). `oracle` (default) times the grasp alone,
from ground-truth estimates: target at most 5 s per trial, with a time step and contact model that
hold a grasped object honestly (the slip is printed beside the time). `compliant` times the whole
algorithm, the wrist camera's 12.5 s exploration included, in one simulation.
"""

import argparse
import math
import time

from drake_grasp import trial
from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

CASES = [("soccer_ball", "spherical"), ("bottle_case", "cylindrical"), ("sponge", "box"), ("apple", "box")]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenario-name", default="default")
    parser.add_argument("--method", choices=["oracle", "compliant"], default="oracle")
    args = parser.parse_args()
    scenario = load_scenario(DEFAULT_SCENARIO_FILE, args.scenario_name)
    config = scenario.plant_config
    print(f"scenario '{args.scenario_name}': time step {config.time_step * 1000:.1f} ms, {config.contact_model}, "
          f"{config.discrete_contact_approximation}")
    walls = []
    for name, grasp in CASES:
        start = time.perf_counter()
        record = trial.run(trial.TrialSpec(name, args.method, grasp, 0), scenario=scenario)
        wall = time.perf_counter() - start
        walls.append(wall)
        slip = (f"slip {record.slip_distance * 1000:.2f} mm / {math.degrees(record.slip_angle):.2f} deg"
                if math.isfinite(record.slip_distance) else "no hold")
        print(f"  {name:12s} {grasp:12s} {'held' if record.success else record.failure:20s} {slip:28s} "
              f"{record.sim_time:5.1f} s simulated, {wall:5.2f} s wall ({record.sim_time / wall:4.1f}x real time)")
    target = " (target <= 5 s)" if args.method == "oracle" else ""
    print(f"mean wall time per {args.method} trial: {sum(walls) / len(walls):.2f} s{target}")


if __name__ == "__main__":
    main()
