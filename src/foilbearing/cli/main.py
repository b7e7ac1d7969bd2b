"""The ``foilbearing`` command: a thin layer over the library.

Every subcommand that computes something takes ``--json`` and then prints its
headline results as one JSON object on stdout, keys named with their units.
Bad input ends with a one-line error on stderr and exit code 2, never a
traceback; a solver failure with exit code 3. A reader that closes stdout early
(``foilbearing case show --json | head -2``) ends the command quietly, with
exit code 141.

This module is the entry point and registers the subcommands, each in its own
module of :mod:`foilbearing.cli` (``register`` adds its parser, ``cmd_*`` runs
it); those import the numerics only when their subcommand runs.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence

from foilbearing.cli import (
    bifurcation,
    case,
    check,
    coefficients,
    identify,
    optimize,
    orbit,
    rotor,
    schedule,
    stability,
    static,
    structure,
    study,
    sweep,
    uncertainty,
)
from foilbearing.cli.common import attach_negative_values, check_plot_folder, parse_list
from foilbearing.errors import InputError, SolverError

__all__ = ["main", "parse_list"]


#: Exit code when stdout's reader went away: 128 + SIGPIPE (13), what a shell reports for a
#: Unix tool killed by SIGPIPE (``yes | head``), so a pipeline's status tells "reader
#: left early" apart from success (0) and from our errors (2, 3), as 130 = 128 + SIGINT does
#: for an interrupt. (Python ignores SIGPIPE, so the write raises BrokenPipeError instead.)
EXIT_BROKEN_PIPE = 141


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code.

    A closed stdout (``BrokenPipeError``, wherever the command writes) ends it
    quietly with :data:`EXIT_BROKEN_PIPE`, as the Python documentation advises
    (``signal`` module, "Note on SIGPIPE"): stdout is pointed at ``os.devnull``
    so that the interpreter's last flush at exit cannot fail again.
    """
    try:
        try:
            code = _run(argv)
        finally:  # also after --help's SystemExit
            sys.stdout.flush()  # a write still buffered fails here, not at exit
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
        return EXIT_BROKEN_PIPE
    return code


def _run(argv: Sequence[str] | None) -> int:
    parser = _parser()
    args = parser.parse_args(attach_negative_values(sys.argv[1:] if argv is None else argv))
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        if getattr(args, "plot", None) is not None:  # before any work: figures come last
            check_plot_folder(args.plot)
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
        epilog="Outputs are checked before any work starts: --out must be writable and new "
        "(--overwrite replaces it; another run's output is refused), and --plot DIR must be "
        "a folder that can be written (made if missing). Exit codes: 0 done, 2 bad input "
        "(one line naming it), 3 a solve or a write that failed.",
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
        bifurcation,
        sweep,
        uncertainty,
        optimize,
        schedule,
        rotor,
        study,
        check,
    ):
        module.register(sub)
    return p
