"""The identified stack parameters written into a case file, its comments and layout kept."""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import tomlkit
import tomlkit.exceptions
from tomlkit.items import Item

from foilbearing.errors import InputError
from foilbearing.identification.fits import Identification
from foilbearing.identification.stack_data import PathLike

__all__ = ["case_values", "update_case_file"]


def case_values(identification: Identification) -> dict[str, str]:
    """The case's ``[actuators]`` entries as quantity strings (5 significant figures)."""
    p, st = identification.no_load.pooled, identification.stiffness
    return {
        "d33_quadratic": f"{p.d33_1_um_per_V2:.5g} um/V**2",
        "d33_linear": f"{p.d33_2_um_per_V:.5g} um/V",
        "stack_stiffness": f"{st.mean_stiffness / 1e6:.5g}e6 N/m",
    }


def update_case_file(case_path: PathLike, identification: Identification) -> None:
    """Write d33_quadratic, d33_linear and stack_stiffness into the case's ``[actuators]``.

    The file is edited with tomlkit, so comments and layout are kept (an inline
    comment on a replaced key stays); it is written atomically (a temporary file
    in the same directory, then ``os.replace``).

    Raises
    ------
    InputError
        If the file cannot be read, is not valid TOML, or has no ``[actuators]`` table.
    """
    path, source = Path(case_path), str(case_path)
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            doc = tomlkit.parse(fh.read())
    except (OSError, UnicodeDecodeError, tomlkit.exceptions.ParseError) as exc:
        raise InputError(f"cannot read the case file as TOML ({exc})", source=source) from None
    table = doc.get("actuators")
    if not isinstance(table, dict):
        message = "no [actuators] table to receive d33_quadratic, d33_linear, stack_stiffness"
        raise InputError(message, source=source)
    for key, text in case_values(identification).items():
        new, old = tomlkit.string(text), table.get(key)
        if isinstance(old, Item):
            new.trivia.indent, new.trivia.comment = old.trivia.indent, old.trivia.comment
            new.trivia.comment_ws = old.trivia.comment_ws
        table[key] = new
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as fh:
            fh.write(doc.as_string())
            fh.flush()
            os.fsync(fh.fileno())
        shutil.copymode(path, tmp)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
