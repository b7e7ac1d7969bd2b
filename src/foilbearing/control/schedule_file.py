"""The voltage-schedule file: a TOML table a controller (or ``foilbearing orbit``) reads.

``foilbearing schedule --out SCHEDULE.toml`` writes it; a user may also write one
by hand. The format (docs/schedule-format.md)::

    [schedule]
    slew_rate = "300 V/s"          # amplifier slew-rate limit (default 300 V/s)

    [[point]]                      # one per speed, speeds increasing
    speed = "10000 rpm"
    voltages = "0 V"               # one for all actuators, or a list of one per actuator

    [[point]]
    speed = "60000 rpm"
    voltages = ["120 V", "40 V", "120 V"]

Quantities are strings with units ("30000 rpm", "150 V"), as in case files (a
bare number is refused). The command adds what it computed (margin, acceleration, limit speed
in ``[schedule]``; log decrement, power loss and minimum film per point); the
reader checks and keeps them but the orbit uses only the speeds, the voltages
and the slew rate.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.case import Case, TableReader, per_item_quantities
from foilbearing.constants import RPM
from foilbearing.control.speed_schedule import DEFAULT_SLEW_RATE, SpeedSchedule
from foilbearing.errors import InputError

__all__ = ["load_schedule", "parse_schedule", "schedule_toml"]


def _optional(values: np.ndarray | None, k: int) -> float | None:
    if values is None or not math.isfinite(float(values[k])):
        return None
    return float(values[k])


def schedule_toml(schedule: SpeedSchedule, title: str = "") -> str:
    """The schedule as the text of a schedule file (see the module docstring)."""
    lines = [
        f"# Voltage schedule{': ' + title if title else ''}",
        "# Written by `foilbearing schedule`; format: docs/schedule-format.md.",
        "# The orbit interpolates the voltages linearly in speed (held beyond the ends)",
        "# and follows them at most at slew_rate.",
        "",
        "[schedule]",
        f'slew_rate = "{schedule.slew_rate:g} V/s"',
    ]
    if schedule.margin is not None:
        lines.append(
            f"margin = {schedule.margin:g}                 # least log decrement asked for"
        )
    if schedule.acceleration is not None:
        lines.append(
            f'acceleration = "{schedule.acceleration:g} rad/s**2"  # speed-up rate of the smoothness'
        )
    if schedule.limit_speed is not None:
        lines.append(
            f'limit_speed = "{schedule.limit_speed / RPM:.0f} rpm"  # no voltage keeps the rotor '
            "stable above"
        )
    for k, w in enumerate(schedule.speeds):
        volts = ", ".join(f'"{v:.2f} V"' for v in schedule.voltages[k])
        lines += ["", "[[point]]", f'speed = "{w / RPM:.1f} rpm"', f"voltages = [{volts}]"]
        dec = _optional(schedule.log_decrement, k)
        if dec is not None:
            lines.append(f"log_decrement = {dec:.5f}")
        loss = _optional(schedule.power_loss, k)
        if loss is not None:
            lines.append(f'power_loss = "{loss:.5g} W"')
        film = _optional(schedule.min_film, k)
        if film is not None:
            lines.append(f'min_film = "{film * 1e6:.3f} um"')
    return "\n".join(lines) + "\n"


def load_schedule(path: Path, case: Case) -> SpeedSchedule:
    """Read and check a schedule file for ``case``; every error is one line naming the field.

    Raises
    ------
    InputError
        Missing file or bad TOML; unknown fields; no ``[[point]]``; speeds not
        increasing or ≤ 0; a voltage list of the wrong length, or a voltage
        outside 0 to the case's ``max_voltage``; a slew rate ≤ 0.
    """
    from foilbearing.io import read_toml

    return parse_schedule(read_toml(path, "schedule file"), case, str(path))


def parse_schedule(data: dict[str, Any], case: Case, source: str) -> SpeedSchedule:
    """The schedule of a schedule file's parsed TOML ``data``; ``source`` names it in errors."""
    act = case.actuators
    if act is None:
        raise InputError(
            "a voltage schedule needs a case with [actuators]: this case has none", source=source
        )
    root = TableReader(data, "", source)
    head = root.table("schedule") if "schedule" in data else TableReader({}, "schedule", source)
    slew = head.positive("slew_rate", "slew_rate", default=DEFAULT_SLEW_RATE)
    margin = head.quantity("margin", "dimensionless", default=None)
    accel = head.positive("acceleration", "angular_acceleration", default=None)
    limit = head.positive("limit_speed", "speed", default=None)
    head.done()
    rows = root.raw("point", default=None)
    root.done()
    if not isinstance(rows, list) or not rows:
        raise InputError(
            "no [[point]] tables: a schedule needs at least one speed with its voltages",
            source=source,
        )
    n = len(act.angles)
    speeds, volts, dec, loss, film = [], [], [], [], []
    for i, row in enumerate(rows):
        t = TableReader(row, f"point[{i}]", source)
        speeds.append(t.positive("speed", "speed"))
        v = per_item_quantities(t.raw("voltages"), n, "voltage", t, "voltages")
        bad = [x for x in v if not 0.0 <= x <= act.max_voltage]
        if bad:
            raise t.error(
                "voltages",
                row["voltages"],
                f"voltages from 0 to max_voltage = {act.max_voltage:g} V",
            )
        volts.append(v)
        d = t.quantity("log_decrement", "dimensionless", default=None)
        dec.append(math.nan if d is None else d)
        p = t.quantity("power_loss", "power", default=None)
        loss.append(math.nan if p is None else p)
        h = t.quantity("min_film", "length", default=None)
        film.append(math.nan if h is None else h)
        t.done()
    w = np.array(speeds)
    if np.any(np.diff(w) <= 0.0):
        k = int(np.flatnonzero(np.diff(w) <= 0.0)[0])
        raise InputError(
            f"point[{k + 1}].speed = {w[k + 1] / RPM:.0f} rpm: expected speeds increasing "
            f"(point[{k}].speed = {w[k] / RPM:.0f} rpm)",
            source=source,
        )
    dec_a = np.array(dec)
    return SpeedSchedule(
        speeds=w,
        voltages=np.array(volts, dtype=float),
        slew_rate=float(slew),
        acceleration=accel,
        margin=margin,
        power_loss=None if np.all(np.isnan(loss)) else np.array(loss),
        log_decrement=None if np.all(np.isnan(dec_a)) else dec_a,
        min_film=None if np.all(np.isnan(film)) else np.array(film),
        limit_speed=limit,
        source=source,
    )
