"""Fast tests that kill the mutation survivors of issue 48 item 7 that matter: each
asserts the physical sense of a sign the survivors flipped."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, default_case
from foilbearing.static import film_at_position


def test_a_compressed_stack_lowers_its_lobe_and_opens_the_film() -> None:
    """Lobe reading (docs/model.md §3.8): a stack compressed by D (units of C) lets its
    lobe of the foil down by D times the lobe's shape, so the rigid film gets thicker,
    most at that actuator (60 deg), by D at the lobe's crown; the other lobes stay. Killed
    survivor: ``h_rigid_loaded`` with the lobe term's sign flipped (the film thinner)."""
    case = default_case().with_voltages(150.0).with_actuator_reading("lobe", "held")
    case = replace(case, grid=Grid(n_theta=48, n_z=4, orbit_n_z=None, orbit_axial_order=None))
    m = film_at_position(case, 0.3, 0.2, speed=50e3 * math.pi / 30.0).model
    assert m.lobe_shapes is not None
    compression = np.array([0.05, 0.0, 0.0])
    opened = m.h_rigid_loaded(0.3, 0.2, compression) - m.h_rigid(0.3, 0.2)
    assert opened.min() >= 0.0
    crown = int(np.argmax(opened[:, 0]))
    assert m.grid.theta[crown] == pytest.approx(math.radians(60.0), abs=2 * math.pi / 48)
    assert opened.max() == pytest.approx(0.05 * m.lobe_shapes[0].max(), rel=1e-12)
    far = np.abs(np.angle(np.exp(1j * (m.grid.theta - math.radians(240.0))))) < 0.2
    np.testing.assert_allclose(opened[far], 0.0, atol=1e-12)


def test_a_held_run_started_at_its_equilibrium_stays_there() -> None:
    """Under ``dynamics = "held"`` the orbit's rigid film is the lobes less the stacks'
    held compression (``preload_at``): without imbalance or disturbance, a run started at
    the static equilibrium (solved by the static analysis, an independent route) stays
    at it, to the stepper's Newton tolerance. Killed survivor: the held reading's sign in
    ``orbit/system.py`` ``preload_at`` (the film closed by the compression instead)."""
    from foilbearing.constants import RPM
    from foilbearing.control import constant_speed
    from foilbearing.orbit import simulate

    case = default_case().with_voltages(150.0).with_actuator_reading("local", "held")
    grid = Grid(n_theta=32, n_z=4, orbit_n_z=None, orbit_axial_order=None)
    case = replace(case, grid=grid, disturbance=None)
    case = replace(case, rotor=replace(case.rotor, imbalance=0.0))
    run = simulate(case, constant_speed(50e3 * RPM, 0.004))
    assert run.status == "completed"
    drift = np.hypot(run.e_x - run.e_x[0], run.e_y - run.e_y[0]).max()
    assert drift < 1e-3 * case.bearing.clearance, drift / case.bearing.clearance


# ------------------------------------------------------------- the stack under the film


def _lobe_model(axial_order: int = 2):
    from foilbearing.film import film_model

    case = default_case().with_voltages(100.0).with_actuator_reading("lobe", "compliant")
    grid = Grid(n_theta=32, n_z=4, axial_order=axial_order, orbit_n_z=None, orbit_axial_order=None)
    case = replace(case, grid=grid)
    return case, film_model(case)


def test_the_stack_is_compressed_by_its_spring_law_under_the_film_pressure() -> None:
    """``stack_compression`` (docs/model.md §3.8, Eq. 3b): each stack is a spring of
    stiffness k_p + 4k_sp per unit area (N/m³) under the gauge pressure at its angle, so
    D_n C (k_p + 4k_sp) = p_a max(q(θ_n), 0): the force balance on the stack, with k_p
    by hand from the case's stack stiffness and contact area (0.46e6 N/m over 3.54e-4
    m²), q at θ_n by ``at_angles`` (np.interp: an independent interpolation). The film's
    pressure pushes, its sub-ambient part does not pull; a film at ambient compresses
    nothing; the compression is linear in the pressure; ``"local"`` lowers no lobe."""
    case, m = _lobe_model()
    g = m.grid
    k_stack = 0.46e6 / 3.54e-4 + 4 * 3.95e6  # N/m³
    pa, c = case.gas.ambient_pressure, case.bearing.clearance
    # One gauge pressure above ambient at 60 and 180 deg, below it at 300 deg.
    q = 0.2 + 0.5 * np.cos(g.theta - math.radians(100.0))
    P = 1.0 + np.repeat(q[:, None], g.n_z, axis=1)
    q_at = m.at_angles(q, m.preload_angles)
    assert q_at[0] > 0.5 and 0.2 < q_at[1] < 0.35 and q_at[2] < -0.2
    D = m.stack_compression(P)
    np.testing.assert_allclose(D * c * k_stack, pa * np.maximum(q_at, 0.0), rtol=1e-3)
    assert D[0] > D[1] > 0.0 and D[2] == 0.0
    np.testing.assert_array_equal(m.stack_compression(P.ravel()), D)  # flat P too
    np.testing.assert_allclose(m.stack_compression(1.0 + 2.0 * (P - 1.0)), 2.0 * D, rtol=1e-13)
    np.testing.assert_array_equal(m.stack_compression(np.ones(g.shape)), np.zeros(3))
    np.testing.assert_array_equal(m.stack_compression(np.full(g.shape, 0.5)), np.zeros(3))
    local = replace(m, stack_compliance=0.0)  # the "local" reading's model
    np.testing.assert_array_equal(local.stack_compression(P), np.zeros(3))
    # A hand number: 1 kPa over a stack lowers its lobe by 1e3/k_stack = 0.76 nm.
    one_kpa = 1.0 + np.full(g.shape, 1e3 / pa)
    assert m.stack_compression(one_kpa) * c == pytest.approx(np.full(3, 1e3 / k_stack), rel=1e-3)


def test_the_lowered_lobes_open_the_film_the_stack_compression_says() -> None:
    """``film``: under ``"lobe"`` the film of a pressure field is the rigid film plus
    each lobe lowered by its stack's compression plus the bump's deflection; with the
    stacks held rigid (compliance 0) the lobe term vanishes. A difference of two films,
    so the deflection cancels: exactly Σ_n D_n lobe_n(θ)."""
    _, m = _lobe_model()
    g = m.grid
    q = 0.3 + 0.2 * np.sin(g.theta)
    P = 1.0 + np.repeat(q[:, None], g.n_z, axis=1)
    D = m.stack_compression(P)
    assert np.all(D > 0.0)
    rigid = replace(m, stack_compliance=0.0)
    opened = m.film(P, 0.2, -0.1) - rigid.film(P, 0.2, -0.1)
    assert m.lobe_shapes is not None
    np.testing.assert_allclose(opened, (D @ m.lobe_shapes)[:, None] * np.ones(g.n_z), atol=1e-15)


# ------------------------------------------------------------- interpolation at the stingers


def test_interpolation_rows_are_linear_interpolation_on_the_periodic_grid() -> None:
    """``interpolation_rows``: each row's weights are ≥ 0 and sum to 1 (a constant field
    is itself at any angle); a field linear in θ is reproduced exactly between the cells;
    at a cell centre the row is that cell alone; across the seam (2π) the two cells on
    either side share it; and any field agrees with np.interp (``at_angles``)."""
    from foilbearing.film import interpolation_rows

    _, m = _lobe_model()
    th = m.grid.theta
    d = 2 * math.pi / th.size
    angles = (0.3, 1.0, 2.0 * math.pi - 0.01, 0.01, -0.5, 7.0, float(th[5]), float(th[-1]) + d / 2)
    rows = interpolation_rows(th, angles)
    assert rows.shape == (len(angles), th.size) and rows.min() >= 0.0
    np.testing.assert_allclose(rows.sum(axis=1), 1.0, rtol=1e-14)
    assert np.count_nonzero(rows, axis=1).max() <= 2
    inner = [a for a in angles[:2]]
    np.testing.assert_allclose(
        interpolation_rows(th, tuple(inner)) @ (3.0 - 2.0 * th),
        3.0 - 2.0 * np.array(inner),
        rtol=1e-13,
    )
    np.testing.assert_allclose(rows[6], np.eye(th.size)[5], atol=1e-12)
    seam = rows[7]
    assert seam[-1] == pytest.approx(0.5) and seam[0] == pytest.approx(0.5)
    rng = np.random.default_rng(3)
    field = rng.normal(size=th.size)
    np.testing.assert_allclose(rows @ field, m.at_angles(field, angles), rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(m.actuator_rows, interpolation_rows(th, m.preload_angles))


# ------------------------------------------------------------- imbalance and disturbance


def test_the_imbalance_force_is_m_e_omega_squared_rotating_with_the_rotor() -> None:
    """The orbit's input force (per unit mass and clearance) at constant speed, without
    the disturbance: the load W/m along +X plus the imbalance force m_u e ω² (here
    8.5 g·mm at 12 krpm: 13.4 N, by hand) along the rotor's angle ωt; during a ramp the
    tangential term m_u e ω̇ joins it, 90 deg behind."""
    from foilbearing.constants import RPM
    from foilbearing.control import constant_speed, linear_ramp
    from foilbearing.orbit import OrbitSimulation

    case = replace(default_case(), disturbance=None)
    m, c, w = case.rotor.mass, case.bearing.clearance, 12000 * RPM
    sim = OrbitSimulation(case, constant_speed(w, 0.1))
    volts = sim.volts(0.0)
    assert 8.5e-6 * w**2 == pytest.approx(13.43, abs=0.01)
    for t in (0.0, 0.0013, 0.0271):
        f = sim.inputs(t, volts).force * m * c - np.array([8.8, 0.0])
        want = 8.5e-6 * w**2 * np.array([math.cos(w * t), math.sin(w * t)])
        np.testing.assert_allclose(f, want, rtol=1e-9, atol=1e-9)
        quiet = sim.inputs(t, volts, imbalance=False).force * m * c
        np.testing.assert_allclose(quiet, [8.8, 0.0], rtol=1e-12)
    accel = 500.0  # rad/s²
    ramp = OrbitSimulation(case, linear_ramp(w, 2 * w, accel))
    t = 0.01
    omega, phi = w + accel * t, w * t + 0.5 * accel * t * t
    f = ramp.inputs(t, volts).force * m * c - np.array([8.8, 0.0])
    radial = 8.5e-6 * omega**2 * np.array([math.cos(phi), math.sin(phi)])
    tangential = 8.5e-6 * accel * np.array([math.sin(phi), -math.cos(phi)])
    np.testing.assert_allclose(f, radial + tangential, rtol=1e-9)


# ------------------------------------------------------------- coefficients: lobes and speeds


def _coarse_case(reading: tuple[str, str] = ("local", "compliant")):
    case = default_case().with_voltages(100.0).with_actuator_reading(*reading)
    grid = Grid(n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None)
    return replace(case, grid=grid)


def _static_stiffness(case, st) -> np.ndarray:
    """−∂F/∂e from central differences of the film force at ±1e-4 C (film_at_position, which
    solves the stacks' compressions with the film under ``"lobe"``), N/m."""
    from foilbearing.static import film_at_position

    d, c = 1e-4, case.bearing.clearance
    fd = np.empty((2, 2))
    for j, (dx, dy) in enumerate([(d, 0.0), (0.0, d)]):
        plus = film_at_position(case, st.eps_x + dx, st.eps_y + dy, speed=st.speed)
        minus = film_at_position(case, st.eps_x - dx, st.eps_y - dy, speed=st.speed)
        fd[:, j] = -(np.array(plus.force) - np.array(minus.force)) / (2 * d * c)
    return fd


def test_lobe_stiffness_at_a_low_frequency_is_the_static_derivative_with_the_stacks() -> None:
    """Under ``"lobe" + "compliant"`` the stacks' compression follows the film during the
    motion (``_with_lobes``: ΔD = (I − M X_D)⁻¹ M X_ε): at ω_e = 0.001 ω the stiffness is
    −∂F/∂e of static films each with its own stack compression (central differences), to
    the difference's error. The stacks (c_s = p_a/(C(k_p + 4k_sp)) = 0.77) soften the
    bearing: the held stacks' stiffness differs by far more than that error."""
    from foilbearing.coefficients import force_coefficients
    from foilbearing.static import solve_equilibrium

    case = _coarse_case(("lobe", "compliant"))
    st = solve_equilibrium(case, speed=40e3 * math.pi / 30)
    assert st.converged
    co = force_coefficients(st, 1e-3 * st.speed)
    fd = _static_stiffness(case, st)
    np.testing.assert_allclose(co.K[0], fd, rtol=3e-3, atol=3e-3 * np.abs(fd).max())
    held = force_coefficients(
        replace(st, model=replace(st.model, actuator=replace(st.model.actuator, dynamics="held"))),
        1e-3 * st.speed,
    )
    assert np.abs(held.K[0] - co.K[0]).max() > 0.05 * np.abs(fd).max()


def test_coefficients_over_speeds_are_each_speed_solved_on_its_own() -> None:
    """``coefficients_over_speeds``: each speed about its own equilibrium, the same as one
    run at that speed; the default excitation is 20 ratios ω_e/ω from 0.1 to 2.0 of each
    speed, so frequency (Hz) = ratio · ω/2π; the printed table is K in MN/m and C in
    kN·s/m at the first ratio, against the speed in rpm."""
    from foilbearing.coefficients import coefficients_over_speeds, force_coefficients
    from foilbearing.static import solve_equilibrium

    case = _coarse_case()
    rpm = (30e3, 60e3)
    sweep = coefficients_over_speeds(case, [f"{r:g} rpm" for r in rpm])
    np.testing.assert_allclose(sweep.speeds, np.array(rpm) * math.pi / 30, rtol=1e-14)
    np.testing.assert_allclose(sweep.frequency_ratios, np.linspace(0.1, 2.0, 20))
    for point, r in zip(sweep.points[1:], rpm[1:], strict=True):  # one checked: the cost
        w = r * math.pi / 30
        alone = force_coefficients(solve_equilibrium(case.with_speed(w)), [0.1 * w, 2.0 * w])
        np.testing.assert_allclose(point.K[[0, -1]], alone.K, rtol=1e-9)
        np.testing.assert_allclose(point.C[[0, -1]], alone.C, rtol=1e-9)
        np.testing.assert_allclose(point.frequencies, np.linspace(0.1, 2.0, 20) * w, rtol=1e-14)
    # faster, the film is stiffer along the load (the journal sits nearer the centre)
    assert sweep.points[1].static.eccentricity < sweep.points[0].static.eccentricity
    ds = sweep.to_dataset()
    assert ds.sizes["speed"] == 2 and ds.sizes["frequency_ratio"] == 20
    np.testing.assert_allclose(
        ds["frequency"].values, np.outer(sweep.speeds, ds["frequency_ratio"].values) / (2 * math.pi)
    )
    head = sweep.headline()
    assert head["load_N"] == pytest.approx(8.8) and len(head["speeds"]) == 2
    title, rows, _ = sweep._summary()
    assert "2 speeds" in title and "8.8 N" in title and "ω_e/ω = 0.1" in title
    np.testing.assert_allclose(rows["speed_rpm"], rpm, rtol=1e-12)
    for k, (i, j) in enumerate([(0, 0), (0, 1), (1, 0), (1, 1)]):
        name = ("XX", "XY", "YX", "YY")[k]
        np.testing.assert_allclose(
            rows[f"K_{name}_MN_per_m"], [p.K[0, i, j] / 1e6 for p in sweep.points]
        )
        np.testing.assert_allclose(
            rows[f"C_{name}_kNs_per_m"], [p.C[0, i, j] / 1e3 for p in sweep.points]
        )
    fixed = coefficients_over_speeds(case, [30e3 * math.pi / 30], "100 Hz")
    assert fixed.frequency_ratios is None
    assert fixed.points[0].frequencies[0] == pytest.approx(2 * math.pi * 100.0)
    assert "100 Hz" in fixed._summary()[0]


# ------------------------------------------------------------- quantities and readouts


def test_a_speed_ramp_given_in_quantities_is_the_ramp_in_si() -> None:
    """The paper's speed-up, 3 to 90 krpm at 500 rad/s², lasts (90 − 3) krpm/500 rad/s²
    = 18.2 s, given in rpm or in rad/s; a quantity of another kind is one error naming
    the argument."""
    from foilbearing.control import linear_ramp
    from foilbearing.errors import InputError

    rpm = math.pi / 30
    quantities = linear_ramp("3000 rpm", "90 krpm", "500 rad/s**2")
    floats = linear_ramp(3000 * rpm, 90000 * rpm, 500.0)
    np.testing.assert_allclose(quantities.times, floats.times, rtol=1e-14)
    np.testing.assert_allclose(quantities.speeds, [3000 * rpm, 90000 * rpm], rtol=1e-14)
    assert (
        quantities.times[-1] == pytest.approx(87000 * rpm / 500.0) == pytest.approx(18.22, abs=0.01)
    )
    for args, name in (
        (("3000 N", "90 krpm", "500 rad/s**2"), "start"),
        (("3000 rpm", "90 m", "500 rad/s**2"), "stop"),
        (("3000 rpm", "90 krpm", "500 rpm"), "acceleration"),
    ):
        with pytest.raises(InputError, match=rf"\b{name}\b"):
            linear_ramp(*args)


def test_divergence_reports_which_event_came_first_and_when() -> None:
    """A synthetic speed-up (ω = 1000 + 100 t rad/s) whose whirl grows as r(t) = 0.1 C e^t
    about a centre of 0.3 C: its radius passes 0.9 C at t = ln 9 = 2.197 s. Without
    contact that is the divergence, by "orbit radius"; with a contact at 3 s after it,
    the divergence is still the radius's, and the orbit was large for 3 − 2.197 s before
    the contact; with a contact at 1 s, before it, the contact is the divergence."""
    from foilbearing.signals import divergence

    c = 1e-4
    t = np.arange(0.0, 3.0, 4e-4)
    speed = 1000.0 + 100.0 * t
    r = 0.1 * c * np.exp(t)
    phase = 2 * math.pi * 100.0 * t
    e_x, e_y = 0.3 * c + r * np.cos(phase), r * np.sin(phase)
    rpm = 30 / math.pi
    t9 = math.log(9.0)
    free = divergence(t, e_x, e_y, speed, c, stopped_by_contact=False, window_s=0.02)
    assert free is not None and free.by == "orbit radius" and free.contact_speed_rpm is None
    assert free.time_s == pytest.approx(t9, abs=0.02) and free.large_orbit_before_contact_s == 0.0
    assert free.speed_rpm == pytest.approx((1000.0 + 100.0 * free.time_s) * rpm, rel=1e-6)
    late = divergence(t, e_x, e_y, speed, c, stopped_by_contact=True, window_s=0.02)
    assert late is not None and late.by == "orbit radius" and late.time_s == free.time_s
    assert late.contact_speed_rpm == pytest.approx((1000.0 + 100.0 * t[-1]) * rpm, rel=1e-9)
    assert late.large_orbit_before_contact_s == pytest.approx(t[-1] - free.time_s, rel=1e-12)
    early = divergence(
        t, e_x, e_y, speed, c, stopped_by_contact=True, contact_time=1.0, window_s=0.02
    )
    assert early is not None and early.by == "contact" and early.time_s == 1.0
    assert early.speed_rpm == early.contact_speed_rpm == pytest.approx(1100.0 * rpm, rel=1e-9)
    assert early.large_orbit_before_contact_s == 0.0
    calm = divergence(
        t, e_x * 0 + 0.3 * c, e_y * 0, speed, c, stopped_by_contact=False, window_s=0.02
    )
    assert calm is None


def test_the_coefficients_dataset_labels_shared_quantities_as_the_static_one_does() -> None:
    """The coefficients' Dataset carries the static point's speed, load, eccentricity and
    attitude angle with the static Dataset's units and labels (one quantity, one name),
    and its frequency ratio as the speed sweep's; each of these has a ``long_name``."""
    from foilbearing.coefficients import coefficients_over_speeds
    from foilbearing.static import solve_equilibrium

    case = _coarse_case()
    st = solve_equilibrium(case, speed=40e3 * math.pi / 30)
    from foilbearing.coefficients import force_coefficients

    ds = force_coefficients(st, [0.5 * st.speed, st.speed]).to_dataset()
    static = st.to_dataset()
    for name in ("speed", "load", "eccentricity", "attitude_angle"):
        assert ds[name].attrs == static[name].attrs, name
    for name in ("speed", "load", "eccentricity", "attitude_angle", "frequency", "frequency_ratio"):
        assert ds[name].attrs.get("long_name"), name
    assert "ω_e" in ds["frequency"].attrs["long_name"] and ds["frequency"].attrs["units"] == "Hz"
    sweep = coefficients_over_speeds(case, [40e3 * math.pi / 30], frequency_ratios=[0.5, 1.0])
    assert ds["frequency_ratio"].attrs == sweep.to_dataset()["frequency_ratio"].attrs


def test_a_printed_static_point_says_whether_it_is_an_equilibrium() -> None:
    """A printed equilibrium is titled as one, a film at a prescribed position as that,
    each with the case's grid and the headline's numbers (the eccentricity of the
    position given: √(0.3² + 0.2²))."""
    from foilbearing.static import film_at_position, solve_equilibrium

    case = _coarse_case()
    w = 40e3 * math.pi / 30
    eq = repr(solve_equilibrium(case, speed=w))
    point = film_at_position(case, 0.3, 0.2, speed=w)
    text = repr(point)
    assert eq.startswith("Static equilibrium, ") and "32" in eq.splitlines()[0]
    assert text.startswith("Static point (position prescribed), ")
    assert case.title in text.splitlines()[0]
    ecc = next(ln for ln in text.splitlines() if ln.strip().startswith("eccentricity"))
    assert float(ecc.split()[1]) == pytest.approx(math.hypot(0.3, 0.2), rel=1e-3)
    assert "min_film_um" not in text.splitlines()[0]


def test_the_disturbance_is_its_multisine_with_phases_over_the_whole_turn() -> None:
    """F(t) = a Σ_k cos(2π f_k t + φ_k) per direction, summed here by hand from the tones'
    frequencies and phases at times where ``+ φ`` and ``− φ`` differ; the phases are
    uniform over [0, 2π): 512 of them reach within 0.1 rad of either end, their mean
    is π (within 4 standard errors, 4 · 1.81/√512)."""
    from foilbearing.case import Disturbance
    from foilbearing.orbit.disturbance import DisturbanceForce

    force = DisturbanceForce(Disturbance(0.02, 5.0, 500.0, tones=256, seed=3))
    phases = force.phases
    assert phases.shape == (2, 256) and force.amplitude == pytest.approx(0.02 * math.sqrt(2 / 256))
    assert 0.0 <= phases.min() < 0.1 and 2 * math.pi - 0.1 < phases.max() < 2 * math.pi
    assert abs(phases.mean() - math.pi) < 4 * (math.pi / math.sqrt(3)) / math.sqrt(512)
    for t in (0.0137, 0.25):
        by_hand = [
            force.amplitude
            * sum(
                math.cos(2 * math.pi * f * t + p)
                for f, p in zip(force.frequencies, row, strict=True)
            )
            for row in phases
        ]
        np.testing.assert_allclose(force(t), by_hand, rtol=1e-9, atol=1e-15)


def test_the_static_force_along_x_is_the_load_direction_component() -> None:
    """In the static Dataset, ``force`` along ``axis = "X"`` is F_X (along the load, which
    the equilibrium balances: −W) and along ``"Y"`` F_Y (≈ 0 at equilibrium)."""
    from foilbearing.static import solve_equilibrium

    case = _coarse_case()
    st = solve_equilibrium(case, speed=40e3 * math.pi / 30)
    ds = st.to_dataset()
    assert float(ds["force"].sel(axis="X")) == pytest.approx(st.force[0], rel=1e-15)
    assert float(ds["force"].sel(axis="X")) == pytest.approx(-8.8, rel=1e-6)
    assert abs(float(ds["force"].sel(axis="Y"))) < 1e-6


def test_lobe_stiffness_with_a_stack_under_the_lifted_film_is_the_static_derivative() -> None:
    """As the lobe test above, under a heavier load (20 N, ε₀ = 0.66) whose film has
    lifted off the foil over the stack at 300 deg (gauge pressure 0 there): that stack is
    not loaded, so it does not follow the motion (``_with_lobes``' ``loaded``); K at
    ω_e = 0.001 ω is still −∂F/∂e of static films each with its own compressions."""
    from foilbearing.coefficients import force_coefficients
    from foilbearing.static import solve_equilibrium

    case = _coarse_case(("lobe", "compliant"))
    case = replace(case, operation=replace(case.operation, load=20.0))
    st = solve_equilibrium(case, speed=40e3 * math.pi / 30)
    assert st.converged
    assert st.model.actuator_rows is not None
    q = st.model.actuator_rows @ st.model.grid.gauge_mean(st.P)
    assert q[2] == 0.0 < q[1], q  # the stack at 300 deg unloaded, at 180 deg loaded
    co = force_coefficients(st, 1e-3 * st.speed)
    fd = _static_stiffness(case, st)
    np.testing.assert_allclose(co.K[0], fd, rtol=3e-3, atol=3e-3 * np.abs(fd).max())


def test_the_smoothed_edge_width_is_kappa_cells_squared() -> None:
    """δ = κ Δθ² (docs/lift-off.md): 0.1 on cells of 2π/96 is 4.28e-4, and w = δ √Λ; κ < 0
    or NaN is refused."""
    from foilbearing.laws.lift_off import LiftOff

    d = 2 * math.pi / 96
    assert (
        LiftOff(0.1).delta(d)
        == pytest.approx(0.1 * d * d, rel=1e-15)
        == pytest.approx(4.28e-4, rel=1e-3)
    )
    assert LiftOff(0.1).width(d, 4.0) == pytest.approx(2.0 * 0.1 * d * d, rel=1e-15)
    assert LiftOff(0.0).delta(d) == 0.0 and LiftOff(0.0).sharp
    for bad in (-0.1, math.nan, math.inf):
        with pytest.raises(ValueError, match="kappa"):
            LiftOff(bad)


def test_an_unknown_actuator_reading_is_refused_naming_the_field_and_the_choices() -> None:
    from foilbearing.laws.actuator import ActuatorReading

    with pytest.raises(
        ValueError,
        match=r"ActuatorReading\.preload_response = 'sideways': expected one of 'local', 'lobe'$",
    ):
        ActuatorReading("sideways")
    with pytest.raises(
        ValueError,
        match=r"ActuatorReading\.dynamics = 'loose': expected one of 'compliant', 'held'$",
    ):
        ActuatorReading("lobe", "loose")


def test_a_static_point_of_an_untitled_case_is_printed_as_the_case() -> None:
    from foilbearing.static import film_at_position

    case = replace(_coarse_case(), title="")
    text = repr(film_at_position(case, 0.3, 0.2, speed=40e3 * math.pi / 30))
    assert text.startswith("Static point (position prescribed), case; ")
