"""Deprecated: the studies moved to :mod:`drake_grasp.studies` (the paper's figures and the
beyond-paper studies) and the machinery every study uses to :mod:`drake_grasp.sweeps` (results,
fingerprints, locks, reaper, executors, runner, stats); ``drake_grasp.experiments.<module>`` works
for one release, with a DeprecationWarning."""
