"""Pieces shared by the subcommands of the ``foilbearing`` command."""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_case_arg"]


def add_case_arg(p: argparse.ArgumentParser) -> None:
    """The optional positional CASE argument (default: the built-in case, see ``load_case``)."""
    p.add_argument(
        "case",
        nargs="?",
        type=Path,
        default=None,
        help="case file (TOML); default: the paper's C-GFB",
    )
