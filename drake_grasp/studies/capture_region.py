"""Capture regions: the set of estimate errors a grasp still succeeds from, sampled where it matters.

The paper measures the hand's tolerance to pose error quasi-statically (Fig. 4). In full dynamics each
sample is a whole trial (seconds of simulation), so a uniform grid fine enough to locate the edge of
the region wastes most of its trials deep inside or far outside it. This module samples a 2-D error
plane adaptively, as a quadtree over the plane:

1. a coarse grid of `base` × `base` cells, every corner a trial;
2. a cell whose four corners disagree (some succeed, some fail) straddles the region's edge: it is
   split into four, and the five new points (centre and edge midpoints) become trials;
3. repeat to `depth` levels. Cells whose corners agree are not refined (the region is assumed not to
   hide an island smaller than a cell there: the base grid sets that scale).

The region's area is then bracketed by the leaves: at least the area of the cells whose corners all
succeed, at most the area of those with any success; the estimate counts each leaf by the fraction of
its corners that succeed. Everything here is pure: points are exact integer coordinates on the finest
grid, so the same results give the same next points (a sweep resumes by recomputing them).
"""

import dataclasses
import itertools
import math


@dataclasses.dataclass(frozen=True)
class ErrorAxis:
    """One axis of the error plane: its name, unit (for labels and areas) and range."""

    name: str
    unit: str
    lo: float
    hi: float

    def __post_init__(self):
        if not (math.isfinite(self.lo) and math.isfinite(self.hi) and self.hi > self.lo):
            raise ValueError(f"error axis {self.name}: need lo < hi, got [{self.lo}, {self.hi}]")


@dataclasses.dataclass(frozen=True)
class Quadtree:
    """The sampling scheme of a plane.

    Attributes:
        x, y: the plane's axes.
        base: cells per side of the coarse grid.
        depth: refinement levels below it (the finest cell is 1 / (base · 2^depth) of a side).
    """

    x: ErrorAxis
    y: ErrorAxis
    base: int = 4
    depth: int = 2

    def __post_init__(self):
        if self.base < 1 or self.depth < 0:
            raise ValueError(f"need base >= 1 and depth >= 0, got {self.base}, {self.depth}")

    @property
    def resolution(self) -> int:
        """Finest-grid intervals per side: every point is an integer pair in [0, resolution]²."""
        return self.base * 2**self.depth

    def value(self, point: tuple[int, int]) -> tuple[float, float]:
        """The errors (x, y) of a grid point, in the axes' units."""
        n = self.resolution
        a, b = point
        return (self.x.lo + (self.x.hi - self.x.lo) * a / n, self.y.lo + (self.y.hi - self.y.lo) * b / n)

    def cell_area(self, size: int) -> float:
        """The area of a cell `size` finest intervals wide, in x-unit × y-unit."""
        n = self.resolution
        return (self.x.hi - self.x.lo) * (self.y.hi - self.y.lo) * (size / n) ** 2

    def base_points(self) -> list[tuple[int, int]]:
        step = 2**self.depth
        return [(i * step, j * step) for i in range(self.base + 1) for j in range(self.base + 1)]

    def leaves(self, results: dict) -> list[tuple[tuple[int, int], int]]:
        """The quadtree's leaf cells given the `results` so far ({point: success}); each is (corner,
        size), the corner its lowest (x, y) point. A cell is split while its corners are all known and
        disagree and it is above the finest level."""
        step = 2**self.depth
        stack = [((i * step, j * step), step) for i in range(self.base) for j in range(self.base)]
        leaves = []
        while stack:
            corner, size = stack.pop()
            outcomes = [results.get(p) for p in _corners(corner, size)]
            if size > 1 and None not in outcomes and len(set(outcomes)) > 1:
                half = size // 2
                stack += [((corner[0] + dx, corner[1] + dy), half) for dx in (0, half) for dy in (0, half)]
            else:
                leaves.append((corner, size))
        return sorted(leaves)

    def next_points(self, results: dict) -> list[tuple[int, int]]:
        """The points still to run: those of the base grid, then the corners of every leaf that the
        current results have not measured (the children of the cells just split)."""
        wanted = set(self.base_points())
        for corner, size in self.leaves(results):
            wanted.update(_corners(corner, size))
        return sorted(p for p in wanted if p not in results)

    def area(self, results: dict) -> "RegionArea":
        """The capture region's area from complete results (no next points left)."""
        missing = self.next_points(results)
        if missing:
            raise ValueError(f"{len(missing)} points of the quadtree are not measured yet")
        lower = upper = estimate = 0.0
        for corner, size in self.leaves(results):
            successes = sum(bool(results[p]) for p in _corners(corner, size))
            cell = self.cell_area(size)
            lower += cell if successes == 4 else 0.0
            upper += cell if successes > 0 else 0.0
            estimate += cell * successes / 4.0
        total = self.cell_area(self.resolution)
        return RegionArea(estimate, lower, upper, total, len(results))


@dataclasses.dataclass(frozen=True)
class RegionArea:
    """A capture region's area (x-unit × y-unit): estimate within [lower, upper], of `total`, from
    `trials` trials."""

    estimate: float
    lower: float
    upper: float
    total: float
    trials: int

    @property
    def fraction(self) -> float:
        return self.estimate / self.total


def _corners(corner: tuple[int, int], size: int) -> list[tuple[int, int]]:
    a, b = corner
    return [(a + dx, b + dy) for dx, dy in itertools.product((0, size), (0, size))]
