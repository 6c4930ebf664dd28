"""One exploration, run: the camera starts above a point of the table looking down, the visual
primitives explore the object, and the estimate is read (the algorithm's side: nothing here compares
an estimate with the truth; `drake_grasp.perception.evaluation` does).

`explore` builds the exploration Diagram for one scenario (`wiring.MakeExploration`), simulates it
and returns an `ExplorationResult`: the `ObjectEstimate`, and the object's true poses at the start and
the end, which only evaluation reads (`run_exploration` returns the estimate only).
"""

import dataclasses
import time

import numpy as np
from pydrake.math import RigidTransform
from pydrake.systems.framework import EventStatus

from drake_grasp.objects import ObjectSpec
from drake_grasp.primitives.estimate import ObjectEstimate
from drake_grasp.primitives.sequencer import ExplorationPhase
from drake_grasp.simulation import StartSimulation, recording
from drake_grasp.perception.config import PerceptionConfig
from drake_grasp.station import Scenario
from drake_grasp.perception.wiring import Exploration, MakeExploration, start_camera_pose, start_configuration


@dataclasses.dataclass
class ExplorationResult:
    """One exploration: the estimate, and (for evaluation only) where the object really was.

    Attributes:
        estimate: what the primitives found.
        X_WO_start, X_WO_end: the object's true pose at the start and at the end (a round object
            can roll a little on the table while it is looked at).
    """

    estimate: ObjectEstimate
    X_WO_start: RigidTransform
    X_WO_end: RigidTransform


def run_exploration(scenario: Scenario, config: PerceptionConfig | None = None, object_spec: ObjectSpec | None = None,
                    *, look_at: np.ndarray | None = None, replay_html: str | None = None) -> ObjectEstimate:
    """Builds the exploration for `scenario`, runs it once, returns the estimate (see `explore`)."""
    return explore(scenario, config, object_spec, look_at=look_at, replay_html=replay_html).estimate


def explore(scenario: Scenario, config: PerceptionConfig | None = None, object_spec: ObjectSpec | None = None,
            *, look_at: np.ndarray | None = None, replay_html: str | None = None,
            on_finish=None) -> ExplorationResult:
    """Builds the exploration for `scenario` and runs it once.

    Deterministic: the same inputs give the same estimate (nothing here is random; per-trial
    variation of the object's placement is the caller's, in `scenario.object`).

    Args:
        scenario: the station scenario; `scenario.object` places the object.
        config: the choices (default: the scenario's `perception`).
        object_spec: the object, when already resolved.
        look_at: the point the camera starts above (default: the placement's x, y — where the object
            is expected; a trial passes the nominal placement, not the varied one).
        replay_html: if given, write a Meshcat replay of the exploration there.
        on_finish: if given, called as on_finish(exploration, root context) when the simulation has
            ended, to read more than the estimate (a study reads the resemblance primitives'
            statistics: `resemblance_statistics`).
    """
    config = config or scenario.perception
    wall_start = time.perf_counter()
    exploration = MakeExploration(scenario, config, object_spec, replay=bool(replay_html))
    station = exploration.station
    if look_at is None:
        look_at = np.array([scenario.object.x, scenario.object.y, 0.0])
    table_height = config.depth.table_height
    q0 = start_configuration(station, start_camera_pose(look_at, config, table_height), config)

    motion = exploration.primitives.camera_motion
    sim = StartSimulation(exploration.diagram, station, q0,
                          lambda root: motion.SetInitialPositions(motion.GetMyMutableContextFromRoot(root), q0))
    simulator, context, plant_context = sim.simulator, sim.context, sim.plant_context
    plant = station.plant
    sequencer = exploration.sequencer
    sequencer_context = sequencer.GetMyContextFromRoot(context)
    simulator.set_monitor(lambda root: EventStatus.ReachedTermination(sequencer, "exploration over")
                          if sequencer.state(sequencer_context).phase.finished else EventStatus.Succeeded())
    object_body = plant.get_body(plant.GetBodyIndices(station.object_instance)[0])
    X_WO_start = object_body.EvalPoseInWorld(plant_context)
    build_time = time.perf_counter() - wall_start

    sim_start = time.perf_counter()
    with recording(exploration.meshcat, replay_html):
        simulator.AdvanceTo(config.sequencer.total_time + 1.0)
    sim_wall = time.perf_counter() - sim_start

    if on_finish is not None:
        on_finish(exploration, context)
    state = sequencer.state(sequencer_context)
    timings = {
        "build_time": build_time,
        "sim_time": context.get_time(),
        "sim_wall_time": sim_wall,
        "wall_time": time.perf_counter() - wall_start,
        "frames": exploration.primitives.camera.frames,
        "phase_starts": {ExplorationPhase(p).name.lower(): t for p, t in state.phase_starts},
    }
    return ExplorationResult(read_estimate(exploration, context, timings), X_WO_start,
                             object_body.EvalPoseInWorld(plant_context))


def resemblance_statistics(exploration: Exploration, context, shape: str = "box"):
    """The silhouette statistics (`scores.FeatureStatistics`) a resemblance primitive gathered, in
    `context` (the exploration's root context): its resemblance is `scores.evaluate` of them. The
    three primitives see the same views from the same latched frame, so any one of them will do."""
    from drake_grasp.primitives.scores import FeatureStatistics

    primitive = exploration.primitives.resemblance[shape]
    return FeatureStatistics.from_vector(primitive.statistics_vector(primitive.GetMyContextFromRoot(context)))


def read_estimate(exploration: Exploration, context, timings: dict | None = None) -> ObjectEstimate:
    """The ObjectEstimate that the primitives' outputs hold in `context` (the exploration's root context)."""
    estimator = exploration.primitives.estimator
    estimate = estimator.GetOutputPort("estimate").Eval(estimator.GetMyContextFromRoot(context))
    return dataclasses.replace(estimate, timings=dict(timings or {}))
