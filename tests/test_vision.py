"""Tests of drake_grasp.vision (segmentation and blob moments) on synthetic images made here.

Shapes are rasterised by point-sampling pixel centres: a pixel at (u, v) is in the shape if its centre
is. Tolerances come from that pixelisation (see each test).
"""

import colorsys
import math
import warnings

import numpy as np
import pytest

from drake_grasp.vision import (
    LABEL_DO_NOT_RENDER,
    LABEL_DONT_CARE,
    LABEL_EMPTY,
    LABEL_MAX_UNRESERVED,
    LABEL_UNSPECIFIED,
    BlobFeatures,
    blob_features,
    contour_area,
    keep_largest_component,
    mask_from_color,
    mask_from_label,
    mask_from_labels_excluding,
    pixels_to_metres,
    rgb_to_hsv,
    square_pixels_to_square_metres,
    touches_border,
)

IMAGE_HEIGHT = 240
IMAGE_WIDTH = 320
IMAGE_CENTRE = (159.5, 119.5)  # (u, v) of the image centre, between pixel centres (px)


def _pixel_grid() -> tuple[np.ndarray, np.ndarray]:
    """(u, v) coordinates of every pixel centre, each of shape (H, W)."""
    v, u = np.mgrid[0:IMAGE_HEIGHT, 0:IMAGE_WIDTH]
    return u.astype(float), v.astype(float)


def _in_blob_frame(centre: tuple[float, float], angle: float) -> tuple[np.ndarray, np.ndarray]:
    """Pixel coordinates in a frame at `centre` whose x axis is at `angle` from +u toward +v."""
    u, v = _pixel_grid()
    du, dv = u - centre[0], v - centre[1]
    return math.cos(angle) * du + math.sin(angle) * dv, -math.sin(angle) * du + math.cos(angle) * dv


def ellipse_mask(centre, semi_major, semi_minor, angle=0.0) -> np.ndarray:
    """Mask of an ellipse, semi-axes in px, major axis at `angle` (rad) from +u toward +v."""
    x, y = _in_blob_frame(centre, angle)
    return (x / semi_major) ** 2 + (y / semi_minor) ** 2 <= 1.0


def rectangle_mask(centre, width, height, angle=0.0) -> np.ndarray:
    """Mask of a width × height rectangle (px), its width side at `angle` (rad) from +u toward +v."""
    x, y = _in_blob_frame(centre, angle)
    return (np.abs(x) <= 0.5 * width) & (np.abs(y) <= 0.5 * height)


def axis_angle_difference(angle_a: float, angle_b: float) -> float:
    """Difference of two axis angles modulo π, in [−π/2, π/2) (rad)."""
    return (angle_a - angle_b + 0.5 * math.pi) % math.pi - 0.5 * math.pi


# Tolerances, measured over 200 random sub-pixel centres and angles (worst case in brackets):
# - disc of radius r = 40 px: the ~2πr boundary pixels each misplace up to half a pixel of area at
#   distance ≈ r; the errors partly cancel, and the second moments (πr⁴/4) are off by O(r^-1.5):
#   eccentricity − 1 [0.44 %], area / πr² − 1 [0.21 %]; centroid of a 30 px disc [0.08 px].
#   We allow 1 %, 1 %, 0.2 px (at r = 10 px the eccentricity error reaches 5 %).
# - ellipse with semi-axes 60 × 20 px: eccentricity [0.44 %], axis angle [0.002 rad]; we allow 1 %,
#   0.01 rad.
# - rotated rectangle 120 × 30 px: the raster of a rotated edge is a staircase whose ±½-pixel teeth
#   change the variance across the short side h by O(1/h): eccentricity [0.33 %], angle [0.009 rad];
#   we allow 2 %, 0.02 rad.
DISC_RADIUS = 40.0
DISC_ECCENTRICITY_TOLERANCE = 0.01
DISC_AREA_RELATIVE_TOLERANCE = 0.01
CENTROID_TOLERANCE_PX = 0.2
ELLIPSE_ECCENTRICITY_RELATIVE_TOLERANCE = 0.01
ELLIPSE_ANGLE_TOLERANCE = 0.01
RECTANGLE_ECCENTRICITY_RELATIVE_TOLERANCE = 0.02
RECTANGLE_ANGLE_TOLERANCE = 0.02


# ---------------------------------------------------------------------------------------------------
# Moments


@pytest.mark.parametrize("centre", [IMAGE_CENTRE, (160.0, 120.0), (101.3, 87.7)])
def test_disc_has_eccentricity_one_and_area_pi_r_squared(centre):
    features = blob_features(ellipse_mask(centre, DISC_RADIUS, DISC_RADIUS))

    assert isinstance(features, BlobFeatures)
    assert 1.0 <= features.eccentricity <= 1.0 + DISC_ECCENTRICITY_TOLERANCE
    assert features.area == pytest.approx(math.pi * DISC_RADIUS**2, rel=DISC_AREA_RELATIVE_TOLERANCE)
    # A disc's coordinates have standard deviation r/2 along every axis.
    assert features.major_axis_std == pytest.approx(0.5 * DISC_RADIUS, rel=0.01)
    assert features.minor_axis_std == pytest.approx(0.5 * DISC_RADIUS, rel=0.01)


def test_disc_centred_on_a_pixel_is_exactly_symmetric():
    features = blob_features(ellipse_mask((160.0, 120.0), DISC_RADIUS, DISC_RADIUS))

    assert features.mu20 == features.mu02
    assert features.mu11 == 0.0
    assert features.eccentricity == 1.0


def test_centroid_of_an_off_centre_disc():
    centre = (231.25, 64.5)  # (u, v): right of and above the image centre
    features = blob_features(ellipse_mask(centre, 30.0, 30.0))

    assert features.centroid[0] == pytest.approx(centre[0], abs=CENTROID_TOLERANCE_PX)
    assert features.centroid[1] == pytest.approx(centre[1], abs=CENTROID_TOLERANCE_PX)


@pytest.mark.parametrize("angle", [0.0, 0.4, -1.1, 0.5 * math.pi, 2.5])
def test_ellipse_eccentricity_is_axis_ratio_and_angle_is_its_orientation(angle):
    semi_major, semi_minor = 60.0, 20.0
    features = blob_features(ellipse_mask(IMAGE_CENTRE, semi_major, semi_minor, angle))

    assert features.eccentricity == pytest.approx(
        semi_major / semi_minor, rel=ELLIPSE_ECCENTRICITY_RELATIVE_TOLERANCE
    )
    assert abs(axis_angle_difference(features.principal_axis_angle, angle)) < ELLIPSE_ANGLE_TOLERANCE
    assert -0.5 * math.pi < features.principal_axis_angle <= 0.5 * math.pi
    # An ellipse's coordinates have standard deviation (semi-axis)/2 along each axis.
    assert features.major_axis_std == pytest.approx(0.5 * semi_major, rel=0.01)
    assert features.minor_axis_std == pytest.approx(0.5 * semi_minor, rel=0.01)


@pytest.mark.parametrize("angle", [math.pi / 6, -math.pi / 4, 1.2, 2.0, math.pi - 0.3])
def test_rotated_rectangle_gives_its_angle_and_width_over_height(angle):
    width, height = 120.0, 30.0
    features = blob_features(rectangle_mask(IMAGE_CENTRE, width, height, angle))

    # Variances w²/12 and h²/12, so the ratio of standard deviations is w/h.
    assert features.eccentricity == pytest.approx(
        width / height, rel=RECTANGLE_ECCENTRICITY_RELATIVE_TOLERANCE
    )
    assert abs(axis_angle_difference(features.principal_axis_angle, angle)) < RECTANGLE_ANGLE_TOLERANCE


def test_axis_aligned_rectangle_moments_are_exact():
    mask = np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool)
    width, height = 60, 20
    mask[100 : 100 + height, 50 : 50 + width] = True  # rows v, columns u

    features = blob_features(mask)

    assert features.area == width * height
    assert features.centroid == (50 + (width - 1) / 2, 100 + (height - 1) / 2)
    # n pixel centres 1 px apart have variance (n² − 1)/12.
    assert features.mu20 == pytest.approx(width * height * (width**2 - 1) / 12)
    assert features.mu02 == pytest.approx(width * height * (height**2 - 1) / 12)
    assert features.mu11 == 0.0
    assert features.principal_axis_angle == 0.0
    assert features.eccentricity == pytest.approx(math.sqrt((width**2 - 1) / (height**2 - 1)))
    np.testing.assert_allclose(
        features.covariance, np.diag([(width**2 - 1) / 12, (height**2 - 1) / 12]), rtol=1e-12
    )


def test_tall_rectangle_has_a_vertical_principal_axis():
    mask = np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool)
    mask[20:200, 150:170] = True  # 20 wide (u), 180 tall (v)

    features = blob_features(mask)

    assert features.principal_axis_angle == pytest.approx(0.5 * math.pi)


def test_angle_is_measured_from_u_toward_v():
    mask = np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool)
    index = np.arange(100)
    mask[20 + index, 30 + index] = True  # down and to the right: from +u toward +v
    assert blob_features(mask).principal_axis_angle == pytest.approx(math.pi / 4)

    mask = np.fliplr(mask)  # up and to the right
    assert blob_features(mask).principal_axis_angle == pytest.approx(-math.pi / 4)


def test_empty_mask_gives_no_object_without_warnings():
    with warnings.catch_warnings(), np.errstate(all="raise"):
        warnings.simplefilter("error")
        features = blob_features(np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool))
        area = contour_area(np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool))
        at_border = touches_border(np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool))

    assert features is None
    assert area == 0
    assert not at_border


@pytest.mark.parametrize("direction", ["horizontal", "vertical", "diagonal"])
def test_one_pixel_wide_line_has_infinite_eccentricity_without_warnings(direction):
    mask = np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool)
    if direction == "horizontal":
        mask[50, 10:300] = True
    elif direction == "vertical":
        mask[10:230, 77] = True
    else:
        index = np.arange(150)
        mask[40 + index, 90 + index] = True

    with warnings.catch_warnings(), np.errstate(all="raise"):
        warnings.simplefilter("error")
        features = blob_features(mask)

    assert features.eccentricity == math.inf
    assert features.minor_axis_std == 0.0
    assert features.major_axis_std > 0.0


def test_single_pixel_is_a_point_with_eccentricity_one():
    mask = np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool)
    mask[7, 11] = True

    with warnings.catch_warnings(), np.errstate(all="raise"):
        warnings.simplefilter("error")
        features = blob_features(mask)

    assert features.area == 1
    assert features.centroid == (11.0, 7.0)
    assert features.eccentricity == 1.0
    assert features.major_axis_std == features.minor_axis_std == 0.0


def test_blob_features_is_frozen_and_rejects_non_2d_masks():
    features = blob_features(ellipse_mask(IMAGE_CENTRE, 10.0, 5.0))
    with pytest.raises(AttributeError):
        features.area = 3
    with pytest.raises(ValueError):
        blob_features(np.ones((4, 4, 1), dtype=bool))


def test_contour_area_is_the_pixel_count():
    mask = ellipse_mask(IMAGE_CENTRE, 50.0, 20.0, 0.3)
    assert contour_area(mask) == int(mask.sum()) == blob_features(mask).area


def test_touches_border():
    assert not touches_border(ellipse_mask(IMAGE_CENTRE, 40.0, 40.0))
    assert touches_border(ellipse_mask((5.0, 120.0), 40.0, 40.0))  # cut by the left edge
    assert touches_border(ellipse_mask((160.0, 239.0), 10.0, 10.0))  # cut by the bottom edge

    mask = np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool)
    mask[3, 100] = True  # three rows between it and the top edge
    assert not touches_border(mask)
    assert not touches_border(mask, margin_px=2)
    assert touches_border(mask, margin_px=3)


def test_pixels_to_metres():
    # 100 px at 0.5 m with a 500 px focal length: 0.1 m; areas scale with the square.
    assert pixels_to_metres(100.0, depth_m=0.5, focal_px=500.0) == pytest.approx(0.1)
    assert square_pixels_to_square_metres(100.0**2, depth_m=0.5, focal_px=500.0) == pytest.approx(0.01)
    np.testing.assert_allclose(pixels_to_metres(np.array([50.0, 200.0]), 1.0, 500.0), [0.1, 0.4])


# ---------------------------------------------------------------------------------------------------
# Segmentation: label image


def _label_image(dtype=np.int16, with_channel=True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A label image with background, labels 3 and 5 and some don't-care pixels; and the true masks."""
    labels = np.full((IMAGE_HEIGHT, IMAGE_WIDTH), LABEL_EMPTY, dtype=dtype)
    object_mask = ellipse_mask((100.0, 120.0), 40.0, 25.0, 0.2)
    table_mask = np.zeros_like(object_mask)
    table_mask[180:, :] = True
    labels[table_mask] = 5
    labels[object_mask] = 3
    labels[:10, :10] = LABEL_DONT_CARE
    return (labels[:, :, np.newaxis] if with_channel else labels), object_mask, table_mask


def test_reserved_label_values_match_drake():
    from pydrake.geometry import RenderLabel

    assert LABEL_EMPTY == int(RenderLabel.kEmpty)
    assert LABEL_DONT_CARE == int(RenderLabel.kDontCare)
    assert LABEL_DO_NOT_RENDER == int(RenderLabel.kDoNotRender)
    assert LABEL_UNSPECIFIED == int(RenderLabel.kUnspecified)
    assert LABEL_MAX_UNRESERVED == int(RenderLabel.kMaxUnreserved)


@pytest.mark.parametrize(("dtype", "with_channel"), [(np.int16, True), (np.int32, False)])
def test_mask_from_label_picks_the_object(dtype, with_channel):
    labels, object_mask, table_mask = _label_image(dtype, with_channel)

    mask = mask_from_label(labels, 3)

    assert mask.shape == (IMAGE_HEIGHT, IMAGE_WIDTH)
    assert mask.dtype == bool
    np.testing.assert_array_equal(mask, object_mask)
    np.testing.assert_array_equal(mask_from_label(labels, 5), table_mask)
    np.testing.assert_array_equal(mask_from_label(labels, [3, 5]), object_mask | table_mask)
    assert not mask_from_label(labels, 4).any()


def test_mask_from_label_accepts_a_drake_render_label():
    from pydrake.geometry import RenderLabel

    labels, object_mask, _ = _label_image()
    np.testing.assert_array_equal(mask_from_label(labels, RenderLabel(3)), object_mask)


def test_mask_excluding_labels_drops_background_dont_care_and_excluded():
    labels, object_mask, _ = _label_image()
    labels[200:210, 0:10, 0] = LABEL_UNSPECIFIED

    np.testing.assert_array_equal(mask_from_labels_excluding(labels, {5}), object_mask)


def test_label_image_of_wrong_shape_or_type_is_rejected():
    with pytest.raises(ValueError):
        mask_from_label(np.zeros((4, 4, 3), dtype=np.int16), 1)
    with pytest.raises(ValueError):
        mask_from_label(np.zeros((4, 4), dtype=np.float32), 1)


def test_largest_component_only_drops_smaller_blobs():
    labels, object_mask, _ = _label_image()
    labels[20:25, 250:255, 0] = 3  # a small second blob with the object's label

    np.testing.assert_array_equal(mask_from_label(labels, 3, largest_component_only=True), object_mask)
    assert mask_from_label(labels, 3).sum() == object_mask.sum() + 25


def test_keep_largest_component_connectivity():
    mask = np.zeros((6, 6), dtype=bool)
    mask[0, 0] = mask[1, 1] = mask[2, 2] = True  # a diagonal: one blob for 8-connectivity only
    mask[4, 3:6] = True

    diagonal = np.eye(6, dtype=bool) & (np.arange(6) < 3)
    np.testing.assert_array_equal(keep_largest_component(mask, connectivity=8), diagonal)
    assert keep_largest_component(mask, connectivity=4).sum() == 3
    assert keep_largest_component(mask, connectivity=4)[4, 3]
    assert not keep_largest_component(np.zeros((3, 3), dtype=bool)).any()
    with pytest.raises(ValueError):
        keep_largest_component(mask, connectivity=6)


# ---------------------------------------------------------------------------------------------------
# Segmentation: colour

YELLOW_HUE_RANGE = (math.radians(40.0), math.radians(70.0))  # yellow is at 60° (π/3 rad)


def test_rgb_to_hsv_matches_colorsys():
    rng = np.random.default_rng(0)
    rgb = rng.integers(0, 256, size=(50, 3), dtype=np.uint8)
    rgb[:5] = [[0, 0, 0], [255, 255, 255], [128, 128, 128], [255, 0, 0], [255, 0, 1]]

    hsv = rgb_to_hsv(rgb)

    expected = np.array([colorsys.rgb_to_hsv(*(pixel / 255.0)) for pixel in rgb])
    expected[:, 0] *= 2.0 * math.pi
    expected[:, 0] %= 2.0 * math.pi
    np.testing.assert_allclose(hsv, expected, atol=1e-12)
    assert np.all((hsv[:, 0] >= 0.0) & (hsv[:, 0] < 2.0 * math.pi))


def test_color_thresholding_picks_a_yellow_square_out_of_a_grey_image():
    image = np.full((IMAGE_HEIGHT, IMAGE_WIDTH, 4), 128, dtype=np.uint8)
    image[..., 3] = 255
    image[50:90, 200:260, :3] = [230, 200, 20]  # yellow paper
    image[150:180, 30:60, :3] = [20, 40, 220]  # a blue distractor
    image[150:180, 100:130, :3] = [250, 250, 240]  # white: yellowish hue, too little saturation
    image[200:220, 250:280, :3] = [40, 35, 5]  # yellow in deep shadow: too dark
    expected = np.zeros((IMAGE_HEIGHT, IMAGE_WIDTH), dtype=bool)
    expected[50:90, 200:260] = True

    mask = mask_from_color(image, YELLOW_HUE_RANGE, min_saturation=0.5, min_value=0.3)

    np.testing.assert_array_equal(mask, expected)
    features = blob_features(mask)
    assert features.centroid == (229.5, 69.5)


def test_color_thresholding_with_a_hue_range_that_wraps_through_red():
    image = np.full((20, 30, 3), 128, dtype=np.uint8)
    image[2:6, 2:6] = [220, 30, 10]  # red-orange, hue just above 0
    image[10:14, 10:14] = [220, 10, 40]  # crimson, hue just below 2π
    image[15:18, 20:25] = [230, 200, 20]  # yellow: outside the range

    mask = mask_from_color(image, (math.radians(340.0), math.radians(20.0)), 0.5, 0.3)

    assert mask.sum() == 32
    assert mask[2:6, 2:6].all() and mask[10:14, 10:14].all()
