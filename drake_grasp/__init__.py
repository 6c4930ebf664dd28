"""drake-grasp: compliance-centric grasping with a BarrettHand on a Barrett WAM, in Drake.

The package layout follows the module map in docs/design.md (§1): facts about the hardware (`hand`, `arm`),
the object catalogue (`objects`), pure math (`quality`, `vision`), Drake systems (`primitives`,
`control`), the station builder (`station`), trials (`trial`) and experiments (`experiments`).
"""

__version__ = "0.1.0"
