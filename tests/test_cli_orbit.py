"""``foilbearing orbit``: JSON keys, NetCDF with checkpoint, resume, errors before work."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from foilbearing.cli import main


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
