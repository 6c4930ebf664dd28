"""drake-grasp: compliance-centric grasping with a BarrettHand on a Barrett WAM, in Drake.

The package layout follows the module map in docs/design.md (§1): facts about the hardware (`hand`, `arm`),
objects (`objects`: the catalogue, users' files, convex pieces, generators), pure math (`quality`,
`vision`), Drake systems (`primitives`, `control`), perception (`perception`), the station builder
(`station`), trials (`trial`), the sweep machinery (`sweeps`) and the studies (`studies`). The names
documented as public for scripts are in `drake_grasp.api`.
"""

__version__ = "0.2.0"
