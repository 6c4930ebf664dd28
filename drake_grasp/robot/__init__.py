"""The robot's hardware facts and the model files made from them.

* `hand`: the BarrettHand BH8-280 (the BH8 manual's D-H table, ranges, gears, breakaway, masses) and
  its compliance modes;
* `arm`: the 7-DoF Barrett WAM (classical D-H, joint and effort limits, masses, home, mount);
* `contact`: the contact parameters (friction, hydroelastic modulus, damping) as SDFormat snippets;
* `modelgen`: writes models/*/*.sdf from `hand` and `arm` (`drake-grasp models`).

Pure facts and numbers (layer 0 of docs/design.md's module map), except `modelgen`, which uses Drake's
RigidTransform to write the files.
"""
