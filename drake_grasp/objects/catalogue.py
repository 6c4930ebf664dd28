"""The object catalogue: the paper's nine objects and the primitive families of Fig. 4.

Each is an `objects.ObjectSpec` built from Drake primitives or convex meshes (see `objects` for the
frames and conventions). Every size and mass here is **assumed** (the paper gives none): the table in
docs/design.md §4.3 gives them with their household (YCB) analogues.
"""

from __future__ import annotations

import dataclasses
import functools
import math

from typing import Callable

import numpy as np
from drake_grasp.objects.spec import (
    CYLINDER_FAMILY_LENGTH, DEFAULT_DENSITY, ObjectError, ObjectSpec, ShapePiece, YELLOW_PAPER_RGBA,
    _cached_hull_obj,
)
from drake_grasp.objects.mass_properties import _make_spec


# --- The paper's nine objects (docs/design.md §4.3) ----------------------------------------------
# Sizes and masses are assumed (the paper gives none); YCB analogues in brackets. Every object is
# modelled in the pose it rests in on the table: z up, x along its longest horizontal extent.

_LYING_ALONG_X = (0.0, math.pi / 2.0, 0.0)  # rpy that turns a Drake cylinder/capsule's z onto x.

BANANA_CHORD = 0.18  # m, tip to tip [YCB 011 banana]
BANANA_DIAMETER = 0.036  # m
BANANA_BEND_RADIUS = 0.15  # m, radius of the centreline arc
BANANA_SEGMENTS = 4  # capsules in the chain (assumed)


def _banana() -> ObjectSpec:
    """A chain of capsules along a circular arc lying in the table plane, bulging towards +y."""
    radius = BANANA_DIAMETER / 2.0
    # The tips are the end capsules' caps: chord = 2·(R·sin θ + r), θ = half the arc angle.
    half_angle = math.asin((BANANA_CHORD / 2.0 - radius) / BANANA_BEND_RADIUS)
    angles = np.linspace(-half_angle, half_angle, BANANA_SEGMENTS + 1)
    centreline = np.column_stack(
        [
            BANANA_BEND_RADIUS * np.sin(angles),
            BANANA_BEND_RADIUS * np.cos(angles),
            np.zeros_like(angles),
        ]
    )
    pieces = []
    for a, b in zip(centreline[:-1], centreline[1:]):
        direction = b - a
        pieces.append(
            ShapePiece(
                "capsule",
                (radius, float(np.linalg.norm(direction))),
                p_OP=tuple((a + b) / 2.0),
                rpy_OP=(0.0, math.pi / 2.0, math.atan2(direction[1], direction[0])),
            )
        )
    return _make_spec(
        "banana", pieces, 0.12, overlapping=True, paper_class="annulus",
        closest_primitive="cylinder",
    )


def _apple() -> ObjectSpec:
    # 0.075 × 0.075 × 0.072 m [YCB 013 apple], 0.15 kg.
    pieces = [ShapePiece("ellipsoid", (0.075 / 2.0, 0.075 / 2.0, 0.072 / 2.0))]
    return _make_spec("apple", pieces, 0.15, paper_class="annulus", closest_primitive="sphere")


BELL_PEPPER_DIAMETER = 0.085  # m
BELL_PEPPER_HEIGHT = 0.09  # m
BELL_PEPPER_LOBES = 4
BELL_PEPPER_LOBE_OFFSET = 0.012  # m, distance of a lobe's axis from the pepper's axis (assumed)


def _bell_pepper() -> ObjectSpec:
    """The convex hull of four vertical ellipsoidal lobes: a rounded-square convex body."""
    lobe_radius = BELL_PEPPER_DIAMETER / 2.0 - BELL_PEPPER_LOBE_OFFSET
    semi = np.array([lobe_radius, lobe_radius, BELL_PEPPER_HEIGHT / 2.0])
    # A latitude-longitude grid that contains each lobe's equator and poles (the extremes).
    lat = np.linspace(-math.pi / 2.0, math.pi / 2.0, 11)
    lon = np.linspace(0.0, 2.0 * math.pi, 24, endpoint=False)
    lat, lon = np.meshgrid(lat, lon, indexing="ij")
    unit = np.column_stack(
        [(np.cos(lat) * np.cos(lon)).ravel(), (np.cos(lat) * np.sin(lon)).ravel(),
         np.sin(lat).ravel()]
    )
    points = []
    for k in range(BELL_PEPPER_LOBES):
        phi = 2.0 * math.pi * k / BELL_PEPPER_LOBES
        centre = BELL_PEPPER_LOBE_OFFSET * np.array([math.cos(phi), math.sin(phi), 0.0])
        points.append(unit * semi + centre)
    path = _cached_hull_obj("bell_pepper", np.vstack(points))
    pieces = [ShapePiece("convex", (), mesh_path=path)]
    return _make_spec(
        "bell_pepper", pieces, 0.16, paper_class="annulus", closest_primitive="sphere"
    )


def _sponge() -> ObjectSpec:
    # 0.11 × 0.07 × 0.035 m [YCB 026 sponge], 0.012 kg; a sharp box (exact contact).
    pieces = [ShapePiece("box", (0.11, 0.07, 0.035))]
    return _make_spec("sponge", pieces, 0.012, paper_class="annulus", closest_primitive="box")


SPECTACLE_CASE_SIZE = (0.16, 0.06, 0.04)  # m
SPECTACLE_CASE_EXPONENT = 4.0  # superellipsoid |x/a|^n + |y/b|^n + |z/c|^n = 1 (2 = ellipsoid)


def superellipsoid_points(
    semi_axes, exponent: float, n_lat: int = 13, n_lon: int = 32
) -> np.ndarray:
    """Surface points of the superellipsoid Σ|xᵢ/aᵢ|^n = 1, its extremes ±aᵢ included.

    Args:
        semi_axes: (a, b, c) semi-axes (m).
        exponent: n ≥ 1 (convex); 2 is an ellipsoid, large n approaches a box.
        n_lat: Latitude samples, poles included (odd, so that the equator is included).
        n_lon: Longitude samples (a multiple of 4, so that the ±x and ±y extremes are included).
    """
    e = 2.0 / exponent
    lat = np.linspace(-math.pi / 2.0, math.pi / 2.0, n_lat)
    lon = np.linspace(-math.pi, math.pi, n_lon, endpoint=False)
    lat, lon = np.meshgrid(lat, lon, indexing="ij")

    def signed_power(v):
        return np.sign(v) * np.abs(v) ** e

    a, b, c = semi_axes
    x = a * signed_power(np.cos(lat)) * signed_power(np.cos(lon))
    y = b * signed_power(np.cos(lat)) * signed_power(np.sin(lon))
    z = c * signed_power(np.sin(lat))
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


def _spectacle_case() -> ObjectSpec:
    """A superellipsoid of exponent 4 (a box with well-rounded edges), lying flat."""
    points = superellipsoid_points(np.array(SPECTACLE_CASE_SIZE) / 2.0, SPECTACLE_CASE_EXPONENT)
    path = _cached_hull_obj("spectacle_case", points)
    pieces = [ShapePiece("convex", (), mesh_path=path)]
    return _make_spec(
        "spectacle_case", pieces, 0.06, paper_class="annulus", closest_primitive="box"
    )


TOY_BRIDGE_SIZE = (0.15, 0.05, 0.06)  # m: span (x), width (y), height (z)
TOY_BRIDGE_BEAM_THICKNESS = 0.02  # m (assumed)
TOY_BRIDGE_LEG_WIDTH = 0.03  # m, along the span (assumed)


def _toy_bridge() -> ObjectSpec:
    """An arch: a beam on two legs (three boxes that touch and do not overlap)."""
    span, width, height = TOY_BRIDGE_SIZE
    leg_height = height - TOY_BRIDGE_BEAM_THICKNESS
    leg_x = span / 2.0 - TOY_BRIDGE_LEG_WIDTH / 2.0
    beam = (span, width, TOY_BRIDGE_BEAM_THICKNESS)
    leg = (TOY_BRIDGE_LEG_WIDTH, width, leg_height)
    pieces = [
        ShapePiece("box", beam, p_OP=(0.0, 0.0, height - TOY_BRIDGE_BEAM_THICKNESS / 2.0)),
        ShapePiece("box", leg, p_OP=(-leg_x, 0.0, leg_height / 2.0)),
        ShapePiece("box", leg, p_OP=(leg_x, 0.0, leg_height / 2.0)),
    ]
    return _make_spec("toy_bridge", pieces, 0.10, paper_class="annulus", closest_primitive="box")


def _soccer_ball() -> ObjectSpec:
    # Ø 0.20 m, 0.30 kg (a size-3 ball is Ø ~0.19 m, ~0.3 kg).
    pieces = [ShapePiece("sphere", (0.10,))]
    return _make_spec(
        "soccer_ball", pieces, 0.30, paper_class="sun_ray_sphere", closest_primitive="sphere"
    )


def _game_box() -> ObjectSpec:
    # 0.26 × 0.18 × 0.08 m lying flat, 0.40 kg.
    pieces = [ShapePiece("box", (0.26, 0.18, 0.08))]
    return _make_spec(
        "game_box", pieces, 0.40, paper_class="sun_ray_box", closest_primitive="box"
    )


def _bottle_case() -> ObjectSpec:
    # Ø 0.10 × 0.35 m, lying on its side with its axis along O's x, 0.35 kg.
    pieces = [ShapePiece("cylinder", (0.05, 0.35), rpy_OP=_LYING_ALONG_X)]
    return _make_spec(
        "bottle_case", pieces, 0.35, paper_class="sun_ray_cylinder", closest_primitive="cylinder"
    )


_PAPER_FACTORIES: dict[str, Callable[[], ObjectSpec]] = {
    "banana": _banana,
    "apple": _apple,
    "bell_pepper": _bell_pepper,
    "sponge": _sponge,
    "spectacle_case": _spectacle_case,
    "toy_bridge": _toy_bridge,
    "soccer_ball": _soccer_ball,
    "game_box": _game_box,
    "bottle_case": _bottle_case,
}

PAPER_OBJECTS: tuple[str, ...] = tuple(_PAPER_FACTORIES)
"""Names of the paper's nine objects, in the order of the table in docs/design.md §4.3 (annulus first)."""


@functools.lru_cache(maxsize=None)
def _paper_object_cached(name: str) -> ObjectSpec:
    return _PAPER_FACTORIES[name]()


def paper_object(name: str, *, rgba=None, friction: float | None = None) -> ObjectSpec:
    """One of the paper's nine objects (docs/design.md §4.3).

    Args:
        name: One of ``PAPER_OBJECTS``.
        rgba: Visual colour (RGBA, 0–1); default yellow paper.
        friction: Coulomb friction of this object; None uses the scene's.

    Raises:
        ObjectError: Unknown name (the message lists the valid names).
    """
    if name not in _PAPER_FACTORIES:
        raise ObjectError(f"unknown object {name!r}; valid names: {', '.join(PAPER_OBJECTS)}")
    spec = _paper_object_cached(name)
    if rgba is not None:
        spec = dataclasses.replace(spec, rgba=tuple(float(v) for v in rgba))
    if friction is not None:
        spec = dataclasses.replace(spec, friction=float(friction))
    return spec


# --- Primitive families (Fig. 4) -----------------------------------------------------------------


def _mm(size: float) -> str:
    return f"{size * 1000.0:.4g}mm".replace(".", "p")


PRIMITIVE_SIZE_RANGE = (0.001, 10.0)  # m: from a millimetre (Drake's geometry breaks down far below)
# to ten metres (far past anything the hand can hold: a number that large is a typo or the wrong unit)


def _check_size(label: str, **sizes: float) -> None:
    low, high = PRIMITIVE_SIZE_RANGE
    for key, value in sizes.items():
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
            raise ObjectError(f"{label}: {key} must be a positive number of metres, got {value!r}")
        if not low <= value <= high:
            raise ObjectError(f"{label}: {key} {value:g} m is outside [{low:g}, {high:g}] m (sizes are in metres)")


def sphere_object(
    diameter: float,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid sphere (Fig. 4's sphere family), named e.g. ``sphere_120mm``.

    Args:
        diameter: Diameter (m).
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    _check_size("sphere", diameter=diameter)
    return _make_spec(
        f"sphere_{_mm(diameter)}", [ShapePiece("sphere", (diameter / 2.0,))], mass, density=density,
        closest_primitive="sphere", rgba=rgba,
    )


def cube_object(
    edge: float,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid cube (Fig. 4's cube family) resting on a face, its edges along O's (and T's) axes.

    Args:
        edge: Edge length (m).
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    _check_size("cube", edge=edge)
    return _box_family(f"cube_{_mm(edge)}", (edge, edge, edge), mass, density, rgba)


def _box_family(name: str, size: tuple, mass: float | None, density: float, rgba) -> ObjectSpec:
    """A solid box of `size` (m, along O's axes) resting on its face, as Fig. 4's box families are."""
    return _make_spec(name, [ShapePiece("box", tuple(size))], mass, density=density, closest_primitive="box",
                      rgba=rgba)


def box_object(
    length: float,
    width: float,
    height: float,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid box resting on a face, `length` along O's x, `width` along y, `height` up (m): a
    domino, a tile, a book, named e.g. ``box_50mmx25mmx10mm``.

    Args:
        length, width, height: Edges along O's x, y and z (m).
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    _check_size("box", length=length, width=width, height=height)
    return _box_family(f"box_{_mm(length)}x{_mm(width)}x{_mm(height)}", (length, width, height), mass, density, rgba)


# The footprint of Fig. 4's flower family (a plate lying flat, the paper's "flower": small and flat), m:
# about the generated plates' (`objects.flower`), wider than the hand's closed fingertips are apart.
PLATE_FAMILY_FOOTPRINT = (0.08, 0.05)


def plate_object(
    thickness: float,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid plate lying flat (Fig. 4's flower family): `PLATE_FAMILY_FOOTPRINT` (its long side along
    O's x), `thickness` m tall.

    Args:
        thickness: Height (m).
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    _check_size("plate", thickness=thickness)
    return _box_family(f"plate_{_mm(thickness)}", (*PLATE_FAMILY_FOOTPRINT, thickness), mass, density, rgba)


def cylinder_object(
    diameter: float,
    length: float | None = None,
    *,
    mass: float | None = None,
    density: float = DEFAULT_DENSITY,
    rgba=YELLOW_PAPER_RGBA,
) -> ObjectSpec:
    """A solid cylinder (Fig. 4's cylinder family) lying on its side, its axis along O's x.

    In its nominal pose (R_TO = I) the axis lies along the table's x, so a cylindrical grasp from
    above closes its fingers along y, as for the cubes (the paper's Sec. 3, Fig. 4; docs/design.md §2);
    pose errors along x then run along the axis and errors along y across it.

    The length is **fixed** (``CYLINDER_FAMILY_LENGTH`` = 0.30 m) while the diameter grows:
    Fig. 4's size axis is what the fingers wrap around, the cross-section; a fixed length longer
    than the hand is wide keeps the fingers on the curved side (never the end caps) for every
    diameter and every pose error along the axis, so only the diameter changes between sizes. A
    proportional length would make small cylinders short stubs the fingers close past and large
    ones logs longer than the table.

    Args:
        diameter: Diameter (m).
        length: Length (m); default CYLINDER_FAMILY_LENGTH.
        mass: Mass (kg); default density × volume.
        density: Density (kg/m³) used when `mass` is None; default DEFAULT_DENSITY (assumed).
        rgba: Visual colour.
    """
    length = CYLINDER_FAMILY_LENGTH if length is None else length
    _check_size("cylinder", diameter=diameter, length=length)
    return _make_spec(
        f"cylinder_{_mm(diameter)}x{_mm(length)}",
        [ShapePiece("cylinder", (diameter / 2.0, length), rpy_OP=_LYING_ALONG_X)],
        mass, density=density, closest_primitive="cylinder", rgba=rgba,
    )

