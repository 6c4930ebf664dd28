"""The station: scenario loading, model hygiene, the wrist camera, and the pick-up demo."""

import logging
import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.analysis import Simulator

from drake_grasp import cli
from drake_grasp.control.arm_motion import ArmKinematics
from drake_grasp.demo import run_demo
from drake_grasp.station import MakeStation, load_scenario
from drake_grasp.vision import blob_features, mask_from_label


@pytest.fixture
def scenario():
    return load_scenario()


def test_station_builds_and_simulates_without_warnings(scenario, caplog):
    caplog.set_level(logging.WARNING, logger="drake")
    station = MakeStation(scenario)
    simulator = Simulator(station.diagram)
    context = simulator.get_mutable_context()
    plant_context = station.plant.GetMyContextFromRoot(context)
    q0 = station.plant.GetPositions(plant_context, station.wam)
    station.diagram.GetInputPort("wam.desired_state").FixValue(context, np.concatenate([q0, np.zeros(7)]))
    station.diagram.GetInputPort("hand.command").FixValue(context, [0.0, 0.0])
    simulator.AdvanceTo(0.1)
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING], caplog.text
    # Gravity-compensated and commanded to stay: the arm does not sag.
    q1 = station.plant.GetPositions(station.plant.GetMyContextFromRoot(context), station.wam)
    assert np.abs(q1 - q0).max() < math.radians(0.5)


def test_scenario_errors_are_one_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("default:\n  plant_config: {time_step: -1}\n")
    with pytest.raises(ValueError, match="time_step") as e:
        load_scenario(bad)
    assert "\n" not in str(e.value)
    bad.write_text("default:\n  object: [unclosed\n")
    with pytest.raises(ValueError, match="malformed") as e:
        load_scenario(bad)
    assert "\n" not in str(e.value)
    with pytest.raises(ValueError, match="cannot read"):
        load_scenario(tmp_path / "missing.yaml")


def test_wrist_camera_sees_the_object_at_the_image_centre(scenario):
    scenario.object.name = "apple"
    station = MakeStation(scenario)
    plant = station.plant
    context = station.diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    # Palm 0.3 m above the object, palm normal (and camera axis) pointing straight down.
    p_WO = station.X_WO_nominal().translation()
    R_WP = RotationMatrix.MakeXRotation(math.pi)
    kinematics = ArmKinematics(plant, station.wam)
    q = kinematics.solve(RigidTransform(R_WP, p_WO + [0, 0, 0.3]), np.array([0, 0.6, 0, 1.6, 0, 0.9, 0]))
    plant.SetPositions(plant_context, station.wam, q)
    label = station.diagram.GetOutputPort("camera.label_image").Eval(context).data
    object_body = plant.get_body(plant.GetBodyIndices(station.object_instance)[0])
    features = blob_features(mask_from_label(label, int(object_body.index())))
    assert features is not None, "the object is not in the label image"
    height, width = label.shape[:2]
    u, v = features.centroid
    assert abs(u - (width - 1) / 2) < 0.05 * width and abs(v - (height - 1) / 2) < 0.05 * height
    assert features.eccentricity < 1.1  # an apple seen from above is round
    # Depth at the object's centre is the distance from the camera to the apple's top.
    depth = station.diagram.GetOutputPort("camera.depth_image").Eval(context).data
    camera_height = 0.3 + 0.002
    top = p_WO[2] + station.object_spec.extents[2] / 2
    assert depth[height // 2, width // 2, 0] == pytest.approx(p_WO[2] + camera_height - top, abs=0.005)


def test_demo_lifts_and_holds_a_ball(scenario):
    # The default suite's short version of the demo: 2 s hold instead of 10 s.
    result = run_demo(scenario, hold_time=2.0)
    assert result.held, result.summary()
    assert result.lift > 0.08
    assert result.slip_distance < 0.005
    assert result.grasp == "spherical"


@pytest.mark.slow
def test_demo_full_hold_on_two_objects(scenario):
    for name in ("soccer_ball", "bottle_case"):
        scenario.object.name = name
        result = run_demo(scenario)
        assert result.held, result.summary()
        assert result.slip_distance < 0.01


@pytest.mark.parametrize(
    "argv, message",
    [
        (["demo", "--object", "no_such_thing"], "unknown object"),
        (["demo", "--object", "/no/such/mesh.stl"], "not found"),
        (["demo", "--object", "sphere:nan"], "sphere"),
        (["demo", "--object", "soccer_ball", "--seed", "-3"], "--seed"),
        (["demo", "--object", "soccer_ball", "--replay", "/no/such/dir/out.html"], "does not exist"),
    ],
)
def test_cli_bad_input_is_one_line_and_exit_code_2(argv, message, capsys):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert message in err
    assert err.count("\n") == 1 and "Traceback" not in err
