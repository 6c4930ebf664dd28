"""Benchmark of the ε metric (drake_grasp.quality) against a bare scipy ConvexHull call.

For 3, 4, 5 and 6 contacts (8 cone edges, μ = 0.5) it draws seeded random force-closure grasps on a
4 cm sphere and times, per grasp, (a) the full ``epsilon_l1`` call (input checks, wrench
construction, flatness check, hull, facet distances) and (b) ``scipy.spatial.ConvexHull`` alone on
the same, precomputed wrenches. The two take turns within each pass and the best pass of each is
kept, to filter out noise from other processes.

Run: /work/venv/bin/python scripts/bench_quality.py [--seed N] [--grasps N] [--passes N]
Not a test: the numbers depend on the machine.
"""

import argparse
import pathlib
import sys
import time

import numpy as np
from scipy.spatial import ConvexHull

try:
    from drake_grasp.quality import epsilon_l1, primitive_wrenches
except ModuleNotFoundError:  # Run from a checkout without installing the package.
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
    from drake_grasp.quality import epsilon_l1, primitive_wrenches

SPHERE_RADIUS = 0.04  # m
MU = 0.5
NUM_EDGES = 8


def random_force_closure_grasps(rng, num_contacts, num_grasps):
    """Contacts uniform on the sphere (normals inwards), kept when ε > 0."""
    grasps = []
    while len(grasps) < num_grasps:
        directions = rng.normal(size=(num_contacts, 3))
        directions /= np.linalg.norm(directions, axis=1, keepdims=True)
        points, normals = SPHERE_RADIUS * directions, -directions
        if epsilon_l1(points, normals, MU, np.zeros(3), SPHERE_RADIUS, NUM_EDGES) > 0.0:
            grasps.append((points, normals))
    return grasps


def best_seconds_per_call(timed_runs, passes):
    """Smallest mean time per call of each (function, arguments) pair over ``passes`` passes.

    The pairs take turns within each pass, so that all of them see the same machine load.
    """
    best = [np.inf] * len(timed_runs)
    for _ in range(passes):
        for index, (function, arguments) in enumerate(timed_runs):
            start = time.perf_counter()
            for argument in arguments:
                function(argument)
            best[index] = min(best[index], (time.perf_counter() - start) / len(arguments))
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=0, help="random seed for the grasps")
    parser.add_argument("--grasps", type=int, default=40, help="grasps per contact count")
    parser.add_argument("--passes", type=int, default=7, help="timed passes (best is kept)")
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)

    print(f"ε (L1, {NUM_EDGES} edges, μ = {MU}) vs bare scipy ConvexHull, {args.grasps} seeded "
          f"force-closure grasps per row, best of {args.passes} interleaved passes")
    print(f"{'contacts':>8} {'wrenches':>8} {'ε evals/s':>10} {'ε ms':>7} {'hull ms':>8} "
          f"{'ratio':>6}")
    for num_contacts in (3, 4, 5, 6):
        grasps = random_force_closure_grasps(rng, num_contacts, args.grasps)
        wrench_sets = [primitive_wrenches(points, normals, MU, np.zeros(3), SPHERE_RADIUS,
                                          NUM_EDGES) for points, normals in grasps]
        epsilon_seconds, hull_seconds = best_seconds_per_call(
            [(lambda grasp: epsilon_l1(grasp[0], grasp[1], MU, np.zeros(3), SPHERE_RADIUS,
                                       NUM_EDGES), grasps),
             (ConvexHull, wrench_sets)],
            args.passes)
        print(f"{num_contacts:>8} {num_contacts * NUM_EDGES:>8} {1.0 / epsilon_seconds:>10.0f} "
              f"{epsilon_seconds * 1e3:>7.2f} {hull_seconds * 1e3:>8.2f} "
              f"{epsilon_seconds / hull_seconds:>6.2f}")


if __name__ == "__main__":
    main()
