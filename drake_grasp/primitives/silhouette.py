"""One camera sample as the visual primitives see it: the object's silhouette and the camera pose.

Pure numpy. `measure_silhouette` turns a mask into a `Silhouette`: the blob features of
`drake_grasp.vision` (contour area, centroid, principal axis angle, eccentricity) plus the blob's
minimum-area bounding rectangle (for sizes and for the axes of blobs that are not elongated). A
`CameraSample` adds the time and the camera pose X_WC at which the image was taken; it travels
between LeafSystems as a flat vector (`CameraSample.to_vector` / `from_vector`), so that a primitive's
input can be fixed in a unit test with `FixValue`.

Image conventions: those of `drake_grasp.vision` (u right, v down, pixel centres at integer
coordinates, angles from +u toward +v).
"""


import dataclasses
import math

import numpy as np
from scipy.spatial import ConvexHull, QhullError

from drake_grasp.vision import blob_features, touches_border

# Eccentricity is reported finite (a straight line of pixels has an infinite one).
MAX_ECCENTRICITY = 1.0e3


@dataclasses.dataclass(frozen=True)
class Rectangle:
    """A rectangle in the image: its sides along e1 = (cos θ, sin θ) and e2 = (−sin θ, cos θ).

    Attributes:
        angle: θ, direction of the long side from +u toward +v, in (−π/2, π/2] (rad).
        s1: (min, max) of e1·(u, v) over the rectangle (px).
        s2: (min, max) of e2·(u, v) over the rectangle (px).
    """

    angle: float
    s1: tuple[float, float]
    s2: tuple[float, float]

    @property
    def e1(self) -> np.ndarray:
        return np.array([math.cos(self.angle), math.sin(self.angle)])

    @property
    def e2(self) -> np.ndarray:
        return np.array([-math.sin(self.angle), math.cos(self.angle)])

    @property
    def length(self) -> float:
        return self.s1[1] - self.s1[0]

    @property
    def width(self) -> float:
        return self.s2[1] - self.s2[0]


@dataclasses.dataclass(frozen=True)
class Silhouette:
    """The object's silhouette in one image, px.

    Attributes:
        area: contour area (pixel count), px².
        centroid: (u, v), px.
        axis_angle: principal axis from the second-order central moments, (−π/2, π/2] rad.
        eccentricity: sqrt(λmax/λmin) of the second moments, in [1, MAX_ECCENTRICITY].
        rectangle: the minimum-area rectangle around the blob's pixels (pixel squares, not centres).
        touches_border: the blob reaches the image border (it may be cut).
    """

    area: float
    centroid: tuple[float, float]
    axis_angle: float
    eccentricity: float
    rectangle: Rectangle
    touches_border: bool


def min_area_rectangle(mask: np.ndarray) -> Rectangle | None:
    """The minimum-area rectangle that contains every True pixel (as a unit square), or None if empty.

    Rotating calipers on the convex hull of the pixels' corners: the best rectangle has a side along
    a hull edge. The long side is e1; for a square the side nearest +u is e1. The hull is that of
    the leftmost and rightmost pixel of each row (every other pixel of the row lies between them):
    the same hull as of all the pixels, from a few hundred corners instead of a whole image's worth.
    """
    mask = np.asarray(mask, dtype=bool)
    rows = np.flatnonzero(mask.any(axis=1))
    if not len(rows):
        return None
    inside = mask[rows]
    left = inside.argmax(axis=1)
    right = mask.shape[1] - 1 - inside[:, ::-1].argmax(axis=1)
    u, v = np.concatenate([left, right]), np.concatenate([rows, rows])
    corners = np.concatenate([np.column_stack([u + du, v + dv]) for du in (-0.5, 0.5) for dv in (-0.5, 0.5)])
    corners = corners.astype(float)
    try:
        points = corners[ConvexHull(corners).vertices]
    except QhullError:  # fewer than 3 non-collinear corners cannot happen for unit squares; be safe
        points = corners
    edges = np.diff(np.vstack([points, points[:1]]), axis=0)
    angles = np.unique(np.round(np.mod(np.arctan2(edges[:, 1], edges[:, 0]), math.pi / 2.0), 12))
    best = None
    for angle in angles:
        e1 = np.array([math.cos(angle), math.sin(angle)])
        e2 = np.array([-e1[1], e1[0]])
        p1, p2 = points @ e1, points @ e2
        area = np.ptp(p1) * np.ptp(p2)
        if best is None or area < best[0] - 1e-9:
            best = (area, angle, (p1.min(), p1.max()), (p2.min(), p2.max()))
    _, angle, s1, s2 = best  # angle in [0, π/2)
    length, width = s1[1] - s1[0], s2[1] - s2[0]
    square = abs(length - width) <= 1e-9
    if (not square and length < width) or (square and angle > math.pi / 4.0):
        # Turn by +π/2 so that e1 is the long side (or the side nearest +u): e1 ← e2, e2 ← −e1.
        angle, s1, s2 = angle + math.pi / 2.0, s2, (-s1[1], -s1[0])
    wrapped = angle
    if angle > math.pi / 2.0:  # wrap into (−π/2, π/2]: e1 and e2 both change sign
        wrapped = angle - math.pi
        s1, s2 = (-s1[1], -s1[0]), (-s2[1], -s2[0])
    return Rectangle(float(wrapped), (float(s1[0]), float(s1[1])), (float(s2[0]), float(s2[1])))


def measure_silhouette(mask: np.ndarray) -> Silhouette | None:
    """The silhouette features of the True pixels of `mask`, or None if there are none."""
    features = blob_features(mask)
    if features is None:
        return None
    rectangle = min_area_rectangle(mask)
    return Silhouette(
        area=float(features.area),
        centroid=(float(features.centroid[0]), float(features.centroid[1])),
        axis_angle=float(features.principal_axis_angle),
        eccentricity=float(min(features.eccentricity, MAX_ECCENTRICITY)),
        rectangle=rectangle,
        touches_border=touches_border(mask),
    )


@dataclasses.dataclass(frozen=True)
class CameraSample:
    """One image's silhouette (or none) with the time and camera pose it was taken at.

    Attributes:
        time: s.
        silhouette: None when the object is not in the image.
        p_WC: camera position in the world, m.
        R_WC: camera orientation (3×3).
    """

    time: float
    silhouette: Silhouette | None
    p_WC: np.ndarray
    R_WC: np.ndarray

    SIZE = 25
    """Length of the vector form."""

    @property
    def visible(self) -> bool:
        return self.silhouette is not None

    @property
    def usable(self) -> bool:
        """Visible and not cut by the image border: its features can be trusted."""
        return self.silhouette is not None and not self.silhouette.touches_border

    def to_vector(self) -> np.ndarray:
        """[time, visible, area, u, v, axis_angle, eccentricity, rect angle, rect s1 (2), rect s2 (2),
        touches_border, p_WC (3), R_WC (9, row-major)]."""
        x = np.zeros(self.SIZE)
        x[0] = self.time
        s = self.silhouette
        if s is not None:
            r = s.rectangle
            x[1:13] = [1.0, s.area, s.centroid[0], s.centroid[1], s.axis_angle, s.eccentricity,
                       r.angle, r.s1[0], r.s1[1], r.s2[0], r.s2[1], float(s.touches_border)]
        x[13:16] = self.p_WC
        x[16:25] = np.asarray(self.R_WC).reshape(9)
        return x

    @classmethod
    def from_vector(cls, x: np.ndarray) -> "CameraSample":
        x = np.asarray(x, float)
        silhouette = None
        if x[1] > 0.5:
            silhouette = Silhouette(
                area=x[2], centroid=(x[3], x[4]), axis_angle=x[5], eccentricity=x[6],
                rectangle=Rectangle(x[7], (x[8], x[9]), (x[10], x[11])), touches_border=bool(x[12] > 0.5))
        return cls(time=float(x[0]), silhouette=silhouette, p_WC=x[13:16].copy(), R_WC=x[16:25].reshape(3, 3).copy())

    @classmethod
    def empty(cls) -> "CameraSample":
        """No image yet (time −1, nothing visible, identity pose)."""
        return cls(time=-1.0, silhouette=None, p_WC=np.zeros(3), R_WC=np.eye(3))
