"""The film model, the static analysis and the force coefficients, rule by rule, on a coarse
grid (32 x 4).

Each readout is checked against a closed form or a second route to it: the film's
geometry against the formula of docs/model.md §2, the equilibrium against the film
solved at its position on its own, the coefficients against finite differences of the
static force, the drag torque against integrals done by hand. The grid is coarse so that
these run in seconds, against every mutant of ``film.py``, ``static.py`` and
``coefficients.py`` (``make mutation``); the physics on the default grid is in
``test_static.py``, ``test_lift_off.py`` and ``test_coefficients.py``.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, default_case
from foilbearing.coefficients import dynamic_compliance, force_coefficients
from foilbearing.errors import InputError, SolverError
from foilbearing.film import drag_torque, film_model
from foilbearing.static import (
    EquilibriumOptions,
    film_at_position,
    solve_equilibrium,
)
from foilbearing.structure import preload_shape

RPM = math.pi / 30.0


def _coarse(volts: float = 100.0):
    return replace(
        default_case().with_voltages(volts),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
    )


def _sharp(volts: float = 100.0):
    """The coarse case with the unsmoothed step of k(θ) (α → ∞): k = k_assy on the arcs."""
    case = _coarse(volts)
    assert case.actuators is not None
    return replace(case, actuators=replace(case.actuators, smoothness=math.inf))


def _rigid():
    return replace(_coarse(), foil=None, actuators=None)


# ----------------------------------------------------------------------------- film.py


def test_film_geometry_is_the_model_formula() -> None:
    """H_r = 1 + ε_X cos θ + ε_Y sin θ − r_p/C on every cell (uniform in z), with r_p the
    preload shape of the base preloads at the actuator angles (docs/model.md §2)."""
    case = _coarse(120.0)
    model = film_model(case)
    g = model.grid
    assert g.shape == (32, 4)
    assert g.half_length == pytest.approx(case.bearing.length / (2 * case.bearing.radius))
    act, c = case.actuators, case.bearing.clearance
    assert act is not None
    r_p = preload_shape(g.theta, act.angles, act.base_preloads())
    np.testing.assert_allclose(model.preload, r_p / c, rtol=1e-14)
    assert model.preload.max() > 0.1  # the lobes are there
    h = model.h_rigid(0.3, -0.2)
    expected = 1.0 + 0.3 * np.cos(g.theta) - 0.2 * np.sin(g.theta) - r_p / c
    np.testing.assert_allclose(h, np.repeat(expected[:, None], 4, axis=1), rtol=1e-14)
    assert model.preload_angles == act.angles
    np.testing.assert_allclose(model.base_preloads, act.base_preloads(), rtol=1e-15)
    assert model.actuator_stiffness == act.stiffness
    # another grid on request
    assert film_model(case, n_theta=16, n_z=3).grid.shape == (16, 3)


def test_film_compliance_is_two_springs_in_series() -> None:
    """c = p_a/(C k(θ)): the bump's p_a/(C k_b) everywhere and, at each stinger's centre,
    the actuator's p_a/(C (k_p + 4 k_sp)) (Eq. 7: 1/k_assy = 1/k_b + 1/(k_p + 4k_sp));
    nothing of the actuators half-way between two stingers (the unsmoothed k(θ); the
    smoothed one, α = 50, reaches 95 % of the step at the centre). The shimmed GFB and the
    GFB have the bump alone, a rigid bearing nothing; lift-off follows the case."""
    case = replace(
        _sharp(),
        grid=Grid(
            n_theta=360, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
    )
    model = film_model(case)
    act, foil = case.actuators, case.foil
    assert act is not None and foil is not None
    pa, c, k_b = case.gas.ambient_pressure, case.bearing.clearance, foil.bump_stiffness
    np.testing.assert_allclose(model.bump_compliance, pa / (c * k_b), rtol=1e-14)
    centre = model.at_angles(model.actuator_compliance, act.angles)
    np.testing.assert_allclose(centre, pa / (c * act.stiffness), rtol=1e-12)
    between = model.at_angles(model.actuator_compliance, tuple(a + math.pi / 3 for a in act.angles))
    np.testing.assert_array_equal(between, 0.0)
    smooth = film_model(
        replace(
            _coarse(),
            grid=Grid(
                n_theta=360, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
            ),
        )
    )
    k_assy = case.assembly_stiffness()
    assert k_assy is not None
    half = act.stinger_arc / 2
    k_centre = k_b  # Eq. (8) at θ_0, summed over the three stingers
    for theta_n in act.angles:
        d = math.remainder(act.angles[0] - theta_n, 2 * math.pi)
        k_centre -= (
            (k_b - k_assy) * (math.atan(50 * (d + half)) - math.atan(50 * (d - half))) / math.pi
        )
    np.testing.assert_allclose(
        smooth.at_angles(smooth.compliance, act.angles),
        pa / (c * k_centre),
        rtol=1e-3,  # read half a 1° cell off the peak
    )
    assert np.all(model.actuator_compliance >= 0.0)
    np.testing.assert_allclose(model.compliance, pa / (c * model.stiffness), rtol=1e-12)  # type: ignore[operator]
    np.testing.assert_allclose(
        model.compliance, model.bump_compliance + model.actuator_compliance, rtol=1e-15
    )
    assert model.lift_off is True
    assert film_model(case.with_subambient("retained")).lift_off is False

    shimmed = film_model(case.shimmed())
    np.testing.assert_array_equal(shimmed.actuator_compliance, 0.0)
    np.testing.assert_array_equal(shimmed.stiffness, k_b)
    np.testing.assert_allclose(shimmed.bump_compliance, pa / (c * k_b), rtol=1e-14)
    assert shimmed.actuator_stiffness is None and shimmed.lift_off is True
    # the shims are as thick as the base preloads: the same preload shape
    np.testing.assert_allclose(shimmed.preload, model.preload, rtol=1e-14)

    gfb = film_model(replace(case, actuators=None))
    np.testing.assert_array_equal(gfb.preload, 0.0)
    np.testing.assert_array_equal(gfb.actuator_compliance, 0.0)
    assert gfb.preload_angles == () and gfb.base_preloads == ()

    rigid = film_model(replace(case, foil=None, actuators=None))
    assert rigid.stiffness is None and rigid.lift_off is False
    np.testing.assert_array_equal(rigid.compliance, 0.0)


def test_film_interpolates_periodically_at_angles() -> None:
    """``at_angles``: linear interpolation of a cell field, periodic in θ; between the last
    cell and 2π + the first it interpolates across the seam (cos θ, error ≤ Δθ²/8)."""
    model = film_model(_coarse())
    g = model.grid
    field = np.cos(g.theta)
    angles = (0.0, 1e-3, 2 * math.pi - 1e-3, -0.5, 7.0, 3.0, math.pi)
    got = model.at_angles(field, angles)
    np.testing.assert_allclose(got, np.cos(angles), atol=g.d_theta**2 / 8 + 1e-12)
    # at a cell centre it is the cell's value
    assert model.at_angles(field, (float(g.theta[5]),))[0] == pytest.approx(field[5], rel=1e-14)
    ramp = np.arange(g.n_theta, dtype=float)  # a jump at the seam: half-way is the mean
    seam = float(g.theta[-1]) + 0.5 * g.d_theta
    assert model.at_angles(ramp, (seam,))[0] == pytest.approx(0.5 * (g.n_theta - 1), rel=1e-12)
    assert model.at_angles(ramp, (seam - 2 * math.pi,))[0] == pytest.approx(
        0.5 * (g.n_theta - 1), rel=1e-12
    )


# --------------------------------------------------------------------------- static.py


@pytest.fixture(scope="module")
def equilibrium():
    return solve_equilibrium(_coarse(), speed=40e3 * RPM)


@pytest.fixture(scope="module")
def sharp_equilibrium():
    return solve_equilibrium(_sharp(), speed=40e3 * RPM)


def test_equilibrium_balances_the_load_and_matches_the_film_at_its_position(equilibrium) -> None:
    """F + W = 0 to the solver's tolerance; the film solved on its own at the equilibrium's
    position has the same pressure and film; the readouts are those of the arrays."""
    st = equilibrium
    case = st.case
    load = case.operation.load
    assert st.converged and st.equilibrium and st.iterations > 0
    assert st.message.startswith("converged in ")
    assert st.force[0] == pytest.approx(-load, rel=1e-6)
    assert abs(st.force[1]) < 1e-6 * load
    assert st.force_residual <= 1e-8 and st.residual <= 1e-8
    assert st.speed == 40e3 * RPM
    assert st.bearing_number == pytest.approx(case.bearing_number(40e3 * RPM), rel=1e-15)
    other = film_at_position(case, st.eps_x, st.eps_y, speed=st.speed)
    assert other.converged is True and other.equilibrium is False
    assert math.isnan(other.force_residual) and other.message.startswith("converged")
    assert isinstance(other.iterations, int) and other.iterations > 0
    assert other.residual <= 1e-8 and other.speed == st.speed
    # the reported residual is max|R|/(ΔθΔZ) of the Reynolds residual at the result
    from foilbearing.reynolds import coupled_system

    m = st.model
    h_r = m.h_rigid(st.eps_x, st.eps_y)
    R = coupled_system(
        st.P.ravel(), m.grid, h_r, m.compliance, st.bearing_number, lift_off=m.lift_off
    )[0]
    assert st.residual == pytest.approx(
        float(np.max(np.abs(R))) / (m.grid.d_theta * m.grid.d_z), rel=1e-6, abs=1e-14
    )
    np.testing.assert_allclose(other.P, st.P, rtol=1e-7)
    np.testing.assert_allclose(other.H, st.H, rtol=1e-7)
    assert other.force[0] == pytest.approx(st.force[0], rel=1e-6)
    # The film force is the pressure integral ∫∫ (p − p_a)(cos θ, sin θ) R dθ dz over the full
    # length (θ from −X: the wall at θ pushes the journal along (cos θ, sin θ)).
    g, pa, r = st.model.grid, case.gas.ambient_pressure, case.bearing.radius
    cell = 2 * g.d_theta * g.d_z * r * r * pa  # both halves of the bearing
    fx = float(np.sum((st.P - 1.0) * np.cos(g.theta)[:, None])) * cell
    fy = float(np.sum((st.P - 1.0) * np.sin(g.theta)[:, None])) * cell
    assert st.force == pytest.approx((fx, fy), rel=1e-6, abs=1e-9 * load)
    # readouts
    assert st.eccentricity == pytest.approx(math.hypot(st.eps_x, st.eps_y), rel=1e-15)
    assert 0.0 < st.attitude_angle < math.pi / 2 and st.eps_x > 0.0 < st.eps_y
    assert math.tan(st.attitude_angle) == pytest.approx(st.eps_y / st.eps_x, rel=1e-12)
    i_min = int(np.argmin(st.H[:, 0]))
    assert st.min_film == pytest.approx(st.H.min() * case.bearing.clearance, rel=1e-15)
    assert st.min_film_angle == float(g.theta[i_min])
    assert st.power_loss == pytest.approx(st.drag_torque * st.speed, rel=1e-15)


def test_equilibrium_film_and_reported_preload(sharp_equilibrium) -> None:
    """H = H_r + c max(p̄ − 1, 0) (the foil pushed by the axially averaged gauge pressure,
    never pulled); the stinger's share of that deflection at each actuator is p_A/(k_p +
    4k_sp), which is what Eq. (3b) takes off the base preload (unsmoothed k(θ), so that
    k = k_assy at the stinger)."""
    st = sharp_equilibrium
    model, case = st.model, st.case
    p_mean = st.P.mean(axis=1) - 1.0
    w = model.compliance * np.maximum(p_mean, 0.0)
    np.testing.assert_allclose(st.H, model.h_rigid(st.eps_x, st.eps_y) + w[:, None], rtol=1e-14)
    act = case.actuators
    assert act is not None
    pa = case.gas.ambient_pressure
    p_a = model.at_angles(p_mean, act.angles) * pa
    np.testing.assert_allclose(st.actuator_pressure, p_a, rtol=1e-14)
    assert np.sum(p_a > 0) >= 1
    # The actuator spring's deflection read from the film: C c_act(θ_n) p̄_+(θ_n).
    c = case.bearing.clearance
    stinger = (
        c
        * model.at_angles(model.actuator_compliance, act.angles)
        * np.maximum(model.at_angles(p_mean, act.angles), 0.0)
    )
    base = act.base_preloads()
    np.testing.assert_allclose(base - st.preload, stinger, rtol=1e-12, atol=1e-15)
    assert np.all(st.preload <= base)


def test_reported_preload_where_the_film_is_sub_ambient() -> None:
    """With the suction retained a stinger can sit under sub-ambient film; the foil is not
    pulled (bumps carry no tension), so that stinger keeps its base preload."""
    case = _coarse(0.0).with_subambient("retained")
    act = case.actuators
    assert act is not None
    st = film_at_position(case, -0.45, 0.45, speed=40e3 * RPM)
    assert st.converged
    assert np.any(st.actuator_pressure < 0.0) and np.any(st.actuator_pressure > 0.0)
    base = act.base_preloads()
    sub = st.actuator_pressure <= 0.0
    np.testing.assert_array_equal(st.preload[sub], base[sub])
    np.testing.assert_allclose(
        st.preload[~sub], base[~sub] - st.actuator_pressure[~sub] / act.stiffness, rtol=1e-12
    )


def test_shimmed_preload_is_the_shim_thickness() -> None:
    case = _coarse().shimmed()
    st = film_at_position(case, 0.2, 0.1, speed=40e3 * RPM)
    assert case.shims is not None
    np.testing.assert_array_equal(st.preload, case.shims.thicknesses)
    rigid = film_at_position(_rigid(), 0.2, 0.1, speed=40e3 * RPM)
    assert rigid.preload.size == 0 and rigid.actuator_pressure.size == 0


def test_drag_torque_pressure_term_by_hand() -> None:
    """T = R³ ∫∫ [μωR/(C H) + (C H p_a/(2R)) ∂P/∂θ] dθ dZ over the full length. For
    P = 1 + a sin θ and H = 1 + ε cos θ the pressure term is R³ (C p_a/(2R)) a ε π L/R
    times the central difference's sin(Δθ)/Δθ; the shear term is checked by Petroff's
    torque for H = 1."""
    case = _rigid()
    g = film_model(case).grid
    b, mu, pa = case.bearing, case.gas.viscosity, case.gas.ambient_pressure
    r, c, omega = b.radius, b.clearance, 30e3 * RPM
    th = g.theta[:, None] * np.ones(g.n_z)
    petroff = 2 * math.pi * mu * omega * r**3 * b.length / c
    assert drag_torque(case, g, np.ones(g.shape), np.ones(g.shape), omega) == pytest.approx(
        petroff, rel=1e-12
    )
    a, eps = 0.3, 0.4
    H = 1.0 + eps * np.cos(th)
    shear = drag_torque(case, g, np.ones(g.shape), H, omega)
    shear_exact = mu * omega * r**4 / c * 2 * math.pi / math.sqrt(1 - eps**2) * b.length / r
    assert shear == pytest.approx(shear_exact, rel=1e-6)  # spectral for a periodic integrand
    total = drag_torque(case, g, 1.0 + a * np.sin(th), H, omega)
    dtheta = g.d_theta
    pressure = r**3 * c * pa / (2 * r) * a * eps * math.pi * b.length / r
    pressure *= math.sin(dtheta) / dtheta
    assert total - shear == pytest.approx(pressure, rel=1e-10)


def test_equilibrium_from_a_nearby_start_and_by_load_continuation() -> None:
    """The same equilibrium from the centre, from a nearby start (with its pressure), and by
    load continuation when Newton is held to too few iterations to go straight there; a
    Newton that meets the tolerances on its last allowed step has converged."""
    case = _coarse()
    direct = solve_equilibrium(case, speed=40e3 * RPM)
    same = solve_equilibrium(case, speed=40e3 * RPM, start=(direct.eps_x, direct.eps_y, direct.P))
    no_p = solve_equilibrium(case, speed=40e3 * RPM, start=(direct.eps_x, direct.eps_y, None))
    assert same.converged and same.iterations <= 1 < no_p.iterations  # the pressure is used
    near = solve_equilibrium(case, speed=42e3 * RPM, start=(direct.eps_x, direct.eps_y, direct.P))
    again = solve_equilibrium(case, speed=42e3 * RPM)
    assert near.converged and again.converged
    assert near.iterations < again.iterations
    assert near.eps_x == pytest.approx(again.eps_x, abs=1e-7)
    assert near.eps_y == pytest.approx(again.eps_y, abs=1e-7)
    opts = EquilibriumOptions(max_iter=4)
    cont = solve_equilibrium(case, speed=40e3 * RPM, options=opts)
    assert cont.converged
    assert cont.message.startswith("direct Newton failed (no convergence in 4 iterations); ")
    assert cont.message.endswith(f"converged in {cont.iterations} Newton iterations")
    assert cont.iterations > direct.iterations
    steps = re.search(r"load continuation in (\d+) steps: ", cont.message)
    assert steps is not None and int(steps.group(1)) >= 5  # 0.1, 0.25, 0.475, 0.81, 1 at best
    assert cont.eps_x == pytest.approx(direct.eps_x, abs=1e-7)
    assert cont.eps_y == pytest.approx(direct.eps_y, abs=1e-7)


def test_failed_equilibrium_says_what_to_try() -> None:
    """A rigid bearing at a crawl cannot carry the load: no equilibrium, no NaN, and the
    message gives the residuals and what to try."""
    case = replace(_rigid(), operation=replace(_rigid().operation, load=200.0))
    st = solve_equilibrium(case, speed=2e3 * RPM)
    assert st.converged is False
    assert st.message.startswith("equilibrium not found: direct Newton failed (")
    assert "Try: a start from a nearby converged point, a finer grid" in st.message
    assert "% of the load" in st.message
    assert np.all(np.isfinite(st.P)) and math.isfinite(st.eps_x)


@pytest.mark.parametrize("speed", [0.0, -1.0, math.nan, math.inf])
def test_bad_speed_is_a_one_line_error(speed: float) -> None:
    with pytest.raises(InputError) as err:
        solve_equilibrium(_coarse(), speed=speed)
    assert str(err.value) == f"speed = {speed!r} rad/s: expected a speed > 0 (e.g. '50000 rpm')"


def test_speed_defaults_to_the_case_and_any_positive_speed_is_allowed() -> None:
    """Without ``speed`` the case's operating speed is used; 0.5 rad/s is a speed too."""
    case = _coarse().with_speed(40e3 * RPM)
    assert solve_equilibrium(case).speed == 40e3 * RPM
    assert film_at_position(case, 0.1, 0.0).speed == 40e3 * RPM
    assert film_at_position(_rigid(), 0.1, 0.0, speed=0.5).speed == 0.5


def test_solver_options_reach_the_pressure_solve() -> None:
    """A pressure Newton held to one iteration does not converge at a prescribed position."""
    from foilbearing.reynolds import NewtonOptions

    opts = EquilibriumOptions(newton=NewtonOptions(max_iter=1))
    st = film_at_position(_coarse(), 0.3, 0.1, speed=40e3 * RPM, options=opts)
    assert st.converged is False and "max_iter" in st.message  # (continuation steps counted)


def test_rigid_position_that_closes_the_film_is_an_error() -> None:
    with pytest.raises(InputError) as err:
        film_at_position(_rigid(), 1.2, 0.0, speed=40e3 * RPM)
    assert str(err.value) == (
        "journal position (1.2, 0) closes the film (min h/C = -0.194) of a rigid bearing: "
        "choose a smaller eccentricity"
    )
    # a compliant foil opens under the pressure: allowed
    assert film_at_position(_coarse(0.0), 1.2, 0.0, speed=40e3 * RPM).min_film > 0.0


def test_static_headline_and_dataset_units(equilibrium) -> None:
    st = equilibrium
    h = st.headline()
    assert h["speed_rpm"] == pytest.approx(40e3, rel=1e-14)
    assert h["voltages_V"] == [100.0, 100.0, 100.0] and h["bearing"] == "C-GFB"
    assert h["min_film_um"] == pytest.approx(st.min_film * 1e6, rel=1e-15)
    assert h["preload_um"] == pytest.approx([x * 1e6 for x in st.preload], rel=1e-15)
    assert h["actuator_pressure_kPa"] == pytest.approx(
        [x / 1e3 for x in st.actuator_pressure], rel=1e-15
    )
    assert h["attitude_deg"] == pytest.approx(math.degrees(st.attitude_angle), rel=1e-15)
    assert h["min_film_angle_deg"] == pytest.approx(math.degrees(st.min_film_angle), rel=1e-15)
    assert h["converged"] is True and h["force_N"] == list(st.force)
    ds = st.to_dataset()
    pa, c, r = st.case.gas.ambient_pressure, st.case.bearing.clearance, st.case.bearing.radius
    np.testing.assert_allclose(ds["pressure"].values, st.P * pa, rtol=1e-15)
    np.testing.assert_allclose(ds["gauge_pressure_mean"].values, (st.P.mean(1) - 1) * pa)
    np.testing.assert_allclose(ds["film_thickness"].values, st.H * c, rtol=1e-15)
    np.testing.assert_allclose(ds["preload_shape"].values, st.model.preload * c, rtol=1e-15)
    np.testing.assert_allclose(ds["z"].values, st.model.grid.z * r, rtol=1e-15)
    assert ds["pressure"].attrs["units"] == "Pa" and ds["z"].attrs["units"] == "m"
    assert ds.attrs["converged"] == 1
    # the dataset is in SI; the headline shows it in the units its keys name
    np.testing.assert_array_equal(ds["stinger_preload"].values, st.preload)
    assert ds["stinger_preload"].attrs["units"] == "m"
    assert float(ds["speed"]) == st.speed and ds["speed"].attrs["units"] == "rad/s"
    assert float(ds["attitude_angle"]) == st.attitude_angle
    np.testing.assert_array_equal(ds["actuator_pressure"].values, st.actuator_pressure)
    rigid_st = film_at_position(_rigid(), 0.1, 0.0, speed=40e3 * RPM)
    rigid = rigid_st.to_dataset()
    assert rigid["stinger_preload"].shape == (0,) and rigid["voltage"].shape == (0,)
    assert rigid_st.headline()["preload_um"] == [] and rigid_st.headline()["voltages_V"] == []


# --------------------------------------------------------------------- coefficients.py


def test_stiffness_at_a_low_frequency_is_the_static_derivative(equilibrium) -> None:
    """K at ω_e = 0.001 ω equals −∂F/∂e from central differences of the film force at
    positions ±1e-4 C about the equilibrium (the two agree to the difference's error);
    C is finite and the direct damping positive."""
    st = equilibrium
    case = st.case
    co = force_coefficients(st, 1e-3 * st.speed)
    c = case.bearing.clearance
    d = 1e-4
    fd = np.empty((2, 2))
    for j, (dx, dy) in enumerate([(d, 0.0), (0.0, d)]):
        plus = film_at_position(case, st.eps_x + dx, st.eps_y + dy, speed=st.speed)
        minus = film_at_position(case, st.eps_x - dx, st.eps_y - dy, speed=st.speed)
        fd[:, j] = -(np.array(plus.force) - np.array(minus.force)) / (2 * d * c)
    np.testing.assert_allclose(co.K[0], fd, rtol=2e-3, atol=2e-3 * np.abs(fd).max())
    assert co.C[0, 0, 0] > 0.0 and co.C[0, 1, 1] > 0.0
    assert co.K.shape == (1, 2, 2) and co.frequencies[0] == 1e-3 * st.speed


def test_dynamic_compliance_is_the_kelvin_voigt_bump_in_series(equilibrium) -> None:
    """c' = c_b/(1 + jγ ω_e/ω) + c_act where the foil is engaged (p̄ > 1), 0 elsewhere;
    γ = 0 gives the static compliance; the bump's loss tangent at ω_e is γ ω_e/ω."""
    st = equilibrium
    model = st.model
    gamma = st.case.foil.loss_factor  # type: ignore[union-attr]
    assert gamma > 0.0
    engaged = st.P.mean(axis=1) > 1.0
    assert engaged.any() and not engaged.all()
    nu = 0.4
    c_dyn = dynamic_compliance(st, nu * st.speed)
    assert c_dyn.dtype == complex
    np.testing.assert_array_equal(c_dyn[~engaged], 0.0)
    bump = c_dyn[engaged] - model.actuator_compliance[engaged]
    k_bump = 1.0 / bump  # ∝ the bump's complex stiffness
    np.testing.assert_allclose(k_bump.imag / k_bump.real, gamma * nu, rtol=1e-12)
    np.testing.assert_allclose(1.0 / k_bump.real, model.bump_compliance[engaged], rtol=1e-12)
    static = dynamic_compliance(st, nu * st.speed, loss_factor=0.0)
    np.testing.assert_allclose(static[engaged], model.compliance[engaged], rtol=1e-15)
    assert np.all(static.imag == 0.0)
    twice = dynamic_compliance(st, nu * st.speed, loss_factor=2 * gamma)
    k2 = 1.0 / (twice[engaged] - model.actuator_compliance[engaged])
    np.testing.assert_allclose(k2.imag / k2.real, 2 * gamma * nu, rtol=1e-12)
    rigid = film_at_position(_rigid(), 0.1, 0.0, speed=40e3 * RPM)
    np.testing.assert_array_equal(dynamic_compliance(rigid, 100.0), 0.0)
    assert dynamic_compliance(rigid, 100.0).shape == (32,)


def test_loss_factor_adds_damping_and_rigid_foil_none(equilibrium) -> None:
    """The bump's damper adds direct damping; a foil with γ = 0 equals the case with its
    loss factor overridden to 0."""
    st = equilibrium
    nu = 0.5 * st.speed
    with_loss = force_coefficients(st, nu)
    without = force_coefficients(st, nu, loss_factor=0.0)
    assert with_loss.C[0, 0, 0] > without.C[0, 0, 0]
    no_gamma = replace(st.case, foil=replace(st.case.foil, loss_factor=0.0))
    st0 = solve_equilibrium(no_gamma, speed=st.speed)
    same = force_coefficients(st0, nu)
    np.testing.assert_allclose(same.K, without.K, rtol=1e-6)
    np.testing.assert_allclose(same.C, without.C, rtol=1e-6)


def test_coefficient_headline_and_dataset(equilibrium) -> None:
    st = equilibrium
    freqs = np.array([0.5, 1.0]) * st.speed
    co = force_coefficients(st, freqs)
    h = co.headline()
    assert h["speed_rpm"] == pytest.approx(40e3, rel=1e-14)
    assert h["frequency_ratio"] == pytest.approx([0.5, 1.0], rel=1e-15)
    assert h["frequency_Hz"] == pytest.approx((freqs / (2 * math.pi)).tolist(), rel=1e-15)
    assert h["K_N_per_m"] == co.K.tolist() and h["C_Ns_per_m"] == co.C.tolist()
    assert h["eccentricity"] == st.eccentricity
    assert h["attitude_deg"] == pytest.approx(math.degrees(st.attitude_angle), rel=1e-15)
    ds = co.to_dataset()
    np.testing.assert_allclose(ds["frequency"].values, freqs / (2 * math.pi), rtol=1e-15)
    np.testing.assert_array_equal(ds["stiffness"].values, co.K)
    np.testing.assert_array_equal(ds["damping"].values, co.C)
    assert ds["stiffness"].attrs["units"] == "N/m" and ds["damping"].attrs["units"] == "N s/m"
    assert ds["frequency"].attrs["units"] == "Hz" and list(ds["i"].values) == ["X", "Y"]
    assert float(ds["speed"]) == st.speed and ds["speed"].attrs["units"] == "rad/s"
    assert float(ds["attitude_angle"]) == st.attitude_angle
    assert ds["attitude_angle"].attrs["units"] == "rad"
    assert float(ds["eccentricity"]) == st.eccentricity
    np.testing.assert_allclose(ds["frequency_ratio"].values, [0.5, 1.0], rtol=1e-15)


def test_coefficient_bad_inputs_are_one_line_errors(equilibrium) -> None:
    st = equilibrium
    for bad in ([], [0.0], [-1.0], [np.nan]):
        with pytest.raises(InputError) as err:
            force_coefficients(st, bad)
        assert str(err.value) == (
            f"excitation frequency {list(map(float, bad))!r} rad/s: every frequency must be > 0"
        )
    failed = replace(st, converged=False, message="no convergence in 3 iterations")
    with pytest.raises(SolverError) as s_err:
        force_coefficients(failed, 100.0)
    assert str(s_err.value) == (
        "the static point did not converge (no convergence in 3 iterations): the coefficients "
        "need a converged equilibrium"
    )
    rigid = film_at_position(_rigid(), 0.1, 0.0, speed=40e3 * RPM)
    with pytest.raises(InputError) as err:
        dynamic_compliance(rigid, 100.0, loss_factor=0.1)
    assert str(err.value) == "foil damping (loss factor) asked for a case without [foil]"
    with pytest.raises(InputError) as err:
        dynamic_compliance(st, 100.0, loss_factor=-0.1)
    assert str(err.value) == "loss factor = -0.1: must be >= 0"


# ------------------------------------------------------------- what the results write


def test_static_dataset_layout_and_labels(equilibrium) -> None:
    """The static NetCDF's layout, read by users and by ``load`` tools: every variable's
    dimensions, units and long name, the coordinates', and the headline's keys as attrs."""
    ds = equilibrium.to_dataset()
    layout = {
        name: (var.dims, var.attrs.get("units"), var.attrs.get("long_name"))
        for name, var in ds.variables.items()
    }
    assert layout == {
        "theta": (("theta",), "rad", "θ from −X"),
        "z": (("z",), "m", "z from the mid-plane"),
        "axis": (("axis",), None, "X along the load, Y 90° after it"),
        "speed": ((), "rad/s", "rotor speed ω"),
        "load": ((), "N", "static load W along +X"),
        "bearing_number": ((), "1", "bearing number Λ"),
        "eccentricity": ((), "1", "ε₀ = e/C"),
        "eps_X": ((), "1", "journal position ε_X (load direction)"),
        "eps_Y": ((), "1", "journal position ε_Y"),
        "attitude_angle": ((), "rad", "attitude angle φ₀ from +X"),
        "min_film": ((), "m", "minimum film thickness"),
        "min_film_angle": ((), "rad", "θ of the minimum film"),
        "drag_torque": ((), "N m", "viscous drag torque of the film"),
        "power_loss": ((), "W", "viscous power loss of the film"),
        "pressure": (("theta", "z"), "Pa", "p"),
        "gauge_pressure_mean": (("theta",), "Pa", "axially averaged gauge pressure p_A"),
        "film_thickness": (("theta", "z"), "m", "h"),
        "preload_shape": (("theta",), "m", "r_p (base preload shape)"),
        "force": (("axis",), "N", "film force"),
        "voltage": (("actuator",), "V", "actuator voltage"),
        "stinger_preload": (("stinger",), "m", "preload at each stinger (Eq. 3b)"),
        "actuator_pressure": (("stinger",), "Pa", "gauge pressure over each stinger's arc"),
    }
    assert set(ds.attrs) == {
        "bearing",
        "iterations",
        "reynolds_residual",
        "force_residual",
        "converged",
        "message",
    }


def test_static_headline_keys_and_values(equilibrium) -> None:
    """The ``--json`` headline: its unit-named keys and what each holds."""
    st = equilibrium
    h = st.headline()
    assert list(h) == [
        "speed_rpm",
        "load_N",
        "voltages_V",
        "bearing",
        "bearing_number",
        "eccentricity",
        "eps_X",
        "eps_Y",
        "attitude_deg",
        "min_film_um",
        "min_film_angle_deg",
        "force_N",
        "preload_um",
        "actuator_pressure_kPa",
        "drag_torque_Nm",
        "power_loss_W",
        "iterations",
        "reynolds_residual",
        "force_residual",
        "converged",
        "message",
    ]
    assert (h["bearing_number"], h["eccentricity"]) == (st.bearing_number, st.eccentricity)
    assert (h["eps_X"], h["eps_Y"]) == (st.eps_x, st.eps_y)
    assert (h["drag_torque_Nm"], h["power_loss_W"]) == (st.drag_torque, st.power_loss)
    assert h["load_N"] == st.case.operation.load
    assert (h["iterations"], h["reynolds_residual"]) == (st.iterations, st.residual)
    assert (h["force_residual"], h["message"]) == (st.force_residual, st.message)


def test_coefficient_dataset_layout(equilibrium) -> None:
    co = force_coefficients(equilibrium, [100.0, 200.0])
    ds = co.to_dataset()
    layout = {name: (var.dims, var.attrs.get("units")) for name, var in ds.variables.items()}
    assert layout == {
        "frequency": (("frequency",), "Hz"),
        "i": (("i",), None),
        "j": (("j",), None),
        "stiffness": (("frequency", "i", "j"), "N/m"),
        "damping": (("frequency", "i", "j"), "N s/m"),
        "frequency_ratio": (("frequency",), "1"),
        "speed": ((), "rad/s"),
        "load": ((), "N"),
        "eccentricity": ((), "1"),
        "attitude_angle": ((), "rad"),
    }
    assert list(ds["i"].values) == ["X", "Y"] and list(ds["j"].values) == ["X", "Y"]
    assert not ds.attrs  # everything is a variable with its units


def test_equilibrium_newton_failures_say_what_failed() -> None:
    """The inner Newton's outcomes, each with its message: the pressure solve at the start
    failing, no convergence within the iterations allowed (with the iterations counted),
    and the line search that cannot keep the film open. None is reported converged."""
    from foilbearing.reynolds import NewtonOptions
    from foilbearing.static import _Equilibrium

    case = _coarse()
    model = film_model(case)
    lam = case.bearing_number(40e3 * RPM)
    load = case.operation.load / (case.gas.ambient_pressure * case.bearing.radius**2)
    start_fails = _Equilibrium(model, lam, EquilibriumOptions(newton=NewtonOptions(max_iter=1)))
    out = start_fails.solve(load, np.zeros(2), None)
    assert not out.converged and out.force_res == np.inf
    assert out.message.startswith("pressure solve at the starting position failed: ")
    assert out.P.shape == (model.grid.size,) and np.all(np.isfinite(out.P))
    np.testing.assert_array_equal(out.eps, [0.0, 0.0])
    two = _Equilibrium(model, lam, EquilibriumOptions(max_iter=2)).solve(load, np.zeros(2), None)
    assert not two.converged and two.message == "no convergence in 2 iterations"
    full = _Equilibrium(model, lam, EquilibriumOptions()).solve(load, np.zeros(2), None)
    assert full.converged and full.message == "converged"
    assert two.iterations < full.iterations
    assert two.force_res > 1e-8 and two.residual >= 0.0
    # The equilibrium's own Newton steps: the start's pressure solve plus one per step.
    first = _Equilibrium(model, lam, EquilibriumOptions(max_iter=0)).solve(load, np.zeros(2), None)
    assert two.iterations == first.iterations + 2
    assert first.message == "no convergence in 0 iterations"
    # A film that may not thin below h/C = 0.99: no step keeps it open.
    closed = _Equilibrium(model, lam, EquilibriumOptions(min_film=0.99)).solve(
        load, np.zeros(2), None
    )
    assert not closed.converged
    assert closed.message == (
        "line search failed (the film would close below h/C = 0.99, or the residual did not "
        "decrease)"
    )
    assert closed.iterations == first.iterations + 1
    np.testing.assert_array_equal(closed.eps, [0.0, 0.0])


def test_failed_equilibrium_message_gives_where_it_stopped() -> None:
    """The failure message names the position, Λ and how much of the load was carried; its
    force residual is against the whole load (the film carries the part it stopped at)."""
    case = replace(_rigid(), operation=replace(_rigid().operation, load=200.0))
    st = solve_equilibrium(case, speed=2e3 * RPM)
    assert not st.converged
    assert f"at ε = ({st.eps_x:.4f}, {st.eps_y:.4f}), Λ = {st.bearing_number:.4g}" in st.message
    found = re.search(r"stopped at ([0-9.]+) % of the load; ", st.message)
    assert found is not None and 0.0 <= float(found.group(1)) < 100.0
    unbalanced = math.hypot(st.force[0] + 200.0, st.force[1]) / 200.0  # the reported film's
    assert st.force_residual == pytest.approx(unbalanced, rel=1e-6)
    assert st.force_residual > 0.5  # a rigid journal at 2000 rpm carries a few % of 200 N
    assert f"|F + W|/|W| = {st.force_residual:.2e}" in st.message
    assert st.message.endswith(
        "Try: a start from a nearby converged point, a finer grid, or check that the bearing "
        "can carry the load at this speed (the film may be closing)."
    )
