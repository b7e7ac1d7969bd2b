"""The report page: its sections in order, its style, written atomically."""

from __future__ import annotations

import json
import re
from html import escape
from pathlib import Path
from typing import Any

from foilbearing.errors import InputError
from foilbearing.io import write_text
from foilbearing.output.report.captions import _figure, _orbit_order
from foilbearing.output.report.sections import _TABLES, STAGES, _comparison, _generic, _intro

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
#comparison td:nth-child(1){width:24%}#comparison td:nth-child(4){white-space:nowrap}
.note{color:#555;font-size:.92rem}code{background:#f3f3f3;padding:0 .2rem;border-radius:3px}
footer{margin-top:3rem;color:#666;font-size:.85rem}
"""


def write_report(out_dir: Path) -> Path:
    """Write ``out_dir/report.html`` from the study results in ``out_dir``.

    Parameters
    ----------
    out_dir
        A folder written by ``foilbearing study``: ``summary.json`` and PNG figures.

    Returns
    -------
    Path
        The written page (atomic write: it is there whole or not at all).

    Raises
    ------
    InputError
        If ``summary.json`` is missing or not a JSON object.
    """
    out_dir = Path(out_dir)
    path = out_dir / "summary.json"
    if not path.is_file():
        raise InputError("no summary.json; run `foilbearing study --out DIR`", source=str(out_dir))
    try:
        summary = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise InputError(f"not valid JSON ({exc})", source=str(path)) from exc
    if not isinstance(summary, dict):
        raise InputError("expected a JSON object at the top level", source=str(path))
    return write_text(out_dir / "report.html", render_report(summary, out_dir))


def render_report(summary: dict[str, Any], out_dir: Path) -> str:
    """The HTML text of the report.

    Parameters
    ----------
    summary
        The study's ``summary.json`` as a dict.
    out_dir
        Where the figures are; they are found by file name (the folder may have moved).

    Returns
    -------
    str
        A complete HTML document with every figure embedded.
    """
    from importlib.metadata import version

    __version__ = version("foilbearing")
    case = summary.get("case") or {}
    title = f"foilbearing study: {case.get('title', 'unnamed case')}"
    used: set[str] = set()
    sections: list[tuple[str, str, str]] = []  # (anchor, heading, html)
    if summary.get("paper_comparison"):
        body = _comparison(summary["paper_comparison"])
        sections.append(("comparison", "Our numbers beside the paper's", body))
    # case_point: the readouts at the case speed that the reference table shows
    known = {key for key, _ in STAGES} | {"case", "paper_comparison", "case_point"}
    extra = [(k, k.replace("_", " ").capitalize()) for k in summary if k not in known]
    for key, heading in [*STAGES, *extra]:
        data = summary.get(key)
        if not isinstance(data, dict) or not data:
            continue
        names = [Path(str(p)).name for p in data.get("figures") or []]
        if key == "orbits":
            names += [p.name for p in sorted(out_dir.glob("orbit_*.png"), key=_orbit_order)]
        names = [n for n in dict.fromkeys(names) if n not in used]
        used.update(names)
        body = _TABLES.get(key, _generic)(data, case) + "".join(_figure(out_dir, n) for n in names)
        sections.append((re.sub(r"[^A-Za-z0-9_-]", "-", key), heading, body))
    rest = sorted(p.name for p in out_dir.glob("*.png") if p.name not in used)
    if rest:
        sections.append(("other", "Other figures", "".join(_figure(out_dir, n) for n in rest)))

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
