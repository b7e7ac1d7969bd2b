"""Pieces shared by the subcommands of the ``foilbearing`` command."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from foilbearing.case import Case

__all__ = ["add_case_arg", "add_subambient_arg", "apply_subambient"]


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
