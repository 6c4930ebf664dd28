"""Generated novel objects through whole trials: does any end in a simulation error?

Issue 12's acceptance check, as a user would run it and resumable like every sweep: N objects of the
novel-object generator (`drake-grasp objects generate`), each through every oracle grasp (spherical,
cylindrical, box, from the true pose) and one trial of the whole compliance-centric algorithm (camera
only, its own choice), with the default scenario (the full 10 s hold) and seed 0. A failed grasp is
fine; a simulation error is not. Prints and writes (with --report) the counts of outcomes, per
method and per object class, and each simulation error and perception failure with its detail (a
perception failure is an outcome of its own: the camera's estimate could not place a grasp).

Run: .venv/bin/python scripts/novel_objects_check.py [--count 40] [--seed 0] [--workers 2]
     [--out out/novel-check] [--report docs/results/novel_objects_check.md]
"""

import argparse
import collections
import pathlib
import time

from drake_grasp.sweeps.executors import LocalExecutor
from drake_grasp.studies.novel import ensure_objects
from drake_grasp.sweeps.results import write_atomically
from drake_grasp.sweeps.runner import TrialSpec, run_trials
from drake_grasp.trial import PERCEPTION_FAILED, SIMULATION_ERROR

GRASPS = ("spherical", "cylindrical", "box")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=40)
    parser.add_argument("--seed", type=int, default=0, help="the generator's seed")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", default="out/novel-check")
    parser.add_argument("--report", help="write the summary as Markdown here")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    start = time.perf_counter()
    objects = ensure_objects(out / "objects", args.count, args.seed)
    specs = [TrialSpec(o["file"], "oracle", g, 0) for o in objects for g in GRASPS]
    specs += [TrialSpec(o["file"], "compliant", "", 0) for o in objects]
    rows = run_trials(specs, out / "trials.csv", executor=LocalExecutor(args.workers), label="check")
    wall = time.perf_counter() - start
    shape_class = {o["file"]: o["class"] for o in objects}
    outcomes = collections.Counter()
    per_class = collections.defaultdict(collections.Counter)
    crashed, unperceived = [], []
    for r in rows:
        outcome = "success" if str(r["success"]) in ("1", "True") else r["failure"]
        method = "oracle" if r["method"] == "oracle" else "compliant (camera, own choice)"
        outcomes[(method, outcome)] += 1
        per_class[shape_class[r["object"]]][outcome] += 1
        if r["failure"] == SIMULATION_ERROR:
            crashed.append(f"{pathlib.Path(r['object']).name} {r['method']}/{r['grasp'] or 'own'}: {r['detail']}")
        if r["failure"] == PERCEPTION_FAILED:
            unperceived.append(f"{pathlib.Path(r['object']).name} {r['method']}/{r['grasp'] or 'own'}: {r['detail']}")
    errors = sum(n for (_, outcome), n in outcomes.items() if outcome == SIMULATION_ERROR)
    lines = [f"# Novel objects through whole trials ({len(objects)} objects, generator seed {args.seed})", "",
             f"Made by `scripts/novel_objects_check.py --count {args.count} --seed {args.seed}`: every oracle grasp "
             "and one camera-driven trial of the algorithm per object, default scenario (10 s hold), trial seed 0. "
             f"{len(rows)} trials, {wall:.0f} s wall on {args.workers} workers.", "",
             f"**Simulation errors: {errors} of {len(rows)} trials.**", "",
             "| method | outcome | trials |", "|---|---|---|"]
    lines += [f"| {m} | {o} | {n} |" for (m, o), n in sorted(outcomes.items())]
    lines += ["", "| class | " + " | ".join(sorted({o for c in per_class.values() for o in c})) + " |"]
    names = sorted({o for c in per_class.values() for o in c})
    lines += ["|---|" + "---|" * len(names)]
    lines += [f"| {c} | " + " | ".join(str(per_class[c][n]) for n in names) + " |" for c in sorted(per_class)]
    if crashed:
        lines += ["", "Simulation errors:", *[f"- {c}" for c in crashed]]
    if unperceived:
        lines += ["", "Perception failures:", *[f"- {c}" for c in unperceived]]
    text = "\n".join(lines) + "\n"
    print(text)
    if args.report:
        write_atomically(pathlib.Path(args.report), text)
    return 0 if errors == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
