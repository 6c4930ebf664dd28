"""Quasi-static grasping: approach until contact, close with breakaway, by SceneGraph distances."""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix

from drake_grasp.robot import hand
from drake_grasp.robot.hand import ComplianceMode
from drake_grasp.objects import cube_object, cylinder_object, sphere_object
from drake_grasp.quality import grasp_quality
from drake_grasp.quasistatic import CONTACT_TOLERANCE, QuasiStaticHand

# Palm normal down (-z of the object frame), the hand base 0.3 m above the object's centre.
X_ABOVE = RigidTransform(RotationMatrix.MakeXRotation(math.pi), [0.0, 0.0, 0.3])


def _assert_no_penetration(sim: QuasiStaticHand, grasp):
    sim.set_hand(grasp.X_OH, grasp.joint_angles)
    distance, link = sim.hand_distance()
    assert distance >= -0.5e-3, f"{link} penetrates the object by {-distance * 1000:.2f} mm"
    for contact in grasp.contacts:
        assert -0.5e-3 <= contact.distance <= CONTACT_TOLERANCE


def test_sphere_under_the_palm_in_spherical_mode_gets_three_symmetric_finger_contacts():
    spec = sphere_object(0.10)
    sim = QuasiStaticHand(spec)
    grasp = sim.grasp(X_ABOVE, ComplianceMode.SPHERICAL)
    _assert_no_penetration(sim, grasp)
    assert grasp.touched_during_approach == "bh_base"  # the palm centre meets the sphere's top
    assert grasp.approach_distance == pytest.approx(0.3 - hand.PALM_HEIGHT - 0.05, abs=CONTACT_TOLERANCE)
    fingers = {c.link.split("_")[2] for c in grasp.contacts if c.link.startswith("bh_finger")}
    assert fingers == {"1", "2", "3"}
    # F1 and F2 mirror each other about the object's yz plane.
    by_link = {c.link: c for c in grasp.contacts}
    c1, c2 = by_link["bh_finger_1_distal"], by_link["bh_finger_2_distal"]
    np.testing.assert_allclose(c1.point * [-1, 1, 1], c2.point, atol=1e-4)
    assert grasp.joint_angles[2] == pytest.approx(grasp.joint_angles[3], abs=1e-4)
    # Every contact lies on the sphere, and its inward normal points to the centre (to 2 %: the distal
    # links are convex meshes, whose witness normals Drake finds iteratively).
    for c in grasp.contacts:
        assert np.linalg.norm(c.point) == pytest.approx(0.05, abs=1e-4)
        np.testing.assert_allclose(c.normal, -c.point / np.linalg.norm(c.point), atol=2e-2)
    points, normals = grasp.contact_arrays()
    assert grasp_quality(points, normals, 0.5, np.zeros(3), spec.max_radius).epsilon > 0.1


def test_lying_cylinder_in_cylindrical_mode_is_wrapped():
    spec = cylinder_object(0.08)  # axis along the object's x; fingers close along y
    sim = QuasiStaticHand(spec)
    grasp = sim.grasp(X_ABOVE, ComplianceMode.CYLINDRICAL)
    _assert_no_penetration(sim, grasp)
    links = set(grasp.touching_links)
    assert "bh_base" in links
    for f in (1, 2, 3):
        assert any(l.startswith(f"bh_finger_{f}") for l in links)
    # The fingertips reach below the cylinder's axis: the hand wraps it.
    finger_points = [c.point for c in grasp.contacts if c.link.startswith("bh_finger")]
    assert all(p[2] < 0 for p in finger_points)
    points, normals = grasp.contact_arrays()
    assert grasp_quality(points, normals, 0.5, np.zeros(3), spec.max_radius).epsilon > 0


def test_with_no_object_in_reach_every_finger_closes_to_its_limits():
    sim = QuasiStaticHand(sphere_object(0.05))
    far = RigidTransform(RotationMatrix.MakeXRotation(math.pi), [1.0, 0.0, 0.3])
    grasp = sim.grasp(far, ComplianceMode.CYLINDRICAL, max_approach=0.2)
    assert grasp.touched_during_approach is None
    assert grasp.approach_distance == pytest.approx(0.2)
    assert grasp.contacts == []
    np.testing.assert_allclose(grasp.joint_angles[2:5], hand.PROXIMAL_LIMITS[1])
    np.testing.assert_allclose(grasp.joint_angles[5:8], hand.DISTAL_LIMITS[1])
    assert all(grasp.broke_away)  # the proximal limit stops the link, and the clutch slips


def test_a_proximal_contact_breaks_away_and_the_distal_wraps_on_until_it_touches():
    # A 22 cm cube under the palm: the open proximal links land on its top face (breakaway at 0),
    # then the distal links close alone until they meet its sides.
    sim = QuasiStaticHand(cube_object(0.22))
    grasp = sim.grasp(X_ABOVE, ComplianceMode.CYLINDRICAL)
    _assert_no_penetration(sim, grasp)
    assert all(grasp.broke_away)
    q = grasp.joint_angles
    np.testing.assert_allclose(q[2:5], 0.0, atol=1e-9)
    assert np.all((q[5:8] > math.radians(5)) & (q[5:8] < hand.DISTAL_LIMITS[1] - math.radians(1)))
    for f in (1, 2, 3):
        assert f"bh_finger_{f}_distal" in grasp.touching_links


def test_grasps_are_repeatable_and_the_diagram_is_reused():
    sim = QuasiStaticHand(sphere_object(0.12))
    a = sim.grasp(X_ABOVE, ComplianceMode.SPHERICAL)
    b = sim.grasp(RigidTransform(X_ABOVE.rotation(), [0.02, 0, 0.3]), ComplianceMode.SPHERICAL)
    c = sim.grasp(X_ABOVE, ComplianceMode.SPHERICAL)
    np.testing.assert_array_equal(a.joint_angles, c.joint_angles)
    assert not np.allclose(a.joint_angles, b.joint_angles)


def test_with_the_table_the_fingers_stop_on_it_and_no_table_contact_is_reported():
    from drake_grasp.objects import paper_object

    spec = paper_object("sponge")  # 3.5 cm tall: closing from right above it reaches the table
    free = QuasiStaticHand(spec).grasp(X_ABOVE, ComplianceMode.SPHERICAL)
    on_table = QuasiStaticHand(spec, table=True)
    grasp = on_table.grasp(X_ABOVE, ComplianceMode.SPHERICAL)
    _assert_no_penetration(on_table, grasp)  # neither the sponge nor the table is penetrated
    assert all(c.link != "support_table" for c in grasp.contacts)
    # Without the table the fingertips close past the table plane; with it they stop before.
    assert np.any(free.joint_angles[2:] > grasp.joint_angles[2:] + math.radians(5))
