"""Fig. 4 of the paper: validating the sun-flower-annulus picture with quasi-static grasps.

For spheres (spherical mode, palm centre aimed at the sphere centre), cubes and cylinders
(cylindrical mode, hand aligned with the object's axes, fingers closing along the object's y) of
growing size, the hand starts above the object with a position error along x or along y, approaches
along its palm normal until the first contact, closes with breakaway (`drake_grasp.quasistatic`),
and the grasp is scored with the ε metric (`drake_grasp.quality`). The objects float in free space
(no table), as in the paper's quasi-static simulation.

Cylinders lie along the object's x with a fixed length of 0.30 m (`objects.CYLINDER_FAMILY_LENGTH`),
so an error along x runs along the axis and an error along y across it.

The flower (beyond the paper's figure, which stops at the annulus): plates lying flat on a table
(`objects.plate_object`: an 8 × 5 cm footprint, 4-40 mm thick, the thickness as their size), grasped
with the palm held by position over the centre (cylindrical mode, the fingertips' deepest sweep 2 mm
above the table: the precision grasp that the flower grasp replaced; the quasi-static hand does not
model the flower grasp's compliant arm) with the same position errors. They rest on the
table, which stops the fingers like the object does; only contacts with the object count in ε.

The sweep is resumable: each (shape, size) is one task, whose rows are appended to ``fig4.csv`` as
soon as it finishes, each with the fingerprint of the sweep's settings (`Fig4Config.fingerprint`); a
rerun computes only what is missing for the current fingerprint.

The experiment:
    objects: spheres, cubes and cylinders (0.30 m long), 2-34 cm (`Fig4Config`: 27 sizes; --quick 9),
        floating in free space; plates 4-40 mm thick on a table (10 thicknesses; --quick 4);
    grasps: the spherical mode for spheres, the cylindrical mode for cubes and cylinders, the precision
        grasp for plates, quasi-static, with a hand position error along x or y (-6 to 6 cm: 21
        errors; --quick 7);
    seeds: none (quasi-static and deterministic);
    writes: fig4.csv (one row per shape, size, axis and error), fig4.png and fig4.svg.
"""

import contextlib
import dataclasses
import math
import pathlib
import sys
import time

import numpy as np

from drake_grasp.sweeps.results import save_figure

FIELDS = [
    "fingerprint", "shape", "size", "axis", "error", "epsilon", "volume", "num_contacts", "fingers_touching",
    "palm_touching", "links", "approach_distance", "spread", "proximal_1", "proximal_2", "proximal_3",
    "distal_1", "distal_2", "distal_3",
]
KEY = ["fingerprint", "shape", "size", "axis", "error"]
TYPES = {"fingerprint": "hex", "num_contacts": "int", "fingers_touching": "int", "palm_touching": "int",
         **{name: "float" for name in ("size", "error", "epsilon", "volume", "approach_distance", "spread",
                                       "proximal_1", "proximal_2", "proximal_3", "distal_1", "distal_2", "distal_3")}}
SHAPES = ("sphere", "cube", "cylinder", "plate")
FLOWER = "plate"  # the family on a table, with the precision grasp
AXES = ("x", "y")


@dataclasses.dataclass
class Fig4Config:
    """The sweep. Sizes in m (sphere and cylinder diameter, cube edge), errors in m.

    Attributes:
        sizes: object sizes, from a few cm to past the hand's envelope (~0.30 m).
        errors: hand position errors, applied along x and along y.
        friction: μ of the ε metric (docs/design.md §4.4: 0.5).
        num_edges: friction-cone edges of the ε metric (docs/design.md §4.5: 8).
        start_clearance: the palm starts this far from the object's top before the approach, m.
        thicknesses: the flower's plate thicknesses, m (its sizes; none: the paper's three families only).
    """

    sizes: list[float]
    errors: list[float]
    thicknesses: list[float] = dataclasses.field(default_factory=list)
    friction: float = 0.5
    num_edges: int = 8
    start_clearance: float = 0.10

    def fingerprint(self) -> str:
        """The fingerprint of what decides a row besides its key (shape, size, axis, error): the ε
        metric's friction and cone edges, the start clearance, and the package version."""
        from drake_grasp.sweeps.fingerprint import sweep_fingerprint

        return sweep_fingerprint("fig4", self.friction, self.num_edges, self.start_clearance)

    @classmethod
    def full(cls) -> "Fig4Config":
        # 27 sizes, 2 cm to 34 cm; 21 errors, -6 cm to 6 cm every 6 mm.
        return cls(sizes=[round(s, 4) for s in np.linspace(0.02, 0.34, 27)],
                   errors=[round(e, 4) + 0.0 for e in np.linspace(-0.06, 0.06, 21)],
                   thicknesses=[round(t, 4) for t in np.linspace(0.004, 0.04, 10)])

    @classmethod
    def quick(cls) -> "Fig4Config":
        # 9 sizes, 2 cm to 34 cm; 7 errors, -6 cm to 6 cm every 2 cm.
        return cls(sizes=[round(s, 4) for s in np.linspace(0.02, 0.34, 9)],
                   errors=[round(e, 4) + 0.0 for e in np.linspace(-0.06, 0.06, 7)],
                   thicknesses=[0.006, 0.012, 0.02, 0.04])

    def sizes_of(self, shape: str) -> list[float]:
        """The sizes of a family: the plates' thicknesses for the flower, else `sizes`."""
        return self.thicknesses if shape == FLOWER else self.sizes

    def __post_init__(self):
        for name in ("sizes", "errors"):
            values = getattr(self, name)
            if not values or not all(math.isfinite(v) for v in values):
                raise ValueError(f"fig4: {name} must be a non-empty list of finite numbers")
        if min(self.sizes) <= 0 or not all(math.isfinite(t) and t > 0 for t in self.thicknesses):
            raise ValueError("fig4: sizes and thicknesses must be positive")
        if not (self.friction >= 0 and math.isfinite(self.friction)):
            raise ValueError(f"fig4: friction must be >= 0, got {self.friction}")


def make_object(shape: str, size: float):
    """The Fig. 4 object of a shape family and size, and the compliance mode used on it."""
    from drake_grasp.robot.hand import ComplianceMode
    from drake_grasp.objects import cube_object, cylinder_object, sphere_object
    from drake_grasp.objects.catalogue import plate_object

    if shape == "sphere":
        return sphere_object(size), ComplianceMode.SPHERICAL
    if shape == "cube":
        return cube_object(size), ComplianceMode.CYLINDRICAL
    if shape == "cylinder":
        return cylinder_object(size), ComplianceMode.CYLINDRICAL
    if shape == FLOWER:
        return plate_object(size), ComplianceMode.CYLINDRICAL
    raise ValueError(f"fig4: unknown shape '{shape}' (choose from {', '.join(SHAPES)})")


def hand_start_pose(spec, axis: str, error: float, clearance: float):
    """X_OH: the hand base above the object, palm normal down (-z_O), hand y along the object's y,
    offset by `error` along the object's x or y, the palm `clearance` above the object's top."""
    from pydrake.math import RigidTransform, RotationMatrix

    from drake_grasp.robot import hand

    offset = np.zeros(3)
    offset["xy".index(axis)] = error
    top = spec.extents[2] / 2
    # RotX(pi): hand x = object x, hand y = -object y, hand z (palm normal) = -object z.
    R_OH = RotationMatrix.MakeXRotation(math.pi)
    p_OH = offset + [0.0, 0.0, top + clearance + hand.PALM_HEIGHT]
    return RigidTransform(R_OH, p_OH)


# Fig. 4's flower palm height: the fingertips' deepest sweep this far above the table, m. The
# quasi-static hand holds the palm by position, so the figure keeps the palm-held sweep of the
# precision grasp that the flower grasp replaced (docs/design.md §5.4b); the flower grasp's compliant
# arm, which follows the tips down the table, is not modelled here (§5.4f).
POSITION_HELD_CLEARANCE = 0.002


def precision_start_pose(spec, axis: str, error: float, clearance: float):
    """X_OH: the hand base with the palm level over the plate's centre, fingers across its short side,
    at the height where the fingertips' deepest sweep passes POSITION_HELD_CLEARANCE above the table
    (the palm held by position), offset by `error` along the object's x or y and `clearance` back
    along the palm normal."""
    from pydrake.math import RigidTransform

    from drake_grasp.robot import hand
    from drake_grasp.grasps import oracle_estimate, precision_grasp
    from drake_grasp.robot.hand import ComplianceMode

    estimate = oracle_estimate(RigidTransform(), spec)
    X_OP = precision_grasp(estimate).X_WP_target  # its palm orientation and place over the centre
    p = X_OP.translation().copy()
    p[2] = estimate.table_height + hand.fingertip_sweep_depth(ComplianceMode.CYLINDRICAL.spread) + POSITION_HELD_CLEARANCE
    X_OH = RigidTransform(X_OP.rotation(), p) @ RigidTransform([0.0, 0.0, -hand.PALM_HEIGHT - clearance])
    offset = np.zeros(3)
    offset["xy".index(axis)] = error
    return RigidTransform(X_OH.rotation(), X_OH.translation() + offset)


def run_task(shape: str, size: float, config: Fig4Config) -> list[dict]:
    """All grasps of one (shape, size): both axes, every error. Runs in a worker process."""
    from drake_grasp.quality import grasp_quality
    from drake_grasp.quasistatic import QuasiStaticHand

    spec, mode = make_object(shape, size)
    flower = shape == FLOWER
    sim = QuasiStaticHand(spec, table=flower)
    rows = []
    for axis in AXES:
        for error in config.errors:
            if flower:  # to the precision grasp's palm height, or the first touch before it
                X_OH = precision_start_pose(spec, axis, error, config.start_clearance)
                grasp = sim.grasp(X_OH, mode, max_approach=config.start_clearance)
            else:
                X_OH = hand_start_pose(spec, axis, error, config.start_clearance)
                grasp = sim.grasp(X_OH, mode, max_approach=config.start_clearance + spec.extents[2] + 0.2)
            points, normals = grasp.contact_arrays()
            quality = grasp_quality(points, normals, config.friction, np.zeros(3), spec.max_radius,
                                    config.num_edges)
            links = grasp.touching_links
            fingers = sorted({int(l.split("_")[2]) for l in links if l.startswith("bh_finger_")})
            q = grasp.joint_angles
            rows.append({
                "shape": shape, "size": float(size), "axis": axis, "error": float(error),
                "epsilon": float(quality.epsilon), "volume": float(quality.volume),
                "num_contacts": len(links), "fingers_touching": len(fingers),
                "palm_touching": int("bh_base" in links), "links": " ".join(links),
                "approach_distance": float(grasp.approach_distance), "spread": float(q[0]),
                "proximal_1": float(q[2]), "proximal_2": float(q[3]), "proximal_3": float(q[4]),
                "distal_1": float(q[5]), "distal_2": float(q[6]), "distal_3": float(q[7]),
            })
    return rows


def run_fig4(config: Fig4Config, out_dir: pathlib.Path, workers: int | None = None,
             progress=sys.stderr, executor=None) -> list[dict]:
    """Runs (or resumes) the sweep into out_dir/fig4.csv; returns every row as read back.

    Tasks run on `executor` (`executors.make_executor`), or with none on a local executor of
    `workers` processes (default: every core).
    """
    from drake_grasp.sweeps.lock import results_lock

    with results_lock(out_dir):
        return _run_fig4(config, out_dir, workers, progress, executor)


def _run_fig4(config: Fig4Config, out_dir: pathlib.Path, workers, progress, executor) -> list[dict]:
    from drake_grasp.sweeps.executors import LocalExecutor
    from drake_grasp.sweeps.results import ResultsTable

    table = ResultsTable(out_dir / "fig4.csv", FIELDS, KEY, TYPES)
    fingerprint = config.fingerprint()
    tasks = [
        (shape, size, config) for shape in SHAPES for size in config.sizes_of(shape)
        if not all((fingerprint, shape, size, axis, error) in table for axis in AXES for error in config.errors)
    ]
    total = sum(len(config.sizes_of(shape)) for shape in SHAPES)
    done = total - len(tasks)
    if done:
        print(f"fig4: resuming, {done}/{total} (shape, size) tasks already in {table.path}", file=progress)
    executor = executor or LocalExecutor(workers)
    start = time.perf_counter()
    with contextlib.closing(executor.imap_unordered(run_task, tasks)) as results:
        for index, rows in results:
            table.append([dict(row, fingerprint=fingerprint) for row in rows])
            done += 1
            shape, size, _ = tasks[index]
            print(f"fig4: {done}/{total} tasks ({shape} {size * 100:.1f} cm) {time.perf_counter() - start:.0f} s",
                  file=progress)
    wanted = {(s, str(float(z)), a, str(float(e))) for s in SHAPES for z in config.sizes_of(s) for a in AXES
              for e in config.errors}
    return [r for r in table.rows_of(fingerprint) if (r["shape"], r["size"], r["axis"], r["error"]) in wanted]


# --- Analysis. ------------------------------------------------------------------------------------

@dataclasses.dataclass
class ShapeSummary:
    """ε statistics of one shape family, per size (sizes ascending)."""

    shape: str
    sizes: np.ndarray
    errors: np.ndarray
    epsilon: dict  # axis -> array (len(errors), len(sizes))
    fingers: dict  # axis -> array (len(errors), len(sizes)) of fingers touching

    def mean(self, axis: str) -> np.ndarray:
        return self.epsilon[axis].mean(axis=0)

    def max(self, axis: str) -> np.ndarray:
        return self.epsilon[axis].max(axis=0)

    def at_zero(self, axis: str) -> np.ndarray:
        i = int(np.argmin(np.abs(self.errors)))
        return self.epsilon[axis][i]

    def peak_size(self) -> float:
        """The size at which ε_mean (over both axes and all errors) peaks, m."""
        both = (self.mean("x") + self.mean("y")) / 2
        return float(self.sizes[int(np.argmax(both))])


def summarise(rows: list[dict]) -> dict[str, ShapeSummary]:
    """Groups the CSV rows into per-shape grids."""
    out = {}
    for shape in SHAPES:
        mine = [r for r in rows if r["shape"] == shape]
        if not mine:
            continue
        sizes = np.array(sorted({float(r["size"]) for r in mine}))
        errors = np.array(sorted({float(r["error"]) for r in mine}))
        eps, fingers = {}, {}
        for axis in AXES:
            grid = np.full((len(errors), len(sizes)), np.nan)
            fgrid = np.full((len(errors), len(sizes)), np.nan)
            for r in mine:
                if r["axis"] != axis:
                    continue
                i = int(np.searchsorted(errors, float(r["error"])))
                j = int(np.searchsorted(sizes, float(r["size"])))
                grid[i, j] = float(r["epsilon"])
                fgrid[i, j] = float(r["fingers_touching"])
            eps[axis], fingers[axis] = grid, fgrid
        out[shape] = ShapeSummary(shape, sizes, errors, eps, fingers)
    return out


def summary_lines(summaries: dict[str, ShapeSummary], rows: list[dict]) -> list[str]:
    """A short, honest reading of the sweep: per shape the peak of ε_mean and where it falls off,
    and what happens to large cubes."""
    lines = []
    for shape, s in summaries.items():
        if shape == FLOWER:
            lines.append(flower_line(s))
            continue
        both = (s.mean("x") + s.mean("y")) / 2
        peak = int(np.argmax(both))
        below = [j for j in range(peak, len(both)) if both[j] < 0.1 * both[peak]]
        falls = f"falls below 10% of the peak at {s.sizes[below[0]] * 100:.1f} cm" if below else \
            "stays above 10% of the peak up to the largest size"
        lines.append(f"{shape}: eps_mean peaks at {s.sizes[peak] * 100:.1f} cm ({both[peak]:.3f}) and {falls}")
    cube = summaries.get("cube")
    if cube is not None:
        both = (cube.mean("x") + cube.mean("y")) / 2
        peak = int(np.argmax(both))
        large_sizes = [z for j, z in enumerate(cube.sizes) if j > peak and both[j] < 0.1 * both[peak]]
        if large_sizes:
            large = [r for r in rows if r["shape"] == "cube" and float(r["size"]) >= large_sizes[0]]
            flat = np.mean([all(abs(float(r[f"proximal_{f}"])) < 1e-6 for f in (1, 2, 3)) for r in large])
            two = np.mean([int(r["fingers_touching"]) <= 2 for r in large])
            lines.append(
                f"large cubes (>= {large_sizes[0] * 100:.1f} cm): in {100 * flat:.0f}% of grasps the open "
                "proximal links land flat on the top face and break away at 0 deg, so the distal links "
                f"close beside the cube; {100 * two:.0f}% touch with two fingers or fewer"
            )
    return lines


def flower_line(s: ShapeSummary) -> str:
    """The flower's reading: the thinnest plate the precision grasp holds with any ε at all, and where."""
    both = (s.mean("x") + s.mean("y")) / 2
    held = [j for j in range(len(both)) if both[j] > 0]
    if not held:
        return (f"plates ({s.sizes[0] * 1000:.0f}-{s.sizes[-1] * 1000:.0f} mm thick, precision grasp): eps = 0 at "
                "every thickness and error")
    j = held[0]
    errors = sorted({round(float(e) * 100, 1) for axis in AXES for i, e in enumerate(s.errors)
                     if s.epsilon[axis][i, j] > 0})
    return (f"plates (precision grasp): eps = 0 for every error below {s.sizes[j] * 1000:.0f} mm thick; from "
            f"{s.sizes[j] * 1000:.0f} mm eps_mean {both[j]:.3f} (eps > 0 for errors {errors[0]:g} to {errors[-1]:g} cm); "
            f"at {s.sizes[-1] * 1000:.0f} mm {both[-1]:.3f}")


def plot(summaries: dict[str, ShapeSummary], out_dir: pathlib.Path) -> list[pathlib.Path]:
    """Fig. 4's layout: per shape and error axis, a colour map of ε over (size, error), and under it
    ε_mean, ε_max and ε_0 against size. Writes fig4.png and fig4.svg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    columns = [(shape, axis) for shape in summaries for axis in AXES]
    vmax = max(float(np.nanmax(s.epsilon[a])) for s in summaries.values() for a in AXES) or 1.0
    fig, axes = plt.subplots(2, len(columns), figsize=(3.0 * len(columns), 6.0), squeeze=False,
                             gridspec_kw={"height_ratios": [1.2, 1.0]})
    image = None
    for c, (shape, axis) in enumerate(columns):
        s = summaries[shape]
        sizes_cm, errors_cm = s.sizes * 100, s.errors * 100
        top, bottom = axes[0][c], axes[1][c]
        image = top.imshow(
            s.epsilon[axis], origin="lower", aspect="auto", cmap="viridis", vmin=0, vmax=vmax,
            extent=[sizes_cm[0], sizes_cm[-1], errors_cm[0], errors_cm[-1]], interpolation="nearest",
        )
        size_label = "thickness (cm)" if shape == FLOWER else "size (cm)"
        top.set_title(f"{shape}{' (precision)' if shape == FLOWER else ''},\nerror along {axis}", fontsize=9)
        top.set_xlabel(size_label)
        if c == 0:
            top.set_ylabel("pose error (cm)")
        bottom.plot(sizes_cm, s.mean(axis), "-o", ms=3, label="ε mean")
        bottom.plot(sizes_cm, s.max(axis), "-^", ms=3, label="ε max")
        bottom.plot(sizes_cm, s.at_zero(axis), "-s", ms=3, label="ε at 0 error")
        bottom.set_xlabel(size_label)
        bottom.set_ylim(0, vmax * 1.05)
        bottom.grid(alpha=0.3)
        if c == 0:
            bottom.set_ylabel("ε")
            bottom.legend(fontsize=7)
    fig.colorbar(image, ax=[axes[0][c] for c in range(len(columns))], label="ε", shrink=0.9)
    fig.suptitle("Fig. 4: quasi-static grasps with breakaway, ε (L1) over object size and hand pose error")
    paths = save_figure(fig, out_dir, "fig4", dpi=110)
    plt.close(fig)
    return paths
