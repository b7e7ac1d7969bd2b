"""Shared fixtures: the default case file, edited, written where a test can read it."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import tomlkit

from foilbearing.case import default_case_path


@pytest.fixture(scope="session")
def write_case(tmp_path_factory: pytest.TempPathFactory) -> Callable[..., Path]:
    """``write_case(name, n_theta=, n_z=, edit=)``: the default case file on another grid
    and with ``edit(data)`` applied to its TOML document, in a fresh folder."""

    def write(
        name: str,
        *,
        n_theta: int | None = None,
        n_z: int | None = None,
        edit: Callable[[Any], None] | None = None,
    ) -> Path:
        data = tomlkit.parse(default_case_path().read_text(encoding="utf-8"))
        if n_theta is not None:
            data["grid"]["n_theta"] = n_theta
        if n_z is not None:
            data["grid"]["n_z"] = n_z
        if edit is not None:
            edit(data)
        path = tmp_path_factory.mktemp("cases") / f"{name}.toml"
        path.write_text(tomlkit.dumps(data), encoding="utf-8")
        return path

    return write
