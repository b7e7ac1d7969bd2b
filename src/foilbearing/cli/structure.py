"""``foilbearing structure``: the structure models (k_b, k_assy, preloads; Figs. 7-8).

Stiffness and preload of the foil structure at the given actuator voltages (V),
optionally the figures as PNG files.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from foilbearing.cli.common import add_case_arg, emit, voltage_list

__all__ = ["cmd_structure", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``structure`` subcommand to the main parser's subparsers ``sub``."""
    st = sub.add_parser("structure", help="structure models: k_b, k_assy, preloads; Figs. 7-8")
    add_case_arg(st)
    st.add_argument("--voltage", default="0,50,100,150V", help="voltages, e.g. 0,50,100,150V")
    st.add_argument("--plot", metavar="DIR", type=Path, help="write the figures (PNG) to DIR")
    st.add_argument("--json", action="store_true", help="print one JSON object")
    st.set_defaults(func=cmd_structure)
    return st


def cmd_structure(args: argparse.Namespace) -> int:
    """Run ``structure``; returns the exit code (0)."""
    from foilbearing.case import load_case
    from foilbearing.output.figures import write_structure_figures
    from foilbearing.output.summary import structure_summary

    case = load_case(args.case)
    voltages = voltage_list(args.voltage, case)
    out = structure_summary(case, voltages)
    if args.plot is not None:
        out["figures"] = [str(p) for p in write_structure_figures(case, args.plot)]
    if args.json:
        emit(out)
    else:
        for key, value in out.items():
            print(f"  {key:<20} {value}")
    return 0
