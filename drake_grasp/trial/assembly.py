"""One place assembles a trial's Diagram, whatever the method, in the same order: the trial's
variation applied to the scenario and the object; the station; what the method adds to it (for the
camera-driven algorithm, perception and the supervisor that decides and executes; for a given plan,
the grasp executor); then the simulation and the judgement (`execution.execute`).

Each method's module (`trial.compliant`, `execution.run_trial` for oracle and planned grasps) says
only what differs, as a `wire` function: what it adds to the builder and how its sequence starts.
"""

import dataclasses
import time
from collections.abc import Callable

import numpy as np
from pydrake.systems.framework import DiagramBuilder

from drake_grasp.objects import ObjectSpec
from drake_grasp.protocol import TrialVariation
from drake_grasp.station import MakeStation, Scenario, Station
from drake_grasp.trial.execution import Executed, apply_variation, execute
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
    """

    sequence: object
    q_start: np.ndarray
    time_limit: float
    initialize: Callable | None = None


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


def assemble_and_run(scenario: Scenario, spec: ObjectSpec, *, seed: int, record_fields: dict, camera: bool,
                     wire: Wire, replay_html: str | None = None, monitor_period: float = 0.05) -> Assembled:
    """Runs one trial: variation, station (with the wrist camera if `camera`), the method's wiring,
    simulation and judgement. `record_fields` name the record (method, grasp, estimate_source)."""
    wall_start = time.perf_counter()
    variation = TrialVariation.draw(seed, scenario.protocol)
    scenario, spec = apply_variation(scenario, spec, variation)
    record = TrialRecord(object=spec.name, seed=seed, success=False, failure="",
                         variation=dataclasses.asdict(variation), **record_fields)
    station = MakeStation(scenario, spec, camera=camera)
    builder = DiagramBuilder()
    builder.AddNamedSystem("station", station.diagram)
    wiring = wire(builder, station, scenario, spec, record)
    run = None
    if wiring is not None:
        run = execute(builder, station, wiring.sequence, scenario.protocol, wiring.q_start, record,
                      wiring.time_limit, replay_html, monitor_period, wiring.initialize)
    return Assembled(record, run, spec, wall_start)
