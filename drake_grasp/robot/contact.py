"""Contact parameters of the scene and the SDFormat snippets that declare them.

One concept: how a collision geometry of the scene touches another one. The objects are
*compliant hydroelastic* (a soft pressure field of modulus `hydroelastic_modulus`); the table is
*rigid hydroelastic*. Pairs that hydroelastics cannot handle (e.g. two rigid geometries, or a
geometry without hydroelastic properties) fall back to point contact when the plant's contact model
is ``hydroelastic_with_fallback``.

The parameters are a plain dataclass of floats so that a scenario YAML sets them
(``pydrake.common.yaml.yaml_load_typed(schema=ContactParameters, data=...)``).

Drake references (SDFormat extensions, see Drake's "SDFormat support" page and
``multibody/parsing/detail_sdf_geometry.cc``): ``<drake:proximity_properties>`` with
``<drake:compliant_hydroelastic/>`` or ``<drake:rigid_hydroelastic/>``,
``<drake:hydroelastic_modulus>`` (Pa), ``<drake:mesh_resolution_hint>`` (m, needed by compliant
spheres, ellipsoids, cylinders and capsules; boxes and convex meshes ignore it),
``<drake:hunt_crossley_dissipation>`` (s/m, used by the TAMSI, "similar" and "lagged" discrete
approximations; "sap" uses a relaxation time instead), ``<drake:mu_dynamic>`` and
``<drake:mu_static>``.
"""



import dataclasses


@dataclasses.dataclass
class ContactParameters:
    """Contact material of the objects (and, for friction, of the table).

    Attributes:
        friction: Coulomb friction coefficient μ, used for both static and dynamic friction
            (dimensionless). Hand–object and table–object μ = 0.5 (assumed; docs/design.md §4.4). Drake
            combines the coefficients of two geometries as 2·μ1·μ2/(μ1 + μ2), so equal values
            on both sides give that value.
        hydroelastic_modulus: Hydroelastic modulus of the compliant objects (Pa). 1e6 Pa is soft
            enough for contact patches of a few mm on our light objects and was measured (docs/design.md
            §5.1) to hold grasps at 5–10 ms time steps.
        hunt_crossley_dissipation: Hunt–Crossley dissipation (s/m) of every geometry; damps the
            normal motion of the compliant contact so that objects come to rest. Measured
            (tests/test_objects.py, "lagged" approximation, 10 ms step, objects dropped a few mm
            onto a rigid table): at 5 s/m the 12 g sponge rocks on the table indefinitely, at
            10 s/m a 2 cm cube does, at 20 s/m the sponge still shifts 0.1 mm; at 50 s/m every
            catalogue object rests with no measurable creep at 5 and 10 ms.
        mesh_resolution_fraction: Resolution hint of a compliant geometry's tetrahedral mesh as a
            fraction of the geometry's characteristic (smallest) size (dimensionless).
        mesh_resolution_min: Floor of the resolution hint (m): finer meshes cost contact time
            (the banana's capsules at a 3.6 mm hint made its settling 4× slower).
        mesh_resolution_max: Ceiling of the resolution hint (m): the sag of a tessellated sphere
            or cylinder of radius r is about hint²/(8r), 0.1 mm for the soccer ball at 1 cm.
    """

    friction: float = 0.5
    hydroelastic_modulus: float = 1.0e6
    hunt_crossley_dissipation: float = 50.0
    mesh_resolution_fraction: float = 0.25
    mesh_resolution_min: float = 0.005
    mesh_resolution_max: float = 0.01

    def resolution_hint(self, characteristic_size: float) -> float:
        """The mesh resolution hint (m) for a geometry of the given characteristic size (m)."""
        hint = self.mesh_resolution_fraction * characteristic_size
        return float(min(max(hint, self.mesh_resolution_min), self.mesh_resolution_max))


def _friction_sdf(friction: float) -> str:
    return (
        f"<drake:mu_dynamic>{friction:.6g}</drake:mu_dynamic>"
        f"<drake:mu_static>{friction:.6g}</drake:mu_static>"
    )


def compliant_proximity_sdf(
    contact: ContactParameters, characteristic_size: float, friction: float | None = None
) -> str:
    """The ``<drake:proximity_properties>`` element of a compliant-hydroelastic collision geometry.

    Args:
        contact: The contact parameters.
        characteristic_size: The geometry's smallest dimension (m), e.g. a capsule's diameter; it
            sets the mesh resolution hint.
        friction: Overrides ``contact.friction`` (dimensionless) when given.

    Returns:
        One line of SDFormat XML (the ``drake`` namespace must be declared on the ``<sdf>`` root).
    """
    mu = contact.friction if friction is None else friction
    return (
        "<drake:proximity_properties>"
        "<drake:compliant_hydroelastic/>"
        f"<drake:hydroelastic_modulus>{contact.hydroelastic_modulus:.6g}"
        "</drake:hydroelastic_modulus>"
        f"<drake:mesh_resolution_hint>{contact.resolution_hint(characteristic_size):.6g}"
        "</drake:mesh_resolution_hint>"
        f"<drake:hunt_crossley_dissipation>{contact.hunt_crossley_dissipation:.6g}"
        "</drake:hunt_crossley_dissipation>"
        f"{_friction_sdf(mu)}"
        "</drake:proximity_properties>"
    )


def rigid_proximity_sdf(
    contact: ContactParameters,
    characteristic_size: float | None = None,
    friction: float | None = None,
) -> str:
    """The ``<drake:proximity_properties>`` element of a rigid-hydroelastic geometry (the table).

    Args:
        contact: The contact parameters (friction and dissipation are used).
        characteristic_size: Smallest dimension (m) of a round rigid geometry, which needs a
            resolution hint; leave None for a box or a half space.
        friction: Overrides ``contact.friction`` (dimensionless) when given.

    Returns:
        One line of SDFormat XML (the ``drake`` namespace must be declared on the ``<sdf>`` root).
    """
    mu = contact.friction if friction is None else friction
    hint = ""
    if characteristic_size is not None:
        hint = (
            f"<drake:mesh_resolution_hint>{contact.resolution_hint(characteristic_size):.6g}"
            "</drake:mesh_resolution_hint>"
        )
    return (
        "<drake:proximity_properties>"
        "<drake:rigid_hydroelastic/>"
        f"{hint}"
        f"<drake:hunt_crossley_dissipation>{contact.hunt_crossley_dissipation:.6g}"
        "</drake:hunt_crossley_dissipation>"
        f"{_friction_sdf(mu)}"
        "</drake:proximity_properties>"
    )
