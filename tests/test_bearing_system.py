"""One bearing system, three verbs, the scales computed once (issue 46, item 2).

:class:`~foilbearing.bearing_system.BearingSystem` is built once from a case; its verbs
(equilibrium, coefficients/linearise, transient) share its film model and its
:class:`~foilbearing.bearing_system.Scales`, so they are one bearing by construction.
The tests check that they agree with each other as physics says they must: the
stiffness at a whirl frequency → 0 is the derivative of the static force, and the
transient system is at rest (zero residual, force balance) at the static equilibrium.
On the default case on 32 x 4, in a few seconds.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from foilbearing.bearing_system import BearingSystem, Scales
from foilbearing.case import Case, Grid, default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.control import constant_speed
from foilbearing.errors import InputError
from foilbearing.orbit.system import OrbitSimulation
from foilbearing.reynolds.transient import Inputs
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0
SRC = Path(__file__).resolve().parents[1] / "src" / "foilbearing"


def coarse(volts: float = 150.0) -> Case:
    """The default case at ``volts`` on 32 x 4 (static, linear and orbit), no disturbance."""
    case = default_case().with_voltages(volts)
    grid = Grid(32, 4, lift_off_smoothing=0.1, orbit_n_z=None, orbit_axial_order=None)
    return replace(case, grid=grid, disturbance=None)


# ---------------------------------------------------------------------------- scales
def test_the_scales_are_the_papers_nondimensionalisation_of_the_default_case() -> None:
    """σ, Λ at 10 krpm and the force scale by hand: the default case is μ = 1.85e-5 Pa·s,
    R = 20 mm, C = 100 µm, p_a = 101325 Pa, L = 35 mm, m = 0.897 kg (its case file)."""
    case = default_case()
    s = Scales.from_case(case)
    mu, r, c, pa, length, m = 1.85e-5, 0.02, 100e-6, 101325.0, 0.035, 0.897
    assert (s.viscosity, s.radius, s.length, s.ambient_pressure, s.mass) == (mu, r, length, pa, m)
    assert s.clearance == pytest.approx(c, rel=1e-15)
    # 12 μ R²/(p_a C²) = 12 · 1.85e-5 · 4e-4 / (101325 · 1e-8) = 8.7639e-5 s
    assert s.sigma == pytest.approx(8.7639e-5, rel=1e-4)
    assert s.sigma == pytest.approx(12 * mu * r * r / (pa * c * c), rel=1e-14)
    # Λ = 6 μ ω R²/(p_a C²) = 0.04589 at 10 krpm (0.046 in tests/test_case.py), ∝ ω
    omega = 10e3 * RPM
    assert s.bearing_number(omega) == pytest.approx(0.045888, rel=1e-4)
    assert s.bearing_number(omega) == pytest.approx(s.lambda_per_speed * omega, rel=1e-15)
    assert s.sigma == pytest.approx(2.0 * s.lambda_per_speed, rel=1e-15)  # 2Λ ∂/∂τ = σ ∂/∂t
    assert s.force == pytest.approx(pa * r * r, rel=1e-15) and s.force == pytest.approx(40.53)
    assert s.film_force_per_mass == pytest.approx(pa * r * r / (m * c), rel=1e-14)
    assert s.half_length == pytest.approx(length / (2 * r), rel=1e-15)
    # the foil's compliance p_a/(C k), the drag torque's μ ω R/C, p_a C/(2R) and R³
    k_b = case.foil.bump_stiffness
    assert float(s.compliance(k_b)) == pytest.approx(pa / (c * k_b), rel=1e-14)
    assert s.couette_shear(omega) == pytest.approx(mu * omega * r / c, rel=1e-14)
    assert s.pressure_shear == pytest.approx(pa * c / (2 * r), rel=1e-14)
    assert s.torque == pytest.approx(r**3, rel=1e-15)
    assert Scales.from_parts(case.bearing, case.gas).film_force_per_mass is None


def test_the_scales_are_the_numbers_the_old_code_paths_used() -> None:
    """Bit for bit the expressions the orbit, the case and the static force wrote by hand
    before the scales had a home (so tests/test_numbers_unchanged.py holds)."""
    case = coarse()
    s = Scales.from_case(case)
    b, gas = case.bearing, case.gas
    assert s.sigma == 12.0 * gas.viscosity * b.radius**2 / (gas.ambient_pressure * b.clearance**2)
    old_accel = gas.ambient_pressure * b.radius**2 / (case.rotor.mass * b.clearance)
    assert s.film_force_per_mass == old_accel
    omega = 37e3 * RPM
    old_lam = 6.0 * gas.viscosity * omega * b.radius**2 / (gas.ambient_pressure * b.clearance**2)
    assert s.bearing_number(omega) == old_lam == case.bearing_number(omega)
    assert s.force == gas.ambient_pressure * b.radius**2
    sim = OrbitSimulation(case, constant_speed(20e3 * RPM, 0.01))
    assert sim.system.sigma == s.sigma and sim.system.force_scale == old_accel
    assert sim.inputs(0.0, sim.volts(0.0)).lam == s.bearing_number(20e3 * RPM)


def test_a_bad_scale_is_refused_in_one_line() -> None:
    case = default_case()
    with pytest.raises(InputError, match=r"^Scales.clearance = -0.0001: expected a finite"):
        Scales.from_parts(replace(case.bearing, clearance=-1e-4), case.gas)
    with pytest.raises(InputError, match=r"^Scales.mass = nan"):
        Scales.from_parts(case.bearing, case.gas, mass=math.nan)
    massless = BearingSystem.from_case(coarse())
    massless = replace(massless, scales=Scales.from_parts(case.bearing, case.gas))
    with pytest.raises(InputError, match=r"^transient: no rotor mass; give mass \(kg\) > 0$"):
        massless.transient()
    with pytest.raises(InputError, match=r"^Scales.mass = -1.0"):
        massless.transient(mass=-1.0)
    with pytest.raises(InputError, match="static point on a"):
        massless.linearise(BearingSystem.from_case(coarse(), n_theta=16).equilibrium(), 1.0)


def test_no_module_writes_a_scale_by_hand() -> None:
    """σ, Λ, the force scale, L/(2R), the foil compliance p_a/(C k) and the drag torque's
    μ ω R/C are written in bearing_system/scales.py alone: no other
    module of src/ has a 6 or 12 times the viscosity, nor p_a times R² (the patterns the
    old copies had; a copy spelled otherwise would escape this check)."""
    patterns = [
        re.compile(r"\b(6|12)(\.0)?\s*\*\s*[\w.]*(viscosity|\bmu\b)"),
        re.compile(r"ambient_pressure\s*\*\s*[\w.]*radius"),
        re.compile(r"\bpa\s*\*\s*r\s*\*\s*r\b"),
        re.compile(r"\bpa\s*/\s*\(\s*c\s*\*"),  # the foil compliance p_a/(C k)
        re.compile(r"length\s*/\s*\(2(\.0)?\s*\*\s*[\w.]*radius"),  # L/(2R)
        re.compile(r"\bmu\s*\*\s*omega\s*\*\s*r\b"),  # the drag torque's μ ω R
    ]
    home = SRC / "bearing_system" / "scales.py"
    found = [
        f"{path.relative_to(SRC)}:{n}: {line.strip()}"
        for path in sorted(SRC.rglob("*.py"))
        if path != home and "testing" not in path.parts
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if any(p.search(line) for p in patterns)
    ]
    assert not found, "; ".join(found)
    assert any(p.search(line) for p in patterns for line in home.read_text().splitlines())


def test_the_steady_solvers_loose_arguments_are_unpacked_in_one_place() -> None:
    """The analyses call solve_steady, coupled_system and pressure_response through the
    film model (FilmModel.steady_film, steady_residual, perturbed_pressure), so their
    loose arguments (grid, compliance, lift-off) are written in film.py alone; reynolds/
    defines them and the tests' oracles may call them directly."""
    call = re.compile(r"\b(solve_steady|coupled_system|pressure_response)\(")
    found = sorted(
        str(path.relative_to(SRC))
        for path in SRC.rglob("*.py")
        if "reynolds" not in path.parts and "testing" not in path.parts
        for line in path.read_text(encoding="utf-8").splitlines()
        if call.search(line) and not line.lstrip().startswith(("def ", "#"))
    )
    assert found == ["film.py"] * 3, found


# ---------------------------------------------------------------------------- verbs
def test_the_verbs_are_the_analyses_functions() -> None:
    """A verb gives, to the last bit, what the function it delegates to gives."""
    case = coarse()
    bearing = BearingSystem.from_case(case)
    st = bearing.equilibrium(50e3 * RPM)
    ref = solve_equilibrium(case, speed=50e3 * RPM)
    assert st.converged and (st.eps_x, st.eps_y) == (ref.eps_x, ref.eps_y)
    np.testing.assert_array_equal(st.P, ref.P)
    fc = bearing.linearise(st, [0.5 * st.speed])
    np.testing.assert_array_equal(fc.K, force_coefficients(ref, [0.5 * ref.speed]).K)
    both = bearing.coefficients(50e3 * RPM, [0.5 * st.speed])
    np.testing.assert_array_equal(both.C, fc.C)
    # The load and voltages are the verb's arguments, as with_load/with_voltages are the case's.
    heavier = bearing.equilibrium(50e3 * RPM, "20 N", voltages=0.0)
    ref = solve_equilibrium(case.with_load("20 N").with_voltages(0.0), speed=50e3 * RPM)
    assert heavier.case.operation.load == 20.0 and heavier.eps_x == ref.eps_x
    assert bearing.lift_off is not None and bearing.lift_off == bearing.grid.lift_off
    assert case.foil is not None and case.actuators is not None
    assert bearing.foil_damping == case.foil.damping_law
    assert bearing.actuator == case.actuators.reading
    assert bearing.stiffness is not None and np.all(bearing.stiffness > 0.0)


READINGS = [("local", "compliant"), ("lobe", "compliant")]


@pytest.mark.parametrize(("response", "dynamics"), READINGS)
def test_the_stiffness_at_low_whirl_is_the_derivative_of_the_static_force(
    response: str, dynamics: str
) -> None:
    """K of the linearise verb at ω_e → 0 is −∂F/∂e of the equilibrium verb's film, by
    central differences (δ = 1e-5 C). The viscous bump's damper γ k_b/ω vanishes as ω_e → 0
    (its compliance is k_b (1 + jγ ω_e/ω)), so the quasi-static film is the static film.
    The tolerance, 1e-4 of the largest entry: the difference's truncation (δ² of a smooth
    film, the smoothed lift-off edge) is ~1e-10; the film solver's stopping rule (residual
    1e-10) allows an error of ~1e-9 N in each force, ~2e-6 of the difference K C δ ~ 5e-4 N;
    ω_e = 1e-6 ω moves K by ~1e-12. Measured: 4e-10 (local), 3e-10 (lobe, where the stacks'
    compression lowers the lobes in both the static film and the perturbed one)."""
    case = coarse().with_actuator_reading(response, dynamics)
    bearing = BearingSystem.from_case(case)
    st = bearing.equilibrium(50e3 * RPM)
    assert st.converged, st.message
    k = bearing.linearise(st, 1e-6 * st.speed).K[0]
    d, c = 1e-5, bearing.scales.clearance
    k_fd = np.zeros((2, 2))
    for j, (dx, dy) in enumerate(((d, 0.0), (0.0, d))):
        fp, fm = (
            np.array(bearing.film_at(st.eps_x + s * dx, st.eps_y + s * dy, st.speed).force)
            for s in (1, -1)
        )
        k_fd[:, j] = -(fp - fm) / (2 * d * c)
    np.testing.assert_allclose(k, k_fd, rtol=0.0, atol=1e-4 * np.abs(k_fd).max())


@pytest.mark.parametrize(("response", "dynamics"), READINGS)
def test_the_transient_system_rests_at_the_static_equilibrium(response: str, dynamics: str) -> None:
    """The transient verb's BDF equations at a steady state (c0 = 0, no history) vanish at the
    equilibrium verb's pressure and position: the film's rows (steady Reynolds with the
    smoothed lift-off row), the bump's state U = c_b q, and the journal's force balance
    p_a R²/(m C) ∫∫(P − 1) w + W/(m C) = 0. The tolerances are the static solver's: its
    Reynolds residual (``NewtonOptions.tol`` = 1e-10 per row, in the steady rows' units: the
    BDF rows times Aσ) and its force balance |F + W|/|W| ≤ 1e-8. Measured: 8e-14 and 3e-16."""
    case = coarse().with_actuator_reading(response, dynamics)
    bearing = BearingSystem.from_case(case)
    omega = 50e3 * RPM
    st = bearing.equilibrium(omega)
    assert st.converged, st.message
    system = bearing.transient()
    q = np.maximum(system.grid.gauge_mean(st.P), 0.0)
    u = system.c_bump * q if system.dynamic_bump else np.zeros(system.nt)
    assert system.dynamic_bump  # the viscous bump: U is a state, so its row is checked too
    y = np.concatenate([st.P.ravel(), u, [st.eps_x, st.eps_y, 0.0, 0.0]])
    s = bearing.scales
    load = np.array([case.operation.load / (s.mass * s.clearance), 0.0])  # W/(m C), 1/s²
    inputs = Inputs(s.bearing_number(omega), omega, bearing.preload, load)
    g, _h_min = system.newton_residual(y, inputs, 0.0, np.zeros(system.size))
    n, nt = system.n, system.nt
    film = g[:n] * system.area * s.sigma  # back to the steady rows' units (Eq. 4 per cell)
    assert np.abs(film).max() <= 1e-10
    np.testing.assert_allclose(g[n : n + nt], 0.0, atol=1e-15)  # dU/dt = r (c_b q − U)
    np.testing.assert_array_equal(g[n + nt : n + nt + 2], 0.0)  # dε/dt = v = 0
    accel = g[-2:]
    assert np.abs(accel).max() <= 1e-8 * load[0]
    # Without the load the journal is not at rest: the balance above is the film's force.
    fx = system.force_scale * (system.w @ (st.P.ravel() - 1.0))
    assert fx[0] == pytest.approx(-load[0], rel=1e-8)
    assert system.force_scale * s.mass * s.clearance * (system.w @ (st.P.ravel() - 1.0))[
        0
    ] == pytest.approx(st.force[0], rel=1e-12)


def test_the_orbit_builds_its_system_through_the_transient_verb() -> None:
    """The orbit's TransientSystem is the verb's: same arrays and scales, and its start
    state is the equilibrium verb's."""
    case = coarse()
    sim = OrbitSimulation(case, constant_speed(20e3 * RPM, 0.01))
    verb = BearingSystem.from_case(case.orbit_case()).transient()
    assert isinstance(sim.bearing, BearingSystem)
    for name in ("sigma", "force_scale", "gamma", "lift_delta", "c_stack"):
        assert getattr(sim.system, name) == getattr(verb, name), name
    for name in ("c_act", "c_bump", "w", "lobes"):
        np.testing.assert_array_equal(getattr(sim.system, name), getattr(verb, name))
    y0 = sim.initial_state()
    assert case.actuators is not None
    st = sim.bearing.equilibrium(20e3 * RPM, voltages=case.actuators.voltages)
    np.testing.assert_array_equal(y0[: sim.system.n], st.P.ravel())
    # A lighter rotor: the same film, accelerated more.
    light = sim.bearing.transient(mass=0.5 * case.rotor.mass)
    assert light.force_scale == pytest.approx(2.0 * verb.force_scale, rel=1e-15)


def test_the_film_at_a_heavily_loaded_lobe_position_is_the_equilibrium_s_film() -> None:
    """At 50 N and 40 krpm under the lobe reading (ε = 0.91) the journal overlaps the
    uncompressed lobe by 0.6 C: only the stack's compression opens the film, and a film
    solve from P = 1, D = 0 at that position stalls. The film at the equilibrium's position
    is the equilibrium's film (force = load to the solver's tolerance; D_n alike), and the
    stiffness is −∂F/∂e of that film by central differences (tolerance as above).
    Measured: the film's force 50 N to 3e-12 N, D_n to 4e-15 C; K and the differences
    agree to 2e-10 of the largest entry (before the ray walk, the differences of unconverged films gave
    K_XX 6.5 MN/m against 1.18)."""
    case = coarse().with_load("50 N")
    bearing = BearingSystem.from_case(case.with_actuator_reading("lobe", "compliant"))
    st = bearing.equilibrium(40e3 * RPM)
    assert st.converged and st.eccentricity > 0.85, st.message
    assert bearing.film.h_rigid(st.eps_x, st.eps_y).min() < -0.5  # the lobe overlaps
    at = bearing.film_at(st.eps_x, st.eps_y, st.speed)
    assert at.converged, at.message
    np.testing.assert_allclose(at.force, st.force, rtol=0.0, atol=1e-8 * 50.0)
    film = bearing.film
    np.testing.assert_allclose(
        film.stack_compression(at.P), film.stack_compression(st.P), rtol=0.0, atol=1e-9
    )
    k = bearing.linearise(st, 1e-6 * st.speed).K[0]
    d, c = 1e-5, bearing.scales.clearance
    k_fd = np.zeros((2, 2))
    for j, (dx, dy) in enumerate(((d, 0.0), (0.0, d))):
        films = [bearing.film_at(st.eps_x + s * dx, st.eps_y + s * dy, st.speed) for s in (1, -1)]
        assert all(f.converged for f in films)
        k_fd[:, j] = -(np.array(films[0].force) - np.array(films[1].force)) / (2 * d * c)
    np.testing.assert_allclose(k, k_fd, rtol=0.0, atol=1e-4 * np.abs(k_fd).max())
