"""Shape resemblance from how two silhouette features vary over the camera's motion (pure numpy).

The paper's rule (DESIGN §1): constant contour area and eccentricity ≈ 1 → sphere; constant area and
eccentricity ≫ 1 → cylinder (rotationally symmetric about its principal axis); varying area → box.
"Constant" only means something for a given motion, so the features are modelled as functions of
where the camera is on its sphere around the object centre: φa = rotation about the object's axis a
(the cylinder primitive's arc), φb = rotation about the cross axis b (the sphere primitive's arc),
both 0 at the reference (first) view. Over the samples of the motion a least-squares fit

    y(φa, φb) ≈ β0 + β1 φa + β2 |φa| + β3 φa² + β4 φb + β5 |φb| + β6 φb²,

for y = log(area · (distance / f)²) (the silhouette's area in m² at the object, so that a change of
distance is not a change of shape) and y = log(eccentricity), separates what each arc does. A box's
cross-section gives |φ| terms (its area rises on both sides of a face-on view), perspective and
ellipses give φ², an asymmetric view φ.

* variation along a, V_a = the largest deviation of the a-terms from the reference view over the
  explored range of φa, both features combined (root of the sum of squares); V_b alike.
* invariance I_a = exp(−(V_a / τ_V)²), I_b alike; roundness R = exp(−((e0 − 1) / τ_e)²), e0 = the
  fitted eccentricity of the reference view (face-on, from above).
* sphere = R · I_a · I_b: round, and invariant under both arcs.
* cylinder = max(I_a · (1 − R · I_b), R · I_b · (1 − R · I_a)): invariant about one axis and, if the
  silhouette is round (a cylinder as long as it is wide, seen from above), not about the other; for an
  elongated silhouette (R ≈ 0) the candidate axis is the principal axis only.
* box = 1 − max(I_a, R · I_b): no invariance about the principal axis (the paper asks for
  eccentricity ≫ 1 too; we drop that so that cubes, square from above, are boxes: choice).

All three lie in [0, 1]. τ_V and τ_e are choices (diagrams/perception.scenarios.yaml).
"""


import dataclasses
import math

import numpy as np

NUM_BASIS = 7
NUM_FEATURES = 2  # log area, log eccentricity
SHAPES = ("sphere", "cylinder", "box")


def basis(phi_a: float, phi_b: float) -> np.ndarray:
    """The regressors [1, φa, |φa|, φa², φb, |φb|, φb²]."""
    return np.array([1.0, phi_a, abs(phi_a), phi_a * phi_a, phi_b, abs(phi_b), phi_b * phi_b])


@dataclasses.dataclass
class FeatureStatistics:
    """Running sums of the regression over the motion (what a resemblance primitive keeps in state).

    Attributes:
        XtX: Σ x xᵀ (7×7).
        XtY: Σ x yᵀ (7×2).
        count: number of samples.
        phi_range: [min φa, max φa, min φb, max φb] seen (rad).
    """

    XtX: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((NUM_BASIS, NUM_BASIS)))
    XtY: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((NUM_BASIS, NUM_FEATURES)))
    count: float = 0.0
    phi_range: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(4))

    SIZE = NUM_BASIS * NUM_BASIS + NUM_BASIS * NUM_FEATURES + 1 + 4

    def add(self, phi_a: float, phi_b: float, metric_area: float, eccentricity: float) -> None:
        """Adds one view: angles (rad), silhouette area at the object (m²), eccentricity (≥ 1)."""
        x = basis(phi_a, phi_b)
        y = np.array([math.log(metric_area), math.log(max(eccentricity, 1.0))])
        self.XtX += np.outer(x, x)
        self.XtY += np.outer(x, y)
        self.count += 1.0
        self.phi_range = np.array([min(self.phi_range[0], phi_a), max(self.phi_range[1], phi_a),
                                   min(self.phi_range[2], phi_b), max(self.phi_range[3], phi_b)])

    def to_vector(self) -> np.ndarray:
        return np.concatenate([self.XtX.ravel(), self.XtY.ravel(), [self.count], self.phi_range])

    @classmethod
    def from_vector(cls, x: np.ndarray) -> "FeatureStatistics":
        x = np.asarray(x, float)
        n1, n2 = NUM_BASIS * NUM_BASIS, NUM_BASIS * NUM_FEATURES
        return cls(x[:n1].reshape(NUM_BASIS, NUM_BASIS).copy(), x[n1:n1 + n2].reshape(NUM_BASIS, NUM_FEATURES).copy(),
                   float(x[n1 + n2]), x[n1 + n2 + 1:n1 + n2 + 5].copy())


@dataclasses.dataclass
class ScoreParams:
    """Attributes:
        variation_scale: τ_V, log-feature variation at which invariance has dropped to 1/e.
        roundness_scale: τ_e, eccentricity excess over 1 at which roundness has dropped to 1/e.
        ridge: regularisation of the fit (keeps the terms of an arc never travelled at 0).
        min_samples: fewer samples give no resemblance (all 0).
    """

    variation_scale: float = 0.05
    roundness_scale: float = 0.15
    ridge: float = 1e-3
    min_samples: int = 10


@dataclasses.dataclass(frozen=True)
class ShapeEvidence:
    """What the fit says. Attributes: variation along a and b (log units), reference eccentricity
    e0, invariances I_a, I_b, roundness R, and the three resemblances."""

    variation_a: float
    variation_b: float
    eccentricity_0: float
    invariance_a: float
    invariance_b: float
    roundness: float
    sphere: float
    cylinder: float
    box: float

    def resemblance(self, shape: str) -> float:
        return float(getattr(self, shape))

    def to_vector(self) -> np.ndarray:
        return np.array([getattr(self, f.name) for f in dataclasses.fields(self)])


def fit(stats: FeatureStatistics, ridge: float) -> np.ndarray:
    """β (7×2) of the regression, with a ridge on every term but the constant."""
    regulariser = ridge * max(stats.count, 1.0) * np.diag([0.0] + [1.0] * (NUM_BASIS - 1))
    return np.linalg.solve(stats.XtX + regulariser + 1e-12 * np.eye(NUM_BASIS), stats.XtY)


def _variation(beta: np.ndarray, lo: float, hi: float, columns: slice) -> float:
    """Largest deviation from φ = 0 of the terms in `columns` over φ in [lo, hi], features combined."""
    phi = np.linspace(min(lo, 0.0), max(hi, 0.0), 61)
    terms = np.column_stack([phi, np.abs(phi), phi * phi]) @ beta[columns]  # (61, features)
    return float(np.sqrt(np.sum(np.max(np.abs(terms), axis=0) ** 2)))


def evaluate(stats: FeatureStatistics, params: ScoreParams) -> ShapeEvidence:
    """The resemblances (each in [0, 1]) of the silhouette statistics, and the evidence behind them."""
    if stats.count < params.min_samples:
        return ShapeEvidence(0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    beta = fit(stats, params.ridge)
    lo_a, hi_a, lo_b, hi_b = stats.phi_range
    v_a = _variation(beta, lo_a, hi_a, slice(1, 4))
    v_b = _variation(beta, lo_b, hi_b, slice(4, 7))
    e0 = math.exp(max(float(beta[0, 1]), 0.0))
    i_a = math.exp(-((v_a / params.variation_scale) ** 2))
    i_b = math.exp(-((v_b / params.variation_scale) ** 2))
    r = math.exp(-(((e0 - 1.0) / params.roundness_scale) ** 2))
    sphere = r * i_a * i_b
    cylinder = max(i_a * (1.0 - r * i_b), r * i_b * (1.0 - r * i_a))
    box = 1.0 - max(i_a, r * i_b)
    clip = lambda x: float(min(max(x, 0.0), 1.0))  # noqa: E731
    return ShapeEvidence(v_a, v_b, e0, i_a, i_b, r, clip(sphere), clip(cylinder), clip(box))
