"""Shape resemblance from how two silhouette features vary over the camera's motion (pure numpy).

The paper's rule (Sec. 4; docs/design.md §2): constant contour area and eccentricity ≈ 1 → sphere;
constant area and eccentricity ≫ 1 → cylinder (rotationally symmetric about its principal axis);
varying area → box.
"Constant" only means something for a given motion, so the features are modelled as functions of
where the camera is on its sphere around the object centre: φa = rotation about the object's axis a
(the cylinder primitive's arc), φb = rotation about the cross axis b (the sphere primitive's arc),
both 0 at the reference (first) view. The arcs are travelled one after the other, so every view lies
on one of the two arcs (the one whose angle is larger); on each arc a least-squares fit

    y(φ) ≈ β0 + β1 φ + β2 |φ| + β3 φ²

is made for y = log(area · (distance / f)²) (the silhouette's area in m² at the object, so that a
change of distance is not a change of shape) and y = log(eccentricity). A box's cross-section gives
|φ| terms (its silhouette grows on both sides of a face-on view), perspective and ellipses φ², an
asymmetric view φ.

* variation along a, V_a = the largest deviation of the fitted curve from its value at φ = 0 over the
  explored range of φa, both features combined (root of the sum of squares); V_b alike.
* invariance I_a = exp(−(V_a / τ_V)²), I_b alike; roundness R = exp(−((e0 − 1) / τ_e)²), e0 = the
  fitted eccentricity of the reference view (face-on, from above).
* sphere = exp(−[(V_a² + V_b²) / τ_S² + ((e0 − 1) / τ_Se)²]): round, and invariant under both arcs
  up to what a *near*-sphere shows (below).
* cylinder = max(I_a, R · I_b) · (1 − sphere): invariant about one axis (the principal axis; for a
  round silhouette, a cylinder as long as it is wide seen from above, either arc's axis) and not a
  sphere.
* box = 1 − max(I_a, R · I_b, sphere): no invariance about the principal axis (nor, for a round
  silhouette, about the cross axis), and not a sphere (the paper asks for eccentricity ≫ 1 too; we
  drop that so that cubes, square from above, are boxes: choice).

The sphere's own tolerances (issue 15, item 4; docs/results/near_primitives.md). A strict "constant"
(τ_V = 0.04, τ_e = 0.15: what confirms a cylinder's symmetry about its axis and keeps flat boxes,
whose silhouette barely changes about their long axis, from being cylinders) names a perfect sphere
but not an ellipsoid within 10 % of one: tilting such an ellipsoid 40° changes its silhouette's area
and eccentricity by up to 7 % each (V_a = 0.105, V_b = 0.056 over the default arcs of ±40° and ±29°),
and from above it is up to 1.22 times as long as wide, so on main 1 of 10 generated near-spheres was
named a sphere (the others a box or a cylinder). The sphere hypothesis therefore gets tolerances of
its own, derived from that definition of a near-sphere, not fitted to measurements: τ_S and τ_Se put
the two extreme ellipsoids whose semi-axes are within ±10 % of a common radius at sphere = 1/2, the
oblate one (1.1, 1.1, 0.9: round from above, the largest variation) and the prolate one (1.1, 0.9,
0.9: the most eccentric from above), both computed for ideal (orthographic) silhouettes along the
default arcs (`primitives.sphere_tolerances.sphere_scales_from_ellipsoids`); every other ellipsoid
of that family then scores above 1/2. The cylinder and box hypotheses exclude a sphere by this same
sphere score (before: by the strict invariances), so that "not invariant enough to be a sphere" and
"a sphere" never disagree. An object that is not round from above has a small sphere score from its
eccentricity alone (0.18 at e0 = 1.4, below 10⁻⁷ at e0 = 2.2: every cylinder and elongated object of
the paper), so its cylinder and box scores are as before.

All three lie in [0, 1]. τ_V, τ_e, τ_S and τ_Se are choices (the scenario's `perception:`, diagrams/station.scenarios.yaml).
"""

import dataclasses
import math

import numpy as np

NUM_BASIS = 4  # per arc: 1, φ, |φ|, φ²
NUM_FEATURES = 2  # log area, log eccentricity
SHAPES = ("sphere", "cylinder", "box")


def basis(phi: float) -> np.ndarray:
    """The regressors [1, φ, |φ|, φ²] of one arc."""
    return np.array([1.0, phi, abs(phi), phi * phi])


@dataclasses.dataclass
class ArcStatistics:
    """Running sums of one arc's regression: Σ x xᵀ (4×4), Σ x yᵀ (4×2), count, [min φ, max φ]."""

    XtX: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((NUM_BASIS, NUM_BASIS)))
    XtY: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros((NUM_BASIS, NUM_FEATURES)))
    count: float = 0.0
    phi_range: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(2))

    SIZE = NUM_BASIS * NUM_BASIS + NUM_BASIS * NUM_FEATURES + 1 + 2

    def add(self, phi: float, y: np.ndarray) -> None:
        x = basis(phi)
        self.XtX += np.outer(x, x)
        self.XtY += np.outer(x, y)
        self.count += 1.0
        self.phi_range = np.array([min(self.phi_range[0], phi), max(self.phi_range[1], phi)])

    def fit(self, ridge: float) -> np.ndarray:
        """β (4×2), with a ridge on every term but the constant."""
        regulariser = ridge * max(self.count, 1.0) * np.diag([0.0, 1.0, 1.0, 1.0])
        return np.linalg.solve(self.XtX + regulariser + 1e-12 * np.eye(NUM_BASIS), self.XtY)

    def variation(self, ridge: float) -> float:
        """Largest deviation of the fitted curves from φ = 0 over the explored range, features combined."""
        if self.count < NUM_BASIS:
            return 0.0
        beta = self.fit(ridge)
        phi = np.linspace(min(self.phi_range[0], 0.0), max(self.phi_range[1], 0.0), 61)
        terms = np.column_stack([phi, np.abs(phi), phi * phi]) @ beta[1:]  # (61, features)
        return float(np.sqrt(np.sum(np.max(np.abs(terms), axis=0) ** 2)))

    def to_vector(self) -> np.ndarray:
        return np.concatenate([self.XtX.ravel(), self.XtY.ravel(), [self.count], self.phi_range])

    @classmethod
    def from_vector(cls, x: np.ndarray) -> "ArcStatistics":
        x = np.asarray(x, float)
        n1, n2 = NUM_BASIS * NUM_BASIS, NUM_BASIS * NUM_FEATURES
        return cls(x[:n1].reshape(NUM_BASIS, NUM_BASIS).copy(), x[n1:n1 + n2].reshape(NUM_BASIS, NUM_FEATURES).copy(),
                   float(x[n1 + n2]), x[n1 + n2 + 1:n1 + n2 + 3].copy())


@dataclasses.dataclass
class FeatureStatistics:
    """The silhouette statistics of an exploration: one `ArcStatistics` per arc (about a, about b)."""

    arc_a: ArcStatistics = dataclasses.field(default_factory=ArcStatistics)
    arc_b: ArcStatistics = dataclasses.field(default_factory=ArcStatistics)

    SIZE = 2 * ArcStatistics.SIZE

    @property
    def count(self) -> float:
        return self.arc_a.count + self.arc_b.count

    def add(self, phi_a: float, phi_b: float, metric_area: float, eccentricity: float) -> None:
        """Adds one view: angles (rad), silhouette area at the object (m²), eccentricity (≥ 1). The
        view belongs to the arc whose angle is the larger."""
        y = np.array([math.log(metric_area), math.log(max(eccentricity, 1.0))])
        if abs(phi_a) >= abs(phi_b):
            self.arc_a.add(phi_a, y)
        else:
            self.arc_b.add(phi_b, y)

    def to_vector(self) -> np.ndarray:
        return np.concatenate([self.arc_a.to_vector(), self.arc_b.to_vector()])

    @classmethod
    def from_vector(cls, x: np.ndarray) -> "FeatureStatistics":
        n = ArcStatistics.SIZE
        return cls(ArcStatistics.from_vector(x[:n]), ArcStatistics.from_vector(x[n:2 * n]))


@dataclasses.dataclass
class ScoreParams:
    """Attributes:
        variation_scale: τ_V, log-feature variation at which invariance has dropped to 1/e.
        roundness_scale: τ_e, eccentricity excess over 1 at which roundness has dropped to 1/e.
        sphere_variation_scale: τ_S, the sphere hypothesis's variation scale (see the module
            docstring: an ellipsoid within 10 % of a sphere scores at least 1/2).
        sphere_roundness_scale: τ_Se, the sphere hypothesis's eccentricity-excess scale.
        ridge: regularisation of the fit (keeps the terms of an arc never travelled at 0).
        min_samples: fewer samples give no resemblance (all 0).
    """

    variation_scale: float = 0.04
    roundness_scale: float = 0.15
    sphere_variation_scale: float = 0.143
    sphere_roundness_scale: float = 0.306
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


def evaluate(stats: FeatureStatistics, params: ScoreParams) -> ShapeEvidence:
    """The resemblances (each in [0, 1]) of the silhouette statistics, and the evidence behind them."""
    if stats.count < params.min_samples:
        return ShapeEvidence(0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    v_a = stats.arc_a.variation(params.ridge)
    v_b = stats.arc_b.variation(params.ridge)
    # The reference view's eccentricity: the arcs' fits at φ = 0, weighted by their views.
    intercepts = [(arc.count, arc.fit(params.ridge)[0, 1]) for arc in (stats.arc_a, stats.arc_b)
                  if arc.count >= NUM_BASIS]
    log_e0 = sum(n * b for n, b in intercepts) / sum(n for n, _ in intercepts) if intercepts else 0.0
    e0 = math.exp(max(float(log_e0), 0.0))
    i_a = math.exp(-((v_a / params.variation_scale) ** 2))
    i_b = math.exp(-((v_b / params.variation_scale) ** 2))
    r = math.exp(-(((e0 - 1.0) / params.roundness_scale) ** 2))
    sphere = math.exp(-((v_a * v_a + v_b * v_b) / params.sphere_variation_scale**2
                        + ((e0 - 1.0) / params.sphere_roundness_scale) ** 2))
    cylinder = max(i_a, r * i_b) * (1.0 - sphere)
    box = 1.0 - max(i_a, r * i_b, sphere)
    clip = lambda x: float(min(max(x, 0.0), 1.0))  # noqa: E731
    return ShapeEvidence(v_a, v_b, e0, i_a, i_b, r, clip(sphere), clip(cylinder), clip(box))
