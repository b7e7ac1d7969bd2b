"""One self-contained HTML page from what ``foilbearing study`` wrote.

The page is rendered from a :class:`~foilbearing.output.result.StudyResult`:
the study's summary, its folder and the figures each stage wrote there (a
folder alone is read with :meth:`~foilbearing.output.result.StudyResult.load`).
Every figure is embedded as a base64 data URI and the style sheet is
inline, so the file can be mailed or archived alone; it loads nothing from
anywhere and runs no script. Stages appear in the paper's order and only if
``summary.json`` has them.
"""

from __future__ import annotations

from foilbearing.output.report.captions import (
    png_size,
)
from foilbearing.output.report.page import (
    render_report,
    write_report,
)
from foilbearing.output.report.sections import (
    STAGES,
)

__all__ = [
    "STAGES",
    "png_size",
    "render_report",
    "write_report",
]
