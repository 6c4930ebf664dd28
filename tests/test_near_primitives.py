"""The near-primitive generator (drake_grasp.objects.near_primitives) and its study's pure parts."""

import json
import math

import numpy as np
import pytest
import trimesh

from drake_grasp.objects import near_primitives as npr

COUNT = 16  # four of each class


@pytest.fixture(scope="module")
def objects():
    return [npr.near_primitive(3, i) for i in range(COUNT)]


def test_classes_cycle_and_map_to_primitives(objects):
    assert [o.shape_class for o in objects[:4]] == list(npr.CLASSES)
    assert {o.primitive for o in objects} == {"sphere", "box", "cylinder"}
    assert all(npr.PRIMITIVE_OF_CLASS[o.shape_class] == o.primitive for o in objects)


def test_meshes_are_watertight_convex_solids_resting_on_their_base(objects):
    for o in objects + [npr.perfect_mesh(c) for c in npr.PERFECT]:
        m = o.mesh
        assert m.is_watertight and m.is_winding_consistent and m.volume > 0, o.name
        assert m.volume == pytest.approx(m.convex_hull.volume, rel=1e-4), o.name
        assert np.allclose(m.bounds.mean(axis=0), 0.0, atol=1e-6), o.name  # centred
        assert 0.04 <= np.max(m.extents) <= 0.30, o.name


def test_parameters_within_the_stated_ranges(objects):
    def within(value, low_high, slack=1e-12):
        return low_high[0] - slack <= value <= low_high[1] + slack

    for o in objects:
        p = o.params
        if o.shape_class == "ellipsoid":
            assert within(2 * p["radius"], npr.SPHERE_DIAMETER)
            deviations = np.array(p["semi_axes"]) / p["radius"] - 1.0
            assert np.all(np.abs(deviations) <= npr.ELLIPSOID_DEVIATION + 1e-12)
            assert p["semi_axes"][2] == min(p["semi_axes"])  # rests on its smallest semi-axis
        elif o.shape_class == "rounded_box":
            assert all(within(s, npr.BOX_SIDE) for s in p["sides"])
            assert within(p["fillet_fraction"], npr.BOX_FILLET)
            assert p["fillet"] == pytest.approx(p["fillet_fraction"] * min(p["sides"]))
        else:
            assert within(p["diameter"], npr.CYLINDER_DIAMETER) and within(p["aspect"], npr.CYLINDER_ASPECT)
            assert p["length"] == pytest.approx(p["aspect"] * p["diameter"])
            if o.shape_class == "tapered_cylinder":
                assert within(p["taper"], npr.CYLINDER_TAPER)
                assert (p["radius_big"] - p["radius_small"]) / (p["diameter"] / 2) == pytest.approx(p["taper"])
            else:
                assert within(p["bulge"], npr.CYLINDER_BULGE) and within(p["end_fillet"], npr.CYLINDER_END_FILLET)


def test_volumes_match_the_shapes_formulas(objects):
    """The meshes are inner approximations of the nominal solids, within a few per cent."""
    for o in objects:
        p, volume = o.params, o.mesh.volume
        if o.shape_class == "ellipsoid":
            nominal = 4.0 / 3.0 * math.pi * np.prod(p["semi_axes"])
        elif o.shape_class == "rounded_box":
            # Steiner: inner box (a, b, c) grown by a ball of radius r.
            r = p["fillet"]
            a, b, c = np.array(p["sides"]) - 2 * r
            nominal = a * b * c + 2 * (a * b + b * c + c * a) * r + math.pi * (a + b + c) * r**2 + 4 / 3 * math.pi * r**3
        elif o.shape_class == "tapered_cylinder":
            r1, r2 = p["radius_big"], p["radius_small"]
            nominal = math.pi * p["length"] / 3.0 * (r1 * r1 + r1 * r2 + r2 * r2)
        else:
            r, length = p["diameter"] / 2, p["length"]
            low = math.pi * r * r * length * (1 - 0.6 * p["end_fillet"] ** 2 * 2 * r / length)  # rounded ends
            high = math.pi * (r * (1 + p["bulge"])) ** 2 * length
            assert 0.97 * low <= volume <= high, o.name
            continue
        assert volume == pytest.approx(nominal, rel=0.03), o.name
        assert volume <= nominal * (1 + 1e-6), o.name  # inside the nominal solid


def test_perfect_meshes_have_no_departure():
    sphere, box, cylinder = (npr.perfect_mesh(c) for c in ("ellipsoid", "rounded_box", "tapered_cylinder"))
    assert np.allclose(sphere.mesh.extents, 0.09, atol=1e-6)
    assert len(box.mesh.vertices) == 8 and np.allclose(sorted(box.mesh.extents), [0.06, 0.07, 0.10], atol=1e-6)
    assert cylinder.mesh.extents[0] == pytest.approx(0.18, abs=1e-6)
    assert cylinder.mesh.extents[1] == pytest.approx(0.065, abs=1e-3)


def test_every_object_rests_stably_as_generated(objects):
    """The loader's own test (else it would turn the object over, with a warning); a tapered cylinder
    rests on a side facet made horizontal, not on an end's rim."""
    from drake_grasp.objects.mesh_files import _rests_stably_upright

    for o in objects:
        m = o.mesh
        assert _rests_stably_upright(m.convex_hull, np.asarray(m.center_mass)), o.name
        if o.shape_class == "tapered_cylinder":
            z_min = m.vertices[:, 2].min()
            bottom = (m.face_normals[:, 2] < -1 + 1e-6) & (np.abs(m.triangles[:, :, 2] - z_min).max(axis=1) < 1e-6)
            assert m.area_faces[bottom].sum() > 1e-4, o.name  # a quad facet along the length, flat on the table


def test_same_seed_gives_byte_identical_files(tmp_path):
    a = npr.generate(6, 7, tmp_path / "a", perfect=True)
    npr.generate(6, 7, tmp_path / "b", perfect=True)
    npr.generate(3, 7, tmp_path / "c")
    npr.generate(6, 8, tmp_path / "d")
    for row in a:
        assert (tmp_path / "a" / row["file"]).read_bytes() == (tmp_path / "b" / row["file"]).read_bytes()
    for row in a[:3]:  # object i of seed s does not depend on how many were generated
        assert (tmp_path / "a" / row["file"]).read_bytes() == (tmp_path / "c" / row["file"]).read_bytes()
    other = {p.name: p.read_bytes() for p in (tmp_path / "d").glob("*.obj")}
    assert all(other[row["file"].replace("_7_", "_8_")] != (tmp_path / "a" / row["file"]).read_bytes()
               for row in a[:6])
    manifest = json.loads((tmp_path / "a" / "manifest.json").read_text())
    assert manifest == a and [r["primitive"] for r in a[:4]] == ["sphere", "box", "cylinder", "cylinder"]
    mesh = trimesh.load(tmp_path / "a" / a[0]["file"], process=True)
    assert mesh.is_watertight and mesh.volume == pytest.approx(a[0]["volume_m3"], rel=1e-5)


def test_bad_arguments():
    with pytest.raises(ValueError):
        npr.near_primitive(-1, 0)
    with pytest.raises(ValueError):
        npr.draw_parameters("torus", np.random.default_rng(0))
    with pytest.raises(ValueError):
        npr.rounded_box_mesh([0.1, 0.1, 0.1], 0.06)


# --- The study's pure parts: the sphere's tolerances, re-scoring, the report -----------------------

import pathlib  # noqa: E402

from drake_grasp.studies import near_primitives as study  # noqa: E402
from drake_grasp.studies import near_primitives_report as analysis  # noqa: E402
from drake_grasp.primitives import scores, sphere_tolerances  # noqa: E402


def test_the_configured_sphere_scales_are_derived_from_the_10_percent_ellipsoids():
    tau_s, tau_se = sphere_tolerances.sphere_scales_from_ellipsoids()
    default = scores.ScoreParams()
    assert default.sphere_variation_scale == pytest.approx(tau_s, abs=1e-3)
    assert default.sphere_roundness_scale == pytest.approx(tau_se, abs=1e-3)
    scenario = study._scenario("", "default")
    assert scenario.perception.scores == default  # the scenario file says the same


@pytest.mark.parametrize("semi_axes", [[1.1, 1.1, 0.9], [1.1, 0.9, 0.9]])
def test_the_extreme_10_percent_ellipsoids_are_at_one_half(semi_axes):
    assert sphere_tolerances.ellipsoid_evidence(np.array(semi_axes) * 0.05).sphere == pytest.approx(0.5, abs=0.005)


@pytest.mark.parametrize("semi_axes", [[1.05, 0.95, 0.92], [1.0, 1.0, 1.0], [1.08, 1.02, 0.95], [1.1, 1.0, 0.9],
                                       [1.0, 1.0, 0.9]])
def test_ideal_ellipsoids_within_10_percent_are_spheres(semi_axes):
    new = sphere_tolerances.ellipsoid_evidence(np.array(semi_axes) * 0.05)
    assert new.sphere > 0.5 and new.sphere == max(new.sphere, new.cylinder, new.box)


def test_ideal_boxes_and_cylinders_keep_their_primitive():
    shapes = {"box": [npr.rounded_box_mesh([0.1, 0.07, 0.06], 0.0), npr.rounded_box_mesh([0.08, 0.08, 0.08], 0.016),
                      npr.rounded_box_mesh([0.12, 0.06, 0.05], 0.005)],
              "cylinder": [npr.tapered_cylinder_mesh(0.18, 0.035, 0.03), npr.rounded_cylinder_mesh(0.2, 0.03, 0.05, 0.2)]}
    for primitive, meshes in shapes.items():
        for mesh in meshes:
            stats = sphere_tolerances.ideal_statistics(np.asarray(mesh.vertices), 0.7, 0.5)
            evidence = scores.evaluate(stats, scores.ScoreParams())
            assert max(scores.SHAPES, key=evidence.resemblance) == primitive, (primitive, mesh.extents, evidence)


def test_main_scorer_is_the_old_formula_and_misses_a_near_sphere():
    stats = sphere_tolerances.ideal_statistics(trimesh.creation.icosphere(3).vertices * [0.055, 0.05, 0.046],
                                               0.7, 0.5)
    old, new = analysis.main_scorer(stats.to_vector()), analysis.rescore(stats.to_vector())
    e = old["evidence"]
    assert old["sphere"] == pytest.approx(e.roundness * e.invariance_a * e.invariance_b)
    assert old["box"] == pytest.approx(1 - max(e.invariance_a, e.roundness * e.invariance_b))
    assert old["best"] != "sphere" and new["best"] == "sphere"


def test_fingerprint_leaves_the_scorer_out():
    text = "a:\n  b: 1\n  scores:\n    x: 1\n    y:\n      z: 2\n  c: 3\nscores:\n  w: 1\nd: 4\n"
    assert study.without_block(text, "scores") == "a:\n  b: 1\n  c: 3\nd: 4\n"
    task = study.Task("sphere:0.09", "perfect", "primitive", "sphere", 0)
    scenario = study._scenario("", "default")
    import dataclasses

    other = dataclasses.replace(scenario, perception=dataclasses.replace(
        scenario.perception, scores=scores.ScoreParams(sphere_variation_scale=0.2)))
    assert study.exploration_fingerprint(task, scenario) == study.exploration_fingerprint(task, other)
    moved = dataclasses.replace(scenario, perception=dataclasses.replace(scenario.perception, rate_hz=15.0))
    assert study.exploration_fingerprint(task, scenario) != study.exploration_fingerprint(task, moved)


def _fake_record(obj, set_, shape_class, primitive, stats, seed=0):
    best = analysis.rescore(stats.to_vector())
    return {"fingerprint": "0" * 16, "set": set_, "object": obj, "class": shape_class, "primitive": primitive,
            "seed": str(seed), "found": "1", **{s: repr(best[s]) for s in scores.SHAPES}, "best": best["best"],
            "scorer": analysis.scorer_fingerprint(), "statistics": json.dumps(stats.to_vector().tolist()),
            "evidence": "{}", "errors": "{}", "wall_time": "1.0", "detail": ""}


def test_report_tables_and_figure_from_records(tmp_path):
    rows = npr.generate(4, 2, tmp_path / "objs")
    records = []
    for row in rows:
        mesh = trimesh.load(tmp_path / "objs" / row["file"], process=True)
        stats = sphere_tolerances.ideal_statistics(np.asarray(mesh.vertices), 0.7, 0.5, samples=11)
        records.append(_fake_record(str(tmp_path / "objs" / row["file"]), "near", row["class"], row["primitive"], stats))
    records.append({**records[0], "object": "lost.obj", "found": "0", "statistics": "[]", "detail": "object not found"})
    figure = tmp_path / "np.png"
    text = analysis.report({"development": records, "perfect": records[:1]}, command="x", seeds=(2, 3), count=1,
                           figure=figure, wall=1.0, cpu=1.0, workers=1, baseline=analysis.main_scorer)
    assert figure.is_file() and figure.stat().st_size > 1000
    assert "| development | ellipsoid | sphere |" in text and "95 % CI" in text
    assert "| sphere | " in text and "none |" in text  # the confusion table, with the lost object
    assert "equal the re-scored ones" in text
    acc = analysis.accuracy_rows(analysis.score_records(records))
    assert ("all sphere", "sphere", 1, 2) in acc  # the ideal ellipsoid right, the lost one not


def test_script_bad_arguments_one_line_exit_2(capsys):
    from script_loader import load_script

    script = load_script("near_primitives_check")
    for argv, message in ((["--count", "0"], "--count must be >= 1"), (["--seed", "1"], "evaluation seed must differ"),
                          (["--workers", "0"], "--workers must be >= 1"), (["--report", "x.txt"], "expected a .md"),
                          (["--bogus"], "unrecognized arguments")):
        assert script.main(argv) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("near_primitives_check: error:") and message in err[0], err


def test_one_real_exploration_names_a_near_sphere(tmp_path):
    """The study's whole path on one generated ellipsoid (semi-axes 37/35/35 mm): explored
    as `drake-grasp resemble` does it (default perception, about 15 s), named a sphere (on main: a
    cylinder), its record resumable and re-scored to the run's own resemblances."""
    obj = npr.near_primitive(0, 12)
    assert obj.shape_class == "ellipsoid"
    path = tmp_path / "ellipsoid.obj"
    path.write_text(npr.obj_text(obj.mesh))
    task = study.Task(str(path), "near", "ellipsoid", "sphere", 12)
    records = study.run([task], tmp_path / "explorations.csv")
    (record,) = records
    assert record["found"] == "1" and record["best"] == "sphere", record
    scored = analysis.score_records(records, baseline=analysis.main_scorer)[0]
    assert analysis.run_agrees(scored, analysis.scorer_fingerprint()) is True
    assert scored.chosen("before") != "sphere"  # the scorer on main missed it
    assert study.run([task], tmp_path / "explorations.csv") == records  # resumed, not run again


def test_run_study_writes_summary_and_figure_and_resumes(tmp_path, monkeypatch):
    """The orchestration (objects, lock, records, summary.md, figure, resume) with the exploration
    replaced by ideal silhouettes of a sphere (no simulation)."""
    from drake_grasp.sweeps.executors import LocalExecutor

    sphere = sphere_tolerances.ideal_statistics(trimesh.creation.icosphere(2).vertices * 0.05, 0.7, 0.5, samples=7)

    def fake_explore(task):
        record = _fake_record(task.object, task.set, task.shape_class, task.primitive, sphere, task.seed)
        record.pop("fingerprint")
        return {**record, "statistics": json.loads(record["statistics"]), "evidence": {}, "errors": {}}

    monkeypatch.setattr(study, "explore_one", fake_explore)
    config = study.StudyConfig(count=1, seed=4, eval_seed=5, reference_seeds=1, catalogue=False)
    text = study.run_study(config, tmp_path, LocalExecutor(1), progress=__import__("io").StringIO())
    assert (tmp_path / "summary.md").read_text() == text and (tmp_path / study.FIGURE).is_file()
    assert "this invocation computed 14 of them" in text  # 6 perfect + 4 + 4 near-primitives
    assert "| evaluation | all box | box |" in text
    again = study.run_study(config, tmp_path, LocalExecutor(1), progress=__import__("io").StringIO())
    assert "this invocation computed 0 of them" in again
    with pytest.raises(ValueError, match="must differ"):
        study.run_study(study.StudyConfig(seed=1, eval_seed=1), tmp_path, LocalExecutor(1))
