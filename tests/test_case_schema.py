"""The case schema (foilbearing.case.schema) and the tables derived from it agree with
the reader, the sweep and the summary, field by field.

A field declared in the schema is what a sweep may set and what the summary shows; the
reader refuses, naming the field, a value of another dimension and a value just outside
the range the schema states. All reading, no solving: about a second.
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from dataclasses import fields
from pathlib import Path
from typing import Any

import pytest

from foilbearing.case import case_from_dict, default_case_path, load_case
from foilbearing.case.record import FIELD_UNITS, case_to_dict
from foilbearing.case.schema import (
    CASE_FIELDS,
    NON_QUANTITY_KINDS,
    SWEEP_KINDS,
    CaseField,
    case_field,
)
from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.output.summary import case_summary
from foilbearing.sweep.spec import FIELD_KINDS, load_sweep
from foilbearing.units import SI_UNITS

_SHIMMED = Path(__file__).resolve().parents[1] / "examples" / "shimmed_gfb.toml"


def _case_file(f: CaseField) -> Path:
    """A case file that has the field's table: the shimmed example for [shims], else the
    built-in C-GFB (which has every other table)."""
    return _SHIMMED if f.path.startswith("shims.") else default_case_path()


def _tables(f: CaseField) -> dict[str, Any]:
    return tomllib.loads(_case_file(f).read_text(encoding="utf-8"))


def _put(tables: dict[str, Any], path: str, value: Any) -> None:
    *heads, key = path.split(".")
    node = tables
    for h in heads:
        node = node.setdefault(h, {})
    node[key] = value


def _refused(tables: dict[str, Any], f: CaseField) -> str:
    with pytest.raises(InputError) as info:
        case_from_dict(tables, source="case.toml")
    return str(info.value)


_FILE_FIELDS = [f for f in CASE_FIELDS if f.kind not in ("table", "law")]


def test_every_field_is_declared_once_on_its_dataclass() -> None:
    paths = [f.path for f in CASE_FIELDS]
    assert len(paths) == len(set(paths))
    for f in CASE_FIELDS:
        assert f.attr in {g.name for g in fields(f.owner)}, f.path
        assert f.kind in SI_UNITS or f.kind in NON_QUANTITY_KINDS, f.path
        assert case_field(f.path) is f
    # the record's table of units is the schema's, class by class
    for cls, units in FIELD_UNITS.items():
        assert units == {f.attr: f.unit for f in CASE_FIELDS if f.owner is cls}
    keys = [f.summary for f in CASE_FIELDS if f.summary is not None]
    assert len(keys) == len(set(keys))


def test_a_field_is_sweepable_or_says_why_not() -> None:
    """The sweep's settable fields are the schema's sweepable ones, with their kinds; the
    others carry a reason."""
    assert FIELD_KINDS == SWEEP_KINDS == {f.path: f.kind for f in CASE_FIELDS if f.sweepable}
    for f in CASE_FIELDS:
        assert f.sweepable or len(f.not_swept) > 10, f.path
        assert not (f.sweepable and f.kind in ("table", "law")), f.path


def _sweep_file(tmp_path: Path, f: CaseField, values: list[Any]) -> Path:
    p = tmp_path / "sweep.toml"
    p.write_text(
        f'case = {json.dumps(str(_case_file(f)))}\nanalysis = "static"\n[parameters]\n'
        f'"{f.path}" = {json.dumps(values)}\n',
        encoding="utf-8",
    )
    return p


@pytest.mark.parametrize("f", _FILE_FIELDS, ids=lambda f: f.path)
def test_a_sweep_file_sets_exactly_the_sweepable_fields(tmp_path: Path, f: CaseField) -> None:
    """A sweep over a sweepable field, at its value in the case, reads; any other field is
    refused as an unknown parameter."""
    written = case_to_dict(load_case(_case_file(f)))
    node: Any = written
    for key in f.path.split("."):
        node = node.get(key) if isinstance(node, dict) else None
    value = node[0] if isinstance(node, list) else node
    if value is None:  # left out: the reader's default (an orbit grid following the film's)
        value = {"grid.orbit_n_theta": 48}[f.path]
    path = _sweep_file(tmp_path, f, [value])
    if f.sweepable:
        spec = load_sweep(path)
        assert spec.parameters[0].path == f.path and spec.parameters[0].kind == f.kind
    else:
        with pytest.raises(InputError, match=rf"parameters\.{f.path}: unknown parameter"):
            load_sweep(path)


@pytest.mark.parametrize("f", _FILE_FIELDS, ids=lambda f: f.path)
def test_the_reader_refuses_another_dimension_naming_the_field(f: CaseField) -> None:
    """Each field read with a value the schema's kind does not allow (a length for a mass,
    a unit on a plain number, a quantity for an integer or a word) is refused by name."""
    wrong: Any = "1 m" if f.kind != "length" else "1 kg"
    if f.kind == "choice":
        wrong = "no-such-word"
    tables = _tables(f)
    if f.path.endswith(".angles"):
        wrong = [wrong]
    _put(tables, f.path, wrong)
    assert f.path in _refused(tables, f)
    # and the value of the case, written in the SI unit of the schema's kind, reads back
    base = case_from_dict(_tables(f), source="case.toml")
    value = f.value(base)
    if value is None:
        return
    right = (
        [_as_written(f, v) for v in value] if isinstance(value, tuple) else _as_written(f, value)
    )
    tables = _tables(f)
    _put(tables, f.path, right)
    assert f.value(case_from_dict(tables, source="case.toml")) == value, f.path


def _as_written(f: CaseField, v: Any) -> Any:
    unit = SI_UNITS.get(f.kind, "")
    return f"{float(v)!r} {unit}" if unit else v


def _outside(f: CaseField) -> list[Any]:
    """Values just outside the field's bounds, as a case file writes them (SI)."""
    b = f.bounds
    assert b is not None
    if b.allowed:
        return [3, 0]
    ends = []
    if math.isfinite(b.lo):
        ends.append(b.lo if b.lo_open else b.lo - 1)
    if math.isfinite(b.hi):
        ends.append(b.hi if b.hi_open else b.hi + 1)
    if f.kind == "integer":
        return [int(v) for v in ends]
    unit = SI_UNITS[f.kind]
    return [f"{float(v)!r} {unit}" if unit else float(v) for v in ends]


def _closed_ends(f: CaseField) -> list[Any]:
    """The finite closed ends of the field's bounds (or its allowed values), as written."""
    b = f.bounds
    assert b is not None
    if b.allowed:
        return list(b.allowed)
    ends = [
        e for e, open_ in ((b.lo, b.lo_open), (b.hi, b.hi_open)) if math.isfinite(e) and not open_
    ]
    if f.kind == "integer":
        return [int(v) for v in ends]
    unit = SI_UNITS[f.kind]
    return [f"{float(v)!r} {unit}" if unit else float(v) for v in ends]


_BOUNDED = [f for f in _FILE_FIELDS if f.bounds is not None]


@pytest.mark.parametrize("f", _BOUNDED, ids=lambda f: f.path)
def test_the_reader_refuses_a_value_outside_the_schemas_bounds(f: CaseField) -> None:
    """Just outside each end of the range the schema states, the reader refuses the value
    naming the field; the case's own value is inside the range."""
    base = case_from_dict(_tables(f), source="case.toml")
    value = f.value(base)
    assert f.bounds is not None
    for v in value if isinstance(value, tuple) else (value,):
        if v is not None:
            assert f.bounds.contains(v), f.path
    for end in _closed_ends(f):  # a closed end is allowed
        tables = copy.deepcopy(_tables(f))
        _put(tables, f.path, [end] if f.path.endswith(".angles") else end)
        if f.path == "grid.orbit_n_z":  # 2 cells need the second order (a rule across fields)
            _put(tables, "grid.orbit_axial_order", 2)
        case_from_dict(tables, source="case.toml")
    for bad in _outside(f):
        assert not f.bounds.contains(bad if not isinstance(bad, str) else float(bad.split()[0]))
        tables = copy.deepcopy(_tables(f))
        _put(tables, f.path, [bad] if f.path.endswith(".angles") else bad)
        assert f.path in _refused(tables, f), bad


@pytest.mark.parametrize("path", [_SHIMMED, default_case_path()], ids=["shimmed", "built-in"])
def test_the_summary_shows_each_field_in_its_display_unit(path: Path) -> None:
    """Every field with a summary key is shown under it, in its display unit: µm, rpm, deg,
    g·mm as the summary always wrote them (to the bit)."""
    case = load_case(path)
    summary = case_summary(case)
    shown = 0
    for f in CASE_FIELDS:
        value = f.value(case)
        if f.summary is None or value is None:
            continue
        shown += 1
        assert summary[f.summary] == (
            [_by_hand(f, v) for v in value] if isinstance(value, tuple) else _by_hand(f, value)
        ), f.path
    assert shown >= 15


def test_a_summary_key_names_its_display_unit() -> None:
    """``clearance_um`` is in µm, ``speed_rpm`` in rpm, ``k_b_N_per_m3`` in N/m³: the key
    a script reads says the unit the schema converts to."""
    for f in CASE_FIELDS:
        unit = f.display_unit
        if f.summary is None or not unit:
            continue
        token = unit.replace("**", "").replace("*", "_").replace("/", "_per_")
        assert f.summary.endswith(f"_{token}") or f"_{token}_" in f.summary, (f.path, unit)


def _by_hand(f: CaseField, v: Any) -> Any:
    """The conversions case_summary wrote by hand before the schema."""
    factor = {"mm": 1e3, "um": 1e6, "g*mm": 1e6}
    if f.display_unit == "rpm":
        return v / RPM
    if f.display_unit == "deg":
        return math.degrees(v)
    return v * factor[f.display_unit] if f.display_unit in factor else v
