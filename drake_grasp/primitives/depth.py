"""The depth primitive: keep the object centred while circling it; the image drift gives the depth.

Behaviour (docs/design.md §2, paper Sec. 4), per command:

* TRACK: a proportional servo turns the camera so that the silhouette's centroid stays at the image
  centre (rotation about the camera's own origin).
* APPROACH: TRACK, and move along the optical axis until the silhouette's longer side spans
  `approach_fraction` of the image width (never below `min_camera_height` above the table; a choice
  so that small objects are seen large enough and large ones whole).
* EXPLORE: TRACK, plus an arc: the camera rotates about its y axis around the point where it
  currently believes the object centre to be (at the estimated depth), sweeping back and forth. If
  the estimate is right the object does not move in the image; if not, it drifts, the servo turns
  the camera after it, and the rays through the drifting centroid meet elsewhere: the estimate
  moves there (`estimators.add_ray`). The camera thus converges to circling the object centre at
  radius = the estimated depth.
* In every mode but OFF: if the silhouette touches the image border the camera backs off along its
  optical axis (the object may be cut).

Estimates (outputs), two estimators of the same views:

* the rays through the silhouette's centroid (`estimators.add_ray`): the drift correction above.
  Fast and well conditioned from the first arc on, but the centroid of a perspective silhouette is
  not the projection of the object's centre (from above one sees a box's top face, whose centre is
  higher), so it is only used until the views have spread (`fit_min_tilt`), and as a weak prior.
* the tangent planes (`estimators.tangent_planes`, `estimators.fit_support`): the four sides of the
  silhouette's bounding rectangle back-project to planes tangent to the object, exact under
  perspective. A support-function model (a box grown by a disc and a sphere, in the frame of the
  principal axis — an input from the principal-axis primitive — with "it rests on the table" as one
  more equation) fitted to all of them gives the object centre, and its extents along the axis,
  across it and vertically. Older views weigh less (`forget_time`): the estimate follows an object
  that creeps or rolls on the table.
* an upright object (a carton standing on the table: its principal axis is vertical) gives the fit
  no horizontal direction: the axis made horizontal is only the direction of its few degrees of tilt
  error, unrelated to the object's sides. A box model at 30-60° to the sides cannot fit them, and the
  bounded fit leaves the width across that direction at its bound, 0 (a 10 × 3 × 15 cm box: 1e-21 m,
  or exactly 0). Its extents are therefore fitted again in the frame of its side faces
  (`estimators.face_direction` of the same planes), and `extents_frame` says which direction the
  first extent is along. The centre stays that of the first fit, so the exploration itself (the
  centre steers the arcs) is the same as before for every object.

The depth is the distance from the latest camera position to the estimated centre.
"""


import dataclasses
import math

import numpy as np
from pydrake.systems.framework import Context

from drake_grasp.primitives import estimators
from drake_grasp.primitives.camera_model import CameraIntrinsics, centring_twist
from drake_grasp.primitives.common import PrimitiveCommand, SetDiscreteGroup, VisualPrimitive
from drake_grasp.primitives.silhouette import CameraSample


@dataclasses.dataclass
class DepthParams:
    """Choices of the depth primitive (the scenario's `perception:`, diagrams/station.scenarios.yaml).

    Attributes:
        centring_gain: rad/s of camera rotation per rad of centroid offset.
        arc_amplitude: half-angle of the exploratory arc, rad.
        arc_period: duration of one back-and-forth sweep, s.
        arc_sweeps: sweeps per exploration.
        arc_start: when the arc starts after the command became EXPLORE, s.
        arc_gain: 1/s, correction of the arc angle toward its plan (from the measured camera pose).
        initial_depth: depth assumed along the first ray (the prior), m.
        prior_weight: weight of that prior, in rays (small: the data take over once the camera moves).
        approach_fraction: APPROACH stops when the silhouette's long side spans this part of the width.
        approach_gain: 1/s, forward speed = gain · log(wanted/seen size) · distance.
        approach_speed: largest forward or backward speed when approaching, m/s.
        min_camera_height: the camera does not approach below this height above the table, m.
        table_height: height of the table top in the world, m.
        back_off_speed: backward speed while the silhouette touches the image border, m/s.
        fit_min_tilt: the tangent-plane fit replaces the rays' estimate once the camera has turned
            this far (rad) from its first view (before, all planes come from one side).
        ray_prior_weight: weight (in planes) of the rays' centre as a prior of the fit.
        table_weight: weight (in planes) of "the object rests on the table" in the fit.
        max_views: views kept for the fit (later ones are not stored).
        forget_time: s, older views weigh exp(−age / forget_time) (0: never forget). A round object
            may roll on the table while it is looked at; the estimate follows it.
    """

    centring_gain: float = 3.0
    arc_amplitude: float = 0.35
    arc_period: float = 2.0
    arc_sweeps: int = 1
    arc_start: float = 0.0
    arc_gain: float = 2.0
    initial_depth: float = 0.35
    prior_weight: float = 0.05
    approach_fraction: float = 0.45
    approach_gain: float = 1.5
    approach_speed: float = 0.15
    min_camera_height: float = 0.22
    table_height: float = 0.0
    back_off_speed: float = 0.08
    fit_min_tilt: float = 0.15
    ray_prior_weight: float = 0.3
    table_weight: float = 10.0
    max_views: int = 400
    forget_time: float = 4.0


class DepthPrimitive(VisualPrimitive):
    """The depth primitive (see the module docstring).

    Input ports:
        camera_sample (25): from SilhouetteCamera.
        command (1): a PrimitiveCommand.
        axis (3): the principal-axis primitive's axis (world), the frame of the size model (NaN: none
            yet; the silhouette's long side is used).
    Output ports:
        V_C_desired (6): desired camera twist [ω; v] in C.
        centre (3): estimated object centre, world, m (NaN until the object has been seen).
        depth (1): distance from the latest camera position to the estimated centre, m (NaN before).
        extents (3): the object's extents along `extents_frame`, across it horizontally, and vertically, m.
        extents_frame (3): the horizontal unit direction (world) of the first extent: the axis made
            horizontal, or for an upright axis the direction of the object's side faces (NaN before).
        fit_info (8): [the tangent-plane fit is in use (1/0), its rms residual (m), planes stored, and
            the fitted support parameters (s_a, s_b, s_z, ρ, r), m (see estimators.SupportFit)], of the
            fit in the axis's frame (the centre's; an upright object's extents come from a second fit).
    """

    # Layout of the internal state group (the tangent planes follow).
    _A, _B, _COUNT, _VIEW0, _MAX_TILT, _LAST_TIME, _PLANES = slice(0, 9), slice(9, 12), 12, slice(13, 16), 16, 17, 18
    _VIEW_SIZE = 17  # per view: the time, then 4 tangent planes [ν, o]

    def __init__(self, intrinsics: CameraIntrinsics, period: float, params: DepthParams | None = None):
        super().__init__(period)
        self.intrinsics = intrinsics
        self.params = params or DepthParams()
        self._axis_port = self.DeclareVectorInputPort("axis", 3)
        self._centre = self.DeclareDiscreteState(np.full(3, np.nan))
        self._depth = self.DeclareDiscreteState(np.full(1, np.nan))
        self._extents = self.DeclareDiscreteState(np.full(3, np.nan))
        self._extents_frame = self.DeclareDiscreteState(np.full(3, np.nan))
        self._fit_info = self.DeclareDiscreteState(np.zeros(8))
        self._internal = self.DeclareDiscreteState(np.zeros(self._PLANES + self._VIEW_SIZE * self.params.max_views))
        self.DeclareStateOutputPort("centre", self._centre)
        self.DeclareStateOutputPort("depth", self._depth)
        self.DeclareStateOutputPort("extents", self._extents)
        self.DeclareStateOutputPort("extents_frame", self._extents_frame)
        self.DeclareStateOutputPort("fit_info", self._fit_info)
        self.DeclareCameraRateUpdate()

    def DoUpdate(self, context: Context, discrete_state, sample: CameraSample, new_sample: bool,
                 command: PrimitiveCommand, explore_time: float | None) -> np.ndarray:
        p = self.params
        centre = context.get_discrete_state(self._centre).get_value().copy()
        if new_sample and sample.usable:
            internal = context.get_discrete_state(self._internal).get_value().copy()
            centre, extents, extents_frame, fit_info = self._Estimate(internal, sample, self._axis_port.Eval(context))
            SetDiscreteGroup(discrete_state, self._internal, internal)
            SetDiscreteGroup(discrete_state, self._centre, centre)
            SetDiscreteGroup(discrete_state, self._depth, [np.linalg.norm(centre - sample.p_WC)])
            SetDiscreteGroup(discrete_state, self._extents, extents)
            SetDiscreteGroup(discrete_state, self._extents_frame, extents_frame)
            SetDiscreteGroup(discrete_state, self._fit_info, fit_info)
        s = sample.silhouette
        if s is None:
            return np.zeros(6)  # nothing to look at: hold still
        twist = centring_twist(*self.intrinsics.angles(*s.centroid), p.centring_gain)
        forward = 0.0
        if s.touches_border:
            forward = -p.back_off_speed
        elif command == PrimitiveCommand.APPROACH:
            forward = self._ApproachSpeed(sample, centre)
        twist[5] += forward
        # The arc: about the camera's y axis (at the arc's start), around the estimated centre.
        twist += self.ArcTwist(discrete_state, sample, centre, sample.R_WC[:, 1], explore_time, p)
        return twist

    def _Estimate(self, internal: np.ndarray, sample: CameraSample, axis: np.ndarray):
        """Adds the sample's ray and tangent planes to `internal`; returns (centre, extents, extents_frame,
        fit_info)."""
        p = self.params
        s = sample.silhouette
        A = internal[self._A].reshape(3, 3).copy()
        b = internal[self._B].copy()
        r_W = sample.R_WC @ self.intrinsics.ray(*s.centroid)
        count = int(internal[self._COUNT])
        if count > 0 and p.forget_time > 0:  # older rays weigh less (the object may move)
            decay = math.exp(-(sample.time - internal[self._LAST_TIME]) / p.forget_time)
            A *= decay
            b *= decay
        internal[self._LAST_TIME] = sample.time
        if count == 0:
            A += p.prior_weight * np.eye(3)
            b += p.prior_weight * (sample.p_WC + p.initial_depth * r_W)
            internal[self._VIEW0] = -r_W
        along_W = estimators.image_direction_W(self.intrinsics, sample.R_WC, s.centroid, s.axis_angle)
        estimators.add_ray(A, b, sample.p_WC, r_W, 1.0, along_W, s.eccentricity ** -2)
        internal[self._A] = A.ravel()
        internal[self._B] = b
        ray_centre = estimators.solve_point(A, b)
        view = sample.p_WC - ray_centre
        tilt = math.acos(float(np.clip(np.dot(view / np.linalg.norm(view), internal[self._VIEW0]), -1.0, 1.0)))
        internal[self._MAX_TILT] = max(internal[self._MAX_TILT], tilt)
        if count < p.max_views:
            planes = estimators.tangent_planes(self.intrinsics, sample.R_WC, sample.p_WC, s.rectangle)
            start = self._PLANES + self._VIEW_SIZE * count
            internal[start] = sample.time
            internal[start + 1:start + self._VIEW_SIZE] = planes.ravel()
            count += 1
            internal[self._COUNT] = count
        if not np.all(np.isfinite(axis)):  # no axis yet: the silhouette's long side
            axis = estimators.image_direction_W(self.intrinsics, sample.R_WC, s.centroid, s.rectangle.angle)
        views = internal[self._PLANES:self._PLANES + self._VIEW_SIZE * count].reshape(-1, self._VIEW_SIZE)
        planes = views[:, 1:].reshape(-1, 4)
        weights = np.ones(len(planes))
        if p.forget_time > 0:
            weights = np.repeat(np.exp(-(sample.time - views[:, 0]) / p.forget_time), 4)
        fit = estimators.fit_support(planes, axis, _UP, p.table_height, p.table_weight, ray_centre,
                                     p.ray_prior_weight, weights)
        use_fit = internal[self._MAX_TILT] >= p.fit_min_tilt
        centre = fit.centre if use_fit else ray_centre
        sizes = fit
        if estimators.is_upright(axis):  # an upright object: its size in the frame of its sides
            faces = estimators.face_direction(planes, weights)
            if faces is not None:
                sizes = estimators.fit_support(planes, faces, _UP, p.table_height, p.table_weight, ray_centre,
                                               p.ray_prior_weight, weights)
        return (centre, sizes.extents(), sizes.frame[0].copy(),
                np.concatenate([[float(use_fit), fit.rms, float(len(planes))], fit.parameters]))

    def _ApproachSpeed(self, sample: CameraSample, centre: np.ndarray) -> float:
        """Forward speed (m/s) that brings the silhouette to the wanted size, within the height limit."""
        p = self.params
        seen = max(sample.silhouette.rectangle.length, 1.0)
        wanted = p.approach_fraction * self.intrinsics.width
        distance = np.linalg.norm(centre - sample.p_WC) if np.all(np.isfinite(centre)) else p.initial_depth
        speed = float(np.clip(p.approach_gain * math.log(wanted / seen) * distance, -p.approach_speed,
                              p.approach_speed))
        descent_rate = -sample.R_WC[2, 2]  # how fast the camera drops per m forward
        if speed * descent_rate > 0 and sample.p_WC[2] - p.table_height <= p.min_camera_height:
            speed = 0.0
        return speed


_UP = np.array([0.0, 0.0, 1.0])
