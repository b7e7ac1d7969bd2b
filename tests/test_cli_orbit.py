"""``foilbearing orbit``: JSON keys, NetCDF with checkpoint, resume, errors before work."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import tomlkit

from foilbearing.case import default_case_path
from foilbearing.cli import main


@pytest.fixture()
def coarse_case(tmp_path: Path) -> Path:
    data = tomlkit.parse(default_case_path().read_text())
    data["grid"]["n_theta"] = 32
    data["grid"]["n_z"] = 4
    path = tmp_path / "coarse.toml"
    path.write_text(tomlkit.dumps(data))
    return path


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


@pytest.mark.parametrize(
    ("extra", "text"),
    [
        (["--speed-ramp", "90000rpm:3000rpm:500rad/s2"], "below or at its start"),
        (["--speed-ramp", "3000rpm:90000rpm:0rad/s2"], "acceleration"),
        (["--voltage-ramp", "6s:6.5s:200V"], "max_voltage"),
        (["--sample-rate", "1000Hz"], "cannot resolve the synchronous frequency"),
        (["--controller", "threshold=2um,gain=3"], "KEY=VALUE"),
    ],
)
def test_orbit_bad_input_fails_before_work(extra, text, capsys) -> None:
    assert main(["orbit", *extra]) == 2
    err = capsys.readouterr().err
    assert text in err and "Traceback" not in err
