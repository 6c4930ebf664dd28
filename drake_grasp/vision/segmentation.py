"""Segmentation: from a camera image to the object's mask (the silhouette the visual primitives use).

Two sources of a mask, (docs/design.md §5.4):

- the **label image** (default): Drake's RgbdSensor renders, for every pixel, the render label of the
  geometry seen there. MultibodyPlant labels a geometry with the index of its body, so the object's
  mask is exact. A label image is an integer array of shape (H, W, 1) (``ImageLabel16I.data`` is
  int16); (H, W) is accepted too.
- **colour thresholding** (option): the paper wrapped its objects in yellow paper and thresholded the
  colour image in HSV. Drake's colour images are uint8 RGBA arrays of shape (H, W, 4).

Either can keep only the largest connected component of the mask (drops stray pixels and other
objects of the same colour). `add_image_noise` adds a camera's sensor noise to a colour image before
thresholding (the sensitivity sweep's "colour with image noise").

Image conventions: arrays are indexed ``[v, u]``, v = row (downward), u = column (to the right).
All functions are pure, take plain numpy arrays and return a boolean mask of shape (H, W).
"""

from collections.abc import Iterable

import numpy as np
from scipy import ndimage

# Reserved render labels of Drake's `pydrake.geometry.RenderLabel` (values for drake 1.x; a test checks
# them against pydrake). Labels 0..LABEL_MAX_UNRESERVED are ordinary labels (body indices);
# the values above it never belong to an object.
LABEL_MAX_UNRESERVED = 32763
"""RenderLabel.kMaxUnreserved: the largest label a geometry (an object) can have."""
LABEL_DONT_CARE = 32764
"""RenderLabel.kDontCare: geometry that is seen but should be ignored by perception."""
LABEL_DO_NOT_RENDER = 32765
"""RenderLabel.kDoNotRender: geometry that is not drawn in label images at all."""
LABEL_EMPTY = 32766
"""RenderLabel.kEmpty: background, i.e. no geometry at that pixel."""
LABEL_UNSPECIFIED = 32767
"""RenderLabel.kUnspecified: the default label of a geometry that was given none."""

CONNECTIVITIES = (4, 8)
"""Pixel neighbourhoods for connected components: 4 (edges) or 8 (edges and corners)."""


def mask_from_label(
    label_image: np.ndarray,
    object_label: int | Iterable[int],
    *,
    largest_component_only: bool = False,
) -> np.ndarray:
    """Returns the mask of the pixels that show the object with the given render label(s).

    Args:
        label_image: Render labels, integer array of shape (H, W) or (H, W, 1), e.g.
            ``ImageLabel16I.data`` from Drake's RgbdSensor.
        object_label: The object's label (an int, or a ``RenderLabel``), or several labels whose
            union is the object (e.g. the bodies of a multi-body object).
        largest_component_only: If True, keep only the largest 8-connected component.

    Returns:
        Boolean mask of shape (H, W), True on the object.

    Raises:
        ValueError: If ``label_image`` has another shape or a non-integer type.
    """
    labels = _as_label_array(label_image)
    if isinstance(object_label, Iterable):
        wanted = np.fromiter((int(label) for label in object_label), dtype=np.int64)
        mask = np.isin(labels, wanted)
    else:
        mask = labels == int(object_label)
    return keep_largest_component(mask) if largest_component_only else mask


def mask_from_labels_excluding(
    label_image: np.ndarray,
    excluded_labels: Iterable[int],
    *,
    largest_component_only: bool = False,
) -> np.ndarray:
    """Returns the mask of every object pixel whose label is not excluded.

    For a scene in which the object is "anything that is not the table or the robot": pass the
    labels of the table and robot bodies. Pixels with a reserved label (background ``LABEL_EMPTY``,
    ``LABEL_DONT_CARE``, ``LABEL_DO_NOT_RENDER``, ``LABEL_UNSPECIFIED``) are never in the mask.

    Args:
        label_image: Render labels, integer array of shape (H, W) or (H, W, 1).
        excluded_labels: Labels (ints or ``RenderLabel``) that are not the object.
        largest_component_only: If True, keep only the largest 8-connected component.

    Returns:
        Boolean mask of shape (H, W), True on the object.

    Raises:
        ValueError: If ``label_image`` has another shape or a non-integer type.
    """
    labels = _as_label_array(label_image)
    excluded = np.fromiter((int(label) for label in excluded_labels), dtype=np.int64)
    mask = (labels >= 0) & (labels <= LABEL_MAX_UNRESERVED) & ~np.isin(labels, excluded)
    return keep_largest_component(mask) if largest_component_only else mask


def rgb_to_hsv(rgb_image: np.ndarray) -> np.ndarray:
    """Converts an RGB(A) image to HSV, vectorised.

    Args:
        rgb_image: Array of shape (..., 3) or (..., 4); uint8 in [0, 255] or float in [0, 1]. An
            alpha channel is ignored.

    Returns:
        Float array of shape (..., 3): hue in radians in [0, 2π) (0 = red, π/3 = yellow,
        2π/3 = green, π = cyan, 4π/3 = blue, 5π/3 = magenta; 0 for greys), saturation in [0, 1]
        (0 for black) and value in [0, 1].

    Raises:
        ValueError: If the last axis has neither 3 nor 4 channels.
    """
    rgb = np.asarray(rgb_image)
    if rgb.ndim < 1 or rgb.shape[-1] not in (3, 4):
        raise ValueError(f"expected an RGB or RGBA image of shape (..., 3|4), got {rgb.shape}")
    rgb = rgb[..., :3]
    scale = 1.0 / 255.0 if np.issubdtype(rgb.dtype, np.integer) else 1.0
    rgb = rgb.astype(np.float64) * scale
    red, green, blue = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    value = rgb.max(axis=-1)
    chroma = value - rgb.min(axis=-1)
    saturation = np.divide(chroma, value, out=np.zeros_like(value), where=value > 0)

    # Hue sextant from the channel that is largest (red wins ties, then green), in units of π/3.
    has_chroma = chroma > 0
    safe_chroma = np.where(has_chroma, chroma, 1.0)
    sextant = np.where(
        value == red,
        np.mod((green - blue) / safe_chroma, 6.0),
        np.where(value == green, (blue - red) / safe_chroma + 2.0, (red - green) / safe_chroma + 4.0),
    )
    hue = np.where(has_chroma, sextant * (np.pi / 3.0), 0.0)
    hue = np.mod(hue, 2.0 * np.pi)  # maps a rounding-born 2π back to 0
    return np.stack([hue, saturation, value], axis=-1)


def mask_from_color(
    rgba_image: np.ndarray,
    hue_range: tuple[float, float],
    min_saturation: float,
    min_value: float,
    *,
    largest_component_only: bool = False,
) -> np.ndarray:
    """Returns the mask of the pixels whose colour lies in an HSV box (e.g. yellow-wrapped objects).

    Args:
        rgba_image: Colour image of shape (H, W, 4) or (H, W, 3); uint8 (Drake's ``ImageRgba8U.data``)
            or float in [0, 1]. Alpha is ignored.
        hue_range: (lowest, highest) hue in radians, in [0, 2π). If lowest > highest the range wraps
            through 0 (red), e.g. (5.9, 0.3). Bounds are inclusive.
        min_saturation: Lowest saturation in [0, 1]; rejects greys and white.
        min_value: Lowest value (brightness) in [0, 1]; rejects dark pixels and deep shadow.
        largest_component_only: If True, keep only the largest 8-connected component.

    Returns:
        Boolean mask of shape (H, W), True where the colour matches.

    Raises:
        ValueError: If the image is not (H, W, 3|4).
    """
    image = np.asarray(rgba_image)
    if image.ndim != 3:
        raise ValueError(f"expected a colour image of shape (H, W, 3|4), got {image.shape}")
    hsv = rgb_to_hsv(image)
    hue, saturation, value = hsv[..., 0], hsv[..., 1], hsv[..., 2]
    hue_low, hue_high = hue_range
    if hue_low <= hue_high:
        in_hue = (hue >= hue_low) & (hue <= hue_high)
    else:
        in_hue = (hue >= hue_low) | (hue <= hue_high)
    mask = in_hue & (saturation >= min_saturation) & (value >= min_value)
    return keep_largest_component(mask) if largest_component_only else mask


def add_image_noise(rgba_image: np.ndarray, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """A uint8 colour image with additive Gaussian noise on its colour channels (a camera's sensor
    noise), before segmentation.

    Args:
        rgba_image: uint8 array of shape (H, W, 3) or (H, W, 4) (Drake's ``ImageRgba8U.data``); alpha
            is kept as it is.
        sigma: standard deviation of the noise in 8-bit counts (0 returns an unchanged copy).
        rng: the random stream (numpy Generator); the same stream gives the same image.

    Returns:
        A new uint8 array of the same shape: each colour value plus N(0, sigma^2), rounded and clipped
        to [0, 255].

    Raises:
        ValueError: not a uint8 (H, W, 3|4) image, or sigma negative or not finite.
    """
    image = np.asarray(rgba_image)
    if image.ndim != 3 or image.shape[2] not in (3, 4) or image.dtype != np.uint8:
        raise ValueError(f"expected a uint8 colour image of shape (H, W, 3|4), got {image.dtype} {image.shape}")
    if not (np.isfinite(sigma) and sigma >= 0):
        raise ValueError(f"noise sigma must be a finite number >= 0, got {sigma}")
    out = image.copy()
    if sigma == 0:
        return out
    colour = image[..., :3].astype(np.float64) + rng.normal(0.0, sigma, size=image[..., :3].shape)
    out[..., :3] = np.clip(np.rint(colour), 0, 255).astype(np.uint8)
    return out


def keep_largest_component(mask: np.ndarray, connectivity: int = 8) -> np.ndarray:
    """Returns the largest connected component of a mask.

    Args:
        mask: Boolean array of shape (H, W).
        connectivity: 8 (pixels touching at edges or corners are connected) or 4 (edges only).

    Returns:
        Boolean mask of shape (H, W) holding only the largest component; all False if ``mask`` is
        empty. On a tie the component met first in row-major order wins.

    Raises:
        ValueError: If ``connectivity`` is not 4 or 8.
    """
    if connectivity not in CONNECTIVITIES:
        raise ValueError(f"connectivity must be one of {CONNECTIVITIES}, got {connectivity}")
    mask = np.asarray(mask, dtype=bool)
    structure = ndimage.generate_binary_structure(2, 2 if connectivity == 8 else 1)
    components, count = ndimage.label(mask, structure=structure)
    if count <= 1:
        return mask.copy()
    sizes = np.bincount(components.ravel())
    sizes[0] = 0  # the background is not a component
    return components == int(np.argmax(sizes))


def _as_label_array(label_image: np.ndarray) -> np.ndarray:
    """Returns a label image as an (H, W) integer array (a view when possible)."""
    labels = np.asarray(label_image)
    if labels.ndim == 3 and labels.shape[2] == 1:
        labels = labels[:, :, 0]
    if labels.ndim != 2:
        raise ValueError(f"expected a label image of shape (H, W) or (H, W, 1), got {labels.shape}")
    if not np.issubdtype(labels.dtype, np.integer):
        raise ValueError(f"expected an integer label image, got dtype {labels.dtype}")
    return labels
