"""The derivative of an orbit run with respect to its start state (the BDF steps' own
variational equations, :mod:`foilbearing.orbit.tangent`), against two independent routes:
finite differences of the run, and the semi-discrete system's eigenvalues."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.bifurcation.bearing import SHOOTING_SETTINGS, _hopf_eigenvector, bearing_flow
from foilbearing.case import Grid, default_case
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSettings, OrbitSimulation
from foilbearing.orbit.sampling import Samples
from foilbearing.orbit.stepper import State, run
from foilbearing.orbit.tangent import run_tangent
from foilbearing.stability import whirl_mode
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0


def _case(subambient: str, smoothing: float = 0.0):
    grid = Grid(
        n_theta=32, n_z=4, lift_off_smoothing=smoothing, orbit_n_z=None, orbit_axial_order=None
    )
    case = replace(default_case(), grid=grid, disturbance=None)
    case = case.with_subambient(subambient)
    return replace(case, rotor=replace(case.rotor, imbalance=0.0))


def _sim(case, speed: float) -> OrbitSimulation:
    settings = OrbitSettings(**SHOOTING_SETTINGS)
    return OrbitSimulation(case, constant_speed(speed, 1e3), settings=settings)


def _end(sim: OrbitSimulation, y: np.ndarray, duration: float) -> np.ndarray:
    s = sim.settings
    res = run(
        sim.problem(), State(0.0, y.copy()), Samples(1e-4), s.step_rule, s.newton_rule,
        s.stop_rule(duration),
    )  # fmt: skip
    return np.asarray(res.checkpoint["y"], float)


@pytest.mark.parametrize(
    ("subambient", "smoothing", "tol"),
    [("retained", 0.0, 2e-4), ("lift-off", 0.2, 1e-2)],
    ids=["retained", "smoothed"],
)
def test_run_derivative_equals_central_differences_of_the_run(
    subambient: str, smoothing: float, tol: float
) -> None:
    # On a smooth flow (suction retained, or lift-off under the smoothed law) the
    # variational equations of the steps the run took are the derivative of its end
    # state: central differences of whole runs agree to their own truncation (measured
    # 4e-6 to 5e-5 at steps of 1e-3 to 1e-4 with suction retained). Under the smoothed
    # law the runs' step choices scatter the differences more (measured 1e-4 to 4e-3 of
    # the derivative at steps of 1e-2 to 1e-5); a film row's history enters times α, and
    # without it the derivative is off by 138 % at every step.
    sim = _sim(_case(subambient, smoothing), 45e3 * RPM)
    y0 = sim.initial_state()
    y0[sim.system.n + sim.system.nt] += 0.01  # off the equilibrium: a whirl under way
    duration = 1.0 / 59.0
    tangent = run_tangent(sim, y0, duration)
    assert tangent is not None
    np.testing.assert_array_equal(tangent.end, _end(sim, y0, duration))
    rng = np.random.default_rng(1)
    block = rng.standard_normal((y0.size, 3))
    exact = tangent.apply(block)
    # one direction (the compiled solve) and a block (one block solve) agree to round-off
    np.testing.assert_allclose(tangent.apply(block[:, 0]), exact[:, 0], rtol=1e-9, atol=1e-12)
    # The block products of the storage Jacobian are the sparse matrix's.
    y_mid = tangent.result.checkpoint["y"]
    inputs = sim.inputs(0.0, sim.volts(0.0), imbalance=False)
    mq = sim.system.storage_jacobian(y_mid, inputs.preload)
    np.testing.assert_allclose(
        sim.system.storage_operator(y_mid, inputs.preload)(block), mq @ block, rtol=1e-12
    )
    for k in range(3):
        v = block[:, k] / np.linalg.norm(block[:, k])
        h = 1e-3
        fd = (_end(sim, y0 + h * v, duration) - _end(sim, y0 - h * v, duration)) / (2 * h)
        ex = exact[:, k] / np.linalg.norm(block[:, k])
        assert np.linalg.norm(fd - ex) < tol * np.linalg.norm(ex)


@pytest.mark.parametrize("subambient", ["lift-off", "retained"])
def test_monodromy_at_rest_is_the_exponential_of_the_whirl_eigenvalue(subambient: str) -> None:
    # At the equilibrium the run's derivative over T is exp(A T) of the semi-discrete
    # system, as BDF3 at 24 steps a revolution integrates it: its multiplier nearest the
    # whirl's must be exp(λ T), λ the generalised eigenvalue of the system's own Jacobian
    # and storage matrix (an independent route), to the step's error (measured at 30 krpm,
    # 32 x 4: 6.5e-5 under lift-off, multiplier 0.958; 8.2e-5 with suction retained, 7.77).
    # Under lift-off the held cells stay held: the derivative with the equilibrium's branches.
    case = _case(subambient)
    speed = 30e3 * RPM
    st = solve_equilibrium(case, speed=speed)
    mode = whirl_mode(st, case.rotor.mass)
    _flow, parts = bearing_flow(case, mode.whirl_frequency, 1e-4)
    value, _vector = _hopf_eigenvector(parts, speed, mode.whirl_frequency)
    sim = parts.simulation(speed)
    period = 2.0 * math.pi / abs(value.imag)
    tangent = run_tangent(sim, sim.initial_state(), period)
    assert tangent is not None
    multipliers = np.linalg.eigvals(tangent.apply(np.eye(sim.system.size)))
    expected = np.exp(value * period)
    nearest = multipliers[np.argmin(np.abs(multipliers - expected))]
    assert abs(nearest - expected) < 5e-4 * abs(expected)
    # ... and the largest multiplier is the whirl's: stable at rest below the onset or not
    assert np.max(np.abs(multipliers)) == pytest.approx(abs(nearest), rel=1e-9)


def test_step_weights_are_the_bdf_formulas() -> None:
    # The variational equation takes the stepper's own coefficients: constant-step BDF2,
    # (3 Q_{n+1} − 4 Q_n + Q_{n−1}) / (2h) = f, and BDF1, (Q_{n+1} − Q_n) / h = f.
    from foilbearing.orbit.tangent import _weights

    h = 1e-4
    c0, w = _weights(1.0, [1.0 - h, 1.0 - 2 * h])
    assert c0 == pytest.approx(1.5 / h, rel=1e-9)
    np.testing.assert_allclose(w, [-2.0 / h, 0.5 / h], rtol=1e-9)
    c0, w = _weights(1.0, [1.0 - h])
    assert c0 == pytest.approx(1.0 / h, rel=1e-9) and w[0] == pytest.approx(-1.0 / h, rel=1e-9)
