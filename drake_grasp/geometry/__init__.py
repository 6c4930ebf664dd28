"""Deprecated: the geometry of user objects moved to :mod:`drake_grasp.objects` (cleaning, solid,
novel, near_primitives); these paths work for one release, with a DeprecationWarning."""
