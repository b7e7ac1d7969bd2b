"""Outputs that cannot be lost or clobbered, strict JSON, and a run's edges on the command line.

``--out`` is checked and reserved before any work starts (a folder that cannot be written,
an existing file without ``--overwrite``, an output another run holds: one line, exit 2);
a write the storage refuses at the end leaves the result on stdout, one line on stderr,
exit 3, and no ``.part`` file.
"""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from foilbearing.cli.common import strict_json
from foilbearing.cli.main import main
from foilbearing.io import lock_path, reserve


@pytest.fixture(scope="module")
def coarse_case(write_case) -> Path:
    return write_case("coarse", n_theta=32, n_z=4)


def _strict(text: str) -> dict[str, Any]:
    """``json.loads`` that refuses NaN and Infinity, as a strict JSON reader does."""

    def refuse(token: str) -> Any:
        raise ValueError(f"{token} is not JSON")

    return json.loads(text, parse_constant=refuse)


def _film(case: Path, out: Path, *extra: str, ecc: str = "0.3,0.2") -> list[str]:
    """``static`` at a given journal position (no equilibrium search: fast) into ``out``."""
    return ["static", str(case), "--eccentricity", ecc, "--out", str(out), "--json", *extra]


def _no_solve(monkeypatch: pytest.MonkeyPatch) -> None:
    def solved(*args: Any, **kwargs: Any) -> Any:
        raise AssertionError("work started before the output was checked")

    import foilbearing.orbit
    import foilbearing.static

    for name in ("film_at_position", "solve_equilibrium"):
        monkeypatch.setattr(foilbearing.static, name, solved)
    monkeypatch.setattr(foilbearing.orbit, "simulate", solved)


def _read_only(folder: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Make ``folder`` read-only; where the permission does not bind (root), the kernel's
    refusal of a file created there is simulated."""
    folder.chmod(0o555)
    if os.access(folder, os.W_OK):
        real_open = os.open

        def refusing(path: Any, flags: int, *args: Any, **kwargs: Any) -> int:
            if Path(path).parent == folder and flags & os.O_CREAT:
                raise PermissionError(errno.EACCES, "Permission denied", str(path))
            return real_open(path, flags, *args, **kwargs)

        monkeypatch.setattr(os, "open", refusing)


@pytest.mark.parametrize("command", ["static", "orbit"])
def test_a_read_only_out_folder_is_one_line_before_any_work(
    command: str, coarse_case: Path, tmp_path: Path, monkeypatch, capsys
) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    _no_solve(monkeypatch)
    _read_only(folder, monkeypatch)
    out = folder / "run.nc"
    argv = (
        _film(coarse_case, out)
        if command == "static"
        else ["orbit", str(coarse_case), "--speed", "12000rpm", "--duration", "0.01s", "--json"]
    )
    argv += [] if command == "static" else ["--out", str(out)]
    try:
        assert main(argv) == 2  # and no solve was called (_no_solve)
    finally:
        folder.chmod(0o755)
    captured = capsys.readouterr()
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and str(out) in err[0] and "cannot write" in err[0], err
    assert captured.out == ""
    assert list(folder.iterdir()) == []


def test_an_existing_out_is_refused_unless_overwrite(
    coarse_case: Path, tmp_path: Path, capsys
) -> None:
    import xarray as xr

    out = tmp_path / "film.nc"
    assert main(_film(coarse_case, out)) == 0
    before = out.read_bytes()
    capsys.readouterr()
    assert main(_film(coarse_case, out, ecc="0.1,0.0")) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and str(out) in err[0] and "--overwrite" in err[0], err
    assert out.read_bytes() == before  # untouched
    assert main(_film(coarse_case, out, "--overwrite", ecc="0.1,0.0")) == 0
    assert float(xr.load_dataset(out).eps_X) == pytest.approx(0.1)  # replaced
    assert not lock_path(out).exists()
    assert not list(tmp_path.glob(".*.part"))


def test_a_second_run_on_one_out_refuses_and_the_first_is_intact(
    coarse_case: Path, tmp_path: Path, capsys
) -> None:
    """Another process holds the output (it reserved it at its start): this run refuses in
    one line and touches nothing; the holder then writes its result whole."""
    out = tmp_path / "film.nc"
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import sys; from foilbearing.io import reserve, write_text; r = reserve(sys.argv[1]);"
            " print('held', flush=True); sys.stdin.read(); write_text(sys.argv[1], 'first');"
            " r.release()",
            str(out),
        ],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)},
    )
    try:
        assert holder.stdout is not None and holder.stdout.readline().strip() == "held"
        assert main(_film(coarse_case, out, "--overwrite")) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "being written by another run" in err[0] and str(out) in err[0]
    finally:
        holder.communicate("", timeout=30)
    assert holder.returncode == 0
    assert out.read_text() == "first" and not lock_path(out).exists()


def test_a_lock_left_by_a_dead_run_is_taken_over(coarse_case: Path, tmp_path: Path) -> None:
    out = tmp_path / "film.nc"
    lock_path(out).write_text("pid 999999 on a killed run\n")  # no process holds it
    assert main(_film(coarse_case, out)) == 0
    assert out.stat().st_size > 0 and not lock_path(out).exists()
    held = reserve(out)  # and the reservation is exclusive in one process too
    try:
        assert main(_film(coarse_case, out, "--overwrite")) == 2
    finally:
        held.release()


def _full_disk(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every NetCDF write starts its file, then the disk is full."""
    import xarray as xr

    def full(self: Any, path: Any = None, *args: Any, **kwargs: Any) -> None:
        Path(path).write_bytes(b"CDF\x01")
        raise OSError(errno.ENOSPC, "No space left on device", str(path))

    monkeypatch.setattr(xr.Dataset, "to_netcdf", full)


def test_a_write_failure_at_the_end_still_prints_the_result(
    coarse_case: Path, tmp_path: Path, monkeypatch, capsys
) -> None:
    out = tmp_path / "film.nc"
    _full_disk(monkeypatch)
    assert main(_film(coarse_case, out)) == 3
    captured = capsys.readouterr()
    result = _strict(captured.out)
    assert result["eccentricity"] == pytest.approx((0.3**2 + 0.2**2) ** 0.5)
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and str(out) in err[0] and "No space left on device" in err[0], err
    assert list(tmp_path.iterdir()) == []  # no result, no .part, no lock


def test_an_orbit_whose_save_fails_prints_its_result_and_keeps_its_checkpoint(
    coarse_case: Path, tmp_path: Path, monkeypatch, capsys
) -> None:
    out = tmp_path / "run.nc"
    run = ["orbit", str(coarse_case), "--speed", "12000rpm", "--duration", "0.02s", "--json"]
    assert main([*run, "--stop-time", "0.01s", "--out", str(out)]) == 0
    checkpoint = out.read_bytes()
    capsys.readouterr()
    _full_disk(monkeypatch)
    assert main(["orbit", "--resume", str(out), "--json"]) == 3
    captured = capsys.readouterr()
    result = _strict(captured.out)
    assert result["status"] == "completed" and "netcdf" not in result
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and "No space left on device" in err[0] and "unchanged" in err[0]
    assert out.read_bytes() == checkpoint  # the stopped run can still be resumed
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc"]


def test_json_output_is_strict(coarse_case: Path, capsys) -> None:
    """The centred journal has no force to measure a residual against: ``null``, not NaN."""
    assert main(["static", str(coarse_case), "--eccentricity", "0,0", "--json"]) == 0
    result = _strict(capsys.readouterr().out)
    assert result["eccentricity"] == 0.0 and result["force_residual"] is None
    import numpy as np

    text = strict_json({"a": np.array([1.0, np.nan]), "b": float("inf"), "c": np.float32(2)})
    assert _strict(text) == {"a": [1.0, None], "b": None, "c": 2.0}


def test_an_orbit_in_contact_at_its_first_sample_reports_contact(write_case, capsys) -> None:
    """An imbalance of 20 kg·mm at 12000 rpm (an imbalance force of 32 kN against a 9 N load) closes the
    film within the first steps, before a second sample: the run's status and advice, and
    the divergence at the run's speed, not an internal error."""
    case = write_case(
        "shaken", n_theta=32, n_z=4, edit=lambda d: d["rotor"].update(imbalance="20000 g*mm")
    )
    argv = ["orbit", str(case), "--speed", "12000rpm", "--duration", "0.05s", "--json"]
    assert main(argv) == 0
    result = _strict(capsys.readouterr().out)
    assert result["status"] == "contact" and "touched" in result["advice"]
    assert result["divergence_speed_rpm"] == pytest.approx(12000.0)


def test_a_write_the_disk_refuses_inside_a_command_is_one_line(tmp_path: Path, capsys) -> None:
    """A results folder's point or manifest that cannot be written (sweep, uncertainty,
    study write them deep in their runners) ends the command with one line naming the
    folder, exit 3, and the reservation released; other errors are not hidden."""
    import argparse

    from foilbearing.cli.common import claim_output, guard_outputs

    folder = tmp_path / "res.d"

    @guard_outputs
    def command(args: argparse.Namespace) -> int:
        claim_output(args, folder, may_exist=True)
        raise OSError(errno.ENOSPC, "No space left on device")

    assert command(argparse.Namespace()) == 3
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"in {folder}" in err[0] and "No space left" in err[0], err
    assert not lock_path(folder).exists()

    @guard_outputs
    def broken(args: argparse.Namespace) -> int:
        raise FileNotFoundError(errno.ENOENT, "No such file or directory", "missing.toml")

    with pytest.raises(FileNotFoundError):
        broken(argparse.Namespace())


def _commands_with_plot() -> dict[str, list[str]]:
    """Each subcommand that takes ``--plot``, with a stand-in for each positional it needs
    (a file that does not exist: the --plot check must come before it is read)."""
    import argparse

    from foilbearing.cli.main import _parser

    sub = next(a for a in _parser()._actions if isinstance(a, argparse._SubParsersAction))
    found = {}
    for name, parser in sub.choices.items():
        options = {s for a in parser._actions for s in a.option_strings}
        if "--plot" in options:
            needed = [a for a in parser._actions if not a.option_strings and a.nargs is None]
            found[name] = ["missing.toml"] * len(needed)
    return found


PLOT_COMMANDS = _commands_with_plot()


def test_every_command_with_plot_is_checked() -> None:
    assert {"static", "orbit", "rotor", "uncertainty", "bifurcation"} <= set(PLOT_COMMANDS)


@pytest.mark.parametrize("command", list(PLOT_COMMANDS))
def test_a_file_in_place_of_the_plot_folder_is_one_line_before_any_work(
    command: str, tmp_path: Path, capsys
) -> None:
    """``--plot DIR`` with a file at DIR, or DIR under a file: exit 2 and one line naming
    --plot, before the case (a missing file here) is read; before, the whole analysis ran
    and then ended in a traceback from the figure's writer."""
    blocker = tmp_path / "figs"
    blocker.write_text("not a folder", encoding="utf-8")
    for plot, words in ((blocker, "is a file"), (blocker / "sub", f"is under {blocker}")):
        argv = [command, *PLOT_COMMANDS[command], "--plot", str(plot)]
        assert main(argv) == 2, argv
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and f"--plot {plot} {words}" in err[0], err


@pytest.mark.parametrize("command", ["static", "orbit"])
def test_a_read_only_plot_folder_is_one_line_before_any_work(
    command: str, coarse_case: Path, tmp_path: Path, monkeypatch, capsys
) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    _no_solve(monkeypatch)
    _read_only(folder, monkeypatch)
    argv = [command, str(coarse_case), "--plot", str(folder / "figs")]
    argv += ["--eccentricity", "0.3,0.2"] if command == "static" else ["--speed", "12000rpm"]
    try:
        assert main(argv) == 2  # and no solve was called (_no_solve)
    finally:
        folder.chmod(0o755)
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"--plot {folder / 'figs'}: cannot write figures in" in err[0], err
    assert list(folder.iterdir()) == []
