"""Very fast simulated annealing as GraspIt! runs it (src/EGPlanner/simAnn.cpp; docs/design.md §4.6).

* Schedule (Ingber): T(k) = T0 exp(−c k^(1/D)), T0 = 1e6, c = 7, D = 8, for both the neighbour
  distribution and the acceptance test (GraspIt!'s YC = HC = 7, YDIMS = HDIMS = 8).
* Step counter: GraspIt! starts k at K0 = 30,000 (``DEF_K0``), so T(K0) ≈ 9.3e-6 and T(70,000) ≈
  5.5e-7. A *step* (an *iteration*) is one annealing iteration that found a legal neighbour: k then
  advances by one, whether the neighbour was accepted or not. An iteration whose 11 neighbour
  tries all collide fails and does not advance k. The planner stops when k reaches its step limit,
  GraspIt!'s "max steps": the default 70,000 means 40,000 iterations (k = 30,000 … 69,999).
* Neighbour: each variable v ← v + y · maxJump with y = sgn(u − ½) · T · [(1 + 1/T)^|2u−1| − 1],
  u ~ U(0, 1), redrawn until the value lies in range; a circular variable is wrapped once instead.
  |y| ≤ 1, and log |y| is about uniform between log T and 0: most steps are tiny, a few are large.
* Acceptance: a lower energy always; otherwise with probability exp((E_old − E_new) · 1e-6 / T)
  (GraspIt!'s ERR_ADJ = 1e-6 turns its energies, of order 1–100, into the temperature's scale).

Pure Python/numpy; the random numbers come from an explicit ``numpy.random.Generator``.
"""

from __future__ import annotations

import math

import numpy as np

from baselines.eigengrasp.search_space import SEARCH_VARIABLES

# --- docs/design.md §4.6 (simAnn.cpp, ANNEAL_DEFAULT). --------------------------------------------
T0 = 1.0e6  # DEF_T0
COOLING_C = 7.0  # YC = HC
COOLING_DIMENSIONS = 8  # YDIMS = HDIMS
K0 = 30_000  # DEF_K0: the step counter's start.
ENERGY_SCALE = 1.0e-6  # ERR_ADJ: energies are multiplied by this in the acceptance test.
NEIGHBOR_SCALE = 1.0  # NBR_ADJ: the neighbour distribution's temperature factor.
DEFAULT_MAX_STEPS = 70_000  # the paper's (and GraspIt!'s planner dialog's) step limit.
MAX_NEIGHBOR_TRIES = 11  # simAnn.cpp: attempts 0..maxAttempts (= 10) while the neighbour collides.
# variableNeighbor() gives up redrawing a variable after 100 draws; GraspIt! then keeps the last,
# out-of-range value, which we clamp into range instead.
MAX_REDRAWS = 100
_TINY = 1.0e-7  # simAnn.cpp TINY: values this close outside the range are put on its end.

# --- docs/design.md §4.6 (simAnnPlanner.cpp, egPlanner.cpp). --------------------------------------
BEST_LIST_SIZE = 20  # BEST_LIST_SIZE
MERGE_DISTANCE = 0.2  # addToListOfUniqueSolutions(..., 0.2)
OPEN_LIST_ENERGY = 1.0e5  # a state enters a list that is not full when its energy is below this
INITIAL_ENERGY = 1.0e8  # the reset state's energy (resetParameters), so the first legal step jumps.


def temperature(k: float, t0: float = T0, c: float = COOLING_C, dimensions: int = COOLING_DIMENSIONS) -> float:
    """T(k) = T0 exp(−c k^(1/D)), the temperature at step k (dimensionless)."""
    return t0 * math.exp(-c * math.pow(k, 1.0 / dimensions))


def neighbor_offset(u: float, T: float) -> float:
    """Ingber's neighbour offset y ∈ [−1, 1] (in units of the variable's max jump) for u ∈ [0, 1]."""
    y = T * (math.pow(1.0 + 1.0 / T, abs(2.0 * u - 1.0)) - 1.0)
    return -y if u < 0.5 else y


def acceptance_probability(e_old: float, e_new: float, T: float) -> float:
    """Probability of moving from a state of energy e_old to one of energy e_new at temperature T."""
    if e_new < e_old:
        return 1.0
    return math.exp((e_old - e_new) * ENERGY_SCALE / T)


class UniformStream:
    """Uniform numbers in [0, 1) from a numpy Generator, drawn in blocks (cheap one at a time).

    The sequence depends only on the generator's seed, so a run is deterministic for a seed.
    """

    def __init__(self, rng: np.random.Generator, block: int = 1 << 16):
        self._rng = rng
        self._block = block
        self._values = iter(())

    def next(self) -> float:
        """The next number."""
        try:
            return next(self._values)
        except StopIteration:
            self._values = iter(self._rng.random(self._block).tolist())
            return next(self._values)


_LOWER = [v.lower for v in SEARCH_VARIABLES]
_UPPER = [v.upper for v in SEARCH_VARIABLES]
_JUMP = [v.max_jump for v in SEARCH_VARIABLES]
_CIRCULAR = [v.circular for v in SEARCH_VARIABLES]
_SPAN = [v.span for v in SEARCH_VARIABLES]


def neighbor(state, T: float, uniforms: UniformStream) -> list[float]:
    """A random neighbour of a state at temperature T (GraspIt!'s SimAnn::variableNeighbor).

    Args:
        state: The current state, a sequence of 8 floats (search_space order).
        T: The neighbour temperature (already multiplied by NEIGHBOR_SCALE).
        uniforms: The source of uniform numbers.

    Returns:
        The neighbour, a list of 8 floats, every one in its variable's range.
    """
    out = []
    next_u = uniforms.next
    for value, lo, hi, jump, circular, span in zip(state, _LOWER, _UPPER, _JUMP, _CIRCULAR, _SPAN):
        for _ in range(MAX_REDRAWS):
            u = next_u()
            y = T * (math.pow(1.0 + 1.0 / T, abs(2.0 * u - 1.0)) - 1.0)
            v = value + (-y if u < 0.5 else y) * jump
            if circular:
                if v > hi:
                    v -= span
                elif v < lo:
                    v += span
            if hi < v < hi + _TINY:
                v = hi
            elif lo - _TINY < v < lo:
                v = lo
            if lo <= v <= hi:
                break
        else:
            v = min(max(v, lo), hi)
        out.append(v)
    return out
