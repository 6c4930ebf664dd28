"""The single-run commands: demo, trial, plan-eigengrasp, resemble.

Each runs one thing in this process (a trial, a plan, an exploration), prints one line (or one JSON
object with --json), and with --out saves its record as JSON; --replay writes a Meshcat replay.
"""

import dataclasses
import json
import math
import pathlib

from drake_grasp.cli.common import (UsageError, add_common, add_mesh_options, check_out_dir, check_planner_args,
                                    check_seed, emit, jsonable, mesh_option_args, object_argument, resolve_object_arg,
                                    save_record, single_run_inputs)
from drake_grasp.robot.hand import ComplianceMode

# The compliant grasps' names users may give --grasp besides the records' own: the flower grasp is the
# grasp type "precision" (the position-held grasp it replaced kept the name, and every record has it).
GRASP_ALIASES = {"flower": "precision"}


def add_demo(sub) -> None:
    """`drake-grasp demo`."""
    demo = sub.add_parser(
        "demo",
        help="pick an object up with the hand's compliance (ground-truth pose)",
        description="The arm brings the open hand above the object (its true pose), descends, closes "
        "the fingers (torque close with breakaway), lifts 10 cm and holds 10 s; prints whether the "
        "object was held and how much it slipped in the hand.",
    )
    add_mesh_options(demo)
    demo.add_argument("--object", required=True, metavar="NAME|PATH", type=object_argument,
                      help="a catalogue object (e.g. soccer_ball, bottle_case), a primitive "
                      "(sphere:0.12, cube:0.08, cylinder:0.1x0.3), a mesh file or a model file")
    demo.add_argument("--mode", choices=[m.name.lower() for m in ComplianceMode],
                      help="compliance mode (default: spherical for round objects, else cylindrical)")
    add_common(demo, scenario="object")
    demo.add_argument("--replay", metavar="FILE.html",
                      help="write a Meshcat replay that opens in a browser, no server needed")
    demo.set_defaults(run=_run_demo)


def add_trial(sub) -> None:
    """`drake-grasp trial`."""
    trial = sub.add_parser(
        "trial",
        help="one grasp trial: execute a compliant grasp, lift 10 cm, hold 10 s, judge",
        description="Places the object with the seed's variation, executes the grasp with the WAM and "
        "the hand's torque close, lifts 10 cm, holds 10 s and judges success (object off the table, "
        "moved < 1 cm and 10 deg in the hand during the hold).",
    )
    add_mesh_options(trial)
    trial.add_argument("--object", required=True, metavar="NAME|PATH", type=object_argument,
                       help="a catalogue object, a primitive (sphere:0.12, cube:0.08, cylinder:0.1x0.3) or a mesh file")
    trial.add_argument("--method", choices=["compliant", "eigengrasp"], default="compliant",
                       help="compliant (default): explore with the wrist camera, pick the grasp of the most "
                       "resembling shape, execute it, all in one simulation; eigengrasp: see below")
    trial.add_argument("--grasp", choices=["spherical", "cylindrical", "box", "flower", "precision"],
                       type=lambda name: GRASP_ALIASES.get(name, name),
                       help="force this compliant grasp instead of the algorithm's choice (flower: fingertips "
                       "landed on the table around a thin, flat or small object, the arm compliant; records "
                       "name it 'precision', the grasp it replaced)")
    trial.add_argument("--oracle", action="store_true",
                       help="skip the camera: compute the grasp (--grasp) from the object's true pose and size")
    trial.add_argument("--attempts", type=int, default=1, metavar="N",
                       help="try again up to N times in all (default 1, the paper's protocol): when the wrist "
                       "camera sees the object did not rise with the hand, the hand opens, the camera looks "
                       "again and the next grasp of the decision is executed; the record lists every attempt "
                       "(--method compliant, the algorithm's own choice)")
    trial.add_argument("--estimate-error", metavar="KEY=VALUE,...",
                       help="add a known error to the estimate the grasp is computed from: along, across "
                       "(m, horizontal, along and across the object's principal axis), yaw_deg (deg), size "
                       "(factor on the extents), e.g. along=0.02,yaw_deg=10; with --method eigengrasp, to the "
                       "object pose the planned hand pose is expressed against (no size: the planner has the "
                       "exact model)")
    planner = trial.add_argument_group(
        "--method eigengrasp", "plan with the Eigengrasp planner (table loaded), execute its best grasp the "
        "arm can reach, judge with the same success test (one trial of Fig. 7)")
    planner.add_argument("--energy", metavar="contact|contact-quality",
                         help="the planner's energy (default: contact-quality, as Fig. 7)")
    planner.add_argument("--steps", metavar="N", help="the planner's step limit (default 70000, must be > 30000)")
    planner.add_argument("--plan-seed", type=int, metavar="S", help="the planner's seed (default 0)")
    planner.add_argument("--rank", type=int, metavar="K",
                         help="execute the K-th best grasp the arm can reach (default 1)")
    add_common(trial, scenario="object")
    trial.add_argument("--replay", metavar="FILE.html", help="write a Meshcat replay")
    trial.set_defaults(run=_run_trial)


def add_plan_eigengrasp(sub) -> None:
    """`drake-grasp plan-eigengrasp`."""
    eigengrasp = sub.add_parser(
        "plan-eigengrasp",
        help="plan grasps with GraspIt!'s Eigengrasp planner (the compliance-agnostic baseline)",
        description="Simulated annealing over hand pose and eigengrasp posture with GraspIt!'s "
        "schedule and energy, on the exact object model; the 20 best states are closed with "
        "autograsp (breakaway) and ranked by eps. Prints the three best grasps (hand pose in the "
        "object frame, finger posture, energy, eps) and the planning time.",
    )
    add_mesh_options(eigengrasp)
    eigengrasp.add_argument("--object", required=True, metavar="NAME|PATH", type=object_argument,
                            help="a catalogue object, a primitive (sphere:0.12, cube:0.08, cylinder:0.1x0.3) or a mesh file")
    eigengrasp.add_argument("--steps", default="70000", metavar="N",
                            help="GraspIt!'s step limit; its counter starts at 30000, so the default "
                            "70000 runs 40000 annealing iterations (must be > 30000)")
    eigengrasp.add_argument("--energy", default="contact", metavar="contact|contact-quality",
                            help="annealing energy: GraspIt!'s hand-contact energy (default) or "
                            "contacts-and-quality")
    add_common(eigengrasp, scenario=False)
    eigengrasp.add_argument("--table", action="store_true",
                            help="the object rests on a table (nominal pose): states touching it are illegal")
    eigengrasp.set_defaults(run=_run_plan_eigengrasp)


def add_resemble(sub) -> None:
    """`drake-grasp resemble`."""
    resemble = sub.add_parser(
        "resemble",
        help="explore an object with the wrist camera: estimates and shape resemblances",
        description="Starts the camera above the table looking down at the object's nominal place, runs "
        "the visual primitives (depth and principal axis, then sphere/cylinder/box resemblance) and "
        "prints the estimated centre, depth, principal axis and size beside the ground truth, and the "
        "three resemblances. The object is placed with trial SEED's variation (docs/design.md §4.7).",
    )
    add_mesh_options(resemble)
    resemble.add_argument("--object", required=True, metavar="NAME|PATH", type=object_argument,
                          help="a catalogue object, a primitive (sphere:0.12, cube:0.08, cylinder:0.1x0.3) or a mesh file")
    resemble.add_argument("--nominal", action="store_true", help="place the object without the seed's variation")
    add_common(resemble, scenario="object")
    resemble.add_argument("--replay", metavar="FILE.html", help="write a Meshcat replay of the exploration")
    resemble.set_defaults(run=_run_resemble)


def _run_demo(args) -> int:
    from drake_grasp.demo import run_demo

    replay, scenario, spec = single_run_inputs(args)
    scenario.object.name = args.object
    mode = ComplianceMode.parse(args.mode) if args.mode else None
    result = run_demo(scenario, mode=mode, replay_html=str(replay) if replay else None, object_spec=spec,
                      seed=args.seed)
    emit(args, dataclasses.asdict(result), "demo.json", result.summary(), replay)
    return 0


def _run_trial(args) -> int:
    from drake_grasp import trial

    from drake_grasp.trial.spec import MAX_ATTEMPTS

    if not 1 <= args.attempts <= MAX_ATTEMPTS:
        raise UsageError(f"--attempts must be from 1 to {MAX_ATTEMPTS}, got {args.attempts}")
    if args.attempts > 1 and (args.method != "compliant" or args.grasp or args.oracle):
        raise UsageError("--attempts: only the compliance-centric algorithm's own choice tries again "
                         "(no --grasp, --oracle or --method eigengrasp)")
    replay, scenario, obj = single_run_inputs(args)
    error = _estimate_error_arg(args.estimate_error)
    options = dict(scenario_file=args.scenario or "", scenario_name=args.scenario_name, scale=args.scale,
                   largest_component=args.largest_component, join_gap=args.join_gap, inertia=args.inertia,
                   package_path=mesh_option_args(args)["package_path"], estimate_error=error)
    if args.method == "eigengrasp":
        settings = _planner_settings_args(args, error)
        spec = trial.TrialSpec(args.object, "eigengrasp", settings.label, args.seed, planner=settings, **options)
    else:
        planner_options = {"--energy": args.energy, "--steps": args.steps, "--plan-seed": args.plan_seed,
                           "--rank": args.rank}
        given = [name for name, value in planner_options.items() if value is not None]
        if given:
            raise UsageError(f"{', '.join(given)}: only with --method eigengrasp")
        if args.oracle and args.grasp is None:
            raise UsageError("--oracle needs --grasp (the oracle does not choose)")
        spec = trial.TrialSpec(args.object, "oracle" if args.oracle else "compliant", args.grasp or "", args.seed,
                               attempts=args.attempts, **options)
    record = trial.run(spec, str(replay) if replay else None, scenario=scenario, obj=obj)
    summary = record.summary()
    if record.planned_grasp is not None:
        grasp = record.planned_grasp
        summary += f"; planner rank {grasp['planner_rank']}, eps {grasp['epsilon']:.3f}"
    name = f"eigengrasp_{spec.planner.rank}" if spec.method == "eigengrasp" else record.grasp
    emit(args, record.to_dict(), f"trial_{record.object}_{name}_{record.seed}.json", summary, replay)
    return 0


def _planner_settings_args(args, error):
    """The planner's settings of `trial --method eigengrasp` (UsageError for a bad one)."""
    from drake_grasp.trial import PlannerSettings

    if args.grasp or args.oracle:
        raise UsageError("--grasp and --oracle are for --method compliant (the planner chooses its own grasp)")
    energy = args.energy or "contact-quality"
    steps = check_planner_args(args.steps or "70000", energy)
    rank = 1 if args.rank is None else args.rank
    if rank < 1:
        raise UsageError(f"--rank must be >= 1, got {rank}")
    plan_seed = 0 if args.plan_seed is None else args.plan_seed
    check_seed(plan_seed)
    if error is not None and error.size_scale != 1:
        raise UsageError("--estimate-error size does not apply to --method eigengrasp (the planner has the exact model)")
    return PlannerSettings(energy=energy, steps=steps, seed=plan_seed, rank=rank)


# --estimate-error's keys and their units.
ESTIMATE_ERROR_KEYS = {"along": "m", "across": "m", "yaw_deg": "deg", "size": "factor"}


def _estimate_error_arg(text: str | None):
    """--estimate-error KEY=VALUE,... as an `EstimateError` (None if not given); UsageError (one line)
    for an unknown or repeated key, a value that is not a finite number, or a size <= 0."""
    from drake_grasp.estimate_error import EstimateError

    if text is None:
        return None
    keys = ", ".join(f"{k} ({unit})" for k, unit in ESTIMATE_ERROR_KEYS.items())
    values = {}
    for item in text.split(","):
        key, equals, value = (part.strip() for part in item.partition("="))
        if not equals or key not in ESTIMATE_ERROR_KEYS:
            raise UsageError(f"--estimate-error {text!r}: expected KEY=VALUE,... with KEY in {keys}")
        if key in values:
            raise UsageError(f"--estimate-error {text!r}: {key} is given twice")
        try:
            values[key] = float(value)
        except ValueError:
            raise UsageError(f"--estimate-error {text!r}: {key} must be a number, got {value!r}") from None
        if not math.isfinite(values[key]):
            raise UsageError(f"--estimate-error {text!r}: {key} must be finite")
    if values.get("size", 1.0) <= 0:
        raise UsageError(f"--estimate-error {text!r}: size must be > 0 (1 = no size error)")
    return EstimateError(along=values.get("along", 0.0), across=values.get("across", 0.0),
                         yaw=math.radians(values.get("yaw_deg", 0.0)), size_scale=values.get("size", 1.0))


def _run_plan_eigengrasp(args) -> int:
    from baselines.eigengrasp.planner import EigengraspPlanner

    check_seed(args.seed)
    steps = check_planner_args(args.steps, args.energy)
    if args.out:
        check_out_dir(args.out)
    spec = resolve_object_arg(args)
    plan = EigengraspPlanner(spec, args.energy, table=args.table).plan(steps, seed=args.seed)
    record = plan.to_dict()
    if args.json:
        print(json.dumps(jsonable(record)), flush=True)
    else:
        _print_plan(plan, args.energy, steps)
    if args.out:
        save_record(pathlib.Path(args.out), f"eigengrasp_{spec.name}_{args.energy}_{args.seed}.json", record)
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


def _run_resemble(args) -> int:
    import numpy as np

    from drake_grasp.perception import comparison_record, explore, format_comparison
    from drake_grasp.protocol import TrialVariation
    from drake_grasp.trial import apply_variation

    replay, scenario, spec = single_run_inputs(args)
    look_at = np.array([scenario.object.x, scenario.object.y, 0.0])  # where the object should be
    if not args.nominal:
        scenario, spec = apply_variation(scenario, spec, TrialVariation.draw(args.seed, scenario.protocol))
    result = explore(scenario, None, spec, look_at=look_at, replay_html=str(replay) if replay else None)
    record = dict(comparison_record(result, spec), seed=args.seed, nominal=args.nominal)
    emit(args, record, f"resemble_{spec.name}_{args.seed}.json", "\n".join(format_comparison(record)), replay)
    return 0 if result.estimate.found else 1


