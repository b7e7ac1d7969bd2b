"""A rotor orbit's file stands alone: ``rotor --resume`` continues the recorded run and
refuses what would shape another one, in one line (exit 2)."""

from __future__ import annotations

from pathlib import Path

import pytest

from foilbearing.cli.main import main


@pytest.mark.parametrize(
    "extra",
    [
        ["--orbit", "40000rpm:0.01s"],
        ["--unbalance", "1:1g*mm"],
        ["--shaft-modes", "8"],
        ["--speed-range", "30000rpm:40000rpm:5000rpm"],
        ["--modes", "4"],
    ],
    ids=lambda e: e[0],
)
def test_rotor_resume_refuses_the_options_that_would_shape_another_run(
    extra: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Before, ``rotor --resume`` replaced these by the recorded ones without a word (an
    option equal to its default, as ``--shaft-modes 8``, is refused too: it was given)."""
    pytest.importorskip("ross")
    assert main(["rotor", "--resume", str(tmp_path / "run.nc"), *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert f"start a new run to change {extra[0]}" in err, err
