"""Fig. 6's analysis: statistics, the algorithm's choice, the summary and the figure."""

import json

import pytest

from drake_grasp.studies import fig6


def _row(obj, grasp, seed, success, sphere, cylinder, box):
    extra = {"resemblance": {"sphere": sphere, "cylinder": cylinder, "box": box}}
    return {"object": obj, "grasp": grasp, "seed": str(seed), "success": "1" if success else "0",
            "extra": json.dumps(extra)}


def test_choice_is_the_highest_mean_resemblance_and_summary_counts_its_successes(tmp_path):
    rows = []
    for seed in range(4):
        for grasp in fig6.GRASPS:
            # A ball: sphere resemblance high; only the spherical grasp holds it.
            rows.append(_row("soccer_ball", grasp, seed, grasp == "spherical" or seed == 0, 0.95, 0.3, 0.2))
            # A box: box resemblance high; all grasps hold it but one trial of the box grasp.
            rows.append(_row("game_box", grasp, seed, not (grasp == "box" and seed == 3), 0.1, 0.4, 0.8))
    stats = fig6.grasp_stats(rows, ["soccer_ball", "game_box"])
    assert fig6.chosen_grasp(stats["soccer_ball"]) == "spherical"
    assert fig6.chosen_grasp(stats["game_box"]) == "box"
    assert stats["soccer_ball"]["cylindrical"].successes == 1
    assert stats["game_box"]["box"].rate == pytest.approx(0.75)
    lines = fig6.summary_lines(stats)
    assert lines[-1].startswith("chosen grasps: 88 % (7/8, 95 % CI 53-98 %)")
    assert "paper: 96 % (86/90" in lines[-1]
    paths = fig6.plot(stats, tmp_path)
    assert all(p.exists() and p.stat().st_size > 1000 for p in paths)


def test_config_rejects_no_trials():
    with pytest.raises(ValueError, match="--trials"):
        fig6.Fig6Config(objects=("apple",), trials=0)


def test_a_small_real_sweep_runs_resumes_and_plots(tmp_path, short_scenario_file):
    # Real trials (oracle estimates, 0.5 s hold, to stay short), through the same pool and table.
    import io

    from drake_grasp.sweeps.runner import run_trials

    scenario = short_scenario_file
    config = fig6.Fig6Config(objects=("sponge",), trials=1, seed=5, method="oracle")
    specs = fig6.trial_specs(config, str(scenario))
    table = run_trials(specs, tmp_path / "fig6.csv", workers=1, progress=io.StringIO())
    assert len(table) == 3
    progress = io.StringIO()
    again = run_trials(specs, tmp_path / "fig6.csv", workers=1, progress=progress)
    assert "resuming, 3/3" in progress.getvalue() and len(again) == 3
    stats = fig6.grasp_stats(again, config.objects)
    assert fig6.chosen_grasp(stats["sponge"]) == "box"  # the oracle's choice: the sponge's true class
    assert all(p.exists() for p in fig6.plot(stats, tmp_path))


def test_the_study_runs_on_a_users_own_objects(tmp_path, capsys, short_scenario_file):
    # --objects: the same sweep, table and figure for any objects (here a primitive and a mesh file).
    import trimesh

    from drake_grasp import cli

    mesh = tmp_path / "brick.stl"
    trimesh.creation.box((0.05, 0.12, 0.05)).export(mesh)
    scenario = short_scenario_file
    out = tmp_path / "out"
    assert cli.main(["fig6", "--objects", f"cube:0.06,{mesh}", "--trials", "1", "--method", "oracle",
                     "--workers", "1", "--scenario", str(scenario), "--out", str(out), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["trials"] == 6 and (out / "fig6.png").exists()
    # The oracle chooses the true class: a cube's is known, a user mesh's is not.
    assert result["summary"][0].startswith("cube:0.06: chosen box; spherical ")
    assert result["summary"][1].startswith(f"{mesh}: chosen -; spherical ")
    for bad, message in (("nope", "unknown object 'nope'"), (" , ", "at least one object"),
                         ("apple,apple", "twice")):
        assert cli.main(["fig6", "--objects", bad, "--out", str(out)]) == 2
        assert message in capsys.readouterr().err


def test_plot_labels_name_mesh_files_by_their_stem():
    from drake_grasp.sweeps.results import axis_label

    assert axis_label("bottle_case") == "bottle\ncase"
    assert axis_label("/data/my_mug.stl") == "my\nmug"
    assert axis_label("sphere:0.12") == "sphere:0.12"
