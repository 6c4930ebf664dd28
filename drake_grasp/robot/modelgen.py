"""Writes the robot model files under models/ from the facts in `hand` and `arm`.

The SDFormat files in models/ are what users load (in Drake or any SDF reader); this module is how
they were made, so that every link length and mass in them traces back to one named constant with
its source. A test checks that the committed files equal what this module writes.

Regenerate after changing a fact:

    drake-grasp models            (or: python -m drake_grasp.robot.modelgen)

Both chains are written with each link's body frame equal to its D-H frame at zero joint angles,
so the joint angles in Drake are exactly the D-H joint variables (Theta for the hand, q for the WAM).
"""

from __future__ import annotations

import pathlib

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix

from drake_grasp.robot import arm, hand
from drake_grasp.paths import MODELS_DIR

HAND_SDF = MODELS_DIR / "barrett_hand" / "bh280.sdf"
DISTAL_OBJ = MODELS_DIR / "barrett_hand" / "bh280_distal.obj"
WAM_SDF = MODELS_DIR / "wam" / "wam7.sdf"

# Rigid-hydroelastic fingers and palm: the objects carry the compliance of the contact (their
# modulus is set per scenario), which is also the cheaper pairing for Drake's hydroelastic contact.
# mu = 0.5 as assumed for hand-object (docs/design.md §4.4).
HAND_HUNT_CROSSLEY_DISSIPATION = 1.0  # s/m
HAND_FRICTION = 0.5
HAND_RESOLUTION_HINT = 0.01  # m; only used by the palm cylinder.

_HAND_GREY = "0.25 0.25 0.27 1"
_FINGER_GREY = "0.55 0.55 0.58 1"
_WAM_WHITE = "0.92 0.92 0.92 1"


def _modified_dh(a: float, alpha: float, d: float, theta: float) -> RigidTransform:
    """Craig's modified D-H step: RotX(alpha) TransX(a) RotZ(theta) TransZ(d)."""
    return (
        RigidTransform(RotationMatrix.MakeXRotation(alpha), [a, 0, 0])
        @ RigidTransform(RotationMatrix.MakeZRotation(theta), [0, 0, d])
    )


def _classical_dh(a: float, alpha: float, d: float, theta: float) -> RigidTransform:
    """Classical D-H step: RotZ(theta) TransZ(d) TransX(a) RotX(alpha)."""
    return RigidTransform(RotationMatrix.MakeZRotation(theta), [0, 0, d]) @ RigidTransform(
        RotationMatrix.MakeXRotation(alpha), [a, 0, 0]
    )


def _fmt(values) -> str:
    out = []
    for v in values:
        v = 0.0 if abs(v) < 1e-12 else float(v)
        out.append(f"{v:.9g}")
    return " ".join(out)


def _pose(X: RigidTransform, relative_to: str | None = None) -> str:
    rpy = RollPitchYaw(X.rotation()).vector()
    attr = f' relative_to="{relative_to}"' if relative_to else ""
    return f"<pose{attr}>{_fmt(X.translation())} {_fmt(rpy)}</pose>"


def _box_inertia(mass: float, size) -> str:
    sx, sy, sz = size
    ixx = mass * (sy**2 + sz**2) / 12
    iyy = mass * (sx**2 + sz**2) / 12
    izz = mass * (sx**2 + sy**2) / 12
    return _inertia_xml(mass, (ixx, iyy, izz))


def _inertia_xml(mass, diagonal, X_LCom: RigidTransform | None = None, products=(0.0, 0.0, 0.0)) -> str:
    pose = _pose(X_LCom) if X_LCom is not None else ""
    ixx, iyy, izz = diagonal
    ixy, ixz, iyz = products
    return (
        f"<inertial>{pose}<mass>{mass:.9g}</mass><inertia>"
        f"<ixx>{ixx:.9g}</ixx><iyy>{iyy:.9g}</iyy><izz>{izz:.9g}</izz>"
        f"<ixy>{ixy:.9g}</ixy><ixz>{ixz:.9g}</ixz><iyz>{iyz:.9g}</iyz></inertia></inertial>"
    )


def _distal_inertia() -> str:
    """The distal link's inertia: `hand.DISTAL_MASS` spread uniformly over its shape's convex hull,
    about the hull's centre of mass, in the link frame."""
    import trimesh

    hull = trimesh.convex.convex_hull(hand.distal_link_points())
    hull.density = hand.DISTAL_MASS / hull.volume
    I = np.asarray(hull.moment_inertia)  # about the centre of mass, kg m^2
    X_LCom = RigidTransform(np.asarray(hull.center_mass, float))
    return _inertia_xml(hand.DISTAL_MASS, np.diag(I), X_LCom, (I[0, 1], I[0, 2], I[1, 2]))


def _distal_geometry() -> str:
    """Visual and collision of a distal link: the mesh `distal_obj` writes, beside the SDF file, its
    convex hull declared so that Drake uses it as a convex shape (rigid hydroelastic, exact hull)."""
    shape = f"<geometry><mesh><uri>{DISTAL_OBJ.name}</uri><drake:declare_convex/></mesh></geometry>"
    return (f'<visual name="distal_visual">{shape}<material><diffuse>{_FINGER_GREY}</diffuse></material></visual>'
            f'<collision name="distal_collision">{shape}{_hand_proximity("convex")}</collision>')


def _hand_proximity(shape: str) -> str:
    hint = (
        f"<drake:mesh_resolution_hint>{HAND_RESOLUTION_HINT}</drake:mesh_resolution_hint>"
        if shape in ("cylinder", "sphere", "capsule")
        else ""
    )
    return (
        "<drake:proximity_properties><drake:rigid_hydroelastic/>"
        f"{hint}"
        f"<drake:hunt_crossley_dissipation>{HAND_HUNT_CROSSLEY_DISSIPATION}"
        "</drake:hunt_crossley_dissipation>"
        f"<drake:mu_dynamic>{HAND_FRICTION}</drake:mu_dynamic>"
        f"<drake:mu_static>{HAND_FRICTION}</drake:mu_static>"
        "</drake:proximity_properties>"
    )


def _box_geometry(name: str, X_LG: RigidTransform, size, color: str, collide: bool) -> str:
    shape = f"<geometry><box><size>{_fmt(size)}</size></box></geometry>"
    xml = f'<visual name="{name}_visual">{_pose(X_LG)}{shape}<material><diffuse>{color}</diffuse></material></visual>'
    if collide:
        xml += f'<collision name="{name}_collision">{_pose(X_LG)}{shape}{_hand_proximity("box")}</collision>'
    return xml


def distal_obj() -> str:
    """The distal link's shape as Wavefront OBJ text: the convex hull of `hand.distal_link_points`,
    in the link's frame (m), faces wound outward: the distal links' visual and collision geometry
    (models/barrett_hand/bh280_distal.obj; docs/design.md §4.1a)."""
    from scipy.spatial import ConvexHull

    points = hand.distal_link_points()
    hull = ConvexHull(points)
    lines = ["# Generated by drake_grasp/robot/modelgen.py from drake_grasp/robot/hand.py: do not edit by hand.",
             "# BarrettHand BH8-280 distal link (flat pad, tapered back, rounded tip), metres, distal D-H frame."]
    used = sorted(set(hull.simplices.ravel()))
    index = {v: i + 1 for i, v in enumerate(used)}
    lines += [f"v {_fmt(points[v])}" for v in used]
    centre = points[used].mean(axis=0)
    for simplex in hull.simplices:
        a, b, c = points[simplex]
        if np.dot(np.cross(b - a, c - a), a - centre) < 0:
            simplex = simplex[::-1]
        lines.append("f " + " ".join(str(index[v]) for v in simplex))
    return "\n".join(lines) + "\n"


def _hand_link_frames(finger: int) -> dict[str, RigidTransform]:
    """Poses, at zero joint angles, of one finger's knuckle, proximal and distal frames, and tip."""
    X_WK, X_KP, X_PD, X_DT = (_modified_dh(*row) for row in hand.finger_dh_table(finger))
    return {"knuckle": X_WK, "proximal": X_KP, "distal": X_PD, "tip": X_DT}


def hand_sdf() -> str:
    """SDFormat text of the BarrettHand BH8-280."""
    parts = [
        '<?xml version="1.0"?>',
        "<!-- Generated by drake_grasp/robot/modelgen.py from drake_grasp/robot/hand.py: do not edit by hand.",
        "     BarrettHand BH8-280. D-H numbers: Barrett BH8 manual (see models/barrett_hand/README.md). -->",
        '<sdf version="1.9">',
        '<model name="barrett_hand">',
        # The base: a cylinder whose top face is the palm.
        '<link name="bh_base">',
        _inertia_xml(
            hand.BASE_MASS,
            (
                hand.BASE_MASS * (3 * hand.BASE_RADIUS**2 + hand.PALM_HEIGHT**2) / 12,
                hand.BASE_MASS * (3 * hand.BASE_RADIUS**2 + hand.PALM_HEIGHT**2) / 12,
                hand.BASE_MASS * hand.BASE_RADIUS**2 / 2,
            ),
            RigidTransform([0, 0, hand.PALM_HEIGHT / 2]),
        ),
    ]
    X_palm_center = RigidTransform([0, 0, hand.PALM_HEIGHT / 2])
    cylinder = (
        f"<geometry><cylinder><radius>{hand.BASE_RADIUS}</radius>"
        f"<length>{hand.PALM_HEIGHT}</length></cylinder></geometry>"
    )
    parts.append(
        f'<visual name="palm_visual">{_pose(X_palm_center)}{cylinder}'
        f"<material><diffuse>{_HAND_GREY}</diffuse></material></visual>"
    )
    parts.append(
        f'<collision name="palm_collision">{_pose(X_palm_center)}{cylinder}'
        f'{_hand_proximity("cylinder")}</collision>'
    )
    parts.append("</link>")
    parts.append(
        f'<frame name="bh_palm" attached_to="bh_base">{_pose(RigidTransform([0, 0, hand.PALM_HEIGHT]))}</frame>'
    )
    # The wrist camera looks along the palm normal from the palm centre, just above its surface
    # (assumed mount). Camera convention (Drake's RgbdSensor): +z forward, +x right, +y down.
    parts.append(
        '<frame name="wrist_camera" attached_to="bh_base">'
        f"{_pose(RigidTransform([0, 0, hand.PALM_HEIGHT + 0.002]))}</frame>"
    )

    prox_len = hand.A2
    for finger in hand.FINGERS:
        frames = _hand_link_frames(finger)
        knuckle, proximal, distal = (f"bh_finger_{finger}_{n}" for n in ("knuckle", "proximal", "distal"))
        # Knuckle (spread) link: carries the proximal axis; it sits inside the palm outline.
        knuckle_size = (hand.A1, hand.FINGER_WIDTH, 0.02)  # knuckle frame: z along the spread axis
        parts.append(
            f'<link name="{knuckle}">{_pose(frames["knuckle"], "bh_base")}'
            f"{_box_inertia(hand.KNUCKLE_MASS, knuckle_size)}"
            f'{_box_geometry("knuckle", RigidTransform([hand.A1 / 2, 0, -0.01]), knuckle_size, _HAND_GREY, False)}'
            "</link>"
        )
        if hand.FINGER_R[finger] == 0:
            parts.append(
                f'<joint name="bh_knuckle_{finger}_weld" type="fixed"><parent>bh_base</parent>'
                f"<child>{knuckle}</child></joint>"
            )
        else:
            axis = hand.FINGER_R[finger]  # F1 spreads about -z, F2 about +z.
            lo, hi = hand.SPREAD_LIMITS
            parts.append(
                f'<joint name="bh_spread_{finger}" type="revolute"><parent>bh_base</parent>'
                f"<child>{knuckle}</child><axis><xyz>0 0 {axis}</xyz>"
                f"<limit><lower>{lo:.9g}</lower><upper>{hi:.9g}</upper><effort>2</effort>"
                "<velocity>6.3</velocity></limit><dynamics><damping>0.01</damping></dynamics>"
                "</axis></joint>"
            )
        # Proximal link: a box along +x from the proximal axis to the distal axis, its inner (+y)
        # face flush with the palm surface when the finger is open.
        # Link frames (D-H): x along the link, y toward the inner (grasping) side, z along the joint axis.
        prox_size = (prox_len + hand.PROXIMAL_BEHIND_AXIS, hand.PROXIMAL_THICKNESS, hand.FINGER_WIDTH)
        inner_face = hand.PALM_HEIGHT - hand.DW
        X_PG = RigidTransform([(prox_len - hand.PROXIMAL_BEHIND_AXIS) / 2, inner_face - hand.PROXIMAL_THICKNESS / 2, 0])
        parts.append(
            f'<link name="{proximal}">{_pose(frames["proximal"], knuckle)}'
            f"{_box_inertia(hand.PROXIMAL_MASS, prox_size)}"
            f'{_box_geometry("proximal", X_PG, prox_size, _FINGER_GREY, True)}'
            "</link>"
        )
        lo, hi = hand.PROXIMAL_LIMITS
        parts.append(
            f'<joint name="bh_proximal_{finger}" type="revolute"><parent>{knuckle}</parent>'
            f"<child>{proximal}</child><axis><xyz>0 0 1</xyz>"
            f"<limit><lower>{lo:.9g}</lower><upper>{hi:.9g}</upper><effort>10</effort>"
            "<velocity>6.3</velocity></limit><dynamics><damping>0.005</damping></dynamics>"
            "</axis></joint>"
        )
        # Distal link: the BH8-280's (hand.distal_link_points: flat inner pad holding the fingertip
        # frame, tapered back, rounded tip), one convex mesh in the link's D-H frame.
        parts.append(
            f'<link name="{distal}">{_pose(frames["distal"], proximal)}'
            f"{_distal_inertia()}{_distal_geometry()}"
            "</link>"
        )
        lo, hi = hand.DISTAL_LIMITS
        parts.append(
            f'<joint name="bh_distal_{finger}" type="revolute"><parent>{proximal}</parent>'
            f"<child>{distal}</child><axis><xyz>0 0 1</xyz>"
            f"<limit><lower>{lo:.9g}</lower><upper>{hi:.9g}</upper><effort>5</effort>"
            "<velocity>6.3</velocity></limit><dynamics><damping>0.002</damping></dynamics>"
            "</axis></joint>"
        )
        parts.append(f'<frame name="bh_tip_{finger}" attached_to="{distal}">{_pose(frames["tip"])}</frame>')

    # No collisions inside the hand: fingers touch the palm and each other when closed.
    parts.append('<drake:collision_filter_group name="hand">')
    parts.append("<drake:member>bh_base</drake:member>")
    for finger in hand.FINGERS:
        for part in ("knuckle", "proximal", "distal"):
            parts.append(f"<drake:member>bh_finger_{finger}_{part}</drake:member>")
    parts.append("<drake:ignored_collision_filter_group>hand</drake:ignored_collision_filter_group>")
    parts.append("</drake:collision_filter_group>")
    parts.append("</model>")
    parts.append("</sdf>")
    return "\n".join(parts) + "\n"


def wam_frames() -> list[RigidTransform]:
    """Poses X_{i-1,i} of the WAM's D-H frames at q = 0, for i = 1..7 (frame 0 = DH base)."""
    return [_classical_dh(a, alpha, d, 0.0) for a, alpha, d in arm.DH_ROWS]


def wam_sdf() -> str:
    """SDFormat text of the 7-DoF Barrett WAM (arm only; the hand is welded on by a directive)."""
    parts = [
        '<?xml version="1.0"?>',
        "<!-- Generated by drake_grasp/robot/modelgen.py from drake_grasp/robot/arm.py: do not edit by hand.",
        "     Barrett WAM 7-DoF. D-H: WAM Arm User's Manual table 5 (see models/wam/README.md). -->",
        '<sdf version="1.9">',
        '<model name="wam">',
        '<link name="wam_base">',
        _inertia_xml(arm.BASE_MASS, (0.1, 0.1, 0.1), RigidTransform([0, 0, arm.BASE_TO_JOINT1 / 2])),
        _wam_visual("base", RigidTransform([0, 0, arm.BASE_TO_JOINT1 / 2]), 0.09, arm.BASE_TO_JOINT1),
        "</link>",
        '<frame name="wam_dh_0" attached_to="wam_base">'
        f"{_pose(RigidTransform([0, 0, arm.BASE_TO_JOINT1]))}</frame>",
    ]
    parent = "wam_base"
    parent_frame = "wam_dh_0"
    for i, (X_prev_i, mass) in enumerate(zip(wam_frames(), arm.LINK_MASSES), start=1):
        link = f"wam_link_{i}"
        # The link's body runs from its own D-H origin back to its joint's origin (the previous
        # D-H origin): put the centre of mass at the middle of that segment (an approximation; the
        # manufacturer's full inertias are not needed for position-controlled motion).
        p_i_prev = X_prev_i.inverse().translation()
        length = float(np.linalg.norm(p_i_prev))
        X_LCom = RigidTransform(p_i_prev / 2)
        radius = arm.link_radius(i)
        inertia = 0.4 * mass * radius**2 + mass * length**2 / 12
        parts.append(
            f'<link name="{link}">{_pose(X_prev_i, parent_frame)}'
            f"{_inertia_xml(mass, (inertia, inertia, inertia), X_LCom)}"
        )
        if length > 1e-6:
            parts.append(_wam_segment_visual(f"link_{i}", p_i_prev, radius * 0.8))
        parts.append(_wam_visual(f"joint_{i}", RigidTransform(p_i_prev), radius, radius * 1.6,
                                 RotationMatrix(X_prev_i.rotation().inverse())))
        parts.append("</link>")
        lo, hi, effort = arm.LOWER_LIMITS[i - 1], arm.UPPER_LIMITS[i - 1], arm.EFFORT_LIMITS[i - 1]
        parts.append(
            f'<joint name="wam_joint_{i}" type="revolute">'
            f'<pose relative_to="{parent_frame}">0 0 0 0 0 0</pose>'
            f"<parent>{parent}</parent><child>{link}</child>"
            f"<axis><xyz>0 0 1</xyz><limit><lower>{lo:.9g}</lower><upper>{hi:.9g}</upper>"
            f"<effort>{effort:.9g}</effort><velocity>3</velocity></limit>"
            "<dynamics><damping>0.1</damping></dynamics></axis></joint>"
        )
        parent = parent_frame = link
    parts.append('<frame name="wam_flange" attached_to="wam_link_7"><pose>0 0 0 0 0 0</pose></frame>')
    parts.append("</model>")
    parts.append("</sdf>")
    return "\n".join(parts) + "\n"


def _wam_visual(name: str, X_LG: RigidTransform, radius: float, length: float,
                R: RotationMatrix | None = None) -> str:
    if R is not None:
        X_LG = RigidTransform(R, X_LG.translation())
    return (
        f'<visual name="{name}_visual">{_pose(X_LG)}<geometry><cylinder><radius>{radius:.6g}</radius>'
        f"<length>{length:.6g}</length></cylinder></geometry>"
        f"<material><diffuse>{_WAM_WHITE}</diffuse></material></visual>"
    )


def _wam_segment_visual(name: str, p_LE, radius: float) -> str:
    """A cylinder from the link origin to point p_LE, for drawing."""
    p_LE = np.asarray(p_LE, dtype=float)
    length = float(np.linalg.norm(p_LE))
    z = p_LE / length
    R = RotationMatrix.MakeFromOneVector(z, 2)
    return _wam_visual(name, RigidTransform(R, p_LE / 2), radius, length)


def write_models() -> list[pathlib.Path]:
    """Writes the hand and WAM SDF files and the distal links' mesh; returns their paths."""
    written = []
    for path, text in ((HAND_SDF, hand_sdf()), (DISTAL_OBJ, distal_obj()), (WAM_SDF, wam_sdf())):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        written.append(path)
    return written


if __name__ == "__main__":
    for p in write_models():
        print(f"wrote {p}")
