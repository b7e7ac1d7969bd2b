"""The actuator in the film, four readings (docs/model.md §3.8): one law in the static and
linear analyses, each checked against an independent route."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, default_case, load_case
from foilbearing.coefficients import force_coefficients
from foilbearing.errors import InputError
from foilbearing.paper import PAPER
from foilbearing.reynolds import film_force, solve_steady
from foilbearing.stability import onset_speed
from foilbearing.static import film_at_position, solve_equilibrium

RPM = math.pi / 30.0
READINGS = [
    ("local", "compliant"),
    ("local", "held"),
    ("lobe", "compliant"),
    ("lobe", "held"),
]


def reading_case(response: str, dynamics: str, volts: float = 150.0, grid=(48, 6)):
    """The default case at ``volts`` under one reading, undamped foil, on a coarse grid."""
    case = default_case().with_voltages(volts).with_actuator_reading(response, dynamics)
    assert case.foil is not None
    return replace(
        case,
        foil=replace(case.foil, loss_factor=0.0),
        grid=Grid(
            n_theta=grid[0],
            n_z=grid[1],
            lift_off_smoothing=0.0,
            orbit_n_z=None,
            orbit_axial_order=None,
        ),
    )


def held_force(st, eps_x: float, eps_y: float) -> np.ndarray:
    """The film force (N) at a journal position with every stack frozen at its compression
    in ``st``: a pocket (``local``) or lowered lobes (``lobe``) become part of the rigid
    film, and only the bump deflects. Solved by the plain steady solver, not the bordered
    Newton of the static analysis."""
    m = st.model
    q = np.maximum(st.P.mean(axis=1) - 1.0, 0.0)
    h_r = m.h_rigid_loaded(eps_x, eps_y, m.stack_compression(st.P))
    h_r = h_r + (m.actuator_compliance * q)[:, None]
    sol = solve_steady(m.grid, h_r, m.bump_compliance, st.bearing_number, st.P, lift_off=True)
    assert sol.converged
    fx, fy = film_force(m.grid, sol.P)
    scale = st.case.gas.ambient_pressure * st.case.bearing.radius**2
    return np.array([fx, fy]) * scale


@pytest.mark.parametrize(("response", "dynamics"), READINGS)
def test_zero_frequency_stiffness_is_the_derivative_of_the_static_force(
    response: str, dynamics: str
) -> None:
    # As ν -> 0 (γ = 0) K must equal the finite-difference derivative of the static film
    # force under the same law: with the stacks following the pressure (compliant) or
    # frozen at their equilibrium compression (held, an independent steady solve).
    case = reading_case(response, dynamics)
    st = solve_equilibrium(case, speed=50e3 * RPM)
    assert st.converged
    k = force_coefficients(st, 1e-6 * st.speed).K[0]
    d, c = 1e-5, case.bearing.clearance
    k_fd = np.zeros((2, 2))
    for j, (dx, dy) in enumerate(((d, 0.0), (0.0, d))):
        if dynamics == "compliant":
            fp, fm = (
                np.array(film_at_position(case, st.eps_x + s * dx, st.eps_y + s * dy).force)
                for s in (1, -1)
            )
        else:
            fp, fm = (held_force(st, st.eps_x + s * dx, st.eps_y + s * dy) for s in (1, -1))
        k_fd[:, j] = -(fp - fm) / (2 * d * c)
    np.testing.assert_allclose(k, k_fd, rtol=1e-3, atol=1e-3 * np.abs(k_fd).max())


def test_the_readings_differ_where_the_stack_is_compliant() -> None:
    # The held stiffness is the compliant one less the stacks' response: for a compliant
    # stack the readings must differ, or the option would change nothing (measured: K_XX
    # 15-60 % apart at 150 V, 50 krpm).
    ks = {}
    for r in READINGS:
        st = solve_equilibrium(reading_case(*r), speed=50e3 * RPM)
        ks[r] = force_coefficients(st, 0.1 * st.speed).K[0]
    for resp in ("local", "lobe"):
        held, compliant = ks[resp, "held"], ks[resp, "compliant"]
        assert abs(held[0, 0] - compliant[0, 0]) > 0.05 * abs(held[0, 0])


@pytest.mark.parametrize(("response", "dynamics"), READINGS)
def test_an_infinitely_stiff_stack_is_the_shimmed_bearing(response: str, dynamics: str) -> None:
    # With k_p -> ∞ the stack neither shortens nor yields: every reading must give the
    # shimmed GFB with shims as thick as the base preloads (k = k_b everywhere).
    case = reading_case(response, dynamics)
    act = case.actuators
    assert act is not None
    stiff = replace(case, actuators=replace(act, stack_stiffness=act.stack_stiffness * 1e9))
    shimmed = stiff.shimmed()
    st, ref = (solve_equilibrium(c, speed=50e3 * RPM) for c in (stiff, shimmed))
    assert st.converged and ref.converged
    assert abs(st.eps_x - ref.eps_x) < 1e-6 and abs(st.eps_y - ref.eps_y) < 1e-6
    np.testing.assert_allclose(st.preload, ref.preload, atol=1e-12)
    k, kr = (force_coefficients(s, 0.1 * s.speed) for s in (st, ref))
    np.testing.assert_allclose(k.K, kr.K, rtol=1e-5, atol=1e-5 * np.abs(kr.K).max())
    np.testing.assert_allclose(k.C, kr.C, rtol=1e-5, atol=1e-5 * np.abs(kr.C).max())


def test_lobe_equilibrium_lowers_each_lobe_by_the_stack_compression() -> None:
    # Under "lobe" the film at θ_n is the base lobe lowered by p_A(θ_n)/(k_p + 4k_sp)
    # (Eq. 3b), with the bump's deflection on top; the force balances the load.
    case = default_case().with_voltages(150.0).with_actuator_reading("lobe")
    st = solve_equilibrium(case, speed=90e3 * RPM)
    assert st.converged and st.force_residual < 1e-8
    assert abs(st.force[0] + case.operation.load) < 1e-6 * case.operation.load
    m = st.model
    c = case.bearing.clearance
    q = st.P.mean(axis=1) - 1.0
    base = np.asarray(m.base_preloads)
    lowered = (base - st.preload) / c  # the stacks' compression, units of C
    pa = case.gas.ambient_pressure
    np.testing.assert_allclose(
        lowered, pa * np.maximum(m.at_angles(q, m.preload_angles), 0) / (c * m.actuator_stiffness)
    )
    r_p = (base / c) @ m.lobe_shapes - lowered @ m.lobe_shapes
    th = m.grid.theta
    h = (
        1
        + st.eps_x * np.cos(th)
        + st.eps_y * np.sin(th)
        - r_p
        + m.bump_compliance * np.maximum(q, 0)
    )
    np.testing.assert_allclose(st.H[:, 0], h, rtol=1e-12)


def test_lobe_preloads_beside_the_papers() -> None:
    # Fig. 11 (150 V, 90 krpm): the paper's 65.36 / 54.06 / 64.62 um. Measured under "lobe"
    # 68.12 / 54.54 / 68.08 um (+4.2 / +0.9 / +5.4 %), under "local" 66.06 / 54.92 / 65.22;
    # asserted within 6 %: μ is assumed and the paper's own model differs in detail.
    paper = np.asarray(PAPER["preload_150V_90krpm_um"])
    for response, tol in (("lobe", 0.06), ("local", 0.02)):
        case = default_case().with_voltages(150.0).with_actuator_reading(response)
        st = solve_equilibrium(case, speed=90e3 * RPM)
        ours = st.preload * 1e6
        print(response, np.round(ours, 2), "paper", paper, np.round(100 * (ours / paper - 1), 1))
        np.testing.assert_allclose(ours, paper, rtol=tol)


def test_the_positioner_reading_raises_the_onset_at_150_V() -> None:
    # The design question (docs/model.md §3.8): held lobes keep the film's stiffness at the
    # lobes, where a compliant stack gives it up. On the 48 × 6 grid the 150 V onset must
    # rise from local-compliant to lobe-held, and lie below the shimmed GFB's (the ideal
    # positioner at the base stroke, which lobe-held tends to as k_p -> ∞).
    speeds = [rpm * RPM for rpm in range(30_000, 120_001, 10_000)]
    on = {r: onset_speed(reading_case(*r), speeds).onset_speed for r in (READINGS[0], READINGS[3])}
    shim = onset_speed(reading_case("local", "compliant").shimmed(), speeds).onset_speed
    assert on[READINGS[0]] is not None and on[READINGS[3]] is not None and shim is not None
    assert on[READINGS[0]] < 0.8 * on[READINGS[3]] < 0.8 * shim


def test_a_reading_outside_the_allowed_values_is_a_one_line_error() -> None:
    with pytest.raises(InputError, match=r"preload_response = 'pocket': expected one of"):
        default_case().with_actuator_reading(preload_response="pocket")
    with pytest.raises(InputError, match=r"dynamics = 'frozen': expected one of"):
        default_case().with_actuator_reading(dynamics="frozen")
    with pytest.raises(InputError, match=r"no \[actuators\]"):
        default_case().shimmed().with_actuator_reading(dynamics="held")


def test_the_orbit_refuses_held_stingers_under_a_controller() -> None:
    from foilbearing.control import SubsyncController, constant_speed
    from foilbearing.orbit import OrbitSimulation

    prof = constant_speed(20e3 * RPM, 0.01)
    held = default_case().with_actuator_reading("local", "held")
    with pytest.raises(InputError, match="closed-loop controller"):
        OrbitSimulation(held, prof, SubsyncController())


def orbit_case(response: str, dynamics: str, volts: float = 150.0, imbalance: float = 0.0):
    """The default case under a reading on the 32 × 4 grid, deterministic (no disturbance)."""
    case = default_case().with_voltages(volts).with_actuator_reading(response, dynamics)
    case = replace(
        case,
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
        disturbance=None,
    )
    return replace(case, rotor=replace(case.rotor, imbalance=imbalance))


@pytest.mark.parametrize(
    ("response", "dynamics"), [("local", "held"), ("lobe", "held"), ("lobe", "compliant")]
)
def test_free_whirl_matches_the_linear_eigenvalue(response: str, dynamics: str) -> None:
    # One law in both analyses: the orbit's small free motion whirls at the frequency and
    # decays with the log decrement of the linear analysis under the same reading
    # (measured at 150 V, 15 krpm: local + held 163.9 Hz against 164.3, decrement 0.66
    # against 0.64; lobe + held 165.3 against 164.8, 0.63 against 0.60; lobe + compliant,
    # the lobes following their stacks inside the film, 97.1 against 97.1, 0.283 against
    # 0.271). At rest the journal stays at its equilibrium: the held input is the static
    # film's compression, and the compliant lobes' law is the static one.
    from scipy.signal import find_peaks

    from foilbearing.control import constant_speed
    from foilbearing.orbit import OrbitSettings, OrbitSimulation
    from foilbearing.orbit.sampling import Samples
    from foilbearing.orbit.stepper import State, run
    from foilbearing.stability import whirl_mode

    case = orbit_case(response, dynamics)
    speed = 15e3 * RPM
    mode = whirl_mode(solve_equilibrium(case, speed=speed), case.rotor.mass)
    sim = OrbitSimulation(
        case, constant_speed(speed, 0.12), settings=OrbitSettings(steps_per_rev=32)
    )
    s = sim.settings
    y0 = sim.initial_state()
    rest = run(
        sim.problem(),
        State(0.0, y0.copy()),
        Samples(1e-4),
        s.step_rule,
        s.newton_rule,
        s.stop_rule(),
    )
    assert np.max(np.abs(rest.e_x - rest.e_x[0])) < 1e-9 * case.bearing.clearance
    y0[sim.system.n + sim.system.nt] += 0.002
    res = run(
        sim.problem(), State(0.0, y0), Samples(1e-4), s.step_rule, s.newton_rule, s.stop_rule()
    )
    x = res.e_x - res.e_x[-200:].mean()
    peaks, _ = find_peaks(x, distance=20)
    freq = 1.0 / np.median(np.diff(res.time[peaks]))
    amp = x[peaks][x[peaks] > 0.02 * x[peaks][0]]
    dec = np.median(np.log(amp[:-1] / amp[1:]))
    assert freq == pytest.approx(mode.whirl_frequency / (2 * math.pi), rel=0.01)
    assert dec == pytest.approx(mode.log_decrement, rel=0.1)


@pytest.mark.parametrize(
    ("response", "dynamics"), [("local", "held"), ("lobe", "held"), ("lobe", "compliant")]
)
def test_the_stingers_follow_a_voltage_ramp_as_the_reference_integrator_does(
    response: str, dynamics: str
) -> None:
    # The held input moves with the voltage, and compliant lobes move with the voltage and
    # the film: the fast stepper and solve_ivp's BDF (the projected-dynamics reference, its
    # own elimination of the lobes' rates) must give the same orbit while the voltage
    # ramps from 100 to 150 V under 1 g·mm, within 1 % of its extent (measured under
    # lobe + compliant: 0.006 %).
    from foilbearing.control import constant_speed, voltage_ramp
    from foilbearing.orbit import OrbitSettings, OrbitSimulation, simulate
    from foilbearing.testing.ivp_orbit import reference_orbit

    case = orbit_case(response, dynamics, volts=100.0, imbalance=1e-6)
    prof = constant_speed(20e3 * RPM, 0.01)
    ramp = voltage_ramp(0.002, 0.008, 150.0, initial=100.0)
    settings = OrbitSettings(steps_per_rev=96, sample_rate=20_000)
    fast = simulate(case, prof, ramp, settings=settings)
    sim = OrbitSimulation(case, prof, ramp, settings=settings)
    ref = reference_orbit(sim, 0.01, rtol=1e-6, atol=1e-8)
    assert fast.status == "completed" and ref["success"]
    if dynamics == "held":
        assert sim.held is not None and len(sim.held.times) > 10  # knots along the ramp
    else:
        assert sim.held is None and sim.system.n_lobe == 3  # the lobes' border
    for ours, theirs in ((fast.e_x, ref["e_x"]), (fast.e_y, ref["e_y"])):
        assert np.max(np.abs(ours - theirs)) < 0.01 * np.ptp(theirs)


def test_the_orbit_of_an_infinitely_stiff_stack_is_the_shimmed_bearings() -> None:
    # A rigid stack neither shortens nor yields: under every reading the orbit integrates,
    # the C-GFB's orbit must be the shimmed GFB's (shims at the base preload) on the same run.
    from foilbearing.control import constant_speed
    from foilbearing.orbit import simulate

    for response, dynamics in READINGS:
        case = orbit_case(response, dynamics, imbalance=1e-6)
        act = case.actuators
        assert act is not None
        stiff = replace(case, actuators=replace(act, stack_stiffness=act.stack_stiffness * 1e9))
        prof = constant_speed(20e3 * RPM, 0.01)
        ours, shim = simulate(stiff, prof), simulate(stiff.shimmed(), prof)
        assert np.max(np.abs(ours.e_x - shim.e_x)) < 1e-4 * np.ptp(shim.e_x)


def test_the_cli_takes_the_reading_and_refuses_bad_values(write_case, capsys) -> None:
    import json

    from foilbearing.cli.main import main

    path = write_case("coarse", n_theta=48, n_z=6)
    args = ["static", str(path), "--speed", "90000rpm", "--voltage", "150V", "--json"]
    assert main([*args, "--preload-response", "lobe", "--actuator-dynamics", "held"]) == 0
    out = json.loads(capsys.readouterr().out)
    case = reading_case("lobe", "held", grid=(48, 6))
    case = replace(case, foil=default_case().foil, grid=load_case(path).grid)
    st = solve_equilibrium(case, speed=90e3 * RPM)
    np.testing.assert_allclose(out["preload_um"], st.preload * 1e6, rtol=1e-9)
    assert main([*args, "--preload-response", "pocket"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "actuators.preload_response = 'pocket'" in err[0]
    # The orbit takes every reading and says which one made the run.
    orbit = ["orbit", str(path), "--speed-ramp", "20000rpm:20500rpm:500rad/s**2", "--json"]
    assert main([*orbit, "--preload-response", "lobe", "--actuator-dynamics", "compliant"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "completed" and out["actuator_reading"] == "lobe+compliant"

    def no_actuators(data) -> None:
        data["shims"] = {"angles": ["60 deg"], "arc": "27.7 deg", "thickness": "20 um"}
        del data["actuators"]

    shimmed = write_case("shimmed", n_theta=48, n_z=6, edit=no_actuators)
    assert main(["static", str(shimmed), "--actuator-dynamics", "held"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no [actuators]" in err[0]


def test_a_stiff_stack_recovers_the_shimmed_onset_in_the_design_scan() -> None:
    # The design answer's two ends: at the identified K_p the default reading gives up most
    # of the shimmed GFB's 150 V onset; at K_p × 1e4 every reading is within 3 % of it (the
    # shims are 1.2 % thinner than the free stroke a rigid stack gives).
    from foilbearing.design import stack_design

    case = reading_case("local", "compliant")
    speeds = [rpm * RPM for rpm in range(30_000, 150_001, 10_000)]
    d = stack_design(case, 150.0, factors=(1.0, 1e4), speeds=speeds)
    assert d.shimmed_onset is not None
    for key, onsets in d.onsets.items():
        assert abs(onsets[1] - d.shimmed_onset) < 0.03 * d.shimmed_onset, key
        assert d.required_factor[key] is not None and d.required_factor[key] <= 1e4
    assert d.onsets["local+compliant"][0] < 0.8 * d.shimmed_onset
    rows = d.table()
    assert rows[0]["bearing"].startswith("shimmed") and len(rows) == 3  # × 3, × 10 not scanned


def test_stability_design_on_the_command_line(write_case, capsys, tmp_path) -> None:
    # The CLI's table is the API's (one voltage, the shimmed GFB first), the figure is
    # written and a second voltage is a one-line error.
    import json

    from foilbearing.cli.main import main

    path = write_case("coarse_design", n_theta=48, n_z=6)
    args = ["stability", str(path), "--design", "--speed-range", "40000rpm:140000rpm:20000rpm"]
    assert main([*args, "--json", "--plot", str(tmp_path)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["voltage_V"] == 150.0 and out["table"][0]["bearing"].startswith("shimmed")
    need = out["required_stack_stiffness_N_per_m"]
    assert set(need) == {"local+compliant", "local+held", "lobe+compliant", "lobe+held"}
    assert (tmp_path / "stack_design.png").stat().st_size > 10_000
    assert main([*args, "--voltage", "100,150V"]) == 2
    assert "--design takes one voltage" in capsys.readouterr().err


def test_the_study_runs_the_protocol_under_the_papers_reading(tmp_path) -> None:
    """``foilbearing study --paper-reading``'s stage runs the paper's protocol under lobe +
    held at 1 g·mm: its 0 V run is, sample for sample, a direct speed-up of that reading
    (and not of the case's own reading), its runs and files carry the ``lobe-held_`` prefix,
    and the report's table, captions and comparison rows name the reading (stopped at
    0.03 s on 32 x 4: the stage's plumbing, not its readouts)."""
    from foilbearing.control import linear_ramp
    from foilbearing.orbit import simulate
    from foilbearing.orbit.netcdf import load_orbit
    from foilbearing.output.report.captions import READING_TEXT, _caption
    from foilbearing.output.report.sections import _orbits
    from foilbearing.paper_dynamics import orbit_comparison
    from foilbearing.study.paper import paper_reading_orbits

    case = replace(
        default_case(),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
        disturbance=None,
    )
    got = paper_reading_orbits(case, tmp_path, lambda line: None, stop_time=0.03)
    runs = got["runs"]
    assert [r["voltage_V"] for r in runs] == [0.0, 50.0, 100.0, 150.0]
    assert all(r["label"].startswith("lobe-held_") and r["imbalance_g_mm"] == 1.0 for r in runs)
    assert (tmp_path / "orbit_lobe-held_0V_1gmm.nc").is_file()
    assert got["reading"] == "lobe + held" and got["figures"]

    profile = linear_ramp(3000 * RPM, 90000 * RPM, 500.0)
    held = case.with_actuator_reading("lobe", "held")
    held = replace(held, rotor=replace(held.rotor, imbalance=1e-6))
    direct = simulate(held, profile, stop_time=0.03)
    own = simulate(replace(case, rotor=held.rotor), profile, stop_time=0.03)
    zero, _spec = load_orbit(tmp_path / "orbit_lobe-held_0V_1gmm.nc")
    np.testing.assert_array_equal(zero.e_x, direct.e_x)
    act = zero.case.actuators  # the file records the reading: resumed, it runs under it
    assert act is not None and (act.preload_response, act.dynamics) == ("lobe", "held")
    assert np.max(np.abs(own.e_x - direct.e_x)) > 1e-3 * np.ptp(direct.e_x)

    html = _orbits(got, {"actuator_reading": "local + compliant"})
    assert "<b>lobe + held</b>" in html and "the paper's reading" in html
    name = f"orbit_{runs[1]['label']}_transient.png"
    assert _caption(name, runs).endswith(READING_TEXT)
    rows = orbit_comparison(runs, None, 0.0, "the paper's: lobe + held")
    assert all("lobe + held" in r.quantity for r in rows)
