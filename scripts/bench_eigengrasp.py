"""Benchmark of the Eigengrasp planner (baselines/eigengrasp): annealing steps per second.

For each object it builds the planner (once), runs one plan of ``--steps`` (GraspIt!'s step limit:
the default 70,000 is 40,000 annealing iterations from k = 30,000) and prints the annealing rate
(iterations per second of wall time, and per second of this process's CPU time, which other
processes on a shared machine do not inflate), the wall time of the whole plan (annealing plus
autograsp of the 20 best states), and what the plan found: ε of the three best grasps after
autograsp and which fingers touch.

GraspIt! itself, built and run on a machine like ours, does 2,400-7,900 steps per second on these
objects (docs/design.md §4.6): a 70,000-step plan in 11-27 s.

Run: .venv/bin/python scripts/bench_eigengrasp.py [--objects a,b] [--steps N] [--seed S]
     [--energy contact|contact-quality] [--json FILE]
Not a test: the numbers depend on the machine and its load.
"""

import argparse
import json
import pathlib
import sys
import time

try:
    from baselines.eigengrasp.planner import EigengraspPlanner
except ModuleNotFoundError:  # Run from a checkout without installing the package.
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
    from baselines.eigengrasp.planner import EigengraspPlanner
from baselines.eigengrasp import annealing
from drake_grasp.objects import resolve_object

FIG7_OBJECTS = ("sponge", "spectacle_case", "toy_bridge", "soccer_ball", "game_box", "bottle_case")
GRASPIT_STEPS_PER_SECOND = (2_400, 7_900)  # docs/design.md §4.6, measured on a machine like ours.


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--objects", default=",".join(FIG7_OBJECTS), help="comma-separated object names")
    parser.add_argument("--steps", type=int, default=annealing.DEFAULT_MAX_STEPS)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--energy", default="contact", choices=["contact", "contact-quality"])
    parser.add_argument("--json", metavar="FILE", help="also write the rows as JSON")
    args = parser.parse_args(argv)

    rows = []
    print(f"{args.steps} steps = {args.steps - annealing.K0} iterations, energy {args.energy}, seed {args.seed}; "
          f"GraspIt!: {GRASPIT_STEPS_PER_SECOND[0]}-{GRASPIT_STEPS_PER_SECOND[1]} steps/s")
    print(f"{'object':15s} {'steps/s':>8s} {'(cpu)':>8s} {'plan s':>7s} {'anneal':>7s} {'autogr':>7s} "
          f"{'collide':>7s}  eps of the top 3 after autograsp (fingers touching)")
    for name in args.objects.split(","):
        planner = EigengraspPlanner(resolve_object(name), args.energy)
        start = time.perf_counter()
        plan = planner.plan(args.steps, seed=args.seed)
        wall = time.perf_counter() - start
        row = {
            "object": name, "iterations": plan.iterations, "steps_per_second": plan.steps_per_second,
            "steps_per_cpu_second": plan.iterations / plan.annealing_cpu_time,
            "plan_wall_time": wall, "annealing_time": plan.annealing_time,
            "autograsp_time": plan.autograsp_time, "setup_time": plan.setup_time,
            "collision_fraction": plan.collisions / plan.evaluations,
            "epsilon": [g.epsilon for g in plan.grasps],
            "fingers_touching": [g.fingers_touching for g in plan.grasps],
            "force_closure_in_top3": sum(g.epsilon > 0 for g in plan.grasps),
        }
        rows.append(row)
        grasps = "  ".join(f"{g.epsilon:.4f} ({''.join(map(str, g.fingers_touching)) or '-'})" for g in plan.grasps)
        print(f"{name:15s} {row['steps_per_second']:8.0f} {row['steps_per_cpu_second']:8.0f} {wall:7.1f} "
              f"{plan.annealing_time:7.1f} {plan.autograsp_time:7.1f} {row['collision_fraction']:7.2f}  {grasps}",
              flush=True)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
