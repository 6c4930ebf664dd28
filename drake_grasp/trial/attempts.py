"""A grasp that failed is noticed and tried again: the compliance-centric algorithm with `--attempts N`.

One attempt is one camera-driven trial (`compliant.run_compliant_branches`): explore, decide, grasp,
lift, hold. At its end the robot asks its own sensors whether it holds the object (`sensing.sense_hold`:
the wrist camera sees whether the object rose with the hand and stayed put in it over the hold; the
simulator's contacts and the object's true pose are not sensors). When it does not, or when the arm
could not reach any candidate of the grasp, the next attempt begins:

* the hand opens and the arm goes back to the exploration's start; the object, if the hand still held
  it, falls onto the table (`release.let_fall`: simulated with the table alone, in the scenario's
  physics), and the next attempt's simulation starts with the arm at the exploration's start and the
  object at rest where it came to lie;
* a fresh look: the whole exploration again, because the object may have moved (dropped, pushed,
  tipped over);
* the next candidate: the decision runs without the grasps that already failed on this object
  (`primitives.decision.choose_shape`'s `exclude`), so the next attempt executes the next grasp in the
  decision's order, at its own best pose on the new estimate. The flower grasp alone gets three
  tries, the second turned a half-turn about its approach, before the decision runs without it
  (`funnel.planning.TRIES`): the from-above grasps cannot reach the small and thin objects it is for.
  An upright object has two grasps in turn, the box grasp from above and then the wrap from the arm's
  side (`funnel.planning.grasp_of`).

It stops at the first attempt the camera sees hold, when the object is no longer found or the estimate
cannot place a grasp, or after N attempts. The record is the last attempt's (its success is the
success test's, as for any trial), with every attempt listed (`TrialRecord.attempts`): studies report
first-attempt and within-N success apart. Attempts after the first keep the trial seed's friction and
camera noise; the object's placement is wherever the last attempt left it.
"""

from __future__ import annotations

import dataclasses

from pydrake.math import RollPitchYaw

from drake_grasp.control.arm_motion import UNREACHABLE
from drake_grasp.estimate_error import EstimateError
from drake_grasp.objects import ObjectSpec
from drake_grasp.objects.drake_model import with_mass_scale
from drake_grasp.protocol import TrialVariation
from drake_grasp.station import Scenario
from drake_grasp.trial.compliant import _compliant_record, run_compliant_branches
from drake_grasp.trial.execution import apply_variation
from drake_grasp.trial.record import TrialRecord
from drake_grasp.trial.release import let_fall


def attempt_summary(record: TrialRecord) -> dict:
    """One attempt as the combined record lists it, with the resemblances its own look measured (the
    combined record's top level keeps the last look's): why each attempt chose its grasp."""
    return {"grasp": record.grasp, "chosen": record.chosen_grasp, "success": record.success,
            "failure": record.failure, "detail": record.detail, "sensed_held": record.sensed.get("held"),
            "sensed": dict(record.sensed), "resemblance": dict(record.resemblances or {}),
            "sim_time": record.sim_time, "wall_time": record.wall_time}


def should_try_again(record: TrialRecord) -> bool:
    """Whether the robot itself knows the attempt failed and can try again: the camera saw no hold
    after a grasp, or no candidate of the grasp was reachable."""
    if record.failure == UNREACHABLE:
        return True
    return bool(record.sensed) and not record.sensed.get("held", False)


def run_compliant_attempts(scenario: Scenario, spec: ObjectSpec, *, seed: int, attempts: int,
                           replay_html: str | None = None, monitor_period: float = 0.05,
                           estimate_error: EstimateError | None = None) -> TrialRecord:
    """Up to `attempts` camera-driven trials of the algorithm's own choice (module docstring)."""
    done: list[TrialRecord] = []
    failed_grasps: list[str] = []
    current = scenario
    # The object as each attempt's station simulates it (the trial seed's friction, the scenario's mass
    # scale): what falls when the hand lets go.
    _, falling = apply_variation(scenario, with_mass_scale(spec, scenario.object.mass_scale),
                                 TrialVariation.draw(seed, scenario.protocol))
    for k in range(attempts):
        (trial,) = run_compliant_branches(current, spec, seed=seed, grasps=[None],
                                          replay_html=replay_html if k == attempts - 1 else None,
                                          monitor_period=monitor_period, estimate_error=estimate_error,
                                          exclude=tuple(failed_grasps))
        record = _compliant_record(trial, scenario)
        done.append(record)
        if k == attempts - 1 or not should_try_again(record):
            break
        if record.grasp:
            failed_grasps.append(record.grasp)
        if trial.run is not None and trial.run.X_WO_end is not None:  # let go: it falls and comes to rest
            X = let_fall(current, falling, trial.run.X_WO_end)
            pose = [*map(float, X.translation()), *map(float, RollPitchYaw(X.rotation()).vector())]
            current = dataclasses.replace(current, object=dataclasses.replace(current.object, pose=pose))
    last = dataclasses.replace(done[-1])
    last.attempts = [attempt_summary(r) for r in done]
    last.sim_time = float(sum(r.sim_time for r in done))
    last.wall_time = float(sum(r.wall_time for r in done))
    return last


def first_attempt_success(record: dict | TrialRecord) -> bool:
    """Whether a record's first attempt succeeded (its own success when it made only one)."""
    attempts = record.attempts if isinstance(record, TrialRecord) else record.get("attempts") or []
    success = record.success if isinstance(record, TrialRecord) else record.get("success")
    return bool(attempts[0]["success"]) if attempts else bool(success)


