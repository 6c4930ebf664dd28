"""The visual primitives (paper Sec. 4; docs/design.md §2): active vision with the eye-in-hand camera.

LeafSystems (each with declared, named ports; see `drake_grasp.perception` for the wiring):

- `camera.SilhouetteCamera`: samples the wrist camera at a fixed rate (label image by default) and
  publishes a `camera_sample`: the object's silhouette features and the camera pose.
- `depth.DepthPrimitive`: keeps the object centred while circling it; estimates its centre, depth and
  size.
- `principal_axis.PrincipalAxisPrimitive`: aligns the blob's axis with the image border, arcs around
  it, estimates the axis in space.
- `resemblance.ShapeResemblancePrimitive` (sphere, cylinder, box): resemblance in [0, 1] from the
  variation of contour area and eccentricity over the camera's motion.
- `sequencer.ExplorationSequencer`: the phases (approach; depth + axis; resemblance) as commands.

Every primitive takes a `command` (`common.PrimitiveCommand`) and outputs a desired camera twist
`V_C_desired`; the twists are summed and turned into arm motion by
`drake_grasp.control.camera_motion.CameraTwistController`.

Pure math, testable on arrays: `camera_model` (pinhole, twists, arcs), `silhouette` (features of a
mask, the sample vector), `estimators` (rays, interpretation planes, tangent planes and the
support-function fit), `scores` (the resemblance scores), `sphere_tolerances` (where the sphere
score's tolerances come from).
"""

from drake_grasp.primitives.camera import SegmentationParams, SilhouetteCamera
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.primitives.common import PrimitiveCommand, VisualPrimitive
from drake_grasp.primitives.depth import DepthParams, DepthPrimitive
from drake_grasp.primitives.principal_axis import PrincipalAxisParams, PrincipalAxisPrimitive
from drake_grasp.primitives.resemblance import ResemblanceParams, ShapeResemblancePrimitive
from drake_grasp.primitives.scores import SHAPES, ScoreParams, ShapeEvidence
from drake_grasp.primitives.sequencer import ExplorationSequencer, ExplorationPhase, SequencerParams
from drake_grasp.primitives.silhouette import CameraSample, Silhouette

__all__ = [
    "CameraIntrinsics",
    "CameraSample",
    "DepthParams",
    "DepthPrimitive",
    "ExplorationSequencer",
    "ExplorationPhase",
    "PrimitiveCommand",
    "PrincipalAxisParams",
    "PrincipalAxisPrimitive",
    "ResemblanceParams",
    "SHAPES",
    "ScoreParams",
    "SegmentationParams",
    "SequencerParams",
    "ShapeEvidence",
    "ShapeResemblancePrimitive",
    "Silhouette",
    "SilhouetteCamera",
    "VisualPrimitive",
]
