"""The ``foilbearing sweep`` subcommand: a parameter sweep on Dask.

``foilbearing sweep SWEEP.toml [--out RESULT] [--scheduler ADDRESS]
[--workers N] [--dashboard] [--resume] [--assemble] [--json]`` runs every
point of the sweep file (``docs/sweep-format.md``) on a local Dask cluster
(one single-thread worker process per core, on 127.0.0.1; ``--dashboard``
prints its dashboard's address) or on an existing ``dask.distributed`` scheduler,
writes each finished point to ``RESULT.d/points/`` as it completes and the
assembled Dataset to ``RESULT.nc``. Exit code 0 when every point is ok, 3 when
some failed (they are recorded with their message) or are missing, 2 for bad input,
130 when interrupted (Ctrl-C: the finished points are kept for ``--resume``).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from foilbearing.cli.common import (
    add_dask_args,
    check_dask_args,
    claim_output,
    command_help,
    emit,
    guard_outputs,
)
from foilbearing.errors import InputError

__all__ = ["cmd_sweep", "register"]


def register(subparsers: Any) -> argparse.ArgumentParser:
    """Add the ``sweep`` subcommand to ``subparsers`` (from ``add_subparsers``)."""
    p = subparsers.add_parser(
        "sweep",
        help="parameter sweep over case fields, speed and voltages on Dask",
        description=command_help(__doc__),
    )
    p.add_argument("sweep_file", type=Path, metavar="SWEEP.toml", help="sweep file (TOML)")
    p.add_argument(
        "--out",
        type=Path,
        default=None,
        metavar="RESULT",
        help="writes RESULT.d/ (one file per point) and RESULT.nc "
        "(default: the sweep file's name, in the current folder)",
    )
    add_dask_args(p, "RESULT.d")
    p.add_argument(
        "--assemble",
        action="store_true",
        help="compute nothing: gather the finished points of RESULT.d into RESULT.nc",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_sweep)
    return p


@guard_outputs
def cmd_sweep(args: argparse.Namespace) -> int:
    """Run the ``sweep`` subcommand; returns the exit code (0 all ok, 3 some failed).

    Raises
    ------
    InputError
        Bad sweep file, case, point, option, or a results folder that cannot
        be used; nothing is computed then.
    """
    from foilbearing.sweep.runner import load_sweep, output_paths, run_sweep

    check_dask_args(args)
    spec = load_sweep(args.sweep_file)
    out = args.out if args.out is not None else Path(args.sweep_file.stem)
    folder, _ = output_paths(out)
    if args.assemble and not folder.is_dir():
        raise InputError(f"--assemble: no results folder {folder} (run the sweep first)")
    claim_output(args, folder, may_exist=True)  # its points say what is done (--resume)
    try:
        summary: dict[str, Any] = run_sweep(
            spec,
            out,
            scheduler=args.scheduler,
            n_workers=args.workers,
            dashboard=args.dashboard,
            resume=args.resume or args.assemble,
            compute=not args.assemble,
            progress=not args.json,
        )
    except KeyboardInterrupt:
        kept = len(list((folder / "points").glob("*.json")))
        print(
            f"foilbearing: interrupted: {kept} of {spec.n_points} points kept in {folder}; "
            "run again with --resume",
            file=sys.stderr,
        )
        return 130
    if args.json:
        emit(summary)
    else:
        print(
            f"{summary['n_points']} points: {summary['n_ok']} ok, {summary['n_failed']} failed, "
            f"{summary['n_missing']} missing ({summary['n_computed']} computed, "
            f"{summary['n_skipped']} already done) in {summary['wall_time_s']:.1f} s",
            file=sys.stderr,
        )
        print(f"points:  {summary['results_folder']}/points/")
        print(f"dataset: {summary['dataset']}")
    return 0 if summary["n_ok"] == summary["n_points"] else 3
