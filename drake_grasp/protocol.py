"""The trial protocol of the paper's Sec. 5 and 6 (docs/design.md §4.7), as scenario data.

Success = after lifting the object 10 cm off the table, no obvious slip within 10 s: here, the object
is off the table at the end and its pose relative to the palm moved less than 1 cm and 10 degrees
during the hold. Each trial varies the object's placement and friction by its seed, the same way for
every method. The numbers are choices (assumed where the paper gives none): they live in the
scenario YAML under `protocol`.
"""

import dataclasses
import math

import numpy as np


@dataclasses.dataclass
class ExecutionTimes:
    """Timing of the grasp sequence, s (choices: they live in the scenario's `protocol`)."""

    approach_speed: float = 0.05  # m/s
    touch_force: float = 2.0  # N: contact force on the hand that ends the approach
    close_time: float = 1.6  # s for the fingers to close and settle
    preshape_time: float = 1.2  # s
    lift_height: float = 0.10  # m
    lift_time: float = 1.5  # s
    hold_time: float = 10.0  # s

    joint_speed: float = 1.0  # rad/s: the largest joint speed of the move to the pre-grasp pose
    update_period: float = 0.01  # s


@dataclasses.dataclass
class TrialProtocol:
    """Attributes:
        position_variation: the object's x and y vary uniformly by up to this much, m.
        yaw_variation_deg: the object's yaw varies uniformly by up to this much, degrees.
        friction_variation: the object's friction coefficient varies by up to this fraction.
        slip_distance: largest object displacement in the palm frame during the hold, m.
        slip_angle_deg: largest object rotation in the palm frame during the hold, degrees.
        start_configuration: the WAM's joint angles at the start of a trial, rad.
        execution: timings of the grasp sequence.
    """

    position_variation: float = 0.01
    yaw_variation_deg: float = 10.0
    friction_variation: float = 0.2
    slip_distance: float = 0.01
    slip_angle_deg: float = 10.0
    start_configuration: list[float] = dataclasses.field(
        default_factory=lambda: [0.0, 0.6, 0.0, 1.6, 0.0, 0.9, 0.0])
    execution: ExecutionTimes = dataclasses.field(default_factory=ExecutionTimes)

    def validate(self) -> None:
        for name in ("position_variation", "yaw_variation_deg", "friction_variation", "slip_distance",
                     "slip_angle_deg"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise ValueError(f"protocol.{name} must be a finite number >= 0, got {value}")
        if self.friction_variation >= 1:
            raise ValueError("protocol.friction_variation must be below 1")
        if len(self.start_configuration) != 7 or not np.all(np.isfinite(self.start_configuration)):
            raise ValueError("protocol.start_configuration needs 7 finite joint angles")
        e = self.execution
        for name in ("approach_speed", "touch_force", "close_time", "preshape_time", "lift_height", "lift_time",
                     "joint_speed", "update_period"):
            value = getattr(e, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"protocol.execution.{name} must be a positive number, got {value}")
        if not (math.isfinite(e.hold_time) and e.hold_time >= 0):
            raise ValueError(f"protocol.execution.hold_time must be >= 0, got {e.hold_time}")


@dataclasses.dataclass(frozen=True)
class TrialVariation:
    """One trial's draw: object offset (m), yaw change (rad), friction scale."""

    dx: float
    dy: float
    dyaw: float
    friction_scale: float

    @classmethod
    def draw(cls, seed: int, protocol: TrialProtocol) -> "TrialVariation":
        """The variation of trial `seed`: the same for every method (numpy's PCG64 from the seed)."""
        rng = np.random.default_rng(seed)
        u = rng.uniform(-1.0, 1.0, size=4)
        return cls(
            dx=float(u[0] * protocol.position_variation),
            dy=float(u[1] * protocol.position_variation),
            dyaw=float(math.radians(u[2] * protocol.yaw_variation_deg)),
            friction_scale=float(1.0 + u[3] * protocol.friction_variation),
        )
