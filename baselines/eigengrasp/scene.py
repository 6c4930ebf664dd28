"""The hand and the object in one SceneGraph, for the planner's collision test and distances.

The Drake side of the planner's inner loop. One Diagram per object, built once: the BarrettHand
(models/barrett_hand) as a free body and the object welded at the world origin, so the object frame
O is the world frame. Per annealing step the planner:

1. sets the hand base pose X_OH and the 8 joint angles with one ``MultibodyPlant.SetPositions``;
2. asks SceneGraph whether any hand link penetrates the object (``QueryObject.HasCollisions``, one
   call; collisions inside the hand are filtered, as in the dynamic model);
3. gets the distance from each virtual contact to the object: in numpy for analytic pieces and
   convex mesh pieces (object_distance.py); for ellipsoids by Drake's exact pair query between the
   piece and a zero-radius sphere registered at the contact on its link.

The zero-radius spheres are only added when the object has ellipsoids; they also take part in
``HasCollisions``, which changes nothing: a contact sits on its link's surface, so it penetrates
the object only when its link does.
"""

from __future__ import annotations

import numpy as np
from pydrake.geometry import (Box, Capsule, CollisionFilterDeclaration, Cylinder, GeometrySet,
                              ProximityProperties, SceneGraph, Sphere)
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.systems.framework import DiagramBuilder

from baselines.eigengrasp.object_distance import ConvexPiecesDistance, PrimitiveDistance
from baselines.eigengrasp.virtual_contacts import VIRTUAL_CONTACTS
from drake_grasp.robot import hand
from drake_grasp.robot.contact import ContactParameters
from drake_grasp.robot.modelgen import HAND_SDF
from drake_grasp.objects import AddObject, ObjectSpec, RegisterSupportTable
from drake_grasp.paths import RegisterPackage

HAND_LINKS = ("bh_base",) + tuple(f"bh_finger_{f}_{p}" for f in hand.FINGERS for p in ("knuckle", "proximal", "distal"))
_ANALYTIC_SHAPES = (Sphere, Box, Cylinder, Capsule)


class HandObjectScene:
    """A free BarrettHand and a fixed object, with fast pose setting and queries."""

    def __init__(self, spec: ObjectSpec, contact: ContactParameters | None = None, table: bool = False):
        """
        Args:
            spec: The object; its frame O becomes the world frame.
            contact: Contact parameters of the object model (they do not affect the queries).
            table: Add the table under the object's nominal resting pose: a hand touching it is in
                collision too (the virtual contacts' distances stay distances to the object).
        """
        self.spec = spec
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
        (hand_instance,) = RegisterPackage(Parser(plant)).AddModels(str(HAND_SDF))
        object_instance = AddObject(plant, spec, contact or ContactParameters())
        object_body = plant.get_body(plant.GetBodyIndices(object_instance)[0])
        plant.WeldFrames(plant.world_frame(), object_body.body_frame())
        if table:
            RegisterSupportTable(plant, spec)
        inspector = scene_graph.model_inspector()
        object_geometries = plant.GetCollisionGeometriesForBody(object_body)
        # objects.object_sdf names piece i's collision "collision_{i}".
        piece_of = {g: spec.pieces[int(inspector.GetName(g).rsplit("_", 1)[1])] for g in object_geometries}
        numeric = [g for g in object_geometries if isinstance(inspector.GetShape(g), _ANALYTIC_SHAPES)
                   or piece_of[g].kind == "convex"]
        convex = [piece_of[g] for g in object_geometries if piece_of[g].kind == "convex"]
        self._convex_distance = ConvexPiecesDistance(convex) if convex else None
        # The rest (ellipsoids): Drake's pair queries.
        self._drake_pieces = [g for g in object_geometries if g not in numeric]
        self._contact_geometries = []
        if self._drake_pieces:
            for i, c in enumerate(VIRTUAL_CONTACTS):
                body = plant.GetBodyByName(c.link, hand_instance)
                self._contact_geometries.append(plant.RegisterCollisionGeometry(
                    body, RigidTransform(np.array(c.point)), Sphere(0.0), f"virtual_contact_{i}",
                    ProximityProperties()))
        plant.Finalize()
        hand_geometries = GeometrySet()
        for name in HAND_LINKS:
            for g in plant.GetCollisionGeometriesForBody(plant.GetBodyByName(name, hand_instance)):
                hand_geometries.Add(g)
        scene_graph.collision_filter_manager().Apply(CollisionFilterDeclaration().ExcludeWithin(hand_geometries))

        self._plant = plant
        self._scene_graph: SceneGraph = scene_graph
        self._diagram = builder.Build()
        self._context = self._diagram.CreateDefaultContext()
        self._plant_context = plant.GetMyMutableContextFromRoot(self._context)
        self._sg_context = scene_graph.GetMyContextFromRoot(self._context)
        self._query_port = scene_graph.get_query_output_port()
        base = plant.GetBodyByName(hand.HAND_JOINTS.base_frame, hand_instance)
        start = base.floating_positions_start()
        self._quaternion_slice = slice(start, start + 4)
        self._position_slice = slice(start + 4, start + 7)
        self._joint_indices = np.array([plant.GetJointByName(n, hand_instance).position_start()
                                        for n in hand.HAND_JOINTS.all])
        self._q = plant.GetPositions(self._plant_context).copy()
        self._primitive_distance = PrimitiveDistance(spec.pieces)
        self._convex_only = self._convex_distance is not None and not self._primitive_distance.num_pieces

    @property
    def uses_drake_distances(self) -> bool:
        """Whether some object piece needs Drake's pair queries for the contact distances."""
        return bool(self._drake_pieces)

    def set_configuration(self, quaternion_wxyz, p_OH, joint_angles) -> None:
        """Puts the hand base at X_OH = (quaternion, p_OH) with the given joint angles.

        Args:
            quaternion_wxyz: Unit quaternion (w, x, y, z) of R_OH.
            p_OH: Position of the hand base in O, m.
            joint_angles: (8,) controller-order joint angles, rad.
        """
        q = self._q
        q[self._quaternion_slice] = quaternion_wxyz
        q[self._position_slice] = p_OH
        q[self._joint_indices] = joint_angles
        self._plant.SetPositions(self._plant_context, q)

    def set_hand(self, X_OH: RigidTransform, joint_angles) -> None:
        """Like :meth:`set_configuration`, from a RigidTransform."""
        quaternion = X_OH.rotation().ToQuaternion()
        self.set_configuration([quaternion.w(), quaternion.x(), quaternion.y(), quaternion.z()],
                               X_OH.translation(), joint_angles)

    def in_collision(self) -> bool:
        """Whether any hand link (or virtual contact) penetrates the object (or the table)."""
        return self._query_port.Eval(self._sg_context).HasCollisions()

    def contact_distances(self, points_O: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Signed distances from the virtual contacts to the object, and the object's gradients.

        Args:
            points_O: (19, 3) positions of the virtual contacts in O at the configuration last set
                (m). Analytic pieces use these; Drake-queried pieces use the contacts' geometries.

        Returns:
            (distance (19,) m, negative inside; unit outward gradient (19, 3) of the object's
            distance at each contact: the direction from the closest object point to the contact).
        """
        if self._convex_only:
            distance, gradient = self._convex_distance(points_O)  # nothing to merge
        else:
            distance, gradient = self._primitive_distance(points_O)
            if self._convex_distance is not None:
                d, g = self._convex_distance(points_O)
                closer = d < distance
                distance = np.where(closer, d, distance)
                gradient = np.where(closer[:, None], g, gradient)
        if not self._drake_pieces:
            return distance, gradient
        distance, gradient = distance.copy(), gradient.copy()
        query = self._query_port.Eval(self._sg_context)
        pair_query = query.ComputeSignedDistancePairClosestPoints
        for piece_id in self._drake_pieces:
            for i in range(len(points_O)):
                self._pair_distance(pair_query, i, piece_id, distance, gradient)
        return distance, gradient

    def _pair_distance(self, pair_query, i, piece_id, distance, gradient) -> None:
        """Drake's exact distance from contact i to a piece, kept where it is the smallest."""
        contact_id = self._contact_geometries[i]
        pair = pair_query(contact_id, piece_id)
        if pair.distance < distance[i]:
            distance[i] = pair.distance
            # nhat_BA_W points from B toward A; make it point from the object to the contact.
            nhat = np.asarray(pair.nhat_BA_W)
            gradient[i] = nhat if pair.id_A == contact_id else -nhat

    def hand_distance(self) -> float:
        """Smallest signed distance between a hand link and the object, m (slow; for checks)."""
        query = self._query_port.Eval(self._sg_context)
        contact_ids = set(self._contact_geometries)
        pairs = [p for p in query.ComputeSignedDistancePairwiseClosestPoints()
                 if p.id_A not in contact_ids and p.id_B not in contact_ids]
        return min(p.distance for p in pairs)
