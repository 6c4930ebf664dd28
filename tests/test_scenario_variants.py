"""The scenario parts the sensitivity sweep varies: the object's mass scale and the colour image's noise.

Both are optional fields whose default (omitted) leaves every existing scenario, and so every existing
record's fingerprint, as it was.
"""

import dataclasses
import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.sensors import ImageRgba8U

from drake_grasp.control.arm_motion import ArmKinematics
from drake_grasp.sweeps.fingerprint import digest, scenario_text
from drake_grasp.objects.drake_model import with_mass_scale
from drake_grasp.objects import resolve_object
from drake_grasp.perception import trial_noise_seed
from drake_grasp.primitives.camera import ColorNoise, SegmentationParams, SilhouetteCamera
from drake_grasp.primitives.camera_model import CameraIntrinsics
from drake_grasp.station import DEFAULT_SCENARIO_FILE, MakeStation, load_scenario
from drake_grasp.vision import add_image_noise

EXISTING = ("default", "step_10ms", "point_contact", "color_segmentation")


# --- Defaults leave every existing scenario's YAML dump (its fingerprint) unchanged ------------------


@pytest.mark.parametrize("name", EXISTING)
def test_the_new_fields_are_left_out_of_existing_scenarios_dumps(name):
    scenario = load_scenario(DEFAULT_SCENARIO_FILE, name)
    assert scenario.object.mass_scale is None and scenario.perception.segmentation.color_noise is None
    text = scenario_text(scenario)
    assert "mass_scale" not in text and "color_noise" not in text


def test_set_fields_enter_the_dump_and_the_fingerprint(tmp_path):
    path = tmp_path / "s.yaml"
    path.write_text("heavy:\n  object: {mass_scale: 2.0}\n"
                    "noisy:\n  perception:\n    segmentation:\n      method: color\n"
                    "      color_noise: {sigma: 8.0}\n")
    heavy, noisy = load_scenario(path, "heavy"), load_scenario(path, "noisy")
    assert heavy.object.mass_scale == 2.0
    assert noisy.perception.segmentation.color_noise == ColorNoise(sigma=8.0, seed=0)
    base = digest(scenario_text(load_scenario()))
    assert "mass_scale: 2.0" in scenario_text(heavy) and digest(scenario_text(heavy)) != base
    assert "sigma: 8.0" in scenario_text(noisy) and digest(scenario_text(noisy)) != base


@pytest.mark.parametrize("yaml, message", [
    ("object: {mass_scale: -1.0}", "object.mass_scale"),
    ("object: {mass_scale: .nan}", "object.mass_scale"),
    ("perception: {segmentation: {color_noise: {sigma: 5.0}}}", "needs method 'color'"),
    ("perception: {segmentation: {method: color, color_noise: {sigma: -2.0}}}", "sigma"),
])
def test_bad_values_are_one_line_errors(tmp_path, yaml, message):
    path = tmp_path / "bad.yaml"
    path.write_text(f"bad:\n  {yaml}\n")
    with pytest.raises(ValueError, match=message) as e:
        load_scenario(path, "bad")
    assert "\n" not in str(e.value)


# --- Mass scale ---------------------------------------------------------------------------------------


def test_mass_scale_scales_mass_and_inertia_only():
    spec = resolve_object("banana")
    assert with_mass_scale(spec, None) is spec and with_mass_scale(spec, 1.0) is spec
    heavy = with_mass_scale(spec, 2.0)
    assert heavy.mass == pytest.approx(2 * spec.mass)
    assert heavy.inertia == pytest.approx(tuple(2 * v for v in spec.inertia))
    same = {f.name for f in dataclasses.fields(spec)} - {"mass", "inertia"}
    assert all(getattr(heavy, f) == getattr(spec, f) for f in same)
    with pytest.raises(ValueError, match="mass scale"):
        with_mass_scale(spec, 0.0)


def test_the_station_plants_body_has_the_scaled_mass():
    scenario = load_scenario()
    scenario.object.name = "game_box"
    spec = resolve_object("game_box")
    scenario.object.mass_scale = 0.5
    station = MakeStation(scenario, camera=False)
    body = station.plant.get_body(station.plant.GetBodyIndices(station.object_instance)[0])
    assert body.default_mass() == pytest.approx(0.5 * spec.mass)
    inertia = body.default_spatial_inertia()
    assert inertia.get_com() == pytest.approx(np.zeros(3))  # the centre of mass stays at O
    I = inertia.CalcRotationalInertia().CopyToFullMatrix3()
    ixx, iyy, izz, ixy, ixz, iyz = spec.inertia
    expected = 0.5 * np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
    np.testing.assert_allclose(I, expected, rtol=1e-6, atol=1e-12)
    assert station.object_spec.mass == pytest.approx(0.5 * spec.mass)
    assert station.object_spec.extents == spec.extents


# --- Colour noise -------------------------------------------------------------------------------------


def _yellow_square() -> np.ndarray:
    rgba = np.zeros((240, 320, 4), np.uint8)
    rgba[..., :3] = (204, 230, 255)  # the background's light blue
    rgba[..., 3] = 255
    rgba[80:160, 120:200, :3] = (230, 200, 30)  # yellow paper
    return rgba


def test_add_image_noise_is_seeded_and_keeps_alpha():
    image = _yellow_square()
    assert np.array_equal(add_image_noise(image, 0.0, np.random.default_rng(1)), image)
    a = add_image_noise(image, 10.0, np.random.default_rng(1))
    b = add_image_noise(image, 10.0, np.random.default_rng(1))
    c = add_image_noise(image, 10.0, np.random.default_rng(2))
    assert a.dtype == np.uint8 and np.array_equal(a, b) and not np.array_equal(a, c)
    assert np.array_equal(a[..., 3], image[..., 3])
    centre = a[100:140, 140:180, :3].astype(float) - image[100:140, 140:180, :3]
    assert np.std(centre) == pytest.approx(10.0, rel=0.1)
    assert a[..., 2].max() == 255  # clipped, not wrapped
    with pytest.raises(ValueError):
        add_image_noise(image.astype(float), 1.0, np.random.default_rng(0))


def _camera(noise: ColorNoise | None, noise_seed: int = 0) -> SilhouetteCamera:
    K = CameraIntrinsics(width=320, height=240, fx=200.0, fy=200.0, cx=159.5, cy=119.5)
    return SilhouetteCamera(K, [7], 0.05, SegmentationParams(method="color", largest_component_only=True,
                                                            color_noise=noise), noise_seed)


def test_camera_noise_off_gives_the_same_mask_and_on_is_deterministic_per_seed():
    image = _yellow_square()
    clean = _camera(None)
    assert clean.noisy(image, 0.35) is image
    clean_mask = clean.mask(image)
    assert clean_mask.sum() == 80 * 80
    assert np.array_equal(_camera(ColorNoise(sigma=0.0)).mask(_camera(ColorNoise(sigma=0.0)).noisy(image, 0.35)),
                          clean_mask)
    noisy = _camera(ColorNoise(sigma=40.0), noise_seed=123)
    m1 = noisy.mask(noisy.noisy(image, 0.35))
    m2 = _camera(ColorNoise(sigma=40.0), noise_seed=123).mask(noisy.noisy(image, 0.35))
    assert np.array_equal(m1, m2)  # same trial key, same image index: same mask
    assert not np.array_equal(m1, noisy.mask(noisy.noisy(image, 0.40)))  # the next image: other noise
    other = _camera(ColorNoise(sigma=40.0), noise_seed=124)
    assert not np.array_equal(m1, other.mask(other.noisy(image, 0.35)))  # another trial: other noise
    offset = _camera(ColorNoise(sigma=40.0, seed=1), noise_seed=123)
    assert not np.array_equal(m1, offset.mask(offset.noisy(image, 0.35)))


def test_trial_noise_key_follows_the_trials_variation():
    from drake_grasp.protocol import TrialVariation
    from drake_grasp.trial import apply_variation

    scenario = load_scenario()
    spec = resolve_object("apple")

    def key(seed):
        varied, varied_spec = apply_variation(scenario, spec, TrialVariation.draw(seed, scenario.protocol))
        return trial_noise_seed(MakeStation(varied, varied_spec, camera=False))

    assert key(3) == key(3) and len({key(0), key(1), key(2)}) == 3


def test_noise_of_ten_counts_on_a_rendered_image_changes_the_mask_only_at_the_edges():
    # A small real check: the station's colour image of the apple from 0.3 m above, segmented as the
    # color_segmentation scenario does, without and with 10 counts of noise.
    scenario = load_scenario(DEFAULT_SCENARIO_FILE, "color_segmentation")
    scenario.object.name = "apple"
    station = MakeStation(scenario)
    plant = station.plant
    context = station.diagram.CreateDefaultContext()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    p_WO = station.X_WO_nominal().translation()
    q = ArmKinematics(plant, station.wam).solve(RigidTransform(RotationMatrix.MakeXRotation(math.pi), p_WO + [0, 0, 0.3]),
                                                np.array([0, 0.6, 0, 1.6, 0, 0.9, 0]))
    plant.SetPositions(plant_context, station.wam, q)
    image = station.diagram.GetOutputPort("camera.color_image").Eval(context)
    assert isinstance(image, ImageRgba8U)
    params = dataclasses.replace(scenario.perception.segmentation, color_noise=ColorNoise(sigma=10.0))
    K = CameraIntrinsics.from_camera_config(scenario.camera)
    camera = SilhouetteCamera(K, [0], 0.05, params, trial_noise_seed(station))
    clean = camera.mask(image.data)
    noisy = camera.mask(camera.noisy(image.data, 1.0))
    assert clean.sum() > 500
    overlap = (clean & noisy).sum() / (clean | noisy).sum()
    assert 0.9 < overlap < 1.0, overlap  # the noise moves some edge pixels, not the blob


@pytest.mark.slow
def test_a_noisy_colour_trial_gives_the_same_record_for_the_same_seed(short_scenario):
    from drake_grasp.trial import run_compliant_trial

    scenario = short_scenario
    scenario.perception.segmentation = dataclasses.replace(
        load_scenario(DEFAULT_SCENARIO_FILE, "color_segmentation").perception.segmentation,
        color_noise=ColorNoise(sigma=10.0))
    spec = resolve_object("sponge")
    records = [dataclasses.asdict(run_compliant_trial(scenario, spec, seed=1)) for _ in range(2)]
    for r in records:
        r.pop("wall_time")
    import json

    assert json.dumps(records[0], sort_keys=True, default=str) == json.dumps(records[1], sort_keys=True, default=str)
    assert records[0]["estimate_source"] == "camera" and records[0]["resemblances"]
