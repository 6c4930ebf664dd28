"""One camera-driven grasp, wired by hand from the library's public names (drake_grasp.api): the
station from a scenario, the visual primitives and the exploration sequencer, the supervisor that
decides the compliant grasp and executes it; simulated with a Meshcat recording, then judged.

Run: .venv/bin/python scripts/simulate_grasp.py --object apple [--grasp box] [--replay grasp.html]
This is what `drake-grasp trial --object apple` runs, without the seed's variation.
"""

import argparse
import dataclasses
import json
import time

import numpy as np
from pydrake.systems.framework import DiagramBuilder

from drake_grasp import api


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--object", default="apple")
    parser.add_argument("--grasp", choices=("spherical", "cylindrical", "box"), help="force a grasp")
    parser.add_argument("--scenario-name", default="default")
    parser.add_argument("--hold", type=float, help="hold time, s (default: the scenario's)")
    parser.add_argument("--replay", help="write a Meshcat replay here (.html)")
    args = parser.parse_args(argv)

    scenario = api.load_scenario(scenario_name=args.scenario_name)
    if args.hold is not None:
        scenario.protocol.execution.hold_time = args.hold
    obj = api.resolve_object(args.object)
    config, protocol = scenario.perception, scenario.protocol

    # The station, then perception around it, then the supervisor that decides and grasps.
    station = api.MakeStation(scenario, obj, camera=True)
    builder = DiagramBuilder()
    builder.AddNamedSystem("station", station.diagram)
    primitives = api.AddVisualPrimitives(builder, station, config, connect_arm=False)
    sequencer = api.AddExplorationSequencer(builder, primitives, config)
    look_at = np.array([scenario.object.x, scenario.object.y, 0.0])
    q_start = api.start_configuration(station, api.start_camera_pose(look_at, config, config.depth.table_height),
                                      config)
    supervisor = api.AddCompliantGraspSupervisor(builder, station, primitives, sequencer, q_start,
                                                 protocol.execution, args.grasp)

    def start_camera_motion(context):
        motion = primitives.camera_motion
        motion.SetInitialPositions(motion.GetMyMutableContextFromRoot(context), q_start)

    # Simulate to the end of the sequence and judge it with the paper's success test.
    record = api.TrialRecord(object=obj.name, method="compliant", grasp=args.grasp or "", seed=0, success=False,
                             failure="", estimate_source="camera")
    time_limit = config.sequencer.total_time + protocol.execution.hold_time + 60.0
    start = time.perf_counter()
    run = api.execute(builder, station, supervisor, protocol, q_start, record, time_limit, args.replay, 0.05,
                      start_camera_motion)
    record.wall_time = time.perf_counter() - start
    if run.decision is not None:
        record.grasp, record.chosen_grasp = run.decision.executed, run.decision.chosen
        record.resemblances = dict(run.decision.estimate.resemblances)
    print(record.summary())
    print(json.dumps({k: v for k, v in dataclasses.asdict(record).items() if k in ("success", "failure", "chosen_grasp",
                                                                                  "resemblances", "lift")}))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
