"""Your own bearing: the example cases without actuators through every command (issue 47).

The three example cases of ``examples/`` (a first-generation bump foil bearing, the paper's
shimmed GFB and a rigid gas bearing) run through ``static``, ``coefficients``,
``stability`` and a short ``orbit`` from the command line, in process, on a coarse grid
(32 x 4, the orbit's own grid 32 x 4 at axial order 4; the shimmed bearing on 48 θ cells,
3.7 across its 27.7° shims: on 32, 2.5 across, its orbit at 50 krpm touches down within
1 ms, on 48 and 96 it does not): each file they write reads back
with ``xarray.load_dataset``, and each answer obeys a physical fact (force balance, the
study's onset, Lund's threshold, the rigid bearing's small-eccentricity closed form).
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import tomlkit
import xarray as xr

from foilbearing.case import load_case
from foilbearing.cli.main import main
from foilbearing.coefficients import coefficients_over_speeds, force_coefficients
from foilbearing.constants import RPM
from foilbearing.static import film_at_position, solve_equilibrium

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
KINDS = {
    "bump_foil_bearing": "GFB",
    "shimmed_gfb": "shimmed GFB",
    "rigid_gas_bearing": "rigid",
}


@pytest.fixture(scope="module")
def coarse(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Each example case on 32 x 4 (48 x 4 for the shims), its orbit grid with 4 axial cells
    at order 4, written as a file."""
    folder = tmp_path_factory.mktemp("examples")
    paths = {}
    for name in KINDS:
        data = tomlkit.parse((EXAMPLES / f"{name}.toml").read_text(encoding="utf-8"))
        data["grid"]["n_theta"] = 48 if name == "shimmed_gfb" else 32
        data["grid"]["n_z"] = 4
        paths[name] = folder / f"{name}.toml"
        paths[name].write_text(tomlkit.dumps(data), encoding="utf-8")
    return paths


def _run(argv: list[str], capsys) -> dict:
    assert main([*argv, "--json"]) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("name", list(KINDS))
def test_each_example_case_is_a_valid_case_of_its_kind(name: str, capsys) -> None:
    path = EXAMPLES / f"{name}.toml"
    assert main(["case", "show", str(path), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["source"] == str(path)
    case = load_case(path)
    assert case.kind == KINDS[name] and case.actuators is None
    # The case format's load is the rotor's weight: m g along +X.
    assert case.rotor.mass * 9.80665 == pytest.approx(case.operation.load, rel=0.01)


@pytest.mark.parametrize("name", list(KINDS))
def test_static_over_speeds_balances_the_load_and_its_file_reads_back(
    name: str, coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """A speed list on a case without actuators is the speed sweep: every point an
    equilibrium (film force = −W along X, |F + W|/W below the solver's 1e-8), the journal
    rising towards the centre as the speed (the film's stiffness) grows; the NetCDF file
    holds the same numbers, and the middle point equals a single run at that speed to the
    solver's tolerance (each started from another point)."""
    path = coarse[name]
    load = load_case(path).operation.load
    nc = tmp_path / "speeds.nc"
    out = _run(["static", str(path), "--speed", "20000,30000,40000rpm", "--out", str(nc)], capsys)
    assert out["bearing"] == KINDS[name]
    points = out["points"]
    assert [p["speed_rpm"] for p in points] == pytest.approx([20000, 30000, 40000])
    for p in points:
        assert p["converged"]
        assert np.hypot(p["force_N"][0] + load, p["force_N"][1]) < 1e-8 * load
    ecc = [p["eccentricity"] for p in points]
    assert np.all(np.diff(ecc) < 0), ecc
    ds = xr.load_dataset(nc)
    assert ds.attrs["bearing"] == KINDS[name]
    np.testing.assert_array_equal(ds["eccentricity"].values, ecc)
    single = _run(["static", str(path), "--speed", "30000rpm"], capsys)
    assert single["eccentricity"] == pytest.approx(ecc[1], rel=1e-6)


@pytest.mark.parametrize("name", list(KINDS))
def test_coefficients_over_a_speed_list_are_the_single_runs_and_read_back(
    name: str, coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """``coefficients --speed 20000,40000rpm`` gives at each speed what a single run at that
    speed gives (the same equilibrium and the same perturbation solve: to round-off, 1e-12),
    and the Python API the same; the NetCDF file holds them along ``speed`` x the
    frequency ratios, each ratio ω_e/ω as given, with each speed's own equilibrium (the
    journal rising towards the centre as the speed grows)."""
    path = coarse[name]
    nc = tmp_path / "coef.nc"
    swept = _run(["coefficients", str(path), "--speed", "20000,40000rpm", "--out", str(nc)], capsys)
    assert swept["bearing"] == KINDS[name]
    assert [e["speed_rpm"] for e in swept["speeds"]] == pytest.approx([20000, 40000])
    api = coefficients_over_speeds(load_case(path), ["20 krpm", "40 krpm"])
    ds = xr.load_dataset(nc)
    assert ds["stiffness"].dims == ("speed", "frequency_ratio", "i", "j")
    np.testing.assert_array_equal(ds["frequency_ratio"].values, np.linspace(0.1, 2.0, 20))
    for k, (entry, rpm) in enumerate(zip(swept["speeds"], ("20000rpm", "40000rpm"), strict=True)):
        single = _run(["coefficients", str(path), "--speed", rpm], capsys)
        for key in ("K_N_per_m", "C_Ns_per_m", "frequency_Hz"):
            np.testing.assert_allclose(entry[key], single[key], rtol=1e-12)
        np.testing.assert_allclose(api.points[k].K, single["K_N_per_m"], rtol=1e-12)
        np.testing.assert_allclose(ds["stiffness"].values[k], single["K_N_per_m"], rtol=1e-12)
        np.testing.assert_allclose(ds["damping"].values[k], single["C_Ns_per_m"], rtol=1e-12)
    # each point about its own equilibrium: the journal rises as the film stiffens with speed
    assert ds["eccentricity"].values[1] < ds["eccentricity"].values[0]


def test_coefficients_over_loads_and_speeds_stack_along_both(
    coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """A load list around a speed list: one file along (load, speed, frequency), each point
    the single run at that load and speed (1e-12); a heavier load (a larger eccentricity)
    stiffens the bump bearing's film along the load."""
    path = str(coarse["bump_foil_bearing"])
    nc = tmp_path / "both.nc"
    argv = ["coefficients", path, "--speed", "20000,40000rpm", "--frequency", "400Hz"]
    swept = _run([*argv, "--load", "50,100N", "--out", str(nc)], capsys)
    assert [e["load_N"] for e in swept["loads"]] == [50.0, 100.0]
    ds = xr.load_dataset(nc)
    assert ds["stiffness"].dims == ("load", "speed", "frequency", "i", "j")
    single = _run(
        ["coefficients", path, "--speed", "40000rpm", "--frequency", "400Hz", "--load", "100N"],
        capsys,
    )
    np.testing.assert_allclose(
        swept["loads"][1]["speeds"][1]["K_N_per_m"], single["K_N_per_m"], rtol=1e-12
    )
    np.testing.assert_allclose(ds["stiffness"].values[1, 1], single["K_N_per_m"], rtol=1e-12)
    k_xx = ds["stiffness"].sel(i="X", j="X").values[:, :, 0]
    assert np.all(k_xx[1] > k_xx[0])


@pytest.mark.parametrize(
    "argv",
    [
        ["static", "--voltage", "0V"],
        ["static", "--speed", "10000,20000rpm", "--voltage", "0V"],
        ["coefficients", "--voltage", "0V"],
        ["coefficients", "--voltage", "0V", "--speed", "30000rpm"],
        ["stability", "--voltage", "0V"],
        ["stability", "--shimmed"],
        ["stability", "--design"],
    ],
)
def test_a_voltage_on_a_bearing_without_actuators_is_one_line_saying_why(
    argv: list[str], coarse: dict[str, Path], capsys
) -> None:
    path = str(coarse["bump_foil_bearing"])
    assert main([argv[0], path, *argv[1:]]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    err = captured.err.strip()
    assert len(err.splitlines()) == 1, err
    assert "passive gas foil bearing with no [actuators]" in err and "drop --" in err


@pytest.mark.parametrize("name", list(KINDS))
def test_stability_gives_the_studys_onset_at_lunds_threshold(
    name: str, coarse: dict[str, Path], capsys
) -> None:
    """``stability CASE`` (no voltage) reports the onset of the study's stage, to the last
    digit (the same scan), and the onset is a threshold of the rotor on the film: with
    the coefficients at the whirl frequency, Lund's closed form gives the equivalent
    stiffness K_eq = (K_XX C_YY + K_YY C_XX − K_XY C_YX − K_YX C_XY)/(C_XX + C_YY), the
    whirl frequency ω_s² = ((K_XX − K_eq)(K_YY − K_eq) − K_XY K_YX)/(C_XX C_YY − C_XY C_YX)
    and the critical mass K_eq/ω_s², which must be the rotor's mass. Tolerance 0.5 %: the
    onset is found to 1e-4 of the speed (Brent), where the log decrement moves by 1e-5.
    Each whirl is sub-synchronous, below the half-frequency of a plain journal bearing."""
    from foilbearing.study.bearing import _onset
    from foilbearing.study.plan import study_plan

    path = coarse[name]
    case = load_case(path)
    out = _run(["stability", str(path)], capsys)
    study = _onset(case, study_plan(case))
    assert out["bearing"] == KINDS[name]
    assert out["onset_speed_rpm"] == study["onset_speed_rpm"] is not None
    assert out["whirl_frequency_Hz"] == study["whirl_frequency_Hz"]
    assert 0.0 < out["whirl_ratio"] < 0.5
    speed = out["onset_speed_rpm"] * RPM
    whirl = 2 * math.pi * out["whirl_frequency_Hz"]
    st = solve_equilibrium(case, speed=speed)
    fc = force_coefficients(st, whirl)
    K, C = fc.K[0], fc.C[0]
    k_eq = (K[0, 0] * C[1, 1] + K[1, 1] * C[0, 0] - K[0, 1] * C[1, 0] - K[1, 0] * C[0, 1]) / (
        C[0, 0] + C[1, 1]
    )
    w_s2 = ((K[0, 0] - k_eq) * (K[1, 1] - k_eq) - K[0, 1] * K[1, 0]) / (
        C[0, 0] * C[1, 1] - C[0, 1] * C[1, 0]
    )
    assert math.sqrt(w_s2) == pytest.approx(whirl, rel=5e-3)
    assert k_eq / w_s2 == pytest.approx(case.rotor.mass, rel=5e-3)


def test_the_rigid_example_carries_the_small_eccentricity_closed_form_load() -> None:
    """The rigid gas bearing of the examples at ε = 0.01 and Λ = 0.012 (300 rpm): the
    incompressible short-and-long closed form of tests/test_coefficients.py (first harmonic
    p = Re[g(Z) e^{jθ}], G = Z_e − tanh Z_e) gives the load W = 2π Λ G p_a R² ε at 90°
    from the displacement, and K_XY = −K_YX = 2πΛG p_a R²/C, C_XX = C_YY = 2 K_XY/ω,
    K_XX = K_YY = 0. Tolerance 1 %, as there: grid 64 x 16 and Λ ~ 0.01."""
    case = load_case(EXAMPLES / "rigid_gas_bearing.toml")
    case = replace(case, grid=replace(case.grid, n_theta=64, n_z=16))
    speed, eps = 300 * RPM, 0.01
    st = film_at_position(case, eps, 0.0, speed=speed)
    lam = st.bearing_number
    assert lam == pytest.approx(0.0122, rel=0.01)
    r, c, pa = case.bearing.radius, case.bearing.clearance, case.gas.ambient_pressure
    z_e = case.bearing.length / (2 * r)
    g = z_e - math.tanh(z_e)
    load = 2 * math.pi * lam * g * pa * r**2 * eps
    fx, fy = st.force
    assert fy == pytest.approx(load, rel=0.01) and abs(fx) < 0.01 * load
    k_c = 2 * math.pi * lam * g * pa * r**2 / c
    fc = force_coefficients(st, 0.1 * speed)
    np.testing.assert_allclose(fc.K[0] / k_c, [[0, 1], [-1, 0]], atol=0.01)
    np.testing.assert_allclose(fc.C[0] * speed / (2 * k_c), np.eye(2), atol=0.01)


@pytest.mark.parametrize("name", list(KINDS))
def test_every_file_of_a_case_without_actuators_reads_back(
    name: str, coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """static, coefficients and orbit ``--out`` files reopen with ``xarray.load_dataset``
    and hold the numbers the command printed; an orbit at the case's speed (below each
    bearing's onset), stopped after four revolutions, resumes from its file to eight, the
    film open throughout (above the contact film, 0.005 C)."""
    path = str(coarse[name])
    rpm = load_case(coarse[name]).operation.speed / RPM
    speed = f"{rpm:.0f}rpm"
    files = {k: tmp_path / f"{k}.nc" for k in ("static", "coefficients", "orbit")}
    st = _run(["static", path, "--out", str(files["static"])], capsys)
    ds = xr.load_dataset(files["static"])
    assert float(ds["eccentricity"]) == st["eccentricity"] and ds.attrs["bearing"] == KINDS[name]
    fc = _run(["coefficients", path, "--frequency", "100,200Hz",
               "--out", str(files["coefficients"])], capsys)  # fmt: skip
    ds = xr.load_dataset(files["coefficients"])
    np.testing.assert_array_equal(ds["stiffness"].values, fc["K_N_per_m"])
    revolution = 60.0 / rpm
    orbit = ["orbit", path, "--speed", speed, "--duration", f"{8 * revolution}s"]
    half = _run([*orbit, "--stop-time", f"{4 * revolution}s", "--out", str(files["orbit"])], capsys)
    assert half["status"] == "stopped"
    ds = xr.load_dataset(files["orbit"])
    assert "voltage" not in ds and ds.attrs["status"] == "stopped"
    np.testing.assert_allclose(ds["speed"].values, rpm * RPM, rtol=1e-12)
    done = _run(["orbit", "--resume", str(files["orbit"])], capsys)
    assert done["status"] == "completed"
    ds = xr.load_dataset(files["orbit"])
    assert ds["time"].values[-1] == pytest.approx(8 * revolution, rel=0.02)
    assert ds["min_film"].values.min() > float(ds.attrs["contact_film"]) * ds.attrs["clearance_m"]


def test_a_sweep_of_a_case_without_actuators_reads_back(coarse: dict[str, Path], tmp_path) -> None:
    """The sweep's dataset of a bearing without actuators has no empty ``actuator``
    dimension (NetCDF 3 cannot hold one after another) and reopens with its values."""
    from foilbearing.sweep.records import point_file
    from foilbearing.sweep.runner import ANALYSES, assemble, load_sweep, run_point

    sweep = tmp_path / "sweep.toml"
    sweep.write_text(
        f'case = "{coarse["bump_foil_bearing"]}"\nanalysis = "static"\n'
        '[parameters]\nspeed = ["20000 rpm", "30000 rpm"]\n',
        encoding="utf-8",
    )
    spec = load_sweep(sweep)
    folder = tmp_path / "out.d"
    (folder / "points").mkdir(parents=True)
    for i in range(spec.n_points):
        rec = run_point(
            i, spec.point_data(i), spec.point_source(i), ANALYSES["static"].evaluate, spec.options
        )
        rec["parameters"] = spec.point_values(i)  # as the runner writes a record
        point_file(folder, i).write_text(json.dumps(rec), encoding="utf-8")
    ds = assemble(spec, tmp_path / "out")
    back = xr.load_dataset(tmp_path / "out.nc")
    assert "voltages_V" not in back and (back["status"] == "ok").all()
    np.testing.assert_array_equal(back["eccentricity"].values, ds["eccentricity"].values)


def test_a_constant_speed_orbit_reports_the_linear_imbalance_response(
    coarse: dict[str, Path], tmp_path: Path, capsys
) -> None:
    """The bump bearing at 10 krpm for 0.3 s (50 revolutions; the whirl's log decrement
    0.3 at 69 Hz leaves 4 % of the start by the middle, where the 1X window begins): the
    headline's 1X amplitude equals the linear imbalance response of the film's K and C at
    1X on the orbit's grid, (K − m ω² + jω C) X = m u ω² (1, −j). Measured −1.1 % in X and
    −1.0 % in Y at the default 24 steps a revolution, −0.2/−0.4 % at 48 and −0.07/−0.3 % at
    96 (the gap is the time step's): tolerance 2 %. The orbit plot's one panel is at the
    run's speed."""
    from foilbearing.orbit.analysis import orbit_panel_speeds

    path = coarse["bump_foil_bearing"]
    case = load_case(path)
    out = _run(["orbit", str(path), "--speed", "10000rpm", "--duration", "0.3s",
                "--plot", str(tmp_path)], capsys)  # fmt: skip
    assert out["status"] == "completed"
    w = 10_000 * RPM
    st = solve_equilibrium(case.orbit_case(), speed=w)
    fc = force_coefficients(st, [w])
    m, u = case.rotor.mass, case.rotor.imbalance_radius
    a = fc.K[0] - m * w**2 * np.eye(2) + 1j * w * fc.C[0]
    linear = np.abs(np.linalg.solve(a, m * u * w**2 * np.array([1.0, -1.0j])))
    np.testing.assert_allclose(out["one_x_amplitude_0pk_um"], linear * 1e6, rtol=0.02)
    np.testing.assert_allclose(
        out["one_x_amplitude_pkpk_um"], 2 * np.asarray(out["one_x_amplitude_0pk_um"])
    )
    assert out["one_x_window_s"][0] == pytest.approx(0.15, abs=1e-3)
    assert (tmp_path / "orbit_orbits.png").stat().st_size > 10_000
    assert orbit_panel_speeds(np.full(5, 30_000 * RPM)) == pytest.approx([30_000])
    ramp = np.linspace(3_000, 60_000, 50) * RPM
    assert orbit_panel_speeds(ramp) == pytest.approx([10e3, 20e3, 30e3, 50e3])
