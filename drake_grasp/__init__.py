"""drake-grasp: compliance-centric grasping with a BarrettHand on a Barrett WAM, in Drake.

The package layout follows the module map in docs/design.md (§1): the robot's facts and model files
(`robot`: hand, arm, contact, modelgen), objects (`objects`: the catalogue, users' files, convex
pieces, generators), pure math (`quality`, `vision`), Drake systems (`primitives`, `control`),
perception (`perception`), the station builder (`station`), trials (`trial`), the sweep machinery
(`sweeps`) and the studies (`studies`). The names documented as public for scripts are in
`drake_grasp.api`.
"""

# The release: raised when the public interface changes (modules moved or removed: CHANGELOG.md).
__version__ = "0.53.0"

# What a trial does: part of every stored record's fingerprint (sweeps/fingerprint.py). Raised whenever
# a change alters what a trial measures in any scenario, and only then, so that a release that only
# moves modules keeps every stored study record valid (docs/design.md §5.8).
BEHAVIOUR_VERSION = "0.53.0"
