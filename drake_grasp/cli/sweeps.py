"""The sweep commands: fig4, fig6, fig7, novel, reproduce.

Each runs many trials (or quasi-static grasps) on an executor (local processes or Ray), resumably,
into a results folder it holds the lock of, and prints a summary (or one JSON object with --json).
"""

import dataclasses
import json
import os
import pathlib
import sys
import time

from drake_grasp.cli.common import (UsageError, add_common, add_executor_args, add_mesh_options, check_out_dir,
                                    check_planner_args, check_seed, jsonable, load_scenario_arg, mesh_option_args,
                                    object_list_argument)


def add_fig4(sub) -> None:
    """`drake-grasp fig4`."""
    fig4 = sub.add_parser(
        "fig4",
        help="Fig. 4: quasi-static grasps of spheres, cubes, cylinders and plates; eps over size and pose error",
        description="Sweeps object size and hand pose error for spheres (spherical mode), cubes and "
        "cylinders (cylindrical mode), and, for the flower, plates 4-40 mm thick on a table (the precision "
        "grasp that the flower grasp replaced, palm held by position): approach until contact, close with "
        "breakaway, score with the eps metric. Then the flower in full dynamics: the flower grasp on plates, "
        "sticks and small cubes, each a trial from the true pose shifted along x or y. Writes fig4.csv "
        "(one row per grasp), fig4.png and fig4.svg, fig4_flower.csv (one row per trial), fig4_flower.png "
        "and fig4_flower.svg; resumable.",
    )
    fig4.add_argument("--quick", action="store_true",
                      help="9 sizes (4 plate thicknesses) x 7 errors instead of 27 (10) x 21; the flower: 3 sizes "
                      "per family x 5 errors x 1 seed instead of 5 x 13 x 2")
    add_executor_args(fig4)
    add_common(fig4, scenario=False, seed=False)
    fig4.set_defaults(run=_run_fig4, out_default="out/fig4")


def add_fig6(sub) -> None:
    """`drake-grasp fig6`."""
    fig6 = sub.add_parser(
        "fig6",
        help="Fig. 6: each compliant grasp's shape resemblance against its success, 9 objects",
        description="For each object and each of the three compliant grasps, N trials of 'explore with "
        "the wrist camera, then execute that grasp'. Writes fig6.csv (one row per trial, as they finish; "
        "rerun to resume), fig6.png and fig6.svg, and a summary beside the paper's 95.6% (86/90).",
    )
    fig6.add_argument("--quick", action="store_true", help="4 objects x 3 grasps x 2 trials")
    fig6.add_argument("--trials", type=int, help="trials per object and grasp (default 10)")
    add_mesh_options(fig6)
    fig6.add_argument("--objects", metavar="NAME|PATH,...", type=object_list_argument,
                      help="comma-separated objects instead of the paper's nine (catalogue names, primitives "
                      "such as sphere:0.12, or mesh files): the same study on your own objects")
    add_executor_args(fig6)
    fig6.add_argument("--method", choices=["compliant", "oracle"], default="compliant",
                      help="compliant: camera estimates (the paper's algorithm); oracle: ground truth")
    add_common(fig6, scenario="objects")
    fig6.set_defaults(run=_run_fig6, out_default="out/fig6")


def add_fig7(sub) -> None:
    """`drake-grasp fig7`."""
    fig7 = sub.add_parser(
        "fig7",
        help="Fig. 7: the compliance-centric algorithm against GraspIt!'s Eigengrasp planner",
        description="Plans each of six objects with the Eigengrasp planner (exact model and pose), "
        "executes its three best grasps N times each through the same trial runner and success test as "
        "the compliance-centric trials (reused from Fig. 6's results when present), and plots per object "
        "the compliance-centric success, the planner's average and its best grasp. Resumable.",
    )
    fig7.add_argument("--quick", action="store_true", help="2 objects, 2 trials per grasp")
    fig7.add_argument("--trials", type=int, help="executions of each planned grasp (default 10)")
    add_mesh_options(fig7)
    fig7.add_argument("--objects", metavar="NAME|PATH,...", type=object_list_argument,
                      help="comma-separated objects instead of the paper's six (catalogue names, primitives "
                      "or mesh files): compare the two methods on your own objects")
    add_executor_args(fig7)
    fig7.add_argument("--steps", type=int, default=70_000,
                      help="planner steps, GraspIt!'s counter (default 70000 = 40000 annealing iterations)")
    fig7.add_argument("--energy", choices=["contact", "contact-quality"], default="contact-quality",
                      help="the planner's energy (default: contact-quality, GraspIt!'s 'Contacts AND Quality', "
                      "today's GUI default and the stronger baseline here; contact = 'Hand Contacts')")
    fig7.add_argument("--fig6", metavar="DIR", default="out/fig6",
                      help="where Fig. 6's results are reused from (default out/fig6)")
    fig7.add_argument("--compliant-method", choices=["compliant", "oracle"], default="compliant",
                      help="estimates for compliance-centric trials run here (default: the camera)")
    add_common(fig7, scenario="objects")
    fig7.set_defaults(run=_run_fig7, out_default="out/fig7")


def add_novel(sub) -> None:
    """`drake-grasp novel`."""
    novel = sub.add_parser(
        "novel",
        help="beyond the paper: both methods on generated novel objects",
        description="Generates (or reuses) novel objects (blobs, unions of primitives, plates, L and T "
        "shapes, rings and handles, 3-25 cm), runs the compliance-centric algorithm (camera only, all three "
        "grasps, the chosen one marked) and the Eigengrasp planner (its three best reachable grasps) on them "
        "through the runner, seeds and success test of Fig. 6 and Fig. 7, and writes novel.csv, novel.png "
        "and summary.md (per object and per class, 95 %% intervals, failure reasons). Resumable.",
    )
    novel.add_argument("--quick", action="store_true", help="3 objects, 1 trial per grasp, 40000 planner steps")
    novel.add_argument("--count", type=int, help="novel objects (default 20; quick 3)")
    novel.add_argument("--trials", type=int, help="executions of each grasp, both methods (default 5; quick 1)")
    novel.add_argument("--object-seed", type=int, default=0, help="the generator's seed (default 0)")
    add_executor_args(novel)
    novel.add_argument("--energy", choices=["contact", "contact-quality"], default="contact-quality",
                       help="the Eigengrasp planner's energy (default contact-quality)")
    add_common(novel, scenario="best")
    novel.set_defaults(run=_run_novel, out_default="out/novel")


def add_reproduce(sub) -> None:
    """`drake-grasp reproduce`."""
    reproduce = sub.add_parser(
        "reproduce",
        help="Fig. 4, 6 and 7 and a report of the paper's claims against ours",
        description="Runs (or resumes) the three experiments under --out and writes report.md: each claim "
        "of the paper, its number, ours, and whether ours agrees; beyond the paper, both methods on novel "
        "objects; and report.html, the results page with replays. --quick takes about 10 minutes on 2 cores.",
    )
    reproduce.add_argument("--quick", action="store_true", help="few sizes, objects and trials")
    add_executor_args(reproduce)
    reproduce.add_argument("--energy", choices=["contact", "contact-quality"], default="contact-quality",
                           help="the Eigengrasp planner's energy for Fig. 7")
    reproduce.add_argument("--seed", type=int, default=0, help="first trial seed (default 0)")
    reproduce.add_argument("--out", metavar="DIR", help="output folder (default out/reproduce[-quick])")
    reproduce.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    reproduce.set_defaults(run=_run_reproduce)


def check_sweep_args(args):
    """Rejects bad sweep arguments before any work starts; returns the executor the sweep runs on
    (a context manager: Ray, if started, is shut down on leaving it)."""
    from drake_grasp.sweeps.executors import EXECUTORS, make_executor

    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers must be >= 1, got {args.workers}")
    if getattr(args, "trials", None) is not None and args.trials < 1:
        raise UsageError(f"--trials must be >= 1, got {args.trials}")
    if hasattr(args, "seed"):
        check_seed(args.seed, getattr(args, "trials", None) or (2 if args.quick else 10))
    if args.executor not in EXECUTORS:
        raise UsageError(f"unknown --executor {args.executor!r} (choose from {', '.join(EXECUTORS)})")
    if args.ray_address is not None and args.executor != "ray":
        raise UsageError("--ray-address needs --executor ray")
    if args.ray_address is not None and args.workers is not None:
        raise UsageError("--workers does not apply with --ray-address (the cluster's CPUs decide)")
    if args.ray_address is not None and not args.ray_address.strip():
        raise UsageError("--ray-address is empty")
    cores = os.cpu_count() or 1
    if args.workers is not None and args.workers > cores:
        print(f"drake-grasp {args.command}: note: --workers {args.workers} is more than this machine's {cores} "
              f"cores; using {cores}", file=sys.stderr)
        args.workers = cores
    return make_executor(args.executor, args.workers, args.ray_address)


def scenario_args(args) -> tuple[str, str]:
    load_scenario_arg(args)  # reject a bad scenario before any worker starts
    return (str(pathlib.Path(args.scenario).resolve()) if args.scenario else ""), args.scenario_name


def objects_arg(args, default: tuple[str, ...]) -> tuple[str, ...]:
    """--objects as a tuple (each resolved once here, with the mesh options, so that a bad one is a
    one-line error before any worker starts), or `default`. `--scale` and `--largest-component`
    apply to the mesh files among them; given with no mesh file at all, they are an error."""
    from drake_grasp.objects.names import mesh_options, options_for, resolve_user_object

    objects = tuple(default)
    if args.objects is not None:
        objects = tuple(o.strip() for o in args.objects.split(",") if o.strip())
        if not objects:
            raise UsageError("--objects needs at least one object")
        if len(set(objects)) != len(objects):
            raise UsageError(f"--objects names an object twice: {args.objects}")
    options = mesh_options(args.scale, args.largest_component, getattr(args, "join_gap", None),
                           getattr(args, "inertia", "check"), getattr(args, "package_path", None) or ())
    for option in options:
        if not any(option in options_for(o, **options) for o in objects):
            raise UsageError(f"--{option.replace('_', '-')} applies to object files (mesh or model files) that take "
                             "it, and --objects names none")
    if args.objects is not None:
        for o in objects:
            resolve_user_object(o, **options_for(o, **options))
    return objects



def _run_fig4(args) -> int:
    from drake_grasp.studies import fig4, fig4_flower
    from drake_grasp.sweeps.lock import results_lock
    from drake_grasp.sweeps.results import check_results_file
    from drake_grasp.sweeps.runner import TRIAL_FIELDS

    executor = check_sweep_args(args)
    config = fig4.Fig4Config.quick() if args.quick else fig4.Fig4Config.full()
    flower = fig4_flower.FlowerConfig.quick() if args.quick else fig4_flower.FlowerConfig.full()
    out = check_out_dir(args.out or args.out_default)
    start = time.perf_counter()
    with results_lock(out), executor:
        check_results_file(out / "fig4.csv", fig4.FIELDS)
        check_results_file(out / "fig4_flower.csv", TRIAL_FIELDS)
        rows = fig4.run_fig4(config, out, executor=executor)
        summaries = fig4.summarise(rows)
        figures = fig4.plot(summaries, out)
        flower_results = fig4_flower.run_flower(flower, out, executor=executor)
        flower_maps = fig4_flower.summarise(flower_results)
        figures += fig4_flower.plot(flower_maps, out)
    lines = fig4.summary_lines(summaries, rows) + fig4_flower.summary_lines(flower_maps, flower_results)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps({
            "csv": str(out / "fig4.csv"), "flower_csv": str(out / "fig4_flower.csv"),
            "figures": [str(p) for p in figures], "grasps": len(rows), "flower_trials": len(flower_results),
            "wall_time": wall, "peak_size": {k: s.peak_size() for k, s in summaries.items()}, "summary": lines,
        }))
    else:
        for line in lines:
            print(line)
        print(f"fig4: {len(rows)} quasi-static grasps and {len(flower_results)} flower trials in {wall:.0f} s; "
              f"{out / 'fig4.csv'}, {out / 'fig4_flower.csv'}, {figures[0]}, {figures[2]}")
    return 0



def _run_fig6(args) -> int:
    from drake_grasp.studies import fig6
    from drake_grasp.objects import PAPER_OBJECTS

    executor = check_sweep_args(args)
    scenario_file, scenario_name = scenario_args(args)
    objects = objects_arg(args, fig6.QUICK_OBJECTS if args.quick else PAPER_OBJECTS)
    trials = args.trials or (2 if args.quick else 10)
    config = fig6.Fig6Config(objects=tuple(objects), trials=trials, seed=args.seed, method=args.method,
                             scale=args.scale, largest_component=args.largest_component, join_gap=args.join_gap,
                             inertia=args.inertia, package_path=mesh_option_args(args)["package_path"])
    out = check_out_dir(args.out or args.out_default)
    start = time.perf_counter()
    with executor:
        _, figures, lines, count = fig6.run_sweep(config, out, scenario_file=scenario_file,
                                                  scenario_name=scenario_name, executor=executor)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps({"csv": str(out / "fig6.csv"), "figures": [str(p) for p in figures], "trials": count,
                          "wall_time": wall, "summary": lines}))
    else:
        print("\n".join(lines))
        print(f"fig6: {count} trials, {wall:.0f} s; {out / 'fig6.csv'}, {figures[0]}, {figures[1]}")
    return 0


def _run_fig7(args) -> int:
    from drake_grasp.studies import fig7

    executor = check_sweep_args(args)
    check_planner_args(str(args.steps), args.energy)
    scenario_file, scenario_name = scenario_args(args)
    fig6_dir = pathlib.Path(args.fig6)
    if fig6_dir.exists() and not fig6_dir.is_dir():
        raise UsageError(f"--fig6 {args.fig6}: exists and is not a directory")
    trials = args.trials or (2 if args.quick else 10)
    config = fig7.Fig7Config(objects=objects_arg(args, fig7.QUICK_OBJECTS if args.quick else fig7.OBJECTS),
                             trials=trials,
                             seed=args.seed, steps=args.steps, energy=args.energy,
                             compliant_method=args.compliant_method, scale=args.scale,
                             largest_component=args.largest_component, join_gap=args.join_gap,
                             inertia=args.inertia, package_path=mesh_option_args(args)["package_path"])
    out = check_out_dir(args.out or args.out_default)
    start = time.perf_counter()
    with executor:
        comparison, figures, lines = fig7.run_comparison(config, out, fig6_dir,
                                                         scenario_file=scenario_file, scenario_name=scenario_name,
                                                         executor=executor)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps(jsonable({"csv": str(out / "fig7.csv"), "figures": [str(p) for p in figures],
                                   "comparison": [dataclasses.asdict(c) for c in comparison],
                                   "wall_time": wall, "summary": lines})))
    else:
        print("\n".join(lines))
        print(f"fig7: {wall:.0f} s; {out / 'fig7.csv'}, {figures[0]}, {figures[1]}")
    return 0


def _run_novel(args) -> int:
    from drake_grasp.studies import novel

    executor = check_sweep_args(args)
    scenario_file, scenario_name = scenario_args(args)
    if args.count is not None and args.count < 1:
        raise UsageError(f"--count must be >= 1, got {args.count}")
    if not 0 <= args.object_seed < 2**32:
        raise UsageError(f"--object-seed must be in [0, 2^32), got {args.object_seed}")
    overrides = {k: v for k, v in (("count", args.count), ("trials", args.trials)) if v is not None}
    overrides.update(seed=args.seed, object_seed=args.object_seed, energy=args.energy)
    config = novel.NovelConfig.quick(**overrides) if args.quick else novel.NovelConfig(**overrides)
    out = check_out_dir(args.out or (args.out_default + ("-quick" if args.quick else "")))
    start = time.perf_counter()
    with executor:
        objects = novel.ensure_objects(out / "objects", config.count, config.object_seed)
        rows, figures, lines = novel.run_study(config, out, objects, executor, scenario_file=scenario_file,
                                               scenario_name=scenario_name)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps(jsonable({"csv": str(out / "novel.csv"), "summary_md": str(out / "summary.md"),
                                   "figures": [str(p) for p in figures], "wall_time": wall,
                                   "rows": [dataclasses.asdict(r) for r in rows]})))
    else:
        print(lines[0])
        print(f"novel: {len(rows)} objects, {wall:.0f} s; {out / 'summary.md'}, {out / 'novel.csv'}, {figures[0]}")
    return 0


def _run_reproduce(args) -> int:
    from drake_grasp.studies import reproduce

    executor = check_sweep_args(args)
    out = check_out_dir(args.out or ("out/reproduce-quick" if args.quick else "out/reproduce"))
    with executor:
        report, claims, wall = reproduce.run(out, args.quick, seed=args.seed, energy=args.energy, executor=executor)
    if args.json:
        print(json.dumps({"report": str(report), "wall_time": wall,
                          "claims": [dataclasses.asdict(c) for c in claims]}))
    else:
        for c in claims:
            print(f"[{c.agrees:>6}] {c.claim}: paper {c.paper}; ours {c.ours}")
        print(f"reproduce: {sum(c.agrees == 'yes' for c in claims)}/{len(claims)} claims agree; "
              f"{wall:.0f} s; report {report}")
    return 0

