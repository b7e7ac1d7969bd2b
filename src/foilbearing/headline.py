"""Headlines: the unit-named numbers of a result (the CLI's ``--json``), read off its Dataset.

A result's ``to_dataset()`` holds everything in SI, each variable with its
``units`` attribute. Its ``headline()`` is a view of that Dataset: a table of
:data:`Field` entries says which variable or attribute each key shows, and in
which unit (the key names it, e.g. ``min_film_um``); :func:`headline_view`
converts (:func:`foilbearing.units.from_si`) and returns plain Python numbers
and lists, ready for JSON.
"""

from __future__ import annotations

from typing import Any

from foilbearing.units import from_si

__all__ = ["Field", "headline_view"]

#: One headline entry ``(key, source, unit)``: ``source`` names a variable of the
#: Dataset, or an attribute as ``"@name"``; ``unit`` is the unit the key shows the
#: variable in (None: as stored), or ``"bool"`` for a flag stored as 0/1.
Field = tuple[str, str, str | None]


def headline_view(ds: Any, fields: tuple[Field, ...]) -> dict[str, Any]:
    """The headline ``{key: value}`` that ``fields`` reads off the Dataset ``ds``.

    Parameters
    ----------
    ds : xarray.Dataset
        A result in SI (every variable read here has a ``units`` attribute).
    fields : tuple of Field
        The keys in order, each with its source and unit.

    Returns
    -------
    dict
        Floats for 0-d variables, (nested) lists for the others, attributes as
        stored (flags as bool).
    """
    out: dict[str, Any] = {}
    for key, source, unit in fields:
        if source.startswith("@"):
            value = ds.attrs[source[1:]]
            out[key] = bool(value) if unit == "bool" else _plain(value)
            continue
        var = ds[source]
        values = var.values if unit is None else from_si(var.values, unit, var.attrs["units"])
        out[key] = values.item() if values.ndim == 0 else values.tolist()
    return out


def _plain(value: Any) -> Any:
    """A NumPy scalar or array attribute as a Python number or list."""
    return value.tolist() if hasattr(value, "tolist") else value
