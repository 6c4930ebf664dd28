"""What the `drake-grasp` commands share: their common options, the checks of their input (each a
one-line UsageError, exit code 2, before any work starts) and how a single run's result is printed
and saved."""

import argparse
import json
import math
import os
import pathlib


class UsageError(ValueError):
    """Bad input from the command line: reported in one line, exit code 2."""


class OneLineParser(argparse.ArgumentParser):
    """An ArgumentParser whose errors raise UsageError (one line, for the caller to print and exit
    with code 2) instead of printing the usage: for the scripts under scripts/."""

    def error(self, message):
        raise UsageError(message)


def add_mesh_options(p: argparse.ArgumentParser) -> None:
    """--scale, --largest-component, --join-gap, --inertia and --package-path, for every command that
    takes --object."""
    p.add_argument("--scale", type=float, default=1.0, metavar="S",
                   help="multiply a mesh or model file's coordinates by S (e.g. 0.001 for a file in millimetres)")
    p.add_argument("--largest-component", action="store_true",
                   help="a mesh of parts farther apart than the join gap: keep the largest (else an error)")
    p.add_argument("--join-gap", type=float, default=None, metavar="M",
                   help="closed shells of a mesh this close (m) are one object (default: 2 mm or 2 %% of its "
                   "largest extent, whichever is larger)")
    p.add_argument("--inertia", default="check", choices=("check", "file", "geometry"),
                   help="a model file's inertial: check it and replace an implausible one by the collision "
                   "geometry's (default), keep the file's (refused if it cannot be simulated), or use the geometry's")
    p.add_argument("--package-path", action="append", default=[], metavar="DIR",
                   help="resolve an SDF/URDF file's package:// URIs against DIR's package.xml or those below it "
                   "(repeatable; package.xml files in the file's folder and the 8 above it are found without it)")


def mesh_option_args(args) -> dict:
    """The object-file options of a command line (keyword arguments of resolve_user_object)."""
    return {"scale": args.scale, "largest_component": args.largest_component,
            "join_gap": getattr(args, "join_gap", None), "inertia": getattr(args, "inertia", "check"),
            "package_path": tuple(getattr(args, "package_path", None) or ())}


def object_argument(text: str) -> str:
    """An object as a command line names it (argparse's ``type`` of --object, --objects' entries and
    `objects check`'s FILE): a Gazebo model folder (one with a model.config) becomes the path of its
    SDF file (`objects.names.gazebo_model_file`), so that every record and option names the file;
    anything else, and a folder whose model.config names no SDF (the loader then refuses it in one
    line, exit 2), is returned as given."""
    from pathlib import Path

    from drake_grasp.objects import ObjectError
    from drake_grasp.objects.names import gazebo_model_file

    path = Path(text.strip()).expanduser()
    if not path.is_dir() or not (path / "model.config").is_file():
        return text
    try:
        return str(gazebo_model_file(path, text.strip()))
    except ObjectError:
        return text


def object_list_argument(text: str) -> str:
    """--objects' comma-separated list, each entry as `object_argument` gives it."""
    return ",".join(object_argument(entry.strip()) if entry.strip() else entry for entry in text.split(","))


def resolve_object_arg(args):
    """The --object of a single-run command, with its object-file options."""
    from drake_grasp.objects import resolve_user_object

    return resolve_user_object(args.object, **mesh_option_args(args))


# --scenario-name's default for the commands whose default depends on the object (`add_common`'s
# scenario="object").
_BY_OBJECT_HELP = ("scenario in that file (default: table_top, the best estimate, for object files; default, the "
                   "paper's silhouettes, for the paper's objects and primitives)")


def add_common(p: argparse.ArgumentParser, scenario: bool | str = True, seed: bool = True) -> None:
    """--seed, --out, --json and (`scenario`) --scenario and --scenario-name: True, the "default"
    scenario unless named (the paper's algorithm: the paper's figures); "best", the best estimate
    ("table_top"); "object" ("objects"), chosen by --object (by --objects: the best estimate if
    any of them is an object file; `station.default_scenario_name`)."""
    if seed:  # (fig4's quasi-static sweep is deterministic: it has no seed)
        p.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    p.add_argument("--out", metavar="DIR", help="directory for result files")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a line")
    if scenario:
        p.add_argument("--scenario", metavar="FILE.yaml",
                       help="scenario file (default: diagrams/station.scenarios.yaml)")
        if scenario in ("object", "objects"):
            p.add_argument("--scenario-name", default=None, help=_BY_OBJECT_HELP)
        elif scenario == "best":
            p.add_argument("--scenario-name", default=None,
                           help="scenario in that file (default: table_top, the best estimate; with a file of "
                           "your own: default)")
        else:
            p.add_argument("--scenario-name", default="default",
                           help="scenario in that file (default: default, the paper's algorithm)")


def add_executor_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--workers", type=int,
                   help="worker processes, or the CPUs of the local Ray instance (default: all cores)")
    p.add_argument("--executor", default="local", metavar="local|ray",
                   help="where trials run: local processes (default) or Ray tasks (pip install -e '.[ray]'); "
                   "the results are the same")
    p.add_argument("--ray-address", metavar="ADDR",
                   help="join this Ray cluster (auto, HOST:PORT or ray://HOST:10001) instead of starting a "
                   "local Ray instance with --workers CPUs; needs --executor ray")


def load_scenario_arg(args):
    """The scenario --scenario and --scenario-name name. With no name, it is chosen (and set on
    `args`) from --object where the command has one, else it is the best estimate's (with the
    project's scenario file; a file of the user's own: its "default")."""
    from drake_grasp.station import (BEST_SCENARIO_NAME, DEFAULT_SCENARIO_FILE, PAPER_SCENARIO_NAME,
                                     default_scenario_name, load_scenario)

    if args.scenario_name is None:
        if getattr(args, "object", None) is not None:
            args.scenario_name = default_scenario_name(args.object, args.scenario)
        elif hasattr(args, "objects"):  # a sweep: the paper's objects unless --objects names a file
            names = [o.strip() for o in (args.objects or "").split(",") if o.strip()]
            chosen = {default_scenario_name(o, args.scenario) for o in names}
            args.scenario_name = BEST_SCENARIO_NAME if BEST_SCENARIO_NAME in chosen else PAPER_SCENARIO_NAME
        else:
            args.scenario_name = BEST_SCENARIO_NAME if not args.scenario else PAPER_SCENARIO_NAME
    return load_scenario(args.scenario or DEFAULT_SCENARIO_FILE, args.scenario_name)


def emit(args, record: dict, filename: str, summary: str, replay: pathlib.Path | None) -> None:
    """Prints a single run's record (one JSON object with --json, else the summary and where the
    replay went), then writes it to --out (atomically): if writing fails, the result is still shown.

    Raises:
        RuntimeError: (one line, exit code 1) if the record could not be written.
    """
    if args.json:
        print(json.dumps(jsonable(record)), flush=True)
    else:
        print(summary, flush=True)
        if replay:
            print(f"replay: {replay}", flush=True)
    if args.out:
        save_record(pathlib.Path(args.out), filename, record)


def save_record(out: pathlib.Path, filename: str, record: dict) -> None:
    """Writes a record as JSON to out/filename; RuntimeError (one line) if that fails."""
    try:
        out.mkdir(parents=True, exist_ok=True)
        write_json_atomically(out / filename, record)
    except OSError as e:
        raise RuntimeError(f"could not write {out / filename}: {e.strerror or e}") from None


def check_out_dir(path: str | os.PathLike, option: str = "--out") -> pathlib.Path:
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


def check_seed(seed: int, trials: int = 1) -> None:
    """A seed in [0, 2^32); a sweep of `trials` trials uses seed .. seed + trials - 1, all in range."""
    if not 0 <= seed < 2**32:
        raise UsageError(f"--seed must be in [0, 2^32), got {seed}")
    if seed + trials - 1 >= 2**32:
        raise UsageError(f"--seed {seed} with {trials} trials uses seeds up to {seed + trials - 1}, past "
                         f"2^32 - 1; use --seed <= {2**32 - trials}")


def single_run_inputs(args) -> tuple:
    """(replay path or None, scenario, object) of a single-run command (demo, trial, resemble): the
    seed, the replay file name, the scenario and the object checked, each a one-line error."""
    check_seed(args.seed)
    if args.out:
        check_out_dir(args.out)
    replay = writable_file(args.replay, ".html") if args.replay else None
    return replay, load_scenario_arg(args), resolve_object_arg(args)


def writable_file(path: str, suffix: str) -> pathlib.Path:
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



def check_planner_args(steps: str, energy: str) -> int:
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



def jsonable(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    return value


def write_json_atomically(path: pathlib.Path, record: dict) -> None:
    from drake_grasp.sweeps.results import write_atomically

    write_atomically(path, json.dumps(jsonable(record), indent=2) + "\n")

