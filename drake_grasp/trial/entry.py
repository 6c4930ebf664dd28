"""The one trial entry point: a `TrialSpec` of any method in, its `TrialRecord` out.

Every caller runs a trial through `run`: the sweeps' runner (in worker processes), the command line's
`trial` and `demo`, the studies and the tests. The methods differ only in how the grasp is decided:

* **oracle**: the compliant grasp the spec names, computed from the ground-truth estimate
  (`grasps.oracle_estimate`) of the object as it lies (`oracle_plan`);
* **compliant**: the paper's algorithm; the wrist camera explores and the supervisor decides and
  computes the grasp in the same simulation (`compliant.run_compliant_trial`);
* **eigengrasp**: a grasp of the Eigengrasp planner (`eigengrasp.run_eigengrasp_trial`).

Camera-driven trials that differ only in the grasp they are forced to execute (Fig. 6 runs all three
after the same exploration) share that exploration: `run_shared` runs them as one simulation that
branches at the decision (`compliant.run_compliant_trials`), with the records they give one by one.

A spec's estimate error (issue 15) is added to the estimate the grasp is computed from and recorded
in the record's `variation` (only when there is one, so that every other record stays as it was).
"""

import dataclasses

from drake_grasp.estimate_error import EstimateError, perturb_estimate
from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp
from drake_grasp.objects import ObjectSpec, resolve_user_object
from drake_grasp.station import DEFAULT_SCENARIO_FILE, Scenario, load_scenario
from drake_grasp.trial.attempts import run_compliant_attempts
from drake_grasp.trial.compliant import run_compliant_trial, run_compliant_trials
from drake_grasp.trial.eigengrasp import run_eigengrasp_trial
from drake_grasp.trial.given_plan import PlanFunction, run_trial
from drake_grasp.trial.record import TrialRecord
from drake_grasp.trial.spec import METHODS, TrialSpec


def resolve(spec: TrialSpec) -> tuple[Scenario, ObjectSpec]:
    """The scenario and the object a spec names (ValueError, one line, for a bad one)."""
    scenario = load_scenario(spec.scenario_file or DEFAULT_SCENARIO_FILE, spec.scenario_name)
    return scenario, resolve_user_object(spec.object, **spec.object_options())


def oracle_plan(grasp: str, estimate_error: EstimateError | None = None) -> PlanFunction:
    """The plan function of an oracle trial: the compliant `grasp` computed from the ground-truth
    estimate of the object as it lies, with `estimate_error` added to that estimate."""

    def plan(X_WO, object_spec):
        return plan_compliant_grasp(grasp, perturb_estimate(oracle_estimate(X_WO, object_spec), estimate_error))

    return plan


def run(spec: TrialSpec, replay_html: str | None = None, *, scenario: Scenario | None = None,
        obj: ObjectSpec | None = None, monitor_period: float = 0.05) -> TrialRecord:
    """Runs the trial `spec` describes and returns its record (never raises for a failed grasp or
    simulation).

    Args:
        spec: the trial.
        replay_html: also write a Meshcat replay there (the record is the same).
        scenario, obj: the scenario and object the spec names, when the caller has them already
            (resolved and checked, or changed in memory, as the tests' short hold): else as `resolve`.
        monitor_period: how often the executor's phase is checked, s.

    Raises:
        ValueError: an unknown method, or a bad scenario or object (when it loads them).
    """
    if spec.method not in METHODS:
        raise ValueError(f"unknown method '{spec.method}'")
    if scenario is None:
        scenario = load_scenario(spec.scenario_file or DEFAULT_SCENARIO_FILE, spec.scenario_name)
    if obj is None:
        obj = resolve_user_object(spec.object, **spec.object_options())
    error = spec.estimate_error if spec.has_estimate_error else None
    if spec.method == "compliant":
        # An empty grasp runs the algorithm's own choice; a named one is forced (Fig. 6's protocol).
        if spec.attempts > 1:
            record = run_compliant_attempts(scenario, obj, seed=spec.seed, attempts=spec.attempts,
                                            replay_html=replay_html, monitor_period=monitor_period,
                                            estimate_error=error)
        else:
            record = run_compliant_trial(scenario, obj, seed=spec.seed, grasp=spec.grasp or None,
                                         replay_html=replay_html, monitor_period=monitor_period, estimate_error=error)
    elif spec.method == "oracle":
        record = run_trial(scenario, obj, oracle_plan(spec.grasp, error), seed=spec.seed, method="oracle",
                           grasp=spec.grasp, replay_html=replay_html, monitor_period=monitor_period)
    else:
        record = run_eigengrasp_trial(spec, scenario, obj, replay_html, monitor_period)
    if error is not None:
        record.variation["estimate_error"] = error.to_dict()
    return record


def exploration_key(spec: TrialSpec) -> TrialSpec | None:
    """What a spec's exploration depends on: specs with the same key explore identically and may
    share one exploration (`run_shared`). The spec without its grasp for a camera-driven trial
    (object and its options, seed, scenario, estimate error); None for the other methods, whose
    trials share nothing."""
    return dataclasses.replace(spec, grasp="") if spec.method == "compliant" else None


def run_shared(specs: list[TrialSpec], *, scenario: Scenario | None = None, obj: ObjectSpec | None = None,
               monitor_period: float = 0.05) -> list[TrialRecord]:
    """The records of `specs`, in order, as `run` gives them one by one; specs with one
    `exploration_key` (at most one spec per grasp) run as one simulation that explores once and
    branches at the decision, the others one by one.

    Args:
        specs: trials that all name one scenario and one object (with the same options).
        scenario, obj: those, when the caller has them already (else as `resolve`).
        monitor_period: as `run`'s.

    Raises:
        ValueError: specs that name different scenarios or objects; a bad scenario or object.
    """
    if not specs:
        return []
    where = {(s.scenario_file, s.scenario_name, s.object, s.scale, s.largest_component, s.join_gap, s.inertia,
              s.package_path) for s in specs}
    if len(where) > 1:
        raise ValueError("run_shared: the specs name more than one scenario or object")
    if scenario is None or obj is None:
        scenario, obj = resolve(specs[0])
    records: list[TrialRecord | None] = [None] * len(specs)
    groups: dict[TrialSpec, list[int]] = {}
    for index, spec in enumerate(specs):
        key = exploration_key(spec)
        if key is None or spec.attempts > 1 or any(specs[i].grasp == spec.grasp for i in groups.get(key, [])):
            records[index] = run(spec, scenario=scenario, obj=obj, monitor_period=monitor_period)
        else:
            groups.setdefault(key, []).append(index)
    for key, indices in groups.items():
        error = key.estimate_error if key.has_estimate_error else None
        shared = run_compliant_trials(scenario, obj, seed=key.seed, grasps=[specs[i].grasp or None for i in indices],
                                      monitor_period=monitor_period, estimate_error=error)
        for i, record in zip(indices, shared):
            if error is not None:
                record.variation["estimate_error"] = error.to_dict()
            records[i] = record
    return records
