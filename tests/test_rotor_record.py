"""A rotor orbit's file stands alone: it records the rotor and both bearing cases as data
with their sha256, ``rotor --resume`` rebuilds the run from it alone (the rotor file and
case files deleted or edited since), a damaged record is a one-line error (exit 2), and
``rotor --resume`` refuses what would shape another run."""

from __future__ import annotations

import dataclasses
import json
import shutil
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import tomlkit
import xarray as xr

from foilbearing.case import default_case_path
from foilbearing.cli.main import main
from foilbearing.rotor import load_rotor
from foilbearing.rotor.record import RotorRecord, rotor_from_dict_record, rotor_to_dict

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
#: A short constant-speed run of the rigid rotor on two coarse C-GFBs (32 x 4).
RUN = ["--orbit", "40000rpm:0.005s", "--shaft-modes", "2", "--unbalance", "1:1g*mm"]
STOP = ["--stop-time", "0.0025s"]
CLEARANCE = 100e-6  # m, the built-in case's


def _bare(rotor: Any) -> Any:
    """``rotor`` with every ``source`` cleared (where it was read from is not data)."""
    sites = tuple(
        dataclasses.replace(b, case=dataclasses.replace(b.case, source=None))
        for b in rotor.bearings
    )
    return dataclasses.replace(rotor, source=None, bearings=sites)


@pytest.mark.parametrize("name", ["rotor_rigid_symmetric", "rotor_two_disk"])
def test_the_rotor_as_data_reads_back_to_the_same_rotor(name: str) -> None:
    """Every field, the bearing cases' voltages included, back to the bit; the sha256
    changes with any field."""
    rotor = load_rotor(EXAMPLES / f"{name}.toml")
    tables = rotor_to_dict(rotor)
    assert _bare(rotor_from_dict_record(json.loads(json.dumps(tables)))) == _bare(rotor)
    record = RotorRecord.of(rotor, str(EXAMPLES / f"{name}.toml"))
    assert record.file_sha256 == record.sha256
    tables["bearings"][1]["case"]["bearing"]["clearance"] = "9e-05 m"
    assert RotorRecord(tables).sha256 != record.sha256


def _files(folder: Path, clearance: str | None = None) -> Path:
    """The rigid symmetric rotor on two copies of the coarse C-GFB case file ``case.toml``
    (beside it, named relative to it), in ``folder``; returns the rotor file."""
    data = tomlkit.parse(default_case_path().read_text(encoding="utf-8"))
    data["grid"]["n_theta"], data["grid"]["n_z"] = 32, 4
    if clearance is not None:
        data["bearing"]["clearance"] = clearance
    (folder / "case.toml").write_text(tomlkit.dumps(data), encoding="utf-8")
    text = (EXAMPLES / "rotor_rigid_symmetric.toml").read_text(encoding="utf-8")
    rotor = folder / "rotor.toml"
    rotor.write_text(text.replace('case = "default"', 'case = "case.toml"'), encoding="utf-8")
    return rotor


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> dict[str, Any]:
    assert main([*argv, "--json"]) == 0, capsys.readouterr().err
    return dict(json.loads(capsys.readouterr().out)["orbit"])


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """The uninterrupted run (its file and JSON) and a run stopped halfway (its file)."""
    pytest.importorskip("ross")
    capsys = _Capture()
    folder = tmp_path_factory.mktemp("rotor")
    rotor = _files(folder)
    whole = folder / "whole.nc"
    assert main(["rotor", str(rotor), *RUN, "--out", str(whole), "--json"]) == 0
    printed = json.loads(capsys.out())["orbit"]
    part = folder / "part.nc"
    assert main(["rotor", str(rotor), *RUN, *STOP, "--out", str(part), "--json"]) == 0
    assert json.loads(capsys.out())["orbit"]["status"] == "stopped"
    capsys.close()
    return {"whole": xr.load_dataset(whole), "printed": printed, "part": part}


class _Capture:
    """stdout captured outside a test's capsys (a module fixture's runs)."""

    def __init__(self) -> None:
        import io
        import sys

        self._sys, self._buffer = sys, io.StringIO()
        self._old, sys.stdout = sys.stdout, self._buffer

    def out(self) -> str:
        text = self._buffer.getvalue()
        self._buffer.seek(0)
        self._buffer.truncate()
        return text

    def close(self) -> None:
        self._sys.stdout = self._old


def _copy_of_part(runs: dict[str, Any], folder: Path) -> Path:
    path = folder / "part.nc"
    shutil.copy(runs["part"], path)
    return path


def _same_as_whole(path: Path, runs: dict[str, Any], printed: dict[str, Any]) -> None:
    """The resumed run ends where the uninterrupted run ends (within 2e-5 C, the
    rotor's documented resume tolerance), with the whole run's steps and Newton
    iterations (before, the last part's only)."""
    a, whole = xr.load_dataset(path), runs["whole"]
    assert a.attrs["status"] == "completed" and a.time.size == whole.time.size
    assert float(np.abs(a.journal - whole.journal).max()) < 2e-5 * CLEARANCE
    assert abs(printed["steps"] - runs["printed"]["steps"]) <= 2
    assert a.attrs["steps"] == printed["steps"]
    ratio = a.attrs["newton_iterations"] / runs["whole"].attrs["newton_iterations"]
    assert abs(ratio - 1.0) < 0.02


def test_a_rotor_run_resumes_from_its_record_alone(
    runs: dict[str, Any], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The rotor file and both bearing cases' file deleted after the stop: the run is
    rebuilt from its record and ends as the uninterrupted run."""
    part = _copy_of_part(runs, tmp_path)
    folder = runs["part"].parent
    moved = tmp_path / "away"
    moved.mkdir()
    for name in ("rotor.toml", "case.toml"):
        shutil.move(folder / name, moved / name)
    try:
        printed = _run(["rotor", "--resume", str(part)], capsys)
    finally:
        for name in ("rotor.toml", "case.toml"):
            shutil.move(moved / name, folder / name)
    _same_as_whole(part, runs, printed)


def test_an_edited_bearing_case_file_is_one_notice_and_the_run_goes_on_as_recorded(
    runs: dict[str, Any], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The bearings' case file edited (clearance 100 -> 90 um) after the stop: one line
    on stderr names the field, and the run ends as the uninterrupted run on the
    recorded cases (before, the resumed run read the case files again: the edited case)."""
    part = _copy_of_part(runs, tmp_path)
    folder = runs["part"].parent
    original = (folder / "case.toml").read_text(encoding="utf-8")
    _files(folder, clearance="90 um")
    try:
        assert main(["rotor", "--resume", str(part), "--json"]) == 0
    finally:
        (folder / "case.toml").write_text(original, encoding="utf-8")
    captured = capsys.readouterr()
    notes = [ln for ln in captured.err.splitlines() if "note:" in ln]
    assert len(notes) == 1 and "has changed since the run started" in notes[0], notes
    assert "bearings.0.case.bearing.clearance" in notes[0] or "clearance" in notes[0]
    _same_as_whole(part, runs, json.loads(captured.out)["orbit"])


def _record_edit(edit: Callable[[dict[str, Any]], None]) -> Callable[[xr.Dataset], None]:
    def apply(ds: xr.Dataset) -> None:
        data = json.loads(ds.attrs["rotor_run"])
        edit(data)
        ds.attrs["rotor_run"] = json.dumps(data)

    return apply


def _set(name: str, value: float) -> Callable[[xr.Dataset], None]:
    def apply(ds: xr.Dataset) -> None:
        values = np.array(ds[name].values, float)
        values.flat[0] = value
        ds[name] = (ds[name].dims, values)

    return apply


def _shift_t(ds: xr.Dataset) -> None:
    ds["checkpoint_t"] = (ds["checkpoint_t"].dims, ds["checkpoint_t"].values + 1.0)


DAMAGE: dict[str, tuple[Callable[[xr.Dataset], None], str]] = {
    "cut record": (
        lambda ds: ds.attrs.update(rotor_run=ds.attrs["rotor_run"][:300]),
        "not valid JSON",
    ),
    "hash mismatch": (
        _record_edit(
            lambda d: d["rotor_record"]["tables"]["material"].update(density="7000.0 kg/m**3")
        ),
        "does not match its sha256",
    ),
    "option missing": (_record_edit(lambda d: d.pop("orbit")), "'orbit' missing"),
    "option mistyped": (_record_edit(lambda d: d.update(shaft_modes="two")), "shaft_modes"),
    "NaN state": (_set("checkpoint_y", np.nan), "checkpoint_y holds values that are not"),
    "unknown status": (lambda ds: ds.attrs.update(status="paused"), "status = 'paused'"),
    "checkpoint_t beyond the end": (_shift_t, "checkpoint_t = "),
    "infinite journal": (_set("journal", np.inf), "journal holds values that are not finite"),
}


@pytest.mark.parametrize("kind", list(DAMAGE))
def test_a_damaged_rotor_run_is_a_one_line_error(
    kind: str, runs: dict[str, Any], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Each damage of what ``rotor --resume`` reads: exit 2, one line naming the file and
    what is wrong, no traceback, nothing run (before: tracebacks, or a run on NaNs)."""
    damage, text = DAMAGE[kind]
    ds = xr.load_dataset(runs["part"])
    damage(ds)
    path = tmp_path / "damaged.nc"
    ds.to_netcdf(path)
    capsys.readouterr()
    assert main(["rotor", "--resume", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert str(path) in err and text in err, err
    assert "Traceback" not in err


def test_a_rotor_run_of_the_first_form_still_resumes(
    runs: dict[str, Any], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A file written before the record (the rotor file's text, the case files read
    again) resumes as it did, to the uninterrupted run."""
    ds = xr.load_dataset(runs["part"])
    data = json.loads(ds.attrs["rotor_run"])
    rotor_file = Path(data["rotor_file"])
    for key in ("format", "rotor_record"):
        del data[key]
    data["rotor_text"] = rotor_file.read_text(encoding="utf-8")
    ds.attrs["rotor_run"] = json.dumps(data)
    path = tmp_path / "old.nc"
    ds.to_netcdf(path)
    _same_as_whole(path, runs, _run(["rotor", "--resume", str(path)], capsys))


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
