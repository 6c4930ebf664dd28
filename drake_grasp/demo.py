"""The station demo: pick an object up with the hand's compliance, using its ground-truth pose.

The arm brings the open hand above the object, descends along the palm normal until the palm touches
it (or reaches its top), closes the fingers with torque close and breakaway, lifts 10 cm and holds
10 s; the demo says whether the object was held and how much it slipped in the hand during the hold.

It is one oracle trial (`trial.run`: the compliant grasp of the chosen compliance mode computed
from the object's true pose and size): spherical mode -> the spherical grasp; cylindrical mode -> the
cylindrical grasp for elongated objects, the box grasp for the others.
"""

import dataclasses
import math

from drake_grasp import trial
from drake_grasp.grasps import GraspType
from drake_grasp.robot.hand import ComplianceMode
from drake_grasp.objects import ObjectSpec, resolve_object
from drake_grasp.station import Scenario


@dataclasses.dataclass
class DemoResult:
    """What happened. Distances in m, angles in rad, times in s."""

    object_name: str
    mode: str
    grasp: str
    held: bool
    failure: str
    lift: float  # how far the object rose above its resting height at the end
    slip_distance: float  # object position change in the palm frame during the hold
    slip_angle: float  # object orientation change in the palm frame during the hold
    hold_time: float
    breakaway: list[bool]
    breakaway_angles: list[float]  # proximal angle at which each clutch slipped (nan: it did not)
    final_finger_angles: list[float]  # spread, proximal 1..3, distal 1..3
    sim_time: float
    wall_time: float

    def summary(self) -> str:
        verdict = "held" if self.held else f"NOT held ({self.failure})"
        angles = ", ".join("-" if not math.isfinite(a) else f"{math.degrees(a):.0f}" for a in self.breakaway_angles)
        slip = (f"slip over the {self.hold_time:.0f} s hold {self.slip_distance * 1000:.2f} mm, "
                f"{math.degrees(self.slip_angle):.2f} deg" if math.isfinite(self.slip_distance) else "no hold")
        lift = f"lifted {self.lift * 100:.1f} cm" if math.isfinite(self.lift) else "not lifted"
        return (
            f"{self.object_name} ({self.mode} mode, {self.grasp} grasp): {verdict}; {lift}; {slip}; "
            f"breakaway at [{angles}] deg; {self.sim_time:.1f} s simulated in {self.wall_time:.1f} s "
            f"({self.sim_time / max(self.wall_time, 1e-9):.1f}x real time)"
        )


def default_mode(spec: ObjectSpec) -> ComplianceMode:
    """Spherical mode for round objects, cylindrical for the rest (ground truth: the demo only)."""
    return ComplianceMode.SPHERICAL if spec.closest_primitive == "sphere" else ComplianceMode.CYLINDRICAL


def grasp_for_mode(mode: ComplianceMode, spec: ObjectSpec) -> GraspType:
    """The compliant grasp the demo uses for a compliance mode on an object."""
    if mode == ComplianceMode.SPHERICAL:
        return GraspType.SPHERICAL
    return GraspType.CYLINDRICAL if spec.principal_axis is not None else GraspType.BOX


def run_demo(scenario: Scenario, mode: ComplianceMode | None = None, replay_html: str | None = None,
             object_spec: ObjectSpec | None = None, hold_time: float | None = None, seed: int = 0) -> DemoResult:
    """Runs the pick-up and judges it.

    Args:
        scenario: the station's scenario (its object placement says what to pick up).
        mode: the compliance mode (default: `default_mode` of the object).
        replay_html: if given, write a Meshcat replay there.
        object_spec: the object, if already resolved.
        hold_time: how long to hold after the lift, s (default: the scenario's protocol, 10 s).
        seed: the trial seed (the object's small placement and friction variation).
    """
    spec = object_spec or resolve_object(scenario.object.name)
    mode = mode or default_mode(spec)
    grasp = grasp_for_mode(mode, spec)
    if hold_time is not None:
        scenario = dataclasses.replace(scenario, protocol=dataclasses.replace(
            scenario.protocol, execution=dataclasses.replace(scenario.protocol.execution, hold_time=hold_time)))
    record = trial.run(trial.TrialSpec(scenario.object.name, "oracle", grasp.value, seed), replay_html,
                       scenario=scenario, obj=spec)
    return DemoResult(
        object_name=spec.name, mode=mode.name.lower(), grasp=grasp.value, held=record.success,
        failure=record.failure, lift=record.lift, slip_distance=record.slip_distance,
        slip_angle=record.slip_angle, hold_time=scenario.protocol.execution.hold_time,
        breakaway=record.breakaway, breakaway_angles=record.breakaway_angles,
        final_finger_angles=record.finger_angles, sim_time=record.sim_time, wall_time=record.wall_time,
    )
