"""The ``foilbearing uncertainty`` subcommand: envelopes and sensitivity indices on Dask.

``foilbearing uncertainty [UQ.toml] [--samples N] [--estimator sobol|rbd_fast]
[--sampler sobol|lhs] [--scheduler ADDRESS] [--workers N] [--dashboard] [--resume] [--out DIR]
[--plot DIR] [--json]``
draws the sample of the uncertainty file (``docs/uncertainty.md``; default:
what the paper leaves open), evaluates every point on a local Dask cluster or an existing
scheduler, writes each finished point to ``DIR/points/`` as it completes, and
the percentiles and sensitivity indices to ``DIR/uncertainty.nc`` and
``DIR/uncertainty.json``. Exit code 0 when every point is ok, 3 when some
failed (recorded with their message), 2 for bad input.
"""

from __future__ import annotations

import argparse
import math
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

#: foilbearing.uncertainty.design's ESTIMATORS and SAMPLERS, spelt out: ``--help`` loads no SciPy.
ESTIMATORS = ("sobol", "rbd_fast")
SAMPLERS = ("sobol", "lhs")

__all__ = ["cmd_uncertainty", "register"]


def register(subparsers: Any) -> argparse.ArgumentParser:
    """Add the ``uncertainty`` subcommand to ``subparsers``."""
    p = subparsers.add_parser(
        "uncertainty",
        help="uncertainty envelopes and sensitivity indices of the predictions (Dask)",
        description=command_help(__doc__),
    )
    p.add_argument(
        "uq_file",
        type=Path,
        nargs="?",
        default=None,
        metavar="UQ.toml",
        help="uncertainty file (default: the built-in one, what the paper leaves open)",
    )
    p.add_argument(
        "--samples",
        type=int,
        default=None,
        metavar="N",
        help="model evaluations (default: the file's samples)",
    )
    p.add_argument(
        "--estimator",
        choices=ESTIMATORS,
        default=None,
        help="sensitivity indices: sobol (first order and total, Saltelli design; noise at "
        "8 base rows, usable at 36) or rbd_fast (first order, any sample; holds at 64 "
        "evaluations of an lhs sample); default: the file's estimator",
    )
    p.add_argument(
        "--sampler",
        choices=SAMPLERS,
        default=None,
        help="the unit sample: sobol (scrambled Sobol' sequence) or lhs (Latin hypercube; "
        "the one for rbd_fast); default: the file's sampler",
    )
    p.add_argument(
        "--out",
        type=Path,
        default=None,
        metavar="DIR",
        help="results folder (default: the file's name, in the current folder)",
    )
    add_dask_args(p, "DIR")
    p.add_argument(
        "--plot",
        type=Path,
        default=None,
        metavar="DIR",
        help="write the band and index figures (PNG) to DIR",
    )
    p.add_argument(
        "--grid-check",
        action="store_true",
        help="after the sample, solve the static and stability outputs at the centre of the "
        "inputs on the case's grid and on twice its cells: each output's grid error, printed "
        "beside its envelope (about 15 s on the built-in file)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=cmd_uncertainty)
    return p


@guard_outputs
def cmd_uncertainty(args: argparse.Namespace) -> int:
    """Run the ``uncertainty`` subcommand; returns the exit code (0 all ok, 3 some failed).

    Raises
    ------
    InputError
        Bad uncertainty file, case, sample count or results folder; nothing is
        computed then.
    """
    from foilbearing.output.figures import write_uncertainty_figures
    from foilbearing.uncertainty import load_uncertainty, result_paths, run_uncertainty

    check_dask_args(args)
    spec = load_uncertainty(
        args.uq_file, samples=args.samples, estimator=args.estimator, sampler=args.sampler
    )
    stem = args.uq_file.stem if args.uq_file is not None else "uncertainty_paper"
    out = args.out if args.out is not None else Path(stem)
    claim_output(args, out, may_exist=True)  # its points say what is done (--resume)
    if not args.json:
        print(
            f"{spec.n_points} points ({spec.estimator} estimator, {spec.sampler} sample, "
            f"{len(spec.inputs)} inputs) -> {out}/",
            file=sys.stderr,
        )
    ds, summary = run_uncertainty(
        spec,
        out,
        scheduler=args.scheduler,
        n_workers=args.workers,
        dashboard=args.dashboard,
        resume=args.resume,
        progress=not args.json,
        grid_check=2 if args.grid_check else 1,
    )
    figures: list[str] = []
    if args.plot is not None:
        figures = [str(p) for p in write_uncertainty_figures(ds, args.plot)]
    summary["figures"] = figures
    if args.json:
        emit(summary)
        return 0 if summary["n_ok"] == summary["n_points"] else 3
    print(
        f"{summary['n_points']} points: {summary['n_ok']} ok, {summary['n_failed']} failed, "
        f"{summary['n_missing']} missing in {summary['wall_time_s']:.1f} s",
        file=sys.stderr,
    )
    print(_table(summary))
    paths = result_paths(out)
    print(f"points:  {paths['points']}/")
    print(f"dataset: {paths['dataset']}")
    for f in figures:
        print(f"figure:  {f}")
    return 0 if summary["n_ok"] == summary["n_points"] else 3


def _fmt(x: float | None) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x:.4g}"


def _table(summary: dict[str, Any]) -> str:
    """Percentiles and the input with the largest index, one line per output.

    Indices are those of :func:`~foilbearing.uncertainty.summary_json`: in [0, 1],
    "–" where not estimable at the sample's size; the first line names the
    estimator and the size. With a grid check, each output's grid error at the centre of
    the inputs follows its percentiles.
    """
    check = summary.get("grid_check")
    errors = (check or {}).get("outputs") or {}
    head = f"{'output':<44} {'p5':>9} {'p50':>9} {'p95':>9}"
    lines = [f"indices: {summary['indices']['description']}; – where not estimable"]
    if check:
        g, f = check["grid"], check["refined_grid"]
        lines.append(
            f"grid error: each output at the inputs' centre on {g[0]} x {g[1]} against "
            f"{f[0]} x {f[1]} (the first less the second), a shift of the whole envelope"
        )
        head += f" {'grid err':>9}"
    lines.append(head + "  most influential (S1 / ST)")
    for name, o in summary["outputs"].items():
        s1 = {k: v for k, v in o.get("first_order", {}).items() if v is not None}
        st = {k: v for k, v in (o.get("total_order") or {}).items() if v is not None}
        ranked = st or s1
        top = max(ranked, key=lambda k: ranked[k]) if ranked else None
        infl = "–" if top is None else f"{top} ({_fmt(s1.get(top))} / {_fmt(st.get(top))})"
        line = f"{name:<44} {_fmt(o['p5']):>9} {_fmt(o['p50']):>9} {_fmt(o['p95']):>9}"
        if check:
            err = (errors.get(name) or {}).get("error")
            line += f" {'–' if err is None else format(err, '+.2g'):>9}"
        lines.append(line + f"  {infl}")
    return "\n".join(lines)
