"""The object estimate: what the visual primitives found, gathered into one value.

`gather_estimate` (pure) turns the primitives' outputs — the depth primitive's centre and extents,
the principal axis and whether the object is elongated, the three shape resemblances — into an
`ObjectEstimate` in the world frame. `ObjectEstimator` is the LeafSystem that does it inside the
Diagram, so a supervisor reads one `estimate` port instead of a dozen; the exploration reads the same
port when it ends.
"""

import dataclasses
import math

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import Context, LeafSystem

from drake_grasp.primitives.scores import SHAPES
from drake_grasp.primitives.sequencer import ExplorationPhase, phase_value
from drake_grasp.primitives.silhouette import CameraSample

OBJECT_NOT_FOUND = "object not found"

@dataclasses.dataclass
class ObjectEstimate:
    """What one exploration found (world frame W; m, rad, s).

    Attributes:
        status: "ok", or "object not found" (the object never came into view).
        centre: the object centre (where the rays through the silhouette centroids meet), or None.
        depth: distance from `camera_position` (the camera at the end) to the centre.
        camera_position: where the camera was when the exploration ended.
        principal_axis: unit vector of the object's long axis, or None if the object is not elongated.
        axes: 3×3, columns (a, b, c): a = the principal axis (or, for a round object, the direction of
            a silhouette side), b = horizontal across it, c = a × b (up).
        extents: the object's size along a, b, c: length and width from the silhouette's tangent
            planes; height = twice the centre's height above the table (it rests on the table).
        resemblances: {"sphere", "cylinder", "box"} → resemblance in [0, 1].
        evidence: what the resemblances rest on (variations, invariances, roundness; see scores).
        elongation: the mean eccentricity of the silhouette over the exploration.
        timings: build, simulated and wall-clock times, frames rendered, phase start times.
    """

    status: str
    centre: np.ndarray | None = None
    depth: float = math.nan
    camera_position: np.ndarray | None = None
    principal_axis: np.ndarray | None = None
    axes: np.ndarray | None = None
    extents: np.ndarray | None = None
    resemblances: dict = dataclasses.field(default_factory=dict)
    evidence: dict = dataclasses.field(default_factory=dict)
    elongation: float = math.nan
    timings: dict = dataclasses.field(default_factory=dict)

    @property
    def found(self) -> bool:
        return self.status == "ok"

    @property
    def best_shape(self) -> str | None:
        """The shape with the highest resemblance (the compliant grasp to execute), or None."""
        if not self.resemblances:
            return None
        return max(SHAPES, key=lambda s: self.resemblances.get(s, 0.0))

    def as_grasp_estimate(self):
        """This estimate as `drake_grasp.grasps.ObjectEstimate` (what the compliant grasps take)."""
        from drake_grasp.grasps import ObjectEstimate as GraspEstimate

        if not self.found:
            raise ValueError("no estimate: the object was not found")
        return GraspEstimate(center=np.array(self.centre), R_WB=np.array(self.axes), size=np.array(self.extents),
                             principal_axis=None if self.principal_axis is None else np.array(self.principal_axis),
                             source="camera")

    def to_dict(self) -> dict:
        """Plain data (lists, floats) for JSON."""

        def plain(x):
            if isinstance(x, np.ndarray):
                return x.tolist()
            if isinstance(x, dict):
                return {k: plain(v) for k, v in x.items()}
            if isinstance(x, (list, tuple)):
                return [plain(v) for v in x]
            if isinstance(x, (np.floating, np.integer)):
                return x.item()
            return x

        return {f.name: plain(getattr(self, f.name)) for f in dataclasses.fields(self)}


# Names of the box resemblance primitive's `evidence` entries kept in the estimate.
EVIDENCE_NAMES = ("variation_a", "variation_b", "eccentricity_0", "invariance_a", "invariance_b", "roundness")


def estimate_axes(axis: np.ndarray, elongated: bool) -> tuple[np.ndarray, np.ndarray | None]:
    """The object's axes (a, b, c as columns) and principal axis (or None) from the axis primitive.

    a is the principal axis when the object is elongated; otherwise the direction of a silhouette side,
    taken horizontal. b is horizontal across a, and c = a × b (up for a horizontal a).
    """
    up = np.array([0.0, 0.0, 1.0])
    a = np.asarray(axis, float) if np.all(np.isfinite(axis)) else np.array([1.0, 0.0, 0.0])
    if not elongated:
        a = a - a[2] * up
        a = a / np.linalg.norm(a) if np.linalg.norm(a) > 1e-6 else np.array([1.0, 0.0, 0.0])
    b = np.cross(up, a)
    if np.linalg.norm(b) < 1e-6:  # a vertical axis: any horizontal b
        b = np.array([0.0, 1.0, 0.0])
    b /= np.linalg.norm(b)
    c = np.cross(a, b)
    return np.column_stack([a, b, c]), (a.copy() if elongated else None)


def gather_estimate(phase: ExplorationPhase, centre: np.ndarray, camera_position: np.ndarray, axis: np.ndarray,
                    axis_info: np.ndarray, extents: np.ndarray, resemblances: dict, evidence: np.ndarray
                    ) -> ObjectEstimate:
    """The ObjectEstimate from the primitives' outputs (see `ObjectEstimator`'s ports for each)."""
    if phase == ExplorationPhase.NOT_FOUND or not np.all(np.isfinite(centre)):
        return ObjectEstimate(status=OBJECT_NOT_FOUND)
    elongated, mean_eccentricity = axis_info[0] > 0.5, axis_info[1]
    axes, principal_axis = estimate_axes(axis, elongated)
    centre = np.array(centre, float)
    camera_position = np.array(camera_position, float)
    return ObjectEstimate(
        status="ok", centre=centre, depth=float(np.linalg.norm(centre - camera_position)),
        camera_position=camera_position, principal_axis=principal_axis, axes=axes,
        extents=np.array(extents, float), resemblances={s: float(resemblances[s]) for s in SHAPES},
        evidence={n: float(v) for n, v in zip(EVIDENCE_NAMES, evidence)}, elongation=float(mean_eccentricity))


class ObjectEstimator(LeafSystem):
    """Gathers the primitives' outputs into one ObjectEstimate (no state: a function of its inputs).

    Input ports:
        phase (1): the exploration sequencer's ExplorationPhase (NOT_FOUND: no estimate).
        camera_sample (25): the latest camera sample (for the camera's position).
        centre (3), extents (3): from the depth primitive, m.
        axis (3), axis_info (3): from the principal axis primitive.
        sphere_resemblance, cylinder_resemblance, box_resemblance (1 each): in [0, 1].
        evidence (9): from the box resemblance primitive (its `evidence` output).
    Output ports:
        estimate: the ObjectEstimate (abstract).
    """

    def __init__(self):
        super().__init__()
        for name, size in (("phase", 1), ("camera_sample", CameraSample.SIZE), ("centre", 3), ("extents", 3),
                           ("axis", 3), ("axis_info", 3)):
            self.DeclareVectorInputPort(name, size)
        for shape in SHAPES:
            self.DeclareVectorInputPort(f"{shape}_resemblance", 1)
        self.DeclareVectorInputPort("evidence", 9)
        self.DeclareAbstractOutputPort("estimate", lambda: AbstractValue.Make(ObjectEstimate(status=OBJECT_NOT_FOUND)),
                                       self._CalcEstimate, {self.all_input_ports_ticket()})

    def _CalcEstimate(self, context: Context, output: AbstractValue) -> None:
        def read(name):
            return np.asarray(self.GetInputPort(name).Eval(context), float)

        output.set_value(gather_estimate(
            phase_value(read("phase")[0]), read("centre"), read("camera_sample")[13:16], read("axis"),
            read("axis_info"), read("extents"), {s: read(f"{s}_resemblance")[0] for s in SHAPES}, read("evidence")))
