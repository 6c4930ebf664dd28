"""Fingerprints: a short hash of everything that decides a record's outcome.

A results file keeps records across runs, so a rerun must never reuse a record computed from other
inputs. Each record therefore carries a fingerprint of its inputs beside its key (object, method,
grasp, seed): the resolved scenario (after the scenario file's overrides), the perception
configuration, the object's content, the planned grasp (for planner trials), an estimate error
(where a trial adds one) and the behaviour version (`drake_grasp.BEHAVIOUR_VERSION`, which stands for what the code and the models it ships do). The trial protocol's timings and thresholds
are part of the scenario (`Scenario.protocol`), so they enter with it. Rows whose fingerprint differs
from the current one are kept in the file but never used: each fingerprint has its own results, and
changing a parameter back finds its old records again.

Every function here is pure apart from reading the files it is given. A fingerprint is the first
16 hex digits of a SHA-256 over a canonical text (sorted-key JSON, or Drake's YAML dump of a
dataclass), so it is the same in every process and on every machine.
"""

import dataclasses
import functools
import hashlib
import json
import os
import pathlib

import drake_grasp

DIGITS = 16  # 64 bits: no two different inputs of one results file share a fingerprint in practice


def digest(*parts) -> str:
    """The fingerprint of `parts` (JSON-able values): SHA-256 of their canonical JSON, 16 hex digits."""
    text = json.dumps(parts, sort_keys=True, separators=(",", ":"), default=_canonical)
    return hashlib.sha256(text.encode()).hexdigest()[:DIGITS]


def _canonical(value):
    """JSON for what json cannot write itself: dataclasses as their dicts, paths as text."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return dataclasses.asdict(value)
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return value.tolist()
    raise TypeError(f"cannot fingerprint a {type(value).__name__}")


def object_content(name_or_path: str, **object_kwargs) -> dict:
    """What an object argument stands for, as plain data: the argument itself, plus the bytes of its
    file (as a hash) and the version of the import (repair, joining, decomposition) for a path, the parsed numbers for a primitive, or the catalogue name and the
    behaviour version for a catalogue object. The keyword arguments of the object's construction (a
    mass, a scale) enter too.

    Raises:
        ObjectError: as `objects.resolve_object` for a bad argument.
    """
    from drake_grasp.objects import _PAPER_FACTORIES, _PRIMITIVE_PATTERNS, ObjectError
    from drake_grasp.objects.pieces import IMPORT_VERSION

    text = str(name_or_path).strip()
    content = {"argument": text, "kwargs": object_kwargs}
    kind = text.split(":", 1)[0].lower() if ":" in text else None
    if text in _PAPER_FACTORIES:
        content["catalogue"] = {"name": text, "version": drake_grasp.BEHAVIOUR_VERSION}
    elif kind in _PRIMITIVE_PATTERNS:
        match = _PRIMITIVE_PATTERNS[kind].fullmatch(text.lower())
        if match is None:
            raise ObjectError(f"bad primitive {text!r}")
        content["primitive"] = {"kind": kind, "values": [float(v) for v in match.groups() if v is not None]}
    else:
        path = pathlib.Path(text).expanduser()
        try:
            content["file"] = {"name": path.name, "sha256": _file_sha256(path.resolve(), path.stat().st_mtime_ns,
                                                                          path.stat().st_size),
                               "import": IMPORT_VERSION}
        except OSError as e:
            raise ObjectError(f"{text}: cannot read ({e.strerror})") from None
    return content


@functools.lru_cache(maxsize=64)
def _file_sha256(path: pathlib.Path, mtime_ns: int, size: int) -> str:
    """A file's SHA-256 (cached per path, modification time and size: a sweep asks once per trial)."""
    return hashlib.sha256(path.read_bytes()).hexdigest()


def object_fingerprint(name_or_path: str, **object_kwargs) -> str:
    """The fingerprint of an object argument's content (`object_content`)."""
    return digest(object_content(name_or_path, **object_kwargs))


def scenario_text(scenario) -> str:
    """A resolved scenario (or any Drake-style dataclass, e.g. the perception configuration) as
    canonical text: Drake's typed YAML dump, which writes every field in schema order."""
    from pydrake.common.yaml import yaml_dump_typed

    return yaml_dump_typed(scenario)


def scenario_fingerprint(scenario_file: str = "", scenario_name: str = "default") -> str:
    """The fingerprint of the scenario a trial runs in, after the file's overrides of the default
    scenario, with the perception configuration the camera-driven trials use. Reads the files each time (a sweep calls it once
    per scenario, before its trials run)."""
    from drake_grasp.station import DEFAULT_SCENARIO_FILE, load_scenario

    scenario = load_scenario(scenario_file or DEFAULT_SCENARIO_FILE, scenario_name)
    return digest(scenario_text(scenario))


def trial_fingerprint(spec, scenario_print: str | None = None, object_print: str | None = None) -> str:
    """The fingerprint of one trial (`trial.TrialSpec`): scenario and perception, object content,
    the planned grasp (planner trials) and the behaviour version; and, only where a spec has them (so
    that every other record keeps its fingerprint), an estimate error, more than one attempt and the
    settings of a planner trial that plans itself. The method, grasp and seed are the record's key and not repeated here.
    Precomputed scenario and object fingerprints may be given."""
    if scenario_print is None:
        scenario_print = scenario_fingerprint(spec.scenario_file, spec.scenario_name)
    if object_print is None:
        object_print = object_fingerprint(spec.object, **spec.object_options())
    parts = ["trial", drake_grasp.BEHAVIOUR_VERSION, scenario_print, object_print, spec.planned]
    if spec.has_estimate_error:
        parts.append({"estimate_error": spec.estimate_error})
    if spec.attempts > 1:
        parts.append({"attempts": spec.attempts})
    if spec.method == "eigengrasp" and spec.planned is None:
        from drake_grasp.trial.spec import PlannerSettings

        parts.append({"planner": spec.planner or PlannerSettings()})
    return digest(*parts)


def sweep_fingerprint(name: str, *parts) -> str:
    """The fingerprint of a sweep with no scenario (Fig. 4): its name, its parameters that are not
    part of a row's key, and the behaviour version."""
    return digest(name, drake_grasp.BEHAVIOUR_VERSION, *parts)
