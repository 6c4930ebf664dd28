"""The three shape-resemblance primitives: sphere, cylinder, box.

They run in parallel once the depth and principal-axis primitives have converged (paper Sec. 4):
each observes every image, records how the silhouette's contour area and eccentricity vary with
where the camera is on its sphere around the object centre, and scores its shape from that
(`drake_grasp.primitives.scores`). Each also contributes the camera motion that tests its own
hypothesis, i.e. the motion under which its shape would look the same:

* cylinder: an arc about the object's principal axis (a cylinder is rotationally symmetric about it);
* sphere: an arc about the cross axis b (a sphere looks the same from everywhere; a cylinder does not
  when the camera tilts along its axis);
* box: none of its own — a box has no continuous symmetry; it reads the variation the other two
  provoke.

The arcs are scheduled in time (`arc_start`), so that the summed motion visits one arc after the
other: the sweeps about a and about b then stay apart in the regression (φa and φb are measured
from the camera's actual pose, not from the commands). On entering EXPLORE a primitive latches the
axis (an input) as its frame: a = the axis made perpendicular to the current view, b = view × a; the
arcs pivot about the depth primitive's current centre estimate (an input), which also sets the
distance that turns the silhouette's area into m² (a round object may roll a little while it is
looked at).
"""


import dataclasses

import numpy as np
from pydrake.systems.framework import Context

from drake_grasp.primitives import estimators, scores
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.common import PrimitiveCommand, SetDiscreteGroup, VisualPrimitive
from drake_grasp.primitives.silhouette import CameraSample

ARC_AXES = ("axis", "cross", "none")


@dataclasses.dataclass
class ResemblanceParams:
    """Choices of one resemblance primitive (the scenario's `perception:`, diagrams/station.scenarios.yaml).

    Attributes:
        arc_about: "axis" (rotate about the principal axis a), "cross" (about b) or "none".
        arc_amplitude: half-angle of the arc, rad.
        arc_start: when the arc starts after the command became EXPLORE, s.
        arc_period: duration of one back-and-forth sweep, s.
        arc_sweeps: number of sweeps.
        arc_gain: 1/s, correction of the arc angle toward its plan.
    """

    arc_about: str = "none"
    arc_amplitude: float = 0.6
    arc_start: float = 0.0
    arc_period: float = 4.0
    arc_sweeps: int = 1
    arc_gain: float = 2.0

    def validate(self) -> None:
        if self.arc_about not in ARC_AXES:
            raise ValueError(f"arc_about must be one of {ARC_AXES}, got {self.arc_about!r}")


DEFAULT_ARCS = {
    "cylinder": ResemblanceParams(arc_about="axis", arc_amplitude=0.7, arc_start=0.0, arc_period=4.0),
    "sphere": ResemblanceParams(arc_about="cross", arc_amplitude=0.5, arc_start=4.0, arc_period=3.0),
    "box": ResemblanceParams(arc_about="none"),
}


class ShapeResemblancePrimitive(VisualPrimitive):
    """The resemblance primitive of one shape (see the module docstring).

    Input ports:
        camera_sample (25), command (1): as every primitive.
        centre (3): the estimated object centre (world, m).
        axis (3): the estimated principal axis (world; or a rectangle side for a round object).
    Output ports:
        V_C_desired (6): desired camera twist [ω; v] in C.
        resemblance (1): how much the object resembles the shape, in [0, 1].
        evidence (9): `scores.ShapeEvidence.to_vector()` (variations, invariances, roundness, all three
            resemblances).
        frame (9): [centre when the frame was latched, a, b] (world), NaN before EXPLORE.
    """

    _STATS = slice(0, scores.FeatureStatistics.SIZE)
    _INTERNAL_SIZE = scores.FeatureStatistics.SIZE

    def __init__(self, shape: str, intrinsics: CameraIntrinsics, period: float,
                 params: ResemblanceParams | None = None, score_params: scores.ScoreParams | None = None,
                 confirm_time: float | None = None):
        """`confirm_time` (s): under CONFIRM the arc starts at once and lasts this long (the minimal
        exploration's confirming arc); None: CONFIRM runs the arc as EXPLORE does."""
        super().__init__(period)
        if shape not in scores.SHAPES:
            raise ValueError(f"unknown shape {shape!r}; expected one of {scores.SHAPES}")
        self.shape = shape
        self.intrinsics = intrinsics
        self.params = params or DEFAULT_ARCS[shape]
        self.params.validate()
        self.score_params = score_params or scores.ScoreParams()
        self._confirm_params = self.params if confirm_time is None else dataclasses.replace(
            self.params, arc_start=0.0, arc_period=confirm_time, arc_sweeps=1)
        self._centre_port = self.DeclareVectorInputPort("centre", 3)
        self._axis_port = self.DeclareVectorInputPort("axis", 3)
        self._resemblance = self.DeclareDiscreteState(np.zeros(1))
        self._evidence = self.DeclareDiscreteState(np.zeros(9))
        self._frame = self.DeclareDiscreteState(np.full(9, np.nan))
        self._internal = self.DeclareDiscreteState(np.zeros(self._INTERNAL_SIZE))
        self.DeclareStateOutputPort("resemblance", self._resemblance)
        self.DeclareStateOutputPort("evidence", self._evidence)
        self.DeclareStateOutputPort("frame", self._frame)
        self.DeclareCameraRateUpdate()

    def statistics_vector(self, context: Context) -> np.ndarray:
        """The `scores.FeatureStatistics` vector gathered so far (zeros before EXPLORE)."""
        return context.get_discrete_state(self._internal).get_value()[self._STATS].copy()

    def DoUpdate(self, context: Context, discrete_state, sample: CameraSample, new_sample: bool,
                 command: PrimitiveCommand, explore_time: float | None) -> np.ndarray:
        if not command.exploring:
            return np.zeros(6)  # this primitive only acts while exploring
        frame = context.get_discrete_state(self._frame).get_value().copy()
        internal = context.get_discrete_state(self._internal).get_value().copy()
        centre = self._centre_port.Eval(context)
        if explore_time < 0.5 * self.period:
            frame[:] = np.nan  # a new exploration: forget the previous one's frame
        if not np.all(np.isfinite(frame)):
            # Latch the frame (as soon as centre, axis and object are known); forget earlier statistics.
            axis = self._axis_port.Eval(context)
            if not (np.all(np.isfinite(centre)) and np.all(np.isfinite(axis)) and sample.visible):
                SetDiscreteGroup(discrete_state, self._frame, frame)
                return np.zeros(6)
            a, b = estimators.exploration_frame(axis, sample.p_WC - centre)
            frame = np.concatenate([centre, a, b])
            internal[:] = 0.0
            internal[self._STATS] = scores.FeatureStatistics().to_vector()
            SetDiscreteGroup(discrete_state, self._frame, frame)
        # The axes are latched; the centre is the depth primitive's current estimate (it may move).
        a, b = frame[3:6], frame[6:9]
        if new_sample and sample.usable:
            stats = scores.FeatureStatistics.from_vector(internal[self._STATS])
            phi_a, phi_b = estimators.view_angles(sample.p_WC, centre, a, b)
            distance = float(np.linalg.norm(sample.p_WC - centre))
            metric_area = sample.silhouette.area * distance**2 / (self.intrinsics.fx * self.intrinsics.fy)
            stats.add(phi_a, phi_b, metric_area, sample.silhouette.eccentricity)
            internal[self._STATS] = stats.to_vector()
            evidence = scores.evaluate(stats, self.score_params)
            SetDiscreteGroup(discrete_state, self._resemblance, [evidence.resemblance(self.shape)])
            SetDiscreteGroup(discrete_state, self._evidence, evidence.to_vector())
        SetDiscreteGroup(discrete_state, self._internal, internal)
        p = self._confirm_params if command == PrimitiveCommand.CONFIRM else self.params
        if p.arc_about == "none" or sample.silhouette is None:
            return np.zeros(6)
        return self.ArcTwist(discrete_state, sample, centre, a if p.arc_about == "axis" else b, explore_time, p)
