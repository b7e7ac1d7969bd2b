"""``foilbearing case show [CASE] [--json]``: print a bearing case and its derived quantities.

The inputs of the case file (default: the paper's C-GFB), the bump stiffness k_b,
the assembly stiffness k_assy, the base preloads and the bearing number Λ, in
engineering units (``--json``: one object, keys named with their units).
"""

from __future__ import annotations

import argparse
from typing import Any

from foilbearing.cli.common import add_case_arg, emit

__all__ = ["cmd_case_show", "register"]


def register(sub: Any) -> argparse.ArgumentParser:
    """Add the ``case`` subcommand (with its ``show`` action) to the main parser's subparsers ``sub``."""
    case_p = sub.add_parser("case", help="show a bearing case and its derived quantities")
    case_sub = case_p.add_subparsers(title="case commands", metavar="ACTION")
    show = case_sub.add_parser("show", help="print the case: inputs, k_b, k_assy, base preloads, Λ")
    add_case_arg(show)
    show.add_argument("--json", action="store_true", help="print one JSON object")
    show.set_defaults(func=cmd_case_show)
    return case_p


def cmd_case_show(args: argparse.Namespace) -> int:
    """Run ``case show``: print the case and its derived quantities; returns 0."""
    from foilbearing.case import load_case
    from foilbearing.output.summary import case_summary, format_summary

    case = load_case(args.case)
    summary = case_summary(case)
    if args.json:
        emit(summary)
    else:
        print(f"Case: {case.title or case.source}")
        print(format_summary(summary))
    return 0
