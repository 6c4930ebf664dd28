"""Wilson score intervals: the values every report's success rates carry."""

import math

import pytest

from drake_grasp.sweeps.stats import format_rate, wilson_interval


def test_wilson_matches_published_values():
    # Brown, Cai & DasGupta (2001) and any statistics package: 8/10 at 95 % -> [0.490, 0.943].
    lo, hi = wilson_interval(8, 10)
    assert lo == pytest.approx(0.4902, abs=1e-4)
    assert hi == pytest.approx(0.9433, abs=1e-4)


def test_wilson_ends_are_exact_and_never_empty():
    assert wilson_interval(10, 10)[1] == 1.0
    assert wilson_interval(10, 10)[0] == pytest.approx(0.7225, abs=1e-4)  # 10/10 does not mean 100 %
    assert wilson_interval(0, 10)[0] == 0.0
    assert wilson_interval(0, 10)[1] == pytest.approx(0.2775, abs=1e-4)
    for n in (1, 2, 5, 30):
        for k in range(n + 1):
            lo, hi = wilson_interval(k, n)
            assert 0.0 <= lo < k / n + 1e-12 or k == 0
            assert lo <= k / n <= hi <= 1.0
            assert hi - lo > 0.0


def test_wilson_narrows_with_more_trials():
    widths = [wilson_interval(n // 2, n)[1] - wilson_interval(n // 2, n)[0] for n in (10, 100, 1000)]
    assert widths[0] > widths[1] > widths[2]


def test_wilson_rejects_impossible_counts():
    with pytest.raises(ValueError):
        wilson_interval(11, 10)
    with pytest.raises(ValueError):
        wilson_interval(-1, 10)
    with pytest.raises(ValueError):
        wilson_interval(1, 10, confidence=1.0)
    assert all(math.isnan(v) for v in wilson_interval(0, 0))


def test_format_rate():
    assert format_rate(9, 10) == "90 % (9/10, 95 % CI 60-98 %)"
    assert format_rate(0, 0) == "n/a"


def test_short_rate_and_error_bars():
    from drake_grasp.sweeps.stats import error_bars, short_rate

    assert short_rate(9, 10).startswith("90 % (9/10; ") and short_rate(0, 0) == "n/a"
    heights, (below, above) = error_bars([(10, 10), (0, 4), (0, 0)])
    assert heights == [100.0, 0.0, 0.0]
    assert above[0] == 0.0 and below[0] > 20.0  # 10/10: the interval reaches down to ~72 %
    assert below[1] == 0.0 and above[1] > 40.0  # 0/4: up to ~49 %
    assert below[2] == above[2] == 0.0
