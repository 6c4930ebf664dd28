"""GraspIt!'s Eigengrasp simulated-annealing planner, reimplemented (docs/design.md §4.6).

Modules, one concept each:

* ``eigengrasps``: the Barrett's eigengrasp basis and origin; amplitudes -> joint angles.
* ``virtual_contacts``: the 19 virtual contacts on our hand model, and where they are for a posture.
* ``search_space``: the axis-angle hand pose relative to the object (8 variables with the amplitudes).
* ``annealing``: GraspIt!'s very fast simulated annealing (schedule, neighbours, acceptance).
* ``energy``: the ``contact`` and ``contact-quality`` energies on plain arrays.
* ``object_distance``: distances from points to the object's pieces (numpy).
* ``scene``: the Drake side (hand and object in one SceneGraph: collision test, exact distances).
* ``planner``: the loop, the best list, autograsp and ε ranking: ``EigengraspPlanner``,
  ``plan_eigengrasp``.

Command line: ``drake-grasp plan-eigengrasp --object NAME``.
"""
