"""A result as a person reads it: a few text lines (``repr``) or an HTML table (notebooks).

A result's headline is a dict with unit-named keys (``min_film_um``,
``speed_rpm``, ``power_loss_W``: :mod:`foilbearing.headline`). :func:`summary_text`
and :func:`summary_html` show it as a table of quantity, value and unit, the unit
read off the key's suffix (:data:`UNIT_SUFFIXES`). :class:`Summarised` gives a
result class its ``__repr__`` and ``_repr_html_`` from one ``_summary()`` method.
"""

from __future__ import annotations

import html
import math
from collections.abc import Mapping, Sequence
from typing import Any

__all__ = [
    "UNIT_SUFFIXES",
    "Summarised",
    "format_value",
    "split_unit",
    "summary_html",
    "summary_text",
]

#: Key suffix -> unit shown, longest first (so ``_Ns_per_m`` wins over ``_per_m``).
UNIT_SUFFIXES: tuple[tuple[str, str], ...] = (
    ("_N_per_m3", "N/m³"),
    ("_kNs_per_m", "kN·s/m"),
    ("_MN_per_m", "MN/m"),
    ("_Ns_per_m", "N·s/m"),
    ("_N_per_m", "N/m"),
    ("_N_rms", "N rms"),
    ("_rpm_Hz", "rpm, Hz"),
    ("_Pa_s", "Pa·s"),
    ("_kPa", "kPa"),
    ("_rpm", "rpm"),
    ("_deg", "°"),
    ("_rad", "rad"),
    ("_um", "µm"),
    ("_mm", "mm"),
    ("_Hz", "Hz"),
    ("_Nm", "N·m"),
    ("_kg", "kg"),
    ("_Pa", "Pa"),
    ("_N", "N"),
    ("_W", "W"),
    ("_V", "V"),
    ("_s", "s"),
)

#: At most this many entries of a list are shown, then how many there are.
MAX_ITEMS = 4
#: A text value is cut after this many characters.
MAX_TEXT = 110


def split_unit(key: str) -> tuple[str, str]:
    """``("min film", "µm")`` for ``"min_film_um"``: the quantity and the unit its key names."""
    for suffix, unit in UNIT_SUFFIXES:
        if key.endswith(suffix) and len(key) > len(suffix):
            return key[: -len(suffix)].replace("_", " "), unit
    return key.replace("_", " "), ""


def format_value(value: Any) -> str:
    """A headline value in a few characters: 4 significant digits, lists cut after
    :data:`MAX_ITEMS` entries, flags as yes/no, None as "–"."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return _number(value)
    if isinstance(value, (list, tuple)):
        shown = ", ".join(format_value(v) for v in value[:MAX_ITEMS])
        more = f", … ({len(value)} in all)" if len(value) > MAX_ITEMS else ""
        return f"[{shown}{more}]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{k}: {format_value(v)}" for k, v in value.items()) + "}"
    text = str(value)
    return text if len(text) <= MAX_TEXT else text[: MAX_TEXT - 1] + "…"


def _number(x: float) -> str:
    """4 significant digits, in plain notation from 0.001 to a million (30000 rpm, not
    3e+04), without trailing zeros."""
    if not math.isfinite(x) or x == 0.0 or not 1e-3 <= abs(x) < 1e6:
        return f"{x:.4g}"
    decimals = max(0, 3 - math.floor(math.log10(abs(x))))
    text = f"{round(x, decimals):.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def _rows(headline: Mapping[str, Any], keys: Sequence[str] | None) -> list[tuple[str, str, str]]:
    chosen = headline.keys() if keys is None else [k for k in keys if k in headline]
    return [(*split_unit(k), format_value(headline[k])) for k in chosen]


def summary_text(title: str, headline: Mapping[str, Any], keys: Sequence[str] | None = None) -> str:
    """``title`` then one ``quantity  value unit`` line per key of ``headline``
    (all keys, or those of ``keys`` that it has, in that order)."""
    rows = _rows(headline, keys)
    width = max((len(q) for q, _, _ in rows), default=0)
    lines = [title] + [f"  {q:<{width}}  {v} {u}".rstrip() for q, u, v in rows]
    return "\n".join(lines)


def summary_html(title: str, headline: Mapping[str, Any], keys: Sequence[str] | None = None) -> str:
    """The same as :func:`summary_text` as an HTML table (quantity, value, unit)."""
    esc = html.escape
    body = "".join(
        f"<tr><td style='text-align:left'>{esc(q)}</td><td>{esc(v)}</td>"
        f"<td style='text-align:left'>{esc(u)}</td></tr>"
        for q, u, v in _rows(headline, keys)
    )
    return (
        f"<table><caption style='text-align:left'><b>{esc(title)}</b></caption>"
        "<thead><tr><th>quantity</th><th>value</th><th>unit</th></tr></thead>"
        f"<tbody>{body}</tbody></table>"
    )


class Summarised:
    """Mixin: ``repr`` and the notebook's HTML from ``_summary()``, which returns
    ``(title, headline, keys)`` (keys: which headline entries to show, None for all).

    A dataclass that uses it says ``repr=False``, or its generated ``__repr__`` wins.
    """

    __slots__ = ()

    def _summary(self) -> tuple[str, Mapping[str, Any], Sequence[str] | None]:
        raise NotImplementedError

    def __repr__(self) -> str:
        return summary_text(*self._summary())

    def _repr_html_(self) -> str:
        return summary_html(*self._summary())
