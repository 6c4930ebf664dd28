"""The sphere score's tolerances, derived from ideal silhouettes of ellipsoids (issue 15, item 4).

`primitives/scores.py` gives the sphere hypothesis tolerances of its own, τ_S (on the arcs' combined
variation) and τ_Se (on the top view's eccentricity), and its docstring says where they come from:
they put the two extreme ellipsoids whose semi-axes are within ±10 % of a common radius at
sphere = 1/2. This module is that derivation, so the configured numbers (the scenario's
`perception: scores:`) can be checked against it rather than trusted: the orthographic silhouette of a
convex body (`silhouette_features`, what `vision.moments` measures on a mask), the
`scores.FeatureStatistics` of an ideal, noise-free exploration along the primitives' two arcs
(`ideal_statistics`), the evidence of an ellipsoid (`ellipsoid_evidence`) and the tolerances
themselves (`sphere_scales_from_ellipsoids`).

Pure numpy/scipy math about the scorer (layer 0): no Drake systems, no experiment. The near-primitives
study (`studies/near_primitives.py`) reports how the scorer does on explored objects; its tests
also use `ideal_statistics` to make statistics without a simulation.
"""

from __future__ import annotations

import math

import numpy as np


def silhouette_features(vertices: np.ndarray, view: np.ndarray) -> tuple[float, float]:
    """(area, eccentricity) of the orthographic silhouette of the convex hull of `vertices` seen along
    the unit direction `view`: the polygon's area and sqrt(λmax/λmin) of its central second moments
    (what `vision.moments` measures on a mask)."""
    from scipy.spatial import ConvexHull

    view = np.asarray(view, float) / np.linalg.norm(view)
    helper = np.array([1.0, 0.0, 0.0]) if abs(view[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(view, helper)
    u /= np.linalg.norm(u)
    w = np.cross(view, u)
    points = np.column_stack([vertices @ u, vertices @ w])
    polygon = points[ConvexHull(points).vertices]
    x, y = polygon[:, 0], polygon[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cross = x * y1 - x1 * y
    area = cross.sum() / 2.0
    cx, cy = ((x + x1) * cross).sum() / (6 * area), ((y + y1) * cross).sum() / (6 * area)
    ixx = ((x * x + x * x1 + x1 * x1) * cross).sum() / 12.0 - area * cx * cx
    iyy = ((y * y + y * y1 + y1 * y1) * cross).sum() / 12.0 - area * cy * cy
    ixy = ((x * y1 + 2 * x * y + 2 * x1 * y1 + x1 * y) * cross).sum() / 24.0 - area * cx * cy
    low, high = np.linalg.eigvalsh(np.array([[ixx, ixy], [ixy, iyy]]))
    return float(abs(area)), float(math.sqrt(high / low))


def _rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * k @ k


def ideal_statistics(vertices: np.ndarray, amplitude_a: float, amplitude_b: float, samples: int = 21):
    """The `scores.FeatureStatistics` of an ideal exploration of a convex body resting with its z up:
    orthographic silhouettes from straight above, then along an arc of ±amplitude_a about the top
    view's principal axis a and one of ±amplitude_b about the cross axis b (as the cylinder and sphere
    primitives travel them), `samples` views each, no noise, no perspective."""
    from drake_grasp.primitives import scores

    vertices = np.asarray(vertices, float)
    up = np.array([0.0, 0.0, 1.0])
    # The top view's principal axis: the dominant eigenvector of the silhouette's horizontal spread.
    hull = vertices[:, :2] - vertices[:, :2].mean(axis=0)
    axis2 = np.linalg.eigh(hull.T @ hull)[1][:, 1]
    a = np.array([axis2[0], axis2[1], 0.0])
    b = np.cross(up, a)
    stats = scores.FeatureStatistics()
    for phi in np.linspace(-amplitude_a, amplitude_a, samples):
        stats.add(phi, 0.0, *silhouette_features(vertices, _rotation(a, phi) @ up))
    for phi in np.linspace(-amplitude_b, amplitude_b, samples):
        stats.add(0.0, phi, *silhouette_features(vertices, _rotation(b, phi) @ up))
    return stats


def ellipsoid_evidence(semi_axes, amplitude_a: float = 0.7, amplitude_b: float = 0.5, score_params=None):
    """`scores.evaluate` of the ideal exploration of an ellipsoid (semi-axes along x, y, z)."""
    import trimesh

    from drake_grasp.primitives import scores

    unit = trimesh.creation.icosphere(subdivisions=3, radius=1.0).vertices
    stats = ideal_statistics(unit * np.asarray(semi_axes, float), amplitude_a, amplitude_b)
    return scores.evaluate(stats, score_params or scores.ScoreParams())


def sphere_scales_from_ellipsoids(deviation: float = 0.10, amplitude_a: float = 0.7,
                                  amplitude_b: float = 0.5) -> tuple[float, float]:
    """(τ_S, τ_Se): the sphere hypothesis's tolerances that put the two extreme ellipsoids with
    semi-axes within ±`deviation` of a common radius (resting on the smallest) at sphere = 1/2:

    * the oblate one (1+d, 1+d, 1−d), round from above with the largest variation V:
      (V_a² + V_b²) / τ_S² = ln 2;
    * the prolate one (1+d, 1−d, 1−d), the most eccentric from above (e0):
      (V_a² + V_b²) / τ_S² + ((e0 − 1) / τ_Se)² = ln 2.

    Ideal silhouettes along the given arc amplitudes (default: the default scenario's ±40° and ±29°).
    """
    d = deviation
    oblate = ellipsoid_evidence([1 + d, 1 + d, 1 - d], amplitude_a, amplitude_b)
    prolate = ellipsoid_evidence([1 + d, 1 - d, 1 - d], amplitude_a, amplitude_b)
    tau_s = math.sqrt((oblate.variation_a ** 2 + oblate.variation_b ** 2) / math.log(2.0))
    rest = math.log(2.0) - (prolate.variation_a ** 2 + prolate.variation_b ** 2) / tau_s ** 2
    return tau_s, (prolate.eccentricity_0 - 1.0) / math.sqrt(rest)
