"""``foilbearing identify``: the PZT parameters from measured stack data (Figs. 5b, 6b-c).

Fits the piezoelectric constant D33 (m/V) and the stack stiffness K_p (N/m) to a
no-load and a stiffness CSV (default: the bundled example measurements), and can
write them into a case file.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from foilbearing.cli.common import emit, print_fields
from foilbearing.errors import InputError

__all__ = ["cmd_identify", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``identify`` subcommand to the main parser's subparsers ``sub``."""
    ident = sub.add_parser("identify", help="identify PZT parameters from measured stack data")
    ident.add_argument("no_load", type=Path, nargs="?", help="no-load CSV (voltage_V, stackN_um)")
    ident.add_argument(
        "stiffness",
        type=Path,
        nargs="?",
        help="stiffness CSV (stack, voltage_V, load_N, displacement_um)",
    )
    ident.add_argument(
        "--contact-area",
        default="3.54e-4 m**2",
        help="stinger-foil contact area (default 3.54e-4 m**2)",
    )
    ident.add_argument(
        "--update",
        metavar="CASE.toml",
        type=Path,
        help="write the identified D33 and K_p into this case file",
    )
    ident.add_argument("--plot", metavar="DIR", type=Path, help="write Figs. 5b, 6b-c (PNG) to DIR")
    ident.add_argument("--json", action="store_true", help="print one JSON object")
    ident.set_defaults(func=cmd_identify)
    return ident


def cmd_identify(args: argparse.Namespace) -> int:
    """Run ``identify``; returns the exit code (0)."""
    from foilbearing import identification as ident
    from foilbearing.output.figures import write_identification_figures
    from foilbearing.units import parse_quantity

    example_no_load, example_stiffness = ident.example_measurements()
    no_load = args.no_load or example_no_load
    stiffness = args.stiffness or example_stiffness
    area = parse_quantity(args.contact_area, "area", field="--contact-area")
    if area <= 0.0:
        raise InputError(f"--contact-area {args.contact_area!r}: must be > 0")
    result = ident.identify(no_load, stiffness, area)
    out = dict(result.headline())
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_identification_figures(result, args.plot)]
    if args.update is not None:
        ident.update_case_file(args.update, result)
        out["updated_case"] = str(args.update)
    if args.json:
        emit(out)
    else:
        print_fields(out)
    return 0
