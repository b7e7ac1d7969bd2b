"""Dynamic force coefficients: the perturbed Reynolds equation checked against independent results."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.errors import InputError
from foilbearing.static import film_at_position, solve_equilibrium

RPM = math.pi / 30.0


@pytest.mark.parametrize(
    ("subambient", "smoothing", "d"),
    [("lift-off", 0.0, 1e-5), ("retained", 0.0, 1e-5), ("lift-off", 0.2, 1e-4)],
)
def test_zero_frequency_stiffness_equals_static_derivative(
    subambient: str, smoothing: float, d: float
) -> None:
    # Static and linear analyses share one discretisation: as ν -> 0 (γ = 0, so the foil
    # is purely elastic) K must equal the finite-difference derivative of the static force.
    # Under lift-off the coefficients linearise the same complementarity law (ΔP = 0 on held
    # cells); the held set does not change under ±1e-5 C (asserted), where the force is smooth.
    # With the smoothed edge (κ = 0.2) they linearise its law, and the step (1e-4 C) may move
    # the sharp law's held set: the static force is smooth (docs/lift-off.md).
    case = default_case().with_voltages(150.0).with_subambient(subambient)
    assert case.foil is not None
    case = replace(
        case,
        foil=replace(case.foil, loss_factor=0.0),
        grid=replace(case.grid, lift_off_smoothing=smoothing),
    )
    st = solve_equilibrium(case, speed=50e3 * RPM)
    k = force_coefficients(st, 1e-6 * st.speed).K[0]
    c = case.bearing.clearance
    k_fd = np.zeros((2, 2))
    for j, (dx, dy) in enumerate(((d, 0.0), (0.0, d))):
        fp = film_at_position(case, st.eps_x + dx, st.eps_y + dy, speed=st.speed)
        fm = film_at_position(case, st.eps_x - dx, st.eps_y - dy, speed=st.speed)
        for f in (fp, fm):
            assert smoothing > 0.0 or np.array_equal(f.P == 1.0, st.P == 1.0)
        k_fd[:, j] = -(np.array(fp.force) - np.array(fm.force)) / (2 * d * c)
    np.testing.assert_allclose(k, k_fd, rtol=1e-3, atol=1e-3 * np.abs(k_fd).max())


def test_perturbed_system_on_the_block_lu_equals_the_sparse_assembly() -> None:
    # pressure_response assembles (J_P − jw H₀) + (J_H − jw P₀) S on the foil-coupled
    # pattern and factorises it with the block-cyclic LU; the same system built from the
    # scipy.sparse products and solved by SuperLU must give the same ΔP. Under lift-off
    # the cells the static film holds at ambient have ΔP = 0 (identity rows).
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    from foilbearing.coefficients import _journal_columns, dynamic_compliance
    from foilbearing.reynolds.perturbed import (
        foil_operator,
        pressure_response,
        reynolds_jacobians,
    )

    case = default_case().with_voltages(150.0)  # under the sharp lift-off law
    case = replace(case, grid=replace(case.grid, lift_off_smoothing=0.0))
    st = solve_equilibrium(case, speed=50e3 * RPM)
    grid, dh = st.model.grid, _journal_columns(st.model)
    nu = 0.4
    compliance = dynamic_compliance(st, nu * st.speed)
    assert np.iscomplexobj(compliance) and np.any(compliance != 0)
    j_p, j_h = reynolds_jacobians(grid, st.P, st.H, st.bearing_number)
    jw = 2j * nu * st.bearing_number * grid.d_theta * grid.d_z
    j_film = j_h - jw * sp.diags(st.P.ravel())
    system = (j_p - jw * sp.diags(st.H.ravel())) + j_film @ foil_operator(grid, compliance)
    rhs = -(j_film @ dh).astype(np.complex128)
    held = (st.P.ravel() == 1.0).astype(float)  # the complementarity sets them exactly
    assert 0 < held.sum() < held.size
    system = sp.diags(1.0 - held) @ system + sp.diags(held)
    rhs = (1.0 - held)[:, None] * rhs
    reference = splu(sp.csc_matrix(system)).solve(rhs)
    dp = pressure_response(grid, st.P, st.H, st.bearing_number, nu, compliance, dh, lift_off=True)
    assert np.abs(dp - reference).max() < 1e-10 * np.abs(reference).max()
    assert np.all(dp[held > 0] == 0.0)


def test_small_eccentricity_closed_form() -> None:
    # Rigid bearing, ε -> 0, Λ -> 0 (incompressible limit): with H = 1 + ε cos θ the first
    # harmonic solves ∇²p = Λ ∂H/∂θ + 2Λ ∂H/∂τ exactly, p = Re[g(Z) e^{jθ}],
    # g'' − g = jΛε + 2Λ ε', g(±Z_e) = 0, which gives (G = Z_e − tanh Z_e)
    #   K_XY = −K_YX = 2πΛG p_a R²/C,  C_XX = C_YY = 4πΛG p_a R²/(C ω),  K_XX = K_YY = 0,
    # and the whirl ratio K_XY/(ω C_XX) = 1/2. Tolerance 1 %: grid 64 x 16 and Λ = 0.014.
    base = default_case()
    rigid = replace(base, foil=None, actuators=None, grid=replace(base.grid, n_theta=64, n_z=16))
    speed = 3000 * RPM
    st = film_at_position(rigid, 0.01, 0.0, speed=speed)
    lam = st.bearing_number
    ze = rigid.bearing.length / (2 * rigid.bearing.radius)
    g = ze - math.tanh(ze)
    pa, r, c = rigid.gas.ambient_pressure, rigid.bearing.radius, rigid.bearing.clearance
    k_c = pa * r**2 / c * 2 * math.pi * lam * g
    c_d = pa * r**2 / (c * speed) * 4 * math.pi * lam * g
    fc = force_coefficients(st, 0.1 * speed)
    np.testing.assert_allclose(fc.K[0] / k_c, [[0, 1], [-1, 0]], atol=0.01)
    np.testing.assert_allclose(fc.C[0] / c_d, [[1, 0], [0, 1]], atol=0.01)


def test_concentric_symmetry() -> None:
    # Zero eccentricity, no preload: the bearing is isotropic.
    case = replace(default_case(), actuators=None)
    st = film_at_position(case, 0.0, 0.0, speed=60e3 * RPM)
    fc = force_coefficients(st, [0.3 * st.speed, 1.0 * st.speed])
    for k, cc in zip(fc.K, fc.C, strict=True):
        scale = np.abs(k).max()
        assert k[0, 0] == pytest.approx(k[1, 1], abs=1e-9 * scale)
        assert k[0, 1] == pytest.approx(-k[1, 0], abs=1e-9 * scale)
        assert cc[0, 0] == pytest.approx(cc[1, 1], abs=1e-9 * np.abs(cc).max())


def test_loss_factor_adds_direct_damping() -> None:
    st = solve_equilibrium(default_case().with_voltages(100.0), speed=40e3 * RPM)
    w = 0.5 * st.speed
    dampings = [force_coefficients(st, w, loss_factor=g).C[0] for g in (0.0, 0.1, 0.2)]
    for i in range(2):
        assert dampings[0][i, i] < dampings[1][i, i] < dampings[2][i, i]


def test_bad_inputs() -> None:
    st = solve_equilibrium(default_case(), speed=40e3 * RPM)
    with pytest.raises(InputError, match="frequency"):
        force_coefficients(st, 0.0)
    with pytest.raises(InputError, match="frequency"):
        force_coefficients(st, [-10.0])
    rigid = replace(default_case(), foil=None, actuators=None)
    st_r = solve_equilibrium(rigid, speed=40e3 * RPM)
    with pytest.raises(InputError, match="without \\[foil\\]"):
        force_coefficients(st_r, 100.0, loss_factor=0.1)


def test_film_model_keeps_the_bump_and_actuator_springs_apart() -> None:
    """The film model's two compliances are the bump's p_a/(C k_b) and the actuators' share,
    springs in series: their sum is p_a/(C k(θ)) of the structural stiffness function (Eq. 8)
    to round-off; the actuators' share is small halfway between the stingers, zero on the shimmed
    bearing (rigid shims), and under a stinger at most p_a/(C k_assy) − p_a/(C k_b)."""
    from foilbearing.film import film_model

    case = default_case().with_voltages(100.0)
    m = film_model(case)
    scale = case.gas.ambient_pressure / case.bearing.clearance
    k_b = case.foil.bump_stiffness
    np.testing.assert_allclose(m.bump_compliance, scale / k_b, rtol=1e-15)
    np.testing.assert_allclose(m.compliance, scale / m.stiffness, rtol=1e-12)
    k_assy = case.assembly_stiffness()
    at_stinger = np.argmin(np.abs(m.grid.theta - np.pi))  # the actuator at 180°
    # The smoothed k(θ) lies between k_assy and k_b, so the share under a stinger is
    # positive and at most that of the sharp Eq. 8 (k = k_assy).
    assert 0.3 * (scale / k_assy - scale / k_b) < m.actuator_compliance[at_stinger]
    assert m.actuator_compliance[at_stinger] <= scale / k_assy - scale / k_b
    # Halfway between actuators (0°, 120°, 240°) only the tail of the smoothed k(θ) is left:
    # 0.55 % of the bump's compliance with the default smoothness (measured).
    for mid in (0.0, 2 * np.pi / 3, 4 * np.pi / 3):
        i = np.argmin(np.abs(np.angle(np.exp(1j * (m.grid.theta - mid)))))
        assert m.actuator_compliance[i] < 0.01 * m.bump_compliance[i]
    shim = film_model(case.shimmed())
    assert np.all(shim.actuator_compliance == 0.0)
    np.testing.assert_allclose(shim.compliance, scale / k_b, rtol=1e-15)
