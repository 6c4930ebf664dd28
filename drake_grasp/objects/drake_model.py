"""An object as Drake sees it: the SDFormat model of an `objects.ObjectSpec`, added to a plant, and
the table slab that kinematic queries rest it on.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.parsing import Parser

from drake_grasp.robot.contact import ContactParameters, compliant_proximity_sdf
from drake_grasp.objects.mass_properties import _pose
from drake_grasp.objects.spec import ObjectSpec, ShapePiece


# --- Drake model ----------------------------------------------------------------------------------


def _f(value: float) -> str:
    return f"{value + 0.0:.9g}"  # + 0.0 turns -0.0 into 0.0.


def _geometry_sdf(piece: ShapePiece) -> str:
    s = piece.size
    if piece.kind == "sphere":
        return f"<sphere><radius>{_f(s[0])}</radius></sphere>"
    if piece.kind == "ellipsoid":
        return f"<ellipsoid><radii>{_f(s[0])} {_f(s[1])} {_f(s[2])}</radii></ellipsoid>"
    if piece.kind == "box":
        return f"<box><size>{_f(s[0])} {_f(s[1])} {_f(s[2])}</size></box>"
    if piece.kind == "cylinder":
        return f"<cylinder><radius>{_f(s[0])}</radius><length>{_f(s[1])}</length></cylinder>"
    if piece.kind == "capsule":
        return f"<capsule><radius>{_f(s[0])}</radius><length>{_f(s[1])}</length></capsule>"
    # Drake resolves only file:// URIs (not plain paths) in SDFormat parsed from a string.
    return f"<mesh><uri>{Path(piece.mesh_path).as_uri()}</uri><drake:declare_convex/></mesh>"


def _facet_down(piece: ShapePiece, R_TO: RotationMatrix, resolution_hint: float) -> ShapePiece:
    """Spins a cylinder lying on its side about its own axis so that its contact mesh rests on a
    facet, not on an edge.

    Drake's compliant cylinder is a prism of n = ceil(2πr / resolution_hint) rim vertices at angles
    2πk/n about the cylinder's z from its x axis (geometry/proximity/make_cylinder_mesh.cc,
    MakeCylinderVolumeMeshWithMa). Resting on an edge, it rolls half a facet (5.8° for our bottle
    case at n = 31) before it settles; the spin puts a facet's middle straight down instead. The
    ideal cylinder is symmetric about its axis, so the spin changes only the tessellation.
    """
    R_OP, p_OP = _pose(piece)
    down_P = R_OP.T @ R_TO.matrix().T @ np.array([0.0, 0.0, -1.0])
    if abs(down_P[2]) > 1e-9:
        return piece  # Not lying on its side.
    n = math.ceil(2.0 * math.pi * piece.size[0] / resolution_hint)
    facet = 2.0 * math.pi / n
    spin = math.atan2(down_P[1], down_P[0]) - facet / 2.0
    R_OP_spun = RotationMatrix(R_OP) @ RotationMatrix.MakeZRotation(spin)
    rpy_OP = tuple(float(v) for v in RollPitchYaw(R_OP_spun).vector())
    return dataclasses.replace(piece, rpy_OP=rpy_OP)


def object_sdf(spec: ObjectSpec, contact: ContactParameters | None = None) -> str:
    """SDFormat 1.9 text of the object: one model and one body, both named ``spec.name``.

    The body frame is O; the inertial is at O (the centre of mass). Each piece is one collision
    geometry (compliant hydroelastic, `contact`'s parameters; friction ``spec.friction`` if set) and
    one visual of colour ``spec.rgba``. Mesh pieces are referenced by absolute ``file://`` URI.

    Args:
        spec: The object.
        contact: Contact parameters; default ``ContactParameters()``.
    """
    contact = ContactParameters() if contact is None else contact
    ixx, iyy, izz, ixy, ixz, iyz = spec.inertia
    rgba = " ".join(_f(v) for v in spec.rgba)
    elements = []
    for index, piece in enumerate(spec.pieces):
        if piece.kind == "cylinder":
            hint = contact.resolution_hint(piece.characteristic_size())
            piece = _facet_down(piece, spec.R_TO, hint)
        pose = " ".join(_f(v) for v in (*piece.p_OP, *piece.rpy_OP))
        geometry = _geometry_sdf(piece)
        proximity = compliant_proximity_sdf(contact, piece.characteristic_size(), spec.friction)
        elements.append(
            f'      <collision name="collision_{index}">\n'
            f"        <pose>{pose}</pose>\n"
            f"        <geometry>{geometry}</geometry>\n"
            f"        {proximity}\n"
            f"      </collision>\n"
            f'      <visual name="visual_{index}">\n'
            f"        <pose>{pose}</pose>\n"
            f"        <geometry>{geometry}</geometry>\n"
            f"        <material><diffuse>{rgba}</diffuse></material>\n"
            f"      </visual>\n"
        )
    return (
        '<?xml version="1.0"?>\n'
        '<sdf version="1.9" xmlns:drake="http://drake.mit.edu">\n'
        f'  <model name="{spec.name}">\n'
        f'    <link name="{spec.name}">\n'
        "      <inertial>\n"
        "        <pose>0 0 0 0 0 0</pose>\n"
        f"        <mass>{_f(spec.mass)}</mass>\n"
        f"        <inertia><ixx>{_f(ixx)}</ixx><iyy>{_f(iyy)}</iyy><izz>{_f(izz)}</izz>"
        f"<ixy>{_f(ixy)}</ixy><ixz>{_f(ixz)}</ixz><iyz>{_f(iyz)}</iyz></inertia>\n"
        "      </inertial>\n"
        + "".join(elements)
        + "    </link>\n"
        "  </model>\n"
        "</sdf>\n"
    )


def with_mass_scale(spec: ObjectSpec, scale: float | None) -> ObjectSpec:
    """The object with its mass and its rotational inertia about the centre of mass scaled by `scale`
    (a denser or lighter body of the same shape): geometry, frame O (at the centre of mass), friction
    and everything else unchanged. `scale` None or 1 returns `spec` itself.

    Raises:
        ValueError: `scale` not a finite number > 0.
    """
    if scale is None or scale == 1.0:
        return spec
    if not (math.isfinite(scale) and scale > 0):
        raise ValueError(f"mass scale must be a finite number > 0, got {scale}")
    return dataclasses.replace(spec, mass=spec.mass * scale, inertia=tuple(float(v) * scale for v in spec.inertia))


def AddObject(plant, spec: ObjectSpec, contact: ContactParameters | None = None):
    """Adds the object to a MultibodyPlant (before Finalize) as a free body.

    Parsing is strict: a parser warning about our own model is an error.

    Args:
        plant: The MultibodyPlant (registered with a SceneGraph).
        spec: The object.
        contact: Contact parameters; default ``ContactParameters()``.

    Returns:
        The ModelInstanceIndex of the model named ``spec.name``; its body is
        ``plant.GetBodyByName(spec.name, model)``, whose frame is O.
    """
    parser = Parser(plant)
    parser.SetStrictParsing()
    (model,) = parser.AddModelsFromString(object_sdf(spec, contact), "sdf")
    return model


SUPPORT_TABLE_SIZE = (2.0, 2.0, 0.1)  # m: a slab large enough to be the table under any object


def RegisterSupportTable(plant, spec: ObjectSpec, friction: float = 0.5):
    """Registers (before Finalize) the table the object rests on, in a plant whose world frame is
    the object frame O: an anchored slab whose top is the table plane of the object's nominal
    resting pose (z_T = 0 at -rest_height below O, tilted by R_TO). Returns its geometry id.

    For kinematic queries (planning, quasi-static closing) that must respect the table.
    """
    from pydrake.geometry import Box, ProximityProperties, AddContactMaterial
    from pydrake.multibody.plant import CoulombFriction

    R_OT = spec.R_TO.inverse()
    p_OT = R_OT @ np.array([0.0, 0.0, -spec.rest_height])
    X_OT = RigidTransform(R_OT, p_OT)
    X_TS = RigidTransform([0.0, 0.0, -SUPPORT_TABLE_SIZE[2] / 2])
    properties = ProximityProperties()
    AddContactMaterial(friction=CoulombFriction(friction, friction), properties=properties)
    return plant.RegisterCollisionGeometry(plant.world_body(), X_OT @ X_TS, Box(*SUPPORT_TABLE_SIZE),
                                           "support_table", properties)
