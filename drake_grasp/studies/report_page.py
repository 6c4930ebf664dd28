"""The results page: report.md as one HTML page that opens offline, with its figures and replays.

`reproduce` writes its report as Markdown (readable in a terminal and on a code host); this module
renders the same text as ``report.html`` beside it, so nothing is said in one that the other lacks:
the figures the report links are shown inline, and a last section links one Meshcat replay per
object and method (self-contained HTML files that play the simulation in a browser, no server).
Markdown is rendered by Python-Markdown (its `tables` extension), not by hand.
"""

import dataclasses
import html
import pathlib
import re

import markdown

STYLE = """
body { font-family: system-ui, sans-serif; max-width: 72rem; margin: 2rem auto; padding: 0 1rem; color: #222; }
table { border-collapse: collapse; margin: 1rem 0; font-size: 0.9rem; }
th, td { border: 1px solid #ccc; padding: 0.3rem 0.5rem; vertical-align: top; text-align: left; }
th { background: #f3f3f3; }
img { max-width: 100%; }
img.figure { border: 1px solid #ddd; margin: 0.5rem 0; }
code { background: #f3f3f3; padding: 0 0.2rem; }
"""


@dataclasses.dataclass(frozen=True)
class Replay:
    """One replay file: the object, the method it shows, and its path relative to the page."""

    object: str
    method: str
    path: str
    outcome: str = ""  # e.g. "held" or the failure reason


def report_html(markdown_text: str, replays: list[Replay], title: str = "drake-grasp report") -> str:
    """The page: the report's Markdown rendered, each linked PNG figure also shown as an image, and a
    table of replays (object × method)."""
    body = markdown.markdown(markdown_text, extensions=["tables"], output_format="html")
    # A link to a figure becomes the figure (the link kept under it).
    body = re.sub(r'<a href="([^"]+\.png)">([^<]*)</a>',
                  lambda m: f'<br><img class="figure" src="{m.group(1)}" alt="{m.group(2)}"><br>'
                            f'<a href="{m.group(1)}">{m.group(2)}</a>', body)
    if replays:
        methods = sorted({r.method for r in replays})
        objects = list(dict.fromkeys(r.object for r in replays))
        cell = {(r.object, r.method): r for r in replays}
        rows = []
        for obj in objects:
            cells = []
            for method in methods:
                r = cell.get((obj, method))
                cells.append("<td>-</td>" if r is None else
                             f'<td><a href="{html.escape(r.path)}">replay</a> {html.escape(r.outcome)}</td>')
            rows.append(f"<tr><td>{html.escape(obj)}</td>{''.join(cells)}</tr>")
        header = "".join(f"<th>{html.escape(m)}</th>" for m in methods)
        body += ("\n<h2>Replays</h2>\n<p>One trial per object and method (seed of the first trial), as the "
                 "simulation ran it: each opens in a browser, offline.</p>\n"
                 f"<table><tr><th>object</th>{header}</tr>\n" + "\n".join(rows) + "</table>\n")
    return (f'<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n<title>{html.escape(title)}</title>\n'
            f"<style>{STYLE}</style>\n</head>\n<body>\n{body}\n</body>\n</html>\n")


def write_report_html(path: pathlib.Path, markdown_text: str, replays: list[Replay]) -> pathlib.Path:
    """Writes the page to `path` atomically (a reader never sees half a page); returns `path`."""
    from drake_grasp.sweeps.results import write_atomically

    write_atomically(path, report_html(markdown_text, replays))
    return path
