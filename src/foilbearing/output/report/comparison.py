"""The paper-versus-ours table: each row's deviation, its shading by one rule, its why."""

from __future__ import annotations

import re
from typing import Any

from foilbearing.output.report.tables import _table

__all__ = ["SHADING_LIMIT_PERCENT", "SHADING_RULE", "deviations_percent", "shaded"]


#: A row is shaded where a deviation of it exceeds this (%) in magnitude.
SHADING_LIMIT_PERCENT = 5.0

#: The rule, as the page states it above the table.
SHADING_RULE = (
    f"Shaded: every row where a deviation exceeds {SHADING_LIMIT_PERCENT:g} % in magnitude "
    "(the largest, where a row has several) or where we contradict the paper (a deviation "
    "that begins with “contradicts”)."
)

#: A percentage, or several joined by " / " before one "%" (item by item).
_PERCENTAGES = re.compile(r"[+\-−]?\d+(?:\.\d+)?(?:\s*/\s*[+\-−]?\d+(?:\.\d+)?)*\s*%")


def deviations_percent(deviation: str) -> list[float]:
    """Every percentage in a deviation cell: ``+1.0 / -3.4 / +0.5 %`` gives three."""
    out = []
    for m in _PERCENTAGES.finditer(deviation):
        for x in re.findall(r"[+\-−]?\d+(?:\.\d+)?", m.group(0)):
            out.append(float(x.replace("−", "-")))
    return out


def shaded(deviation: str) -> bool:
    """The table's one rule (:data:`SHADING_RULE`) on a deviation cell."""
    text = deviation.strip()
    if text.lower().startswith("contradicts"):
        return True
    return any(abs(x) > SHADING_LIMIT_PERCENT for x in deviations_percent(text))


def _comparison(rows: list[dict[str, Any]]) -> str:
    """The table, the rule above it; each reason followed by the theory section it names."""
    heads = ["quantity", "paper", "ours", "deviation", "why they differ"]
    cells = []
    for r in rows:
        why = str(r.get("note") or "")
        if r.get("theory"):
            why += f" ({r['theory']})"
        cells.append([str(r.get(k) or "—") for k in ("quantity", "paper", "ours", "deviation")])
        cells[-1].append(why or "—")
    flags = [shaded(c[3]) for c in cells]
    return (
        f'<p class="note">{SHADING_RULE} A deviation is ours against the paper, in per cent '
        "of the paper's value, or in words where the paper gives no number. Orbit rows read "
        "an onset where the sub-synchronous amplitude stays above 1 µm and a divergence at "
        "contact (docs/model.md, section 5); the viscosity, rotor mass and imbalance are "
        "ours, the paper gives none (section 1). Each reason names the section of the "
        "repository's theory pages that explains it.</p>" + _table(heads, cells, flags=flags)
    )
