"""Quantities at the edges: parse "100 um", "90000 rpm", "1.85e-5 Pa*s" once, to SI.

Inside the package every number is SI. Input files may give a dimensional value
either as a plain number (taken as SI) or as a quantity string, converted here
against the dimension the field requires; the dimension is tied to the field,
never guessed from its name.
"""

from __future__ import annotations

import math
from functools import cache
from typing import Any

import pint

from foilbearing.errors import InputError

__all__ = ["SI_UNITS", "parse_quantity", "parse_speed_range", "ureg"]

ureg: Any = pint.UnitRegistry()
ureg.define("rpm = revolution / minute")

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


@cache
def _unit(kind: str) -> Any:
    return ureg.parse_units(SI_UNITS[kind]) if SI_UNITS[kind] else ureg.dimensionless


def parse_quantity(value: object, kind: str, *, field: str, source: str | None = None) -> float:
    """Convert a plain number (SI) or a quantity string to a float in SI units.

    Parameters
    ----------
    value
        A number (already SI; angles in radians) or a string such as ``"100 um"``,
        ``"60 deg"``, ``"90000 rpm"``.
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
        dimension, or is not finite.
    """
    target = _unit(kind)
    if isinstance(value, bool):
        raise InputError(f"{field} = {value!r}: expected a number or a quantity", source=source)
    if isinstance(value, int | float):
        result = float(value)
    elif isinstance(value, str):
        try:
            quantity: Any = ureg.Quantity(value)
        except Exception:
            raise InputError(
                f"{field} = {value!r}: not a quantity (write e.g. '{_example(kind)}')",
                source=source,
            ) from None
        try:
            if not isinstance(quantity, ureg.Quantity):
                quantity = ureg.Quantity(float(quantity), "")
            result = float(quantity.to(target).magnitude)
        except pint.DimensionalityError:
            wanted = SI_UNITS[kind] or "dimensionless"
            raise InputError(
                f"{field} = {value!r}: wrong dimension, expected {kind} (in {wanted}, "
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
    if not math.isfinite(result):
        raise InputError(f"{field} = {value!r}: must be finite", source=source)
    return result


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
