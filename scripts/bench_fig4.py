#!/usr/bin/env python3
"""Benchmark of the Fig. 4 machinery: quasi-static grasps per second, and the full sweep's wall time.

    .venv/bin/python scripts/bench_fig4.py [--skip-sweep] [--workers N]

The ε metric's own benchmark (against a bare qhull call) is scripts/bench_quality.py.
"""

import argparse
import math
import os
import pathlib
import tempfile
import time

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from drake_grasp.studies import fig4
from drake_grasp.robot.hand import ComplianceMode
from drake_grasp.objects import cube_object, cylinder_object, sphere_object
from drake_grasp.quality import grasp_quality
from drake_grasp.quasistatic import QuasiStaticHand


def grasps_per_second(spec, mode, n=200, seed=0):
    """Quasi-static grasps (approach + close) per second from random lateral offsets, one core."""
    rng = np.random.default_rng(seed)
    sim = QuasiStaticHand(spec)
    R = RotationMatrix.MakeXRotation(math.pi)
    poses = [RigidTransform(R, [*rng.uniform(-0.03, 0.03, 2), 0.4]) for _ in range(n)]
    start = time.perf_counter()
    epsilons = []
    for X in poses:
        g = sim.grasp(X, mode)
        p, nrm = g.contact_arrays()
        epsilons.append(grasp_quality(p, nrm, 0.5, np.zeros(3), spec.max_radius).epsilon)
    elapsed = time.perf_counter() - start
    return n / elapsed, float(np.mean(epsilons))


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--skip-sweep", action="store_true")
    parser.add_argument("--workers", type=int, default=os.cpu_count())
    args = parser.parse_args()
    print("quasi-static grasp + eps, one core:")
    for spec, mode in [(sphere_object(0.12), ComplianceMode.SPHERICAL), (cube_object(0.06), ComplianceMode.CYLINDRICAL),
                       (cylinder_object(0.10), ComplianceMode.CYLINDRICAL)]:
        rate, eps = grasps_per_second(spec, mode)
        print(f"  {spec.name:24s} {rate:7.1f} grasps/s   (mean eps {eps:.3f})")
    if args.skip_sweep:
        return
    with tempfile.TemporaryDirectory() as tmp:
        config = fig4.Fig4Config.full()
        start = time.perf_counter()
        rows = fig4.run_fig4(config, pathlib.Path(tmp), workers=args.workers, progress=open(os.devnull, "w"))
        fig4.plot(fig4.summarise(rows), pathlib.Path(tmp))
        wall = time.perf_counter() - start
    print(f"full fig4: {len(rows)} grasps, {args.workers} workers, {wall:.1f} s wall (target: < 300 s on 2 cores)")


if __name__ == "__main__":
    main()
