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

pytest.importorskip("ross", minversion="3.0")

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _coarse(rotor: RotorCase, subambient: str | None = None) -> RotorCase:
    """The rotor with each bearing on the 32 × 4 grid (static, linear and orbit alike)."""
    bearings = []
    for b in rotor.bearings:
        case = replace(b.case, grid=Grid(32, 4))
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
    y0 = system.initial_state()
    assert np.abs(system.derivative(0.0, y0)[-system.m :]).max() < 1e-6
    values = np.linalg.eigvals(_jacobian(lambda y: system.derivative(0.0, y), y0))
    for f, d in zip(linear.frequency[0], linear.log_decrement[0], strict=True):
        w = 2 * math.pi * f
        s = values[np.argmin(np.abs(values - complex(-d * f, w)))]
        assert s.imag / (2 * math.pi) == pytest.approx(f, rel=2e-3)
        assert -2 * math.pi * s.real / s.imag == pytest.approx(d, abs=5e-3)
    assert linear.log_decrement[0].min() < 0.01  # near the onset: one mode barely damped


def _damped_sine(t, a, sigma, w, phase, offset):  # type: ignore[no-untyped-def]
    return a * np.exp(-sigma * t) * np.cos(w * t + phase) + offset


@pytest.mark.slow
def test_free_whirl_of_the_nonlinear_rotor_is_its_linear_mode() -> None:
    """The rigid example with suction retained, 10 krpm: both journals moved by 0.5 % of
    the clearance along ROSS's x; the run's motion, fitted by one damped sine after 30 ms
    (the other modes have decayed), whirls at the frequency of the linear analysis' least
    damped mode within 1 % and decays with its log decrement within 10 % (measured 41.92
    against 42.00 Hz, 0.581 against 0.599: the linear analysis takes each mode's coefficients
    at its real whirl frequency, which a decrement of 0.6 makes a few per cent approximate).
    """
    from foilbearing.rotor import reduced_modes, ross_rotor
    from foilbearing.rotor.nonlinear import RotorOrbitSystem

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
    run = system.run(0.15, y0=y0, atol_factor=1e-2)
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
    reference = system.run(0.05, y0=y0, atol_factor=1e-2)
    assert fast.status == "completed" and fast.steps > 100
    k = min(fast.time.size, reference.time.size)
    assert np.allclose(fast.time[:k], reference.time[:k])
    extent = np.ptp(reference.journals[0, 0, :k])
    assert np.abs(fast.journals[:, :, :k] - reference.journals[:, :, :k]).max() < 0.01 * extent
