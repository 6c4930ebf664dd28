"""The principal-axis primitive: align the blob's axis with the image border, then arc about it.

Behaviour (docs/design.md §2, paper Sec. 4), per command:

* TRACK (and APPROACH): a servo rolls the camera about its optical axis so that the blob's principal
  axis (second-order central moments) lies along the image's u axis (the long border). It acts only
  on an elongated object (see `elongated` below) seen as an elongated blob (eccentricity ≥
  `servo_min_eccentricity`): a round blob has no axis to align, and a cube seen at a tilt looks
  elongated along the tilt, which is not an axis of the object.
* EXPLORE: TRACK, plus an arc about the camera's x axis through the estimated object centre (an
  input: the depth primitive's estimate). After the servo has aligned the blob, the camera's x axis
  is the image of the object's axis, so the arc runs *around* the axis: if that is the object's axis
  in space, the blob's axis does not turn in the image (invariance) and the servo has nothing to do.
  Its motion (rotation about x) is orthogonal to the depth primitive's (rotation about y): the two
  run in parallel.

Estimate: every image line along the blob's axis (through its centroid) back-projects to a plane
that contains the object's axis in space; the axis is the direction common to all these planes
(`estimators.axis_from_planes`). `elongated` says whether the object has a principal axis: the mean
eccentricity over the views reaches `elongated_eccentricity`. For an object that has none, the
"axis" output is the direction of a side of the silhouette's minimum-area rectangle (the side nearest
u; a cube's edge, an arbitrary direction for a sphere), from the planes of those sides and sought
across the first view direction, so that the resemblance primitives always get a frame.
"""


import dataclasses
import math

import numpy as np
from pydrake.systems.framework import Context

from drake_grasp.primitives import estimators
from drake_grasp.primitives.camera_model import CameraIntrinsics, wrap_angle
from drake_grasp.primitives.common import PrimitiveCommand, SetDiscreteGroup, VisualPrimitive
from drake_grasp.primitives.silhouette import CameraSample


@dataclasses.dataclass
class PrincipalAxisParams:
    """Choices of the principal-axis primitive (the scenario's `perception:`, diagrams/station.scenarios.yaml).

    Attributes:
        roll_gain: rad/s of roll per rad of blob-axis angle.
        servo_min_eccentricity: the roll servo acts on blobs at least this eccentric.
        elongated_eccentricity: mean eccentricity from which the object has a principal axis.
        arc_amplitude: half-angle of the arc about the axis, rad.
        arc_period: duration of one back-and-forth sweep, s.
        arc_sweeps: sweeps per exploration.
        arc_start: when the arc starts after the command became EXPLORE, s.
        arc_gain: 1/s, correction of the arc angle toward its plan.
    """

    roll_gain: float = 3.0
    servo_min_eccentricity: float = 1.15
    elongated_eccentricity: float = 1.2
    arc_amplitude: float = 0.35
    arc_period: float = 2.0
    arc_sweeps: int = 1
    arc_start: float = 2.0
    arc_gain: float = 2.0


class PrincipalAxisPrimitive(VisualPrimitive):
    """The principal-axis primitive (see the module docstring).

    Input ports:
        camera_sample (25), command (1): as every primitive.
        centre (3): the estimated object centre (world, m): the pivot of the arc.
    Output ports:
        V_C_desired (6): desired camera twist [ω; v] in C.
        axis (3): unit direction in the world (its sign is arbitrary; NaN before the first image).
        axis_info (3): [elongated (1 or 0), mean eccentricity, planes' spread (the second smallest
            eigenvalue of Σ n nᵀ per view: near 0 while all views saw the axis from one side)].
    """

    _M_AXIS, _M_SIDE, _COUNT, _LOG_ECC, _VIEW0 = slice(0, 9), slice(9, 18), 18, 19, slice(20, 23)
    _INTERNAL_SIZE = 23

    def __init__(self, intrinsics: CameraIntrinsics, period: float, params: PrincipalAxisParams | None = None):
        super().__init__(period)
        self.intrinsics = intrinsics
        self.params = params or PrincipalAxisParams()
        self._centre_port = self.DeclareVectorInputPort("centre", 3)
        self._axis = self.DeclareDiscreteState(np.full(3, np.nan))
        self._info = self.DeclareDiscreteState(np.array([0.0, np.nan, 0.0]))
        self._internal = self.DeclareDiscreteState(np.zeros(self._INTERNAL_SIZE))
        self.DeclareStateOutputPort("axis", self._axis)
        self.DeclareStateOutputPort("axis_info", self._info)
        self.DeclareCameraRateUpdate()

    def DoUpdate(self, context: Context, discrete_state, sample: CameraSample, new_sample: bool,
                 command: PrimitiveCommand, explore_time: float | None) -> np.ndarray:
        p = self.params
        s = sample.silhouette
        internal = context.get_discrete_state(self._internal).get_value().copy()
        elongated = context.get_discrete_state(self._info).get_value()[0] > 0.5
        if new_sample and sample.usable:
            if internal[self._COUNT] == 0:
                internal[self._VIEW0] = sample.R_WC[:, 2]
            # The blob's axis (moments) where it has one; the rectangle side nearest u always.
            M_axis = internal[self._M_AXIS].reshape(3, 3).copy()
            M_side = internal[self._M_SIDE].reshape(3, 3).copy()
            if s.eccentricity >= p.servo_min_eccentricity:
                estimators.add_plane(M_axis, estimators.image_line_plane_W(
                    self.intrinsics, sample.R_WC, s.centroid, wrap_angle(s.axis_angle, math.pi)))
            estimators.add_plane(M_side, estimators.image_line_plane_W(
                self.intrinsics, sample.R_WC, s.centroid, wrap_angle(s.rectangle.angle, math.pi / 2.0)))
            internal[self._M_AXIS] = M_axis.ravel()
            internal[self._M_SIDE] = M_side.ravel()
            internal[self._COUNT] += 1
            internal[self._LOG_ECC] += math.log(s.eccentricity)
            count = internal[self._COUNT]
            mean_ecc = math.exp(internal[self._LOG_ECC] / count)
            elongated = mean_ecc >= p.elongated_eccentricity and np.trace(M_axis) > 0
            if elongated:
                axis, eigenvalues = estimators.axis_from_planes(M_axis)
            else:
                # A round object's "axis" is a silhouette side, sought across the first view: its lines'
                # planes, all seen from about there, would otherwise share the view direction itself.
                axis, eigenvalues = estimators.axis_from_planes(M_side, internal[self._VIEW0])
            SetDiscreteGroup(discrete_state, self._internal, internal)
            SetDiscreteGroup(discrete_state, self._axis, axis)
            SetDiscreteGroup(discrete_state, self._info, [float(elongated), mean_ecc, eigenvalues[1] / count])
        if s is None:
            return np.zeros(6)
        twist = np.zeros(6)
        if s.eccentricity >= p.servo_min_eccentricity and elongated:
            # A line at angle θ in the image turns by −ψ when the camera rolls by ψ about +z.
            twist[2] = p.roll_gain * wrap_angle(s.axis_angle, math.pi)
        # The arc: about the camera's x axis (at the arc's start: the blob's axis), around the centre.
        centre = self._centre_port.Eval(context)
        twist += self.ArcTwist(discrete_state, sample, centre, sample.R_WC[:, 0], explore_time, p)
        return twist
