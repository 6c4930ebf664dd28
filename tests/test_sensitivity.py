"""The sensitivity sweep: its conditions as scenarios, the claims' verdicts, and a tiny real sweep."""

import io
import json

import pytest

from drake_grasp.studies import sensitivity as S
from drake_grasp.studies import sensitivity_report as R
from drake_grasp.sweeps.fingerprint import scenario_fingerprint
from drake_grasp.station import load_scenario

NINE = ("banana", "apple", "bell_pepper", "sponge", "spectacle_case", "toy_bridge", "soccer_ball", "game_box",
        "bottle_case")


# --- The conditions file (pure apart from the file it writes) ---------------------------------------


def test_default_conditions_change_one_factor_each():
    conditions = S.default_conditions()
    assert [c.name for c in conditions] == ["base", "friction_0.3", "friction_0.8", "friction_1.0", "mass_x0.5",
                                            "mass_x2", "color", "color_noise_10"]
    for c in conditions[1:]:
        changed = [f for f in ("friction", "mass_scale", "segmentation") if getattr(c, f) is not None]
        assert changed == [{"friction": "friction", "mass": "mass_scale", "perception": "segmentation"}[c.factor]]


def test_conditions_file_loads_back_as_each_conditions_scenario(tmp_path):
    config = S.SensitivityConfig(objects=("apple",), trials=1)
    path = tmp_path / "conditions.yaml"
    S.write_conditions(path, config)
    loaded = {c.name: load_scenario(path, c.name) for c in config.conditions}
    assert loaded["friction_0.3"].contact.friction == 0.3 and loaded["friction_1.0"].contact.friction == 1.0
    assert loaded["mass_x0.5"].object.mass_scale == 0.5 and loaded["mass_x2"].object.mass_scale == 2.0
    assert loaded["base"].object.mass_scale is None and loaded["base"].contact.friction == 0.5
    color, noisy = loaded["color"].perception.segmentation, loaded["color_noise_10"].perception.segmentation
    assert color.method == "color" and color.largest_component_only and color.color_noise is None
    assert noisy.method == "color" and noisy.color_noise.sigma == 10.0
    # Each condition differs only in its factor: the base and the colour condition are exactly the
    # repository's default and color_segmentation scenarios (same fingerprints: records are shared).
    assert scenario_fingerprint(str(path), "base") == scenario_fingerprint("", "default")
    assert scenario_fingerprint(str(path), "color") == scenario_fingerprint("", "color_segmentation")
    assert len({scenario_fingerprint(str(path), c.name) for c in config.conditions}) == len(config.conditions)
    # Rewriting the same file leaves it alone.
    stamp = path.stat().st_mtime_ns
    S.write_conditions(path, config)
    assert path.stat().st_mtime_ns == stamp


def test_conditions_derive_from_the_base_scenario(tmp_path, short_scenario_file):
    config = S.SensitivityConfig(objects=("apple",), trials=1, scenario_file=str(short_scenario_file))
    S.write_conditions(tmp_path / "c.yaml", config)
    for c in config.conditions:
        assert load_scenario(tmp_path / "c.yaml", c.name).protocol.execution.hold_time == 0.5


def test_specs_use_fig6s_seeds_and_cover_conditions_evenly():
    config = S.SensitivityConfig(objects=("apple", "sponge"), trials=2, seed=5)
    specs = S.trial_specs(config, "/x/conditions.yaml")
    assert len(specs) == 2 * 8 * 2
    assert {(s.method, s.grasp, s.scenario_file) for s in specs} == {("compliant", "", "/x/conditions.yaml")}
    assert [s.seed for s in specs[:16]] == [5] * 16 and {s.seed for s in specs[16:]} == {6}


@pytest.mark.parametrize("kwargs, message", [
    ({"trials": 0}, "trials"),
    ({"objects": ("apple", "apple")}, "twice"),
    ({"conditions": (S.Condition("a b", "base", "x"),)}, "name"),
    ({"conditions": (S.Condition("m", "mass", "m", mass_scale=-1.0),)}, "mass scale"),
    ({"conditions": (S.Condition("n", "perception", "n", noise_sigma=3.0),)}, "noise"),
])
def test_bad_configs_are_one_line_errors(kwargs, message):
    with pytest.raises(ValueError, match=message):
        S.SensitivityConfig(**kwargs)


# --- Claims (pure: rows made by hand) -----------------------------------------------------------------


def _rows(obj, outcomes, chosen="spherical", failure="slipped during hold"):
    return [{"object": obj, "success": "1" if ok else "0", "failure": "" if ok else failure,
             "extra": json.dumps({"chosen": chosen})} for ok in outcomes]


def _table():
    conditions = S.default_conditions()[:3]  # base, friction 0.3, friction 0.8
    objects = ("apple", "soccer_ball")
    rows = {
        "base": _rows("apple", [1, 1, 1, 1]) + _rows("soccer_ball", [1, 1, 1, 1]),
        "friction_0.3": _rows("apple", [0, 0, 0, 0]) + _rows("soccer_ball", [1, 1, 1, 1], chosen="box"),
        "friction_0.8": _rows("apple", [1, 1, 1, 0]) + _rows("soccer_ball", [1, 1, 1, 1]),
    }
    return R.tabulate(rows, objects), conditions, objects


def test_claims_hold_or_flip_per_condition():
    table, conditions, objects = _table()
    results = {r.claim: r for r in R.claims(table, conditions, objects)}
    overall = results["Fig. 6: the algorithm's chosen grasps succeed"]
    assert overall.per_condition["base"].verdict == "holds"
    assert overall.per_condition["base"].certainty == "unsure"  # 8/8: the interval reaches 67.6 %
    assert overall.per_condition["friction_0.3"].verdict == "flips"  # 4/8 = 50 % < 85.6 %
    assert overall.per_condition["friction_0.8"].verdict == "holds"  # 7/8 = 87.5 %
    assert overall.across(conditions) == "flips under friction 0.3"
    apple = results["apple: the chosen grasp holds it"]
    assert [apple.per_condition[c.name].verdict for c in conditions] == ["holds", "flips", "holds"]
    assert apple.per_condition["friction_0.3"].certainty == "sure"  # 0/4: the interval tops out at 49 %
    ball = results["soccer_ball (a sun ray): the algorithm chooses the spherical grasp"]
    assert ball.per_condition["friction_0.3"].ours == "0/4 spherical"
    assert ball.across(conditions) == "flips under friction 0.3"
    assert results["soccer_ball: the chosen grasp holds it"].across(conditions) == "holds in every condition"


def test_a_condition_without_trials_is_not_judged():
    table, conditions, objects = _table()
    table["friction_0.8"] = {o: R.Cell() for o in objects}
    overall = R.claims(table, conditions, objects)[0]
    assert overall.per_condition["friction_0.8"].verdict == "n/a"
    assert overall.across(conditions) == "flips under friction 0.3"


def test_summary_has_rates_with_intervals_the_table_and_the_verdicts(tmp_path):
    table, conditions, objects = _table()
    config = S.SensitivityConfig(objects=objects, trials=4, conditions=conditions)
    text = "\n".join(R.summary_lines(table, config, 0.5, "Cost: test."))
    assert "Trials: **24** (4 per object and condition" in text
    assert "| friction 0.3 | 0.3 (0.375) | x1 | label image | 50 % (4/8, 95 % CI 22-78 %) | slipped during hold 4 |" in text
    assert "| apple | 4/4 (spherical 4) | 0/4 (spherical 4) | 3/4 (spherical 4) |" in text
    assert "flips (unsure): 4/8" not in text and "flips (sure)" not in text
    assert "Flip somewhere: " in text and "Cost: test." in text
    R.write_conditions_csv(tmp_path / "conditions.csv", table, conditions)
    lines = (tmp_path / "conditions.csv").read_text().splitlines()
    assert lines[2].startswith("friction_0.3,friction,friction 0.3,4,8,0.5000,")
    paths = R.plot(table, conditions, tmp_path)
    assert all(p.stat().st_size > 1000 for p in paths)


def test_pair_friction_is_drakes_combination():
    assert R.pair_friction(0.5) == 0.5
    assert R.pair_friction(0.3) == pytest.approx(0.375)
    assert R.pair_friction(1.0) == pytest.approx(2 / 3)


def test_cost_note_scales_to_the_full_sweep():
    note = R.cost_note({"trials": 10, "cpu_seconds": 200.0, "wall_seconds": 150.0}, conditions=8)
    assert "20.0 CPU-seconds per trial" in note and "288 trials" in note and "1.6 core-hours" in note
    assert R.cost_note({}, 8) == ""


# --- A tiny real sweep --------------------------------------------------------------------------------


def test_a_tiny_real_sweep_runs_resumes_and_writes_its_report(tmp_path, short_scenario_file):
    conditions = tuple(c for c in S.default_conditions() if c.name in ("base", "mass_x2"))
    config = S.SensitivityConfig(objects=("sponge",), trials=1, conditions=conditions,
                                 scenario_file=str(short_scenario_file))
    progress = io.StringIO()
    result = S.run_sensitivity(config, tmp_path / "out", workers=1, progress=progress)
    assert result.trials == 2
    assert {name: R.totals(cells)[1] for name, cells in result.table.items()} == {"base": 1, "mass_x2": 1}
    assert "sensitivity: 2/2 sponge compliant/ seed 0" in progress.getvalue()
    out = tmp_path / "out"
    for name in ("conditions.yaml", "sensitivity.csv", "conditions.csv", "cost.json", "summary.md",
                 "sensitivity.png", "sensitivity.svg"):
        assert (out / name).is_file(), name
    assert json.loads((out / "cost.json").read_text())["trials"] == 2
    summary = (out / "summary.md").read_text()
    assert "Trials: **2**" in summary and "| mass x2 |" in summary
    # A rerun computes nothing and reports the same.
    progress = io.StringIO()
    again = S.run_sensitivity(config, out, workers=1, progress=progress)
    assert "resuming, 2/2 trials already" in progress.getvalue()
    assert again.lines == result.lines
    assert json.loads((out / "cost.json").read_text())["trials"] == 2


def test_script_rejects_bad_input_before_any_work(tmp_path, capsys):
    from script_loader import load_script

    script = load_script("sensitivity", "sensitivity_script")
    for argv, message in ((["--trials", "0"], "--trials"), (["--objects", "nope"], "unknown object"),
                          (["--conditions", "base,zzz"], "--conditions"), (["--noise-sigma", "-1"], "--noise-sigma"),
                          (["--out", str(tmp_path / "f.txt")], "not a directory"),
                          (["--scenario", str(tmp_path / "missing.yaml")], "cannot read")):
        (tmp_path / "f.txt").write_text("x")
        assert script.main(argv + ["--quick"]) == 2, argv
        err = capsys.readouterr().err
        assert message in err and err.count("\n") == 1, err
    assert not (tmp_path / "out").exists()
