"""Success rates with honest uncertainty: the Wilson score interval.

A study reports k successes in n trials. With n of 2 to 30, as here, the normal approximation
p ± z·sqrt(p(1-p)/n) is useless (it gives [1, 1] for 10/10 and can leave [0, 1]); the Wilson score
interval (E. B. Wilson, "Probable inference, the law of succession, and statistical inference",
J. Am. Stat. Assoc. 22(158), 1927) keeps inside [0, 1], is never empty, and covers close to its
nominal level for small n (Brown, Cai & DasGupta, "Interval estimation for a binomial proportion",
Statistical Science 16(2), 2001, recommend it for n < 40).
"""

import math

from scipy.stats import norm

CONFIDENCE = 0.95  # every interval the project reports


def wilson_interval(successes: int, trials: int, confidence: float = CONFIDENCE) -> tuple[float, float]:
    """The Wilson score interval (lo, hi) for a success probability, from `successes` of `trials`.

    Returns (nan, nan) for zero trials (nothing measured, nothing claimed).

    Raises:
        ValueError: successes outside [0, trials], or confidence outside (0, 1).
    """
    if not 0 <= successes <= trials:
        raise ValueError(f"successes must be in [0, {trials}], got {successes}")
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence}")
    if trials == 0:
        return float("nan"), float("nan")
    z = float(norm.ppf(0.5 + confidence / 2.0))
    p = successes / trials
    denominator = 1.0 + z * z / trials
    centre = (p + z * z / (2.0 * trials)) / denominator
    half = z * math.sqrt(p * (1.0 - p) / trials + z * z / (4.0 * trials * trials)) / denominator
    # Exactly 0 and 1 at the ends (rounding would otherwise leave 1e-17 outside [0, 1]).
    lo = 0.0 if successes == 0 else max(0.0, centre - half)
    hi = 1.0 if successes == trials else min(1.0, centre + half)
    return lo, hi


def format_rate(successes: int, trials: int) -> str:
    """'90 % (9/10, 95 % CI 60-98 %)', or 'n/a' for no trials: how every report writes a rate."""
    if trials == 0:
        return "n/a"
    lo, hi = wilson_interval(successes, trials)
    return (f"{100 * successes / trials:.0f} % ({successes}/{trials}, {100 * CONFIDENCE:.0f} % CI "
            f"{100 * lo:.0f}-{100 * hi:.0f} %)")


def short_rate(successes: int, trials: int) -> str:
    """'90 % (9/10; 60-98 %)': a rate in a table cell, with its 95 % interval; 'n/a' for no trials."""
    if trials == 0:
        return "n/a"
    lo, hi = wilson_interval(successes, trials)
    return f"{100 * successes / trials:.0f} % ({successes}/{trials}; {100 * lo:.0f}-{100 * hi:.0f} %)"


def error_bars(counts) -> tuple[list[float], list[list[float]]]:
    """Bar heights and matplotlib `yerr` (2 x N, below and above) in percent, from (successes, trials)
    pairs: each bar is the rate, its whiskers the 95 % Wilson interval. No trials: a zero bar, no whisker."""
    heights, below, above = [], [], []
    for successes, trials in counts:
        if trials == 0:
            heights.append(0.0)
            below.append(0.0)
            above.append(0.0)
            continue
        rate = 100.0 * successes / trials
        lo, hi = wilson_interval(successes, trials)
        heights.append(rate)
        below.append(max(0.0, rate - 100.0 * lo))
        above.append(max(0.0, 100.0 * hi - rate))
    return heights, [below, above]
