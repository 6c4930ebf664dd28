"""The object estimate: what the visual primitives found, gathered into one value.

`gather_estimate` (pure) turns the primitives' outputs — the depth primitive's centre and extents,
the principal axis and whether the object is elongated, the three shape resemblances — into an
`ObjectEstimate` in the world frame. `ObjectEstimator` is the LeafSystem that does it inside the
Diagram, so a supervisor reads one `estimate` port instead of a dozen; the exploration reads the same
port when it ends.

An estimate can fail in two ways, each a trial's failure reason of its own: the object was never
seen (`OBJECT_NOT_FOUND`), or it was seen but what the primitives measured cannot place a grasp — a
size that is not positive, a principal axis that did not converge, a value that is not finite
(`PERCEPTION_FAILED`; `ObjectEstimate.problem` says which). The supervisor checks this when it
decides, and ends the sequence with that reason instead of grasping.
"""

import dataclasses
import math

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import Context, LeafSystem

from drake_grasp.primitives.decision import choose_shape, decision_margin
from drake_grasp.primitives.depth_views import TableTopVector
from drake_grasp.primitives.exploration_cost import CostVector
from drake_grasp.primitives.estimators import is_upright
from drake_grasp.primitives.flat import table_top_flatness
from drake_grasp.primitives.low import table_top_lowness, table_top_squatness
from drake_grasp.primitives.narrow import table_top_thin_narrowness
from drake_grasp.primitives.round_sides import (table_top_roundness, table_top_tallness, table_top_thin_roundness,
                                               table_top_wideness)
from drake_grasp.primitives.upright import table_top_slenderness, table_top_uprightness
from drake_grasp.primitives.scores import SHAPES
from drake_grasp.primitives.sequencer import ExplorationPhase, phase_value
from drake_grasp.primitives.silhouette import CameraSample

OBJECT_NOT_FOUND = "object not found"
# The object was seen, but the estimate cannot place a grasp (`ObjectEstimate.problem` says why).
PERCEPTION_FAILED = "perception failed"
# An extent below this is no size (m): under a pixel at the exploration's distances (about 1.4 mm at
# 0.3 m), so not measured but left by the bounded size fit at its bound, 0 (it gave 1.25e-21 m).
MIN_EXTENT = 1e-3

@dataclasses.dataclass
class ObjectEstimate:
    """What one exploration found (world frame W; m, rad, s).

    Attributes:
        status: "ok"; "object not found" (the object never came into view); or "perception failed"
            (it came into view, but no silhouette the depth primitive could use gave it a centre).
        centre: the object centre (where the rays through the silhouette centroids meet), or None.
        depth: distance from `camera_position` (the camera at the end) to the centre.
        camera_position: where the camera was when the exploration ended.
        principal_axis: unit vector of the object's long axis, or None if the object is not elongated
            (not finite when the object is elongated but the principal-axis primitive gave no axis).
        axes: 3×3, columns (a, b, c): a = the principal axis (or, for a round object, the direction of
            a silhouette side), b = horizontal across it, c = a × b (up for a lying object; horizontal
            for an upright one, whose principal axis is vertical).
        extents: the object's size along a, b, c, m: the depth primitive's fit of the silhouettes'
            tangent planes (`extents_along_axes`).
        resemblances: {"sphere", "cylinder", "box"} → resemblance in [0, 1].
        evidence: what the resemblances rest on (variations, invariances, roundness; see scores).
        elongation: the mean eccentricity of the silhouette over the exploration.
        timings: build, simulated and wall-clock times, frames rendered, phase start times.
        table_top: with the table-top estimate (a scenario's `perception.table_top`), what it rests on
            and how sure it is: {"views", "cells", "clipped", "uncertainty": {"centre" (m),
            "axis_deg", "extents" (m, 3)}, "silhouettes": the silhouettes' own centre, principal
            axis, axes and extents, which it replaced; "table_z": the table's height, m, the height
            map's reference plane, which the grasps take as the table; "grip_axis" and "grip_reach":
            how far the footprint reaches either way across that horizontal direction from the centre
            where fingers close there (`table_top.grip_reach`; None and NaN where not measured), which
            the flower grasp lands outside of}; None without it (and left out of `to_dict`).
        exploration: what the exploration was and cost (`primitives.exploration_cost`): {"kind" ("full":
            the paper's exploration; "confirmed" or "fallback": the minimal one's hypothesis confirmed,
            or not and the full exploration ran after it), "time_s", "path_m", "path_rad", "images",
            and for the minimal exploration "hypothesis" and "why"}; None where nothing measured it.
    """

    status: str
    centre: np.ndarray | None = None
    depth: float = math.nan
    camera_position: np.ndarray | None = None
    principal_axis: np.ndarray | None = None
    axes: np.ndarray | None = None
    extents: np.ndarray | None = None
    resemblances: dict = dataclasses.field(default_factory=dict)
    evidence: dict = dataclasses.field(default_factory=dict)
    elongation: float = math.nan
    timings: dict = dataclasses.field(default_factory=dict)
    table_top: dict | None = None
    exploration: dict | None = None

    @property
    def found(self) -> bool:
        return self.status == "ok"

    @property
    def best_shape(self) -> str | None:
        """The chosen shape (the compliant grasp to execute), or None: one of the paper's three, or
        "flat" where the table-top estimate measured flatness (`primitives.decision`)."""
        return choose_shape(self.resemblances)

    @property
    def resemblance_margin(self) -> float:
        """How clear the choice was (in [0, 1]; NaN without resemblances): the best resemblance's lead
        over the next, bounded by the flat resemblance's distance from its threshold when there is one
        (`primitives.decision`). A small margin says that no primitive clearly fits."""
        return decision_margin(self.resemblances)

    def problem(self) -> str:
        """Why this estimate cannot place a grasp ("" if it can): the object was not found; it was seen
        but never gave a usable silhouette; or a value the grasps and the decision use (centre, axes,
        extents, principal axis, resemblances) is missing, not finite, or an extent is not positive
        (below `MIN_EXTENT`, m)."""
        if self.status == PERCEPTION_FAILED:
            return "no usable silhouette: the object was seen, but always cut by the image border (no centre)"
        if not self.found:
            return self.status
        for name in ("centre", "axes", "extents"):
            value = getattr(self, name)
            if value is None:
                return f"no {name}"
            if not np.all(np.isfinite(value)):
                return f"{name} not finite: {_short(value)}"
        if self.principal_axis is not None and not np.all(np.isfinite(self.principal_axis)):
            return "the principal axis did not converge (the object is elongated, but the axis primitive gave none)"
        extents = np.asarray(self.extents, float)
        if np.any(extents < MIN_EXTENT):
            return f"size not positive along every axis: extents {_short(extents)} m (under 1 mm counts as 0)"
        missing = [s for s in SHAPES if not math.isfinite(self.resemblances.get(s, math.nan))]
        if missing:
            return f"resemblance not finite: {', '.join(missing)}"
        return ""

    def as_grasp_estimate(self):
        """This estimate as `drake_grasp.grasps.ObjectEstimate` (what the compliant grasps take)."""
        from drake_grasp.grasps import ObjectEstimate as GraspEstimate

        if self.problem():
            raise ValueError(f"no estimate: {self.problem()}")
        top = self.table_top or {}
        table_z, grip_axis = top.get("table_z"), top.get("grip_axis")
        return GraspEstimate(center=np.array(self.centre), R_WB=np.array(self.axes), size=np.array(self.extents),
                             principal_axis=None if self.principal_axis is None else np.array(self.principal_axis),
                             source="camera", table_z=None if table_z is None else float(table_z),
                             grip_axis=None if grip_axis is None else np.array(grip_axis, float),
                             grip_reach=float(top.get("grip_reach", math.nan)))

    def to_dict(self) -> dict:
        """Plain data (lists, floats) for JSON."""

        def plain(x):
            if isinstance(x, np.ndarray):
                return x.tolist()
            if isinstance(x, dict):
                return {k: plain(v) for k, v in x.items()}
            if isinstance(x, (list, tuple)):
                return [plain(v) for v in x]
            if isinstance(x, (np.floating, np.integer)):
                return x.item()
            return x

        return {f.name: plain(getattr(self, f.name)) for f in dataclasses.fields(self)
                if not (f.name in ("table_top", "exploration") and getattr(self, f.name) is None)}


def _short(values) -> str:
    """A vector in a reason: 3 decimals (m, or unitless)."""
    return "[" + ", ".join(f"{float(v):.3f}" for v in np.ravel(values)) + "]"


# Names of the box resemblance primitive's `evidence` entries kept in the estimate.
EVIDENCE_NAMES = ("variation_a", "variation_b", "eccentricity_0", "invariance_a", "invariance_b", "roundness")


def estimate_axes(axis: np.ndarray, elongated: bool) -> tuple[np.ndarray, np.ndarray | None]:
    """The object's axes (a, b, c as columns) and principal axis (or None) from the axis primitive.

    a is the principal axis when the object is elongated; otherwise the direction of a silhouette side,
    taken horizontal. b is horizontal across a, and c = a × b (up for a horizontal a).
    """
    up = np.array([0.0, 0.0, 1.0])
    a = np.asarray(axis, float) if np.all(np.isfinite(axis)) else np.array([1.0, 0.0, 0.0])
    if not elongated:
        a = a - a[2] * up
        a = a / np.linalg.norm(a) if np.linalg.norm(a) > 1e-6 else np.array([1.0, 0.0, 0.0])
    b = np.cross(up, a)
    if np.linalg.norm(b) < 1e-6:  # a vertical axis: any horizontal b
        b = np.array([0.0, 1.0, 0.0])
    b /= np.linalg.norm(b)
    c = np.cross(a, b)
    return np.column_stack([a, b, c]), (a.copy() if elongated else None)


def upright_axes(axis: np.ndarray, extents_frame: np.ndarray) -> np.ndarray | None:
    """An upright object's axes (a, b, c as columns): a = its principal axis (near the vertical), c =
    the depth primitive's `extents_frame` (the direction of its side faces) made perpendicular to a,
    b = c × a (so that c = a × b). None if `extents_frame` is not finite or lies along a."""
    a = np.asarray(axis, float)
    side = np.asarray(extents_frame, float)
    if not np.all(np.isfinite(side)):
        return None
    c = side - float(np.dot(side, a)) * a
    if np.linalg.norm(c) < 1e-6:
        return None
    c /= np.linalg.norm(c)
    return np.column_stack([a, np.cross(c, a), c])


def extents_along_axes(axes: np.ndarray, axis: np.ndarray, extents: np.ndarray) -> np.ndarray:
    """The depth primitive's extents, m, as the sizes along the estimate's axes (a, b, c).

    The depth primitive fits its size model in its own frame (`estimators.fit_support`): a' = its
    `extents_frame` (the principal axis made horizontal; for an upright object, its side faces'
    direction), b' = up × a', and up; its extents are along (a', b', up). The estimate's axes are
    a = the principal axis itself, b horizontal across it, c = a × b. For a lying object (a within 45°
    of the horizontal) the two frames are the same up to the axis's tilt: a ≈ a', b = b', c ≈ up, and
    the extents are kept as they are. For an upright one — a tall carton or bottle standing on the
    table, its principal axis vertical — a is up and c horizontal, along a' (`upright_axes`; ∓a' when
    the axes come from `estimate_axes`): its length is the fit's vertical extent, c's size the extent
    along a'.
    """
    extents = np.array(extents, float)
    if not np.all(np.isfinite(axis)) or not is_upright(np.asarray(axes, float)[:, 0]):
        return extents  # a lying object, or no axis yet (the fit's frame was the silhouette's, a horizontal)
    return extents[[2, 1, 0]]


def gather_estimate(phase: ExplorationPhase, centre: np.ndarray, camera_position: np.ndarray, axis: np.ndarray,
                    axis_info: np.ndarray, extents: np.ndarray, resemblances: dict, evidence: np.ndarray,
                    extents_frame: np.ndarray | None = None, table_top=None) -> ObjectEstimate:
    """The ObjectEstimate from the primitives' outputs (see `ObjectEstimator`'s ports for each).

    Not found: the sequencer never saw the object (or, while it explores, no centre yet).
    PERCEPTION_FAILED: the exploration is over and it saw the object, but no silhouette the depth
    primitive could use (each one cut by the image border) gave it a centre. An elongated object
    whose axis primitive gave no axis keeps a principal axis that is not finite (its axes fall back
    to the world's), so that the supervisor does not grasp along an axis nobody measured. An upright
    elongated object takes its horizontal axes from the depth primitive's `extents_frame`
    (`upright_axes`): its sides, along which its extents were measured.

    With a table-top estimate (`table_top`, a `depth_views.TableTopVector` that holds one), its centre,
    axes and extents replace the silhouettes' (`with_table_top`), and the flat resemblance joins the
    three (`primitives.flat`); whether the object is elongated, and the three resemblances, stay the
    silhouettes'.
    """
    no_centre = not np.all(np.isfinite(centre))
    if phase == ExplorationPhase.NOT_FOUND or (no_centre and not phase.finished):
        return ObjectEstimate(status=OBJECT_NOT_FOUND)
    if no_centre:
        return ObjectEstimate(status=PERCEPTION_FAILED)
    elongated, mean_eccentricity = axis_info[0] > 0.5, axis_info[1]
    axes, principal_axis = estimate_axes(axis, elongated)
    if elongated and not np.all(np.isfinite(axis)):
        principal_axis = np.full(3, np.nan)
    elif elongated and extents_frame is not None and is_upright(axes[:, 0]):
        sides = upright_axes(axes[:, 0], extents_frame)
        axes = axes if sides is None else sides
    centre = np.array(centre, float)
    camera_position = np.array(camera_position, float)
    estimate = ObjectEstimate(
        status="ok", centre=centre, depth=float(np.linalg.norm(centre - camera_position)),
        camera_position=camera_position, principal_axis=principal_axis, axes=axes,
        extents=extents_along_axes(axes, axis, extents), resemblances={s: float(resemblances[s]) for s in SHAPES},
        evidence={n: float(v) for n, v in zip(EVIDENCE_NAMES, evidence)}, elongation=float(mean_eccentricity))
    if table_top is not None and table_top.estimate is not None and not (elongated and principal_axis is not None
                                                                         and not np.all(np.isfinite(principal_axis))):
        estimate = with_table_top(estimate, table_top, elongated)
    return estimate


def with_table_top(estimate: ObjectEstimate, table_top, elongated: bool) -> ObjectEstimate:
    """`estimate` with the table-top estimate's centre, axes and extents (`depth_views.TableTopVector`).

    An elongated object's axis a is the column solid's axis of least inertia; an upright one (a within
    45° of the vertical) takes its horizontal axes from the footprint's smallest rectangle
    (`upright_axes`), and its extents along (a, b, c) are (height, across the sides, along them). An
    object that is not elongated has a along the footprint rectangle's longer side, b across it and
    c up. The depth (from the last camera position) follows the new centre.
    """
    t = table_top.estimate
    spans_sides = np.asarray(t.extents_sides, float)
    axes = None
    if elongated and is_upright(t.principal_axis):
        axes = upright_axes(np.asarray(t.principal_axis, float), t.sides)
        extents = spans_sides[[2, 1, 0]]
        principal_axis = np.asarray(t.principal_axis, float).copy()
    if elongated and (not is_upright(t.principal_axis) or axes is None):
        axes, principal_axis = estimate_axes(np.asarray(t.principal_axis, float), True)
        extents = np.asarray(t.extents_axis, float).copy()
    elif not elongated:
        axes, principal_axis = estimate_axes(np.asarray(t.sides, float), False)
        extents = spans_sides.copy()
    spread = table_top.spread
    uncertainty = None if spread is None else {"centre": spread.centre, "axis_deg": spread.axis_deg,
                                               "extents": [float(x) for x in spread.extents]}
    silhouettes = {"centre": estimate.centre, "principal_axis": estimate.principal_axis, "axes": estimate.axes,
                   "extents": estimate.extents}
    flat, flat_evidence = table_top_flatness(t)
    upright = table_top_uprightness(t)
    centre = np.asarray(t.centre, float).copy()
    return dataclasses.replace(
        estimate, centre=centre, depth=float(np.linalg.norm(centre - estimate.camera_position)), axes=axes,
        principal_axis=principal_axis, extents=extents,
        resemblances={**estimate.resemblances, "flat": flat, "upright": upright, "slender": table_top_slenderness(t),
                      "low": table_top_lowness(t),
                      "round": table_top_roundness(t), "wide": table_top_wideness(t), "tall": table_top_tallness(t),
                      "squat": table_top_squatness(t),
                      "thin_round": table_top_thin_roundness(t), "thin_narrow": table_top_thin_narrowness(t)},
        evidence={**estimate.evidence, **flat_evidence},
        table_top={"views": table_top.views, "cells": t.cells, "clipped": table_top.clipped,
                   "uncertainty": uncertainty, "silhouettes": silhouettes, "table_z": table_top.table_height,
                   "grip_axis": None if t.grip_axis is None else np.asarray(t.grip_axis, float).copy(),
                   "grip_reach": float(t.grip_reach)})


class ObjectEstimator(LeafSystem):
    """Gathers the primitives' outputs into one ObjectEstimate (no state: a function of its inputs).

    Input ports:
        phase (1): the exploration sequencer's ExplorationPhase (NOT_FOUND: no estimate).
        camera_sample (25): the latest camera sample (for the camera's position).
        centre (3), extents (3): from the depth primitive, m.
        extents_frame (3): from the depth primitive, the horizontal direction of the first extent.
        axis (3), axis_info (3): from the principal axis primitive.
        sphere_resemblance, cylinder_resemblance, box_resemblance (1 each): in [0, 1].
        evidence (9): from the box resemblance primitive (its `evidence` output).
        table_top (27, optional): `depth_views.TableTopVector`; unconnected, the silhouettes' estimate.
        exploration_cost (4, optional): `exploration_cost.CostVector`, what the exploration cost so far.
        exploration_outcome (abstract dict, optional): the sequencer's `outcome` (what kind of exploration
            ran); unconnected, "full".
    Output ports:
        estimate: the ObjectEstimate (abstract).
    """

    def __init__(self):
        super().__init__()
        for name, size in (("phase", 1), ("camera_sample", CameraSample.SIZE), ("centre", 3), ("extents", 3),
                           ("extents_frame", 3), ("axis", 3), ("axis_info", 3)):
            self.DeclareVectorInputPort(name, size)
        for shape in SHAPES:
            self.DeclareVectorInputPort(f"{shape}_resemblance", 1)
        self.DeclareVectorInputPort("evidence", 9)
        self._table_top_port = self.DeclareVectorInputPort("table_top", TableTopVector.SIZE)
        self._cost_port = self.DeclareVectorInputPort("exploration_cost", CostVector.SIZE)
        self._outcome_port = self.DeclareAbstractInputPort("exploration_outcome", AbstractValue.Make({"kind": "full"}))
        self.DeclareAbstractOutputPort("estimate", lambda: AbstractValue.Make(ObjectEstimate(status=OBJECT_NOT_FOUND)),
                                       self._CalcEstimate, {self.all_input_ports_ticket()})

    def _CalcEstimate(self, context: Context, output: AbstractValue) -> None:
        def read(name):
            return np.asarray(self.GetInputPort(name).Eval(context), float)

        estimate = gather_estimate(
            phase_value(read("phase")[0]), read("centre"), read("camera_sample")[13:16], read("axis"),
            read("axis_info"), read("extents"), {s: read(f"{s}_resemblance")[0] for s in SHAPES}, read("evidence"),
            read("extents_frame"), self._TableTop(context))
        if self._cost_port.HasValue(context):
            cost = CostVector.from_vector(self._cost_port.Eval(context))
            outcome = self._outcome_port.Eval(context) if self._outcome_port.HasValue(context) else {"kind": "full"}
            estimate = dataclasses.replace(estimate, exploration={**outcome, **cost.to_dict()})
        output.set_value(estimate)

    def _TableTop(self, context: Context):
        if not self._table_top_port.HasValue(context):
            return None
        return TableTopVector.from_vector(self._table_top_port.Eval(context))
