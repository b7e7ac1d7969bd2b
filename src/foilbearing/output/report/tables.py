"""HTML tables of the report and the formatting of their cells."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from html import escape
from typing import Any

__all__ = []


#: A table column: header (with units), how to get the cell from a record, number format.
Column = tuple[str, Callable[[dict[str, Any]], Any], str]


def _records(records: list[dict[str, Any]], cols: list[Column]) -> str:
    """A table with one row per record and one column per ``(header, getter, format)``."""
    if not records or not cols:
        return ""
    rows = [[_f(_get(get, r), spec) for _, get, spec in cols] for r in records]
    num = [j for j, (_, _, spec) in enumerate(cols) if spec]
    return _table([h for h, _, _ in cols], rows, num=num)


def _table(
    heads: list[str], rows: list[list[str]], *, num: Iterable[int] = (), flags: Sequence[bool] = ()
) -> str:
    """A table of plain-text cells (escaped here); the columns in ``num`` right-aligned."""
    cols = set(num)
    th = "".join(f"<th>{escape(h)}</th>" for h in heads)
    trs = []
    for i, row in enumerate(rows):
        flag = ' class="flag"' if i < len(flags) and flags[i] else ""
        tds = "".join(
            f"<td{' class=num' if j in cols else ''}>{escape(c)}</td>" for j, c in enumerate(row)
        )
        trs.append(f"<tr{flag}>{tds}</tr>")
    table = f"<table><thead><tr>{th}</tr></thead><tbody>{''.join(trs)}</tbody></table>"
    return f'<div class="scroll">{table}</div>'


def _get(get: Callable[[dict[str, Any]], Any], record: dict[str, Any]) -> Any:
    try:
        return get(record)
    except (KeyError, IndexError, TypeError, ValueError):
        return None


def _transpose(d: dict[str, Any], keys: tuple[str, ...]) -> list[dict[str, Any]]:
    """Records from parallel lists: ``{k: [a, b]}`` to ``[{k: a}, {k: b}]``."""
    cols = (d.get(k) or [] for k in keys)
    return [dict(zip(keys, v, strict=True)) for v in zip(*cols, strict=False)]


def _entry(name: str, i: int, scale: float = 1.0) -> Callable[[dict[str, Any]], Any]:
    """Element ``i`` (row-major) of the 2 × 2 matrix ``record[name]``, times ``scale``."""
    return lambda r: r[name][i // 2][i % 2] * scale


def _key(name: str) -> Callable[[dict[str, Any]], Any]:
    return lambda r: r.get(name)


def _krpm(name: str) -> Callable[[dict[str, Any]], Any]:
    return lambda r: None if r.get(name) is None else float(r[name]) / 1e3


#: A speed-up's readouts a refined run checks (foilbearing.study.orbits.readout_errors): key,
#: name, the factor to the unit printed, the format on the refined grid and the unit.
_REFINED_READOUTS = (
    ("onset_speed_rpm", "onset", 1e-3, ".2f", " krpm"),
    ("whip_frequency_Hz", "whip", 1.0, ".1f", " Hz"),
    ("divergence_speed_rpm", "divergence", 1e-3, ".2f", " krpm"),
)


def _with_grid_error(
    key: str, scale: float, spec: str, refined: str = "theta_refined"
) -> Callable[[dict[str, Any]], str | None]:
    """A readout with its grid error where the record was refined (its ``refined`` entry:
    :func:`foilbearing.study.orbits.readout_errors` for a speed-up, ``grid_refined`` of
    :func:`foilbearing.study.static.static_errors` for a static point), or the floor stated
    for a speed-up that was not refined (``grid_floor``,
    :func:`foilbearing.study.orbits.floor_errors`), to the digits the error supports;
    otherwise its value times ``scale`` to ``spec``."""

    def get(r: dict[str, Any]) -> str | None:
        errors = r.get(refined) or r.get("grid_floor") or {}
        text = (errors.get("texts") or {}).get(key)
        if text:
            return str(text)
        value = r.get(key)
        if isinstance(value, list):  # one per actuator
            return " / ".join(format(float(v) * scale, spec) for v in value) or None
        return None if value is None else format(float(value) * scale, spec)

    return get


def _refined_readouts(r: dict[str, Any]) -> str | None:
    """A speed-up's readouts on its refined grid: "192 × 4: onset 47.81 krpm, ..."."""
    f = r.get("theta_refined")
    if not f:
        return None
    parts = [
        f"{name} {'none' if f.get(key) is None else format(f[key] * scale, spec)}{unit}"
        for key, name, scale, spec, unit in _REFINED_READOUTS
    ]
    grid = f.get("grid") or ["?", "?"]
    return f"{grid[0]} × {grid[1]}: " + ", ".join(parts)


def _nearest(values: list[float], target: float) -> float:
    return min(values, key=lambda s: abs(s - target))


def _f(x: Any, spec: str) -> str:
    """Format a number, or a list of numbers joined by ' / '; '—' for None."""
    if x is None:
        return "—"
    if isinstance(x, bool):
        return "yes" if x else "NO"
    if isinstance(x, list | tuple):
        return " / ".join(_f(v, spec) for v in x)
    if isinstance(x, int | float) and spec:
        try:
            return format(x, spec)
        except ValueError:
            return format(x, "g")
    return str(x)
