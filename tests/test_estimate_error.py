"""A known error added to an object estimate (issue 15): pure functions."""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix

from drake_grasp.estimate_error import EstimateError, horizontal_axes, perturb_estimate, perturb_pose
from drake_grasp.grasps import ObjectEstimate, oracle_estimate
from drake_grasp.objects import paper_object


def _estimate(axis=(1.0, 0.0, 0.0), yaw=0.0):
    R = RotationMatrix.MakeZRotation(yaw).matrix()
    return ObjectEstimate(np.array([0.5, 0.1, 0.05]), R, np.array([0.3, 0.1, 0.1]),
                          None if axis is None else R @ np.asarray(axis, float))


def test_no_error_is_the_identity():
    estimate = _estimate()
    assert perturb_estimate(estimate, None) is estimate
    assert perturb_estimate(estimate, EstimateError()) is estimate
    assert EstimateError(0.0, 0.0, 0.0, 1.0).is_zero and not EstimateError(yaw=0.1).is_zero
    X_WO = RigidTransform(RotationMatrix.MakeZRotation(0.3), [0.5, 0.0, 0.1])
    assert perturb_pose(X_WO, paper_object("bottle_case"), EstimateError()) is X_WO


def test_an_along_offset_moves_the_centre_along_the_horizontal_axis_by_exactly_that():
    yaw = math.radians(30)
    # A principal axis tilted 45 deg out of the table plane: along is its horizontal projection.
    tilted = _estimate(axis=(1.0, 0.0, 1.0) / np.sqrt(2.0), yaw=yaw)
    moved = perturb_estimate(tilted, EstimateError(along=0.02))
    shift = moved.center - tilted.center
    np.testing.assert_allclose(shift, 0.02 * np.array([math.cos(yaw), math.sin(yaw), 0.0]), atol=1e-15)
    assert np.linalg.norm(shift) == pytest.approx(0.02, abs=1e-15)
    np.testing.assert_array_equal(moved.R_WB, tilted.R_WB)
    np.testing.assert_array_equal(moved.size, tilted.size)


def test_an_across_offset_is_horizontal_and_perpendicular_to_the_axis():
    estimate = _estimate(yaw=math.radians(30))
    along, across = horizontal_axes(estimate)
    moved = perturb_estimate(estimate, EstimateError(across=-0.03))
    shift = moved.center - estimate.center
    assert np.dot(shift, along) == pytest.approx(0.0, abs=1e-15) and shift[2] == 0.0
    np.testing.assert_allclose(shift, -0.03 * across, atol=1e-15)
    np.testing.assert_allclose(across, [-math.sin(math.radians(30)), math.cos(math.radians(30)), 0.0], atol=1e-15)


def test_yaw_turns_the_axes_about_the_vertical_and_size_scales_the_extents():
    estimate = _estimate()
    turned = perturb_estimate(estimate, EstimateError(yaw=math.pi / 2, size_scale=1.1))
    np.testing.assert_allclose(turned.principal_axis, [0.0, 1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(turned.R_WB[:, 2], [0.0, 0.0, 1.0], atol=1e-15)
    np.testing.assert_array_equal(turned.center, estimate.center)  # about the vertical through the centre
    np.testing.assert_allclose(turned.size, 1.1 * estimate.size)


def test_without_a_principal_axis_the_estimates_first_horizontal_axis_is_used():
    along, _ = horizontal_axes(_estimate(axis=None, yaw=math.radians(60)))
    np.testing.assert_allclose(along, [0.5, math.sqrt(3) / 2, 0.0], atol=1e-15)
    # A first axis pointing straight up: the most horizontal of the others.
    R = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])  # columns: z, x, y of the world
    along, _ = horizontal_axes(ObjectEstimate(np.zeros(3), R, np.ones(3)))
    np.testing.assert_allclose(along, [1.0, 0.0, 0.0])


def test_a_pose_error_matches_the_estimate_error_of_the_ground_truth():
    spec = paper_object("bottle_case")
    X_WO = RigidTransform(RotationMatrix.MakeZRotation(0.4), [0.55, 0.01, spec.rest_height])
    error = EstimateError(along=0.02, across=-0.01, yaw=0.2)
    from_pose = oracle_estimate(perturb_pose(X_WO, spec, error), spec)
    from_estimate = perturb_estimate(oracle_estimate(X_WO, spec), error)
    np.testing.assert_allclose(from_pose.center, from_estimate.center, atol=1e-15)
    np.testing.assert_allclose(from_pose.R_WB, from_estimate.R_WB, atol=1e-15)
    np.testing.assert_allclose(from_pose.principal_axis, from_estimate.principal_axis, atol=1e-15)


def test_bad_errors_are_rejected():
    for bad in (dict(size_scale=0.0), dict(size_scale=-1.0), dict(along=math.nan), dict(yaw=math.inf)):
        with pytest.raises(ValueError):
            EstimateError(**bad)
