"""Capture regions: how much estimate error a grasp absorbs, measured in full dynamics.

The paper's central claim is that the hand's compliance turns a coarse estimate into a good grasp
(the sun-flower annulus), shown quasi-statically in its Fig. 4. Here each sample is a whole trial:
the grasp is computed from the object's true pose and size (the oracle estimate) with a *known* error
added, executed on the true object by the same arm, controller, timings and success test as every
other trial, and judged. The set of errors from which the grasp still holds is its capture region.

For each object and compliant grasp, errors span planes (`PLANES`):

* ``position``: the estimate's centre moved along and across the object's principal axis, cm;
* ``yaw``: across the axis, cm, against a rotation of the axis about the vertical, deg;
* ``size``: across the axis, cm, against the estimated size scaled by a percentage.

Each plane is sampled adaptively (`capture_region.Quadtree`): a coarse grid first, then cells whose
corners disagree are split, so that trials go to the region's edge rather than deep inside or far
outside it. The region's area is reported with the bracket the samples allow (cells all of whose
corners held, at least; cells with any success, at most).

The compliance-agnostic baseline gets the same errors: the Eigengrasp planner's best grasp the arm can
reach (planned once per object with the exact model, as in Fig. 7) is expressed against the erred
object pose. A planner that is given the exact model has no size estimate, so the ``size`` plane is
for compliant grasps only.

All trials of one round run in parallel; each is written to ``capture.csv`` as it finishes with a
fingerprint that includes its error, so a rerun resumes (the next round's points are a pure function
of the results so far).

The experiment:
    objects: the paper's nine (or --objects);
    grasps: each compliant grasp (or the chosen one) from the true estimate with a known error, and
        the planner's best reachable grasp with an erred object pose;
    seeds: one trial seed for every sample (one placement, the same for all errors); the errors
        are the samples, refined round by round where outcomes change;
    writes: capture.csv (one row per trial), epsilon.csv (static scores), capture.png and
        capture.svg, summary.md and summary.json.
"""

import dataclasses
import json
import math
import pathlib
import re
import sys
import time

from drake_grasp.studies.capture_region import ErrorAxis, Quadtree, RegionArea
from drake_grasp.sweeps.results import save_figure

GRASPS = ("spherical", "cylindrical", "box")
QUICK_OBJECTS = ("soccer_ball", "sponge")
# Each plane's two axes: (name, unit). Their ranges are the study's (`CaptureConfig`).
PLANES = {"position": (("along", "cm"), ("across", "cm")), "yaw": (("across", "cm"), ("yaw", "deg")),
          "size": (("across", "cm"), ("size", "%"))}
METHODS = ("oracle", "eigengrasp")  # the compliant grasp from an erred estimate; the planner's grasp, shifted
EIGENGRASP_PLANES = ("position", "yaw")


def error_of(plane: str, values: tuple[float, float]):
    """A point of a plane (in its axes' units: cm, deg, %) as an `EstimateError` (m, rad, scale)."""
    from drake_grasp.estimate_error import EstimateError

    error = {"along": 0.0, "across": 0.0, "yaw": 0.0, "size_scale": 1.0}
    for (name, unit), value in zip(PLANES[plane], values):
        if unit == "cm":
            error[name] = value / 100.0
        elif unit == "deg":
            error[name] = math.radians(value)
        else:
            error["size_scale"] = 1.0 + value / 100.0
    return EstimateError(**error)


@dataclasses.dataclass
class CaptureConfig:
    """The study.

    Attributes:
        objects: catalogue names, primitives or mesh files.
        grasps: compliant grasps to map per object ("chosen" = the one the object most resembles,
            its closest primitive, as the algorithm would choose with a perfect estimate).
        planes: error planes (`PLANES`).
        methods: "oracle" (compliant grasps) and/or "eigengrasp" (the planner's best reachable grasp).
        offset_cm, yaw_deg, size_pct: the ranges of the position, yaw and size errors.
        base, depth: the quadtree's coarse grid (cells per side) and refinement levels. The default,
            2 x 2 cells refined once, resolves each region to a quarter of its plane's side along its
            edge: the nine objects' full study is 99 maps, about 1,400 trials, about 4 core-hours.
        seed: the trial seed of every sample (one placement of the object, the same for all errors).
        steps, energy: the planner's settings (as Fig. 7).
    """

    objects: tuple[str, ...] = ()
    grasps: tuple[str, ...] = GRASPS
    planes: tuple[str, ...] = tuple(PLANES)
    methods: tuple[str, ...] = METHODS
    offset_cm: tuple[float, float] = (-4.0, 4.0)
    yaw_deg: tuple[float, float] = (-30.0, 30.0)
    size_pct: tuple[float, float] = (-30.0, 30.0)
    base: int = 2
    depth: int = 1
    seed: int = 0
    steps: int = 70_000
    energy: str = "contact-quality"

    @classmethod
    def quick(cls, seed: int = 0) -> "CaptureConfig":
        """Two objects, the grasp each resembles, the position plane, a 2 x 2 grid refined once."""
        return cls(objects=QUICK_OBJECTS, grasps=("chosen",), planes=("position",), base=2, depth=1, seed=seed)

    def __post_init__(self):
        if not self.objects:
            from drake_grasp.objects import PAPER_OBJECTS

            self.objects = PAPER_OBJECTS
        for grasp in self.grasps:
            if grasp not in GRASPS + ("chosen",):
                raise ValueError(f"capture: unknown grasp '{grasp}' (choose from {', '.join(GRASPS)}, chosen)")
        for plane in self.planes:
            if plane not in PLANES:
                raise ValueError(f"capture: unknown plane '{plane}' (choose from {', '.join(PLANES)})")
        for method in self.methods:
            if method not in METHODS:
                raise ValueError(f"capture: unknown method '{method}' (choose from {', '.join(METHODS)})")
        if self.base < 1 or not 0 <= self.depth <= 4:
            raise ValueError(f"capture: need --base >= 1 and 0 <= --depth <= 4, got {self.base}, {self.depth}")

    def axes(self, plane: str) -> tuple[ErrorAxis, ErrorAxis]:
        """A plane's two axes with this study's ranges."""
        ranges = {"cm": self.offset_cm, "deg": self.yaw_deg, "%": self.size_pct}
        return tuple(ErrorAxis(name, unit, *ranges[unit]) for name, unit in PLANES[plane])

    def quadtree(self, plane: str) -> Quadtree:
        return Quadtree(*self.axes(plane), base=self.base, depth=self.depth)


@dataclasses.dataclass(frozen=True)
class Cell:
    """One capture map: an object, a grasp (a compliant grasp, or the planner's label), a plane, a method."""

    object: str
    method: str
    grasp: str
    plane: str


def chosen_grasp(obj: str) -> str:
    """The compliant grasp of an object's closest primitive (what a perfect estimate would choose)."""
    from drake_grasp.objects import resolve_user_object

    return {"sphere": "spherical", "cylinder": "cylindrical", "box": "box"}[resolve_user_object(obj).closest_primitive]


def cells(config: CaptureConfig, planner_label: str) -> list[Cell]:
    """Every map of the study."""
    out = []
    for obj in config.objects:
        grasps = [chosen_grasp(obj) if g == "chosen" else g for g in config.grasps]
        for plane in config.planes:
            if "oracle" in config.methods:
                out += [Cell(obj, "oracle", g, plane) for g in dict.fromkeys(grasps)]
            if "eigengrasp" in config.methods and plane in EIGENGRASP_PLANES:
                out.append(Cell(obj, "eigengrasp", planner_label, plane))
    return out


def _spec(cell: Cell, plane_point, config: CaptureConfig, quadtree: Quadtree, planned: dict | None,
          scenario_file: str, scenario_name: str):
    from drake_grasp.trial import TrialSpec

    error = error_of(cell.plane, quadtree.value(plane_point))
    return TrialSpec(cell.object, cell.method, cell.grasp, config.seed, scenario_file=scenario_file,
                     scenario_name=scenario_name, planned=planned if cell.method == "eigengrasp" else None,
                     estimate_error=error)


@dataclasses.dataclass(frozen=True)
class Trial:
    """One trial of the study: its map, its point in the map's plane, its spec and outcome."""

    cell: Cell
    point: tuple[int, int]
    spec: object  # trial.TrialSpec
    fingerprint: str
    success: bool
    outcome: tuple = ()  # (object, seed, error, final joint angles, lift, slip): what was simulated


def run_capture(config: CaptureConfig, out_dir: pathlib.Path, executor, progress=sys.stderr,
                scenario_file: str = "", scenario_name: str = "default") -> tuple[dict, list[Trial], int]:
    """Runs (or resumes) the study: rounds of trials until every quadtree is complete. Returns
    ({Cell: (Quadtree, {point: success})}, every trial, how many of them were read back from disk)."""
    from drake_grasp.studies import fig7
    from drake_grasp.sweeps.results import check_results_file
    from drake_grasp.sweeps.runner import TRIAL_FIELDS, fingerprints, run_trials, spec_key, trial_table

    csv = out_dir / "capture.csv"  # the caller (`run`) holds the folder's lock
    check_results_file(csv, TRIAL_FIELDS)
    plans = {}
    planner_label = ""
    if "eigengrasp" in config.methods:
        plan_config = fig7.Fig7Config(objects=config.objects, seed=config.seed, steps=config.steps,
                                      energy=config.energy)
        planner_label = f"{plan_config.plan_tag}#1"
        plans = fig7.ensure_plans(out_dir, plan_config, executor, progress, scenario_file, scenario_name,
                                  label="capture")
    maps = {c: (config.quadtree(c.plane), {}) for c in cells(config, planner_label)}
    trials = []
    reused = 0
    for round_number in range(1, config.depth + 2):
        todo = []
        for cell, (tree, results) in maps.items():
            planned = None
            if cell.method == "eigengrasp":
                executed = plans[cell.object]["executed"]
                if not executed:
                    continue  # the arm reaches none of the planner's grasps: no map
                best = executed[0]
                planned = {"X_OH": best["X_OH"], "joint_angles": best["pregrasp_joint_angles"],
                           "epsilon": best["epsilon"], "energy": config.energy,
                           "planner_rank": best["planner_rank"]}
            for point in tree.next_points(results):
                todo.append((cell, point, _spec(cell, point, config, tree, planned, scenario_file,
                                                scenario_name)))
        if not todo:
            break
        specs = [s for _, _, s in todo]
        prints = fingerprints(specs)
        if csv.is_file():
            on_disk = trial_table(csv, read_only=True)
            reused += sum(spec_key(s, f) in on_disk for s, f in zip(specs, prints))
        rows = run_trials(specs, csv, label=f"capture round {round_number}", executor=executor, progress=progress)
        by_key = {(r["fingerprint"], r["object"], r["method"], r["grasp"]): r for r in rows}
        for (cell, point, spec), fingerprint in zip(todo, prints):
            row = by_key[(fingerprint, spec.object, spec.method, spec.grasp)]
            held = str(row["success"]) in ("1", "True")  # as read back from the CSV
            maps[cell][1][point] = held
            outcome = (spec.object, spec.seed, row["variation"], row["finger_angles"], row["lift"],
                       row["slip_distance"])
            trials.append(Trial(cell, point, spec, fingerprint, held, tuple(str(v) for v in outcome)))
    return maps, trials, reused


def areas(maps: dict) -> dict:
    """{Cell: RegionArea} of the complete maps."""
    return {cell: tree.area(results) for cell, (tree, results) in maps.items()
            if results and not tree.next_points(results)}


def summary_lines(maps: dict) -> list[str]:
    """The capture regions as a Markdown table (areas in the plane's units, with their bracket)."""
    lines = ["| object | method | grasp | plane | capture region (estimate, [lower, upper]) | of the plane | trials |",
             "|---|---|---|---|---|---|---|"]
    for cell, area in areas(maps).items():
        x, y = maps[cell][0].x, maps[cell][0].y
        unit = f"{x.unit} x {y.unit}" if x.unit != y.unit else f"{x.unit}²"
        lines.append(f"| {cell.object} | {cell.method} | {cell.grasp} | {cell.plane} ({x.name} x {y.name}) | "
                     f"{area.estimate:.0f} [{area.lower:.0f}, {area.upper:.0f}] {unit} | {100 * area.fraction:.0f} % | "
                     f"{area.trials} |")
    return lines


def plot(maps: dict, out_dir: pathlib.Path) -> list[pathlib.Path]:
    """One figure: a success map per (object, grasp, method) and plane, like Fig. 4 but in full
    dynamics. Each quadtree leaf is shaded by the share of its corners that held; dots are trials
    (filled: held)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    objects = list(dict.fromkeys(c.object for c in maps))
    order = {m: i for i, m in enumerate(METHODS)}
    panels = {o: sorted((c for c in maps if c.object == o), key=lambda c: (order[c.method], c.grasp, c.plane))
              for o in objects}
    if not objects:
        return []
    columns = max(len(p) for p in panels.values())
    fig, axes = plt.subplots(len(objects), columns, figsize=(max(4.5, 2.8 * columns), 2.4 * len(objects) + 0.6),
                             squeeze=False)
    for i, obj in enumerate(objects):
        for j in range(columns):
            ax = axes[i][j]
            if j >= len(panels[obj]):
                ax.set_axis_off()
                continue
            cell = panels[obj][j]
            tree, results = maps[cell]
            x_axis, y_axis = tree.x, tree.y
            dx = (x_axis.hi - x_axis.lo) / tree.resolution
            dy = (y_axis.hi - y_axis.lo) / tree.resolution
            for corner, size in tree.leaves(results):
                outcomes = [results.get((corner[0] + a, corner[1] + b)) for a in (0, size) for b in (0, size)]
                known = [o for o in outcomes if o is not None]
                share = sum(known) / len(known) if known else 0.5
                x0, y0 = tree.value(corner)
                ax.add_patch(Rectangle((x0, y0), dx * size, dy * size, facecolor=plt.cm.RdYlGn(share),
                                       edgecolor="white", linewidth=0.5, alpha=0.8))
            for point, held in results.items():
                x, y = tree.value(point)
                ax.plot(x, y, "o", ms=3, color="black", mfc="black" if held else "white", mew=0.6)
            ax.set_xlim(x_axis.lo, x_axis.hi)
            ax.set_ylim(y_axis.lo, y_axis.hi)
            ax.set_xlabel(f"{x_axis.name} error ({x_axis.unit})", fontsize=7)
            ax.set_ylabel(f"{y_axis.name} error ({y_axis.unit})", fontsize=7)
            ax.tick_params(labelsize=6)
            label = cell.grasp if cell.method == "oracle" else "planner's best"
            ax.set_title(f"{pathlib.Path(obj).stem}, {label}: {cell.plane}", fontsize=7)
    fig.suptitle("Capture regions in full dynamics\n(cell colour: share of its corners that held, green = all; "
                 "dots: trials, filled = held)", fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.5 / (2.4 * len(objects) + 0.6)))
    paths = save_figure(fig, out_dir, "capture", dpi=110)
    plt.close(fig)
    return paths


def distinct_trials(trials: list[Trial]) -> list[Trial]:
    """Each physical trial once. Maps share samples: a point on the common axis (across, with the
    other error zero) is the same error in every plane, hence the same record; and on an object lying
    with its long axis level and a top narrower than the knuckles, the cylindrical and box grasps plan
    the same hand pose, so their trials (two records) simulate the same thing to the last bit. Counting
    such twins twice would narrow the intervals of ε's calibration without new evidence: a trial counts
    once per record (fingerprint, object, method, grasp), and once per simulated outcome (same
    object, seed and estimate error, identical final joint angles, lift and slip; the error is part
    of it because trials that miss the object end alike whatever the error)."""
    seen, distinct = set(), []
    for t in trials:
        record = ("record", t.fingerprint, t.cell.object, t.cell.method, t.cell.grasp)  # a record's key
        keys = {record} | ({("outcome", t.outcome)} if t.outcome else set())
        if keys & seen:
            continue
        seen |= keys
        distinct.append(t)
    return distinct


def epsilon_against_physics(trials: list[Trial], out_dir: pathlib.Path, progress=sys.stderr,
                            replays_per_kind: int = 2) -> list[str]:
    """ε of every distinct trial's hand pose beside its outcome (`epsilon_physics`): scores (cached in
    epsilon.csv), the reliability curve and ROC (epsilon.png, epsilon.json), replays of the first
    disagreements of each kind; returns the summary's lines."""
    from drake_grasp.studies import epsilon_physics

    trials = distinct_trials(trials)
    if not trials:
        return []
    epsilons = epsilon_physics.score_trials([(t.spec, t.fingerprint) for t in trials], out_dir / "epsilon.csv",
                                            progress)
    result = epsilon_physics.calibrate(epsilons, [t.success for t in trials])
    epsilon_physics.plot(result, out_dir)
    epsilon_physics.save(result, out_dir)
    lines = epsilon_physics.summary_lines(result, "every distinct trial of this study, both methods")
    cases = []
    for kind, indices in (("closure_fell", result.closure_fell), ("no_closure_held", result.no_closure_held)):
        for i in indices[:replays_per_kind]:
            t = trials[i]
            x, y = t.point
            label = re.sub(r"[^A-Za-z0-9_.-]", "_", f"{kind}_{pathlib.Path(t.cell.object).stem}_{t.cell.method}_"
                                                     f"{t.cell.plane}_{x}_{y}_{t.fingerprint[:8]}")
            cases.append((label, t.spec, epsilons[i]))
    paths = epsilon_physics.write_replays([(label, spec) for label, spec, _ in cases], out_dir, progress)
    if cases:
        lines += ["", "Replays of disagreements (open in a browser):", ""]
        lines += [f"- [{path.name}](replays/{path.name}): ε = {eps:.3f}" for path, (_, _, eps) in zip(paths, cases)]
    return lines + ["", "![ε against physics](epsilon.png)"]


def write_summary(maps: dict, out_dir: pathlib.Path, config: CaptureConfig, wall_time: float, where: str,
                  epsilon_lines: list[str] = (), reused: int = 0) -> pathlib.Path:
    """summary.md (the table, how it was sampled, ε against physics) and summary.json (areas, for the
    results page)."""
    from drake_grasp.sweeps.results import write_atomically

    trials = sum(len(results) for _, results in maps.values())
    lines = ["# Capture regions in full dynamics", "",
             f"{len(maps)} maps, {trials} samples ({trials - reused} run in {wall_time:.0f} s wall by this run, executor: "
             f"{where}; {reused} read back from capture.csv); seed {config.seed}; "
             f"quadtree: {config.base} x {config.base} coarse cells, {config.depth} refinement levels (a cell whose "
             "corners disagree is split in four).", "",
             "The compliant grasp is computed from the true pose and size with the error added (method `oracle`); "
             "the planner's best reachable grasp is shifted the same way (size errors do not apply to it).", "",
             *summary_lines(maps), "", "![capture regions](capture.png)", ""]
    if epsilon_lines:
        lines += ["## ε against physics", "", *epsilon_lines, ""]
    path = out_dir / "summary.md"
    write_atomically(path, "\n".join(lines))
    data = [dict(dataclasses.asdict(cell), **dataclasses.asdict(area)) for cell, area in areas(maps).items()]
    write_atomically(out_dir / "summary.json", json.dumps(data, indent=1))
    return path


def run(config: CaptureConfig, out_dir: pathlib.Path, executor, progress=sys.stderr,
        scenario_file: str = "", scenario_name: str = "default", epsilon: bool = True,
        replays_per_kind: int = 2) -> tuple[dict, list[str]]:
    """The study end to end: trials, figure, ε against physics (unless `epsilon` is False) with up to
    `replays_per_kind` replays of each kind of disagreement, summary. Returns (maps, summary lines)."""
    from drake_grasp.sweeps.lock import results_lock

    start = time.perf_counter()
    out_dir.mkdir(parents=True, exist_ok=True)
    with results_lock(out_dir):
        maps, trials, reused = run_capture(config, out_dir, executor, progress, scenario_file, scenario_name)
        plot(maps, out_dir)
        epsilon_lines = epsilon_against_physics(trials, out_dir, progress, replays_per_kind) if epsilon else []
        write_summary(maps, out_dir, config, time.perf_counter() - start, executor.describe(), epsilon_lines,
                      reused)
    return maps, summary_lines(maps) + ([""] + epsilon_lines[:1] if epsilon_lines else [])


def region_area_of(row: dict) -> RegionArea:
    """A summary.json entry's area."""
    return RegionArea(row["estimate"], row["lower"], row["upper"], row["total"], row["trials"])
