"""Fig. 4's flower in full dynamics: the flower grasp on plates, sticks and small cubes, over size and
pose error.

The paper's Fig. 4 stops at the annulus; its "flower" (small and flat objects, held at the fingertips)
is drawn but not simulated. The project's flower grasp (`grasps.precision_grasp`, docs/design.md §5.4f)
lands the fingertips on the table with a compliant arm and closes gently while the arm presses down:
its funnel depends on the arm's force, the table and the fingertips sliding along it, which the
quasi-static hand of `studies.fig4` (palm held by position, no arm) does not model. So this part of
Fig. 4 is measured **in full dynamics**: each point is a whole trial, the flower grasp computed from the
object's true pose and size (the oracle estimate) with a known error added (`estimate_error`), executed
by the same arm, controller, timings and success test as every other trial, and judged held or not.

Three flower families, each lying on the table, with one size that grows:

* ``plate``: an 8 × 5 cm plate (`catalogue.PLATE_FAMILY_FOOTPRINT`, as Fig. 4's quasi-static plates),
  its thickness as its size;
* ``stick``: a round stick or pen, 12 cm long, lying along x, its diameter as its size;
* ``cube``: a cube, its edge as its size.

The error is a shift of the estimate along x (the object's long axis: `EstimateError.along`) or along y
(across it), as in the paper's figure. Every point runs at each of `seeds` (each a placement with the
protocol's ±1 cm, ±10° and friction spread, the same for every point), so a map shows the error and the
placement's spread together; the zero error is one trial per seed, shared by both axes.

The sweep is resumable: trials are appended to ``fig4_flower.csv`` (the sweeps' trial table) as they
finish, keyed by their spec's fingerprint, which includes the estimate error.

The experiment:
    objects: plates 6-16 mm thick, sticks 0.9-2.5 cm across, cubes 1.5-4 cm (`FlowerConfig.full`: 5 sizes
        each; --quick 3);
    grasps: the flower grasp (``precision``) from the true estimate shifted along x or y, -3 to 3 cm
        (13 errors; --quick -2 to 2 cm, 5 errors);
    seeds: 1 and 2 (--quick 1);
    writes: fig4_flower.csv (one row per trial), fig4_flower.png and fig4_flower.svg.
"""

from __future__ import annotations

import dataclasses
import math
import pathlib
import sys

import numpy as np

from drake_grasp.sweeps.results import save_figure
from drake_grasp.sweeps.runner import succeeded

FAMILIES = ("plate", "stick", "cube")
AXES = ("x", "y")  # x: along the object's long axis; y: across it
GRASP = "precision"  # the flower grasp (the name of the grasp it replaced, kept in records)
STICK_LENGTH = 0.12  # m: a pen's length (the generated pens are 11-15 cm)
SIZE_NAMES = {"plate": "thickness", "stick": "diameter", "cube": "edge"}


def object_name(family: str, size: float) -> str:
    """The primitive string of a family's object of `size` (m), as a command line names it."""
    from drake_grasp.objects.catalogue import PLATE_FAMILY_FOOTPRINT

    if family == "plate":
        length, width = PLATE_FAMILY_FOOTPRINT
        return f"box:{length:g}x{width:g}x{size:g}"
    if family == "stick":
        return f"cylinder:{size:g}x{STICK_LENGTH:g}"
    if family == "cube":
        return f"cube:{size:g}"
    raise ValueError(f"fig4 flower: unknown family '{family}' (choose from {', '.join(FAMILIES)})")


@dataclasses.dataclass
class FlowerConfig:
    """The sweep. Sizes and errors in m.

    Attributes:
        sizes: per family, its sizes (plate thickness, stick diameter, cube edge).
        errors: estimate errors applied along x and along y.
        seeds: trial seeds; every point runs at each.
    """

    sizes: dict[str, list[float]]
    errors: list[float]
    seeds: tuple[int, ...] = (1,)

    @classmethod
    def full(cls) -> "FlowerConfig":
        return cls(sizes={"plate": [0.006, 0.008, 0.010, 0.012, 0.016],
                          "stick": [0.009, 0.012, 0.016, 0.020, 0.025],
                          "cube": [0.015, 0.020, 0.025, 0.030, 0.040]},
                   errors=[round(e, 4) + 0.0 for e in np.linspace(-0.03, 0.03, 13)], seeds=(1, 2))

    @classmethod
    def quick(cls) -> "FlowerConfig":
        return cls(sizes={"plate": [0.008, 0.012, 0.016], "stick": [0.012, 0.016, 0.020],
                          "cube": [0.020, 0.025, 0.030]},
                   errors=[round(e, 4) + 0.0 for e in np.linspace(-0.02, 0.02, 5)], seeds=(1,))

    def __post_init__(self):
        for family, sizes in self.sizes.items():
            if family not in FAMILIES:
                raise ValueError(f"fig4 flower: unknown family '{family}' (choose from {', '.join(FAMILIES)})")
            if not sizes or not all(math.isfinite(s) and s > 0 for s in sizes):
                raise ValueError(f"fig4 flower: the {family} sizes must be positive numbers")
        if not self.errors or not all(math.isfinite(e) for e in self.errors):
            raise ValueError("fig4 flower: errors must be a non-empty list of finite numbers")
        if not self.seeds:
            raise ValueError("fig4 flower: give at least one seed")


@dataclasses.dataclass(frozen=True)
class Point:
    """One trial of the sweep: a family's size, an error along an axis (the zero error's axis is ""),
    a seed."""

    family: str
    size: float
    axis: str
    error: float
    seed: int


def points(config: FlowerConfig) -> list[Point]:
    """Every trial of the sweep; the zero error once per (family, size, seed), for both axes."""
    out = []
    for family, sizes in config.sizes.items():
        for size in sizes:
            for seed in config.seeds:
                for axis in AXES:
                    out += [Point(family, size, axis, e, seed) for e in config.errors if e != 0]
                if 0 in config.errors:
                    out.append(Point(family, size, "", 0.0, seed))
    return out


def spec_of(point: Point):
    """The trial of a point: the flower grasp from the true estimate with the point's error."""
    from drake_grasp.estimate_error import EstimateError
    from drake_grasp.trial import TrialSpec

    error = EstimateError(along=point.error) if point.axis == "x" else EstimateError(across=point.error)
    return TrialSpec(object_name(point.family, point.size), "oracle", GRASP, point.seed, estimate_error=error)


def run_flower(config: FlowerConfig, out_dir: pathlib.Path, executor=None, workers: int | None = None,
               progress=sys.stderr) -> dict[Point, dict]:
    """Runs (or resumes) the sweep into out_dir/fig4_flower.csv; returns {point: its row as read back}.
    The caller holds the folder's lock (`sweeps.lock.results_lock`)."""
    from drake_grasp.sweeps.runner import fingerprints, run_trials, spec_key

    todo = points(config)
    specs = [spec_of(p) for p in todo]
    rows = run_trials(specs, out_dir / "fig4_flower.csv", workers=workers, progress=progress,
                      label="fig4 flower", executor=executor)
    by_key = {tuple(r[k] for k in ("fingerprint", "object", "method", "grasp", "seed")): r for r in rows}
    return {p: by_key[tuple(str(v) for v in spec_key(s, f))]
            for p, s, f in zip(todo, specs, fingerprints(specs))}


# --- Analysis. ------------------------------------------------------------------------------------

@dataclasses.dataclass
class FamilyMap:
    """A family's outcomes: per axis, the share of seeds held at each (error, size)."""

    family: str
    sizes: np.ndarray  # m, ascending
    errors: np.ndarray  # m, ascending
    share: dict  # axis -> array (len(errors), len(sizes)) of the share of seeds held

    def width(self, axis: str, j: int) -> tuple[float, float] | None:
        """The run of errors around 0 along `axis` held at every seed, for size j: (lowest, highest),
        m; None when the zero error is not held at every seed."""
        column = self.share[axis][:, j]
        i0 = int(np.argmin(np.abs(self.errors)))
        if not column[i0] >= 1.0:
            return None
        lo = hi = i0
        while lo > 0 and column[lo - 1] >= 1.0:
            lo -= 1
        while hi < len(column) - 1 and column[hi + 1] >= 1.0:
            hi += 1
        return float(self.errors[lo]), float(self.errors[hi])


def summarise(results: dict[Point, dict]) -> dict[str, FamilyMap]:
    """The sweep's outcomes as per-family maps."""
    out = {}
    for family in FAMILIES:
        mine = {p: r for p, r in results.items() if p.family == family}
        if not mine:
            continue
        sizes = np.array(sorted({p.size for p in mine}))
        errors = np.array(sorted({p.error for p in mine}))
        share = {}
        for axis in AXES:
            held_count = np.zeros((len(errors), len(sizes)))
            count = np.zeros((len(errors), len(sizes)))
            for p, r in mine.items():
                if p.axis not in (axis, ""):
                    continue
                i, j = int(np.searchsorted(errors, p.error)), int(np.searchsorted(sizes, p.size))
                count[i, j] += 1
                held_count[i, j] += succeeded(r)
            with np.errstate(invalid="ignore"):
                share[axis] = np.where(count > 0, held_count / np.maximum(count, 1), np.nan)
        out[family] = FamilyMap(family, sizes, errors, share)
    return out


def summary_lines(maps: dict[str, FamilyMap], results: dict[Point, dict]) -> list[str]:
    """Per family and size: trials held (with the 95 % interval), and the run of errors around 0 held
    at every seed along x and y."""
    from drake_grasp.sweeps.stats import short_rate

    lines = []
    for family, m in maps.items():
        parts = []
        for j, size in enumerate(m.sizes):
            rows = [r for p, r in results.items() if p.family == family and p.size == size]
            widths = []
            for axis in AXES:
                w = m.width(axis, j)
                widths.append(f"{axis} {w[0] * 100:+g} to {w[1] * 100:+g} cm" if w else f"{axis} none")
            parts.append(f"{size * 1000:g} mm: {short_rate(sum(succeeded(r) for r in rows), len(rows))} held, "
                         f"funnel {', '.join(widths)}")
        lines.append(f"flower, {family}s ({SIZE_NAMES[family]}; full dynamics, the flower grasp): " + "; ".join(parts))
    return lines


def plot(maps: dict[str, FamilyMap], out_dir: pathlib.Path) -> list[pathlib.Path]:
    """Per family and error axis, a map of the share of seeds held over (size, error), and under it the
    share of errors held against size. Writes fig4_flower.png and fig4_flower.svg."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    columns = [(family, axis) for family in maps for axis in AXES]
    fig, axes = plt.subplots(2, len(columns), figsize=(2.8 * len(columns), 5.6), squeeze=False,
                             gridspec_kw={"height_ratios": [1.2, 1.0]})
    image = None
    for c, (family, axis) in enumerate(columns):
        m = maps[family]
        top, bottom = axes[0][c], axes[1][c]
        labels = [f"{s * 1000:g}" for s in m.sizes]
        errors_cm = m.errors * 100
        step = (errors_cm[1] - errors_cm[0]) if len(errors_cm) > 1 else 1.0
        image = top.imshow(m.share[axis], origin="lower", aspect="auto", cmap="RdYlGn", vmin=0, vmax=1,
                           extent=[-0.5, len(m.sizes) - 0.5, errors_cm[0] - step / 2, errors_cm[-1] + step / 2],
                           interpolation="nearest")
        top.set_xticks(range(len(m.sizes)), labels, fontsize=7)
        top.set_title(f"{family}s, error along {axis}", fontsize=9)
        top.set_xlabel(f"{SIZE_NAMES[family]} (mm)", fontsize=8)
        if c == 0:
            top.set_ylabel("pose error (cm)")
        bottom.plot(range(len(m.sizes)), np.nanmean(m.share[axis], axis=0), "-o", ms=3)
        bottom.set_xticks(range(len(m.sizes)), labels, fontsize=7)
        bottom.set_xlabel(f"{SIZE_NAMES[family]} (mm)", fontsize=8)
        bottom.set_ylim(-0.05, 1.05)
        bottom.grid(alpha=0.3)
        if c == 0:
            bottom.set_ylabel("share of errors held")
    fig.colorbar(image, ax=[ax for row in axes for ax in row], label="share of seeds held", shrink=0.6)
    fig.suptitle("Fig. 4's flower in full dynamics: the flower grasp (fingertips landed on the table, compliant "
                 "arm) over object size and pose error", fontsize=9)
    paths = save_figure(fig, out_dir, "fig4_flower", dpi=110)
    plt.close(fig)
    return paths
