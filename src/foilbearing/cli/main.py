"""The ``foilbearing`` command: a thin layer over the library.

Every subcommand that computes something takes ``--json`` and then prints its
headline results as one JSON object on stdout, keys named with their units.
Bad input ends with a one-line error on stderr and exit code 2, never a
traceback; a solver failure with exit code 3.

This module is the entry point and registers the subcommands, each in its own
module of :mod:`foilbearing.cli` (``register`` adds its parser, ``cmd_*`` runs
it); those import the numerics only when their subcommand runs.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from foilbearing.cli import (
    case,
    coefficients,
    identify,
    optimize,
    orbit,
    schedule,
    stability,
    static,
    structure,
    study,
    sweep,
    uncertainty,
)
from foilbearing.cli.common import parse_list
from foilbearing.errors import InputError, SolverError

__all__ = ["main", "parse_list"]


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code."""
    parser = _parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        return int(args.func(args) or 0)
    except InputError as exc:
        print(f"foilbearing: error: {exc}", file=sys.stderr)
        return 2
    except SolverError as exc:
        print(f"foilbearing: solver failed: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("foilbearing: interrupted", file=sys.stderr)
        return 130


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="foilbearing",
        description="Gas foil bearings with piezoelectric preload control (C-GFB).",
    )
    sub = p.add_subparsers(title="subcommands", metavar="COMMAND")
    # In the order of ``foilbearing --help``.
    for module in (
        case,
        structure,
        identify,
        static,
        coefficients,
        stability,
        orbit,
        sweep,
        uncertainty,
        optimize,
        schedule,
        study,
    ):
        module.register(sub)
    return p
