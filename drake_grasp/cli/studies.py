"""The studies beyond the paper: capture (how much estimate error a grasp absorbs, in full dynamics),
sensitivity (the chosen grasps under other friction, mass and perception), near-primitives (shape
resemblance on almost-spheres, -boxes and -cylinders) and exploration (the paper's proposed minimal
exploration against the full one).

Like the sweeps (`sweeps`), each runs many trials on an executor, resumably, into a results folder it
holds the lock of, and prints a summary (or one JSON object with --json).
"""

import json
import time

from drake_grasp.cli.common import (UsageError, add_common, add_executor_args, check_out_dir, check_planner_args, jsonable,
                                    object_list_argument)
from drake_grasp.cli.sweeps import check_sweep_args, objects_arg, scenario_args


def add_capture(sub) -> None:
    """`drake-grasp capture`."""
    capture = sub.add_parser(
        "capture",
        help="beyond the paper: capture regions, the estimate errors a grasp still succeeds from (full dynamics)",
        description="For each object and compliant grasp, trials whose grasp is computed from the true pose "
        "and size with a known error added (along and across the object's axis, yaw, size), executed on the "
        "true object; the same errors applied to the Eigengrasp planner's best reachable grasp. Each error "
        "plane is sampled adaptively (a coarse grid, then cells whose corners disagree are split). Writes "
        "capture.csv (resumable), capture.png (success maps), summary.md and summary.json (region areas).",
    )
    capture.add_argument("--quick", action="store_true",
                         help="soccer ball and sponge, the grasp each resembles, the position plane, a 2 x 2 "
                         "grid refined once (about 10 minutes on 2 cores)")
    capture.add_argument("--objects", metavar="NAME|PATH,...", type=object_list_argument,
                         help="comma-separated objects (default: the paper's nine)")
    capture.add_argument("--grasps", metavar="GRASP,...",
                         help="compliant grasps to map: spherical, cylindrical, box, or chosen (the grasp of the "
                         "object's closest primitive); default all three")
    capture.add_argument("--planes", metavar="PLANE,...",
                         help="error planes: position (along x across, cm), yaw (across, cm x yaw, deg), size "
                         "(across, cm x size, %%); default all")
    capture.add_argument("--methods", metavar="METHOD,...",
                         help="oracle (compliant grasps from the erred estimate) and/or eigengrasp (the planner's "
                         "best reachable grasp, shifted); default both")
    capture.add_argument("--max-offset", type=float, default=4.0, help="position errors span +-this, cm (default 4)")
    capture.add_argument("--max-yaw", type=float, default=30.0, help="yaw errors span +-this, deg (default 30)")
    capture.add_argument("--max-size", type=float, default=30.0, help="size errors span +-this, %% (default 30)")
    capture.add_argument("--base", type=int, help="coarse grid cells per side (default 2)")
    capture.add_argument("--depth", type=int, help="refinement levels (default 1)")
    capture.add_argument("--steps", type=int, default=70_000, help="planner steps (default 70000)")
    capture.add_argument("--energy", choices=["contact", "contact-quality"], default="contact-quality",
                         help="the planner's energy (default contact-quality)")
    add_executor_args(capture)
    add_common(capture)
    capture.set_defaults(run=_run_capture, out_default="out/capture")


def _names(text: str | None, option: str) -> tuple[str, ...] | None:
    if text is None:
        return None
    names = tuple(n.strip() for n in text.split(",") if n.strip())
    if not names:
        raise UsageError(f"{option} is empty")
    return names


def _run_capture(args) -> int:
    from drake_grasp.studies import capture
    from drake_grasp.objects import PAPER_OBJECTS

    executor = check_sweep_args(args)
    check_planner_args(str(args.steps), args.energy)
    scenario_file, scenario_name = scenario_args(args)
    for option, value in (("--max-offset", args.max_offset), ("--max-yaw", args.max_yaw), ("--max-size", args.max_size)):
        if not 0 < value < 1e3:
            raise UsageError(f"{option} must be > 0, got {value}")
    if args.max_size >= 100:
        raise UsageError(f"--max-size must be below 100 %, got {args.max_size}")
    args.scale, args.largest_component = 1.0, False  # no mesh options here: objects_arg checks them
    args.join_gap, args.inertia = None, "check"
    base = capture.CaptureConfig.quick(seed=args.seed) if args.quick else capture.CaptureConfig(objects=PAPER_OBJECTS)
    overrides = {
        "objects": objects_arg(args, base.objects), "seed": args.seed, "steps": args.steps, "energy": args.energy,
        "offset_cm": (-args.max_offset, args.max_offset), "yaw_deg": (-args.max_yaw, args.max_yaw),
        "size_pct": (-args.max_size, args.max_size),
    }
    for key, option in (("grasps", "--grasps"), ("planes", "--planes"), ("methods", "--methods")):
        names = _names(getattr(args, key), option)
        if names is not None:
            overrides[key] = names
    for key in ("base", "depth"):
        if getattr(args, key) is not None:
            overrides[key] = getattr(args, key)
    config = capture.CaptureConfig(**{**base.__dict__, **overrides})
    out = check_out_dir(args.out or (args.out_default + ("-quick" if args.quick else "")))
    start = time.perf_counter()
    with executor:
        maps, lines = capture.run(config, out, executor, scenario_file=scenario_file,
                                  scenario_name=scenario_name)
    wall = time.perf_counter() - start
    trials = sum(len(results) for _, results in maps.values())
    if args.json:
        print(json.dumps(jsonable({"csv": str(out / "capture.csv"), "summary_md": str(out / "summary.md"),
                                   "figure": str(out / "capture.png"), "trials": trials, "wall_time": wall,
                                   "summary": lines})))
    else:
        print("\n".join(lines))
        print(f"capture: {len(maps)} maps, {trials} trials, {wall:.0f} s; {out / 'summary.md'}, {out / 'capture.png'}")
    return 0


def add_near_primitives(sub) -> None:
    """`drake-grasp near-primitives`."""
    study = sub.add_parser(
        "near-primitives",
        help="beyond the paper: is shape resemblance right on near-primitives (ellipsoids, rounded boxes, "
        "tapered cylinders)?",
        description="Generates near-primitives (ellipsoids within 10 %% of a sphere, rounded boxes, tapered and "
        "rounded cylinders; COUNT per class) for a development and an evaluation seed and explores each with "
        "the wrist camera as `resemble` does, beside the perfect primitives and the paper's nine objects. "
        "Writes explorations.csv (resumable), summary.md (per-class accuracy with 95 %% intervals, confusion "
        "tables) and near_primitives.png.",
    )
    study.add_argument("--count", type=int, default=10, help="near-primitives per class and seed (default 10)")
    study.add_argument("--object-seed", type=int, default=0, help="the development set's generator seed (default 0)")
    study.add_argument("--eval-seed", type=int, default=1, help="the evaluation set's generator seed (default 1)")
    study.add_argument("--reference-seeds", type=int, default=3, metavar="N",
                       help="trial seeds 0..N-1 for the perfect primitives and the paper's objects (default 3)")
    study.add_argument("--skip-catalogue", action="store_true", help="leave out the paper's nine objects")
    study.add_argument("--development-only", action="store_true",
                       help="leave out the evaluation set (while a scorer is being developed on the other)")
    add_executor_args(study)
    add_common(study, scenario=False, seed=False)
    study.set_defaults(run=_run_near_primitives, out_default="out/near-primitives")


def _run_near_primitives(args) -> int:
    from drake_grasp.studies.near_primitives import StudyConfig, run_study

    args.seed, args.quick = 0, False  # the trial seeds are 0..N-1 (--reference-seeds)
    executor = check_sweep_args(args)
    config = StudyConfig(count=args.count, seed=args.object_seed, eval_seed=args.eval_seed,
                         reference_seeds=args.reference_seeds, catalogue=not args.skip_catalogue,
                         development_only=args.development_only)
    config.validate()
    out = check_out_dir(args.out or args.out_default)
    start = time.perf_counter()
    with executor:
        text = run_study(config, out, executor, label="near-primitives")
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps({"summary_md": str(out / "summary.md"), "csv": str(out / "explorations.csv"),
                          "wall_time": wall}))
    else:
        print(text)
        print(f"near-primitives: {wall:.0f} s; {out / 'summary.md'}")
    return 0


def add_sensitivity(sub) -> None:
    """`drake-grasp sensitivity`."""
    study = sub.add_parser(
        "sensitivity",
        help="beyond the paper: the chosen grasps under other friction, object mass and perception",
        description="The algorithm's own grasp on each object, camera-driven, under one changed factor at a time: "
        "the object's friction coefficient (0.3, 0.8, 1.0; Drake combines it with the hand's 0.5), its mass "
        "(x0.5, x2), colour segmentation with and without image noise. Each condition is a named scenario "
        "in conditions.yaml. Writes sensitivity.csv (resumable), summary.md (rates with 95 %% intervals, "
        "which of the paper's claims hold or flip) and sensitivity.png.",
    )
    study.add_argument("--quick", action="store_true", help="3 objects (apple, banana, soccer ball), 1 trial each")
    study.add_argument("--objects", metavar="NAME|PATH,...", type=object_list_argument, help="comma-separated objects (default: the paper's nine)")
    study.add_argument("--trials", type=int, help="trials per object and condition (default 4; quick 1)")
    study.add_argument("--conditions", metavar="NAME,...", help="conditions to run (default: all; see --list)")
    study.add_argument("--noise-sigma", type=float, help="image noise of the noisy colour condition, 8-bit counts "
                       "(default 10)")
    study.add_argument("--list", action="store_true", help="list the conditions and exit")
    add_executor_args(study)
    add_common(study)
    study.set_defaults(run=_run_sensitivity, out_default="out/sensitivity")


def _sensitivity_config(args):
    """The SensitivityConfig the arguments ask for (UsageError or ValueError, one line, if bad)."""
    from drake_grasp.studies import sensitivity

    trials = args.trials or (1 if args.quick else 4)
    sigma = sensitivity.DEFAULT_NOISE_SIGMA if args.noise_sigma is None else args.noise_sigma
    if not 0 <= sigma < float("inf"):
        raise UsageError(f"--noise-sigma must be a finite number >= 0, got {args.noise_sigma}")
    conditions = sensitivity.default_conditions(noise_sigma=sigma)
    names = _names(args.conditions, "--conditions")
    if names is not None:
        known = {c.name: c for c in conditions}
        unknown = [n for n in names if n not in known]
        if unknown:
            raise UsageError(f"--conditions: unknown {', '.join(unknown)} (choose from {', '.join(known)})")
        conditions = tuple(known[n] for n in dict.fromkeys(names))
    args.scale, args.largest_component = 1.0, False  # no mesh options here: objects_arg checks them
    args.join_gap, args.inertia = None, "check"
    objects = objects_arg(args, sensitivity.QUICK_OBJECTS if args.quick else ())
    scenario_file, scenario_name = scenario_args(args)
    return sensitivity.SensitivityConfig(objects=objects, trials=trials, seed=args.seed, conditions=conditions,
                                         scenario_file=scenario_file, scenario_name=scenario_name)


def _run_sensitivity(args) -> int:
    from drake_grasp.studies import sensitivity
    from drake_grasp.studies.sensitivity_report import totals
    from drake_grasp.sweeps.stats import format_rate

    executor = check_sweep_args(args)
    config = _sensitivity_config(args)
    if args.list:
        for c in config.conditions:
            print(f"{c.name}: {c.label}")
        return 0
    out = check_out_dir(args.out or (args.out_default + ("-quick" if args.quick else "")))
    start = time.perf_counter()
    with executor:
        result = sensitivity.run_sensitivity(config, out, args.workers, executor)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps(jsonable({"summary_md": str(result.summary), "figures": [str(p) for p in result.figures],
                                   "trials": result.trials, "wall_time": wall})))
        return 0
    for c in config.conditions:
        print(f"{c.label}: chosen grasps {format_rate(*totals(result.table[c.name]))}")
    for r in result.claims:
        print(f"{r.claim}: {r.across(config.conditions)}")
    print(f"sensitivity: {result.trials} trials, {wall:.0f} s; {result.summary}, {result.figures[0]}")
    return 0


def add_exploration(sub) -> None:
    """`drake-grasp exploration`."""
    study = sub.add_parser(
        "exploration",
        help="beyond the paper: its proposed minimal exploration (a hypothesis, one confirming arc) against "
        "the full one",
        description="Runs the compliance-centric algorithm after the full exploration (scenario table_top) and "
        "after the paper's proposed minimal one (scenario minimal_exploration: a shape hypothesis from the "
        "first views, one arc that confirms it, the full exploration when it does not) on the same objects "
        "and seeds: the paper's nine, near-primitives, novel objects and the flower. Writes full/trials.csv "
        "and minimal/trials.csv (resumable), exploration.png and summary.md: the same chosen grasp, success "
        "of each (95 %% intervals), exploration time and camera path (median, worst), fallbacks and why.",
    )
    study.add_argument("--quick", action="store_true",
                       help="four of the paper's objects, one trial each (a few minutes on 2 cores)")
    study.add_argument("--trials", type=int, help="trials per object and exploration (default 2; quick 1)")
    study.add_argument("--near", type=int, help="near-primitives (default 4; quick 0)")
    study.add_argument("--novel", type=int, help="novel objects (default 7; quick 0)")
    study.add_argument("--flower", type=int, help="flower objects (default 6; quick 0)")
    study.add_argument("--object-seed", type=int, default=0, help="the generators' seed (default 0)")
    add_executor_args(study)
    add_common(study, scenario=False)
    study.set_defaults(run=_run_exploration, out_default="out/exploration")


def _run_exploration(args) -> int:
    from drake_grasp.studies.exploration import ExplorationConfig, run_study

    executor = check_sweep_args(args)
    given = {k: v for k, v in (("trials", args.trials), ("near", args.near), ("novel", args.novel),
                               ("flower", args.flower)) if v is not None}
    try:
        base = ExplorationConfig.quick if args.quick else ExplorationConfig
        config = base(seed=args.seed, object_seed=args.object_seed, **given)
    except ValueError as e:
        raise UsageError(str(e)) from None
    out = check_out_dir(args.out or (args.out_default + ("-quick" if args.quick else "")))
    start = time.perf_counter()
    with executor:
        rows, lines, figures = run_study(config, out, executor)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps(jsonable({"summary_md": str(out / "summary.md"), "figures": [str(p) for p in figures],
                                   "pairs": len(rows), "wall_time": wall})))
        return 0
    print("\n".join(lines))
    print(f"exploration: {len(rows)} trial pairs, {wall:.0f} s; {out / 'summary.md'}, {figures[0]}")
    return 0

