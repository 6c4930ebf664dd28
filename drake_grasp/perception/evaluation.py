"""Evaluation of perception, never part of the decision: the object's true geometry (`ground_truth`,
`object_support`, `object_extent`), an estimate's errors against it (`compare`), and an
exploration's comparison as a record and as lines (`comparison_record`, `format_comparison`).

The algorithm's side (`perception.wiring`, `perception.exploration`, the primitives and the
supervisor) never imports this module (tests/test_perception.py asserts it).
"""

import dataclasses
import math

import numpy as np
from pydrake.math import RigidTransform

from drake_grasp.objects import ObjectSpec
from drake_grasp.perception.exploration import ExplorationResult
from drake_grasp.primitives.estimate import OBJECT_NOT_FOUND, ObjectEstimate
from drake_grasp.primitives.estimators import is_upright
from drake_grasp.primitives.scores import SHAPES
from drake_grasp.station import Scenario, object_rest_pose


def _shape_support(kind: str, size: tuple, mesh_vertices: np.ndarray | None, u: np.ndarray) -> float:
    """Support function h(u) = max over the shape of u·x, for a Drake shape in its own frame."""
    if kind == "sphere":
        return size[0]
    if kind == "ellipsoid":
        return float(np.linalg.norm(np.asarray(size) * u))
    if kind == "box":
        return float(0.5 * np.abs(u) @ np.asarray(size))
    if kind in ("cylinder", "capsule"):
        radius, length = size
        lateral = math.hypot(u[0], u[1])
        return 0.5 * length * abs(u[2]) + radius * (lateral if kind == "cylinder" else 1.0)
    return float(np.max(mesh_vertices @ u))


def object_support(spec: ObjectSpec, X_WO: RigidTransform, u_W: np.ndarray) -> float:
    """max over the object of u·p (world), for a world direction u: the object's support function."""
    import trimesh

    best = -math.inf
    for piece in spec.pieces:
        X_WP = X_WO @ piece.X_OP
        R = X_WP.rotation().matrix()
        vertices = None
        if piece.kind == "convex":
            vertices = np.asarray(trimesh.load(piece.mesh_path, force="mesh", process=False).vertices, float)
        h = float(np.dot(u_W, X_WP.translation())) + _shape_support(piece.kind, piece.size, vertices, R.T @ u_W)
        best = max(best, h)
    return best


def object_extent(spec: ObjectSpec, X_WO: RigidTransform, u_W: np.ndarray) -> float:
    """The object's extent along the unit world direction u, m."""
    u = np.asarray(u_W, float) / np.linalg.norm(u_W)
    return object_support(spec, X_WO, u) + object_support(spec, X_WO, -u)


@dataclasses.dataclass
class GroundTruth:
    """The object as it really is (world frame): centre of mass, principal axis (or None), extents
    (length, width, height: along the principal axis or, for an object with none or an upright one,
    the longer side of the smallest horizontal bounding rectangle; across it; and vertically), and the
    closest primitive shape."""

    centre: np.ndarray
    principal_axis: np.ndarray | None
    extents: np.ndarray
    shape: str | None


def ground_truth(spec: ObjectSpec, X_WO: RigidTransform) -> GroundTruth:
    up = np.array([0.0, 0.0, 1.0])
    height = object_extent(spec, X_WO, up)
    axis = None
    if spec.principal_axis is not None:
        axis = X_WO.rotation().matrix() @ np.asarray(spec.principal_axis)
    lying = axis is not None and not is_upright(axis)  # an upright axis names no horizontal direction
    if lying:
        horizontal = axis - axis[2] * up
        directions = [math.atan2(horizontal[1], horizontal[0])]
    else:
        directions = np.linspace(0.0, math.pi / 2.0, 91)
    best = None
    for theta in directions:
        u = np.array([math.cos(theta), math.sin(theta), 0.0])
        v = np.array([-math.sin(theta), math.cos(theta), 0.0])
        lu, lv = object_extent(spec, X_WO, u), object_extent(spec, X_WO, v)
        if best is None or lu * lv < best[0] * best[1] - 1e-12:
            best = (lu, lv)
    length, width = best if lying else sorted(best, reverse=True)
    return GroundTruth(X_WO.translation().copy(), axis, np.array([length, width, height]), spec.closest_primitive)


@dataclasses.dataclass
class EstimateErrors:
    """An estimate against the truth.

    Attributes:
        centre: distance between the estimated and true centre, m.
        depth: relative depth error, (estimated − true distance) / true distance, from the final camera.
        axis_deg: angle between the estimated and true principal axes (None unless both exist).
        extents: relative errors of (length, width, height), sorted horizontal extents when the object
            has no principal axis, or an upright one (estimated or true).
        shape_correct: the highest resemblance names the true closest primitive (None if unknown).
    """

    centre: float
    depth: float
    axis_deg: float | None
    extents: np.ndarray
    shape_correct: bool | None

    def passes(self, centre_tol=0.01, depth_tol=0.05, axis_tol_deg=10.0, size_tol=0.15) -> bool:
        """The issue's acceptance thresholds (and the class, when known)."""
        ok = self.centre <= centre_tol and abs(self.depth) <= depth_tol and np.all(np.abs(self.extents) <= size_tol)
        ok = ok and (self.axis_deg is None or self.axis_deg <= axis_tol_deg)
        return bool(ok and self.shape_correct is not False)


def compare(estimate: ObjectEstimate, truth: GroundTruth) -> EstimateErrors:
    """How far `estimate` is from `truth` (the estimate must be found)."""
    if not estimate.found:
        raise ValueError("no estimate to compare: the object was not found")
    true_depth = float(np.linalg.norm(truth.centre - estimate.camera_position))
    axis_deg = None
    if truth.principal_axis is not None and estimate.principal_axis is not None:
        cosine = abs(float(np.dot(truth.principal_axis, estimate.principal_axis)))
        axis_deg = math.degrees(math.acos(min(cosine, 1.0)))
    extents = np.array(estimate.extents, float)
    if is_upright(np.asarray(estimate.axes)[:, 0]):  # along (vertical a, b, horizontal c): as the truth's
        extents = extents[[2, 1, 0]]                # (horizontal, horizontal, vertical)
    true_extents = np.array(truth.extents, float)
    if any(axis is None or is_upright(axis) for axis in (truth.principal_axis, estimate.principal_axis)):
        # No horizontal axis to tell length from width (a round object, or an upright one): sorted.
        extents[:2] = sorted(extents[:2], reverse=True)
        true_extents[:2] = sorted(true_extents[:2], reverse=True)
    shape_correct = None if truth.shape is None else estimate.best_shape == truth.shape
    return EstimateErrors(
        centre=float(np.linalg.norm(estimate.centre - truth.centre)),
        depth=(estimate.depth - true_depth) / true_depth,
        axis_deg=axis_deg,
        extents=(extents - true_extents) / true_extents,
        shape_correct=shape_correct,
    )


def true_pose(scenario: Scenario, spec: ObjectSpec) -> RigidTransform:
    """The object's resting pose for the scenario's placement (it does not move while looked at)."""
    return object_rest_pose(spec, scenario.object)




def comparison_record(result: ExplorationResult, spec: ObjectSpec) -> dict:
    """Plain data: the estimate beside the truth (at the end of the exploration) and the errors."""
    estimate = result.estimate
    record = {"object": spec.name, "estimate": estimate.to_dict(), "best_shape": estimate.best_shape}
    truth = ground_truth(spec, result.X_WO_end)
    record["truth"] = {
        "centre": truth.centre.tolist(),
        "depth": None if estimate.camera_position is None else
        float(np.linalg.norm(truth.centre - estimate.camera_position)),
        "principal_axis": None if truth.principal_axis is None else truth.principal_axis.tolist(),
        "extents": truth.extents.tolist(),
        "shape": truth.shape,
        "object_moved": float(np.linalg.norm(result.X_WO_end.translation() - result.X_WO_start.translation())),
    }
    if estimate.found:
        errors = compare(estimate, truth)
        record["errors"] = {"centre": errors.centre, "depth": errors.depth, "axis_deg": errors.axis_deg,
                            "extents": errors.extents.tolist(), "shape_correct": errors.shape_correct,
                            "within_tolerances": errors.passes()}
        if estimate.problem():  # seen, but a trial would end here: perception failed
            record["problem"] = estimate.problem()
    return record


def format_comparison(record: dict) -> list[str]:
    """Human-readable lines of a `comparison_record`: estimate | truth | error, then the resemblances."""
    estimate, truth = record["estimate"], record["truth"]
    timings = estimate["timings"]
    if estimate["status"] != "ok":
        why = ("the camera did not see it from the start pose" if estimate["status"] == OBJECT_NOT_FOUND else
               "the camera saw it, but every silhouette was cut by the image border")
        return [f"{record['object']}: {estimate['status']} ({why}); "
                f"{timings.get('sim_time', 0.0):.1f} s simulated in {timings.get('wall_time', 0.0):.1f} s"]

    def vector(v, digits=3):
        return "-" if v is None else "(" + ", ".join(f"{x:.{digits}f}" for x in v) + ")"

    errors = record["errors"]
    axis_error = "-" if errors["axis_deg"] is None else f"{errors['axis_deg']:.1f} deg"
    rows = [
        ("centre (m)", vector(estimate["centre"]), vector(truth["centre"]), f"{errors['centre'] * 1000:.1f} mm"),
        ("depth (m)", f"{estimate['depth']:.3f}", f"{truth['depth']:.3f}", f"{errors['depth'] * 100:+.1f} %"),
        ("principal axis", vector(estimate["principal_axis"], 2), vector(truth["principal_axis"], 2), axis_error),
        ("size (m)", " x ".join(f"{x:.3f}" for x in _as_truth_extents(estimate)),
         " x ".join(f"{x:.3f}" for x in truth["extents"]),
         " ".join(f"{e * 100:+.1f}" for e in errors["extents"]) + " %"),
    ]
    lines = [f"{'':16s} {'estimate':26s} {'truth':26s} error"]
    lines += [f"{name:16s} {a:26s} {b:26s} {c}" for name, a, b, c in rows]
    res = estimate["resemblances"]
    verdict = "" if truth["shape"] is None else \
        f" (truth: {truth['shape']}, {'right' if errors['shape_correct'] else 'WRONG'})"
    lines.append("resemblance      " + "  ".join(f"{s} {res[s]:.2f}" for s in SHAPES) +
                 f"  -> {record['best_shape']}{verdict}")
    cost = estimate.get("exploration")
    if cost:
        lines.append(f"exploration ({cost['kind']}): {cost['time_s']:.2f} s, {cost['images']} images, camera path "
                     f"{cost['path_m']:.2f} m and {cost['path_rad']:.2f} rad")
    lines.append(f"{record['object']}: {record['best_shape']} (resemblance {res[record['best_shape']]:.2f}); "
                 f"centre {errors['centre'] * 1000:.1f} mm, depth {errors['depth'] * 100:+.1f} %, axis {axis_error}; "
                 f"{timings['sim_time']:.1f} s simulated, {timings['frames']} frames, {timings['wall_time']:.1f} s wall")
    if record.get("problem"):
        lines.append(f"perception failed: {record['problem']} (a trial would end here)")
    return lines


def _as_truth_extents(estimate: dict) -> list:
    """An estimate's extents (plain data) in the truth's order: length, width (horizontal), height."""
    extents = list(estimate["extents"])
    return extents[::-1] if is_upright(np.asarray(estimate["axes"])[:, 0]) else extents
