"""The `drake-grasp` command.

Every subcommand prints a one-line summary (or one JSON object with --json) and takes --out (and
--seed where a run has randomness). Exit codes are a contract: 2 for bad input (an unknown object, a
broken mesh, a malformed scenario, a number out of range, an output path that cannot be written, a
results folder another run holds), reported as one line on stderr before any work starts, never a
traceback; 1 for a run that could not be carried out; 130 for Ctrl-C and 143 for SIGTERM (both stop
the run's workers).
"""

import argparse
import dataclasses
import json
import math
import os
import pathlib
import signal
import sys
import threading
import time

from drake_grasp.hand import ComplianceMode


class UsageError(ValueError):
    """Bad input from the command line: reported in one line, exit code 2."""


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that it unwinds like Ctrl-C (workers stopped, locks
    released); exit code 143."""


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="drake-grasp",
        description="Compliance-centric grasping (BarrettHand on a Barrett WAM) in Drake.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    demo = sub.add_parser(
        "demo",
        help="pick an object up with the hand's compliance (ground-truth pose)",
        description="The arm brings the open hand above the object (its true pose), descends, closes "
        "the fingers (torque close with breakaway), lifts 10 cm and holds 10 s; prints whether the "
        "object was held and how much it slipped in the hand.",
    )
    _mesh_options(demo)
    demo.add_argument("--object", required=True, metavar="NAME|PATH",
                      help="a catalogue object (e.g. soccer_ball, bottle_case), a primitive "
                      "(sphere:0.12, cube:0.08, cylinder:0.1x0.3) or a mesh file (OBJ, STL, PLY)")
    demo.add_argument("--mode", choices=[m.name.lower() for m in ComplianceMode],
                      help="compliance mode (default: spherical for round objects, else cylindrical)")
    _common(demo)
    demo.add_argument("--replay", metavar="FILE.html",
                      help="write a Meshcat replay that opens in a browser, no server needed")
    demo.set_defaults(run=_run_demo)

    fig4 = sub.add_parser(
        "fig4",
        help="Fig. 4: quasi-static grasps of spheres, cubes, cylinders; eps over size and pose error",
        description="Sweeps object size and hand pose error for spheres (spherical mode), cubes and "
        "cylinders (cylindrical mode): approach until contact, close with breakaway, score with the "
        "eps metric. Writes fig4.csv (one row per grasp), fig4.png and fig4.svg; resumable.",
    )
    fig4.add_argument("--quick", action="store_true", help="9 sizes x 7 errors instead of 27 x 21")
    _executor_args(fig4)
    _common(fig4, scenario=False, seed=False)
    fig4.set_defaults(run=_run_fig4, out_default="out/fig4")

    trial = sub.add_parser(
        "trial",
        help="one grasp trial: execute a compliant grasp, lift 10 cm, hold 10 s, judge",
        description="Places the object with the seed's variation, executes the grasp with the WAM and "
        "the hand's torque close, lifts 10 cm, holds 10 s and judges success (object off the table, "
        "moved < 1 cm and 10 deg in the hand during the hold).",
    )
    _mesh_options(trial)
    trial.add_argument("--object", required=True, metavar="NAME|PATH",
                       help="a catalogue object, a primitive (sphere:0.12, cube:0.08, cylinder:0.1x0.3) or a mesh file")
    trial.add_argument("--method", choices=["compliant", "eigengrasp"], default="compliant",
                       help="compliant (default): explore with the wrist camera, pick the grasp of the most "
                       "resembling shape, execute it, all in one simulation; eigengrasp: see below")
    trial.add_argument("--grasp", choices=["spherical", "cylindrical", "box"],
                       help="force this compliant grasp instead of the algorithm's choice")
    trial.add_argument("--oracle", action="store_true",
                       help="skip the camera: compute the grasp (--grasp) from the object's true pose and size")
    planner = trial.add_argument_group(
        "--method eigengrasp", "plan with the Eigengrasp planner (table loaded), execute its best grasp the "
        "arm can reach, judge with the same success test (one trial of Fig. 7)")
    planner.add_argument("--energy", metavar="contact|contact-quality",
                         help="the planner's energy (default: contact-quality, as Fig. 7)")
    planner.add_argument("--steps", metavar="N", help="the planner's step limit (default 70000, must be > 30000)")
    planner.add_argument("--plan-seed", type=int, metavar="S", help="the planner's seed (default 0)")
    planner.add_argument("--rank", type=int, metavar="K",
                         help="execute the K-th best grasp the arm can reach (default 1)")
    _common(trial)
    trial.add_argument("--replay", metavar="FILE.html", help="write a Meshcat replay")
    trial.set_defaults(run=_run_trial)

    fig6 = sub.add_parser(
        "fig6",
        help="Fig. 6: each compliant grasp's shape resemblance against its success, 9 objects",
        description="For each object and each of the three compliant grasps, N trials of 'explore with "
        "the wrist camera, then execute that grasp'. Writes fig6.csv (one row per trial, as they finish; "
        "rerun to resume), fig6.png and fig6.svg, and a summary beside the paper's 95.6% (86/90).",
    )
    fig6.add_argument("--quick", action="store_true", help="4 objects x 3 grasps x 2 trials")
    fig6.add_argument("--trials", type=int, help="trials per object and grasp (default 10)")
    _mesh_options(fig6)
    fig6.add_argument("--objects", metavar="NAME|PATH,...",
                      help="comma-separated objects instead of the paper's nine (catalogue names, primitives "
                      "such as sphere:0.12, or mesh files): the same study on your own objects")
    _executor_args(fig6)
    fig6.add_argument("--method", choices=["compliant", "oracle"], default="compliant",
                      help="compliant: camera estimates (the paper's algorithm); oracle: ground truth")
    _common(fig6)
    fig6.set_defaults(run=_run_fig6, out_default="out/fig6")

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
    _mesh_options(fig7)
    fig7.add_argument("--objects", metavar="NAME|PATH,...",
                      help="comma-separated objects instead of the paper's six (catalogue names, primitives "
                      "or mesh files): compare the two methods on your own objects")
    _executor_args(fig7)
    fig7.add_argument("--steps", type=int, default=70_000,
                      help="planner steps, GraspIt!'s counter (default 70000 = 40000 annealing iterations)")
    fig7.add_argument("--energy", choices=["contact", "contact-quality"], default="contact-quality",
                      help="the planner's energy (default: contact-quality, GraspIt!'s 'Contacts AND Quality', "
                      "today's GUI default and the stronger baseline here; contact = 'Hand Contacts')")
    fig7.add_argument("--fig6", metavar="DIR", default="out/fig6",
                      help="where Fig. 6's results are reused from (default out/fig6)")
    fig7.add_argument("--compliant-method", choices=["compliant", "oracle"], default="compliant",
                      help="estimates for compliance-centric trials run here (default: the camera)")
    _common(fig7)
    fig7.set_defaults(run=_run_fig7, out_default="out/fig7")

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
    _executor_args(novel)
    novel.add_argument("--energy", choices=["contact", "contact-quality"], default="contact-quality",
                       help="the Eigengrasp planner's energy (default contact-quality)")
    _common(novel)
    novel.set_defaults(run=_run_novel, out_default="out/novel")

    reproduce = sub.add_parser(
        "reproduce",
        help="Fig. 4, 6 and 7 and a report of the paper's claims against ours",
        description="Runs (or resumes) the three experiments under --out and writes report.md: each claim "
        "of the paper, its number, ours, and whether ours agrees; beyond the paper, both methods on novel "
        "objects; and report.html, the results page with replays. --quick takes about 10 minutes on 2 cores.",
    )
    reproduce.add_argument("--quick", action="store_true", help="few sizes, objects and trials")
    _executor_args(reproduce)
    reproduce.add_argument("--energy", choices=["contact", "contact-quality"], default="contact-quality",
                           help="the Eigengrasp planner's energy for Fig. 7")
    reproduce.add_argument("--seed", type=int, default=0, help="first trial seed (default 0)")
    reproduce.add_argument("--out", metavar="DIR", help="output folder (default out/reproduce[-quick])")
    reproduce.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    reproduce.set_defaults(run=_run_reproduce)
    eigengrasp = sub.add_parser(
        "plan-eigengrasp",
        help="plan grasps with GraspIt!'s Eigengrasp planner (the compliance-agnostic baseline)",
        description="Simulated annealing over hand pose and eigengrasp posture with GraspIt!'s "
        "schedule and energy, on the exact object model; the 20 best states are closed with "
        "autograsp (breakaway) and ranked by eps. Prints the three best grasps (hand pose in the "
        "object frame, finger posture, energy, eps) and the planning time.",
    )
    _mesh_options(eigengrasp)
    eigengrasp.add_argument("--object", required=True, metavar="NAME|PATH",
                            help="a catalogue object, a primitive (sphere:0.12, cube:0.08, cylinder:0.1x0.3) or a mesh file")
    eigengrasp.add_argument("--steps", default="70000", metavar="N",
                            help="GraspIt!'s step limit; its counter starts at 30000, so the default "
                            "70000 runs 40000 annealing iterations (must be > 30000)")
    eigengrasp.add_argument("--energy", default="contact", metavar="contact|contact-quality",
                            help="annealing energy: GraspIt!'s hand-contact energy (default) or "
                            "contacts-and-quality")
    _common(eigengrasp, scenario=False)
    eigengrasp.add_argument("--table", action="store_true",
                            help="the object rests on a table (nominal pose): states touching it are illegal")
    eigengrasp.set_defaults(run=_run_plan_eigengrasp)
    resemble = sub.add_parser(
        "resemble",
        help="explore an object with the wrist camera: estimates and shape resemblances",
        description="Starts the camera above the table looking down at the object's nominal place, runs "
        "the visual primitives (depth and principal axis, then sphere/cylinder/box resemblance) and "
        "prints the estimated centre, depth, principal axis and size beside the ground truth, and the "
        "three resemblances. The object is placed with trial SEED's variation (docs/design.md §4.7).",
    )
    _mesh_options(resemble)
    resemble.add_argument("--object", required=True, metavar="NAME|PATH",
                          help="a catalogue object, a primitive (sphere:0.12, cube:0.08, cylinder:0.1x0.3) or a mesh file")
    resemble.add_argument("--nominal", action="store_true", help="place the object without the seed's variation")
    _common(resemble)
    resemble.add_argument("--replay", metavar="FILE.html", help="write a Meshcat replay of the exploration")
    resemble.set_defaults(run=_run_resemble)

    objects_cmd = sub.add_parser("objects", help="object utilities: generate novel test objects")
    objects_sub = objects_cmd.add_subparsers(dest="objects_command", metavar="ACTION", required=True)
    generate = objects_sub.add_parser(
        "generate",
        help="write N novel watertight meshes (metres) and a manifest",
        description="Writes N watertight OBJ meshes in metres (classes in turn: non-convex blobs, unions "
        "of boxes/cylinders/ellipsoids, thin plates, L and T shapes, rings, handles; largest extent "
        "3-25 cm) and manifest.json / manifest.csv. The same --seed gives byte-identical files.",
    )
    generate.add_argument("--count", type=int, required=True, metavar="N", help="how many objects")
    generate.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    generate.add_argument("--out", required=True, metavar="DIR", help="directory for the meshes and manifest")
    generate.add_argument("--json", action="store_true", help="print the manifest as one JSON object")
    generate.set_defaults(run=_run_objects_generate)
    return parser


def _run_objects_generate(args) -> int:
    from drake_grasp.geometry import novel

    _check_seed(args.seed)
    if args.count < 1:
        raise UsageError(f"--count must be >= 1, got {args.count}")
    out = _check_out_dir(args.out)
    rows = novel.generate(args.count, args.seed, out)
    if args.json:
        print(json.dumps({"out": str(out), "objects": rows}))
    else:
        classes = sorted({r["class"] for r in rows})
        print(f"objects generate: {len(rows)} meshes ({', '.join(classes)}) in {out}; {out / 'manifest.json'}")
    return 0


def _run_resemble(args) -> int:
    import numpy as np

    from drake_grasp.perception import comparison_record, explore, format_comparison
    from drake_grasp.protocol import TrialVariation
    from drake_grasp.trial import apply_variation

    replay, scenario, spec = _single_run_inputs(args)
    look_at = np.array([scenario.object.x, scenario.object.y, 0.0])  # where the object should be
    if not args.nominal:
        scenario, spec = apply_variation(scenario, spec, TrialVariation.draw(args.seed, scenario.protocol))
    result = explore(scenario, None, spec, look_at=look_at, replay_html=str(replay) if replay else None)
    record = dict(comparison_record(result, spec), seed=args.seed, nominal=args.nominal)
    _emit(args, record, f"resemble_{spec.name}_{args.seed}.json", "\n".join(format_comparison(record)), replay)
    return 0 if result.estimate.found else 1


def _mesh_options(p: argparse.ArgumentParser) -> None:
    """--scale and --largest-component, for every command that takes --object."""
    p.add_argument("--scale", type=float, default=1.0, metavar="S",
                   help="multiply a mesh file's coordinates by S (e.g. 0.001 for a file in millimetres)")
    p.add_argument("--largest-component", action="store_true",
                   help="a mesh of separate, non-touching solids: keep the largest (else an error)")


def _resolve(args):
    """The --object of a single-run command, with its mesh options."""
    from drake_grasp.objects import resolve_user_object

    return resolve_user_object(args.object, scale=args.scale, largest_component=args.largest_component)


def _common(p: argparse.ArgumentParser, scenario: bool = True, seed: bool = True) -> None:
    if seed:  # (fig4's quasi-static sweep is deterministic: it has no seed)
        p.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    p.add_argument("--out", metavar="DIR", help="directory for result files")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a line")
    if scenario:
        p.add_argument("--scenario", metavar="FILE.yaml",
                       help="scenario file (default: diagrams/station.scenarios.yaml)")
        p.add_argument("--scenario-name", default="default", help="scenario in that file (default: default)")


def _executor_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--workers", type=int,
                   help="worker processes, or the CPUs of the local Ray instance (default: all cores)")
    p.add_argument("--executor", default="local", metavar="local|ray",
                   help="where trials run: local processes (default) or Ray tasks (pip install -e '.[ray]'); "
                   "the results are the same")
    p.add_argument("--ray-address", metavar="ADDR",
                   help="join this Ray cluster (auto, HOST:PORT or ray://HOST:10001) instead of starting a "
                   "local Ray instance with --workers CPUs; needs --executor ray")


def _load_scenario(args):
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    return load_scenario(args.scenario or DEFAULT_SCENARIO_FILE, args.scenario_name)


def _emit(args, record: dict, filename: str, summary: str, replay: pathlib.Path | None) -> None:
    """Prints a single run's record (one JSON object with --json, else the summary and where the
    replay went), then writes it to --out (atomically): if writing fails, the result is still shown.

    Raises:
        RuntimeError: (one line, exit code 1) if the record could not be written.
    """
    if args.json:
        print(json.dumps(_jsonable(record)), flush=True)
    else:
        print(summary, flush=True)
        if replay:
            print(f"replay: {replay}", flush=True)
    if args.out:
        _save_record(pathlib.Path(args.out), filename, record)


def _save_record(out: pathlib.Path, filename: str, record: dict) -> None:
    """Writes a record as JSON to out/filename; RuntimeError (one line) if that fails."""
    try:
        out.mkdir(parents=True, exist_ok=True)
        _write_json_atomically(out / filename, record)
    except OSError as e:
        raise RuntimeError(f"could not write {out / filename}: {e.strerror or e}") from None


def _check_out_dir(path: str | os.PathLike, option: str = "--out") -> pathlib.Path:
    """An output folder that can be written: it is a folder, or can be created as one (its nearest
    existing parent is a writable folder). UsageError (one line) otherwise. Nothing is created."""
    p = pathlib.Path(path)
    if p.exists():
        if not p.is_dir():
            raise UsageError(f"{option} {path}: exists and is not a directory")
        if not os.access(p, os.W_OK | os.X_OK):
            raise UsageError(f"{option} {path}: directory is not writable")
        return p
    parent = p.absolute().parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise UsageError(f"{option} {path}: {parent} is not a directory")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise UsageError(f"{option} {path}: cannot create it ({parent} is not writable)")
    return p


def _check_seed(seed: int, trials: int = 1) -> None:
    """A seed in [0, 2^32); a sweep of `trials` trials uses seed .. seed + trials - 1, all in range."""
    if not 0 <= seed < 2**32:
        raise UsageError(f"--seed must be in [0, 2^32), got {seed}")
    if seed + trials - 1 >= 2**32:
        raise UsageError(f"--seed {seed} with {trials} trials uses seeds up to {seed + trials - 1}, past "
                         f"2^32 - 1; use --seed <= {2**32 - trials}")


def _single_run_inputs(args) -> tuple:
    """(replay path or None, scenario, object) of a single-run command (demo, trial, resemble): the
    seed, the replay file name, the scenario and the object checked, each a one-line error."""
    _check_seed(args.seed)
    if args.out:
        _check_out_dir(args.out)
    replay = _writable_file(args.replay, ".html") if args.replay else None
    return replay, _load_scenario(args), _resolve(args)


def _writable_file(path: str, suffix: str) -> pathlib.Path:
    """A file name that can be written (--replay): the right suffix, not a folder, in a writable
    folder that exists, and writable if it exists. UsageError (one line) otherwise."""
    p = pathlib.Path(path)
    if p.suffix.lower() != suffix:
        raise UsageError(f"{path}: expected a {suffix} file name")
    parent = p.absolute().parent
    if not parent.is_dir():
        raise UsageError(f"{path}: directory {p.parent} does not exist")
    if p.is_dir():
        raise UsageError(f"{path}: is a directory")
    if not os.access(parent, os.W_OK | os.X_OK) or (p.exists() and not os.access(p, os.W_OK)):
        raise UsageError(f"{path}: cannot be written (permission denied)")
    return p


def _run_demo(args) -> int:
    from drake_grasp.demo import run_demo

    replay, scenario, spec = _single_run_inputs(args)
    scenario.object.name = args.object
    mode = ComplianceMode.parse(args.mode) if args.mode else None
    result = run_demo(scenario, mode=mode, replay_html=str(replay) if replay else None, object_spec=spec,
                      seed=args.seed)
    _emit(args, dataclasses.asdict(result), "demo.json", result.summary(), replay)
    return 0


def _run_fig4(args) -> int:
    from drake_grasp.experiments import fig4
    from drake_grasp.experiments.lock import results_lock

    executor = _check_sweep_args(args)
    config = fig4.Fig4Config.quick() if args.quick else fig4.Fig4Config.full()
    out = _check_out_dir(args.out or args.out_default)
    start = time.perf_counter()
    with results_lock(out), executor:
        rows = fig4.run_fig4(config, out, executor=executor)
        summaries = fig4.summarise(rows)
        figures = fig4.plot(summaries, out)
    lines = fig4.summary_lines(summaries, rows)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps({
            "csv": str(out / "fig4.csv"), "figures": [str(p) for p in figures], "grasps": len(rows),
            "wall_time": wall, "peak_size": {k: s.peak_size() for k, s in summaries.items()}, "summary": lines,
        }))
    else:
        for line in lines:
            print(line)
        print(f"fig4: {len(rows)} grasps in {wall:.0f} s; {out / 'fig4.csv'}, {figures[0]}, {figures[1]}")
    return 0


def _run_trial(args) -> int:
    from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp
    from drake_grasp.trial import run_compliant_trial, run_trial

    replay, scenario, spec = _single_run_inputs(args)
    planner_options = {"--energy": args.energy, "--steps": args.steps, "--plan-seed": args.plan_seed,
                       "--rank": args.rank}
    if args.method == "eigengrasp":
        return _run_eigengrasp_trial(args, replay)
    given = [name for name, value in planner_options.items() if value is not None]
    if given:
        raise UsageError(f"{', '.join(given)}: only with --method eigengrasp")
    if args.oracle:
        if args.grasp is None:
            raise UsageError("--oracle needs --grasp (the oracle does not choose)")

        def plan(X_WO, object_spec):
            return plan_compliant_grasp(args.grasp, oracle_estimate(X_WO, object_spec))

        record = run_trial(scenario, spec, plan, seed=args.seed, method="oracle", grasp=args.grasp,
                           replay_html=str(replay) if replay else None)
    else:
        record = run_compliant_trial(scenario, spec, seed=args.seed, grasp=args.grasp,
                                     replay_html=str(replay) if replay else None)
    _emit(args, dataclasses.asdict(record), f"trial_{record.object}_{record.grasp}_{record.seed}.json",
          record.summary(), replay)
    return 0


def _check_planner_args(steps: str, energy: str) -> int:
    """The planner's step limit as an int; UsageError for a bad step limit or energy."""
    from baselines.eigengrasp.annealing import K0
    from baselines.eigengrasp.energy import ENERGIES

    try:
        steps = int(steps)
    except ValueError:
        raise UsageError(f"--steps must be an integer > {K0}, got {steps!r}") from None
    if steps <= K0:
        raise UsageError(f"--steps must be > {K0} (GraspIt!'s step counter starts at {K0}), got {steps}")
    if energy not in ENERGIES:
        raise UsageError(f"unknown --energy {energy!r} (choose from {', '.join(ENERGIES)})")
    return steps


def _run_eigengrasp_trial(args, replay: pathlib.Path | None) -> int:
    from drake_grasp.experiments.fig7 import eigengrasp_trial

    if args.grasp or args.oracle:
        raise UsageError("--grasp and --oracle are for --method compliant (the planner chooses its own grasp)")
    energy = args.energy or "contact-quality"
    steps = _check_planner_args(args.steps or "70000", energy)
    rank = 1 if args.rank is None else args.rank
    if rank < 1:
        raise UsageError(f"--rank must be >= 1, got {rank}")
    plan_seed = 0 if args.plan_seed is None else args.plan_seed
    _check_seed(plan_seed)
    from drake_grasp.objects import mesh_options

    record, grasp = eigengrasp_trial(args.object, args.seed, energy=energy, steps=steps, plan_seed=plan_seed,
                                     rank=rank, scenario_file=args.scenario or "", scenario_name=args.scenario_name,
                                     replay_html=str(replay) if replay else None,
                                     object_options=mesh_options(args.scale, args.largest_component))
    result = dataclasses.asdict(record)
    result["planned_grasp"] = grasp
    summary = record.summary()
    if grasp is not None:
        summary += f"; planner rank {grasp['planner_rank']}, eps {grasp['epsilon']:.3f}"
    _emit(args, result, f"trial_{record.object}_eigengrasp_{rank}_{record.seed}.json", summary, replay)
    return 0


def _run_plan_eigengrasp(args) -> int:
    from baselines.eigengrasp.planner import EigengraspPlanner

    _check_seed(args.seed)
    steps = _check_planner_args(args.steps, args.energy)
    if args.out:
        _check_out_dir(args.out)
    spec = _resolve(args)
    plan = EigengraspPlanner(spec, args.energy, table=args.table).plan(steps, seed=args.seed)
    record = plan.to_dict()
    if args.json:
        print(json.dumps(_jsonable(record)), flush=True)
    else:
        _print_plan(plan, args.energy, steps)
    if args.out:
        _save_record(pathlib.Path(args.out), f"eigengrasp_{spec.name}_{args.energy}_{args.seed}.json", record)
    return 0


def _print_plan(plan, energy: str, steps: int) -> None:
    from baselines.eigengrasp.annealing import K0

    print(f"plan-eigengrasp {plan.object_name}: {len(plan.grasps)} grasps, energy {energy}, "
          f"{plan.iterations} iterations (k {K0}..{steps}) at {plan.steps_per_second:.0f} steps/s")
    for i, g in enumerate(plan.grasps, start=1):
        d = g.to_dict()
        q = [math.degrees(v) for v in g.pregrasp_joint_angles]
        print(f"  #{i} hand in object: p = ({', '.join(f'{v:.1f}' for v in d['position_mm'])}) mm, "
              f"axis ({', '.join(f'{v:.3f}' for v in d['axis'])}) angle {math.degrees(d['angle_rad']):.1f} deg; "
              f"posture spread {q[0]:.1f} proximal {q[2]:.1f} distal {q[5]:.1f} deg; "
              f"energy {g.energy:.2f}; eps {g.epsilon:.4f} after autograsp; fingers touching {g.fingers_touching}")
    print(f"planning time {plan.planning_time:.1f} s (annealing {plan.annealing_time:.1f} s, "
          f"autograsp {plan.autograsp_time:.1f} s)", flush=True)


def _check_sweep_args(args):
    """Rejects bad sweep arguments before any work starts; returns the executor the sweep runs on
    (a context manager: Ray, if started, is shut down on leaving it)."""
    from drake_grasp.experiments.executors import EXECUTORS, make_executor

    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers must be >= 1, got {args.workers}")
    if getattr(args, "trials", None) is not None and args.trials < 1:
        raise UsageError(f"--trials must be >= 1, got {args.trials}")
    if hasattr(args, "seed"):
        _check_seed(args.seed, getattr(args, "trials", None) or (2 if args.quick else 10))
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


def _scenario_args(args) -> tuple[str, str]:
    _load_scenario(args)  # reject a bad scenario before any worker starts
    return (str(pathlib.Path(args.scenario).resolve()) if args.scenario else ""), args.scenario_name


def _objects_arg(args, default: tuple[str, ...]) -> tuple[str, ...]:
    """--objects as a tuple (each resolved once here, with the mesh options, so that a bad one is a
    one-line error before any worker starts), or `default`. `--scale` and `--largest-component`
    apply to the mesh files among them; given with no mesh file at all, they are an error."""
    from drake_grasp.objects import is_mesh_file, mesh_options, resolve_user_object

    objects = tuple(default)
    if args.objects is not None:
        objects = tuple(o.strip() for o in args.objects.split(",") if o.strip())
        if not objects:
            raise UsageError("--objects needs at least one object")
        if len(set(objects)) != len(objects):
            raise UsageError(f"--objects names an object twice: {args.objects}")
    options = mesh_options(args.scale, args.largest_component)
    if options and not any(is_mesh_file(o) for o in objects):
        raise UsageError(f"{'--scale' if 'scale' in options else '--largest-component'} applies to mesh files "
                         "only (OBJ, STL, PLY), and --objects names none")
    if args.objects is not None:
        for o in objects:
            resolve_user_object(o, **(options if is_mesh_file(o) else {}))
    return objects


def _run_fig6(args) -> int:
    from drake_grasp.experiments import fig6
    from drake_grasp.objects import PAPER_OBJECTS

    executor = _check_sweep_args(args)
    scenario_file, scenario_name = _scenario_args(args)
    objects = _objects_arg(args, fig6.QUICK_OBJECTS if args.quick else PAPER_OBJECTS)
    trials = args.trials or (2 if args.quick else 10)
    config = fig6.Fig6Config(objects=tuple(objects), trials=trials, seed=args.seed, method=args.method,
                             scale=args.scale, largest_component=args.largest_component)
    out = _check_out_dir(args.out or args.out_default)
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
    from drake_grasp.experiments import fig7

    executor = _check_sweep_args(args)
    _check_planner_args(str(args.steps), args.energy)
    scenario_file, scenario_name = _scenario_args(args)
    fig6_dir = pathlib.Path(args.fig6)
    if fig6_dir.exists() and not fig6_dir.is_dir():
        raise UsageError(f"--fig6 {args.fig6}: exists and is not a directory")
    trials = args.trials or (2 if args.quick else 10)
    config = fig7.Fig7Config(objects=_objects_arg(args, fig7.QUICK_OBJECTS if args.quick else fig7.OBJECTS),
                             trials=trials,
                             seed=args.seed, steps=args.steps, energy=args.energy,
                             compliant_method=args.compliant_method, scale=args.scale,
                             largest_component=args.largest_component)
    out = _check_out_dir(args.out or args.out_default)
    start = time.perf_counter()
    with executor:
        comparison, figures, lines = fig7.run_comparison(config, out, fig6_dir,
                                                         scenario_file=scenario_file, scenario_name=scenario_name,
                                                         executor=executor)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps(_jsonable({"csv": str(out / "fig7.csv"), "figures": [str(p) for p in figures],
                                    "comparison": [dataclasses.asdict(c) for c in comparison],
                                    "wall_time": wall, "summary": lines})))
    else:
        print("\n".join(lines))
        print(f"fig7: {wall:.0f} s; {out / 'fig7.csv'}, {figures[0]}, {figures[1]}")
    return 0


def _run_novel(args) -> int:
    from drake_grasp.experiments import novel

    executor = _check_sweep_args(args)
    scenario_file, scenario_name = _scenario_args(args)
    if args.count is not None and args.count < 1:
        raise UsageError(f"--count must be >= 1, got {args.count}")
    if not 0 <= args.object_seed < 2**32:
        raise UsageError(f"--object-seed must be in [0, 2^32), got {args.object_seed}")
    overrides = {k: v for k, v in (("count", args.count), ("trials", args.trials)) if v is not None}
    overrides.update(seed=args.seed, object_seed=args.object_seed, energy=args.energy)
    config = novel.NovelConfig.quick(**overrides) if args.quick else novel.NovelConfig(**overrides)
    out = _check_out_dir(args.out or (args.out_default + ("-quick" if args.quick else "")))
    start = time.perf_counter()
    with executor:
        objects = novel.ensure_objects(out / "objects", config.count, config.object_seed)
        rows, figures, lines = novel.run_study(config, out, objects, executor, scenario_file=scenario_file,
                                               scenario_name=scenario_name)
    wall = time.perf_counter() - start
    if args.json:
        print(json.dumps(_jsonable({"csv": str(out / "novel.csv"), "summary_md": str(out / "summary.md"),
                                    "figures": [str(p) for p in figures], "wall_time": wall,
                                    "rows": [dataclasses.asdict(r) for r in rows]})))
    else:
        print(lines[0])
        print(f"novel: {len(rows)} objects, {wall:.0f} s; {out / 'summary.md'}, {out / 'novel.csv'}, {figures[0]}")
    return 0


def _run_reproduce(args) -> int:
    from drake_grasp.experiments import reproduce

    executor = _check_sweep_args(args)
    out = _check_out_dir(args.out or ("out/reproduce-quick" if args.quick else "out/reproduce"))
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


def _jsonable(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    return value


def _write_json_atomically(path: pathlib.Path, record: dict) -> None:
    from drake_grasp.experiments.results import write_atomically

    write_atomically(path, json.dumps(_jsonable(record), indent=2) + "\n")


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `drake-grasp` console script; returns the exit code."""
    import warnings

    from drake_grasp.objects import MeshNote, UnstablePoseWarning

    args = _parser().parse_args(argv)

    def one_line(message, category, *rest, **kwargs):
        kind = "note" if issubclass(category, MeshNote) else "warning"
        print(f"drake-grasp {args.command}: {kind}: {message}", file=sys.stderr, flush=True)

    try:
        with warnings.catch_warnings(), _sigterm_as_interrupt():
            warnings.simplefilter("once", UnstablePoseWarning)
            warnings.showwarning = one_line
            return args.run(args)
    except (UsageError, ValueError, FileNotFoundError) as e:
        # ObjectError and scenario errors are ValueErrors with one-line messages.
        message = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        print(f"drake-grasp {args.command}: error: {message}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        # A run that could not be carried out (e.g. the arm cannot reach the object): one line, exit 1.
        message = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        print(f"drake-grasp {args.command}: failed: {message}", file=sys.stderr)
        return 1
    except KeyboardInterrupt as e:
        terminated = isinstance(e, Terminated)
        print(f"drake-grasp {args.command}: {'terminated' if terminated else 'interrupted'}", file=sys.stderr)
        return 143 if terminated else 130


class _sigterm_as_interrupt:
    """While active (in the main thread), SIGTERM raises `Terminated`, which unwinds like Ctrl-C."""

    def __enter__(self):
        self.previous = None
        if threading.current_thread() is threading.main_thread():
            self.previous = signal.signal(signal.SIGTERM, self._raise)
        return self

    @staticmethod
    def _raise(signum, frame):
        raise Terminated()

    def __exit__(self, *exc):
        if self.previous is not None:
            signal.signal(signal.SIGTERM, self.previous)


if __name__ == "__main__":
    sys.exit(main())
