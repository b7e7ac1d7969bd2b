"""``foilbearing check``: how far to trust a case's numbers on its grid.

The headline readouts of the case on its grid and on grids refined by 2 (and 4 with
``--levels 3``), each with its estimated discretisation error
(:func:`foilbearing.check.grid_check`). Progress goes to stderr.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from foilbearing.cli.common import add_case_arg, add_subambient_arg, apply_subambient, emit
from foilbearing.cli.stability import DEFAULT_SCAN
from foilbearing.errors import InputError
from foilbearing.output.summary import grid_line

__all__ = ["cmd_check", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``check`` subcommand to the main parser's subparsers ``sub``."""
    p = sub.add_parser(
        "check",
        help="the case's readouts on its grid and on refined grids, with their "
        "discretisation errors",
    )
    add_case_arg(p)
    add_subambient_arg(p)
    p.add_argument(
        "--levels",
        type=int,
        default=2,
        help="grids: 2 (the case's and x2 in theta and z; default) or 3 (and x4, "
        "Richardson extrapolation; the x4 level can take minutes)",
    )
    p.add_argument(
        "--speed-range",
        default=None,
        help="onset scan START:STOP:STEP (default: the scan `stability` uses for the case: "
        "the study's onset scan for a bearing without actuators, "
        "5000rpm:150000rpm:5000rpm at the case's voltages for a C-GFB)",
    )
    p.add_argument(
        "--no-onset", action="store_true", help="leave out the linear onset and whirl frequency"
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_check)
    return p


def cmd_check(args: argparse.Namespace) -> int:
    """Run ``check``; returns the exit code (0)."""
    from foilbearing.case import load_case
    from foilbearing.check import grid_check
    from foilbearing.units import parse_speed_range

    case = apply_subambient(load_case(args.case), args.subambient)
    speeds = None
    if args.no_onset:
        if args.speed_range is not None:
            raise InputError("--speed-range is the onset's scan: drop it or --no-onset")
    elif args.speed_range is not None:
        speeds = parse_speed_range(args.speed_range, field="--speed-range")
        case.check_speeds(speeds, "--speed-range")
    elif case.actuators is None:
        from foilbearing.study.plan import study_plan

        speeds = study_plan(case).onset_scan()
    else:
        speeds = parse_speed_range(DEFAULT_SCAN, field="--speed-range")
    result = grid_check(
        case,
        args.levels,
        onset_speeds=speeds,
        progress=lambda line: print(line, file=sys.stderr, flush=True),
    )
    if args.json:
        emit(result.headline())
        return 0
    print(f"  {case.title or case.source}")
    print(f"  {grid_line(case)}; refined in θ and Z, the axial order and κ held")
    print(result.table())
    return 0
