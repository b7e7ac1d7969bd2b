"""An orbit file stands alone: it records its whole case, resumes on it whatever the case file
holds now, and a damaged file is a one-line error naming it (exit 2), never a traceback or a
silently wrong run."""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

from foilbearing.case import default_case, load_case
from foilbearing.cli.main import main
from foilbearing.constants import RPM
from foilbearing.control import constant_speed, linear_ramp
from foilbearing.orbit import RunSpec, simulate
from foilbearing.orbit.netcdf import load_orbit, to_netcdf

#: A coarse, short run: 4 revolutions at 12 krpm on 32 x 4, stopped after 2.
RUN = ["--speed", "12000rpm", "--duration", "0.02s", "--steps-per-rev", "16"]
STOP = ["--stop-time", "0.01s"]


@pytest.fixture(scope="module")
def whole(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    """The uninterrupted run of the coarse case."""
    folder = tmp_path_factory.mktemp("whole")
    case = _coarse_case(folder)
    out = folder / "whole.nc"
    assert main(["orbit", str(case), *RUN, "--out", str(out)]) == 0
    return xr.load_dataset(out)


def _coarse_case(folder: Path, edit: Callable[[Any], None] | None = None) -> Path:
    import tomlkit

    from foilbearing.case import default_case_path

    data = tomlkit.parse(default_case_path().read_text(encoding="utf-8"))
    data["grid"]["n_theta"], data["grid"]["n_z"] = 32, 4
    if edit is not None:
        edit(data)
    path = folder / "coarse.toml"
    path.write_text(tomlkit.dumps(data), encoding="utf-8")
    return path


def _stopped_run(folder: Path) -> tuple[Path, Path]:
    """(case file, orbit file) of the coarse run stopped halfway, in ``folder``."""
    case = _coarse_case(folder)
    part = folder / "part.nc"
    assert main(["orbit", str(case), *RUN, *STOP, "--out", str(part)]) == 0
    assert xr.load_dataset(part).attrs["status"] == "stopped"
    return case, part


class _Killed(BaseException):
    """The process's end mid-run: nothing after it is written (as SIGKILL)."""


def _killed_run(folder: Path, after: int = 30) -> tuple[Path, Path]:
    """(case file, orbit file) of the coarse run killed after ``after`` steps.

    As ``foilbearing orbit --out`` does, the run writes its checkpoint (atomically) with
    its specification; here after every step, and the process ends after the ``after``-th
    without another word: the file holds what a SIGKILL leaves, a "running" checkpoint
    at an ordinary step (``test_cli_orbit`` kills a process outright; this is its cost-free
    twin)."""
    from foilbearing.cli.main import _parser
    from foilbearing.cli.orbit import run_spec_from_args
    from foilbearing.io import write_with

    case = _coarse_case(folder)
    spec = run_spec_from_args(_parser().parse_args(["orbit", str(case), *RUN]))
    built = spec.build()
    part = folder / "part.nc"
    saved = [0]

    def save(result: Any) -> None:
        write_with(part, lambda tmp: to_netcdf(result, spec, tmp))
        saved[0] += 1
        if saved[0] == after:
            raise _Killed

    with pytest.raises(_Killed):
        simulate(
            built.case, built.profile, None, built.settings, checkpoint=save, checkpoint_every=0.0
        )
    assert xr.load_dataset(part).attrs["status"] == "running"
    return case, part


def test_a_lobe_held_run_records_its_reading_and_resumes_under_it(tmp_path: Path) -> None:
    """The study's paper-reading runs write ``RunSpec.of(profile, case=case.source,
    imbalance=...)``, which names only the file: the file records the case the run ran on,
    so it loads back lobe + held (before, the case file's local + compliant)."""
    base = load_case(_coarse_case(tmp_path))
    reading = base.with_actuator_reading("lobe", "held")
    spec = RunSpec.of(linear_ramp(3000 * RPM, 90000 * RPM, 500.0), case=base.source)
    assert RunSpec.from_json(spec.with_case(reading).to_json()).load_case() == reading
    profile = constant_speed(12000 * RPM, 0.02)
    part = simulate(reading, profile, stop_time=0.002)
    path = tmp_path / "reading.nc"
    to_netcdf(part, RunSpec.of(profile, case=base.source, imbalance=8.5e-6), path)
    back, spec_back = load_orbit(path)
    act = back.case.actuators
    assert act is not None and (act.preload_response, act.dynamics) == ("lobe", "held")
    assert spec_back.load_case() == back.case == part.case


def test_a_run_resumes_without_its_case_file(tmp_path: Path, whole: xr.Dataset) -> None:
    """The case file deleted after a kill: the run resumes from its record alone and
    ends where the uninterrupted run ends (within 1e-3 C, as test_cli_orbit's kill)."""
    case, part = _killed_run(tmp_path)
    case.unlink()
    assert main(["orbit", "--resume", str(part)]) == 0
    a = xr.load_dataset(part)
    assert a.attrs["status"] == "completed" and a.time.size == whole.time.size
    assert float(np.abs(a.e_x - whole.e_x).max()) < 1e-3 * 100e-6  # 1e-3 C


def test_a_resume_after_the_case_file_was_edited_goes_on_with_the_recorded_case(
    tmp_path: Path, whole: xr.Dataset, capsys: pytest.CaptureFixture[str]
) -> None:
    """Clearance edited 100 -> 90 um between a kill and ``--resume``: one line on stderr
    says so and names the field, and the run ends where the uninterrupted run on the
    recorded case ends (within 1e-3 C, as test_cli_orbit's kill; continued on the edited
    case, as before the record, it ended 13 um off, the journal's state being in units
    of C)."""
    case, part = _killed_run(tmp_path)
    _coarse_case(tmp_path, edit=lambda d: d["bearing"].update(clearance="90 um"))
    assert load_case(case).bearing.clearance == pytest.approx(90e-6)
    capsys.readouterr()
    assert main(["orbit", "--resume", str(part)]) == 0
    notes = [ln for ln in capsys.readouterr().err.splitlines() if "note:" in ln]
    assert len(notes) == 1
    assert "has changed since the run started" in notes[0]
    assert "bearing.clearance" in notes[0] and str(case) in notes[0]
    a = xr.load_dataset(part)
    assert a.attrs["status"] == "completed" and a.attrs["clearance_m"] == pytest.approx(100e-6)
    assert a.time.size == whole.time.size
    assert float(np.abs(a.e_x - whole.e_x).max()) < 1e-3 * 100e-6


def test_an_unchanged_case_file_gives_no_notice(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    case, part = _stopped_run(tmp_path)
    case.write_text("# a comment only\n" + case.read_text(encoding="utf-8"), encoding="utf-8")
    capsys.readouterr()
    load_orbit(part)
    assert capsys.readouterr().err == ""


@pytest.fixture(scope="module")
def stopped(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return _stopped_run(tmp_path_factory.mktemp("stopped"))[1]


def _spec_edit(edit: Callable[[dict[str, Any]], None]) -> Callable[[xr.Dataset], None]:
    def apply(ds: xr.Dataset) -> None:
        data = json.loads(ds.attrs["run_spec"])
        edit(data)
        ds.attrs["run_spec"] = json.dumps(data)

    return apply


def _set(name: str, change: Callable[[np.ndarray], np.ndarray]) -> Callable[[xr.Dataset], None]:
    def apply(ds: xr.Dataset) -> None:
        values = change(np.array(ds[name].values, float))
        ds[name] = (f"{name}_dim" if name.startswith("checkpoint_") else "time", values)

    return apply


def _with(i: int, value: float) -> Callable[[np.ndarray], np.ndarray]:
    def change(a: np.ndarray) -> np.ndarray:
        a[i] = value
        return a

    return change


DAMAGE: dict[str, tuple[Callable[[xr.Dataset], None], str]] = {
    "NaN state": (_set("checkpoint_y", _with(3, np.nan)), "checkpoint_y holds values that"),
    "NaN past state": (_set("checkpoint_y_prev", _with(0, np.nan)), "checkpoint_y_prev holds"),
    "short state": (_set("checkpoint_y", lambda a: a[:-5]), "the run's case has"),
    "garbage state": (_set("checkpoint_y", _with(1, 1e300)), "film pressure p/p_a = 1e+300"),
    "negative pressure": (_set("checkpoint_y_prev", _with(0, -0.5)), "p/p_a = -0.5: expected"),
    "journal far away": (_set("checkpoint_y", _with(-3, 5e3)), "displacement of 5e+03 C"),
    "journal flying": (_set("checkpoint_y", _with(-1, 1e12)), "journal velocity of 1e+12 C/s"),
    "negative step": (_set("checkpoint_h_prev", lambda a: -a), "expected one step > 0 s"),
    "garbage series": (_set("e_x", _with(2, np.inf)), "e_x holds values that are not finite"),
    "cut run_spec": (
        lambda ds: ds.attrs.update(run_spec=ds.attrs["run_spec"][:400]),
        "not valid JSON",
    ),
    "unknown status": (lambda ds: ds.attrs.update(status="paused"), "status = 'paused'"),
    "checkpoint_t beyond the end": (
        _set("checkpoint_t", lambda a: a + 1.0),
        "expected one time within the run's profile",
    ),
    "checkpoint_t before the samples": (
        _set("checkpoint_t", lambda a: a * 0.5),
        "not increasing up to the checkpoint",
    ),
    "hash mismatch": (
        _spec_edit(lambda d: d["recorded_case"]["tables"]["bearing"].update(clearance="9e-05 m")),
        "does not match its sha256",
    ),
    "speeds not numbers": (
        _spec_edit(lambda d: d.update(speeds=["fast", 1.0])),
        "run specification damaged",
    ),
    "spec key missing": (
        _spec_edit(lambda d: d.pop("speed_times")),
        "'speed_times' missing",
    ),
}


@pytest.mark.parametrize("kind", list(DAMAGE))
def test_a_damaged_orbit_file_is_a_one_line_error(
    kind: str, stopped: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Each damage of what ``--resume`` reads: exit 2, one line naming the file and what
    is wrong, no traceback, and nothing run."""
    damage, text = DAMAGE[kind]
    ds = xr.load_dataset(stopped)
    damage(ds)
    path = tmp_path / "damaged.nc"
    ds.to_netcdf(path)
    capsys.readouterr()
    assert main(["orbit", "--resume", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert str(path) in err and text in err, err
    assert "Traceback" not in err


def test_a_file_of_an_earlier_version_without_its_case_file_says_why(
    stopped: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A /1 record held only the case file's path: it resumes from the file while the file
    reads, and with the file gone says so in one line."""
    ds = xr.load_dataset(stopped)
    data = json.loads(ds.attrs["run_spec"])
    data["format"] = "foilbearing.orbit.RunSpec/1"
    del data["recorded_case"]
    data["case"] = str(tmp_path / "gone.toml")
    ds.attrs["run_spec"] = json.dumps(data)
    path = tmp_path / "old.nc"
    ds.to_netcdf(path)
    capsys.readouterr()
    assert main(["orbit", "--resume", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "earlier version" in err and "gone.toml" in err
    shutil.copy(
        Path(json.loads(xr.load_dataset(stopped).attrs["run_spec"])["case"]), tmp_path / "gone.toml"
    )
    back, spec = load_orbit(path)
    assert spec.recorded_case is None and back.case == load_case(tmp_path / "gone.toml")
    assert default_case().title == back.case.title


def test_simulate_refuses_to_resume_a_run_on_another_case() -> None:
    """Through the API, a run resumed with a case other than its own (another clearance,
    another actuator reading) is refused in one line naming the fields; before, only a
    grid of another size was caught, and the run went on with the new case."""
    from dataclasses import replace

    from foilbearing.case import Grid
    from foilbearing.errors import InputError

    case = replace(default_case(), grid=Grid(n_theta=32, n_z=4), disturbance=None)
    profile = constant_speed(12000 * RPM, 0.004)
    part = simulate(case, profile, stop_time=0.001)
    wider = replace(case, bearing=replace(case.bearing, clearance=90e-6))
    with pytest.raises(InputError, match=r"bearing\.clearance: 9\.99.*e-05 m then, 9e-05 m now"):
        simulate(wider, profile, resume=part)
    with pytest.raises(InputError, match=r"actuators\.dynamics: compliant then, held now"):
        simulate(case.with_actuator_reading(dynamics="held"), profile, resume=part)
    assert simulate(case, profile, resume=part).status == "completed"


#: Options that shape a run, each as a user would give it with ``--resume``; the value of
#: --sample-rate is the default's own, which a resume would ignore just as silently.
REFUSED_ON_RESUME = {
    "--load": ["--load", "50N"],
    "--speed-ramp": ["--speed-ramp", "3000rpm:6000rpm:500rad/s**2"],
    "--voltage-ramp": ["--voltage-ramp", "0s:0.01s:100V"],
    "--steps-per-rev": ["--steps-per-rev", "48"],
    "--sample-rate": ["--sample-rate", "10000Hz"],
    "--actuator-dynamics": ["--actuator-dynamics", "held"],
    "CASE": ["case.toml"],
}


def test_resume_refuses_the_options_that_would_shape_another_run(
    stopped: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``--resume`` continues the recorded run: an option that would shape it (case, load,
    speeds, voltages, steps, reading) is refused in one line naming it, exit 2, before any
    work, and the file is left as it was (before, the option was silently ignored); the
    options that apply to a resume (--stop-time, --out, --json) still run."""
    path = tmp_path / "part.nc"
    shutil.copy(stopped, path)
    before = path.read_bytes()
    for written, extra in REFUSED_ON_RESUME.items():
        capsys.readouterr()
        argv = ["orbit", *(extra if written == "CASE" else []), "--resume", str(path)]
        argv += [] if written == "CASE" else extra
        assert main(argv) == 2, written
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "--resume continues the recorded run" in err, err
        assert (written if written != "CASE" else "case.toml") in err, err
        assert "Traceback" not in err
    assert path.read_bytes() == before
    out = tmp_path / "copy.nc"
    code = main(["orbit", "--resume", str(path), "--out", str(out), "--stop-time", "0.015s"])
    assert code == 0 and xr.load_dataset(out).attrs["status"] == "stopped"
    assert path.read_bytes() == before
