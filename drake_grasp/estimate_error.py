"""A known error added to an object estimate: where a grasp computed from it is off, and by how much.

Issue 15's capture-region study runs trials in full dynamics with the estimate the grasp is computed
from deliberately wrong: shifted along and across the object's axis, yawed, scaled. `EstimateError`
says how (plain data, part of a trial's spec and record); `perturb_estimate` applies it to a
`grasps.ObjectEstimate`, and `perturb_pose` to an object pose (for a planner's grasp, which is
expressed in the object frame).

The offsets are horizontal, in the frame of the estimate's principal axis: *along* is the axis
projected onto the table plane (for an object with no principal axis, its first axis `R_WB[:, 0]`,
which for the ground truth is the object's x, along its longest horizontal extent), *across* is the
horizontal direction perpendicular to it (z × along). Both are taken from the estimate as it was,
before the yaw. The yaw turns the estimate about the vertical through its (shifted) centre. The size
scale multiplies the extents about the centre (so an estimate scaled up reaches further below the
centre too: the grasp then believes the table lower, as a camera that overestimates size would).
"""

import dataclasses
import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from drake_grasp.grasps import ObjectEstimate, oracle_estimate


@dataclasses.dataclass(frozen=True)
class EstimateError:
    """A known error in an object estimate.

    Attributes:
        along: offset of the centre along the horizontal principal axis, m.
        across: offset of the centre across it (horizontal, z × along), m.
        yaw: rotation about the vertical through the centre, rad (counter-clockwise from above).
        size_scale: factor on the estimated extents (1: none); dimensionless, > 0.
    """

    along: float = 0.0
    across: float = 0.0
    yaw: float = 0.0
    size_scale: float = 1.0

    def __post_init__(self):
        for name in ("along", "across", "yaw", "size_scale"):
            if not math.isfinite(getattr(self, name)):
                raise ValueError(f"estimate error: {name} must be finite, got {getattr(self, name)}")
        if self.size_scale <= 0:
            raise ValueError(f"estimate error: size scale must be > 0, got {self.size_scale}")

    @property
    def is_zero(self) -> bool:
        """No error at all (the estimate is used as it is)."""
        return self.along == 0 and self.across == 0 and self.yaw == 0 and self.size_scale == 1

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


def horizontal_axes(estimate: ObjectEstimate) -> tuple[np.ndarray, np.ndarray]:
    """The unit horizontal directions (along, across) an estimate's error is measured in (world frame).

    *along*: the principal axis (else the estimate's first axis) projected onto the horizontal; if that
    is vertical, the estimate's most horizontal axis; if every axis were vertical, world x. *across*:
    z × along.
    """
    R = np.asarray(estimate.R_WB, float)
    candidates = ([] if estimate.principal_axis is None else [np.asarray(estimate.principal_axis, float)])
    candidates += [R[:, 0]] + [R[:, i] for i in np.argsort(np.abs(R[2, :]))] + [np.array([1.0, 0.0, 0.0])]
    for axis in candidates:
        horizontal = np.array([axis[0], axis[1], 0.0])
        norm = np.linalg.norm(horizontal)
        if norm > 1e-6:
            along = horizontal / norm
            return along, np.cross([0.0, 0.0, 1.0], along)
    raise AssertionError("unreachable: world x is horizontal")


def offset(estimate: ObjectEstimate, error: EstimateError) -> np.ndarray:
    """The error's shift of the estimate's centre, world frame, m."""
    along, across = horizontal_axes(estimate)
    return error.along * along + error.across * across


def perturb_estimate(estimate: ObjectEstimate, error: EstimateError | None) -> ObjectEstimate:
    """The estimate with `error` added: centre shifted, axes (and principal axis, and the grip's axis
    where one was measured) yawed about the vertical, extents and the grip's reach scaled. No error
    (None or zero) returns `estimate` itself."""
    if error is None or error.is_zero:
        return estimate
    R_yaw = RotationMatrix.MakeZRotation(error.yaw).matrix()
    axis = None if estimate.principal_axis is None else R_yaw @ np.asarray(estimate.principal_axis, float)
    grip_axis = None if estimate.grip_axis is None else R_yaw @ np.asarray(estimate.grip_axis, float)
    return dataclasses.replace(estimate, center=np.asarray(estimate.center, float) + offset(estimate, error),
                               R_WB=R_yaw @ np.asarray(estimate.R_WB, float),
                               size=np.asarray(estimate.size, float) * error.size_scale, principal_axis=axis,
                               grip_axis=grip_axis, grip_reach=estimate.grip_reach * error.size_scale)


def perturb_pose(X_WO: RigidTransform, spec, error: EstimateError | None) -> RigidTransform:
    """An object pose with `error`'s offsets and yaw added, measured in the frame of the object's
    ground-truth estimate (`grasps.oracle_estimate`: its principal axis, else its x). The size scale
    does not apply to a pose (it is ignored here). No error (None or zero) returns `X_WO` itself.

    Args:
        X_WO: the object's pose, world frame.
        spec: the object (`objects.ObjectSpec`: its principal axis and extents).
        error: the error to add.
    """
    if error is None or (error.along == 0 and error.across == 0 and error.yaw == 0):
        return X_WO
    shift = offset(oracle_estimate(X_WO, spec), error)
    return RigidTransform(RotationMatrix.MakeZRotation(error.yaw) @ X_WO.rotation(), X_WO.translation() + shift)
