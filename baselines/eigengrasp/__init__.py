"""GraspIt!'s Eigengrasp simulated-annealing planner, reimplemented (DESIGN.md §7)."""
