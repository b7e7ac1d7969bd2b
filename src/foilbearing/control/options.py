"""The option strings of speed and voltage programs, read once for every command.

``foilbearing orbit`` (through :meth:`foilbearing.orbit.spec.RunSpec.from_cli_strings`, which
also reads the strings an earlier version stored) and ``foilbearing rotor --orbit`` take the
same strings: a quantity with its unit (``"40000rpm"``, ``"500rad/s**2"``, ``"0.5s"``), a speed
ramp ``START:STOP:ACCELERATION`` or a constant speed for a duration, a voltage ramp
``T0:T1:V`` and the controller's ``KEY=VALUE,...``. Each function returns SI values (s,
rad/s, rad/s², V, m) or the program itself, and a string that does not parse is one
:class:`~foilbearing.errors.InputError` line naming the option.
"""

from __future__ import annotations

from foilbearing.control.profiles import SpeedProfile, constant_speed, linear_ramp
from foilbearing.errors import InputError

__all__ = [
    "CONTROLLER_KEYS",
    "cli_quantity",
    "controller_args",
    "positive_time",
    "speed_program",
    "speed_ramp",
    "steady_speed",
    "voltage_ramp_times",
]

#: ``--controller``'s keys: the kind of quantity each takes and the controller's attribute.
CONTROLLER_KEYS = {
    "threshold": ("length", "threshold"),
    "target": ("voltage", "target"),
    "slew": ("slew_rate", "slew_rate"),
    "window": ("time", "window"),
    "period": ("time", "period"),
    "initial": ("voltage", "initial"),
}


def cli_quantity(text: str, kind: str, option: str) -> float:
    """A command-line quantity in SI (``rad/s2`` is read as ``rad/s**2``); ``option``
    names it in the one-line error."""
    from foilbearing.units import parse_quantity

    return parse_quantity(
        text.replace("s2", "s**2") if kind == "angular_acceleration" else text, kind, field=option
    )


def positive_time(text: str, option: str) -> float:
    """A time > 0, s (``--stop-time``, ``--checkpoint-every``), else one line naming
    ``option``, worded as every command words it (``--stop-time = '-1s': a time must be > 0``)."""
    value = cli_quantity(text, "time", option)
    if not value > 0.0:
        raise InputError(f"{option} = {text!r}: a time must be > 0")
    return value


def _ramp(parts: list[str], option: str) -> SpeedProfile:
    """The linear ramp of START, STOP and ACCELERATION (rad/s, rad/s, rad/s²)."""
    return linear_ramp(
        cli_quantity(parts[0], "speed", f"{option} START"),
        cli_quantity(parts[1], "speed", f"{option} STOP"),
        cli_quantity(parts[2], "angular_acceleration", f"{option} ACCELERATION"),
    )


def speed_ramp(text: str, option: str = "--speed-ramp") -> SpeedProfile:
    """``START:STOP:ACCELERATION`` (e.g. ``3000rpm:90000rpm:500rad/s**2``): the speed-up."""
    parts = text.split(":")
    if len(parts) != 3:
        raise InputError(f"{option} {text!r}: expected START:STOP:ACCELERATION")
    return _ramp(parts, option)


def steady_speed(
    speed: str, duration: str, options: tuple[str, str] = ("--speed", "--duration")
) -> SpeedProfile:
    """A constant ``speed`` for ``duration`` (e.g. ``"40000rpm"``, ``"0.2s"``); ``options``
    name the two strings in the errors."""
    return constant_speed(
        cli_quantity(speed, "speed", options[0]), cli_quantity(duration, "time", options[1])
    )


def speed_program(text: str, option: str = "--orbit") -> SpeedProfile:
    """``SPEED:DURATION`` (constant, e.g. ``40000rpm:0.2s``) or ``START:STOP:ACCELERATION``
    (a speed-up, e.g. ``30000rpm:60000rpm:500rad/s**2``)."""
    parts = text.split(":")
    if len(parts) == 2:
        speed = cli_quantity(parts[0], "speed", f"{option} SPEED")
        duration = cli_quantity(parts[1], "time", f"{option} DURATION")
        if speed <= 0 or duration <= 0:
            raise InputError(f"{option} {text!r}: speed and duration must be > 0")
        return constant_speed(speed, duration)
    if len(parts) == 3:
        return _ramp(parts, option)
    raise InputError(
        f"{option} {text!r}: write SPEED:DURATION (e.g. 40000rpm:0.2s) or "
        "START:STOP:ACCELERATION (e.g. 30000rpm:60000rpm:500rad/s**2)"
    )


def voltage_ramp_times(text: str, option: str = "--voltage-ramp") -> tuple[float, float, float]:
    """``T0:T1:V`` (e.g. ``6.0s:6.5s:150V``): the ramp's start and end, s, and its final
    voltage, V (:func:`foilbearing.control.voltage_ramp` takes them, with the case's voltages
    as the start)."""
    parts = text.split(":")
    if len(parts) != 3:
        raise InputError(f"{option} {text!r}: expected T0:T1:V, e.g. 6.0s:6.5s:150V")
    return (
        cli_quantity(parts[0], "time", f"{option} T0"),
        cli_quantity(parts[1], "time", f"{option} T1"),
        cli_quantity(parts[2], "voltage", f"{option} V"),
    )


def controller_args(text: str, option: str = "--controller") -> dict[str, float]:
    """``threshold=2um,target=150V,...`` as the controller's keyword arguments (SI); the
    keys are :data:`CONTROLLER_KEYS`."""
    out: dict[str, float] = {}
    for item in filter(None, (s.strip() for s in text.split(","))):
        key, _, value = item.partition("=")
        if key not in CONTROLLER_KEYS or not value:
            raise InputError(
                f"{option} {item!r}: expected KEY=VALUE with KEY one of "
                + ", ".join(CONTROLLER_KEYS)
            )
        kind, name = CONTROLLER_KEYS[key]
        out[name] = cli_quantity(value, kind, f"{option} {key}")
    return out
