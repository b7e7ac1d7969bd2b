"""Pieces shared by the subcommands of the ``foilbearing`` command."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from foilbearing.case import Case

__all__ = [
    "add_case_arg",
    "add_dask_args",
    "add_subambient_arg",
    "apply_subambient",
    "check_dask_args",
    "emit",
    "parse_list",
]


def add_case_arg(p: argparse.ArgumentParser) -> None:
    """The optional positional CASE argument (default: the built-in case, see ``load_case``)."""
    p.add_argument(
        "case",
        nargs="?",
        type=Path,
        default=None,
        help="case file (TOML); default: the paper's C-GFB",
    )


def add_subambient_arg(p: argparse.ArgumentParser) -> None:
    """``--subambient lift-off|retained``: the film model where the pressure is sub-ambient."""
    p.add_argument(
        "--subambient",
        default=None,
        metavar="MODEL",
        help="film under a foil below ambient pressure: lift-off (the foil leaves the bumps, "
        "no suction; default for a foil bearing) or retained (suction held, for comparison); "
        "default: the case's [foil] subambient",
    )


def apply_subambient(case: Case, model: str | None) -> Case:
    """The case with ``--subambient`` applied (unchanged when the option is absent)."""
    return case if model is None else case.with_subambient(model)


def add_dask_args(p: argparse.ArgumentParser, what: str) -> None:
    """``--scheduler``, ``--workers`` and ``--resume``: where the points of ``what`` run."""
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        default=None,
        help="address of a running dask.distributed scheduler (default: a local cluster)",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        metavar="N",
        help="worker processes of the local cluster (default: one per core)",
    )
    p.add_argument("--resume", action="store_true", help=f"continue {what}, skip finished points")


def check_dask_args(args: argparse.Namespace) -> None:
    """One-line errors for ``--workers`` below 1 or given with ``--scheduler``."""
    from foilbearing.errors import InputError

    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers {args.workers}: expected at least 1")
    if args.workers is not None and args.scheduler is not None:
        raise InputError("--workers sets the local cluster's size; with --scheduler leave it out")


def parse_list(text: str, kind: str, field: str) -> list[float]:
    """Parse "0,50,100,150V" or "10000rpm,50000rpm" into SI floats.

    A unit written on the last item applies to bare numbers before it.
    """
    from foilbearing.errors import InputError
    from foilbearing.units import parse_quantity

    items = [s.strip() for s in text.split(",") if s.strip()]
    if not items:
        raise InputError(f"{field} = {text!r}: expected one or more values")
    last = items[-1]
    unit = last.lstrip("+-0123456789.eE ")
    out = []
    for item in items:
        bare = item.lstrip("+-").replace(".", "", 1).replace("e", "", 1).replace("E", "", 1)
        value = (
            f"{item} {unit}" if unit and bare.replace("-", "").replace("+", "").isdigit() else item
        )
        out.append(parse_quantity(value, kind, field=field))
    return out


def emit(obj: dict[str, Any]) -> None:
    """Print ``obj`` as one indented JSON object on stdout (arrays as lists, paths as text)."""
    print(json.dumps(obj, indent=2, default=_json_default))


def _json_default(x: Any) -> Any:
    if hasattr(x, "tolist"):
        return x.tolist()
    if isinstance(x, Path):
        return str(x)
    raise TypeError(f"not JSON serialisable: {type(x).__name__}")
