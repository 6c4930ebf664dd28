"""Letting go: where the object rests when the robot tries again.

An attempt can fail with the object still in the hand: it slipped in the fingers during the hold, or
the wrist camera did not see it held (`trial.sensing`). A real robot then opens the hand and backs off,
the object falls onto the table, and the next attempt's fresh look (`trial.attempts`) sees it where it
came to rest. This module gives that rest: the object is let fall from the pose the attempt left it in,
with no velocity, onto the station's table alone (the hand and arm gone: they backed off), in the
scenario's own physics (its plant configuration and contact), until it moves slower than
`objects.settling.REST_SPEED` or LET_FALL_TIME has passed. An object the attempt left lying on the
table stays where it is.

Why it matters (behaviour 0.51.0): before, the next attempt began with the object floating where the
hand had held it, and it fell while the camera's exploration looked. The first views saw it in the air,
and the estimate put it where it no longer was: in the stored records of behaviour 0.50.0 (five novel
seeds, three everyday seeds), 24 of the 42 attempts that followed an attempt ending with the object in
the hand missed it.
"""

from __future__ import annotations

from pydrake.math import RigidTransform
from pydrake.multibody.parsing import FlattenModelDirectives, ModelDirectives, Parser, ProcessModelDirectives
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from drake_grasp.objects import ObjectSpec
from drake_grasp.objects.drake_model import AddObject
from drake_grasp.objects.settling import advance_to_rest
from drake_grasp.paths import RegisterPackage
from drake_grasp.station import Scenario

# How long the object may take to come to rest, s: a fall from the lift's height takes about 0.2 s, and
# a ring or a bottle that lands on its edge rolls for a second or two.
LET_FALL_TIME = 4.0
TABLE = "table"  # the model instance of the station's table in the scenario's directives


def table_directives(directives: list, parser: Parser) -> ModelDirectives:
    """The scenario's `directives`, flattened, less everything but the table and its weld: the world
    the object falls into once the robot has backed off."""
    flat = FlattenModelDirectives(ModelDirectives(directives=directives), parser.package_map())
    kept = [d for d in flat.directives
            if (d.add_model is not None and d.add_model.name == TABLE)
            or (d.add_weld is not None and d.add_weld.child.startswith(f"{TABLE}::"))]
    return ModelDirectives(directives=kept)


def let_fall(scenario: Scenario, spec: ObjectSpec, X_WO: RigidTransform) -> RigidTransform:
    """The object `spec` (as the station simulates it: friction and mass as given), let go at rest at
    the world pose `X_WO`: its pose once it lies still on the scenario's table (module docstring)."""
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(scenario.plant_config, builder)
    parser = RegisterPackage(Parser(plant))
    ProcessModelDirectives(table_directives(scenario.directives, parser), parser)
    (index,) = plant.GetBodyIndices(AddObject(plant, spec, scenario.contact))
    body = plant.get_body(index)
    plant.SetDefaultFloatingBaseBodyPose(body, X_WO)
    plant.Finalize()
    simulator = Simulator(builder.Build())
    context = plant.GetMyContextFromRoot(simulator.get_context())
    advance_to_rest(simulator, body, context, LET_FALL_TIME)
    return body.EvalPoseInWorld(context)
