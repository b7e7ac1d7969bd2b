"""The paper-versus-ours table: each row's deviation, its shading by one rule, its why."""

from __future__ import annotations

import re
from typing import Any

from foilbearing.output.report.tables import (
    _table,
)

__all__: list[str] = []


def _comparison(rows: list[dict[str, Any]]) -> str:
    heads = ["quantity", "paper", "ours", "deviation", "why they differ"]
    cells = [[str(r.get(k, "")) for k in ("quantity", "paper", "ours", "deviation", "note")]
             for r in rows]  # fmt: skip
    flags = [_flagged(c[2], c[3]) for c in cells]
    return (
        '<p class="note">Shaded: a deviation above 5 %, or a statement of the paper that we do '
        "not reproduce (NO).</p>" + _table(heads, cells, num=(3,), flags=flags)
    )


def _flagged(ours: str, deviation: str) -> bool:
    m = re.match(r"\s*([+-]?[0-9.]+)\s*%", deviation)
    return bool(m and abs(float(m.group(1))) > 5.0) or bool(re.search(r"\bNO\b", ours))
