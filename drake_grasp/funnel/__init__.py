"""The widest funnel on the shape the camera saw (issue: hold what users bring)."""
