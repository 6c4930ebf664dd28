"""Where a body set down on the table comes to rest: a quasi-static roll of its convex hull.

A body set down with some orientation first touches the table with its lowest point. If its centre of
mass is not over that point it turns about it, then about an edge, until it stands on a face with the
centre of mass over it: where gravity, turning it slowly (no momentum), leaves it. In terms of the
direction d that points down in the body's frame, the centre of mass stands

    h(d) = max_v (v - c)·d

above the table (v the hull's vertices, c the centre of mass), and a slow roll is a descent of h over
the unit sphere from the starting d: the subgradient is the lowest vertex's offset from the centre of
mass, and moving d against its part across d is the body turning about that vertex so that its centre
of mass goes down. The descent ends where the centre of mass lies over the hull's face whose normal is
d (a local minimum of h, which the faces' normals are), and the base of that face tells how surely it
stays there.

Why not the lowest of those minima (the most stable face, `mesh_files._lowest_resting_rotation`)? It is
where a body shaken long enough ends, not where one set down ends: a scanned can that rocks 5° onto
its rim is on the table, not upside down. And a base made of the vertices near the lowest one (model
files' test until 0.39.0) takes a rounded bottom for a flat one: pybullet's random object 306, a 9 cm
lump, stood on such a base and rolled 57° within 0.75 s of the trial's start, while the camera looked.

The roll is what the loader uses to tell a body that clearly stands (`stays`: it turns under a degree,
onto a broad base). Where it does not, the station's own simulator says where the body comes to rest
(`settle_in_simulator`): the roll knows no momentum and no compliant contact, and the simulator is what
the trial will run (docs/design.md §4.3).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from scipy.optimize import nnls
from scipy.spatial import ConvexHull, QhullError

# A body that settles less than this (deg) from z up keeps z up, as the file has it: a scanned box or
# can rocks that much on its uneven base in the trial's first steps (0.5-1.6° for YCB's cracker box,
# tuna can and pudding box as OCRTOC and Gazebo ship them), before the camera's first look, and a rest
# turned by a degree would change every trial of them for nothing.
ROCK_DEG = 3.0
# The roll's step (deg) and the steps it may take (400° of turning).
STEP_DEG = 0.05
MAX_STEPS = 8000
# Vertices within this angle of the supporting plane, seen from the hull's size, are its base (deg): a
# scanned face is not one plane.
BASE_TOLERANCE_DEG = 0.5


@dataclasses.dataclass(frozen=True)
class Rest:
    """Where a quasi-static roll ends.

    Attributes:
        down: the unit direction, in the body's frame, that points down when it rests.
        turned_deg: how far the body turned from its starting orientation (deg).
        margin_deg: how far inside its base's edges the centre of mass lies, as an angle seen from the
            centre of mass (deg; the angle the body must be tipped by to fall off that base). Negative
            or zero: it rests on an edge or a point (an unstable balance).
        height: the centre of mass's height above the table (m).
    """

    down: np.ndarray
    turned_deg: float
    margin_deg: float
    height: float


def _min_norm_point(points: np.ndarray) -> np.ndarray:
    """The point of the convex hull of `points` (K × 3) nearest the origin (Wolfe's problem, as a
    non-negative least-squares one with the weights' sum held at one by a heavy row)."""
    if len(points) == 1:
        return points[0]
    scale = 1e3 * max(float(np.max(np.abs(points))), 1e-12)
    a = np.vstack([points.T, np.full((1, len(points)), scale)])
    b = np.append(np.zeros(3), scale)
    weights, _ = nnls(a, b)
    return weights @ points


def roll_to_rest(vertices: np.ndarray, p_cm: np.ndarray, down: np.ndarray = (0.0, 0.0, -1.0)) -> Rest:
    """The rest a body reaches from `down` (the direction, in its frame, that points down as it is set
    down), rolling slowly over its hull's `vertices` (N × 3, m, its frame) about its centre of mass
    `p_cm` (m, its frame).

    Each step of STEP_DEG turns d against the steepest descent of h: the point nearest the origin of
    the hull of the lowest vertices' offsets across d (those within the step's reach of the lowest).
    On one vertex that is its offset; on an edge, the edge's direction (the body turns about the edge);
    on a face with the centre of mass over it, none: the roll ends."""
    offsets = np.asarray(vertices, float) - np.asarray(p_cm, float)
    size = float(np.max(offsets.max(axis=0) - offsets.min(axis=0)))
    start = np.asarray(down, float) / np.linalg.norm(down)
    d = start.copy()
    step = math.radians(STEP_DEG)
    reach = size * math.sin(step)
    for _ in range(MAX_STEPS):
        heights = offsets @ d
        lowest = offsets[heights >= float(heights.max()) - reach]
        across = lowest - np.outer(lowest @ d, d)
        descent = _min_norm_point(across)
        length = float(np.linalg.norm(descent))
        if length < 0.5 * reach:  # the centre of mass over a face (or balanced on an edge)
            break
        d = d - step * descent / length
        d /= np.linalg.norm(d)
    height = float(np.max(offsets @ d))
    turned = math.degrees(math.acos(float(np.clip(d @ start, -1.0, 1.0))))
    return Rest(down=d, turned_deg=turned, margin_deg=base_margin_deg(offsets, d, height), height=height)


def base_margin_deg(offsets: np.ndarray, down: np.ndarray, height: float) -> float:
    """How far inside its base the centre of mass lies (deg, seen from it; ≤ 0 on an edge or a point).
    The base is the hull's vertices within BASE_TOLERANCE_DEG of the supporting plane; `offsets` are
    the vertices less the centre of mass, `height` the centre of mass's height above that plane."""
    size = float(np.max(offsets.max(axis=0) - offsets.min(axis=0)))
    base = offsets[offsets @ down >= height - size * math.sin(math.radians(BASE_TOLERANCE_DEG))]
    u = np.cross(down, [1.0, 0.0, 0.0])
    if np.linalg.norm(u) < 0.1:
        u = np.cross(down, [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    w = np.cross(down, u)
    try:
        equations = ConvexHull(np.column_stack([base @ u, base @ w])).equations  # a·x + b ≤ 0 inside
    except (QhullError, ValueError):  # fewer than three points, or all in a line
        return 0.0
    inside = float(np.min(-equations[:, 2]))  # the centre of mass is the origin
    return math.degrees(math.atan2(inside, height))


def resting_rotation(down: np.ndarray) -> RotationMatrix:
    """R_TO: the smallest rotation that turns the body's `down` direction to the table's -z (the body
    keeps its heading as far as the turn allows)."""
    d = np.asarray(down, float) / np.linalg.norm(down)
    target = np.array([0.0, 0.0, -1.0])
    axis = np.cross(d, target)
    sin, cos = float(np.linalg.norm(axis)), float(d @ target)
    if sin < 1e-12:
        return RotationMatrix() if cos > 0.0 else RotationMatrix.MakeXRotation(math.pi)
    return RotationMatrix(AngleAxis(math.atan2(sin, cos), axis / sin))


# A body whose roll from how it is set down turns it less than this (deg), onto a base whose edges its
# centre of mass stands at least ROBUST_MARGIN_DEG inside, stays as it is set down without a check in
# the simulator.
STAYS_DEG = 0.5
ROBUST_MARGIN_DEG = 10.0
# The check in the simulator: how long it may take to come to rest (s), and what counts as rest.
SETTLE_TIME = 3.0
SETTLE_CHECK = 0.25  # s between looks
REST_SPEED = 0.01  # rad/s and m/s (the body's spatial velocity, each part)


def stays(vertices: np.ndarray, p_cm: np.ndarray) -> bool:
    """Whether a body set down as it is (z up) stays so without a check in the simulator: its
    quasi-static roll (`roll_to_rest`) turns it less than STAYS_DEG onto a base with the centre of mass
    ROBUST_MARGIN_DEG inside its edges."""
    rest = roll_to_rest(vertices, p_cm)
    return rest.turned_deg < STAYS_DEG and rest.margin_deg >= ROBUST_MARGIN_DEG


# How far from z up (deg) a mesh file's body is set down to see whether it stands: as a hand sets a body
# down, never exactly upright. A symmetric body balanced on a point (a capsule on its round end) stays
# balanced in a simulation started exactly upright; tilted 2° it falls, and a body on its base rocks back.
SET_DOWN_TILT_DEG = 2.0


def stays_up_in_simulator(spec) -> bool:
    """Whether the body `spec`, set down on the station's table SET_DOWN_TILT_DEG from z up
    (`settle_in_simulator`), comes to rest within ROCK_DEG of z up; False if the simulator cannot step
    it."""
    try:
        R_TO, rested = settle_in_simulator(spec, tilt_deg=SET_DOWN_TILT_DEG)
    except RuntimeError:
        return False
    return rested and degrees_from_upright(table_down(R_TO)) < ROCK_DEG


def table_down(R_TO: RotationMatrix) -> np.ndarray:
    """The table's down direction in the body's frame O, for a body resting as `R_TO` has it."""
    return R_TO.inverse() @ np.array([0.0, 0.0, -1.0])


def degrees_from_upright(down: np.ndarray) -> float:
    """How far (deg) a body whose frame sees the table's down as `down` (unit) is turned from z up."""
    return math.degrees(math.acos(float(np.clip(-down[2], -1.0, 1.0))))


def settle_in_simulator(spec, contact=None, tilt_deg: float = 0.0) -> tuple[RotationMatrix, bool]:
    """Where the body `spec` set down on the station's table as its R_TO has it (turned `tilt_deg` about
    the table's x axis, and raised so that it does not start in the table) comes to rest, in the
    station's own contact model (5 ms, hydroelastic, lagged SAP): (R_TO at rest with its heading
    removed as far as `resting_rotation` allows, whether it came to rest within SETTLE_TIME).

    A quasi-static roll knows nothing of momentum or of the compliant contact: pybullet's random object
    850 rolls 5° quasi-statically and stops on a base 1° wide, and in the simulator it falls 46°; 370,
    a 12 cm fin, stands on a base 5° wide and falls flat. The simulator settles them as a trial would,
    before the camera looks."""
    from drake_grasp.objects.drake_model import AddObject  # (objects/__init__ imports this module)
    from drake_grasp.paths import RegisterPackage

    builder = DiagramBuilder()
    # The default scenario's plant (diagrams/station.scenarios.yaml); the station module builds on the
    # objects package, so its scenario is not read here.
    config = MultibodyPlantConfig(time_step=0.005, contact_model="hydroelastic_with_fallback",
                                  discrete_contact_approximation="lagged")
    plant, _ = AddMultibodyPlant(config, builder)
    (table,) = RegisterPackage(Parser(plant)).AddModels(url="package://drake_grasp/table/table.sdf")
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("table_top", table))
    model = AddObject(plant, spec, contact)
    (index,) = plant.GetBodyIndices(model)
    body = plant.get_body(index)
    lift = spec.max_radius * math.sin(math.radians(abs(tilt_deg)))
    plant.SetDefaultFloatingBaseBodyPose(body, RigidTransform(RotationMatrix.MakeXRotation(math.radians(tilt_deg))
                                                              @ spec.R_TO, [0.0, 0.0, spec.rest_height + lift]))
    plant.Finalize()
    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = plant.GetMyContextFromRoot(simulator.get_context())
    rested = advance_to_rest(simulator, body, context)
    R_WO = body.EvalPoseInWorld(context).rotation()
    down_O = R_WO.inverse() @ np.array([0.0, 0.0, -1.0])
    return resting_rotation(down_O), rested


def advance_to_rest(simulator: Simulator, body, plant_context, max_time: float = SETTLE_TIME) -> bool:
    """Advances `simulator` from time 0 in steps of SETTLE_CHECK until `body` (whose plant's context is
    `plant_context`) moves slower than REST_SPEED, looked at from the second step on, or `max_time`
    (s) has passed; returns whether it came to rest."""
    t = 0.0
    while t < max_time - 1e-9:
        t += SETTLE_CHECK
        simulator.AdvanceTo(t)
        velocity = body.EvalSpatialVelocityInWorld(plant_context)
        if t >= 2 * SETTLE_CHECK and max(np.linalg.norm(velocity.rotational()),
                                         np.linalg.norm(velocity.translational())) < REST_SPEED:
            return True
    return False
