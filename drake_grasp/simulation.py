"""The simulation harness that every run of the station shares: exploration, trials, demos.

A run adds its systems to a builder beside the station, then this module does the rest the same way
for all of them: optionally a Meshcat visualizer (illustration geometry), the Diagram and its
Simulator, the initial state (the WAM at its start configuration, the fingers open, plus whatever the
run's own systems need), and the replay, recorded while the simulation runs and written as one
self-contained HTML file that opens in a browser with no server.
"""

import contextlib
import dataclasses
import pathlib
from collections.abc import Callable

import numpy as np
from pydrake.geometry import Meshcat, MeshcatVisualizer, MeshcatVisualizerParams, Role
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import Context, Diagram, DiagramBuilder


def AddReplay(builder: DiagramBuilder, station_system) -> Meshcat:
    """Adds a Meshcat visualizer of the station's illustration geometry to `builder`; returns its
    Meshcat (record with `recording`)."""
    meshcat = Meshcat()
    MeshcatVisualizer.AddToBuilder(builder, station_system.GetOutputPort("query_object"), meshcat,
                                   MeshcatVisualizerParams(role=Role.kIllustration))
    return meshcat


@dataclasses.dataclass
class StationSimulation:
    """A built Diagram with its Simulator, in the station's initial state.

    Attributes:
        diagram: the whole Diagram (the station and the run's systems).
        simulator: its Simulator (not yet initialised).
        context: the root context.
        plant_context: the station plant's context in it.
    """

    diagram: Diagram
    simulator: Simulator
    context: Context
    plant_context: Context


def StartSimulation(diagram: Diagram, station, q_start: np.ndarray,
                    initialize: Callable[[Context], None] | None = None) -> StationSimulation:
    """The Simulator of `diagram` (which holds `station`) with the arm at `q_start` (rad) and the
    fingers open; `initialize(root_context)` then sets the run's own initial state."""
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    plant = station.plant
    plant_context = plant.GetMyMutableContextFromRoot(context)
    plant.SetPositions(plant_context, station.wam, np.asarray(q_start, float))
    station.hand_controller.SetInitialFingers(station.hand_controller.GetMyMutableContextFromRoot(context))
    if initialize is not None:
        initialize(context)
    return StationSimulation(diagram, simulator, context, plant_context)


@contextlib.contextmanager
def recording(meshcat: Meshcat | None, html_path: str | pathlib.Path | None, look_at: np.ndarray | None = None):
    """Records what `meshcat` shows while the block runs, then writes the replay to `html_path`
    (also when the block raises: a failed run's replay shows how it failed). With no meshcat, does
    nothing. `look_at` (m, world) points the replay's camera at the scene from the front and above."""
    if meshcat is None:
        yield
        return
    if look_at is not None:
        p = np.asarray(look_at, float)
        meshcat.SetCameraPose(p + [0.45, -0.75, 0.45], p)
    meshcat.StartRecording()
    try:
        yield
    finally:
        meshcat.StopRecording()
        meshcat.PublishRecording()
        pathlib.Path(html_path).write_text(meshcat.StaticHtml())
