"""The choices of the wrist camera's exploration, as one dataclass: a part of the scenario.

`station.Scenario.perception` holds one; its numbers live in diagrams/station.scenarios.yaml under
`perception:` (a scenario variant such as `color_segmentation` changes only what it names). The
schema sits below the station so that a scenario can hold it; `perception` builds the exploration
from it.
"""

import dataclasses
import math
import typing

from drake_grasp.control.camera_motion import CameraMotionParams
from drake_grasp.funnel.params import FunnelParams
from drake_grasp.primitives.camera import SegmentationParams
from drake_grasp.primitives.depth import DepthParams
from drake_grasp.primitives.principal_axis import PrincipalAxisParams
from drake_grasp.primitives.resemblance import DEFAULT_ARCS, ResemblanceParams
from drake_grasp.primitives.scores import SHAPES, ScoreParams
from drake_grasp.primitives.sequencer import SequencerParams
from drake_grasp.primitives.table_top import TableTopParams


@dataclasses.dataclass
class PerceptionConfig:
    """Every choice of the exploration (a scenario's `perception`)."""

    rate_hz: float = 20.0
    start_height: float = 0.45
    segmentation: SegmentationParams = dataclasses.field(default_factory=SegmentationParams)
    sequencer: SequencerParams = dataclasses.field(default_factory=SequencerParams)
    depth: DepthParams = dataclasses.field(default_factory=DepthParams)
    axis: PrincipalAxisParams = dataclasses.field(default_factory=PrincipalAxisParams)
    sphere: ResemblanceParams = dataclasses.field(default_factory=lambda: dataclasses.replace(DEFAULT_ARCS["sphere"]))
    cylinder: ResemblanceParams = dataclasses.field(
        default_factory=lambda: dataclasses.replace(DEFAULT_ARCS["cylinder"]))
    box: ResemblanceParams = dataclasses.field(default_factory=lambda: dataclasses.replace(DEFAULT_ARCS["box"]))
    scores: ScoreParams = dataclasses.field(default_factory=ScoreParams)
    camera_motion: CameraMotionParams = dataclasses.field(default_factory=CameraMotionParams)
    start_configuration: list[float] = dataclasses.field(default_factory=lambda: [0.0, 0.6, 0.0, 1.6, 0.0, 0.9, 0.0])
    # The table-top estimate from depth views (primitives.table_top); None: the silhouettes' estimate
    # alone, as in the paper. None is left out of the scenario's YAML dump (fingerprints unchanged).
    table_top: typing.Optional[TableTopParams] = None
    # The funnel search on the shape the depth views saw (funnel.search); None: each grasp at its
    # primitive's pose, as in the paper. It needs the table-top estimate's height map.
    grasp_search: typing.Optional[FunnelParams] = None

    @property
    def period(self) -> float:
        return 1.0 / self.rate_hz

    def validate(self) -> None:
        if not (math.isfinite(self.rate_hz) and 10.0 <= self.rate_hz <= 30.0):
            raise ValueError(f"rate_hz must be in [10, 30] Hz, got {self.rate_hz}")
        if not (math.isfinite(self.start_height) and self.start_height > 0):
            raise ValueError(f"start_height must be positive, got {self.start_height}")
        if len(self.start_configuration) != 7:
            raise ValueError("start_configuration needs 7 joint angles")
        self.segmentation.validate()
        self.sequencer.validate()
        if self.sequencer.minimal is not None and self.table_top is None:
            raise ValueError("sequencer.minimal (the minimal exploration) needs the table-top estimate "
                             "(perception.table_top): its confirming arc turns about the depth views' centre and axis")
        for shape in SHAPES:
            getattr(self, shape).validate()
        if self.grasp_search is not None:
            if self.table_top is None:
                raise ValueError("grasp_search (the funnel search) needs the table-top estimate (perception.table_top): "
                                 "it closes the hand on the shape its depth views saw")
            self.grasp_search.validate()
        if self.table_top is not None:
            self.table_top.validate()
            ratio = self.table_top.view_period * self.rate_hz
            if abs(ratio - round(ratio)) > 1e-6:
                raise ValueError(f"table_top.view_period must be a multiple of the camera period (1/rate_hz = "
                                 f"{self.period:g} s), got {self.table_top.view_period}")
