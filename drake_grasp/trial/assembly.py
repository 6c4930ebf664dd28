"""One place assembles a trial's Diagram, whatever the method, in the same order: the trial's
variation applied to the scenario and the object; the station; what the method adds to it (for the
camera-driven algorithm, perception and the supervisor that decides and executes; for a given plan,
the grasp executor); then the simulation and the judgement (`execution.execute`).

Each method's module (`trial.compliant`, `execution.run_trial` for oracle and planned grasps) says
only what differs, as a `wire` function: what it adds to the builder and how its sequence starts.

Trials that differ only in what a method decides (Fig. 6's three grasps after one exploration) are
assembled once and run as branches (`assemble_and_run_branches`): the part before the decision is
simulated once, and each branch goes on from a copy of its state.
"""

import dataclasses
import time
from collections.abc import Callable

import numpy as np
from pydrake.systems.framework import Context, DiagramBuilder

from drake_grasp.objects import ObjectSpec
from drake_grasp.protocol import TrialVariation
from drake_grasp.station import MakeStation, Scenario, Station
from drake_grasp.trial.execution import Branch, Executed, apply_variation, execute_branches
from drake_grasp.trial.record import TrialRecord


@dataclasses.dataclass
class Wiring:
    """What a method added to the station in the builder.

    Attributes:
        sequence: the system that runs the grasp sequence to its end (a GraspExecutor, or the
            camera-driven supervisor, which is one).
        q_start: the arm's joint angles at time 0, rad.
        time_limit: simulated time after which the trial fails, s.
        initialize: called with the root context before the simulation starts (more initial state).
        prepare: called with a root context and a branch's value, before the decision, to make the
            run that branch (`assemble_and_run_branches`; the camera-driven supervisor's forced grasp).
    """

    sequence: object
    q_start: np.ndarray
    time_limit: float
    initialize: Callable | None = None
    prepare: Callable[[Context, object], None] | None = None


# (builder holding the station, the station, the trial's scenario and object, its record) -> the
# Wiring, or None when the method ends the trial before anything moves (its record says why).
Wire = Callable[[DiagramBuilder, Station, Scenario, ObjectSpec, TrialRecord], Wiring | None]


@dataclasses.dataclass
class Assembled:
    """A trial run: its record (wall time still to set by the method), what the simulation saw
    (None if it never started), the trial's object (varied) and when the trial began (perf_counter)."""

    record: TrialRecord
    run: Executed | None
    spec: ObjectSpec
    wall_start: float

    def wall_time(self) -> float:
        """The trial's wall time, s: from its start to the end of its simulation, or for a branch of a
        shared run its own part and its share of the shared part (`execution.execute_branches`);
        for a trial that never simulated, from its start to now."""
        if self.run is None:
            return time.perf_counter() - self.wall_start
        return self.run.wall_time


def assemble_and_run(scenario: Scenario, spec: ObjectSpec, *, seed: int, record_fields: dict, camera: bool,
                     wire: Wire, replay_html: str | None = None, monitor_period: float = 0.05) -> Assembled:
    """Runs one trial: variation, station (with the wrist camera if `camera`), the method's wiring,
    simulation and judgement. `record_fields` name the record (method, grasp, estimate_source)."""
    return assemble_and_run_branches(scenario, spec, seed=seed, branches=[(record_fields, None)], camera=camera,
                                     wire=wire, replay_html=replay_html, monitor_period=monitor_period)[0]


def assemble_and_run_branches(scenario: Scenario, spec: ObjectSpec, *, seed: int, branches: list[tuple[dict, object]],
                              camera: bool, wire: Wire, replay_html: str | None = None,
                              monitor_period: float = 0.05) -> list[Assembled]:
    """Runs several trials of one seed that differ only in what the method decides, as branches of
    one simulation (`execution.execute_branches`): each branch is (its record's fields, the value
    the wiring's `prepare` sets). With one branch, `prepare` is not needed (as `assemble_and_run`).

    Every branch's record is the record the same trial run alone would give (wall time aside).
    """
    wall_start = time.perf_counter()
    variation = TrialVariation.draw(seed, scenario.protocol)
    scenario, spec = apply_variation(scenario, spec, variation)
    records = [TrialRecord(object=spec.name, seed=seed, success=False, failure="",
                           variation=dataclasses.asdict(variation), **fields) for fields, _ in branches]
    station = MakeStation(scenario, spec, camera=camera)
    builder = DiagramBuilder()
    builder.AddNamedSystem("station", station.diagram)
    wiring = wire(builder, station, scenario, spec, records[0])
    if wiring is None:  # the method ended the trial before anything moved: every branch the same way
        for record in records[1:]:
            record.failure, record.detail = records[0].failure, records[0].detail
        return [Assembled(record, None, spec, wall_start) for record in records]
    if len(branches) > 1 and wiring.prepare is None:
        raise ValueError("this method's trials cannot branch (its wiring has no prepare)")

    def prepare_for(value):
        if wiring.prepare is None:
            return None
        return lambda context: wiring.prepare(context, value)

    runs = execute_branches(builder, station, wiring.sequence, scenario.protocol, wiring.q_start,
                            [Branch(record, prepare_for(value)) for record, (_, value) in zip(records, branches)],
                            wiring.time_limit, replay_html, monitor_period, wiring.initialize, wall_start)
    return [Assembled(record, run, spec, wall_start) for record, run in zip(records, runs)]
