"""The sweep file: parameters, their units and values, and the validated grid.

:func:`load_sweep` reads a sweep file (``docs/sweep-format.md``), resolves each
swept name to a case field (:data:`FIELD_KINDS`, from the case schema), converts the values to SI,
and validates the case of every grid point before any work (:class:`SweepSpec`).
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.case import Case, case_from_dict, default_case_path, load_case
from foilbearing.case.schema import SWEEP_KINDS
from foilbearing.errors import InputError
from foilbearing.io import read_toml
from foilbearing.sweep.analyses import ANALYSES, value_list
from foilbearing.units import SI_UNITS, ureg

__all__ = ["FIELD_KINDS", "Parameter", "SweepSpec", "base_tables", "load_sweep", "write_field"]

#: Sweepable case fields (dotted TOML path) and the kind of quantity each takes: those of
#: the case schema not marked as not swept (:data:`foilbearing.case.schema.SWEEP_KINDS`).
FIELD_KINDS: dict[str, str] = SWEEP_KINDS
ALIASES = {"speed": "operation.speed", "voltage": "actuators.voltages"}
_VOLTAGE_I = re.compile(r"^voltage\[(\d+)\]$")
_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*")


@dataclass(frozen=True)
class Parameter:
    """One swept parameter: its values as written, in SI, and as coordinates.

    ``coords`` are the values in ``unit``, the unit of the first value as
    written (SI for plain numbers); ``dim`` is the Dataset dimension name.
    """

    name: str  # as written: "speed", "bearing.clearance", "voltage[1]"
    path: str  # the case field: "operation.speed"
    index: int | None  # actuator index of voltage[i]
    kind: str
    raw: tuple[Any, ...]
    values: tuple[Any, ...]  # SI
    unit: str
    coords: tuple[Any, ...]

    @property
    def dim(self) -> str:
        """Dimension name: the name with ``.`` and ``[i]`` as ``_`` (``voltage_1``)."""
        return re.sub(r"[.\[]", "_", self.name).rstrip("]")


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: base case tables, analysis, parameters (grid in C order)."""

    source: str
    title: str
    case_file: str
    base: dict[str, Any]
    analysis: str
    options: dict[str, Any]
    parameters: tuple[Parameter, ...]

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of values of each parameter."""
        return tuple(len(p.values) for p in self.parameters)

    @property
    def n_points(self) -> int:
        """Number of grid points."""
        return math.prod(self.shape)

    def point_values(self, index: int) -> dict[str, Any]:
        """The point's parameter values as written, by parameter name."""
        ijk = np.unravel_index(index, self.shape)
        return {p.name: p.raw[int(i)] for p, i in zip(self.parameters, ijk, strict=True)}

    def point_source(self, index: int) -> str:
        """Where a point comes from, for messages: file, index and values."""
        vals = ", ".join(f"{k} = {v!r}" for k, v in self.point_values(index).items())
        return f"{self.source}, point {index} ({vals})"

    def point_data(self, index: int) -> dict[str, Any]:
        """The case tables of point ``index`` (a new dict)."""
        data = copy.deepcopy(self.base)
        ijk = np.unravel_index(index, self.shape)
        for p, i in zip(self.parameters, ijk, strict=True):
            write_field(data, p.path, p.raw[int(i)], p.index)
        return data

    def point_case(self, index: int) -> Case:
        """The validated case of point ``index``."""
        return case_from_dict(self.point_data(index), source=self.point_source(index))

    def describe(self) -> dict[str, Any]:
        """What the results folder's ``sweep.json`` records of the sweep."""
        return {
            "sweep_file": self.source,
            "case_file": self.case_file,
            "analysis": self.analysis,
            "options": self.options,
            "parameters": [
                {"name": p.name, "dim": p.dim, "values": list(p.raw), "si": list(p.values)}
                for p in self.parameters
            ],
            "case": self.base,
        }

    def fingerprint(self) -> str:
        """SHA-256 of everything that determines the results."""
        key = [self.base, self.analysis, self.options, [(p.name, p.raw) for p in self.parameters]]
        return hashlib.sha256(json.dumps(key, sort_keys=True, default=str).encode()).hexdigest()


def load_sweep(path: str | Path) -> SweepSpec:
    """Read a sweep file and validate every point of its grid.

    Raises
    ------
    InputError
        Bad TOML, unknown table or key, unknown field path, wrong unit, or a
        point whose case is invalid; the message names the sweep file, the
        parameter and the value.
    """
    path = Path(path)
    src = str(path)
    data = read_toml(path, "sweep file")
    analysis = data.get("analysis", "static")
    if analysis not in ANALYSES:
        raise InputError(f"analysis = {analysis!r}: expected one of {sorted(ANALYSES)}", source=src)
    allowed = {"title", "case", "analysis", "set", "parameters", *ANALYSES}
    for key in data:
        if key not in allowed or (key in ANALYSES and key != analysis):
            raise InputError(f"unknown key {key!r} (allowed: {sorted(allowed)})", source=src)
    case_path, base, base_case = base_tables(data, path)
    n_act = len(base_case.actuators.angles) if base_case.actuators is not None else 0
    table = data.get(analysis, {})
    if not isinstance(table, dict):
        raise InputError(f"[{analysis}] must be a table", source=src)
    parse = ANALYSES[analysis].parse_options
    if parse is None and table:
        raise InputError(f"[{analysis}]: this analysis takes no options", source=src)
    options = parse(table, src) if parse is not None else {}
    params = _parameters(data.get("parameters"), n_act, ANALYSES[analysis].fixed, src)
    spec = SweepSpec(
        src, str(data.get("title", "")), str(case_path), base, analysis, options, params
    )
    for index in range(spec.n_points):
        spec.point_case(index)
    return spec


def base_tables(data: dict[str, Any], path: Path) -> tuple[Path, dict[str, Any], Case]:
    """The case a sweep or uncertainty file ``path`` (read as ``data``) starts from.

    Its ``case`` (a path relative to the file, or ``"default"``) with the fixed
    edits of its ``[set]`` table written in (any case field, ``voltage`` or
    ``voltage[i]``), validated. Returns the case file's path, the edited tables
    and the validated case.
    """
    src = str(path)
    case_ref = data.get("case", "default")
    if not isinstance(case_ref, str):
        raise InputError(f"case = {case_ref!r}: expected a path or 'default'", source=src)
    case_path = default_case_path() if case_ref == "default" else path.parent / case_ref
    base_case = load_case(case_path)  # errors name the case file
    base = tomllib.loads(case_path.read_text(encoding="utf-8"))
    n_act = len(base_case.actuators.angles) if base_case.actuators is not None else 0
    fixed = _flatten(data.get("set", {}), "set", src)
    for name, value in fixed.items():
        fpath, idx, _ = _resolve(name, n_act, "set", src)
        write_field(base, fpath, value, idx)
    return case_path, base, case_from_dict(copy.deepcopy(base), source=f"{src} [set]")


def _flatten(table: Any, where: str, src: str) -> dict[str, Any]:
    if not isinstance(table, dict):
        raise InputError(f"[{where}] must be a table of 'field = value' entries", source=src)
    out: dict[str, Any] = {}
    for key, value in table.items():
        if isinstance(value, dict):
            out.update({f"{key}.{k}": v for k, v in _flatten(value, where, src).items()})
        else:
            out[key] = value
    return out


def _resolve(name: str, n_act: int, where: str, src: str) -> tuple[str, int | None, str]:
    """Case field path, actuator index and kind of a parameter name."""
    m = _VOLTAGE_I.match(name)
    if (m or ALIASES.get(name, name) == "actuators.voltages") and n_act == 0:
        raise InputError(f"{where}.{name}: the case has no [actuators]", source=src)
    if m:
        i = int(m.group(1))
        if not 0 <= i < n_act:
            raise InputError(
                f"{where}.{name}: the case has {n_act} actuators (voltage[0] to "
                f"voltage[{n_act - 1}])",
                source=src,
            )
        return "actuators.voltages", i, "voltage"
    path = ALIASES.get(name, name)
    if path not in FIELD_KINDS:
        raise InputError(
            f"{where}.{name}: unknown parameter (allowed: speed, voltage, voltage[i], or a case "
            f"field: {', '.join(FIELD_KINDS)})",
            source=src,
        )
    return path, None, FIELD_KINDS[path]


def _parameters(table: Any, n_act: int, fixed: tuple[str, ...], src: str) -> tuple[Parameter, ...]:
    flat = _flatten(table if table is not None else {}, "parameters", src)
    if not flat:
        raise InputError("[parameters] is missing or empty: nothing to sweep", source=src)
    params: list[Parameter] = []
    seen: dict[tuple[str, int | None], str] = {}
    for name, raw in flat.items():
        fpath, idx, kind = _resolve(name, n_act, "parameters", src)
        if fpath in fixed:
            raise InputError(
                f"parameters.{name}: set by this analysis, cannot be swept", source=src
            )
        clash = next((n for (f, j), n in seen.items() if f == fpath and j in (idx, None)), None)
        clash = clash or next((n for (f, _), n in seen.items() if f == fpath and idx is None), None)
        if clash is not None:
            raise InputError(f"parameters.{name}: the same field as {clash}", source=src)
        seen[(fpath, idx)] = name
        if not isinstance(raw, list) or not raw:
            raise InputError(
                f"parameters.{name} = {raw!r}: expected a non-empty list of values", source=src
            )
        values = value_list(raw, kind, f"parameters.{name}", src)
        unit, coords = _coordinates(raw, values, kind)
        params.append(Parameter(name, fpath, idx, kind, tuple(raw), values, unit, coords))
    return tuple(params)


def _coordinates(raw: list[Any], values: tuple[Any, ...], kind: str) -> tuple[str, tuple[Any, ...]]:
    """Coordinate values in the unit of the first value as written (SI for plain numbers)."""
    if kind in ("integer", "dimensionless"):
        return "1", values
    if kind == "choice":
        return "", values
    si = SI_UNITS[kind]
    first = raw[0]
    unit = _NUMBER.sub("", first, count=1).strip() if isinstance(first, str) else ""
    try:
        coords = tuple(
            float((ureg.Quantity(r) if isinstance(r, str) else ureg.Quantity(r, si)).to(unit).m)
            for r in raw
        )
    except Exception:  # no unit written, or one pint reads differently: SI
        return si, values
    return unit or si, coords


def write_field(data: dict[str, Any], path: str, value: Any, index: int | None = None) -> None:
    """Write ``value`` at the dotted ``path`` of the case tables (actuator ``index`` of a list)."""
    *tables, key = path.split(".")
    node = data
    for t in tables:
        node = node.setdefault(t, {})
        if not isinstance(node, dict):
            return  # case_from_dict reports the malformed table
    if index is None:
        node[key] = value
        return
    current = node.get(key, 0.0)
    n = len(data.get("actuators", {}).get("angles", [])) or index + 1
    items = list(current) if isinstance(current, list) else [current]
    items = items * n if len(items) == 1 else items
    items[index] = value
    node[key] = items
