"""``foilbearing schedule``: the least-drag actuator voltages that keep the rotor stable.

``foilbearing schedule [CASE] [--speed-range 10000rpm:90000rpm[:STEP]] [--margin 0.1]
[--slew-rate 300V/s] [--acceleration 500rad/s**2] [--out SCHEDULE.toml] [--plot DIR]
[--json]`` chooses, at each speed, the voltage of each actuator that minimises the
power loss with a log decrement of at least the margin (the most stable voltages
where none meets it), smooths it for the amplifier's slew rate and reports the
speed above which no voltage keeps the rotor stable. ``foilbearing orbit
--voltage-schedule SCHEDULE.toml`` runs it.
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from foilbearing.cli.common import (
    add_case_arg,
    add_overwrite_arg,
    claim_output,
    command_help,
    emit,
    guard_outputs,
)
from foilbearing.errors import InputError

__all__ = ["cmd_schedule", "register", "schedule_speeds"]

DEFAULT_POINTS = 17  # speeds of a START:STOP range without a step


def register(subparsers: Any) -> argparse.ArgumentParser:
    """Add the ``schedule`` subcommand to ``subparsers`` (from ``add_subparsers``)."""
    p = subparsers.add_parser(
        "schedule",
        help="voltage schedule: least-drag voltages per speed with a stability margin",
        description=command_help(__doc__),
    )
    add_case_arg(p)
    p.add_argument(
        "--speed-range",
        default="10000rpm:90000rpm",
        help=f"START:STOP[:STEP] (default 10000rpm:90000rpm, {DEFAULT_POINTS} speeds without STEP)",
    )
    p.add_argument(
        "--margin",
        type=float,
        default=None,
        help="least log decrement of the least stable whirl mode (default 0.1)",
    )
    p.add_argument(
        "--slew-rate", default="300V/s", help="amplifier slew-rate limit (default 300V/s)"
    )
    p.add_argument(
        "--acceleration",
        default="500rad/s**2",
        help="speed-up rate the smoothness is set for (default the paper's 500rad/s**2)",
    )
    p.add_argument("--out", default=None, help="write the schedule file (TOML) here")
    add_overwrite_arg(p)
    p.add_argument("--plot", default=None, metavar="DIR", help="write the figure (PNG) to DIR")
    p.add_argument(
        "--grid-check",
        action="store_true",
        help="solve the schedule's points again on twice the cells in θ and Z: each log "
        "decrement's and power loss's grid error, and whether the margin still holds",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_schedule)
    return p


def schedule_speeds(text: str, field: str = "--speed-range") -> list[float]:
    """Speeds, rad/s, from START:STOP:STEP or START:STOP (then 17 evenly spaced)."""
    import numpy as np

    from foilbearing.units import parse_quantity, parse_speed_range

    parts = text.split(":")
    if len(parts) == 3:
        return parse_speed_range(text, field=field)
    if len(parts) != 2:
        raise InputError(f"{field} {text!r}: expected START:STOP or START:STOP:STEP")
    lo, hi = (parse_quantity(p, "speed", field=field) for p in parts)
    if not 0.0 < lo < hi:
        raise InputError(f"{field} {text!r}: need 0 < START < STOP")
    return [float(w) for w in np.linspace(lo, hi, DEFAULT_POINTS)]


@guard_outputs
def cmd_schedule(args: argparse.Namespace) -> int:
    """Run the ``schedule`` subcommand; returns the exit code.

    Raises
    ------
    InputError
        A bad speed range (or one beyond the case's ``operation.max_speed``), a
        negative margin, a bad slew rate or acceleration, a case without
        actuators; nothing is computed then.
    """
    from pathlib import Path

    from foilbearing.case import load_case
    from foilbearing.control.schedule_file import schedule_toml
    from foilbearing.design.schedule_search import (
        DEFAULT_MARGIN,
        check_speed_range,
        schedule_grid_check,
        voltage_schedule,
    )
    from foilbearing.io import save_figure
    from foilbearing.output.plots.schedule import plot_schedule
    from foilbearing.units import parse_quantity

    margin = DEFAULT_MARGIN if args.margin is None else args.margin
    if not (math.isfinite(margin) and margin >= 0.0):
        raise InputError(f"--margin {margin!r}: expected a log decrement >= 0 (e.g. 0.1)")
    slew = parse_quantity(args.slew_rate, "slew_rate", field="--slew-rate")
    accel = parse_quantity(
        args.acceleration.replace("s2", "s**2"), "angular_acceleration", field="--acceleration"
    )
    for name, value in (("--slew-rate", slew), ("--acceleration", accel)):
        if not value > 0.0:
            raise InputError(f"{name} {value!r}: expected a value > 0")
    case = load_case(args.case)
    if case.actuators is None:
        raise InputError("schedule needs a case with [actuators]: there are no voltages to choose")
    speeds = schedule_speeds(args.speed_range)
    check_speed_range(case, speeds)
    target = claim_output(args, args.out)
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    schedule = voltage_schedule(
        case, speeds, margin=margin, slew_rate=slew, acceleration=accel, progress=progress
    )
    head: dict[str, Any] = schedule.headline()
    if args.grid_check:
        head["grid_refined"] = schedule_grid_check(case, schedule, 2, progress)
    if target is not None and target.write_text(schedule_toml(schedule, case.title)):
        head["schedule_file"] = str(target.path)
    if args.plot is not None:
        angles = [math.degrees(a) for a in case.actuators.angles]
        path = save_figure(plot_schedule(schedule, angles), Path(args.plot) / "schedule.png")
        head["figures"] = [str(path)]
    if args.json:
        emit(head)
        return 0
    check = head.get("grid_refined")
    errors = check["errors"] if check else {}
    print(
        " speed (rpm)  voltages (V)              log dec"
        + ("  ± grid" if check else "")
        + "  power (W)  at 150 V (W)"
    )
    for k, w in enumerate(head["speeds_rpm"]):
        volts = "/".join(f"{v:6.1f}" for v in head["voltages_V"][k])
        dec, loss = head["log_decrement"][k], head["power_loss_W"][k]
        ref = head["power_loss_150V_W"][k]
        err = errors["log_decrement"][k] if check else None
        grid = "" if not check else f"  {'-' if err is None else format(abs(err), '.3f'):>6}"
        print(
            f" {w:10.0f}  {volts:<24}  {dec:+7.3f}{grid}  {loss:9.3f}  "
            + (f"{ref:12.3f}" if ref is not None else f"{'-':>12}")
        )
    limit = head["limit_speed_rpm"]
    print(
        "stable to the top speed with the schedule"
        if limit is None
        else f"limit speed {limit:.0f} rpm: above it no voltage keeps the rotor stable"
    )
    if check:
        g, f = check["grid"], check["refined_grid"]
        below = check["below_margin_rpm"]
        fine_limit = check["limit_speed_rpm"]
        print(
            f"grid check: the schedule's points on {f[0]} x {f[1]} (searched on {g[0]} x {g[1]}): "
            + (
                "the margin missed at " + ", ".join(f"{w:.0f}" for w in below) + " rpm"
                if below
                else "every speed that met the margin still meets it"
            )
            + (
                ""
                if fine_limit is None
                else f"; limit speed {fine_limit:.0f} rpm on the finer grid"
            )
        )
    for key in ("schedule_file", "figures"):
        if key in head:
            print(f"  {key}: {head[key]}")
    return 0
