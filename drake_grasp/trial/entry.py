"""The one trial entry point: a `TrialSpec` of any method in, its `TrialRecord` out.

Every caller runs a trial through `run`: the sweeps' runner (in worker processes), the command line's
`trial` and `demo`, the studies and the tests. The methods differ only in how the grasp is decided:

* **oracle**: the compliant grasp the spec names, computed from the ground-truth estimate
  (`grasps.oracle_estimate`) of the object as it lies (`oracle_plan`);
* **compliant**: the paper's algorithm; the wrist camera explores and the supervisor decides and
  computes the grasp in the same simulation (`compliant.run_compliant_trial`);
* **eigengrasp**: a grasp of the Eigengrasp planner (`eigengrasp.run_eigengrasp_trial`).

A spec's estimate error (issue 15) is added to the estimate the grasp is computed from and recorded
in the record's `variation` (only when there is one, so that every other record stays as it was).
"""

from drake_grasp.estimate_error import EstimateError, perturb_estimate
from drake_grasp.grasps import oracle_estimate, plan_compliant_grasp
from drake_grasp.objects import ObjectSpec, resolve_user_object
from drake_grasp.station import DEFAULT_SCENARIO_FILE, Scenario, load_scenario
from drake_grasp.trial.compliant import run_compliant_trial
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
        record = run_compliant_trial(scenario, obj, seed=spec.seed, grasp=spec.grasp or None, replay_html=replay_html,
                                     monitor_period=monitor_period, estimate_error=error)
    elif spec.method == "oracle":
        record = run_trial(scenario, obj, oracle_plan(spec.grasp, error), seed=spec.seed, method="oracle",
                           grasp=spec.grasp, replay_html=replay_html, monitor_period=monitor_period)
    else:
        record = run_eigengrasp_trial(spec, scenario, obj, replay_html, monitor_period)
    if error is not None:
        record.variation["estimate_error"] = error.to_dict()
    return record
