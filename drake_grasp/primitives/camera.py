"""The wrist camera at a fixed rate: one LeafSystem that samples an image and measures the silhouette.

`SilhouetteCamera` is the only consumer of the RgbdSensor's images in the exploration diagram. The
station's sensor renders on demand, so the camera's cost is set here: one image per period, and only
the image type the segmentation needs (the label image by default: a perfect object mask; the colour
image only when colour segmentation — the paper's yellow paper — is asked for).
"""


import dataclasses
import math
import typing

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.framework import Context, LeafSystem
from pydrake.systems.sensors import ImageLabel16I, ImageRgba8U

from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.silhouette import CameraSample, measure_silhouette
from drake_grasp.vision import add_image_noise, mask_from_color, mask_from_label


@dataclasses.dataclass
class ColorNoise:
    """Additive Gaussian noise on the colour image before colour segmentation (a camera's sensor noise).

    Attributes:
        sigma: standard deviation, in 8-bit counts, of the noise on each colour value.
        seed: mixed into the noise's random stream besides the trial's own key (see `SilhouetteCamera`):
            another seed, other noise for the same trial.
    """

    sigma: float = 10.0
    seed: int = 0

    def validate(self) -> None:
        if not (math.isfinite(self.sigma) and self.sigma >= 0):
            raise ValueError(f"segmentation.color_noise.sigma must be a finite number >= 0 (8-bit counts), "
                             f"got {self.sigma}")
        if not 0 <= self.seed < 2**63:
            raise ValueError(f"segmentation.color_noise.seed must be in [0, 2^63), got {self.seed}")


@dataclasses.dataclass
class SegmentationParams:
    """How the object's pixels are found.

    Attributes:
        method: "label" (the label image: pixels whose render label is the object's) or "color"
            (HSV thresholds on the colour image, like the paper's yellow-wrapped objects).
        hue_range_deg: (lowest, highest) hue, degrees, for "color" (wraps through 0 if lowest > highest).
        min_saturation, min_value: lowest saturation and value in [0, 1], for "color".
        largest_component_only: keep only the largest connected blob.
        color_noise: with "color", Gaussian noise added to the colour image before thresholding
            (`ColorNoise`); omitted (None): no noise. None is left out of the scenario's YAML dump,
            so scenarios without it keep their fingerprints.
    """

    method: str = "label"
    hue_range_deg: list[float] = dataclasses.field(default_factory=lambda: [40.0, 65.0])
    min_saturation: float = 0.5
    min_value: float = 0.3
    largest_component_only: bool = False
    color_noise: typing.Optional[ColorNoise] = None

    def validate(self) -> None:
        if self.method not in ("label", "color"):
            raise ValueError(f"segmentation.method must be 'label' or 'color', got {self.method!r}")
        if len(self.hue_range_deg) != 2:
            raise ValueError("segmentation.hue_range_deg needs two angles")
        if self.color_noise is not None:
            if self.method != "color":
                raise ValueError("segmentation.color_noise needs method 'color' (the label image has no noise)")
            self.color_noise.validate()


class SilhouetteCamera(LeafSystem):
    """Samples the wrist camera every `period` s and measures the object's silhouette.

    Input ports:
        label_image (ImageLabel16I) — or color_image (ImageRgba8U) with colour segmentation.
        X_WC (RigidTransform): the camera's pose, as the RgbdSensor reports it.
        active (1, optional): 0 stops sampling (no image is rendered; the last sample is held), e.g.
            once the exploration is over and the arm grasps; unconnected, the camera always samples.
    Output ports:
        camera_sample: `CameraSample.to_vector()` of the latest image (time, silhouette, X_WC).

    With `segmentation.color_noise`, each colour image gets Gaussian noise before thresholding. The
    noise of an image is a pure function of (`color_noise.seed`, `noise_seed`, the image's index
    round(t / period)): the same trial gives the same images, whatever else runs, and a sample taken
    twice at one time is the same sample.
    """

    def __init__(self, intrinsics: CameraIntrinsics, object_labels: list[int], period: float,
                 segmentation: SegmentationParams | None = None, noise_seed: int = 0):
        super().__init__()
        self.intrinsics = intrinsics
        self.object_labels = [int(label) for label in object_labels]
        self.segmentation = segmentation or SegmentationParams()
        self.segmentation.validate()
        if not 0 <= int(noise_seed) < 2**64:
            raise ValueError(f"noise_seed must be in [0, 2^64), got {noise_seed}")
        self.noise_seed = int(noise_seed)
        self.period = float(period)
        if self.segmentation.method == "label":
            self._image_port = self.DeclareAbstractInputPort("label_image", AbstractValue.Make(ImageLabel16I()))
        else:
            self._image_port = self.DeclareAbstractInputPort("color_image", AbstractValue.Make(ImageRgba8U()))
        self._pose_port = self.DeclareAbstractInputPort("X_WC", AbstractValue.Make(RigidTransform()))
        self._active_port = self.DeclareVectorInputPort("active", 1)
        self._state = self.DeclareDiscreteState(CameraSample.empty().to_vector())
        self.DeclareStateOutputPort("camera_sample", self._state)
        self.DeclarePeriodicDiscreteUpdateEvent(period, 0.0, self._Sample)
        self.frames = 0  # images taken (a diagnostic; not state)

    def image_input_port(self):
        """The image input: ``label_image`` or ``color_image``, as the segmentation method needs."""
        return self._image_port

    def mask(self, image: np.ndarray) -> np.ndarray:
        """The object's mask in an image array (label (H, W, 1) or RGBA (H, W, 4))."""
        s = self.segmentation
        if s.method == "label":
            return mask_from_label(image, self.object_labels, largest_component_only=s.largest_component_only)
        hue = tuple(math.radians(h) % (2 * math.pi) for h in s.hue_range_deg)
        return mask_from_color(image, hue, s.min_saturation, s.min_value,
                               largest_component_only=s.largest_component_only)

    def noisy(self, image: np.ndarray, time: float) -> np.ndarray:
        """The colour image as the segmentation sees it at `time`: with `color_noise`, plus that
        image's noise; else `image` itself."""
        noise = self.segmentation.color_noise
        if noise is None or self.segmentation.method != "color":
            return image
        index = int(round(time / self.period))
        rng = np.random.default_rng([int(noise.seed), self.noise_seed, index])
        return add_image_noise(image, noise.sigma, rng)

    def _Sample(self, context: Context, discrete_state) -> None:
        if self._active_port.HasValue(context) and self._active_port.Eval(context)[0] < 0.5:
            return  # the discrete state (the last sample) is left as it is
        image = self.noisy(self._image_port.Eval(context).data, context.get_time())
        X_WC = self._pose_port.Eval(context)
        self.frames += 1
        sample = CameraSample(time=context.get_time(), silhouette=measure_silhouette(self.mask(image)),
                              p_WC=X_WC.translation(), R_WC=X_WC.rotation().matrix())
        discrete_state.get_mutable_vector(self._state).SetFromVector(sample.to_vector())
