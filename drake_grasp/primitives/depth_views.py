"""Depth views for the table-top estimate: the wrist camera's depth images gathered into height maps.

`DepthViews` samples the depth image (and the mask the silhouette camera uses) every
`TableTopParams.view_period` s while the exploration runs, back-projects the object's pixels and
raises two height maps with them, the views dealt alternately to each (`table_top.HeightMap`). Its
`table_top` output is the estimate of both maps together and the spread of the two halves
(`table_top.estimate`, `table_top.spread`), as a vector the ObjectEstimator reads
(`TableTopVector`). Each view also carves the free space it saw through out of the columns under the
object (`free_space.carve`, when `TableTopParams.carve`): the `height_map` output's carved levels. It steers
nothing: the exploration, and so every silhouette primitive, is the same with it as without it.
"""

import dataclasses
import math

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.framework import Context, LeafSystem
from pydrake.systems.sensors import ImageDepth32F

from drake_grasp.primitives import free_space, table_top
from drake_grasp.primitives.camera import SilhouetteCamera
from drake_grasp.primitives.camera_model import CameraIntrinsics


@dataclasses.dataclass
class TableTopVector:
    """The `table_top` output (world frame; m, degrees), 32 numbers:

    valid (1: an estimate), centre (3), principal_axis (3), sides (3), extents_axis (3),
    extents_sides (3), height, cells, clipped (1: the object overran the map), views; then the spread
    of the two halves: centre, axis_deg, extents (3) (NaN while either half has no estimate); the
    table's height, the height map's reference plane (what the object stands on, known to the scene);
    and the estimate's edge rise (`table_top.edge_rise`), grip width (`table_top.grip_width`), grip
    axis (3) and grip reach (`table_top.grip_reach`).
    """

    SIZE = 32

    estimate: table_top.TableTopEstimate | None
    spread: table_top.Spread | None
    clipped: bool
    views: int
    table_height: float = 0.0

    def to_vector(self) -> np.ndarray:
        v = np.full(self.SIZE, np.nan)
        v[0] = 0.0 if self.estimate is None else 1.0
        e = self.estimate
        if e is not None:
            v[1:17] = np.concatenate([e.centre, e.principal_axis, e.sides, e.extents_axis, e.extents_sides,
                                      [e.height]])
            v[17] = e.cells
            v[26], v[27] = e.edge_rise, e.grip_width
            if e.grip_axis is not None:
                v[28:31] = e.grip_axis
            v[31] = e.grip_reach
        v[18], v[19] = float(self.clipped), float(self.views)
        if self.spread is not None:
            v[20], v[21], v[22:25] = self.spread.centre, self.spread.axis_deg, self.spread.extents
        v[25] = self.table_height
        return v

    @classmethod
    def from_vector(cls, v) -> "TableTopVector":
        v = np.asarray(v, float)
        estimate = None
        if v[0] > 0.5:
            estimate = table_top.TableTopEstimate(
                centre=v[1:4].copy(), principal_axis=v[4:7].copy(), sides=v[7:10].copy(),
                extents_axis=v[10:13].copy(), extents_sides=v[13:16].copy(), height=float(v[16]),
                cells=int(v[17]), edge_rise=float(v[26]), grip_width=float(v[27]),
                grip_axis=v[28:31].copy() if np.all(np.isfinite(v[28:31])) else None, grip_reach=float(v[31]))
        spread = None if not math.isfinite(v[20]) else table_top.Spread(float(v[20]), float(v[21]), v[22:25].copy())
        return cls(estimate, spread, bool(v[18] > 0.5), int(v[19]), float(v[25]))


class DepthViews(LeafSystem):
    """Gathers depth views into two half height maps; outputs the table-top estimate (module docstring).

    Input ports:
        depth_image (ImageDepth32F): the wrist camera's depth image.
        label_image (ImageLabel16I) or color_image (ImageRgba8U): what the silhouette camera segments
            (its `image_input_port`'s type; the same mask, `SilhouetteCamera.mask`).
        X_WC (RigidTransform): the camera's pose.
        active (1): 0 stops the views (the exploration is over); unconnected, always active.
    Output ports:
        table_top (27): `TableTopVector`, computed from the state (only when a view changed it).
        height_map (abstract `table_top.HeightMap`): both halves' views together, with the carved
            levels (the funnel search closes the hand on its column solid: `funnel.observed_shape`).
    """

    # The state's head: [origin set (1/0), origin x, origin y, views, clipped]; the two maps' heights
    # follow, then their support points (`table_top.HeightMap.support`), then the carved levels of both
    # (`free_space.carve`: one float of bits per cell).
    _HEAD = 5

    def __init__(self, camera: SilhouetteCamera, params: table_top.TableTopParams, table_height: float = 0.0):
        super().__init__()
        params.validate()
        self.params = params
        self.camera = camera
        self.intrinsics: CameraIntrinsics = camera.intrinsics
        self.table_height = float(table_height)
        n = params.cells
        self._depth_port = self.DeclareAbstractInputPort("depth_image", AbstractValue.Make(ImageDepth32F()))
        mask_port = camera.image_input_port()
        self._image_port = self.DeclareAbstractInputPort(mask_port.get_name(), mask_port.Allocate())
        self._pose_port = self.DeclareAbstractInputPort("X_WC", AbstractValue.Make(RigidTransform()))
        self._active_port = self.DeclareVectorInputPort("active", 1)
        initial = np.concatenate([np.zeros(self._HEAD), np.full(2 * n * n, np.nan),
                                  np.full(2 * table_top.SUPPORT_DIRECTIONS * 2, np.nan), np.zeros(n * n)])
        self._state = self.DeclareDiscreteState(initial)
        self.DeclareVectorOutputPort("table_top", TableTopVector.SIZE, self._CalcTableTop,
                                     {self.discrete_state_ticket(self._state)})
        self.DeclareAbstractOutputPort(
            "height_map", lambda: AbstractValue.Make(table_top.HeightMap.around((0.0, 0.0), params.cell, n)),
            self._CalcHeightMap, {self.discrete_state_ticket(self._state)})
        self.DeclarePeriodicDiscreteUpdateEvent(params.view_period, 0.0, self._View)

    def image_input_port(self):
        """The mask's image input (``label_image`` or ``color_image``, as the silhouette camera's)."""
        return self._image_port

    def maps(self, state: np.ndarray) -> tuple[table_top.HeightMap, table_top.HeightMap]:
        """The two half maps held in a state vector (views 0, 2, 4, ... and 1, 3, 5, ...)."""
        n = self.params.cells
        origin = np.asarray(state[1:3], float)
        clipped = bool(state[4] > 0.5)
        return tuple(table_top.HeightMap(origin.copy(), self.params.cell,
                                         np.array(state[self._HEAD + k * n * n:self._HEAD + (k + 1) * n * n]).reshape(n, n),
                                         self.table_height, clipped, np.array(state[self._support_slice(k)]).reshape(-1, 2))
                     for k in (0, 1))

    def _support_slice(self, half: int) -> slice:
        """Where half map `half`'s support points lie in the state (after both maps' heights)."""
        n, k = self.params.cells, 2 * table_top.SUPPORT_DIRECTIONS
        start = self._HEAD + 2 * n * n + half * k
        return slice(start, start + k)

    def _carved_slice(self) -> slice:
        """Where the carved levels lie in the state (after both maps' support points)."""
        n = self.params.cells
        start = self._support_slice(1).stop
        return slice(start, start + n * n)

    def _View(self, context: Context, discrete_state) -> None:
        if self._active_port.HasValue(context) and self._active_port.Eval(context)[0] < 0.5:
            return
        t = context.get_time()
        image = self.camera.noisy(self._image_port.Eval(context).data, t)
        mask = self.camera.mask(image)
        if not np.any(mask):
            return
        X_WC = self._pose_port.Eval(context)
        depth = self._depth_port.Eval(context).data
        points = table_top.back_project(depth, mask, self.intrinsics, X_WC.rotation().matrix(), X_WC.translation(),
                                        self.params.pixel_stride)
        above = points[points[:, 2] > self.table_height]
        if len(above) == 0:
            return
        state = context.get_discrete_state(self._state).get_value().copy()
        n = self.params.cells
        if state[0] < 0.5:  # the first view places the map around what it sees
            state[0] = 1.0
            state[1:3] = table_top.HeightMap.around(np.mean(above[:, :2], axis=0), self.params.cell, n).origin
        half = int(state[3]) % 2
        height_map = self.maps(state)[half]
        height_map.add(above)
        state[self._HEAD + half * n * n:self._HEAD + (half + 1) * n * n] = height_map.heights.reshape(-1)
        state[self._support_slice(half)] = height_map.support.reshape(-1)
        if self.params.carve:
            both = self.maps(state)
            heights = np.fmax(both[0].heights, both[1].heights)
            bits = np.asarray(state[self._carved_slice()]).reshape(n, n)
            state[self._carved_slice()] = free_space.carve(
                bits, heights, both[0].origin, self.params.cell, self.table_height, depth, self.intrinsics,
                X_WC.rotation().matrix(), X_WC.translation()).reshape(-1)
        state[3] += 1.0
        state[4] = float(height_map.clipped or state[4] > 0.5)
        discrete_state.get_mutable_vector(self._state).SetFromVector(state)

    def _CalcHeightMap(self, context: Context, output: AbstractValue) -> None:
        state = context.get_discrete_state(self._state).get_value()
        first, second = self.maps(state)
        both = first.merged(second)
        if self.params.carve:
            n = self.params.cells
            both.carved = np.array(state[self._carved_slice()]).reshape(n, n)
        output.set_value(both)

    def _CalcTableTop(self, context: Context, output) -> None:
        state = context.get_discrete_state(self._state).get_value()
        output.SetFromVector(table_top_vector(self.maps(state), int(state[3]), self.params.min_cells).to_vector())


def table_top_vector(maps: tuple[table_top.HeightMap, table_top.HeightMap], views: int,
                     min_cells: int) -> TableTopVector:
    """The estimate of both half maps together, and the spread of the halves."""
    first, second = maps
    both = first.merged(second)
    whole = table_top.estimate(both, min_cells)
    halves = [table_top.estimate(m, min_cells) for m in maps]
    bracket = 0.0 if whole is None else whole.centre_bracket
    return TableTopVector(whole, table_top.spread(*halves, both.cell, bracket), both.clipped, views, both.table_height)


class TableTopFrame(LeafSystem):
    """The table-top estimate as the frame the resemblance primitives explore in (the minimal
    exploration's): its centre, and its principal axis where that lies within 45° of the table (a lying
    object's), else a side of its footprint (horizontal: a round or upright object's). After the approach
    alone the depth and principal-axis primitives have not explored yet (their centre is their prior,
    their axis as often the view direction as the object's), while the depth views already hold the
    object's top.

    Input ports:
        table_top (27): `TableTopVector`.
    Output ports:
        centre (3), axis (3): world frame (m; unit vector), NaN before an estimate.
    """

    def __init__(self):
        super().__init__()
        self._table_top_port = self.DeclareVectorInputPort("table_top", TableTopVector.SIZE)
        self.DeclareVectorOutputPort("centre", 3, lambda context, output: output.SetFromVector(self.frame(context)[0]))
        self.DeclareVectorOutputPort("axis", 3, lambda context, output: output.SetFromVector(self.frame(context)[1]))

    def frame(self, context: Context) -> tuple[np.ndarray, np.ndarray]:
        return table_top_frame(TableTopVector.from_vector(self._table_top_port.Eval(context)))


def table_top_frame(vector: TableTopVector) -> tuple[np.ndarray, np.ndarray]:
    """(centre, axis) of a table-top estimate (`TableTopFrame`); NaN without one."""
    estimate = vector.estimate
    if estimate is None:
        return np.full(3, np.nan), np.full(3, np.nan)
    axis = np.asarray(estimate.principal_axis, float)
    if abs(axis[2]) > math.cos(math.radians(45.0)):
        axis = np.asarray(estimate.sides, float)
    return np.asarray(estimate.centre, float), axis
