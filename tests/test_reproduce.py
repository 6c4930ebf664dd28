"""The reproduction report: verdicts follow the stated rules from the measured numbers."""

import json

from drake_grasp.studies import fig6, fig7, reproduce


def _stats(rates: dict[str, dict[str, float]]):
    rows = []
    for obj, per in rates.items():
        for grasp, rate in per.items():
            for i in range(10):
                rows.append({"object": obj, "grasp": grasp, "seed": str(i), "success": "1" if i < rate * 10 else "0",
                             "extra": json.dumps({"resemblance": {"sphere": 0.9 if grasp == "spherical" else 0.1,
                                                                  "cylinder": 0.2, "box": 0.1}})})
    return fig6.grasp_stats(rows, list(rates))


def test_fig6_claims_follow_the_rules():
    stats = _stats({"apple": {"spherical": 1.0, "cylindrical": 0.9, "box": 0.8},
                    "soccer_ball": {"spherical": 1.0, "cylindrical": 0.1, "box": 0.0}})
    claims = {c.claim: c for c in reproduce.fig6_claims(stats)}
    assert claims["Fig. 6: the chosen grasps succeed"].agrees == "yes"  # 20/20 is within 10 points of 95.6 %
    assert claims["Fig. 6: in the annulus all three grasps do about equally well"].agrees == "yes"
    assert claims["Fig. 6: on the soccer ball only the spherical grasp works"].agrees == "yes"
    worse = _stats({"soccer_ball": {"spherical": 1.0, "cylindrical": 1.0, "box": 0.0}})
    claims = {c.claim: c for c in reproduce.fig6_claims(worse)}
    assert claims["Fig. 6: on the soccer ball only the spherical grasp works"].agrees == "partly"


def test_fig7_claims_and_report(tmp_path):
    rows = [fig7.Comparison("soccer_ball", 1.0, 10, "spherical", 0.0, 0.0, 30, {}),
            fig7.Comparison("game_box", 1.0, 10, "box", 0.2, 0.6, 30, {})]
    claims = reproduce.fig7_claims(rows)
    verdicts = {c.claim: c.agrees for c in claims}
    assert verdicts["Fig. 7: the planner fails every attempt on the soccer_ball"] == "yes"
    assert verdicts["Fig. 7: game box 100 % for both methods"] == "no"
    path = tmp_path / "report.md"
    reproduce.write_report(path, claims, 12.0, True, "contact-quality", [], {"fig6": "24 rows"},
                           flower_lines=["plates (precision grasp): eps = 0 for every error below 20 mm thick"])
    text = path.read_text()
    assert "reused: fig6 24 rows" in text
    assert "## Beyond the paper: the flower" in text and "- plates (precision grasp): eps = 0" in text
    assert "1 of 2 claims agree" in text and "| Fig. 7: game box 100 % for both methods |" in text


def test_report_quotes_the_scaling_benchmark_or_says_how_to_run_it(tmp_path):
    missing = "\n".join(reproduce.scaling_lines(tmp_path / "scaling.json"))
    assert "## Scaling" in missing and "scripts/bench_scaling.py" in missing
    runs = [{"executor": "local", "workers": 1, "trials_per_second": 0.25},
            {"executor": "local", "workers": 2, "trials_per_second": 0.45},
            {"executor": "ray", "workers": 2, "trials_per_second": 0.40}]
    (tmp_path / "scaling.json").write_text(json.dumps({
        "date": "2026-01-01T10:00+00:00", "machine": "test CPU, 2 CPUs", "load_average_before": [0.1, 0.2, 0.3],
        "workload": "8 oracle trials", "runs": runs, "identical_records": True}))
    path = tmp_path / "report.md"
    reproduce.write_report(path, [], 1.0, True, "contact", [], scaling_file=tmp_path / "scaling.json")
    text = path.read_text()
    assert "2026-01-01T10:00+00:00 (test CPU, 2 CPUs" in text
    assert "| local | 2 | 0.450 | 1.80x |" in text and "| ray | 2 | 0.400 | 1.60x |" in text
    (tmp_path / "scaling.json").write_text("{")
    assert "could not be read" in "\n".join(reproduce.scaling_lines(tmp_path / "scaling.json"))


def test_study_sections_are_included_when_present_with_links_rebased(tmp_path):
    from drake_grasp.studies.reproduce import study_sections

    lines = study_sections(tmp_path)
    assert len(lines) == 2 and "drake-grasp capture --out" in lines[0]  # none present: how to add them
    (tmp_path / "capture").mkdir()
    (tmp_path / "capture" / "summary.md").write_text(
        "# Capture regions\n\nText.\n\n## ε against physics\n\n![map](capture.png) [r](replays/a.html) "
        "[web](https://example.org)\n")
    text = "\n".join(study_sections(tmp_path))
    assert "## Beyond the paper: capture regions" in text and "# Capture regions" not in text
    assert "### ε against physics" in text
    assert "](capture/capture.png)" in text and "](capture/replays/a.html)" in text
    assert "](https://example.org)" in text
