"""Pure image functions for the visual primitives: segmentation and blob moments.

Plain numpy in, plain numpy (or a frozen dataclass) out; no Drake systems. The LeafSystems in
`drake_grasp.primitives` read Drake's RgbdSensor images (``image.data``) and call these.

- `segmentation`: the object's mask from the label image (default) or by HSV colour thresholding.
- `moments`: contour area, centroid, principal axis and eccentricity of the mask (`BlobFeatures`).

Image axes: u = column (to the right), v = row (downward); angles from +u toward +v, in radians.
"""

from drake_grasp.vision.moments import (
    BlobFeatures,
    blob_features,
    contour_area,
    pixels_to_metres,
    square_pixels_to_square_metres,
    touches_border,
)
from drake_grasp.vision.segmentation import (
    LABEL_DO_NOT_RENDER,
    LABEL_DONT_CARE,
    LABEL_EMPTY,
    LABEL_MAX_UNRESERVED,
    LABEL_UNSPECIFIED,
    add_image_noise,
    keep_largest_component,
    mask_from_color,
    mask_from_label,
    mask_from_labels_excluding,
    rgb_to_hsv,
)

__all__ = [
    "BlobFeatures",
    "LABEL_DO_NOT_RENDER",
    "LABEL_DONT_CARE",
    "LABEL_EMPTY",
    "LABEL_MAX_UNRESERVED",
    "LABEL_UNSPECIFIED",
    "add_image_noise",
    "blob_features",
    "contour_area",
    "keep_largest_component",
    "mask_from_color",
    "mask_from_label",
    "mask_from_labels_excluding",
    "pixels_to_metres",
    "rgb_to_hsv",
    "square_pixels_to_square_metres",
    "touches_border",
]
