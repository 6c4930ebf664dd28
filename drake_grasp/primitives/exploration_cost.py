"""What an exploration cost: its simulated time, the camera's path (m and rad) and the images it used.

The paper calls its exploration a proof of concept: "it is not practical to move the camera around an
object prior to each grasp" (Sec. 4). On a robot an exploration is paid for in time and in arm motion,
and in simulation in rendered images. `ExplorationCost` measures all three from the camera's samples
(one per rendered image, `SilhouetteCamera`), while the camera runs:

* images: the samples taken;
* time: the simulated time of the last one, s (every exploration starts at t = 0);
* path: the distance the camera's optical centre travelled, m, and the angle its orientation turned
  through, rad (the sum, over successive images, of the geodesic angle between their orientations).

Successive images are one camera period apart, so the path is the polygon through the camera's
poses at the images: a lower bound of the true path that misses only motion within one period.
It steers nothing. The system reads each sample half a period after it was taken, so the last image
counts as soon as the next half period has passed.
"""

import dataclasses
import math

import numpy as np
from pydrake.systems.framework import BasicVector, Context, LeafSystem

from drake_grasp.primitives.silhouette import CameraSample

# The state: images, time of the last image (s), path (m), turn (rad), then the last pose: p_WC (3),
# R_WC (9, row-major).
_STATE_SIZE = 4 + 3 + 9


@dataclasses.dataclass(frozen=True)
class CostVector:
    """The `cost` output: [images, time (s), path (m), turn (rad)]."""

    SIZE = 4

    images: int
    time: float
    path: float
    turn: float

    @classmethod
    def from_vector(cls, v) -> "CostVector":
        v = np.asarray(v, float)
        return cls(int(round(v[0])), float(v[1]), float(v[2]), float(v[3]))

    def to_dict(self) -> dict:
        """What it cost, as the record's `exploration` has it (beside what kind of exploration ran)."""
        return {"time_s": self.time, "path_m": self.path, "path_rad": self.turn, "images": self.images}


def rotation_angle(R_a: np.ndarray, R_b: np.ndarray) -> float:
    """The angle of the rotation that takes orientation R_a to R_b, rad (in [0, π])."""
    cosine = (float(np.trace(np.asarray(R_a).T @ np.asarray(R_b))) - 1.0) / 2.0
    return math.acos(min(1.0, max(-1.0, cosine)))


class ExplorationCost(LeafSystem):
    """Sums the camera's path and images over an exploration (module docstring).

    Input ports:
        camera_sample (25): the silhouette camera's latest sample (`CameraSample.to_vector`).
    Output ports:
        cost (4): [images, time of the last image (s), path (m), turn (rad)] (`CostVector`).
    """

    def __init__(self, period: float):
        """
        Args:
            period: the camera's period, s (the samples are read half a period after each image).
        """
        super().__init__()
        self._sample_port = self.DeclareVectorInputPort("camera_sample", CameraSample.SIZE)
        initial = np.zeros(_STATE_SIZE)
        initial[1] = -math.inf  # no image yet
        self._state = self.DeclareDiscreteState(initial)
        self.DeclarePeriodicDiscreteUpdateEvent(period, period / 2, self._Update)
        self.DeclareVectorOutputPort("cost", CostVector.SIZE, self._CalcCost, {self.xd_ticket()})

    def _Update(self, context: Context, discrete_state) -> None:
        sample = np.asarray(self._sample_port.Eval(context), float)
        x = np.array(context.get_discrete_state(self._state).get_value())
        time, p, R = float(sample[0]), sample[13:16], sample[16:25].reshape(3, 3)
        if time < 0 or not time > x[1]:  # no image yet, or none since the last update (the camera stopped)
            return
        if x[0] > 0:
            x[2] += float(np.linalg.norm(p - x[4:7]))
            x[3] += rotation_angle(x[7:16].reshape(3, 3), R)
        x[0] += 1
        x[1] = time
        x[4:7], x[7:16] = p, R.reshape(-1)
        discrete_state.get_mutable_vector(self._state).SetFromVector(x)

    def _CalcCost(self, context: Context, output: BasicVector) -> None:
        x = context.get_discrete_state(self._state).get_value()
        output.SetFromVector([x[0], max(x[1], 0.0), x[2], x[3]])
