"""Quasi-static grasping: approach until contact, then close with breakaway, by distance queries.

No dynamics: the hand is moved kinematically, the object does not move, and every step is a
*conservative advancement* computed from SceneGraph signed distances, so the hand never passes
through the object:

* Approach: the hand translates along its palm normal. No point of the hand moves farther than the
  translation, so translating by (distance - margin) cannot cause contact.
* Closing: each finger turns about its joint axes. A point at most R from an axis moves at most
  R * dtheta when the joint turns by dtheta, so dtheta = (distance - margin) / R is safe.

Closing follows the BarrettHand's clutch (docs/design.md §4.1): in the coupled phase the distal joint turns
at a third of the proximal rate; a proximal-link contact (or the proximal limit) makes the clutch
break away and the distal joint closes alone until its link touches or reaches its limit; a distal
contact in the coupled phase stops the whole finger. The spread is set first and stays. Fingers
do not collide with each other (as in the dynamic model, collisions inside the hand are filtered).

This is the quasi-static closing of the paper's Sec. 3 (Fig. 4) and the "autograsp" of the
Eigengrasp baseline. One contact is reported per hand link touching the object: the closest points
of the link and the object (Drake's signed-distance witness points), with the object's inward normal.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from pydrake.geometry import Box, SceneGraph
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.systems.framework import DiagramBuilder

from drake_grasp.robot import hand
from drake_grasp.robot.contact import ContactParameters
from drake_grasp.robot.hand import ComplianceMode
from drake_grasp.robot.modelgen import HAND_SDF
from drake_grasp.objects import AddObject, ObjectSpec, RegisterSupportTable
from drake_grasp.paths import RegisterPackage

CONTACT_TOLERANCE = 1.0e-3  # m: a link closer than this to the object touches it.
ADVANCE_MARGIN = 0.25e-3  # m: conservative steps stop this far from the surface.
MAX_STEPS = 400  # per phase; a grazing approach converges slowly, so bound it.


@dataclasses.dataclass(frozen=True)
class Contact:
    """A hand link touching the object. Positions and normals in the object frame O (m).

    Attributes:
        link: the hand body ("bh_base" for the palm, "bh_finger_2_distal", ...).
        point: the contact point on the object's surface.
        normal: unit normal at the point, pointing into the object.
        distance: signed distance between link and object at the end, m (negative = penetration).
    """

    link: str
    point: np.ndarray
    normal: np.ndarray
    distance: float


@dataclasses.dataclass
class QuasiStaticGrasp:
    """The result of one quasi-static grasp.

    Attributes:
        X_OH: the hand base pose in the object frame when closing (after the approach).
        joint_angles: [spread1, spread2, proximal1..3, distal1..3] at the end, rad.
        contacts: one per touching link.
        approach_distance: how far the hand travelled along its palm normal, m.
        touched_during_approach: the link that stopped the approach (None if nothing was hit).
        broke_away: per finger, whether its clutch slipped.
    """

    X_OH: RigidTransform
    joint_angles: np.ndarray
    contacts: list[Contact]
    approach_distance: float
    touched_during_approach: str | None
    broke_away: list[bool]

    @property
    def touching_links(self) -> list[str]:
        return [c.link for c in self.contacts]

    def contact_arrays(self) -> tuple[np.ndarray, np.ndarray]:
        """(points N x 3, inward normals N x 3) in the object frame, for the ε metric."""
        if not self.contacts:
            return np.zeros((0, 3)), np.zeros((0, 3))
        return np.array([c.point for c in self.contacts]), np.array([c.normal for c in self.contacts])


class QuasiStaticHand:
    """A BarrettHand and one object in a SceneGraph, for quasi-static grasps of that object.

    Build it once per object and call `grasp` for as many hand poses as needed: the Diagram is not
    rebuilt. The object frame O is the world frame here.
    """

    def __init__(self, spec: ObjectSpec, contact: ContactParameters | None = None, table: bool = False):
        """
        Args:
            spec: the object; its frame O is the world frame here.
            contact: its contact parameters (they do not change the queries).
            table: add the table the object rests on (its nominal pose) as an obstacle: the hand
                stops on it like on the object, but only object contacts are reported.
        """
        self.spec = spec
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
        parser = RegisterPackage(Parser(plant))
        (self._hand,) = parser.AddModels(str(HAND_SDF))
        object_instance = AddObject(plant, spec, contact or ContactParameters())
        object_body = plant.get_body(plant.GetBodyIndices(object_instance)[0])
        plant.WeldFrames(plant.world_frame(), object_body.body_frame())
        self._table_geometries = {RegisterSupportTable(plant, spec)} if table else set()
        plant.Finalize()
        self._plant = plant
        self._diagram = builder.Build()
        self._context = self._diagram.CreateDefaultContext()
        self._plant_context = plant.GetMyMutableContextFromRoot(self._context)
        self._sg_context = scene_graph.GetMyContextFromRoot(self._context)
        self._scene_graph: SceneGraph = scene_graph
        self._base = plant.GetBodyByName(hand.HAND_JOINTS.base_frame, self._hand)
        self._object_geometries = set(plant.GetCollisionGeometriesForBody(object_body))
        self._joints = [plant.GetJointByName(n, self._hand) for n in hand.HAND_JOINTS.all]
        self._link_geometries = {}
        for name in ["bh_base"] + [f"bh_finger_{f}_{p}" for f in hand.FINGERS for p in ("proximal", "distal")]:
            body = plant.GetBodyByName(name, self._hand)
            self._link_geometries[name] = plant.GetCollisionGeometriesForBody(body)
        # Reach of each link's collision geometry from its joint axes (the links' z axes), m.
        self._proximal_reach = self._link_reach("bh_finger_1_proximal")
        self._distal_reach = self._link_reach("bh_finger_1_distal")
        self._distal_reach_from_proximal = hand.A2 + self._distal_reach

    def _link_reach(self, body_name: str) -> float:
        inspector = self._scene_graph.model_inspector()
        reach = 0.0
        for geometry in self._link_geometries[body_name]:
            shape = inspector.GetShape(geometry)
            X_BG = inspector.GetPoseInFrame(geometry)
            if isinstance(shape, Box):
                half = np.array([shape.width(), shape.depth(), shape.height()]) / 2
                points_G = np.array(np.meshgrid(*[[-1, 1]] * 3)).reshape(3, -1).T * half
            else:  # a convex mesh (the distal links): the vertices of the hull SceneGraph uses
                hull = inspector.GetConvexHull(geometry)
                points_G = [hull.vertex(i) for i in range(hull.num_vertices())]
            for p_G in points_G:
                p = X_BG @ p_G
                reach = max(reach, math.hypot(p[0], p[1]))
        return reach

    # --- Queries. ---------------------------------------------------------------------------------

    def _query(self):
        return self._scene_graph.get_query_output_port().Eval(self._sg_context)

    def _link_distance(self, query, link: str, obstacles: bool = True):
        """(signed distance, witness pair) between a hand link and the object (and the table, if
        there is one and `obstacles`)."""
        best, best_pair = math.inf, None
        others = self._object_geometries | self._table_geometries if obstacles else self._object_geometries
        for g_link in self._link_geometries[link]:
            for g_object in others:
                pair = query.ComputeSignedDistancePairClosestPoints(g_link, g_object)
                if pair.distance < best:
                    best, best_pair = pair.distance, pair
        return best, best_pair

    def _set_joint_angles(self, q: np.ndarray) -> None:
        for joint, angle in zip(self._joints, q):
            joint.set_angle(self._plant_context, float(angle))

    def hand_distance(self) -> tuple[float, str]:
        """Smallest signed distance from any hand link to the object (or the table), m, and that link."""
        query = self._query()
        return min((self._link_distance(query, link)[0], link) for link in self._link_geometries)

    def set_hand(self, X_OH: RigidTransform, joint_angles: np.ndarray) -> None:
        """Puts the hand base at X_OH with the given joint angles (controller order)."""
        self._plant.SetFreeBodyPose(self._plant_context, self._base, X_OH)
        self._set_joint_angles(joint_angles)

    # --- The grasp. -------------------------------------------------------------------------------

    def grasp(self, X_OH: RigidTransform, mode: ComplianceMode | float, approach: bool = True,
              max_approach: float = 0.5, start_angles: np.ndarray | None = None) -> QuasiStaticGrasp:
        """Approach along the palm normal until the first contact, then close with breakaway.

        Args:
            X_OH: the hand base's starting pose in the object frame.
            mode: a compliance mode, or a spread angle in rad.
            approach: translate along the palm normal until a link touches (else close in place).
            max_approach: give up the approach after this distance, m (the hand missed the object).
            start_angles: finger angles to start closing from (controller order; default open).
        """
        spread = mode.spread if isinstance(mode, ComplianceMode) else float(mode)
        q = np.zeros(8) if start_angles is None else np.array(start_angles, dtype=float)
        q[0:2] = spread
        self.set_hand(X_OH, q)
        travelled, touched = 0.0, None
        if approach:
            travelled, touched = self._approach(X_OH, max_approach)
        X_OH_final = self._plant.EvalBodyPoseInWorld(self._plant_context, self._base)
        broke_away = [self._close_finger(f, q) for f in range(3)]
        return QuasiStaticGrasp(
            X_OH=X_OH_final, joint_angles=q.copy(), contacts=self._contacts(),
            approach_distance=travelled, touched_during_approach=touched, broke_away=broke_away,
        )

    def grasp_plan(self, plan, X_WO: RigidTransform) -> QuasiStaticGrasp:
        """The quasi-static grasp of a `grasps.GraspPlan` as the executor runs it, with the object at X_WO
        (world): a plan that stops on contact (a compliant grasp) approaches from its pre-grasp pose until
        a link touches, at most to its target; any other (a planned grasp) is taken to its target. The
        hand starts at the plan's spread and finger preshape, then closes with breakaway."""
        start = np.zeros(8)
        start[0:2] = plan.spread
        start[2:8] = plan.finger_preshape
        X_PH = RigidTransform([0.0, 0.0, -hand.PALM_HEIGHT])  # the hand base, seen from the palm
        X_OW = X_WO.inverse()
        if plan.stop_on_contact:
            return self.grasp(X_OW @ plan.X_WP_pregrasp @ X_PH, plan.spread, approach=True,
                              max_approach=plan.approach_distance, start_angles=start)
        return self.grasp(X_OW @ plan.X_WP_target @ X_PH, plan.spread, approach=False, start_angles=start)

    def _approach(self, X_OH: RigidTransform, max_approach: float) -> tuple[float, str | None]:
        z_O = X_OH.rotation().col(2)  # palm normal, object frame
        travelled = 0.0
        for _ in range(MAX_STEPS):
            distance, link = self.hand_distance()
            if distance <= CONTACT_TOLERANCE:
                return travelled, link
            step = distance - ADVANCE_MARGIN
            if travelled + step > max_approach:
                step = max_approach - travelled
                travelled = max_approach
                self._plant.SetFreeBodyPose(self._plant_context, self._base,
                                            RigidTransform(X_OH.rotation(), X_OH.translation() + travelled * z_O))
                return travelled, None
            travelled += step
            self._plant.SetFreeBodyPose(self._plant_context, self._base,
                                        RigidTransform(X_OH.rotation(), X_OH.translation() + travelled * z_O))
        return travelled, None

    def _close_finger(self, f: int, q: np.ndarray) -> bool:
        """Closes finger f (0-based) in place in q; returns whether its clutch broke away."""
        proximal, distal = f"bh_finger_{f + 1}_proximal", f"bh_finger_{f + 1}_distal"
        i_p, i_d = 2 + f, 5 + f
        p_max, d_max = hand.PROXIMAL_LIMITS[1], hand.DISTAL_LIMITS[1]
        ratio = hand.DISTAL_PER_PROXIMAL
        # Coupled phase.
        broke_away = False
        for _ in range(MAX_STEPS):
            query = self._query()
            d_p = self._link_distance(query, proximal)[0]
            d_d = self._link_distance(query, distal)[0]
            if d_d <= CONTACT_TOLERANCE:
                return False  # a distal contact stalls the whole finger
            if d_p <= CONTACT_TOLERANCE or q[i_p] >= p_max or q[i_d] >= d_max:
                broke_away = True
                break
            step = min(
                (d_p - ADVANCE_MARGIN) / self._proximal_reach,
                (d_d - ADVANCE_MARGIN) / (self._distal_reach_from_proximal + ratio * self._distal_reach),
                p_max - q[i_p],
                (d_max - q[i_d]) / ratio,
            )
            q[i_p] += step
            q[i_d] += ratio * step
            self._set_joint_angles(q)
        if not broke_away:
            return False
        # The clutch has slipped: the distal joint closes alone.
        for _ in range(MAX_STEPS):
            d_d = self._link_distance(self._query(), distal)[0]
            if d_d <= CONTACT_TOLERANCE or q[i_d] >= d_max:
                break
            q[i_d] += min((d_d - ADVANCE_MARGIN) / self._distal_reach, d_max - q[i_d])
            self._set_joint_angles(q)
        return True

    def _contacts(self) -> list[Contact]:
        query = self._query()
        contacts = []
        for link in self._link_geometries:
            distance, pair = self._link_distance(query, link, obstacles=False)
            if distance > CONTACT_TOLERANCE:
                continue
            # Witness points are in each geometry's frame; the object frame is the world here.
            if pair.id_A in self._object_geometries:
                object_id, p_on_object, n_out = pair.id_A, pair.p_ACa, -pair.nhat_BA_W
            else:
                object_id, p_on_object, n_out = pair.id_B, pair.p_BCb, pair.nhat_BA_W
            X_WG = query.GetPoseInWorld(object_id)
            point = X_WG @ p_on_object
            contacts.append(Contact(link=link, point=np.asarray(point), normal=-np.asarray(n_out),
                                    distance=float(distance)))
        return contacts
