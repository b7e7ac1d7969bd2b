"""The report page: its sections in order, its style, written atomically."""

from __future__ import annotations

import re
from html import escape
from pathlib import Path
from typing import Any

from foilbearing.io import write_text
from foilbearing.output.report.captions import _figure
from foilbearing.output.report.sections import (
    _TABLES,
    STAGES,
    _comparison,
    _generic,
    _intro,
    stage_title,
)
from foilbearing.output.result import FIGURE_RECORD_KEY, StudyResult

__all__ = ["render_report", "write_report"]


_CSS = """
body{margin:0;background:#f4f5f7;color:#1a1a1a;font:16px/1.5 system-ui,-apple-system,
"Segoe UI",Roboto,"DejaVu Sans",Arial,sans-serif}
main{max-width:1040px;margin:0 auto;padding:1.5rem 1.25rem 3rem;background:#fff}
h1{font-size:1.7rem;margin:.2rem 0 .8rem}h2{font-size:1.35rem;margin-top:2.4rem;
border-bottom:2px solid #d0d7de;padding-bottom:.2rem}
a{color:#0a58ca}nav ol{columns:2;padding-left:1.4rem}
figure{margin:1.4rem 0;text-align:center}figure img{max-width:100%;height:auto;
border:1px solid #e3e3e3}figcaption{font-size:.92rem;color:#444;margin-top:.35rem}
.scroll{overflow-x:auto;margin:.8rem 0}
table{border-collapse:collapse;font-size:.88rem}
th,td{border:1px solid #d0d7de;padding:.25rem .45rem;text-align:left;vertical-align:top}
th{background:#f0f3f6}td.num{text-align:right;font-variant-numeric:tabular-nums}
tr.flag td{background:#fff1dc}
#comparison{border:2px solid #0a58ca;border-radius:6px;padding:0 1rem 1rem;margin-top:1.5rem}
#comparison h2{border:0;margin-top:1rem}#comparison table{width:100%}
#comparison td:nth-child(1){width:20%}#comparison td:nth-child(4){width:14%}
.note{color:#555;font-size:.92rem}code{background:#f3f3f3;padding:0 .2rem;border-radius:3px}
footer{margin-top:3rem;color:#666;font-size:.85rem}
"""


def write_report(result: StudyResult | str | Path) -> Path:
    """Write ``report.html`` into a study's folder.

    Parameters
    ----------
    result
        The study's result, or a folder written by ``foilbearing study``
        (``summary.json`` and PNG figures), read with :meth:`StudyResult.load`.

    Returns
    -------
    Path
        The written page (atomic write: it is there whole or not at all).

    Raises
    ------
    InputError
        If a folder is given whose ``summary.json`` is missing or not a JSON object.
    """
    if not isinstance(result, StudyResult):
        result = StudyResult.load(result)
    return write_text(result.out_dir / "report.html", render_report(result))


def render_report(result: StudyResult) -> str:
    """The HTML text of the report.

    Parameters
    ----------
    result
        The study's summary, its folder and its figures by section. Figures in the
        folder that no section lists are shown last, under "Other figures".

    Returns
    -------
    str
        A complete HTML document with every figure embedded.
    """
    from importlib.metadata import version

    __version__ = version("foilbearing")
    summary, out_dir = result.summary, result.out_dir
    case = summary.get("case") or {}
    title = f"foilbearing study: {case.get('title', 'unnamed case')}"
    used: set[str] = set()
    sections: list[tuple[str, str, str]] = []  # (anchor, heading, html)
    if summary.get("paper_comparison"):
        body = _comparison(summary["paper_comparison"])
        sections.append(("comparison", "Our numbers beside the paper's", body))
    # case_point: the readouts at the case speed that the reference table shows
    known = {key for key, _ in STAGES} | {"case", "paper_comparison", "case_point"}
    known |= {FIGURE_RECORD_KEY}  # the figure record is the sections' figures, not one
    extra = [(k, k.replace("_", " ").capitalize()) for k in summary if k not in known]
    runs: list[Any] = []  # the speed-ups, which caption their figures
    for key in ("orbits", "orbits_paper_reading"):
        stage = summary.get(key)
        stage_runs = stage.get("runs") if isinstance(stage, dict) else None
        runs += stage_runs if isinstance(stage_runs, list) else []
    for key, heading in [*STAGES, *extra]:
        data = summary.get(key)
        if not isinstance(data, dict) or not data:
            continue
        names = [p.name for p in result.figures.get(key, ())]
        names = [n for n in dict.fromkeys(names) if n not in used]
        used.update(names)
        figures = "".join(_figure(out_dir, n, runs) for n in names)
        body = _TABLES.get(key, _generic)(data, case) + figures
        sections.append(
            (_anchor(key), stage_title(key, data) if key in dict(STAGES) else heading, body)
        )
    rest = sorted(p.name for p in out_dir.glob("*.png") if p.name not in used)
    if rest:
        others = "".join(_figure(out_dir, n, runs) for n in rest)
        sections.append(("other", "Other figures", others))

    toc = "".join(f'<li><a href="#{a}">{escape(t)}</a></li>' for a, t, _ in sections)
    body = "".join(f'<section id="{a}"><h2>{escape(t)}</h2>{h}</section>' for a, t, h in sections)
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{escape(title)}</title><style>{_CSS}</style></head>\n<body><main>"
        f"<h1>{escape(title)}</h1>{_intro(summary, case)}"
        f"<nav><h2>Contents</h2><ol>{toc}</ol></nav>{body}"
        f"<footer>Written by foilbearing {escape(__version__)} from "
        f"<code>{escape(str(out_dir / 'summary.json'))}</code>; figures embedded.</footer>"
        "</main></body></html>\n"
    )


def _anchor(key: str) -> str:
    """An HTML id from a section key: characters other than letters, digits, _ and - as -."""
    return re.sub(r"[^A-Za-z0-9_-]", "-", key)
