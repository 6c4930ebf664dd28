"""A trial of a given grasp plan: a compliant grasp computed from the ground truth (the oracle), or a
grasp planned by the Eigengrasp baseline. What differs from the camera-driven algorithm: no camera,
the arm starts at the protocol's start configuration, and a `GraspExecutor` runs the plan; the rest
is `assembly.assemble_and_run`, as for every method.
"""

from collections.abc import Callable

import numpy as np
from pydrake.math import RigidTransform

from drake_grasp.control.arm_motion import UNREACHABLE, ReachError
from drake_grasp.control.grasp_executor import ConnectGraspExecutor, GraspExecutor
from drake_grasp.grasps import GraspPlan
from drake_grasp.objects import ObjectSpec
from drake_grasp.station import Scenario
from drake_grasp.trial.assembly import Wiring, assemble_and_run
from drake_grasp.trial.record import TrialRecord

PlanFunction = Callable[[RigidTransform, ObjectSpec], GraspPlan]


def run_trial(scenario: Scenario, spec: ObjectSpec, plan_function: PlanFunction, *, seed: int, method: str,
              grasp: str, replay_html: str | None = None, monitor_period: float = 0.05) -> TrialRecord:
    """Runs one trial of a given grasp plan and returns its record (never raises for a failed grasp
    or simulation).

    Args:
        scenario: the station scenario (its protocol gives the variation, thresholds and timings).
        spec: the object (placed as scenario.object says, then varied by the seed).
        plan_function: (X_WO of the varied object, its spec) -> GraspPlan, for oracle and planner
            methods (the compliance-centric algorithm decides its grasp itself: `compliant.run_compliant_trial`).
        seed: the trial's seed: it fixes the variation, the same for every method.
        method, grasp: names for the record.
        replay_html: write a Meshcat replay there.
        monitor_period: how often the runner checks the executor's phase, s.
    """

    def wire(builder, station, scenario, spec, record) -> Wiring | None:
        """The plan's grasp executor, or None (UNREACHABLE in the record) when the arm cannot reach it."""
        protocol = scenario.protocol
        plant = station.plant
        q_start = np.asarray(protocol.start_configuration, float)
        try:
            plan = plan_function(station.X_WO_nominal(), spec)
            executor = GraspExecutor(plant, station.scene_graph, station.wam, plant.GetBodyIndices(station.hand),
                                     plan, q_start, protocol.execution)
        except ReachError as e:
            record.failure, record.detail = UNREACHABLE, str(e)
            return None
        record.estimate_source = getattr(plan, "source", "") or ""
        builder.AddNamedSystem("executor", executor)
        ConnectGraspExecutor(builder, station.diagram, executor)
        return Wiring(executor, q_start, protocol.execution.hold_time + 60.0)

    trial = assemble_and_run(scenario, spec, seed=seed, camera=False, wire=wire, replay_html=replay_html,
                             monitor_period=monitor_period, record_fields={"method": method, "grasp": grasp})
    trial.record.wall_time = trial.wall_time()
    return trial.record
