"""The orbit's assembly (``orbit.system``), input by input, on a coarse grid (32 x 4).

The imbalance force is checked against the second derivative of the imbalance's position
taken numerically, the preload at running voltages against the film model of the case at
those voltages, the start state against the static equilibrium. They run in seconds:
``make mutation`` runs them against every mutant of ``orbit/system.py``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, default_case
from foilbearing.control import SubsyncController, linear_ramp, voltage_ramp
from foilbearing.errors import InputError
from foilbearing.film import film_model
from foilbearing.orbit import OrbitSettings
from foilbearing.orbit.system import OrbitSimulation
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0


def _coarse(volts: float = 100.0):
    return replace(
        default_case().with_voltages(volts),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
        disturbance=None,
    )


def test_imbalance_force_is_the_imbalance_acceleration() -> None:
    """f = W/m + u (ω² cos φ + ω̇ sin φ, ω² sin φ − ω̇ cos φ): the reaction to the
    acceleration of a point at radius u turning through φ(t), here differentiated twice
    numerically along the speed ramp (to 1e-6); in units of C, per unit mass. Without
    imbalance only the load is left. Λ follows the speed."""
    case = _coarse()
    speed = linear_ramp(10e3 * RPM, 60e3 * RPM, 5000.0)
    sim = OrbitSimulation(case, speed)
    u, c, m = case.rotor.imbalance_radius, case.bearing.clearance, case.rotor.mass
    assert u > 0.0
    volts = sim.volts(0.0)
    for t in (0.0, 0.01, 0.05):
        inp = sim.inputs(t, volts)
        h = 1e-6

        def pos(s: float) -> np.ndarray:
            phi = speed.phase(s)
            return u * np.array([math.cos(phi), math.sin(phi)])

        accel = (pos(t + h) - 2 * pos(t) + pos(t - h)) / (h * h)
        expected = (np.array([case.operation.load / m, 0.0]) - accel) / c
        np.testing.assert_allclose(inp.force, expected, rtol=1e-5, atol=1e-6 * abs(expected).max())
        assert inp.lam == pytest.approx(case.bearing_number(speed.omega(t)), rel=1e-14)
        assert inp.omega == speed.omega(t)
        np.testing.assert_array_equal(inp.preload, sim.preload(volts))
        still = sim.inputs(t, volts, imbalance=False)
        np.testing.assert_allclose(still.force, [case.operation.load / (m * c), 0.0], rtol=1e-15)


def test_preload_follows_the_voltages_as_the_film_model_at_those_voltages() -> None:
    """r_p/C at running voltages (one per actuator, unequal) equals the film model's preload
    of the case set to those voltages; the cached value is reused for the same voltages and
    recomputed for others; a shimmed bearing keeps its shims."""
    case = _coarse(0.0)
    sim = OrbitSimulation(case, linear_ramp(10e3 * RPM, 20e3 * RPM, 5000.0))
    for volts in ((20.0, 80.0, 150.0), (150.0, 0.0, 40.0), (20.0, 80.0, 150.0)):
        got = sim.preload(np.array(volts))
        expected = film_model(case.with_voltages(volts)).preload
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-15)
    a = sim.preload(np.array([50.0, 50.0, 50.0]))
    assert sim.preload(np.array([50.0, 50.0, 50.0])) is a
    shimmed = _coarse(100.0).shimmed()
    sim_s = OrbitSimulation(shimmed, linear_ramp(10e3 * RPM, 20e3 * RPM, 5000.0))
    np.testing.assert_array_equal(sim_s.preload(np.zeros(0)), film_model(shimmed).preload)
    assert sim_s.volts(0.3).shape == (0,)
    assert sim_s.n_act == 0 and sim_s.lobes.shape == (0, 32)
    assert sim.n_act == 3 and sim.lobes.shape == (3, 32)


def test_voltages_from_the_case_a_program_or_a_controller() -> None:
    """Without a program the case's voltages; a one-column program applies to every
    actuator; a per-actuator program its own; a controller its applied voltage."""
    case = replace(_coarse(), actuators=replace(_coarse().actuators, voltages=(10.0, 20.0, 30.0)))
    prof = linear_ramp(10e3 * RPM, 20e3 * RPM, 5000.0)
    np.testing.assert_array_equal(OrbitSimulation(case, prof).volts(0.1), [10.0, 20.0, 30.0])
    one = OrbitSimulation(case, prof, voltage_ramp(0.0, 1.0, 100.0))
    np.testing.assert_allclose(one.volts(0.5), [50.0, 50.0, 50.0], rtol=1e-14)
    each = OrbitSimulation(case, prof, voltage_ramp(0.0, 1.0, [100.0, 50.0, 0.0]))
    np.testing.assert_allclose(each.volts(0.5), [50.0, 25.0, 0.0], rtol=1e-14)
    ctrl = OrbitSimulation(case, prof, SubsyncController(initial=12.0))
    np.testing.assert_array_equal(ctrl.volts(0.0), [12.0, 12.0, 12.0])


def test_start_state_is_the_static_equilibrium_at_the_start() -> None:
    """P, the bump deflection U = c_b max(p̄ − 1, 0) and ε are the static equilibrium's at
    the initial speed and voltages, with the journal at rest; a rigid bearing has no U."""
    case = _coarse(0.0)
    prof = linear_ramp(30e3 * RPM, 40e3 * RPM, 5000.0)
    sim = OrbitSimulation(case, prof, voltage_ramp(0.5, 1.0, 150.0, initial=60.0))
    y0 = sim.initial_state()
    st = solve_equilibrium(case.with_voltages(60.0), speed=30e3 * RPM)
    sys_ = sim.system
    assert y0.shape == (sys_.size,)
    np.testing.assert_allclose(y0[: sys_.n], st.P.ravel(), rtol=1e-10)
    u = sys_.c_bump * np.maximum(st.P.mean(axis=1) - 1.0, 0.0)
    np.testing.assert_allclose(y0[sys_.n : -4], u, rtol=1e-8, atol=1e-14)
    assert np.any(u > 0)
    np.testing.assert_allclose(y0[-4:], [st.eps_x, st.eps_y, 0.0, 0.0], rtol=1e-9, atol=1e-15)
    rigid = replace(case, foil=None, actuators=None)
    sim_r = OrbitSimulation(rigid, prof)
    y_r = sim_r.initial_state()
    assert y_r.size == sim_r.system.size
    np.testing.assert_array_equal(y_r[sim_r.system.n : -4], 0.0)


def test_system_scales_and_tolerances() -> None:
    """σ = 12 μ R²/(p_a C²) (the squeeze number per unit frequency), the film force per unit
    mass in C, the foil's compliances and loss factor as the film model's; absolute
    tolerances by part of the state and the error weights 1/(atol + rtol |y|)."""
    case = _coarse()
    prof = linear_ramp(10e3 * RPM, 20e3 * RPM, 5000.0)
    settings = OrbitSettings(rtol=1e-3, atol_pressure=2e-5, atol_position=1e-4)
    sim = OrbitSimulation(case, prof, settings=settings)
    b, gas, m = case.bearing, case.gas, case.rotor.mass
    sys_ = sim.system
    assert sys_.sigma == pytest.approx(
        12 * gas.viscosity * b.radius**2 / (gas.ambient_pressure * b.clearance**2), rel=1e-14
    )
    assert sys_.force_scale == pytest.approx(
        gas.ambient_pressure * b.radius**2 / (m * b.clearance), rel=1e-14
    )
    model = film_model(case)
    np.testing.assert_array_equal(sys_.c_bump, model.bump_compliance)
    np.testing.assert_array_equal(sys_.c_act, model.actuator_compliance)
    assert sys_.gamma == case.foil.loss_factor  # type: ignore[union-attr]
    assert sys_.dynamic_bump and sys_.lift_off is True
    atol = sim.atol()
    n = sys_.n
    np.testing.assert_array_equal(atol[:n], 2e-5)
    np.testing.assert_array_equal(atol[n:-2], 1e-4)
    np.testing.assert_allclose(atol[-2:], 1e-4 * 20e3 * RPM, rtol=1e-14)
    y = np.linspace(-2.0, 2.0, sys_.size)
    np.testing.assert_allclose(sim.weights(y), 1.0 / (atol + 1e-3 * np.abs(y)), rtol=1e-15)
    rigid = OrbitSimulation(replace(case, foil=None, actuators=None), prof)
    assert rigid.system.gamma == 0.0 and rigid.system.lift_off is False


def test_bad_programs_are_one_line_errors() -> None:
    case = _coarse()
    prof = linear_ramp(10e3 * RPM, 20e3 * RPM, 5000.0)
    rigid = replace(case, foil=None, actuators=None)
    with pytest.raises(InputError) as err:
        OrbitSimulation(rigid, prof, voltage_ramp(0.0, 1.0, 100.0))
    assert str(err.value) == "a voltage program needs a case with [actuators]"
    with pytest.raises(InputError) as err:
        OrbitSimulation(case, prof, voltage_ramp(0.0, 1.0, [100.0, 50.0]))
    assert str(err.value) == "voltage program has 2 columns; the case has 3 actuators"
    with pytest.raises(InputError) as err:
        OrbitSimulation(case, prof, voltage_ramp(0.0, 1.0, 200.0))
    assert "allowed 0 to 150 V (max_voltage)" in str(err.value)


def test_no_start_equilibrium_is_a_solver_error_saying_what_to_try() -> None:
    from foilbearing.errors import SolverError

    rigid = replace(_coarse(), foil=None, actuators=None)
    heavy = replace(rigid, operation=replace(rigid.operation, load=200.0))
    sim = OrbitSimulation(heavy, linear_ramp(2e3 * RPM, 3e3 * RPM, 5000.0))
    with pytest.raises(SolverError) as err:
        sim.initial_state()
    text = str(err.value)
    assert text.startswith("no static equilibrium at the start of the run: equilibrium not found")
    assert text.endswith("; start the run at a higher speed or a lower load")


def test_the_stepper_problem_is_the_simulation_seen_through_callables() -> None:
    """``problem()`` hands the stepper the system's callables and arrays: the inputs and
    voltages at t, the storage and factorisation of the system, the tolerances, the
    journal's index; the closed-loop program observes e_X at the phase of the profile and
    its checkpoint follows the run's. The settings come apart by role, field for field."""
    from foilbearing.orbit.problem import RunStats
    from foilbearing.orbit.result import RunStatus
    from foilbearing.orbit.sampling import Samples

    case = _coarse()
    prof = linear_ramp(10e3 * RPM, 20e3 * RPM, 5000.0)
    settings = OrbitSettings(rtol=1e-3, atol_position=1e-4, steps_per_rev=30, max_newton=7)
    sim = OrbitSimulation(case, prof, voltage_ramp(0.5, 1.0, 150.0, initial=60.0), settings)
    pb, sys_ = sim.problem(), sim.system
    assert (pb.size, pb.t_end, pb.journal) == (sys_.size, prof.duration, sys_.n + sys_.nt)
    assert pb.clearance == case.bearing.clearance and pb.speed(0.7) == prof.omega(0.7)
    inp, volts = pb.inputs(0.75)
    np.testing.assert_array_equal(volts, sim.volts(0.75))
    ref = sim.inputs(0.75, sim.volts(0.75))
    assert (inp.lam, inp.omega) == (ref.lam, ref.omega)
    np.testing.assert_array_equal(inp.force, ref.force)
    np.testing.assert_array_equal(inp.preload, ref.preload)
    y = sim.initial_state()
    np.testing.assert_array_equal(pb.storage(y, inp), sys_.storage(y, inp))
    assert pb.lift_slack is sys_._slack and pb.atol is sim.atol()
    assert pb.observe is None and pb.program_checkpoint() == {}
    out = Samples(1e-4)
    pb.record(out, 0.0, y, volts, inp, None)
    pb.record(out, 2e-4, y, volts, inp, 0.5)
    assert out.t == [0.0, 2e-4] and out.h_min[1] == 0.5 * case.bearing.clearance
    stats = RunStats(0.0, 3, 2, 9, None, {"t": 2e-4})
    res = pb.make_result(out, RunStatus.STOPPED, "stopped", stats)
    assert (res.steps, res.factorizations, res.newton_iterations) == (3, 2, 9)
    assert res.status == "stopped" and res.message == "stopped"
    # The checkpoint: the stepper's, and where the power loss's 1 ms evaluations stand.
    power = {"power_next": 1e-3, "power_last_t": 0.0, "power_last": out.power[0]}
    assert res.checkpoint == {"t": 2e-4, **power}
    assert res.settings is settings and res.case is case and res.time.size == 3

    ctrl = SubsyncController(initial=12.0)
    closed = OrbitSimulation(case, prof, ctrl).problem()
    assert closed.observe is not None and closed.program_checkpoint() == ctrl.checkpoint()
    closed.observe(0.25, 1e-6)
    assert list(ctrl._samples)[-1] == (0.25, 1e-6, prof.phase(0.25))

    step, newton = settings.step_rule, settings.newton_rule
    assert (step.steps_per_rev, step.order, step.max_step) == (30, 3, 1e-3)
    assert (newton.newton_tol, newton.newton_fraction, newton.max_newton, newton.rtol) == (
        0.3,
        0.001,
        7,
        1e-3,
    )
    assert settings.sampling.sample_rate == 10_000.0
    assert settings.stop_rule() == settings.stop_rule(None)
    assert (settings.stop_rule(0.2).contact_film, settings.stop_rule(0.2).stop_time) == (0.005, 0.2)


def test_a_fresh_factor_after_slow_steps_gives_the_same_orbit() -> None:
    """``refresh_after`` changes which factor each Newton iteration uses, not what it
    converges to: with a fresh factor every step (0) or after slow steps (4), 8.5 g·mm at
    20 krpm on 32 x 4 is today's orbit to 1e-3 of its extent (the Newton tolerance), and the
    fresh factors take fewer iterations a step; a negative count is a one-line error."""
    from foilbearing.control import constant_speed
    from foilbearing.orbit import simulate

    case = _coarse(0.0)
    speed = constant_speed(20e3 * RPM, 0.01)
    kept = simulate(case, speed)
    extent = np.ptp(kept.e_x)
    for after in (0, 4):
        fresh = simulate(case, speed, settings=OrbitSettings(refresh_after=after))
        assert np.max(np.abs(fresh.e_x - kept.e_x)) < 1e-3 * extent
        assert np.max(np.abs(fresh.e_y - kept.e_y)) < 1e-3 * np.ptp(kept.e_y)
        assert fresh.newton_iterations < kept.newton_iterations
    every = simulate(case, speed, settings=OrbitSettings(refresh_after=0))
    assert every.factorizations >= every.steps
    with pytest.raises(InputError, match="refresh_after = -1: an iteration count >= 0"):
        simulate(case, speed, settings=OrbitSettings(refresh_after=-1))
