"""``foilbearing bifurcation``: is the whirl past the onset bounded? The Hopf type and the
branch of limit cycles from the linear onset (:mod:`foilbearing.bifurcation.bearing`)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from foilbearing.cli.common import (
    add_case_arg,
    add_subambient_arg,
    apply_subambient,
    emit,
    print_fields,
)
from foilbearing.cli.reading import add_reading_args, apply_reading
from foilbearing.errors import InputError

__all__ = ["cmd_bifurcation", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``bifurcation`` subcommand to the main parser's subparsers ``sub``."""
    p = sub.add_parser(
        "bifurcation",
        help="Hopf type and limit-cycle branch from the linear onset (is the whirl bounded?)",
    )
    add_case_arg(p)
    p.add_argument("--voltage", default=None, help="one voltage for all actuators, e.g. 150V")
    p.add_argument(
        "--speed-range",
        default="5000rpm:150000rpm:2500rpm",
        help="onset scan START:STOP:STEP (default 5000rpm:150000rpm:2500rpm)",
    )
    p.add_argument("--steps", type=int, default=8, help="cycles after the two first (default 8)")
    add_subambient_arg(p)
    add_reading_args(p)
    p.add_argument("--plot", metavar="DIR", type=Path, help="write the branch's figure to DIR")
    p.add_argument(
        "--overlay",
        metavar="ORBIT.nc",
        type=Path,
        help="lay a speed-up's sub-synchronous amplitude (an `orbit --out` file) over the "
        "figure's amplitudes (needs --plot)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_bifurcation)
    return p


def cmd_bifurcation(args: argparse.Namespace) -> int:
    """Run ``bifurcation``; returns 0, or 3 when the shooting fails at the Hopf start."""
    from foilbearing.bifurcation import ShootingError
    from foilbearing.bifurcation.bearing import whirl_branch_headline
    from foilbearing.case import load_case
    from foilbearing.cli.common import refuse_without_actuators, voltage_list
    from foilbearing.units import parse_speed_range

    case = apply_reading(apply_subambient(load_case(args.case), args.subambient), args)
    if args.voltage is not None:
        refuse_without_actuators(case, "--voltage", args.voltage)
        volts = voltage_list(args.voltage, case)
        if len(volts) != 1:
            raise InputError(f"--voltage {args.voltage!r}: one voltage, e.g. 150V")
        case = case.with_voltages(volts[0])
    if args.steps < 0:
        raise InputError(f"--steps {args.steps}: a count >= 0")
    envelope = None
    if args.overlay is not None:
        if args.plot is None:
            raise InputError(f"--overlay {args.overlay}: needs --plot DIR (it draws on the figure)")
        from foilbearing.orbit.netcdf import read_subsync_envelope

        envelope = read_subsync_envelope(args.overlay)
    scan = list(parse_speed_range(args.speed_range, field="--speed-range"))
    try:
        out, wb = whirl_branch_headline(
            case, scan, args.steps, progress=None if args.json else _progress
        )
    except ShootingError as exc:
        print(
            f"foilbearing: solver failed: shooting did not converge ({exc}); try a finer "
            "orbit grid or the suction-retained film",
            file=sys.stderr,
        )
        return 3
    if wb is None:  # stable throughout, or unstable from the start: the linear readouts
        return _report(out, args)
    if args.plot is not None:
        from foilbearing.io import save_figure
        from foilbearing.output.plots.bifurcation import plot_whirl_branch

        args.plot.mkdir(parents=True, exist_ok=True)
        out["figure"] = str(
            save_figure(
                plot_whirl_branch(out, case.title, envelope), args.plot / "whirl_branch.png"
            )
        )
    return _report(out, args)


def _progress(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


def _report(out: dict[str, Any], args: argparse.Namespace) -> int:
    if args.json:
        emit(out)
    else:
        print_fields(out)
    return 0
