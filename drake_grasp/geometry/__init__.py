"""Geometry of user objects: cleaning the shapes handed to Drake, the solid a mesh encloses, and a
generator of novel test objects."""
