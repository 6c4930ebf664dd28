"""Image moments of a blob: the silhouette features the visual primitives use.

From a boolean mask (the object's silhouette, see `segmentation`) this module computes the features
named in docs/design.md §2: **contour area**, centroid, **principal axis** (orientation of the blob from its
second-order central moments) and **eccentricity** (ratio of major to minor axis of the blob's
second moments, ≥ 1).

Image axes convention: u = column index, to the right; v = row index, downward; a pixel's
coordinates are those of its centre, so the top-left pixel is at (u, v) = (0, 0). Angles are measured
from +u toward +v (clockwise on screen, since v points down), in radians.

Moments are those of the pixel centres (point samples, as OpenCV's ``cv2.moments`` on a binary image):
a blob that is one pixel wide along a straight line has a zero minor axis and infinite eccentricity.
"""

import dataclasses
import math

import numpy as np


@dataclasses.dataclass(frozen=True)
class BlobFeatures:
    """Silhouette features of one blob, in pixels.

    Attributes:
        area: Contour area, the number of pixels in the blob (px²).
        centroid: (u, v) of the centroid (px).
        mu20: Central moment Σ (u − ū)² over the blob's pixels (px⁴: px² per pixel, summed).
        mu11: Central moment Σ (u − ū)(v − v̄) (px⁴).
        mu02: Central moment Σ (v − v̄)² (px⁴).
        principal_axis_angle: Angle of the major axis, 0.5·atan2(2·mu11, mu20 − mu02), from +u toward
            +v, in (−π/2, π/2] (rad). The axis is a line, so the angle is defined modulo π; it is
            arbitrary (0) for a blob with no preferred axis (eccentricity 1, e.g. a disc).
        eccentricity: sqrt(λ_max / λ_min) of the 2×2 central second-moment matrix, ≥ 1 (unitless);
            1 for a disc or a square, a/b for an a:b ellipse, w/h for a w×h rectangle; ``math.inf``
            when the blob is a straight line of pixels (λ_min = 0); 1 for a single pixel.
        major_axis_std: Standard deviation of the pixels along the major axis, sqrt(λ_max / area) (px).
            A disc of radius r has r/2, a rectangle of length w has w/√12.
        minor_axis_std: Standard deviation along the minor axis, sqrt(λ_min / area) (px).
    """

    area: int
    centroid: tuple[float, float]
    mu20: float
    mu11: float
    mu02: float
    principal_axis_angle: float
    eccentricity: float
    major_axis_std: float
    minor_axis_std: float

    @property
    def covariance(self) -> np.ndarray:
        """The 2×2 covariance of the pixel coordinates [[mu20, mu11], [mu11, mu02]] / area (px²)."""
        return np.array([[self.mu20, self.mu11], [self.mu11, self.mu02]]) / self.area


def blob_features(mask: np.ndarray) -> BlobFeatures | None:
    """Computes the silhouette features of the True pixels of a mask, taken as one blob.

    An empty mask means the object is not in view: the function returns None rather than raising
    or dividing by zero, so callers (visual primitives) test ``if features is None``.

    The sums are taken in exact integer arithmetic, so a straight line of pixels has exactly
    λ_min = 0 and gets ``eccentricity = math.inf`` without a floating-point warning.

    Args:
        mask: Boolean (or 0/1) array of shape (H, W); all True pixels count, whether connected
            or not (see `segmentation.keep_largest_component`).

    Returns:
        The blob's features, or None if the mask has no True pixel.

    Raises:
        ValueError: If ``mask`` is not two-dimensional.
    """
    mask = np.asarray(mask)
    if mask.ndim != 2:
        raise ValueError(f"expected a mask of shape (H, W), got {mask.shape}")
    v, u = np.nonzero(mask)
    count = int(u.size)
    if count == 0:
        return None

    # Exact sums: int64 holds Σu² for images up to 10⁴ × 10⁴ pixels (≤ 10¹⁶ < 9·10¹⁸); they are
    # combined in Python integers, n²·covariance = n·Σu² − (Σu)² etc., so nothing cancels.
    u = u.astype(np.int64)
    v = v.astype(np.int64)
    sum_u, sum_v = int(u.sum()), int(v.sum())
    scaled_uu = count * int(np.dot(u, u)) - sum_u * sum_u
    scaled_uv = count * int(np.dot(u, v)) - sum_u * sum_v
    scaled_vv = count * int(np.dot(v, v)) - sum_v * sum_v
    scaled_det = scaled_uu * scaled_vv - scaled_uv * scaled_uv  # ≥ 0 (Cauchy–Schwarz), exact

    # Eigenvalues of the scaled matrix: λ_max by the stable sum, λ_min = det / λ_max.
    half_trace = 0.5 * (scaled_uu + scaled_vv)
    half_spread = math.hypot(0.5 * (scaled_uu - scaled_vv), scaled_uv)
    scaled_lambda_max = half_trace + half_spread
    if scaled_lambda_max == 0.0:  # a single pixel: no extent, no preferred axis
        scaled_lambda_min = 0.0
        eccentricity = 1.0
    elif scaled_det == 0:  # collinear pixels
        scaled_lambda_min = 0.0
        eccentricity = math.inf
    else:
        scaled_lambda_min = scaled_det / scaled_lambda_max
        eccentricity = math.sqrt(scaled_lambda_max / scaled_lambda_min)

    return BlobFeatures(
        area=count,
        centroid=(sum_u / count, sum_v / count),
        mu20=scaled_uu / count,
        mu11=scaled_uv / count,
        mu02=scaled_vv / count,
        principal_axis_angle=_principal_axis_angle(scaled_uv, scaled_uu - scaled_vv),
        eccentricity=eccentricity,
        major_axis_std=math.sqrt(scaled_lambda_max) / count,
        minor_axis_std=math.sqrt(scaled_lambda_min) / count,
    )


def contour_area(mask: np.ndarray) -> int:
    """Returns the contour area of a blob as its pixel count (px²).

    The pixel count, not the area of a polygon through the boundary pixels' centres (as
    ``cv2.contourArea``): the latter is smaller by about half the perimeter. Only variations of the
    area over the camera motion matter to the shape resemblance primitives, and the pixel count is
    the more stable of the two.

    Args:
        mask: Boolean (or 0/1) array of shape (H, W).

    Returns:
        The number of True pixels.
    """
    return int(np.count_nonzero(mask))


def touches_border(mask: np.ndarray, margin_px: int = 0) -> bool:
    """Tells whether the blob reaches the image border, i.e. may be cut by it.

    A cut blob's area, centroid, principal axis and eccentricity are those of the visible part only:
    a visual primitive should not trust them (and should move the camera back or away).

    Args:
        mask: Boolean (or 0/1) array of shape (H, W).
        margin_px: Width of the border band (px): True if a blob pixel lies within ``margin_px``
            pixels of the image edge; 0 means on the outermost rows or columns.

    Returns:
        True if any True pixel lies in the border band; False otherwise (also for an empty mask).

    Raises:
        ValueError: If ``mask`` is not two-dimensional or ``margin_px`` is negative.
    """
    mask = np.asarray(mask, dtype=bool)
    if mask.ndim != 2:
        raise ValueError(f"expected a mask of shape (H, W), got {mask.shape}")
    if margin_px < 0:
        raise ValueError(f"margin_px must be >= 0, got {margin_px}")
    band = margin_px + 1
    return bool(
        mask[:band, :].any() or mask[-band:, :].any() or mask[:, :band].any() or mask[:, -band:].any()
    )


def pixels_to_metres(
    length_px: float | np.ndarray, depth_m: float, focal_px: float
) -> float | np.ndarray:
    """Converts an image length to the length it spans on a fronto-parallel plane (pinhole camera).

    Args:
        length_px: Length in the image (px), e.g. ``major_axis_std``.
        depth_m: Distance from the camera to the plane along the optical axis (m).
        focal_px: Focal length in pixels (Drake's ``CameraInfo.focal_x()``; the same in x and y for
            square pixels).

    Returns:
        The length on the plane (m).
    """
    return length_px * depth_m / focal_px


def square_pixels_to_square_metres(
    area_px: float | np.ndarray, depth_m: float, focal_px: float
) -> float | np.ndarray:
    """Converts an image area to the area it covers on a fronto-parallel plane (pinhole camera).

    Args:
        area_px: Area in the image (px²), e.g. the contour area.
        depth_m: Distance from the camera to the plane along the optical axis (m).
        focal_px: Focal length in pixels (square pixels).

    Returns:
        The area on the plane (m²).
    """
    return area_px * (depth_m / focal_px) ** 2


def _principal_axis_angle(scaled_uv: int, scaled_uu_minus_vv: int) -> float:
    """0.5·atan2(2·mu11, mu20 − mu02) in (−π/2, π/2] (rad); the scale n² cancels in atan2."""
    # Integer arguments never give −0.0, so atan2 lies in (−π, π] and the half angle in (−π/2, π/2].
    return 0.5 * math.atan2(2 * scaled_uv, scaled_uu_minus_vv)
