"""Quantities at the edges: parse "100 um", "90000 rpm", "1.85e-5 Pa*s" once, to SI.

Inside the package every number is SI. Where a person types a number (case,
sweep, uncertainty, schedule and rotor files, the command line), a dimensional
value is a quantity string with its unit ("100 um", "30 krpm"), converted here
against the dimension the field requires; the dimension is tied to the field,
never guessed from its name. A bare number there is refused ("add a unit"), and
a dimensionless field refuses a unit ("0.1 deg" for a loss factor): both would
otherwise be read silently as something else.

pint does the conversions. Building its unit registry takes about 0.4 s and
importing pint 0.3 s, more than the whole ``foilbearing case show``, so the
registry :data:`ureg` is built on first use, and a plain ``"value unit"`` string
whose unit is one of a small known set (:data:`_FAST_UNITS`) of the dimension
the field requires is converted without pint: by the same factor pint uses
(``value * factor``), so with the same result to the last bit (tested). Every
other string, and every error message, goes through pint.
"""

from __future__ import annotations

import math
import re
from functools import cache
from typing import Any

from foilbearing.errors import InputError

__all__ = [
    "SI_UNITS",
    "QuantityLike",
    "as_si",
    "as_si_array",
    "from_si",
    "parse_quantity",
    "parse_speed_range",
    "si_text",
    "speed_text",
    "ureg",
]


@cache
def _registry() -> Any:
    """pint's unit registry with ``rpm`` (built once, on first use)."""
    import pint

    registry: Any = pint.UnitRegistry()
    registry.define("rpm = revolution / minute")
    return registry


#: pint's unit registry (with ``rpm``), built on first access by the module ``__getattr__``.
ureg: Any


def __getattr__(name: str) -> Any:
    # ``ureg``: the registry, built when first asked for (``from foilbearing.units import ureg``).
    if name == "ureg":
        return _registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


#: The SI unit each kind of field is converted to (the string names a pint unit).
SI_UNITS: dict[str, str] = {
    "length": "m",
    "angle": "rad",
    "area": "m**2",
    "pressure": "Pa",
    "viscosity": "Pa*s",
    "force": "N",
    "mass": "kg",
    "mass_length": "kg*m",
    "density": "kg/m**3",
    "moment_of_inertia": "kg*m**2",
    "acceleration": "m/s**2",
    "speed": "rad/s",
    "frequency": "Hz",
    "angular_acceleration": "rad/s**2",
    "voltage": "V",
    "slew_rate": "V/s",
    "power": "W",
    "time": "s",
    "stiffness": "N/m",
    "damping": "N*s/m",
    "stiffness_per_area": "N/m**3",
    "length_per_voltage": "m/V",
    "length_per_voltage2": "m/V**2",
    "dimensionless": "",
}


#: Units converted without pint: unit string -> (kind of :data:`SI_UNITS`, factor to SI),
#: each factor the one pint's ``Quantity(1, unit).to(SI unit)`` gives (checked by the tests).
_FAST_UNITS: dict[str, tuple[str, float]] = {
    "m": ("length", 1),
    "mm": ("length", 0.001),
    "um": ("length", 1e-06),
    "cm": ("length", 0.01),
    "deg": ("angle", 0.017453292519943295),
    "rad": ("angle", 1),
    "m**2": ("area", 1),
    "mm**2": ("area", 1e-06),
    "Pa": ("pressure", 1),
    "kPa": ("pressure", 1000.0),
    "MPa": ("pressure", 1000000.0),
    "GPa": ("pressure", 1000000000.0),
    "bar": ("pressure", 100000.0),
    "Pa*s": ("viscosity", 1),
    "N": ("force", 1),
    "kg": ("mass", 1),
    "g": ("mass", 0.001),
    "g*mm": ("mass_length", 1e-06),
    "kg*m": ("mass_length", 1),
    "rpm": ("speed", 0.10471975511965977),
    "rad/s": ("speed", 1),
    "Hz": ("frequency", 1),
    "rad/s**2": ("angular_acceleration", 1),
    "V": ("voltage", 1),
    "V/s": ("slew_rate", 1),
    "W": ("power", 1),
    "s": ("time", 1),
    "ms": ("time", 0.001),
    "N/m": ("stiffness", 1),
    "N*s/m": ("damping", 1),
    "N/m**3": ("stiffness_per_area", 1),
    "um/V": ("length_per_voltage", 1e-06),
    "m/V": ("length_per_voltage", 1),
    "um/V**2": ("length_per_voltage2", 1e-06),
    "m/V**2": ("length_per_voltage2", 1),
}

# A decimal number (integer or floating-point literal) and a unit, as in "100 um" or "0.46e6N/m".
_VALUE_UNIT = re.compile(r"\s*([+-]?)(\d+)(\.\d*)?([eE][+-]?\d+)?\s*(\S+)\s*")


def _fast_quantity(value: str, kind: str) -> float | None:
    """``value`` in SI without pint, or None when pint must parse it.

    Only a number followed by a unit of :data:`_FAST_UNITS` of this kind: as pint
    reads it, an integer literal as ``int`` and any other as ``float``, times the
    unit's factor.
    """
    m = _VALUE_UNIT.fullmatch(value)
    if m is None:
        return None
    sign, digits, fraction, exponent, unit = m.groups()
    known = _FAST_UNITS.get(unit)
    if known is None or known[0] != kind:
        return None
    number: int | float
    if fraction is None and exponent is None:
        number = int(digits)
    else:
        number = float(digits + (fraction or "") + (exponent or ""))
    if sign == "-":
        number = -number
    return float(number * known[1])


@cache
def _unit(kind: str) -> Any:
    ureg = _registry()
    return ureg.parse_units(SI_UNITS[kind]) if SI_UNITS[kind] else ureg.dimensionless


def parse_quantity(value: object, kind: str, *, field: str, source: str | None = None) -> float:
    """Convert a quantity string, or a dimensionless number, to a float in SI units.

    Parameters
    ----------
    value
        A string such as ``"100 um"``, ``"60 deg"``, ``"90000 rpm"``; for the kind
        ``"dimensionless"`` a number (or its string) without a unit.
    kind
        Key of :data:`SI_UNITS` naming the dimension the field requires.
    field
        Dotted name of the field, for the error message (``"bearing.clearance"``).
    source
        File the value came from, for the error message.

    Raises
    ------
    InputError
        If the value is not a number or a parsable quantity, has the wrong
        dimension, is a bare number where the kind has a dimension, has a unit
        where it has none, or is not finite.
    """
    wanted = SI_UNITS[kind]  # a KeyError for an unknown kind, whatever the value
    if isinstance(value, bool):
        raise InputError(f"{field} = {value!r}: expected a number or a quantity", source=source)
    if isinstance(value, int | float) and wanted:
        raise _bare_number(value, kind, field, source)
    if kind == "dimensionless":
        return _dimensionless(value, field, source)
    if isinstance(value, str) and (fast := _fast_quantity(value, kind)) is not None:
        result = fast
    elif isinstance(value, str):
        import pint

        ureg = _registry()
        target = _unit(kind)
        try:
            quantity: Any = ureg.Quantity(value)
        except Exception:
            raise InputError(
                f"{field} = {value!r}: not a quantity (write e.g. '{_example(kind)}')",
                source=source,
            ) from None
        if not _has_unit(quantity):
            raise _bare_number(value, kind, field, source)
        try:
            result = float(quantity.to(target).magnitude)
        except pint.DimensionalityError:
            raise InputError(
                f"{field} = {value!r}: wrong dimension, expected {kind} (in {wanted or 'dimensionless'}, "
                f"e.g. '{_example(kind)}')",
                source=source,
            ) from None
        except Exception:
            raise InputError(f"{field} = {value!r}: not a quantity", source=source) from None
    else:
        raise InputError(
            f"{field} = {value!r}: expected a number or a quantity string", source=source
        )
    if (
        kind == "speed"
        and isinstance(value, str)
        and ("hz" in value.lower() or "hertz" in value.lower())
    ):
        # pint's radian is dimensionless, so "1 Hz" would silently become 1 rad/s.
        raise InputError(
            f"{field} = {value!r}: give a rotor speed in rpm or rad/s, not Hz", source=source
        )
    if kind == "frequency" and isinstance(value, str) and ("rpm" in value or "rad" in value):
        # and "60 rpm" would become 2π Hz, not 1 Hz.
        raise InputError(
            f"{field} = {value!r}: give a frequency in Hz (cycles per second), not rpm or rad/s",
            source=source,
        )
    if not math.isfinite(result):
        raise InputError(f"{field} = {value!r}: must be finite", source=source)
    return result


#: The unit a message suggests for a bare number, by kind (default: the kind's SI unit).
_BARE_HINT = {"speed": "rpm", "angle": "deg", "viscosity": "Pa*s", "mass_length": "g*mm"}


def _bare_number(value: object, kind: str, field: str, source: str | None) -> InputError:
    """The one-line error for a number without a unit where ``kind`` has a dimension."""
    number = f"{value:g}" if isinstance(value, int | float) else str(value).strip()
    unit = _BARE_HINT.get(kind, SI_UNITS[kind])
    return InputError(f"{field} = {value!r}: add a unit, e.g. '{number} {unit}'", source=source)


def _has_unit(quantity: Any) -> bool:
    """Whether pint's parse of a string wrote a unit (``"0.1"`` none; ``"10 percent"`` one)."""
    return isinstance(quantity, _registry().Quantity) and str(quantity.units) != "dimensionless"


def _dimensionless(value: object, field: str, source: str | None) -> float:
    """A dimensionless field's value: a number, or a string of a number without a unit.

    A unit is refused, an angle's too: pint's radian is dimensionless, so ``"0.1 deg"``
    would pass as 0.00175. Percent (``"10 %"``) is refused as well, with the fraction to
    write.
    """
    if isinstance(value, int | float):
        result = float(value)
    elif isinstance(value, str):
        ureg = _registry()
        try:  # "%" spelt out: pint reads "10 %" as the number 10
            quantity: Any = ureg.Quantity(value.replace("%", " percent"))
        except Exception:
            raise InputError(
                f"{field} = {value!r}: not a number (write e.g. '0.1')", source=source
            ) from None
        if _has_unit(quantity):
            try:
                fraction = float(quantity.to("dimensionless").magnitude)
                angle = quantity.check("[]") and "rad" in str(quantity.to_base_units().units)
                suggested = float(quantity.magnitude) if angle else fraction
            except Exception:
                suggested = float(quantity.magnitude)
            raise InputError(
                f"{field} is dimensionless: write {suggested:g}, not {value!r}", source=source
            )
        result = float(quantity.magnitude if isinstance(quantity, ureg.Quantity) else quantity)
    else:
        raise InputError(f"{field} = {value!r}: expected a number", source=source)
    if not math.isfinite(result):
        raise InputError(f"{field} = {value!r}: must be finite", source=source)
    return result


#: What the Python API takes where it takes a speed, a load, a length or a frequency: a
#: float in SI, a quantity string ("30 krpm") or a pint ``Quantity`` (:func:`as_si`).
QuantityLike = Any


def as_si(value: QuantityLike, kind: str, *, field: str) -> float:
    """An argument of the Python API in SI: a float as is, or a quantity converted.

    Parameters
    ----------
    value
        A number, already SI (rad/s, N, m, ...: floats stay SI); a quantity string
        (``"30 krpm"``, ``"50 N"``); or a pint ``Quantity`` (of any registry).
    kind
        Key of :data:`SI_UNITS`, or ``"angular_frequency"``: rad/s, given as a
        frequency in Hz (``"100 Hz"`` is 2π·100 rad/s) or as a speed (rad/s, rpm).
    field
        The argument's name, for the one-line error.

    Raises
    ------
    InputError
        A string or quantity of the wrong dimension (the checks of
        :func:`parse_quantity`), or a value that is neither.
    """
    if isinstance(value, bool):
        raise InputError(f"{field} = {value!r}: expected a number or a quantity")
    if isinstance(value, int | float):
        return float(value)
    if hasattr(value, "magnitude") and hasattr(value, "units"):  # a pint Quantity
        magnitude = value.magnitude
        if not isinstance(magnitude, int | float) and getattr(magnitude, "ndim", 1) != 0:
            raise InputError(f"{field} = {value!r}: expected one value (or use as_si_array)")
        value = f"{float(magnitude)!r} {value.units}"
    if not isinstance(value, str):
        item = getattr(value, "item", None)  # a NumPy scalar
        if callable(item) and getattr(value, "ndim", 1) == 0:
            return as_si(item(), kind, field=field)
        raise InputError(f"{field} = {value!r}: expected a number or a quantity")
    if kind == "angular_frequency":
        lowered = value.lower()
        if "hz" in lowered or "hertz" in lowered:
            return 2.0 * math.pi * parse_quantity(value, "frequency", field=field)
        return parse_quantity(value, "speed", field=field)
    return parse_quantity(value, kind, field=field)


def as_si_array(values: Any, kind: str, *, field: str) -> Any:
    """:func:`as_si` of a scalar or a sequence, as a float NumPy array (floats as is).

    A pint ``Quantity`` holding an array is converted whole.
    """
    import numpy as np

    if hasattr(values, "magnitude") and hasattr(values, "units"):
        magnitudes = np.atleast_1d(np.asarray(values.magnitude, dtype=float))
        factor = as_si(values.__class__(1.0, values.units), kind, field=field)
        return magnitudes * factor
    if isinstance(values, list | tuple):
        return np.array(
            [as_si(v, kind, field=f"{field}[{i}]") for i, v in enumerate(values)], dtype=float
        )
    if isinstance(values, str) or np.ndim(values) == 0:
        return np.atleast_1d(as_si(values, kind, field=field))
    return np.asarray(values, dtype=float)


def si_text(value: float, kind: str) -> str | float:
    """``value`` (SI) as the text a file holds, ``"0.0001 m"``; a dimensionless one as is.

    :func:`parse_quantity` reads it back to the same float (the SI unit's factor is 1).
    """
    unit = SI_UNITS[kind]
    return f"{float(value)!r} {unit}" if unit else float(value)


def parse_speed_range(text: str, *, field: str, source: str | None = None) -> list[float]:
    """Speeds (rad/s) from "START:STOP:STEP", e.g. "5000rpm:150000rpm:5000rpm" (at most 1000 steps)."""
    parts = text.split(":")
    if len(parts) != 3:
        raise InputError(
            f"{field} {text!r}: expected START:STOP:STEP, e.g. 5000rpm:150000rpm:5000rpm",
            source=source,
        )
    start, stop, step = (parse_quantity(p, "speed", field=field, source=source) for p in parts)
    if not 0 < start < stop or step <= 0 or (stop - start) / step > 1000:
        raise InputError(
            f"{field} {text!r}: need 0 < START < STOP and 0 < STEP, at most 1000 steps",
            source=source,
        )
    n = round((stop - start) / step) + 1
    return [start + k * step for k in range(n)]


def _example(kind: str) -> str:
    examples = {
        "length": "100 um",
        "angle": "60 deg",
        "area": "3.54e-4 m**2",
        "pressure": "101325 Pa",
        "viscosity": "1.85e-5 Pa*s",
        "force": "8.8 N",
        "mass": "0.897 kg",
        "mass_length": "8.5 g*mm",
        "density": "7850 kg/m**3",
        "moment_of_inertia": "4e-4 kg*m**2",
        "acceleration": "9.81 m/s**2",
        "speed": "90000 rpm",
        "frequency": "120 Hz",
        "angular_acceleration": "500 rad/s**2",
        "voltage": "150 V",
        "time": "6.0 s",
        "stiffness": "0.46e6 N/m",
        "stiffness_per_area": "8.69e9 N/m**3",
        "length_per_voltage": "0.9122 um/V",
        "length_per_voltage2": "-0.0028 um/V**2",
        "dimensionless": "0.1",
    }
    return examples.get(kind, "1.0")


def from_si(value: Any, unit: str, si_unit: str) -> Any:
    """``value`` (a number or array in ``si_unit``, the SI unit of its kind) in ``unit``.

    By the factor of :data:`_FAST_UNITS` (``value / factor``, the inverse of
    :func:`parse_quantity`'s fast path) when both units are there and of one
    kind; by pint otherwise. ``unit == si_unit`` returns ``value`` itself.

    Raises
    ------
    pint.DimensionalityError
        If the units are of different kinds (a bug in the caller's table).
    """
    if unit == si_unit:
        return value
    known, base = _FAST_UNITS.get(unit), _FAST_UNITS.get(si_unit)
    if known is not None and base is not None and known[0] == base[0] and base[1] == 1:
        return value / known[1]
    ureg = _registry()
    return ureg.Quantity(value, si_unit).to(unit).magnitude


def speed_text(rpm: float) -> str:
    """A computed speed (an onset, a divergence) to three significant figures in krpm,
    e.g. "65.0 krpm", "7.84 krpm", "142 krpm".

    An onset on a case's grid is 0.5-2 % from its converged value (docs/lift-off.md,
    "The published onsets' error"); its fourth digit would be noise.
    """
    krpm = rpm / 1e3
    decimals = 0 if abs(krpm) >= 99.95 else 1 if abs(krpm) >= 9.995 else 2
    return f"{krpm:.{decimals}f} krpm"
