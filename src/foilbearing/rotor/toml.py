"""Reading a rotor file (TOML, values with units) into a :class:`RotorCase`.

The format (docs/rotor-format.md)::

    title = "rigid symmetric rotor"

    [material]
    density = "7850 kg/m**3"
    youngs_modulus = "211 GPa"
    poisson_ratio = 0.29

    [shaft]                      # element k between nodes k and k + 1
    lengths = ["50 mm", "50 mm"]
    outer_diameters = ["30 mm", "30 mm"]
    inner_diameters = ["0 mm", "0 mm"]   # optional

    [[disks]]
    node = 1
    mass = "1.79 kg"
    polar_inertia = "4e-4 kg*m**2"
    diametral_inertia = "2e-4 kg*m**2"

    [[bearings]]
    node = 0
    case = "default"             # the built-in C-GFB, or a case file relative to this one
    voltages = "0 V"             # optional: every actuator, or a list, one per actuator
    label = "drive end"          # optional

Bad input is a one-line :class:`~foilbearing.errors.InputError` naming the file and the
field.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from foilbearing.case import Case, default_case, load_case
from foilbearing.case.toml import TableReader
from foilbearing.errors import InputError
from foilbearing.rotor.model import (
    STANDARD_GRAVITY,
    BearingSite,
    Disk,
    Material,
    RotorCase,
    ShaftElement,
)
from foilbearing.units import parse_quantity

__all__ = ["load_rotor", "rotor_from_dict"]


def load_rotor(path: str | Path) -> RotorCase:
    """Read and validate a rotor file; bearing cases are found relative to it."""
    path = Path(path)
    source = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError("rotor file not found", source=source) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(
            f"cannot read rotor file ({exc.__class__.__name__})", source=source
        ) from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", source=source) from None
    return rotor_from_dict(data, source=source, folder=path.parent)


def rotor_from_dict(
    data: dict[str, Any], *, source: str | None = None, folder: Path | None = None
) -> RotorCase:
    """Build a :class:`RotorCase` from the parsed tables (case files relative to ``folder``)."""
    top = TableReader(data, "", source)
    title = top.string("title", "rotor")
    gravity = float(top.nonnegative("gravity", "acceleration", STANDARD_GRAVITY))
    m = top.table("material")
    material = Material(
        m.positive("density", "density"),
        m.positive("youngs_modulus", "pressure"),
        m.number("poisson_ratio", 0.0, 0.5, hi_open=True),
    )
    m.done()
    shaft = _shaft(top.table("shaft"), source)
    disks = tuple(_disk(t) for t in _tables(top, "disks", source, required=False))
    bearings = tuple(
        _bearing(t, k, folder)
        for k, t in enumerate(_tables(top, "bearings", source, required=True))
    )
    top.done()
    return RotorCase(title, material, shaft, disks, bearings, gravity, source)


def _tables(top: TableReader, key: str, source: str | None, *, required: bool) -> list[TableReader]:
    raw = top.raw(key, None if not required else ...)
    if raw is None:
        return []
    if not isinstance(raw, list) or not raw or not all(isinstance(t, dict) for t in raw):
        raise InputError(f"[[{key}]] must be one or more tables", source=source)
    return [TableReader(t, f"{key}[{k}]", source) for k, t in enumerate(raw)]


def _lengths(t: TableReader, key: str, n: int | None) -> list[float]:
    raw = t.raw(key)
    if not isinstance(raw, list) or not raw or (n is not None and len(raw) != n):
        count = "a non-empty list" if n is None else f"a list of {n} (one per element)"
        raise t.error(key, raw, f"{count} of lengths, e.g. ['50 mm', '50 mm']")
    out = []
    for k, v in enumerate(raw):
        x = parse_quantity(v, "length", field=f"{t.prefix}{key}[{k}]", source=t.source)
        if x < 0.0:
            raise t.error(f"{key}[{k}]", v, "a length >= 0")
        out.append(x)
    return out


def _shaft(t: TableReader, source: str | None) -> tuple[ShaftElement, ...]:
    lengths = _lengths(t, "lengths", None)
    outer = _lengths(t, "outer_diameters", len(lengths))
    inner = _lengths(t, "inner_diameters", len(lengths)) if "inner_diameters" in t.data else None
    t.used.add("inner_diameters")  # optional: an unknown field's message lists it all the same
    t.done()
    elements = []
    for k, (length, od) in enumerate(zip(lengths, outer, strict=True)):
        idia = 0.0 if inner is None else inner[k]
        if length <= 0.0 or od <= idia:
            raise InputError(
                f"shaft element {k}: length {length * 1e3:g} mm, diameters {od * 1e3:g} / "
                f"{idia * 1e3:g} mm: need a length > 0 and outer > inner",
                source=source,
            )
        elements.append(ShaftElement(length, od, idia))
    return tuple(elements)


def _disk(t: TableReader) -> Disk:
    disk = Disk(
        t.integer("node", 0, 10_000, 0),
        t.positive("mass", "mass"),
        t.nonnegative("polar_inertia", "moment_of_inertia"),
        t.nonnegative("diametral_inertia", "moment_of_inertia"),
    )
    t.done()
    return disk


def _bearing(t: TableReader, k: int, folder: Path | None) -> BearingSite:
    node = t.integer("node", 0, 10_000, 0)
    name = t.string("case", "default")
    if name == "default":
        case = default_case()
    else:
        path = Path(name)
        case = load_case(path if path.is_absolute() or folder is None else folder / path)
    if "voltages" in t.data:
        case = _with_voltages(t, case)
    label = t.string("label", f"bearing {k} (node {node})")
    t.done()
    return BearingSite(node, case, label)


def _with_voltages(t: TableReader, case: Case) -> Case:
    raw = t.raw("voltages")
    if case.actuators is None:
        raise t.error("voltages", raw, "no voltages: the bearing case has no actuators")
    items = raw if isinstance(raw, list) else [raw] * len(case.actuators.angles)
    if len(items) != len(case.actuators.angles):
        raise t.error(
            "voltages",
            raw,
            f"one voltage, or a list of {len(case.actuators.angles)} (one per actuator)",
        )
    volts = [
        parse_quantity(v, "voltage", field=f"{t.prefix}voltages", source=t.source) for v in items
    ]
    return case.with_voltages(tuple(volts))
