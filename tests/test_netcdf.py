"""Results on disk: NetCDF round trips in SI, each variable with its units attribute."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from foilbearing.case import default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.constants import RPM
from foilbearing.control import constant_speed, voltage_ramp
from foilbearing.orbit import RunSpec, RunStatus, simulate
from foilbearing.orbit.netcdf import load_orbit, to_netcdf
from foilbearing.static import solve_equilibrium
from foilbearing.units import ureg

SI = {"m", "rad", "rad/s", "s", "V", "W", "Pa", "Hz", "N/m", "N s/m"}


@pytest.fixture(scope="module")
def stopped_run():
    """A run of the default case stopped at 2 ms (20 krpm, 100 V): it has a checkpoint."""
    case = default_case().with_voltages(100.0)
    return simulate(case, constant_speed(20e3 * RPM, 0.01), stop_time=0.002)


def test_orbit_file_is_si_and_loads_back_to_the_same_run(stopped_run, tmp_path) -> None:
    """Every variable of the orbit file is in SI by its units attribute, the journal and
    film in metres and the speed in rad/s, and load_orbit gives back the run's arrays and
    checkpoint exactly (the file stores float64)."""
    run = stopped_run
    assert run.status == "stopped"
    path = tmp_path / "run.nc"
    spec = RunSpec.of(
        constant_speed(20e3 * RPM, 0.01),
        voltage_ramp(0.0, 0.001, 100.0, initial=100.0),
        settings=run.settings,
        stop_time=0.002,
    )
    to_netcdf(run, spec, path)
    ds = xr.load_dataset(path)
    for name in ("e_x", "e_y", "speed", "phase", "min_film", "voltage", "power_loss"):
        assert ds[name].attrs["units"] in SI, name
    assert ds.time.attrs["units"] == "s"
    assert ds.attrs["clearance_m"] == run.case.bearing.clearance
    back, spec_back = load_orbit(path)
    assert spec_back == spec.with_case(run.case)  # the case the run ran on, recorded
    assert back.case == run.case
    for name in ("time", "e_x", "e_y", "speed", "phase", "min_film", "voltages", "power_loss"):
        np.testing.assert_array_equal(getattr(back, name), getattr(run, name), err_msg=name)
    assert back.checkpoint.keys() == run.checkpoint.keys()
    for k, v in run.checkpoint.items():
        np.testing.assert_array_equal(np.ravel(back.checkpoint[k]), np.ravel(v), err_msg=k)


def test_an_orbit_file_written_before_si_loads_to_the_same_run(stopped_run, tmp_path) -> None:
    """Files of earlier versions held µm and rpm: load_orbit reads them by their units
    attribute to the same SI arrays (to round-off)."""
    run = stopped_run
    ds = run.to_dataset()
    for name in ("e_x", "e_y", "min_film"):
        ds[name] = ("time", ds[name].values * 1e6, {"units": "um"})
    ds["speed"] = ("time", ds["speed"].values / RPM, {"units": "rpm"})
    ds.attrs["run_spec"] = json.dumps({"case": None})
    path = tmp_path / "old.nc"
    ds.to_netcdf(path)
    back, _ = load_orbit(path)
    for name in ("e_x", "e_y", "min_film", "speed"):
        np.testing.assert_allclose(getattr(back, name), getattr(run, name), rtol=1e-14)


def test_an_orbit_file_with_the_old_string_spec_loads_to_its_run_spec(
    stopped_run, tmp_path
) -> None:
    """Files of earlier versions stored the command line's strings as the specification and
    the status as a plain string: they load to the RunSpec those strings parse to (the
    voltage ramp from the case's voltages) and to the RunStatus."""
    old = {
        "case": None,
        "speed_ramp": "3000rpm:90000rpm:500rad/s**2",
        "speed": "20000rpm",
        "duration": "0.01s",
        "voltage_ramp": "0s:0.001s:100V",
        "controller": None,
        "voltage_schedule": None,
        "stop_time": "0.002s",
        "steps_per_rev": 24,
        "order": 3,
        "sample_rate": "10000.0Hz",
        "subambient": None,
    }
    ds = stopped_run.to_dataset()
    ds.attrs["run_spec"] = json.dumps(old)
    assert isinstance(ds.attrs["status"], str) and type(ds.attrs["status"]) is str
    path = tmp_path / "old_spec.nc"
    ds.to_netcdf(path)
    back, spec = load_orbit(path)
    assert back.status is RunStatus.STOPPED
    assert spec == RunSpec.from_cli_strings(old)
    assert spec.speeds == (20e3 * RPM, 20e3 * RPM) and spec.stop_time == 0.002
    assert spec.voltage.volts == ((0.0,) * 3, (100.0,) * 3)
    assert spec.settings == stopped_run.settings


def test_static_and_coefficient_files_are_si(tmp_path) -> None:
    """The static point's file gives back its film force from the SI pressure field (the
    force balance F + W = 0 read from disk), and the coefficients' file holds K and C in
    N/m and N·s/m at frequencies in Hz."""
    case = default_case().with_voltages(150.0)
    st = solve_equilibrium(case, speed=50e3 * RPM)
    path = tmp_path / "static.nc"
    st.to_dataset().to_netcdf(path)
    ds = xr.load_dataset(path)
    for name in ("pressure", "gauge_pressure_mean", "film_thickness", "preload_shape"):
        assert ds[name].attrs["units"] in SI, name
    theta, z = ds.theta.values, ds.z.values
    assert ds.theta.attrs["units"] == "rad" and ds.z.attrs["units"] == "m"
    gauge = ds.pressure.values - case.gas.ambient_pressure
    area = 2 * case.bearing.radius * (2 * np.pi / theta.size) * (2 * z[0])  # both halves
    fx = float((gauge * np.cos(theta)[:, None]).sum() * area)
    fy = float((gauge * np.sin(theta)[:, None]).sum() * area)
    assert fx == pytest.approx(st.force[0], rel=1e-9)
    assert fy == pytest.approx(st.force[1], rel=1e-9, abs=1e-9 * case.operation.load)
    assert fx == pytest.approx(-case.operation.load, rel=1e-6)
    fc = force_coefficients(st, [st.speed])
    fc_path = tmp_path / "coefficients.nc"
    fc.to_dataset().to_netcdf(fc_path)
    dc = xr.load_dataset(fc_path)
    k = ureg.Quantity(dc.stiffness.values, dc.stiffness.attrs["units"]).to("N/m").magnitude
    c = ureg.Quantity(dc.damping.values, dc.damping.attrs["units"]).to("N*s/m").magnitude
    np.testing.assert_array_equal(k, fc.K)
    np.testing.assert_array_equal(c, fc.C)
    assert dc.frequency.values[0] == pytest.approx(st.speed / (2 * np.pi))
