"""``foilbearing optimize``: one voltage per actuator, beside the paper's equal voltages.

``foilbearing optimize [CASE] --objective onset|drag [--speed 50000rpm]
[--max-evaluations N] [--json]`` searches the actuator voltages that maximise
the linear onset speed of instability (``onset``) or minimise the drag torque at
``--speed`` (``drag``, with ``--load`` and ``--min-film``), and prints the
optimum beside the best of the paper's equal-voltage choices (0/50/100/150 V).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from foilbearing.cli.common import add_case_arg, command_help, emit, positive_quantity
from foilbearing.errors import InputError
from foilbearing.units import speed_text

__all__ = ["cmd_optimize", "register"]

OBJECTIVES = ("onset", "drag")


def register(subparsers: Any) -> argparse.ArgumentParser:
    """Add the ``optimize`` subcommand to ``subparsers`` (from ``add_subparsers``)."""
    p = subparsers.add_parser(
        "optimize",
        help="voltages per actuator: maximise the onset speed or minimise the drag",
        description=command_help(__doc__),
    )
    add_case_arg(p)
    p.add_argument(
        "--objective", default="onset", help="onset (maximise the onset speed) or drag (minimise)"
    )
    p.add_argument("--speed", default=None, help="rotor speed of the drag objective, e.g. 50000rpm")
    p.add_argument("--load", default=None, help="static load of the drag objective (default: case)")
    p.add_argument(
        "--min-film",
        type=float,
        default=0.05,
        metavar="FRACTION",
        help="drag objective: least minimum film, in units of C (default 0.05)",
    )
    p.add_argument(
        "--speed-range",
        default="5000rpm:150000rpm:5000rpm",
        help="onset objective: scan START:STOP:STEP (default 5000rpm:150000rpm:5000rpm)",
    )
    p.add_argument(
        "--max-evaluations",
        type=int,
        default=None,
        metavar="N",
        help="cap on the evaluations (default 60 for onset, 120 for drag)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_optimize)
    return p


def cmd_optimize(args: argparse.Namespace) -> int:
    """Run the ``optimize`` subcommand; returns the exit code.

    Raises
    ------
    InputError
        Unknown objective, ``--speed`` missing for ``drag`` (or given for
        ``onset``), a bad number, or a case without actuators; nothing is
        computed then.
    """
    from foilbearing.case import load_case
    from foilbearing.design.voltages import PAPER_VOLTAGES, maximize_onset, minimize_drag
    from foilbearing.units import parse_speed_range

    if args.objective not in OBJECTIVES:
        raise InputError(f"--objective {args.objective!r}: allowed onset or drag")
    if args.max_evaluations is not None and args.max_evaluations < len(PAPER_VOLTAGES):
        raise InputError(
            f"--max-evaluations {args.max_evaluations}: expected at least {len(PAPER_VOLTAGES)} "
            "(the paper's equal voltages are evaluated first)"
        )
    case = load_case(args.case)
    if case.actuators is None:
        raise InputError("optimize needs a case with [actuators]: there are no voltages to choose")
    progress = None if args.json else (lambda line: print(line, file=sys.stderr, flush=True))
    budget: dict[str, Any] = (
        {} if args.max_evaluations is None else {"max_evaluations": args.max_evaluations}
    )
    if args.objective == "onset":
        if args.speed is not None or args.load is not None:
            raise InputError(
                "--speed and --load belong to --objective drag; the onset objective scans "
                "--speed-range"
            )
        speeds = parse_speed_range(args.speed_range, field="--speed-range")
        result = maximize_onset(case, speeds=speeds, progress=progress, **budget)
    else:
        if args.speed is None:
            raise InputError("--objective drag needs --speed, e.g. --speed 50000rpm")
        speed = positive_quantity(args.speed, "speed", "--speed", "a speed")
        load = (
            None
            if args.load is None
            else positive_quantity(args.load, "force", "--load", "a load", zero=True)
        )
        result = minimize_drag(
            case,
            speed,
            load=load,
            min_film_fraction=args.min_film,
            progress=progress,
            **budget,
        )
    head = result.headline()
    if args.json:
        emit(head)
        return 0
    if result.objective == "onset":
        show = f"onset {speed_text(head['onset_speed_rpm'])}"
        base = f"onset {speed_text(head['baseline_onset_speed_rpm'])}"
    else:
        show = (
            f"drag {head['drag_torque_Nm'] * 1e3:.4f} mN·m, min film {head['min_film_um']:.1f} um"
        )
        base = f"drag {head['baseline_drag_torque_Nm'] * 1e3:.4f} mN·m"
    volts = "/".join(f"{v:.1f}" for v in result.voltages)
    base_volts = "/".join(f"{v:.1f}" for v in result.baseline_voltages)
    print(f"optimum:        {volts} V -> {show}")
    print(f"paper (equal):  {base_volts} V -> {base}")
    print(
        f"improvement {head['improvement_percent']:+.2f} % after {result.evaluations} "
        f"evaluations; {result.message}"
    )
    return 0
