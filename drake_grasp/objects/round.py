"""A generator of low round objects as users bring them: fruit and balls, as meshes or URDFs with real masses.

Why: apples, oranges, lemons, peaches, tennis balls and toy balls are among the commonest things a
user puts on a table, and the paper's spherical grasp, with the BH8-280's rounded fingertips, misses
those lower than the fingers' sweep (docs/design.md §4.1a, §5.4i). The flower generator's balls and
fruit (`objects.flower`) are small (under about 7 cm); these span 4-11 cm, so that the decision between
the spherical, box and flower grasps is measured where it is close (`scripts/holding_study.py --objects
round`).

One class, ``round``: an ellipsoid 4-11 cm across, its other horizontal axis 0.8-1 and its height
0.75-1 times that, three in ten stretched 1.15-1.4 times along one side (a lemon, a kiwi), its surface
made lumpy by up to 6 % of its radius (an apple's dimples, a pepper's lobes). Every second object
(odd ``index``) is written as a URDF naming its OBJ, with a real inertial block: the mesh's own inertia
at a density of 300-900 kg/m³ (a foam ball to an apple); the others are bare meshes, which the loader
gives its default density. Object ``i`` of seed ``s`` is drawn from ``numpy.random.default_rng([s,
i])``: the same (seed, index) gives byte-identical files whatever the count.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

from drake_grasp.objects.generated import (inertial_element, one_link_urdf, placed_on_table, write_generated,
                                          write_manifest)

CLASSES = ("round",)
SIZE_RANGE = (0.04, 0.11)  # m: the largest horizontal diameter before stretching
DENSITY_RANGE = (300.0, 900.0)  # kg/m³ of the URDFs' real masses


def round_object(seed: int, index: int) -> tuple[str, trimesh.Trimesh, float | None]:
    """(name, mesh resting on z = 0 and centred in x and y, mass in kg or None for a bare mesh) of
    object `index` of seed `seed`."""
    rng = np.random.default_rng([seed, index])
    diameter = rng.uniform(*SIZE_RANGE)
    axes = diameter / 2.0 * np.array([1.0, rng.uniform(0.8, 1.0), rng.uniform(0.75, 1.0)])
    if rng.random() < 0.3:
        axes[0] *= rng.uniform(1.15, 1.4)
    sphere = trimesh.creation.icosphere(subdivisions=3)
    lump = rng.uniform(0.0, 0.06)
    waves = rng.normal(size=(3, 3))
    unit = sphere.vertices
    vertices = unit * (1.0 + lump * np.sin(unit @ waves).sum(axis=1, keepdims=True) / 3.0) * axes
    mesh = trimesh.Trimesh(vertices, sphere.faces, process=True)
    placed_on_table(mesh, rng)
    density = rng.uniform(*DENSITY_RANGE)
    mass = float(mesh.volume * density) if index % 2 == 1 else None
    return f"round_{seed}_{index:03d}", mesh, mass


def urdf_text(name: str, mesh_file: str, mesh: trimesh.Trimesh, mass: float) -> str:
    """A one-link URDF naming `mesh_file`, with `mass` (kg) and the mesh's inertia at that mass about
    its centre of mass."""
    return one_link_urdf(name, mesh_file,
                         inertial_element(mass, mesh.center_mass, mesh.moment_inertia * (mass / mesh.volume)))


def generate(count: int, seed: int, out_dir: str | Path) -> list[dict]:
    """Objects 0..count-1 of `seed` written into `out_dir` (`generated.write_generated`: a URDF beside
    its mesh) with their manifest; returns its rows, each with the URDF's mass ("mass_kg", None for a
    bare mesh)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    rows = []
    for index in range(count):
        name, mesh, mass = round_object(seed, index)
        urdf = None if mass is None else urdf_text(name, f"{name}.obj", mesh, mass)
        rows.append(write_generated(out_dir, name, mesh, "round", seed, index, urdf,
                                    mass_kg=None if mass is None else round(mass, 6)))
    write_manifest(out_dir, rows, ["file", "class", "format", "seed", "index", "size_m", "extents_m", "volume_m3",
                                   "mass_kg"])
    return rows
