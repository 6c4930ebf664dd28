"""The studies: the paper's three experiments and the ones beyond it, each one module (with its
report where it has one), built on the sweep machinery (:mod:`drake_grasp.sweeps`).

* the paper: `fig4` (quasi-static ε), `fig6` (the compliant grasps against their resemblance),
  `fig7` (against the Eigengrasp planner), `reproduce` (all of them, a report, `report_page` and
  `replays` for the results page);
* beyond the paper: `novel` (generated objects), `capture` and `capture_region` (capture regions),
  `epsilon_physics` and `calibration` (ε against physics), `sensitivity` and `sensitivity_report`,
  `near_primitives` and `near_primitives_report`.
"""
