"""The pinhole model of the wrist camera, and the 3-D meaning of image points and image lines.

Pure numpy. Conventions (Drake's RgbdSensor, and `drake_grasp.vision`): camera frame C has +z
forward (the optical axis), +x right (image u), +y down (image v); a pixel's coordinates are those of
its centre, so the top-left pixel is (u, v) = (0, 0) and the principal point of a W×H image is
((W − 1)/2, (H − 1)/2).

A camera twist is the spatial velocity of C in the world, expressed in C, stacked [ω; v] (rad/s, m/s),
as Drake's SpatialVelocity.
"""


import dataclasses
import math

import numpy as np


@dataclasses.dataclass(frozen=True)
class CameraIntrinsics:
    """A pinhole camera.

    Attributes:
        width, height: image size, px.
        fx, fy: focal lengths, px.
        cx, cy: principal point, px (pixel-centre coordinates).
    """

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float

    @classmethod
    def from_fov_y(cls, width: int, height: int, fov_y: float) -> "CameraIntrinsics":
        """Square pixels, principal point at the image centre, vertical field of view fov_y (rad)."""
        f = 0.5 * height / math.tan(0.5 * fov_y)
        return cls(width, height, f, f, 0.5 * (width - 1), 0.5 * (height - 1))

    @classmethod
    def from_camera_config(cls, config) -> "CameraIntrinsics":
        """From a pydrake.systems.sensors.CameraConfig (what the station's RgbdSensor uses)."""
        color_camera, _ = config.MakeCameras()
        k = color_camera.core().intrinsics()
        return cls(k.width(), k.height(), k.focal_x(), k.focal_y(), k.center_x(), k.center_y())

    def ray(self, u: float, v: float) -> np.ndarray:
        """Unit direction, in C, of the ray through pixel (u, v)."""
        r = np.array([(u - self.cx) / self.fx, (v - self.cy) / self.fy, 1.0])
        return r / np.linalg.norm(r)

    def angles(self, u: float, v: float) -> tuple[float, float]:
        """(θx, θy): angles of the ray through (u, v) from the optical axis, toward +x and +y (rad)."""
        return math.atan((u - self.cx) / self.fx), math.atan((v - self.cy) / self.fy)

    def line_plane_normal(self, e: np.ndarray, s: float) -> np.ndarray:
        """Unit normal, in C, of the plane through the camera centre that projects to an image line.

        The image line is {(u, v): e·(u, v) = s}. The normal's sign is such that n·p_C > 0 for the
        points p_C (in front of the camera) that project to e·(u, v) > s.
        """
        n = np.array([e[0] * self.fx, e[1] * self.fy, e[0] * self.cx + e[1] * self.cy - s])
        return n / np.linalg.norm(n)

    def project(self, p_C: np.ndarray) -> tuple[float, float]:
        """Pixel (u, v) of a point p_C in front of the camera (z > 0)."""
        return self.fx * p_C[0] / p_C[2] + self.cx, self.fy * p_C[1] / p_C[2] + self.cy


def orbit_twist(omega_C: np.ndarray, p_CO_C: np.ndarray) -> np.ndarray:
    """Camera twist [ω; v] (in C) that rotates the camera rigidly about the point O at rate ω.

    Args:
        omega_C: angular velocity, expressed in C, rad/s.
        p_CO_C: the pivot O relative to the camera, expressed in C, m.

    The camera origin moves with v = ω × (p_C − p_O) = p_CO × ω, so O stays fixed in the camera frame.
    """
    omega_C = np.asarray(omega_C, float)
    return np.concatenate([omega_C, np.cross(np.asarray(p_CO_C, float), omega_C)])


def centring_twist(theta_x: float, theta_y: float, gain: float) -> np.ndarray:
    """Camera twist that turns the optical axis toward a ray at angles (θx, θy) (proportional servo).

    A rotation about +y_C swings the optical axis toward +x_C, a rotation about −x_C toward +y_C.
    """
    return np.array([-gain * theta_y, gain * theta_x, 0.0, 0.0, 0.0, 0.0])


def arc_profile(s: float) -> tuple[float, float]:
    """One back-and-forth sweep: (φ, dφ/ds) for s in [0, 1], φ in [−1, 1].

    Three half-cosine segments, 0 → +1 (s in [0, ¼]), +1 → −1 ([¼, ¾]), −1 → 0 ([¾, 1]): zero
    velocity at both ends and at the turning points, and the same peak rate 2π in every segment
    (the lowest peak for this path among such profiles). Outside [0, 1] it is (0, 0).
    """
    if not 0.0 <= s <= 1.0:
        return 0.0, 0.0
    if s < 0.25:
        x = math.pi * s / 0.25
        return 0.5 * (1.0 - math.cos(x)), 0.5 * math.sin(x) * math.pi / 0.25
    if s < 0.75:
        x = math.pi * (s - 0.25) / 0.5
        return math.cos(x), -math.sin(x) * math.pi / 0.5
    x = math.pi * (s - 0.75) / 0.25
    return -0.5 * (1.0 + math.cos(x)), 0.5 * math.sin(x) * math.pi / 0.25


def arc_command(t: float, amplitude: float, period: float, sweeps: int = 1) -> tuple[float, float]:
    """(φ, dφ/dt) at time t (s) of `sweeps` back-and-forth arcs of ±amplitude (rad), each `period` s.

    (0, 0) before 0 and after sweeps·period. The peak rate is 2π·amplitude/period.
    """
    if period <= 0.0 or t < 0.0 or t > sweeps * period:
        return 0.0, 0.0
    s = (t / period) % 1.0 if t < sweeps * period else 1.0
    phi, dphi = arc_profile(s)
    return amplitude * phi, amplitude * dphi / period


def arc_angle(view_W: np.ndarray, reference_W: np.ndarray, axis_W: np.ndarray) -> float:
    """The signed angle (rad) by which the direction `view` is turned from `reference` about `axis`
    (unit vectors; reference ⊥ axis)."""
    return math.atan2(float(np.dot(axis_W, np.cross(reference_W, view_W))), float(np.dot(reference_W, view_W)))


def wrap_angle(angle: float, period: float) -> float:
    """`angle` wrapped into (−period/2, period/2]."""
    wrapped = math.remainder(angle, period)
    return period / 2.0 if wrapped == -period / 2.0 else wrapped
