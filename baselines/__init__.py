"""Baselines the compliance-centric algorithm is compared with."""
