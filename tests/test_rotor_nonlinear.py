"""The nonlinear rotor (issue 32, item 4): the films of both bearings integrated with the
reduced rotor. Its linearisation is the linear analysis, and its free whirl at small
amplitude is the linear mode."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import curve_fit

from foilbearing.case.model import Grid
from foilbearing.constants import RPM
from foilbearing.control import constant_speed
from foilbearing.errors import InputError
from foilbearing.rotor import RotorCase, load_rotor
from foilbearing.testing.ivp_rotor import RotorIVP

pytest.importorskip("ross", minversion="3.0")

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _coarse(rotor: RotorCase, subambient: str | None = None) -> RotorCase:
    """The rotor with each bearing on the 32 × 4 grid (static, linear and orbit alike)."""
    bearings = []
    for b in rotor.bearings:
        case = replace(
            b.case, grid=Grid(32, 4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None)
        )
        if subambient is not None:
            case = case.with_subambient(subambient)
        bearings.append(replace(b, case=case))
    return replace(rotor, bearings=tuple(bearings))


def _jacobian(fun, y0: np.ndarray) -> np.ndarray:  # type: ignore[no-untyped-def]
    f0 = fun(y0)
    jac = np.empty((y0.size, y0.size))
    for k in range(y0.size):
        h = 1e-7 * max(abs(y0[k]), 1e-3)
        y = y0.copy()
        y[k] += h
        jac[:, k] = (fun(y) - f0) / h
    return jac


def test_the_nonlinear_rotor_linearised_is_the_linear_analysis() -> None:
    """The flexible two-disk rotor at 150 V, 44 krpm, 8 shaft modes: the eigenvalues of the
    nonlinear system's Jacobian at its static state (both films, foils and actuators with the
    rotor) are the modes of the linear analysis (ROSS's bearing tables, matched whirl), all
    six lowest: frequencies within 0.2 % and log decrements within 0.005 (measured 0.08 %
    and 0.002; what is left is the tables' interpolation in frequency). This binds the frame
    map between the films and ROSS, the forces' scale, the gyroscopic and bending terms.

    At that state the rotor is at rest: the films carry the shaft's reactions (its
    accelerations vanish to 1e-6 m/s², 2e-10 measured)."""
    from foilbearing.rotor import reduced_modes, ross_rotor
    from foilbearing.rotor.nonlinear import RotorOrbitSystem

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_two_disk.toml"))
    speed = 44e3 * RPM
    model = ross_rotor(rotor, [speed - 1e3 * RPM, speed, speed + 1e3 * RPM])
    linear = reduced_modes(model, [0, 6], [speed], n_modes=8, num_modes=6)
    system = RotorOrbitSystem(rotor, model, constant_speed(speed, 1.0), n_modes=8)
    ivp = RotorIVP(system)
    y0 = system.initial_state()
    assert np.abs(ivp.derivative(0.0, y0)[-system.m :]).max() < 1e-6
    values = np.linalg.eigvals(_jacobian(lambda y: ivp.derivative(0.0, y), y0))
    for f, d in zip(linear.frequency[0], linear.log_decrement[0], strict=True):
        w = 2 * math.pi * f
        s = values[np.argmin(np.abs(values - complex(-d * f, w)))]
        assert s.imag / (2 * math.pi) == pytest.approx(f, rel=2e-3)
        assert -2 * math.pi * s.real / s.imag == pytest.approx(d, abs=5e-3)
    assert linear.log_decrement[0].min() < 0.01  # near the onset: one mode barely damped


def _damped_sine(t, a, sigma, w, phase, offset):  # type: ignore[no-untyped-def]
    return a * np.exp(-sigma * t) * np.cos(w * t + phase) + offset


def test_free_whirl_of_the_nonlinear_rotor_is_its_linear_mode() -> None:
    """The rigid example with suction retained, 10 krpm: both journals moved by 0.5 % of
    the clearance along ROSS's x; the run's motion, fitted by one damped sine after 30 ms
    (the other modes have decayed), whirls at the frequency of the linear analysis' least
    damped mode within 1 % and decays with its log decrement within 10 % (measured 41.92
    against 42.00 Hz, 0.581 against 0.600: the linear analysis takes each mode's coefficients
    at its real whirl frequency, which a decrement of 0.6 makes a few per cent approximate).
    The run is the rotor's stepper, which ``test_the_rotor_on_the_orbit_stepper_agrees_with_
    solve_ivp`` binds to solve_ivp from this start (solve_ivp's run here fits 41.921 Hz and
    0.5810, in 50 s against the stepper's 0.6 s).
    """
    from foilbearing.rotor import reduced_modes, ross_rotor
    from foilbearing.rotor.nonlinear import RotorOrbitSystem
    from foilbearing.rotor.stepper import run_rotor

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_rigid_symmetric.toml"), "retained")
    speed = 10e3 * RPM
    model = ross_rotor(rotor, [speed - 1e3 * RPM, speed, speed + 1e3 * RPM])
    linear = reduced_modes(model, [0, 2], [speed], n_modes=2)
    k = int(np.argmin(linear.log_decrement[0]))
    f_lin, d_lin = linear.frequency[0, k], linear.log_decrement[0, k]
    system = RotorOrbitSystem(rotor, model, constant_speed(speed, 1.0), n_modes=2)
    y0 = system.initial_state()
    c = rotor.bearings[0].case.bearing.clearance
    y0[system.n_film] += 0.005 * c
    y0[system.n_film + 2] += 0.005 * c
    run = run_rotor(system, 0.15, y0=y0)
    sel = run.time > 0.03
    t, x = run.time[sel], run.journals[0, 0, sel]
    best = None
    for phase in np.linspace(0.0, 2 * math.pi, 6, endpoint=False):
        p0 = [np.ptp(x) / 2, 0.0, 2 * math.pi * f_lin, phase, x.mean()]
        popt, _ = curve_fit(_damped_sine, t, x, p0=p0, maxfev=20_000)
        misfit = float(np.sum((_damped_sine(t, *popt) - x) ** 2))
        if best is None or misfit < best[0]:
            best = (misfit, popt)
    assert best is not None
    _, (_a, sigma, w, _p, _o) = best
    assert w / (2 * math.pi) == pytest.approx(f_lin, rel=0.01)
    assert 2 * math.pi * sigma / w == pytest.approx(d_lin, rel=0.10)


def test_bad_nonlinear_rotor_input_names_the_field() -> None:
    from foilbearing.rotor import ross_rotor
    from foilbearing.rotor.nonlinear import RotorOrbitSystem, Unbalance

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_rigid_symmetric.toml"))
    speed = 40e3 * RPM
    model = ross_rotor(rotor, [speed, speed + 1e3 * RPM], frequencies=[100.0, 1000.0])
    profile = constant_speed(speed, 0.1)
    with pytest.raises(InputError, match=r"unbalance at node 5: the shaft has nodes 0 to 2"):
        RotorOrbitSystem(rotor, model, profile, n_modes=2, unbalances=[Unbalance(5, 1e-6)])
    with pytest.raises(InputError, match=r"voltages: 1 programs for 2 bearings"):
        RotorOrbitSystem(rotor, model, profile, n_modes=2, voltages=[None])
    with pytest.raises(InputError, match=r"n_modes = 99: allowed 0 to"):
        RotorOrbitSystem(rotor, model, profile, n_modes=99)


def test_the_rotor_on_the_orbit_stepper_agrees_with_solve_ivp() -> None:
    """Two integrators of one system: the rotor on the orbit's stepper (each film's compiled
    kernels, the rotor's Schur complement) and solve_ivp's BDF on the same derivative. The
    rigid example with suction retained at 10 krpm, both journals moved by 0.5 % of C:
    within 1 % of the orbit's extent over 50 ms (0.17 % measured)."""
    from foilbearing.rotor import ross_rotor
    from foilbearing.rotor.nonlinear import RotorOrbitSystem
    from foilbearing.rotor.stepper import run_rotor

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_rigid_symmetric.toml"), "retained")
    speed = 10e3 * RPM
    model = ross_rotor(rotor, [speed - 1e3 * RPM, speed], frequencies=[100.0, 1000.0])
    system = RotorOrbitSystem(rotor, model, constant_speed(speed, 0.05), n_modes=2)
    y0 = system.initial_state()
    c = rotor.bearings[0].case.bearing.clearance
    y0[system.n_film] += 0.005 * c
    y0[system.n_film + 2] += 0.005 * c
    fast = run_rotor(system, 0.05, y0=y0)
    reference = RotorIVP(system).run(0.05, y0=y0, atol_factor=1e-2)
    assert fast.status == "completed" and fast.steps > 100
    k = min(fast.time.size, reference.time.size)
    assert np.allclose(fast.time[:k], reference.time[:k])
    extent = np.ptp(reference.journals[0, 0, :k])
    assert np.abs(fast.journals[:, :, :k] - reference.journals[:, :, :k]).max() < 0.01 * extent


def test_rotor_command_runs_the_nonlinear_rotor(tmp_path: Path, write_case, capsys) -> None:  # type: ignore[no-untyped-def]
    # `foilbearing rotor ROTOR.toml --orbit SPEED:DURATION --unbalance ... --out --json`:
    # a 40 ms run of the rigid example on coarse bearings with a 1 g·mm unbalance at its
    # disk. The NetCDF holds each journal's motion: on this symmetric rotor, unbalanced at
    # its middle, both journals move alike (to 1e-3 of the motion). The JSON names the
    # grid, and the largest excursion stays inside the clearance.
    import json

    import xarray as xr

    from foilbearing.cli.main import main

    case = write_case("coarse", n_theta=32, n_z=4)
    text = (EXAMPLES / "rotor_rigid_symmetric.toml").read_text(encoding="utf-8")
    rotor_file = tmp_path / "rotor.toml"
    rotor_file.write_text(text.replace('case = "default"', f'case = "{case.as_posix()}"'))
    out = tmp_path / "run.nc"
    argv = ["rotor", str(rotor_file), "--orbit", "40000rpm:0.04s", "--unbalance",
            "1:1g*mm", "--shaft-modes", "2", "--voltage-ramp", "0.01s:0.02s:150V", "--out", str(out), "--json", "--plot",
            str(tmp_path)]  # fmt: skip
    assert main(argv) == 0
    result = json.loads(capsys.readouterr().out)
    orbit = result["orbit"]
    assert orbit["status"] == "completed" and orbit["grid"] == [[32, 4], [32, 4]]
    c = load_rotor(rotor_file).bearings[0].case.bearing.clearance
    assert 0.0 < orbit["largest_excursion_um"]["bearing A"] < 1e6 * c
    with xr.open_dataset(out) as data:
        assert data["journal"].shape[:2] == (2, 2)
        assert float(data["time"][-1]) == pytest.approx(0.04)
        # symmetric rotor, unbalance at its middle: both journals move alike
        a, b = data["journal"].values
        assert np.abs(a - b).max() < 1e-3 * np.ptp(a)
    assert (tmp_path / "rotor_orbit.png").stat().st_size > 10_000
    # stopped half-way and resumed from its file: the same end, one series
    part = tmp_path / "part.nc"
    argv_part = ["rotor", str(rotor_file), "--orbit", "40000rpm:0.02s", "--shaft-modes", "2",
                 "--stop-time", "0.01s", "--out", str(part), "--json"]  # fmt: skip
    assert main(argv_part) == 0
    stopped = json.loads(capsys.readouterr().out)["orbit"]
    assert stopped["status"] == "stopped" and "--resume" in stopped["advice"]
    assert main(["rotor", "--resume", str(part), "--json"]) == 0
    resumed = json.loads(capsys.readouterr().out)["orbit"]
    assert resumed["status"] == "completed"
    with xr.open_dataset(part) as data:
        assert float(data["time"][-1]) == pytest.approx(0.02)
        assert np.all(np.diff(data["time"].values) > 0)
    assert main(["rotor", "--resume", str(part)]) == 2
    assert "nothing to resume" in capsys.readouterr().err
    assert main(["rotor", str(rotor_file), "--orbit", "40000rpm"]) == 2
    assert "--orbit '40000rpm': write SPEED:DURATION" in capsys.readouterr().err
    assert (
        main(["rotor", str(rotor_file), "--orbit", "4e4rpm:0.01s", "--unbalance", "9:1g*mm"]) == 2
    )
    assert "unbalance at node 9: the shaft has nodes 0 to 2" in capsys.readouterr().err
    assert (
        main(["rotor", str(rotor_file), "--orbit", "4e4rpm:0.01s", "--voltage-ramp", "1s:150V"])
        == 2
    )
    assert "--voltage-ramp '1s:150V': expected T0:T1:V" in capsys.readouterr().err
    both = ["--voltage-ramp", "0s:1s:150V", "--controller", "threshold=1um"]
    assert main(["rotor", str(rotor_file), "--orbit", "4e4rpm:0.01s", *both]) == 2
    assert "give one voltage program" in capsys.readouterr().err
    assert (
        main(["rotor", str(rotor_file), "--orbit", "4e4rpm:0.01s", "--controller", "gain=2"]) == 2
    )
    assert "--controller 'gain=2': expected KEY=VALUE" in capsys.readouterr().err


def test_the_rotor_s_unbalance_orbit_is_the_linear_synchronous_response() -> None:
    """Two methods: the nonlinear rotor's steady 1X orbit (lock-in at the running speed over
    the last 0.1 s of 0.5 s, the free transient decayed) and the receptance of the force
    coefficients, (K + iΩC − mΩ²I)⁻¹ F at Ω, for one bearing carrying half the rigid
    symmetric rotor and half its 0.5 g·mm unbalance. 30 krpm, 32 × 4: within 3 % (1.2 %
    and 1.3 % low along X and Y with the rotor's BDF2 at 48 steps a revolution, 0.9 % and
    0.5 % with BDF3 at 24; an orbit of 0.3 µm, so the film's nonlinearity is small)."""
    from foilbearing.coefficients import force_coefficients
    from foilbearing.rotor.nonlinear import RotorOrbitSystem, Unbalance
    from foilbearing.rotor.stepper import run_rotor
    from foilbearing.static import solve_equilibrium

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_rigid_symmetric.toml"))
    speed, duration, unbalance = 30e3 * RPM, 0.5, 0.5e-6
    profile = constant_speed(speed, duration)
    system = RotorOrbitSystem(rotor, None, profile, n_modes=2, unbalances=[Unbalance(1, unbalance)])
    run = run_rotor(system, duration)
    sel = run.time > duration - 0.1
    t = run.time[sel]
    z = run.journals[0][:, sel]
    z = z - z.mean(axis=1, keepdims=True)
    orbit = np.abs(2 * np.trapezoid(z * np.exp(-1j * speed * t), t, axis=1) / (t[-1] - t[0]))
    case = rotor.loaded_cases()[0]
    fc = force_coefficients(solve_equilibrium(case, speed=speed), speed)
    mass = rotor.mass / 2
    receptance = fc.K[0] + 1j * speed * fc.C[0] - mass * speed**2 * np.eye(2)
    # the unbalance turns with the rotor, from X towards Y: its force is (1, −i) e^{iΩt}
    force = unbalance / 2 * speed**2 * np.array([1.0, -1.0j])
    linear = np.abs(np.linalg.solve(receptance, force))
    assert orbit == pytest.approx(linear, rel=0.03)


@pytest.mark.slow
def test_the_flexible_rotor_on_the_stepper_agrees_with_solve_ivp() -> None:
    """The flexible example at 37.4 krpm, 8 shaft modes, a 1 g·mm unbalance at its heavier
    disk from rest: a violent start that rings the shaft's modes, up to 4.5 kHz with damping
    ratios of 5e-4. The rotor's stepper (BDF2, 48 steps a revolution) follows solve_ivp's
    adaptive BDF within 10 % of the motion's extent over 10 ms (4.4 % measured). BDF3, the
    single bearing's order, is not A-stable and does not: 35 % off at 24 steps a
    revolution, divergent at 48 (those modes' hω falls in its unstable lobe)."""
    from foilbearing.rotor.nonlinear import RotorOrbitSystem, Unbalance
    from foilbearing.rotor.stepper import run_rotor

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_two_disk.toml"))
    speed, duration = 37.4e3 * RPM, 0.01
    system = RotorOrbitSystem(
        rotor, None, constant_speed(speed, duration), n_modes=8, unbalances=[Unbalance(2, 1e-6)]
    )
    fast = run_rotor(system, duration)
    reference = RotorIVP(system).run(duration, atol_factor=1e-2)
    k = min(fast.time.size, reference.time.size)
    extent = np.ptp(reference.journals[:, :, :k], axis=2).max()
    assert np.abs(fast.journals[:, :, :k] - reference.journals[:, :, :k]).max() < 0.1 * extent


def test_a_voltage_ramp_on_the_run_moves_both_journals_to_the_new_equilibrium() -> None:
    """Voltages changed while the rotor runs: both bearings of the rigid example ramp from
    0 to 150 V between 10 and 30 ms at 30 krpm. After 0.25 s each journal sits at the static
    equilibrium of its bearing at 150 V: within 1e-4 C (6e-6 C measured, from 0.645 C at 0 V
    to 0.235 C along the load)."""
    from foilbearing.control import voltage_ramp
    from foilbearing.rotor.nonlinear import RotorOrbitSystem
    from foilbearing.rotor.stepper import run_rotor
    from foilbearing.static import solve_equilibrium

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_rigid_symmetric.toml"))
    speed, duration = 30e3 * RPM, 0.25
    ramp = voltage_ramp(0.01, 0.03, 150.0, initial=0.0)
    profile = constant_speed(speed, duration)
    system = RotorOrbitSystem(rotor, None, profile, n_modes=2, voltages=[ramp, ramp])
    run = run_rotor(system, duration)
    c = rotor.bearings[0].case.bearing.clearance
    last = run.time > duration - 0.05
    for b, case in enumerate(rotor.loaded_cases()):
        start = solve_equilibrium(case.orbit_case(), speed=speed)
        assert run.journals[b, 0, 0] / c == pytest.approx(start.eps_x, abs=1e-9)
        end = solve_equilibrium(case.orbit_case().with_voltages(150.0), speed=speed)
        assert abs(run.journals[b, 0, last].mean() / c - end.eps_x) < 1e-4
        assert abs(run.journals[b, 1, last].mean() / c - end.eps_y) < 1e-4
        assert start.eps_x - end.eps_x > 0.3  # the preload lifts the journal


@pytest.mark.slow
def test_a_controller_on_each_bearing_stops_the_rotor_s_whirl() -> None:
    """The closed loop on a rotor: the rigid example at 48 krpm, above its 0 V onset on this
    grid, both journals moved by 0.2 % of C. The whirl grows from that seed until each
    bearing's controller, reading its own journal's X, sees 1 µm of sub-synchronous motion
    (after more than 0.1 s; 0.33 s measured) and slews its actuators to 150 V. The whirl then
    dies out (its last reading under 0.1 µm; 1.3e-3 µm measured) and each journal comes to
    rest at its bearing's static equilibrium at 150 V (within 1e-3 C; with a controller at
    1000 V/s and 2 µm the whirl reached contact 60 ms after the trigger)."""
    from foilbearing.control import SubsyncController
    from foilbearing.rotor.nonlinear import RotorOrbitSystem
    from foilbearing.rotor.stepper import run_rotor
    from foilbearing.static import solve_equilibrium

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_rigid_symmetric.toml"))
    speed, duration = 48e3 * RPM, 1.0
    controllers = [
        SubsyncController(threshold=1e-6, target=150.0, slew_rate=5000.0, window=0.03,
                          period=0.005)
        for _ in rotor.bearings
    ]  # fmt: skip
    profile = constant_speed(speed, duration)
    system = RotorOrbitSystem(rotor, None, profile, n_modes=2, voltages=controllers)
    y0 = system.initial_state()
    c = rotor.bearings[0].case.bearing.clearance
    y0[system.n_film] += 0.002 * c
    y0[system.n_film + 2] += 0.002 * c
    run = run_rotor(system, duration, y0=y0)
    assert run.status == "completed"
    for b, (controller, case) in enumerate(zip(controllers, rotor.loaded_cases(), strict=True)):
        assert controller.triggered_at is not None and controller.triggered_at > 0.1
        assert np.allclose(controller(duration), 150.0)
        assert controller.amplitude < 1e-7
        end = solve_equilibrium(case.orbit_case().with_voltages(150.0), speed=speed)
        assert abs(run.journals[b, 0, -1] / c - end.eps_x) < 1e-3
    with pytest.raises(InputError, match=r"closed-loop controller reads the run's samples"):
        RotorIVP(system).run(0.01)


def test_a_stopped_rotor_run_resumes_where_it_stopped(tmp_path: Path) -> None:
    """A rotor run stopped at 20 ms, written and read back, then resumed to 40 ms, follows
    the run made in one go: within 1e-3 C at every sample (1.8e-5 C measured: a resumed run
    takes a fresh factor, so it is not the same to round-off), with a voltage ramp crossing
    the stop."""
    from foilbearing.control import voltage_ramp
    from foilbearing.io import write_with
    from foilbearing.rotor.nonlinear import RotorOrbitSystem, load_rotor_orbit
    from foilbearing.rotor.stepper import run_rotor

    rotor = _coarse(load_rotor(EXAMPLES / "rotor_rigid_symmetric.toml"))
    speed, duration = 30e3 * RPM, 0.04
    ramp = voltage_ramp(0.01, 0.03, 150.0, initial=0.0)

    def system() -> RotorOrbitSystem:
        return RotorOrbitSystem(
            rotor, None, constant_speed(speed, duration), n_modes=2, voltages=[ramp, ramp]
        )

    whole = run_rotor(system(), duration)
    first = run_rotor(system(), duration, stop_time=0.02)
    assert first.status == "stopped" and first.resumable
    path = tmp_path / "run.nc"
    write_with(path, first.to_dataset("rotor").to_netcdf)
    saved, _attrs = load_rotor_orbit(path)
    rest = run_rotor(system(), duration, resume=saved)
    assert rest.status == "completed" and not rest.resumable
    assert rest.time.shape == whole.time.shape
    c = rotor.bearings[0].case.bearing.clearance
    np.testing.assert_allclose(rest.journals, whole.journals, atol=1e-3 * c)
    with pytest.raises(InputError, match="nothing to resume"):
        run_rotor(system(), duration, resume=rest)
