"""The inertial a model file gives, checked before it can reach the plant (pure functions).

Why: a model file carries an inertial, and inertials in the wild are often placeholders (izz = 0,
1 kg·m² on a 0.1 kg object) that make the mass matrix singular or the object spin like a flywheel.
Every inertial read from a file is checked (:func:`inertia_problem`): finite and positive-definite,
the principal moments satisfy the triangle inequality, the moments fit inside the collision
geometry (no principal moment above mass × the largest distance of the geometry from the centre of
mass, squared), and the mass implies a plausible density for the collision geometry's volume (20 to
20,000 kg/m³: from expanded foam to tungsten). An implausible inertial is replaced by the one the
collision geometry gives at uniform density (keeping a plausible mass), with a one-line
`InertiaWarning` that names the bad value; ``inertia="file"`` keeps the file's, and refuses one
that cannot be simulated. Nothing read from a file reaches the plant unchecked.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from drake_grasp.objects.spec import DEFAULT_DENSITY, InertiaWarning, ObjectError

PLAUSIBLE_DENSITY = (20.0, 20_000.0)  # kg/m³: expanded foam to tungsten
INERTIA_CHOICES = ("check", "file", "geometry")


def inertia_problem(mass: float, inertia: np.ndarray, volume: float | None = None,
                    radius: float | None = None) -> str | None:
    """Why an inertial cannot be simulated or is implausible for its geometry, or None.

    Args:
        mass: kg.
        inertia: 3×3 rotational inertia about the centre of mass, kg·m².
        volume: the collision geometry's volume (m³), for the density check; None skips it.
        radius: the largest distance (m) of the collision geometry from the centre of mass; None
            skips the size check.
    """
    inertia = np.asarray(inertia, float)
    if not math.isfinite(mass):
        return f"mass {mass:g} kg is not finite" if not math.isnan(mass) else "the mass is missing or NaN"
    if not mass > 0.0:
        return f"mass {mass:g} kg is not positive"
    if not np.all(np.isfinite(inertia)):
        return "the inertia has a non-finite entry"
    if not np.allclose(inertia, inertia.T, rtol=1e-9, atol=1e-15):
        return "the inertia is not symmetric"
    moments = np.linalg.eigvalsh(inertia)
    if moments[0] <= 1e-12 * max(moments[-1], 1e-300) or moments[0] <= 0.0:
        return f"the inertia is not positive-definite (principal moments {_moments(moments)} kg·m²)"
    if moments[2] > (moments[0] + moments[1]) * (1.0 + 1e-6):
        return f"the principal moments {_moments(moments)} kg·m² break the triangle inequality"
    if volume is not None and volume > 0.0:
        density = mass / volume
        if not PLAUSIBLE_DENSITY[0] <= density <= PLAUSIBLE_DENSITY[1]:
            return (f"mass {mass:g} kg in {volume * 1e6:.4g} cm³ of collision geometry is a density of "
                    f"{density:.4g} kg/m³ (plausible: {PLAUSIBLE_DENSITY[0]:g} to {PLAUSIBLE_DENSITY[1]:g})")
    if radius is not None and radius > 0.0 and moments[2] > 1.01 * mass * radius**2:
        return (f"principal moment {moments[2]:.3g} kg·m² exceeds what {mass:g} kg within {radius * 100:.3g} cm "
                f"of its centre of mass can have ({mass * radius**2:.3g} kg·m²)")
    return None


def simulable_problem(mass: float, inertia: np.ndarray) -> str | None:
    """Why an inertial cannot be simulated at all (not finite, not positive-definite, the triangle
    inequality broken), or None: what ``inertia="file"`` still refuses."""
    return inertia_problem(mass, inertia)


def _moments(moments: np.ndarray) -> str:
    return ", ".join(f"{m:.3g}" for m in moments)


def checked_mass_properties(label: str, file_mass: float, file_com: np.ndarray, file_inertia: np.ndarray,
                            geometry: tuple[float, np.ndarray, np.ndarray], radius_about, choice: str,
                            density: float = DEFAULT_DENSITY) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, unit inertia about it) for an object whose file gives `file_mass`
    (kg), `file_com` and `file_inertia` (kg·m² about file_com) and whose collision geometry gives
    `geometry` = (volume, centroid, unit inertia about it). `radius_about(point)` is the geometry's
    largest distance from a point. `choice`: "check" (the file's if plausible, else the geometry's
    with an InertiaWarning), "file" (the file's; ObjectError if it cannot be simulated), "geometry".
    """
    volume, centroid, unit_inertia = geometry
    if choice == "file":
        problem = simulable_problem(file_mass, file_inertia)
        if problem:
            raise ObjectError(f"{label}: the file's inertia cannot be simulated: {problem}")
        return file_mass, np.asarray(file_com, float), np.asarray(file_inertia, float) / file_mass
    if choice == "check":
        problem = inertia_problem(file_mass, file_inertia, volume, radius_about(np.asarray(file_com, float)))
        if problem is None:
            return file_mass, np.asarray(file_com, float), np.asarray(file_inertia, float) / file_mass
        mass = file_mass
        if not (math.isfinite(mass) and PLAUSIBLE_DENSITY[0] <= mass / volume <= PLAUSIBLE_DENSITY[1]):
            mass = density * volume
        warnings.warn(f"{label}: implausible inertia in the file ({problem}); using the collision geometry's "
                      f"at uniform density ({mass:.4g} kg; --inertia file keeps the file's)", InertiaWarning,
                      stacklevel=3)
        return mass, centroid, unit_inertia
    return (file_mass if math.isfinite(file_mass) and file_mass > 0 else density * volume), centroid, unit_inertia


def _check_choice(label: str, choice: str) -> None:
    if choice not in INERTIA_CHOICES:
        raise ObjectError(f"{label}: inertia must be one of {', '.join(INERTIA_CHOICES)}, got {choice!r}")
