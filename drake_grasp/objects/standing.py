"""A generator of slender objects standing on their end: pegs, pencils, markers, vials and sticks.

Why: a peg in a peg board, a marker or a pencil stood on its end, a test tube or a spice vial, a
glue stick: objects users put on a table upright, several times as tall as they are wide and
narrower than the cylindrical grasp closes on (Gazebo's `wooden_peg`, 1.95 × 8 cm, was missed by
it at both seeds: docs/results/holding/real_files.md). None of the other generators stands anything
that thin on its end (`objects.everyday`'s bottles are 5-9 cm across; `objects.flower`'s standing
dominoes are 5 cm tall at most; `objects.tools` lays its markers down). This generator draws them from a
seed, so that the plain command can be measured on them without tuning on any one file
(`scripts/holding_study.py --objects standing`; docs/design.md §5.4o).

The five classes (``CLASSES``), each a closed 2-manifold in metres standing on its flat end, built
with Manifold's booleans:

* ``peg``: a round rod 1.0-3.4 cm across, 6-16 cm tall, its top edge chamfered 0-2 mm;
* ``pencil``: a hexagonal rod 0.8-1.4 cm across its flats, 10-19 cm tall, a cone 1.5-3 cm long on
  top (sharpened, standing on its end);
* ``marker``: a round or hexagonal barrel 1.2-2.4 cm across and 10-15 cm tall, standing on its
  cap, 0.5-3 mm wider over its lower 3-6 cm, a blunt stub on top;
* ``vial``: a tube 1.4-3.2 cm across and 6-15 cm tall with a screw cap 0-3 mm wider and 1-2.5 cm tall;
* ``stick``: a square or oblong bar 1.0-3.0 by 1.0-3.0 cm, 6-18 cm tall (a glue stick, a block of
  wood on end).

Each stands where the table is z = 0, centred in x and y, turned about the vertical by an angle from the
seed. Every second object of a class (odd ``index // len(CLASSES)``) is written as a URDF naming its
OBJ, with the inertial block of a uniform density (wood or plastic, 300-1300 kg/m³: a hollow tube or
marker averaged over its solid); the others are bare meshes, which the loader gives its default
density. Object ``i`` of seed ``s`` is drawn from ``numpy.random.default_rng([s, i])``: the same
(seed, index) gives byte-identical files whatever the count.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.generated import (CIRCULAR_SEGMENTS, inertial_element, manifold, one_link_urdf,
                                          placed_on_table, to_trimesh, write_generated, write_manifest)

CLASSES = ("peg", "pencil", "marker", "vial", "stick")
FORMATS = ("mesh", "urdf")
DENSITY = (300.0, 1300.0)  # kg/m³: a hollow plastic shell averaged over its solid, to solid wood or plastic


def _rod(height: float, radius: float, segments: int, top_radius: float | None = None):
    """A Manifold prism (a cylinder when `segments` is many) standing on z = 0, `height` tall (m)."""
    return manifold().Manifold.cylinder(height, radius, radius if top_radius is None else top_radius,
                                        circular_segments=segments)


def _peg(rng: np.random.Generator):
    radius, height = rng.uniform(0.005, 0.017), rng.uniform(0.06, 0.16)
    chamfer = rng.uniform(0.0, 0.002)
    body = _rod(height - chamfer, radius, CIRCULAR_SEGMENTS)
    if chamfer > 2e-4:
        body = body + _rod(chamfer, radius, CIRCULAR_SEGMENTS, radius - chamfer).translate((0.0, 0.0, height - chamfer))
    return body


def _pencil(rng: np.random.Generator):
    flats, height, cone = rng.uniform(0.008, 0.014), rng.uniform(0.10, 0.19), rng.uniform(0.015, 0.03)
    radius = flats / math.sqrt(3.0)  # a hexagon's corner radius from its width across flats
    body = _rod(height - cone, radius, 6)
    return body + _rod(cone, radius, 6, radius * 0.12).translate((0.0, 0.0, height - cone))


def _marker(rng: np.random.Generator):
    segments = CIRCULAR_SEGMENTS if rng.random() < 0.7 else 6
    radius, height = rng.uniform(0.006, 0.012), rng.uniform(0.10, 0.15)
    cap_radius, cap_height = radius + rng.uniform(0.0005, 0.003), rng.uniform(0.03, 0.06)
    stub = rng.uniform(0.005, 0.012)
    body = _rod(height - stub, radius, segments) + _rod(cap_height, cap_radius, CIRCULAR_SEGMENTS)
    return body + _rod(stub, radius, CIRCULAR_SEGMENTS, radius * 0.6).translate((0.0, 0.0, height - stub))


def _vial(rng: np.random.Generator):
    radius, height = rng.uniform(0.007, 0.016), rng.uniform(0.06, 0.15)
    cap_radius, cap_height = radius + rng.uniform(0.0, 0.003), rng.uniform(0.01, 0.025)
    body = _rod(height - cap_height, radius, CIRCULAR_SEGMENTS)
    return body + _rod(cap_height, cap_radius, CIRCULAR_SEGMENTS).translate((0.0, 0.0, height - cap_height))


def _stick(rng: np.random.Generator):
    width, depth, height = rng.uniform(0.01, 0.03), rng.uniform(0.01, 0.03), rng.uniform(0.06, 0.18)
    return manifold().Manifold.cube((width, depth, height)).translate((-width / 2.0, -depth / 2.0, 0.0))


_GENERATORS = {"peg": _peg, "pencil": _pencil, "marker": _marker, "vial": _vial, "stick": _stick}


def standing_object(seed: int, index: int) -> tuple[str, str, trimesh.Trimesh, float]:
    """(name, class, mesh standing on z = 0, centred in x and y and turned about z, density kg/m³) of
    object `index` of generator seed `seed` (module docstring)."""
    rng = np.random.default_rng([seed, index])
    shape_class = CLASSES[index % len(CLASSES)]
    mesh = placed_on_table(to_trimesh(_GENERATORS[shape_class](rng)), rng)
    return f"{shape_class}_{seed}_{index:03d}", shape_class, mesh, float(rng.uniform(*DENSITY))


def format_of(index: int) -> str:
    """"mesh" or "urdf": every second object of a class is a URDF (module docstring)."""
    return FORMATS[(index // len(CLASSES)) % len(FORMATS)]


def generate(count: int, seed: int, out_dir: str | Path) -> list[dict]:
    """Writes objects 0..count-1 of generator seed `seed` into `out_dir` (an OBJ each, and a URDF naming
    its mesh for every second one of a class) with their manifest; returns its rows, each with the
    URDF's mass ("mass_kg", None for a bare mesh)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for index in range(count):
        name, shape_class, mesh, density = standing_object(seed, index)
        urdf, mass = None, None
        if format_of(index) == "urdf":
            mass = float(mesh.volume) * density
            inertia = np.asarray(mesh.moment_inertia, float) * density / float(mesh.density)
            urdf = one_link_urdf(name, f"{name}.obj", inertial_element(mass, mesh.center_mass, inertia))
        rows.append(write_generated(out_dir, name, mesh, shape_class, seed, index, urdf,
                                    mass_kg=None if mass is None else round(mass, 6)))
    write_manifest(out_dir, rows, ["file", "class", "format", "seed", "index", "size_m", "extents_m", "volume_m3",
                                   "mass_kg"])
    return rows
