"""Adaptive sampling of a capture region, on regions whose area is known exactly."""

import math

import pytest

from drake_grasp.studies.capture_region import ErrorAxis, Quadtree

PLANE = Quadtree(ErrorAxis("across", "cm", -4.0, 4.0), ErrorAxis("yaw", "deg", -30.0, 30.0), base=4, depth=3)


def sample(tree: Quadtree, succeeds) -> dict:
    """Runs the sampling loop to the end with `succeeds(x, y)` standing in for trials."""
    results = {}
    while points := tree.next_points(results):
        results.update({p: succeeds(*tree.value(p)) for p in points})
    return results


def ellipse(x, y, a=2.5, b=18.0, cx=0.5, cy=-3.0):
    return ((x - cx) / a) ** 2 + ((y - cy) / b) ** 2 <= 1.0


def test_an_ellipse_is_bracketed_and_estimated_closely_with_few_trials():
    results = sample(PLANE, ellipse)
    area = PLANE.area(results)
    true = math.pi * 2.5 * 18.0
    assert area.lower <= true <= area.upper
    assert area.estimate == pytest.approx(true, rel=0.08)
    uniform = (PLANE.resolution + 1) ** 2  # 33 x 33 trials for the same finest resolution
    assert area.trials < 0.5 * uniform
    assert area.total == pytest.approx(8.0 * 60.0)


def test_trials_concentrate_on_the_boundary():
    results = sample(PLANE, ellipse)
    finest = [p for p in results if p[0] % 2 or p[1] % 2]  # points only the last level adds
    assert finest
    cell_diagonal = math.hypot(8.0 / 32, 60.0 / 32)
    for p in finest:  # each lies within a coarse cell's reach of the true boundary
        x, y = PLANE.value(p)
        r = math.hypot((x - 0.5) / 2.5, (y + 3.0) / 18.0)
        assert abs(r - 1.0) < 4 * cell_diagonal / 2.5


def test_uniform_planes_need_only_the_base_grid():
    for value, fraction in ((True, 1.0), (False, 0.0)):
        results = sample(PLANE, lambda x, y: value)
        area = PLANE.area(results)
        assert area.trials == (PLANE.base + 1) ** 2
        assert area.fraction == fraction and area.lower == area.estimate == area.upper


def test_sampling_is_deterministic_and_resumable():
    first = sample(PLANE, ellipse)
    partial = dict(list(first.items())[: len(first) // 3])
    resumed = dict(partial)
    while points := PLANE.next_points(resumed):
        resumed.update({p: ellipse(*PLANE.value(p)) for p in points})
    assert resumed == first


def test_incomplete_results_are_not_summarised():
    with pytest.raises(ValueError):
        PLANE.area({})


def test_bad_axes_are_rejected():
    with pytest.raises(ValueError):
        ErrorAxis("yaw", "deg", 10.0, -10.0)
    with pytest.raises(ValueError):
        Quadtree(PLANE.x, PLANE.y, base=0)
