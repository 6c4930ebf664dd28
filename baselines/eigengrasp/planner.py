"""GraspIt!'s Eigengrasp planner: annealing over hand pose and posture, then autograsp and ε.

The loop (src/EGPlanner/simAnnPlanner.cpp, simAnn.cpp, egPlanner.cpp; docs/design.md §4.6):

1. Start from the reset state (palm 350 mm along the object's z, hand open) with energy 1e8.
2. At step k, draw a neighbour of the current state at temperature T(k) (annealing.py); if the hand
   then penetrates the object, draw again, up to 11 tries; if all collide the iteration fails and
   k does not advance. Otherwise evaluate the energy (energy.py) of the neighbour, accept it by
   GraspIt!'s rule, and advance k. Stop when k reaches the step limit (default 70,000, i.e. 40,000
   iterations from k = 30,000).
3. After an accepted move whose energy is below the worst of the best list (or below 1e5 while the
   list holds fewer than 20), add the state to the list unless a listed state within distance 0.2
   (search_space.state_distance) has a lower energy; listed states within 0.2 with a higher energy
   are dropped. Keep the 20 lowest.
4. Close every listed state with autograsp: the quasi-static closing with breakaway of
   drake_grasp.quasistatic (spread fixed, fingers closing from the planned posture, no approach),
   and score its contacts with the ε metric (drake_grasp.quality; friction of the hand–object
   contact, torques scaled by the object's max radius). Rank by ε, then by hull volume, then by
   energy; the three best are the plan.

The planner gets the exact object model, in its own frame O (the object's centre of mass).
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
from pydrake.math import RigidTransform

from baselines.eigengrasp import annealing, energy, eigengrasps, search_space
from baselines.eigengrasp.scene import HandObjectScene
from baselines.eigengrasp.virtual_contacts import FRICTION, contact_frames_for_posture
from drake_grasp.robot import hand
from drake_grasp.robot.contact import ContactParameters
from drake_grasp.objects import ObjectSpec
from drake_grasp.quality import friction_cone_edges, grasp_quality
from drake_grasp.quasistatic import Contact, QuasiStaticHand

NUM_PLANNED_GRASPS = 3  # the paper executes the three best grasps (its Sec. 6; docs/design.md §4.6).
# Stop annealing when this many iterations in a row found no legal neighbour (GraspIt! has no
# such guard and would spin; it never triggers in practice, as a legal state has legal neighbours).
MAX_CONSECUTIVE_FAILURES = 10_000


@dataclasses.dataclass
class PlannedGrasp:
    """One grasp of the plan.

    Attributes:
        X_OH: Hand base pose in the object frame O (autograsp closes in place, so it holds before
            and after closing).
        state: The annealed state (search_space order: Tx, Ty, Tz in m, θ, φ, α in rad, a0, a1).
        pregrasp_joint_angles: (8,) joint angles of the planned posture, controller order, rad.
        joint_angles: (8,) joint angles after autograsp, rad.
        energy: The state's annealing energy (GraspIt!'s units: mm for ``contact``).
        epsilon: ε of the grasp after autograsp (dimensionless, docs/design.md §4.5).
        volume: Volume of its grasp wrench space (dimensionless).
        contacts: The hand's contacts after autograsp.
        step: The step counter k at which the state was found.
    """

    X_OH: RigidTransform
    state: np.ndarray
    pregrasp_joint_angles: np.ndarray
    joint_angles: np.ndarray
    energy: float
    epsilon: float
    volume: float
    contacts: list[Contact]
    step: int

    @property
    def touching_links(self) -> list[str]:
        """Hand links touching the object after autograsp."""
        return [c.link for c in self.contacts]

    @property
    def fingers_touching(self) -> list[int]:
        """Fingers (1, 2, 3) with at least one link touching the object after autograsp."""
        return sorted({int(link.split("_")[2]) for link in self.touching_links if link.startswith("bh_finger")})

    @property
    def palm_touching(self) -> bool:
        """Whether the palm touches the object after autograsp."""
        return "bh_base" in self.touching_links

    def to_dict(self) -> dict:
        """Plain data: pose as position (mm) and axis-angle (rad) of the hand base in O."""
        angle_axis = self.X_OH.rotation().ToAngleAxis()
        return {
            "position_mm": (self.X_OH.translation() * 1000.0).tolist(),
            "axis": np.asarray(angle_axis.axis()).tolist(),
            "angle_rad": float(angle_axis.angle()),
            "X_OH": self.X_OH.GetAsMatrix4().tolist(),
            "state": np.asarray(self.state).tolist(),
            "pregrasp_joint_angles": np.asarray(self.pregrasp_joint_angles).tolist(),
            "joint_angles": np.asarray(self.joint_angles).tolist(),
            "joint_names": list(hand.HAND_JOINTS.all),
            "energy": self.energy,
            "epsilon": self.epsilon,
            "volume": self.volume,
            "force_closure": self.epsilon > 0.0,
            "touching_links": self.touching_links,
            "fingers_touching": self.fingers_touching,
            "step": self.step,
        }


@dataclasses.dataclass
class EigengraspPlan:
    """The result of one planner run.

    Attributes:
        object_name: The object planned for.
        energy_name: "contact" or "contact-quality".
        seed: Seed of the random generator.
        max_steps: GraspIt!'s step limit (the counter starts at annealing.K0).
        iterations: Annealing iterations run (steps that advanced k).
        failed_iterations: Iterations whose 11 neighbour tries all collided (k did not advance).
        evaluations: Neighbours drawn and checked for collision.
        collisions: Of those, how many collided.
        grasps: The best grasps, best first (up to three).
        candidates: Every autograsped state of the best list, ranked.
        annealing_time: Wall time of the annealing, s.
        annealing_cpu_time: CPU time of this process during the annealing, s.
        autograsp_time: Wall time of closing and scoring the best list, s.
        setup_time: Wall time of building the Drake models, s.
    """

    object_name: str
    energy_name: str
    seed: int
    max_steps: int
    iterations: int
    failed_iterations: int
    evaluations: int
    collisions: int
    grasps: list[PlannedGrasp]
    candidates: list[PlannedGrasp]
    annealing_time: float
    annealing_cpu_time: float
    autograsp_time: float
    setup_time: float

    @property
    def planning_time(self) -> float:
        """Annealing plus autograsp, s (the models are built once per object, not per plan)."""
        return self.annealing_time + self.autograsp_time

    @property
    def steps_per_second(self) -> float:
        """Annealing iterations per second of annealing."""
        return self.iterations / self.annealing_time if self.annealing_time > 0 else math.inf

    def to_dict(self) -> dict:
        return {
            "object": self.object_name, "energy": self.energy_name, "seed": self.seed,
            "max_steps": self.max_steps, "first_step": annealing.K0, "iterations": self.iterations,
            "failed_iterations": self.failed_iterations, "evaluations": self.evaluations,
            "collisions": self.collisions, "annealing_time": self.annealing_time,
            "annealing_cpu_time": self.annealing_cpu_time,
            "autograsp_time": self.autograsp_time, "planning_time": self.planning_time,
            "setup_time": self.setup_time, "steps_per_second": self.steps_per_second,
            "grasps": [g.to_dict() for g in self.grasps],
            "candidates": [g.to_dict() for g in self.candidates],
        }


class EigengraspPlanner:
    """The planner for one object; build once, plan as often as needed."""

    def __init__(self, spec: ObjectSpec, energy_name: str = "contact", contact: ContactParameters | None = None,
                 table: bool = False):
        """
        Args:
            spec: The object (exact model, planned in its frame O).
            energy_name: "contact" or "contact-quality" (energy.ENERGIES).
            contact: Contact parameters; the hand–object friction for ε is ``spec.friction`` if set,
                else ``contact.friction``.

        Raises:
            ValueError: Unknown energy name.
        """
        if energy_name not in energy.ENERGIES:
            raise ValueError(f"unknown energy {energy_name!r} (choose from {', '.join(energy.ENERGIES)})")
        start = time.perf_counter()
        self.spec = spec
        self.energy_name = energy_name
        self._contact = contact or ContactParameters()
        self.friction = spec.friction if spec.friction is not None else self._contact.friction
        self.table = table
        self.scene = HandObjectScene(spec, self._contact, table=table)
        self._quasistatic: QuasiStaticHand | None = None
        self._posture_key = None
        self._posture_frames = None
        self._posture_cones = None
        self.setup_time = time.perf_counter() - start

    # --- The energy of a state (the inner loop). --------------------------------------------------

    def _contact_frames(self, spread: float, flex: float, distal: float):
        """The virtual contacts in the hand frame for a posture, cached while it repeats."""
        key = (spread, flex)
        if key != self._posture_key:
            self._posture_key = key
            self._posture_frames = contact_frames_for_posture(spread, flex, distal)
            self._posture_cones = None
        return self._posture_frames

    def _cone_edges(self) -> np.ndarray:
        """Friction-cone edges of the contacts in the hand frame, for the posture last set."""
        if self._posture_cones is None:
            self._posture_cones = friction_cone_edges(self._posture_frames[1], FRICTION,
                                                      energy.QUALITY_CONE_EDGES)
        return self._posture_cones

    def evaluate(self, state) -> float | None:
        """The energy of a state, or None when the hand penetrates the object.

        Args:
            state: 8 floats in search_space order (m, rad, amplitudes).
        """
        tx, ty, tz, theta, phi, alpha, a0, a1 = state
        s = math.sin(0.5 * alpha)
        w = math.cos(0.5 * alpha)
        st = s * math.sin(theta)
        x, y, z = st * math.cos(phi), st * math.sin(phi), s * math.cos(theta)
        # p_OH = p_OP − PALM_HEIGHT · z_P, with z_P the third column of R_OP = R_OH.
        h = hand.PALM_HEIGHT
        p_OH = (tx - h * 2.0 * (x * z + w * y), ty - h * 2.0 * (y * z - w * x), tz - h * (1.0 - 2.0 * (x * x + y * y)))
        spread, flex = eigengrasps.spread_and_flex(a0, a1)
        distal = eigengrasps.distal_angle(flex)
        scene = self.scene
        scene.set_configuration((w, x, y, z), p_OH, (spread, spread, flex, flex, flex, distal, distal, distal))
        if scene.in_collision():
            return None
        points_H, normals_H = self._contact_frames(spread, flex, distal)
        xx, yy, zz, xy, xz, yz, wx, wy, wz = x * x, y * y, z * z, x * y, x * z, y * z, w * x, w * y, w * z
        R_T = np.array([[1.0 - 2.0 * (yy + zz), 2.0 * (xy + wz), 2.0 * (xz - wy)],
                        [2.0 * (xy - wz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz + wx)],
                        [2.0 * (xz + wy), 2.0 * (yz - wx), 1.0 - 2.0 * (xx + yy)]])  # R_OH transposed
        points = points_H @ R_T + p_OH
        normals = normals_H @ R_T
        distances, gradients = scene.contact_distances(points)
        # p̂ points from the contact to its closest object point: −gradient outside the object.
        if distances.min() >= 0.0:
            directions = -gradients
        else:
            directions = -gradients * np.where(distances < 0.0, -1.0, 1.0)[:, None]
        if self.energy_name == "contact":
            return energy.contact_energy(normals, distances, directions)
        # The cones are built in the hand frame (they turn with the hand); ε does not depend on the frame.
        return energy.contact_quality_energy(normals, distances, directions, FRICTION, self._cone_edges)

    # --- Annealing. -----------------------------------------------------------------------------

    def anneal(self, max_steps: int = annealing.DEFAULT_MAX_STEPS, seed: int = 0,
               rng: np.random.Generator | None = None) -> dict:
        """Runs the annealing stage.

        Args:
            max_steps: GraspIt!'s step limit; iterations run while k < max_steps, from k = 30,000.
            seed: Seed of ``numpy.random.default_rng`` when no ``rng`` is given.
            rng: The random generator to use (no global state is touched).

        Returns:
            A dict: "best" (list of (energy, state, k), lowest energy first, at most 20; k is the
            step at which the state was reached),
            "iterations", "failed_iterations", "evaluations", "collisions", "time" (wall, s),
            "cpu_time" (this process's CPU time, s).
        """
        max_steps = _check_steps(max_steps)
        uniforms = annealing.UniformStream(rng if rng is not None else np.random.default_rng(seed))
        evaluate, neighbor, temperature = self.evaluate, annealing.neighbor, annealing.temperature
        max_radius = self.spec.max_radius
        current = [float(v) for v in search_space.RESET_STATE]
        current_energy = annealing.INITIAL_ENERGY
        best: list[tuple[float, list[float], int]] = []
        k = annealing.K0
        iterations = failed = evaluations = collisions = consecutive_failures = 0
        start, cpu_start = time.perf_counter(), time.process_time()
        while k < max_steps:
            T = temperature(k)
            T_neighbor = T * annealing.NEIGHBOR_SCALE
            for _ in range(annealing.MAX_NEIGHBOR_TRIES):
                candidate = neighbor(current, T_neighbor, uniforms)
                evaluations += 1
                candidate_energy = evaluate(candidate)
                if candidate_energy is not None:
                    break
                collisions += 1
            else:
                failed += 1
                consecutive_failures += 1
                if consecutive_failures >= MAX_CONSECUTIVE_FAILURES:
                    break
                continue
            consecutive_failures = 0
            # GraspIt! draws U on every iteration and jumps when P > U.
            u = uniforms.next()
            jumped = annealing.acceptance_probability(current_energy, candidate_energy, T) > u
            if jumped:
                current, current_energy = candidate, candidate_energy
            k += 1
            iterations += 1
            if jumped:
                worst = annealing.OPEN_LIST_ENERGY if len(best) < annealing.BEST_LIST_SIZE else best[-1][0]
                if current_energy < worst:
                    pose = search_space.palm_position_and_quaternion(current)
                    _add_unique(best, (current_energy, current, k - 1, pose), max_radius)
        best = [entry[:3] for entry in best]
        return {"best": best, "iterations": iterations, "failed_iterations": failed,
                "evaluations": evaluations, "collisions": collisions,
                "time": time.perf_counter() - start, "cpu_time": time.process_time() - cpu_start}

    # --- Autograsp and ranking. -------------------------------------------------------------------

    @property
    def quasistatic(self) -> QuasiStaticHand:
        """The quasi-static hand used by autograsp (built on first use)."""
        if self._quasistatic is None:
            self._quasistatic = QuasiStaticHand(self.spec, self._contact, table=self.table)
        return self._quasistatic

    def autograsp(self, state, state_energy: float = math.nan, step: int = -1) -> PlannedGrasp:
        """Closes the hand from a state (autograsp with breakaway, spread fixed) and scores it."""
        state = np.asarray(state, dtype=float)
        X_OH = search_space.hand_pose(state)
        q0 = eigengrasps.joint_angles(search_space.amplitudes(state))
        result = self.quasistatic.grasp(X_OH, float(q0[0]), approach=False, start_angles=q0)
        points, normals = result.contact_arrays()
        quality = grasp_quality(points, normals, self.friction, np.zeros(3), self.spec.max_radius)
        return PlannedGrasp(X_OH=result.X_OH, state=state, pregrasp_joint_angles=q0,
                            joint_angles=result.joint_angles, energy=float(state_energy),
                            epsilon=quality.epsilon, volume=quality.volume, contacts=result.contacts,
                            step=int(step))

    def plan(self, max_steps: int = annealing.DEFAULT_MAX_STEPS, seed: int = 0,
             num_grasps: int = NUM_PLANNED_GRASPS) -> EigengraspPlan:
        """Anneals, then autograsps the best list and keeps the ``num_grasps`` best by ε."""
        result = self.anneal(max_steps, seed=seed)
        start = time.perf_counter()
        candidates = [self.autograsp(s, e, k) for e, s, k in result["best"]]
        candidates.sort(key=lambda g: (-g.epsilon, -g.volume, g.energy))
        autograsp_time = time.perf_counter() - start
        return EigengraspPlan(
            object_name=self.spec.name, energy_name=self.energy_name, seed=seed, max_steps=max_steps,
            iterations=result["iterations"], failed_iterations=result["failed_iterations"],
            evaluations=result["evaluations"], collisions=result["collisions"],
            grasps=candidates[:num_grasps], candidates=candidates, annealing_time=result["time"],
            annealing_cpu_time=result["cpu_time"], autograsp_time=autograsp_time, setup_time=self.setup_time)


def _add_unique(best: list, entry: tuple, max_radius: float) -> None:
    """GraspIt!'s addToListOfUniqueSolutions, then sort and trim to the list size.

    Listed states closer than MERGE_DISTANCE with a higher energy are removed as the list is scanned;
    the scan stops at the first close state with a lower or equal energy, and the new state is then
    not added (GraspIt! keeps the removals made before that point).
    """
    energy_new, pose_new = entry[0], entry[3]
    i, add = 0, True
    while i < len(best):
        if search_space.pose_distance(pose_new, best[i][3], max_radius) < annealing.MERGE_DISTANCE:
            if energy_new < best[i][0]:
                del best[i]
                continue
            add = False
            break
        i += 1
    if add:
        best.append(entry)
        best.sort(key=lambda e: e[0])
        del best[annealing.BEST_LIST_SIZE:]


def _check_steps(max_steps) -> int:
    if isinstance(max_steps, bool) or not isinstance(max_steps, (int, np.integer)):
        if isinstance(max_steps, float) and math.isfinite(max_steps) and max_steps.is_integer():
            max_steps = int(max_steps)
        else:
            raise ValueError(f"max_steps must be an integer > {annealing.K0}, got {max_steps!r}")
    if max_steps <= annealing.K0:
        raise ValueError(f"max_steps must be > {annealing.K0} (GraspIt!'s step counter starts at "
                         f"{annealing.K0}; {annealing.DEFAULT_MAX_STEPS} = "
                         f"{annealing.DEFAULT_MAX_STEPS - annealing.K0} iterations), got {max_steps}")
    return int(max_steps)


def plan_eigengrasp(spec: ObjectSpec, max_steps: int = annealing.DEFAULT_MAX_STEPS, seed: int = 0,
                    energy_name: str = "contact", table: bool = False) -> EigengraspPlan:
    """Plans grasps of an object with GraspIt!'s Eigengrasp planner (see the module docstring).

    Args:
        spec: The object.
        max_steps: GraspIt!'s step limit (default 70,000 = 40,000 iterations from k = 30,000).
        seed: Seed of the random generator; the same seed gives the same plan.
        energy_name: "contact" or "contact-quality".
        table: the object rests on a table (its nominal pose): hand states that collide with the
            table are illegal too, and autograsp stops on it — as in a GraspIt! world with the table
            loaded as an obstacle.
    """
    return EigengraspPlanner(spec, energy_name, table=table).plan(max_steps, seed=seed)
