"""The estimators of the depth and principal-axis primitives, on plain arrays.

The ray and plane estimators are running sums (a few numbers of discrete state in the LeafSystems);
the tangent planes are kept and refitted (a small bounded least-squares problem) at each update:

* **centre and depth** (`add_ray`, `solve_point`): every image contributes the ray from the camera
  centre through the silhouette's centroid. While the camera circles a point that is not the object's
  centre, the centroid drifts in the image and the rays stop meeting at the pivot; the least-squares
  meeting point of all rays, Σ(I − r rᵀ) c = Σ(I − r rᵀ) p, is the object centre, and its distance to
  the camera is the depth. This is the batch (recursive least-squares) form of "the drift corrects the
  depth estimate": each drifting ray pulls the estimate toward the true centre. A weak prior (the
  first ray at an assumed depth) keeps the sums invertible before the camera has moved. The centroid
  is exact across an elongated blob (a symmetric cross-section) but perspective biases it along the
  blob, toward the object's nearer end when the view is tilted along it; the part of each ray's
  constraint along the blob's axis is therefore weighted down (by 1/eccentricity², a choice).
* **principal axis in space** (`add_plane`, `axis_from_planes`): the blob's axis in an image is
  the projection of the object's axis, so the 3-D axis lies in the plane through the camera centre
  and that image line (its interpretation plane). Planes seen from views spread *around* the axis
  (the principal-axis primitive's arc) meet only along the axis direction: it is the eigenvector of
  Σ n nᵀ with the smallest eigenvalue. An arc about the true axis leaves the image axis invariant.
* **centre and size from tangent planes** (`tangent_planes`, `fit_support`): each side of the
  silhouette's bounding rectangle back-projects to a plane through the camera centre tangent to the
  object: a sample h(ν) = ν·p_camera of the object's support function. A support-function model (a
  box grown by a disc and a sphere, exact for boxes, cylinders and spheres) fitted to many of them
  gives the centre and the extents without the perspective bias of the centroid.
"""


import dataclasses
import math

import numpy as np

from drake_grasp.primitives.camera_model import CameraIntrinsics


def add_ray(A: np.ndarray, b: np.ndarray, p_W: np.ndarray, r_W: np.ndarray, weight: float = 1.0,
            along_W: np.ndarray | None = None, along_weight: float = 1.0) -> None:
    """Adds the ray p + t·r (r a unit vector) to the normal equations A c = b, in place.

    The ray constrains the point in the two directions perpendicular to it; with `along_W` (a
    direction perpendicular to r), the constraint along it weighs `along_weight` × `weight` and the
    other `weight`.
    """
    if along_W is None:
        P = weight * (np.eye(3) - np.outer(r_W, r_W))
    else:
        m = np.asarray(along_W, float) - np.dot(along_W, r_W) * r_W
        m = m / np.linalg.norm(m)
        n = np.cross(r_W, m)
        P = weight * (along_weight * np.outer(m, m) + np.outer(n, n))
    A += P
    b += P @ p_W


def image_direction_W(intrinsics: CameraIntrinsics, R_WC: np.ndarray, point_uv, angle: float) -> np.ndarray:
    """World unit direction, perpendicular to the ray through `point_uv`, of the image direction at
    `angle` there (the 3-D direction a small step along the image line takes)."""
    u, v = point_uv
    r = intrinsics.ray(u, v)
    step = intrinsics.ray(u + math.cos(angle), v + math.sin(angle)) - r
    step -= np.dot(step, r) * r
    return np.asarray(R_WC) @ (step / np.linalg.norm(step))


def solve_point(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The least-squares meeting point of the rays summed in (A, b)."""
    return np.linalg.solve(A, b)


def ray_spread(A: np.ndarray, count: float) -> float:
    """How well the rays in A cross: the smallest eigenvalue of A per ray (0 for parallel rays; the
    mean squared sine of the rays' angle to their common direction)."""
    return float(np.linalg.eigvalsh(A)[0] / max(count, 1.0))


def add_plane(M: np.ndarray, n_W: np.ndarray, weight: float = 1.0) -> None:
    """Adds an interpretation plane (unit normal n) to the scatter M = Σ w n nᵀ, in place."""
    M += weight * np.outer(n_W, n_W)


def axis_from_planes(M: np.ndarray, perpendicular_to: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(axis, eigenvalues ascending of M): the direction closest to lying in all planes of M.

    With `perpendicular_to` (a unit vector v), the axis is sought among the directions perpendicular
    to v only (the smallest eigenvector of M restricted to that plane). The axis's sign is fixed so
    that its largest component is positive.
    """
    eigenvalues, eigenvectors = np.linalg.eigh(M)
    axis = eigenvectors[:, 0]
    if perpendicular_to is not None:
        v = np.asarray(perpendicular_to, float) / np.linalg.norm(perpendicular_to)
        helper = np.array([1.0, 0.0, 0.0]) if abs(v[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        e1 = np.cross(v, helper)
        e1 /= np.linalg.norm(e1)
        E = np.column_stack([e1, np.cross(v, e1)])
        _, vectors_2d = np.linalg.eigh(E.T @ M @ E)
        axis = E @ vectors_2d[:, 0]
    axis = axis * np.sign(axis[np.argmax(np.abs(axis))])
    return axis / np.linalg.norm(axis), eigenvalues


def image_line_plane_W(intrinsics: CameraIntrinsics, R_WC: np.ndarray, point_uv, angle: float) -> np.ndarray:
    """World unit normal of the interpretation plane of the image line through `point_uv` at `angle`."""
    e = np.array([-math.sin(angle), math.cos(angle)])
    s = float(e @ np.asarray(point_uv, float))
    return np.asarray(R_WC) @ intrinsics.line_plane_normal(e, s)


def view_angles(p_WC: np.ndarray, centre_W: np.ndarray, a_W: np.ndarray, b_W: np.ndarray) -> tuple[float, float]:
    """(φa, φb): how far the camera has turned about the axes a and b through the centre (rad).

    With n = a × b (the reference view direction, from the centre toward the camera), and w the
    current direction from the centre to the camera: φa = atan2(w·(a × n), w·n) is the rotation about
    a (the camera moving along −b… +b), φb = atan2(w·(b × n), w·n) the rotation about b.
    """
    w = np.asarray(p_WC, float) - np.asarray(centre_W, float)
    n = np.cross(a_W, b_W)
    return (math.atan2(float(w @ np.cross(a_W, n)), float(w @ n)),
            math.atan2(float(w @ np.cross(b_W, n)), float(w @ n)))


def exploration_frame(axis_W: np.ndarray, view_W: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(a, b): the axis made perpendicular to the view direction, and b = view × a (both unit).

    The reference view n = a × b is then the view direction (from the centre toward the camera).
    """
    view = np.asarray(view_W, float) / np.linalg.norm(view_W)
    a = np.asarray(axis_W, float) - float(np.dot(axis_W, view)) * view
    if np.linalg.norm(a) < 1e-9:  # axis along the view: any perpendicular direction
        a = np.cross(view, [1.0, 0.0, 0.0]) if abs(view[0]) < 0.9 else np.cross(view, [0.0, 1.0, 0.0])
    a = a / np.linalg.norm(a)
    return a, np.cross(view, a)


# --- The object's support function from tangent planes -------------------------------------------

SUPPORT_PARAMETERS = ("half_length_a", "half_length_b", "half_height", "disc_radius", "sphere_radius")


def tangent_planes(intrinsics: CameraIntrinsics, R_WC: np.ndarray, p_WC: np.ndarray, rectangle) -> np.ndarray:
    """The four planes tangent to the object through the sides of its silhouette's bounding rectangle.

    Returns:
        (4, 4) rows [ν, o]: outward unit normal ν (world; the object lies on the side ν·x ≤ o) and
        offset o = ν·p_WC (every plane passes through the camera centre). So o = h(ν), a sample of the
        object's support function h(ν) = max over the object of ν·x.
    """
    rows = []
    for e, (s_min, s_max) in ((rectangle.e1, rectangle.s1), (rectangle.e2, rectangle.s2)):
        for normal_C in (-intrinsics.line_plane_normal(e, s_min), intrinsics.line_plane_normal(e, s_max)):
            nu = np.asarray(R_WC) @ normal_C
            rows.append(np.concatenate([nu, [float(nu @ np.asarray(p_WC))]]))
    return np.array(rows)


def support_basis(normals: np.ndarray, a: np.ndarray, b: np.ndarray, up: np.ndarray) -> np.ndarray:
    """Regressors of the support-function model for unit normals (N×3): N×8 columns
    [ν (3, for the centre), |ν·a|, |ν·b|, |ν·up|, sqrt(1 − (ν·a)²), 1]."""
    na = normals @ a
    return np.column_stack([normals, np.abs(na), np.abs(normals @ b), np.abs(normals @ up),
                            np.sqrt(np.clip(1.0 - na * na, 0.0, 1.0)), np.ones(len(normals))])


@dataclasses.dataclass(frozen=True)
class SupportFit:
    """The fitted support-function model h(ν) = ν·c + h0(ν) of the object (world frame, m).

    h0(ν) = s_a|ν·a| + s_b|ν·b| + s_z|ν·up| + ρ·sqrt(1 − (ν·a)²) + r: the support function of a box
    (half-sizes s_a, s_b, s_z along a, b, up) grown by a disc of radius ρ perpendicular to a and by a
    sphere of radius r (Minkowski sums add support functions). It is exact for boxes (ρ = r = 0),
    spheres (only r) and cylinders lying along a (s_a = half-length, ρ = radius), and a rounded
    approximation of everything between.

    Attributes:
        centre: c.
        parameters: (s_a, s_b, s_z, ρ, r), all ≥ 0.
        frame: (a, b, up) the model was fitted in.
        rms: root-mean-square residual of the tangent planes, m.
    """

    centre: np.ndarray
    parameters: np.ndarray
    frame: tuple[np.ndarray, np.ndarray, np.ndarray]
    rms: float

    def half_extent(self, u: np.ndarray) -> float:
        """h0(u): half the object's extent along the unit vector u (it is centrally symmetric)."""
        a, b, up = self.frame
        return float(support_basis(np.asarray(u, float)[None, :], a, b, up)[0, 3:] @ self.parameters)

    def extents(self) -> np.ndarray:
        """The extents along a, b and up, m."""
        return np.array([2.0 * self.half_extent(u) for u in self.frame])


def fit_support(planes: np.ndarray, a: np.ndarray, up: np.ndarray, table_height: float | None = None,
                table_weight: float = 10.0, prior_centre: np.ndarray | None = None,
                prior_weight: float = 0.0, weights: np.ndarray | None = None) -> SupportFit:
    """Least-squares fit of the support-function model to tangent planes (rows [ν, o]).

    Args:
        planes: (N, 4) tangent planes.
        a: the model's first axis (the principal axis); it is made perpendicular to `up`.
        up: the vertical (unit).
        table_height: if given, the object rests on a table at this height: h(−up) = −table_height.
        table_weight: weight of that row (the planes weigh 1 each).
        prior_centre, prior_weight: a weak pull of the centre toward a prior (for few, clustered planes).
        weights: per-plane weights (default 1); the table and prior weights are relative to them.
    """
    from scipy.optimize import lsq_linear

    up = np.asarray(up, float) / np.linalg.norm(up)
    a = np.asarray(a, float) - float(np.dot(a, up)) * up
    a = a / np.linalg.norm(a) if np.linalg.norm(a) > 1e-9 else np.cross(up, [0.0, 1.0, 0.0])
    b = np.cross(up, a)
    X = support_basis(planes[:, :3], a, b, up)
    y = planes[:, 3].copy()
    w = np.ones(len(planes)) if weights is None else np.sqrt(np.asarray(weights, float))
    rows, targets = [w[:, None] * X], [w * y]
    if table_height is not None:
        rows.append(table_weight * support_basis(-up[None, :], a, b, up))
        targets.append([-table_weight * table_height])
    if prior_centre is not None and prior_weight > 0:
        rows.append(prior_weight * np.column_stack([np.eye(3), np.zeros((3, 5))]))
        targets.append(prior_weight * np.asarray(prior_centre, float))
    lower = np.array([-np.inf] * 3 + [0.0] * 5)
    result = lsq_linear(np.vstack(rows), np.concatenate(targets), bounds=(lower, np.full(8, np.inf)), method="bvls")
    residual = w * (X @ result.x - y)
    rms = float(np.sqrt(np.sum(residual**2) / max(np.sum(w * w), 1e-12)))
    return SupportFit(result.x[:3].copy(), result.x[3:].copy(), (a, b, up), rms)


def is_upright(direction: np.ndarray) -> bool:
    """Whether a direction is nearer the vertical than the horizontal (more than 45° from the table
    plane; z is up): the principal axis of an upright object, a carton or bottle standing on the table."""
    d = np.asarray(direction, float)
    return bool(abs(d[2]) > math.hypot(d[0], d[1]))


def face_direction(planes: np.ndarray, weights: np.ndarray | None = None) -> np.ndarray | None:
    """The horizontal direction of an upright object's side faces, from its tangent planes (rows [ν, o]).

    The sides of a silhouette's bounding rectangle follow the object's outline, so the tangent planes
    of an upright box have horizontal normals along its four side faces' normals: angles θ, θ + 90°,
    θ + 180°, θ + 270°. Their circular mean with the angles taken four times, atan2(Σ w sin 4θ, Σ w cos 4θ)/4,
    is θ (each plane weighted by w times the length of its normal's horizontal part). Returns the
    unit horizontal vector at θ, or None when the normals show no such direction (a round section:
    the mean vector is shorter than 1e-9 of the weights).
    """
    normals = np.asarray(planes, float)[:, :3]
    horizontal = np.hypot(normals[:, 0], normals[:, 1])
    w = horizontal * (1.0 if weights is None else np.asarray(weights, float))
    angles = 4.0 * np.arctan2(normals[:, 1], normals[:, 0])
    s, c = float(np.sum(w * np.sin(angles))), float(np.sum(w * np.cos(angles)))
    if math.hypot(s, c) <= 1e-9 * max(float(np.sum(w)), 1e-300):
        return None
    theta = math.atan2(s, c) / 4.0
    return np.array([math.cos(theta), math.sin(theta), 0.0])
