"""The results page: the report's Markdown as HTML, figures inline, replays linked."""

from drake_grasp.studies.report_page import Replay, report_html, write_report_html

REPORT = """# drake-grasp: the paper's claims

| claim | paper | ours | agrees |
|---|---|---|---|
| Fig. 6: the chosen grasps succeed | 95.6 % (86/90) | 100 % (90/90, 95 % CI 96-100 %) | yes |

Figures: [fig6.png](fig6/fig6.png), [fig7.png](fig7/fig7.png)
"""


def test_page_renders_tables_figures_and_replays(tmp_path):
    replays = [Replay("soccer_ball", "compliant", "replays/soccer_ball_compliant.html", "held"),
               Replay("soccer_ball", "eigengrasp", "replays/soccer_ball_eigengrasp.html", "missed"),
               Replay("sponge", "compliant", "replays/sponge_compliant.html", "held")]
    page = report_html(REPORT, replays)
    assert page.startswith("<!DOCTYPE html>") and page.rstrip().endswith("</html>")
    assert "<table>" in page and "<td>100 % (90/90, 95 % CI 96-100 %)</td>" in page
    assert '<img class="figure" src="fig6/fig6.png"' in page and '<img class="figure" src="fig7/fig7.png"' in page
    assert page.count('href="replays/') == 3
    assert "<td>sponge</td>" in page and "<td>-</td>" in page  # no planner replay for the sponge
    path = write_report_html(tmp_path / "report.html", REPORT, replays)
    assert path.read_text() == page
    assert [p.name for p in tmp_path.iterdir()] == ["report.html"]  # no temporary file left


def test_page_without_replays_has_no_replay_section():
    assert "Replays" not in report_html(REPORT, [])
