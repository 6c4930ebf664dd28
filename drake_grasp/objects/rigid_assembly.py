"""A model file's links as one rigid object: links joined by fixed joints, and the links of an
articulated object held where the file draws them.

Object files as projects ship them are not always one link. A ROS or CAD export hangs the object's
link under an empty ``base_link`` by a fixed joint; SAPIEN's PartNet-Mobility objects (the articulated
objects of ManiSkill and Genesis) put an empty ``base`` link above a body link, and a bottle's cap or a
box's lid on a revolute, continuous or prismatic joint; a mug can be a body and a handle welded
together. Drake parses each link as a body of its own, joined by its joints.

drake-grasp grasps one rigid object. So the links of one model become one rigid body:

- links joined by fixed joints are one body, as every simulator treats them;
- a moving joint (revolute, continuous, prismatic, ...) is held at its default position (Drake's
  default context: zero, where the meshes sit as the file draws them; PartNet-Mobility's lids closed),
  and an :class:`ArticulationNote` names the joints held, since a real lid would move in the hand;
- a joint to the world (a model fixed in its scene) is left out, and the object loaded free, as a
  static model is (a note);
- an empty link joined to nothing (a leftover frame: no geometry, no mass) is not a part.

The assembly's inertia is the sum of its links' inertials, each moved into the root link's frame
(the root: the link no joint of the model is a child of). Pure bookkeeping on Drake's parsed plant:
geometry poses from SceneGraph's inspector, link poses from the plant's default context.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from pydrake.math import RigidTransform

from drake_grasp.objects.mass_properties import combined_mass_properties
from drake_grasp.objects.spec import ArticulationNote, ObjectError, StaticModelNote


@dataclass(frozen=True)
class RigidAssembly:
    """One model's links as one rigid body, posed in the root link's frame R (the frame of the link
    no joint of the model is a child of: the object's body frame).

    Attributes:
        links: (link, X_RL) for every link of the model, the root first, its X_RL the identity.
    """

    links: tuple

    def collision_geometries(self, plant, inspector) -> list:
        """(shape, X_RG) of every collision geometry of every link, posed in the root's frame."""
        return [(inspector.GetShape(g), X_RL @ inspector.GetPoseInFrame(g))
                for link, X_RL in self.links for g in plant.GetCollisionGeometriesForBody(link)]

    def mass_properties(self) -> tuple[float, np.ndarray, np.ndarray]:
        """(mass kg, centre of mass in R m, inertia about it in R kg·m²) of the links' inertials
        together (`mass_properties.combined_mass_properties`); mass 0 (and a zero inertia) when no
        link carries one."""
        parts = []
        for link, X_RL in self.links:
            m = float(link.default_mass())
            if not (m > 0.0 and np.isfinite(m)):
                continue
            R = X_RL.rotation().matrix()
            p_LScm = np.asarray(link.default_com(), float)
            shift = np.dot(p_LScm, p_LScm) * np.eye(3) - np.outer(p_LScm, p_LScm)
            parts.append((m, X_RL @ p_LScm, R @ (m * (link.default_unit_inertia().CopyToFullMatrix3() - shift)) @ R.T))
        return combined_mass_properties(parts) if parts else (0.0, np.zeros(3), np.zeros((3, 3)))


def articulation_message(label: str, held) -> str:
    """The ArticulationNote's text for the moving joints `held` ("revolute joint 'lid'", ...)."""
    shown = ", ".join(held[:4]) + (f" and {len(held) - 4} more" if len(held) > 4 else "")
    return f"{label}: the object is articulated; its {shown} held where the file puts {'it' if len(held) == 1 else 'them'} (one rigid body)"


def rigid_assembly(plant, model, label: str, declared: dict[str, str] | None = None) -> RigidAssembly:
    """The links of `model` in the (not yet finalized) `plant` as one rigid body. `declared`: each
    joint's kind as the file names it ({name: "continuous"}), for the notes (Drake parses URDF's
    continuous joint as a revolute one).

    Finalizes the plant (the link poses come from its default context). Warns an ArticulationNote
    for moving joints held, a StaticModelNote for a joint to the world left out.

    Raises:
        ObjectError: One line: the model has no link, or links joined to nothing (two objects).
    """
    links = [plant.get_body(index) for index in plant.GetBodyIndices(model)]
    if not links:
        raise ObjectError(f"{label}: the model has no link")
    world = plant.world_body().index()
    joints = [plant.get_joint(index) for index in plant.GetJointIndices(model)]
    to_world = [j for j in joints if world in (j.parent_body().index(), j.child_body().index())]
    among = [j for j in joints if j not in to_world]
    children = {j.child_body().index() for j in among}
    parents = {j.parent_body().index() for j in among}

    def stray(link) -> bool:  # an empty link joined to nothing (a leftover frame): not a part
        return (link.index() not in parents and not plant.GetCollisionGeometriesForBody(link)
                and not link.default_mass() > 0.0)

    roots = [link for link in links if link.index() not in children and not (len(links) > 1 and stray(link))]
    kept = {link.index() for link in roots} | children
    links = [link for link in links if link.index() in kept]
    if len(roots) != 1:
        names = ", ".join(repr(link.name()) for link in roots)
        raise ObjectError(f"{label}: {len(roots)} links joined to nothing ({names}): one object is expected; "
                          "join them by fixed joints, or give one link's file")
    declared = declared or {}
    # A URDF floating joint reaches the plant as a weld (`readable_models.drake_readable_model`): held
    # like a moving joint between links; to the world, it means what a free body is, so no note.
    moving = [j for j in among if j.type_name() != "weld" or declared.get(j.name()) == "floating"]
    to_world = [j for j in to_world if declared.get(j.name()) != "floating"]
    held = tuple(f"{_joint_kind(j, declared)} joint {j.name()!r}" for j in moving)
    if to_world:
        warnings.warn(f"{label}: the model is fixed to the world in its file ({_joint_kind(to_world[0], declared)} joint "
                      f"{to_world[0].name()!r}); loaded as a free body", StaticModelNote, stacklevel=3)
    if held:
        warnings.warn(articulation_message(label, held), ArticulationNote, stacklevel=3)
    (root,) = roots
    if len(links) == 1:
        return RigidAssembly(((root, RigidTransform()),))
    try:
        plant.Finalize()
        context = plant.CreateDefaultContext()
    except Exception as error:  # Drake raises RuntimeError with multi-line messages.
        raise ObjectError(f"{label}: cannot assemble its links ({' '.join(str(error).split())})") from None
    ordered = [root] + [link for link in links if link.index() != root.index()]
    return RigidAssembly(tuple((link, plant.CalcRelativeTransform(context, root.body_frame(), link.body_frame()))
                               for link in ordered))


def _joint_kind(joint, declared: dict[str, str]) -> str:
    """A joint's kind as the model file names it: as `declared`, else Drake's name ("weld" is URDF's
    and SDFormat's "fixed")."""
    kind = declared.get(joint.name()) or joint.type_name()
    return "fixed" if kind == "weld" else kind
