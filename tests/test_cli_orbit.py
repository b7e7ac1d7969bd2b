"""``foilbearing orbit``: JSON keys, NetCDF with checkpoint, resume, errors before work."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from foilbearing.cli.main import main


@pytest.fixture()
def coarse_case(write_case) -> Path:
    return write_case("coarse", n_theta=32, n_z=4)


def test_orbit_json_netcdf_and_resume(coarse_case: Path, tmp_path: Path, capsys) -> None:
    out = tmp_path / "run.nc"
    argv = [
        "orbit",
        str(coarse_case),
        "--speed",
        "12000rpm",
        "--duration",
        "0.06s",
        "--stop-time",
        "0.03s",
        "--out",
        str(out),
        "--json",
    ]
    assert main(argv) == 0
    first = json.loads(capsys.readouterr().out)
    keys = {
        "onset_speed_rpm",
        "whip_frequency_Hz",
        "divergence_speed_rpm",
        "max_subsync_amplitude_um",
        "wall_time_s",
    }
    assert keys <= set(first)
    assert first["status"] == "stopped" and out.exists()
    assert main(["orbit", "--resume", str(out), "--json"]) == 0
    second = json.loads(capsys.readouterr().out)
    assert second["status"] == "completed"
    import xarray as xr

    ds = xr.load_dataset(out)
    assert ds.time.values[-1] == pytest.approx(0.06, abs=2e-4)
    assert ds.attrs["sample_rate_Hz"] == 10_000.0
    # a completed run has nothing to resume: one line that says how to run on
    assert main(["orbit", "--resume", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "nothing to resume" in err[0] and "longer --duration" in err[0]


def test_orbit_order_and_step_are_stored_and_resumed(coarse_case: Path, tmp_path: Path) -> None:
    # --order and --steps-per-rev go into the file; the resumed run keeps them (its
    # checkpoint holds the order's history), so stop + resume equals a run in one go
    # within the last step's difference before the stop.
    import xarray as xr

    out, whole = tmp_path / "part.nc", tmp_path / "whole.nc"
    base = ["orbit", str(coarse_case), "--speed", "12000rpm", "--duration", "0.04s"]
    opts = ["--order", "2", "--steps-per-rev", "20"]
    assert main([*base, *opts, "--out", str(whole)]) == 0
    assert main([*base, *opts, "--stop-time", "0.02s", "--out", str(out)]) == 0
    assert main(["orbit", "--resume", str(out)]) == 0
    a, b = xr.load_dataset(out), xr.load_dataset(whole)
    assert a.attrs["bdf_order"] == b.attrs["bdf_order"] == 2
    assert a.attrs["steps_per_rev"] == 20 and a.attrs["status"] == "completed"
    assert "checkpoint_y_prev2" in a and "checkpoint_y_prev3" not in a
    assert a.time.size == b.time.size
    assert float(abs(a.e_x - b.e_x).max()) < 0.01 * float(b.e_x.max() - b.e_x.min())


def test_adaptive_steps_are_stored_and_resumed(coarse_case: Path, tmp_path: Path, capsys) -> None:
    # --steps adaptive and --rtol go into the file with the next step the error control
    # chose; the resumed run keeps them, refuses to be given them again, and a tolerance
    # out of range fails in one line before any work.
    import xarray as xr

    out = tmp_path / "part.nc"
    base = ["orbit", str(coarse_case), "--speed", "12000rpm", "--duration", "0.04s"]
    opts = ["--steps", "adaptive", "--rtol", "3e-4"]
    assert main([*base, *opts, "--stop-time", "0.02s", "--out", str(out)]) == 0
    part = xr.load_dataset(out)
    assert part.attrs["time_steps"] == "adaptive" and part.attrs["step_rtol"] == 3e-4
    assert float(np.ravel(part["checkpoint_h_next"].values)[0]) > 0.0
    assert main(["orbit", "--resume", str(out), "--rtol", "1e-3"]) != 0
    assert "--rtol" in capsys.readouterr().err
    assert main(["orbit", "--resume", str(out)]) == 0
    done = xr.load_dataset(out)
    assert done.attrs["status"] == "completed" and done.attrs["step_rtol"] == 3e-4
    assert main([*base, "--steps", "adaptive", "--rtol", "0.5"]) != 0
    err = capsys.readouterr().err
    assert "--rtol" in err and "0.5" in err and "Traceback" not in err


def test_a_file_with_the_old_string_spec_resumes(write_case, tmp_path: Path) -> None:
    """Files of earlier versions held the command line's strings as the run's specification:
    such a file resumes, with its voltage ramp, to the same run as the file written now."""
    import xarray as xr

    case = write_case(
        "light", n_theta=32, n_z=4, edit=lambda d: d["rotor"].update(imbalance="1 g*mm")
    )
    new, old = tmp_path / "new.nc", tmp_path / "old.nc"
    argv = ["orbit", str(case), "--speed", "12000rpm", "--duration", "0.03s"]
    argv += ["--voltage-ramp", "0.005s:0.02s:50V", "--steps-per-rev", "16"]
    assert main([*argv, "--stop-time", "0.01s", "--out", str(new)]) == 0
    ds = xr.load_dataset(new)
    ds.attrs["run_spec"] = json.dumps(
        {
            "case": str(case),
            "speed_ramp": "3000rpm:90000rpm:500rad/s**2",
            "speed": "12000rpm",
            "duration": "0.03s",
            "voltage_ramp": "0.005s:0.02s:50V",
            "controller": None,
            "voltage_schedule": None,
            "stop_time": "0.01s",
            "steps_per_rev": 16,
            "order": 3,
            "sample_rate": "10000Hz",
            "subambient": None,
        }
    )
    ds.to_netcdf(old)
    assert main(["orbit", "--resume", str(new)]) == 0
    assert main(["orbit", "--resume", str(old)]) == 0
    a, b = xr.load_dataset(new), xr.load_dataset(old)
    assert a.attrs["status"] == b.attrs["status"] == "completed"
    assert a.time.values[-1] == pytest.approx(0.03, abs=2e-4)
    np.testing.assert_array_equal(a.e_x.values, b.e_x.values)
    np.testing.assert_array_equal(a.voltage.values, b.voltage.values)
    assert np.allclose(a.voltage.values[a.time.values > 0.02], 50.0)
    assert json.loads(b.attrs["run_spec"]) == json.loads(a.attrs["run_spec"])


@pytest.mark.parametrize(
    ("extra", "text"),
    [
        (["--speed-ramp", "90000rpm:3000rpm:500rad/s2"], "below or at its start"),
        (["--speed-ramp", "3000rpm:90000rpm:0rad/s2"], "acceleration"),
        (["--voltage-ramp", "6s:6.5s:200V"], "max_voltage"),
        (["--sample-rate", "1000Hz"], "cannot resolve the synchronous frequency"),
        (["--controller", "threshold=2um,gain=3"], "KEY=VALUE"),
        (["--steps-per-rev", "0"], "at least 8 resolve the 1X motion"),
    ],
)
def test_orbit_bad_input_fails_before_work(extra, text, capsys) -> None:
    assert main(["orbit", *extra]) == 2
    err = capsys.readouterr().err
    assert text in err and "Traceback" not in err


def _orbit_process(argv: list[str]) -> subprocess.Popen:
    """``foilbearing orbit`` in a child process that Ctrl-C reaches: a child started from
    a background job inherits SIGINT ignored, and Python then never raises
    KeyboardInterrupt, so the default disposition is restored before it starts."""
    return subprocess.Popen(
        [sys.executable, "-m", "foilbearing", "orbit", *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )


def _wait_for_checkpoint(path: Path, proc: subprocess.Popen, timeout: float = 120.0) -> None:
    start = time.monotonic()
    while not (path.exists() and path.stat().st_size > 0):
        assert proc.poll() is None, f"the run ended before its first checkpoint: {proc.stderr}"
        assert time.monotonic() - start < timeout, "no checkpoint written"
        time.sleep(0.05)


@pytest.mark.slow
@pytest.mark.parametrize("how", ["Ctrl-C", "SIGKILL"])
def test_a_stopped_process_resumes_to_the_uninterrupted_run(
    write_case, tmp_path: Path, capsys, how: str
) -> None:
    """Stopped by Ctrl-C (the run saves what it did) or killed outright (the last
    checkpoint, written atomically, survives), the run resumes from where it stopped, not
    from t = 0, and ends where the uninterrupted run ends: e_X within 1e-3 C throughout."""
    import xarray as xr

    case = write_case(
        "light", n_theta=32, n_z=4, edit=lambda d: d["rotor"].update(imbalance="1 g*mm")
    )
    run = ["--speed", "12000rpm", "--duration", "3s", "--json"]
    whole = tmp_path / "whole.nc"
    assert main(["orbit", str(case), *run, "--out", str(whole)]) == 0
    steps_whole = json.loads(capsys.readouterr().out)["steps"]
    part = tmp_path / "part.nc"
    proc = _orbit_process([str(case), *run, "--out", str(part), "--checkpoint-every", "0.3s"])
    _wait_for_checkpoint(part, proc)
    time.sleep(0.5)
    proc.send_signal(signal.SIGINT if how == "Ctrl-C" else signal.SIGKILL)
    out, err = proc.communicate(timeout=60)
    if how == "Ctrl-C":
        assert proc.returncode == 3, err[-2000:]
        assert json.loads(out)["status"] == "interrupted"
    else:
        assert proc.returncode == -signal.SIGKILL
    stopped_at = float(xr.load_dataset(part).time.values[-1])
    steps_before = int(xr.load_dataset(part).attrs["steps"])  # at the checkpoint
    assert 0.0 < stopped_at < 3.0
    assert main(["orbit", "--resume", str(part), "--json"]) == 0
    resumed = json.loads(capsys.readouterr().out)
    assert resumed["status"] == "completed"
    # Not from t = 0: the resumed part took the steps after the checkpoint only, and the
    # count reported is the whole run's (the step grid goes on: within the last step's).
    assert resumed["steps"] - steps_before < steps_whole * (1.0 - 0.5 * stopped_at / 3.0)
    assert abs(resumed["steps"] - steps_whole) <= 2
    a, b = xr.load_dataset(part), xr.load_dataset(whole)
    assert a.time.size == b.time.size
    assert float(np.abs(a.e_x - b.e_x).max()) < 1e-3 * 100.0  # um, C = 100 um
