"""The results page and a replay, opened in a real browser: headless Chromium (Debian's `chromium`).

Slow (a real trial records the replay; the browser plays it in virtual time) and skipped where no
Chromium is installed (`apt-get install chromium`). Each page is screenshotted: it must not be blank
(the pixels vary), and the browser's console must show no uncaught error.
"""

import shutil
import subprocess

import pytest
from matplotlib.image import imread

from drake_grasp import cli
from drake_grasp.studies.report_page import Replay, write_report_html

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
pytestmark = [pytest.mark.slow, pytest.mark.skipif(CHROMIUM is None, reason="needs Debian's chromium")]


def _open(url: str, screenshot) -> str:
    """Loads `url` headless (software WebGL), writes a screenshot, returns the browser's log."""
    result = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
         "--use-angle=swiftshader", "--window-size=1200,800", "--virtual-time-budget=8000",
         "--enable-logging=stderr", "--v=0", f"--screenshot={screenshot}", url],
        capture_output=True, text=True, timeout=300)
    assert screenshot.exists(), result.stderr[-2000:]
    return result.stderr


def _console_errors(log: str) -> list[str]:
    return [line for line in log.splitlines() if "CONSOLE" in line and ("Uncaught" in line or "Error" in line)
            and "GL Driver Message" not in line]


def test_page_and_replay_render(tmp_path):
    replay = tmp_path / "replays" / "soccer_ball_compliant.html"
    replay.parent.mkdir()
    assert cli.main(["demo", "--object", "soccer_ball", "--replay", str(replay)]) == 0
    figure = tmp_path / "fig.png"
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.bar([0, 1], [90, 40], color=["tab:orange", "tab:blue"])
    fig.savefig(figure)
    page = write_report_html(tmp_path / "report.html", "# Report\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n"
                             "Figures: [fig.png](fig.png)\n",
                             [Replay("soccer_ball", "compliant", "replays/soccer_ball_compliant.html", "held")])
    for url, shot in ((page.as_uri(), tmp_path / "page.png"), (replay.as_uri(), tmp_path / "replay.png")):
        log = _open(url, shot)
        assert not _console_errors(log), _console_errors(log)
        pixels = imread(shot)[..., :3]
        assert pixels.std() > 0.05, f"{url} rendered blank"
