"""Letting go (`trial.release`): where the object rests when the robot tries again."""

import pytest
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant

from drake_grasp.objects import resolve_object
from drake_grasp.paths import RegisterPackage
from drake_grasp.station import load_scenario
from drake_grasp.trial.release import let_fall, table_directives


def test_only_the_table_is_left_when_the_robot_has_backed_off():
    scenario = load_scenario()
    kept = table_directives(scenario.directives, RegisterPackage(Parser(MultibodyPlant(0.0)))).directives
    models = [d.add_model.name for d in kept if d.add_model is not None]
    welds = [d.add_weld.child for d in kept if d.add_weld is not None]
    assert models == ["table"] and welds == ["table::table_top"]


def test_an_object_let_go_in_the_air_falls_to_rest_on_the_table():
    """A 6 cm cube let go 12 cm above the table, turned as a slipping grasp leaves it: it lands, and
    lies still on a face (the table top is z = 0)."""
    scenario, spec = load_scenario(), resolve_object("cube:0.06")
    X = let_fall(scenario, spec, RigidTransform(RollPitchYaw(0.3, 0.0, 0.5), [0.55, 0.02, 0.15]))
    assert X.translation()[2] == pytest.approx(0.03, abs=0.002)
    assert abs(X.translation()[0] - 0.55) < 0.1 and abs(X.translation()[1] - 0.02) < 0.1
    # On a face: the cube's z axis is vertical or horizontal again.
    up = abs(X.rotation().matrix()[2, 2])
    assert up == pytest.approx(1.0, abs=0.02) or up == pytest.approx(0.0, abs=0.02)


def test_an_object_left_lying_on_the_table_stays_where_it_is():
    scenario, spec = load_scenario(), resolve_object("cube:0.06")
    X_rest = RigidTransform(RollPitchYaw(0.0, 0.0, 0.4), [0.5, -0.05, 0.03])
    X = let_fall(scenario, spec, X_rest)
    assert X.translation() == pytest.approx(X_rest.translation(), abs=0.001)
    assert (X_rest.rotation().inverse() @ X.rotation()).ToAngleAxis().angle() < 0.01
