"""Fast tests that reach the bifurcation's shooting and branch, and the rotor's weight
shares, for mutation testing (issue 48 item 7): systems whose flow is known in closed form,
so that each test runs in well under a second and asserts an analytic fact.

The closed-form system is the Hopf normal form ``ṙ = r (μ + s r^(2k))``, ``θ̇ = ω``, with
decaying linear modes ``ż_j = −λ_j z_j`` beside it, seen through a fixed linear map S
(y = S ξ; S turns the circles into ellipses, so that the section along Re q̂ is a true
choice). With ``w = r^(−2k)``, ``ẇ = −2kμ w − 2ks``, so
``w(t) = w₀ e^(−2kμt) + s (e^(−2kμt) − 1)/μ``: cycles of radius ``r^(2k) = −μ/s``, period
2π/ω, radial multiplier ``exp(−2kμT)`` for s < 0 (``exp(2k|μ|T)`` for s > 0 on μ < 0) and
``exp(−λ_j T)`` for the linear modes.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from foilbearing.bifurcation import FlowMap, HopfPoint, ShootingError, hopf_branch, periodic_orbit
from foilbearing.bifurcation.shooting import bordered_solve, floquet_multipliers

OMEGA = 1.7
ELLIPSE = np.array([[2.0, 0.3], [0.0, 0.5]])


def _closed_form(
    s: float = -1.0,
    k: int = 1,
    decay: tuple[float, ...] = (0.7,),
    *,
    dense_max: int = 64,
    tangent: bool = False,
    blocks: bool = False,
    no_flow_above: float = math.inf,
    omega: float = OMEGA,
    ellipse: np.ndarray = ELLIPSE,
    centre: float = 0.0,
    p_hopf: float = 0.0,
) -> FlowMap:
    """The closed-form system; its equilibrium at ``centre`` in every component, its
    Hopf point at p = ``p_hopf`` (μ = p − p_hopf)."""
    n = 2 + len(decay)
    lam = np.asarray(decay, float)
    S = np.eye(n)
    S[:2, :2] = ellipse
    S_inv = np.linalg.inv(S)

    def advance(y0: np.ndarray, T: float, p: float) -> np.ndarray:
        return centre + moved(np.asarray(y0, float) - centre, T, p - p_hopf)

    def moved(y0: np.ndarray, T: float, mu: float) -> np.ndarray:
        if mu > no_flow_above:
            return np.full(n, np.nan)
        xi = S_inv @ np.asarray(y0, float)
        r0 = math.hypot(xi[0], xi[1])
        out = np.empty(n)
        out[2:] = xi[2:] * np.exp(-lam * T)
        if r0 == 0.0:
            out[:2] = 0.0
            return S @ out
        e = math.exp(-2 * k * mu * T)
        g = -2 * k * T if abs(mu * T) < 1e-14 else math.expm1(-2 * k * mu * T) / mu
        w = r0 ** (-2 * k) * e + s * g
        if w <= 0.0:  # blown up within T
            return np.full(n, np.nan)
        r = w ** (-1.0 / (2 * k))
        angle = math.atan2(xi[1], xi[0]) + omega * T
        out[0], out[1] = r * math.cos(angle), r * math.sin(angle)
        return S @ out

    def field(y: np.ndarray, p: float) -> np.ndarray:
        xi = S_inv @ (np.asarray(y, float) - centre)
        g = p - p_hopf + s * (xi[0] ** 2 + xi[1] ** 2) ** k
        rate = np.concatenate(
            [[g * xi[0] - omega * xi[1], omega * xi[0] + g * xi[1]], -lam * xi[2:]]
        )
        return S @ rate

    def central(y0: np.ndarray, T: float, mu: float, v: np.ndarray) -> np.ndarray:
        v = np.asarray(v, float)
        if v.ndim == 2:
            return np.column_stack([central(y0, T, mu, c) for c in v.T])
        h = 1e-5
        return (advance(y0 + h * v, T, mu) - advance(y0 - h * v, T, mu)) / (2 * h)

    return FlowMap(
        advance=advance,
        field=field,
        tangent=central if tangent else None,
        dense_max=dense_max,
        tangent_blocks=blocks,
    )


def _hopf(
    n: int,
    turn: complex = 1.0,
    unstable_side: int = 1,
    *,
    ellipse: np.ndarray = ELLIPSE,
    p_hopf: float = 0.0,
    omega: float = OMEGA,
) -> HopfPoint:
    q = np.zeros(n, complex)
    q[:2] = ellipse @ np.array([1.0, -1j])  # A q = iω q for the linear part S [[0,−ω],[ω,0]] S⁻¹
    return HopfPoint(p_hopf, omega, turn * q, unstable_side)


def _radius(y: np.ndarray, ellipse: np.ndarray = ELLIPSE) -> float:
    xi = np.linalg.solve(ellipse, y[:2])
    return float(np.hypot(*xi))


def _zero(n: int):  # type: ignore[no-untyped-def]
    return lambda mu: np.zeros(n)


PERIOD = 2 * math.pi / OMEGA


# ------------------------------------------------------------------------------ shooting


@pytest.mark.parametrize("tangent", [False, True])
def test_shooting_finds_the_closed_form_cycle_and_all_its_multipliers(tangent: bool) -> None:
    """μ = 0.04 on the supercritical form, from a guess 10 % off in radius and 2 % in
    period: r = 0.2, T = 2π/ω, multipliers {1, exp(−2μT), exp(−λT)} to 1e-6, by finite
    differences of the flow and by a given (central-difference) tangent alike."""
    flow = _closed_form(tangent=tangent)
    mu = 0.04
    guess = np.concatenate([ELLIPSE @ [0.22, 0.0], [0.01]])
    orbit = periodic_orbit(flow, guess, 1.02 * PERIOD, mu, tol=1e-10)
    assert _radius(orbit.state) == pytest.approx(0.2, abs=1e-8)
    assert abs(orbit.state[2]) < 1e-8
    assert orbit.period == pytest.approx(PERIOD, rel=1e-9)
    assert orbit.parameter == mu
    assert orbit.residual <= 1e-10 and orbit.iterations >= 2
    want = np.array([1.0, math.exp(-2 * mu * PERIOD), math.exp(-0.7 * PERIOD)])  # largest first
    np.testing.assert_allclose(np.abs(orbit.multipliers), want, rtol=1e-6)
    np.testing.assert_allclose(np.abs(orbit.nontrivial_multipliers), want[1:], rtol=1e-6)
    assert orbit.stable
    # on the section through the guess normal to the flow there
    normal = flow.field(guess, mu)
    assert normal @ (orbit.state - guess) == pytest.approx(0.0, abs=1e-9)


def test_a_cycle_on_the_stable_side_of_a_subcritical_hopf_is_unstable() -> None:
    """s = +1, μ = −0.04: r = 0.2 again, its radial multiplier exp(+2|μ|T) > 1."""
    flow = _closed_form(s=1.0)
    orbit = periodic_orbit(flow, np.concatenate([ELLIPSE @ [0.21, 0.0], [0.0]]), PERIOD, -0.04)
    assert _radius(orbit.state) == pytest.approx(0.2, abs=1e-8)
    assert abs(orbit.multipliers[0]) == pytest.approx(math.exp(0.08 * PERIOD), rel=1e-6)
    assert abs(orbit.nontrivial_multipliers[0]) > 1.0
    assert not orbit.stable


def test_a_guess_where_no_flow_exists_fails_with_its_residual() -> None:
    """Where the flow is undefined (NaN: contact, say), Newton stops at once and says so."""
    flow = _closed_form(no_flow_above=0.0)
    with pytest.raises(
        ShootingError, match=r"in 7 Newton iterations at p = 0.04 \(last residual nan"
    ):
        periodic_orbit(flow, np.array([0.4, 0.0, 0.0]), PERIOD, 0.04, max_iter=7)


def test_newton_that_cannot_reach_a_cycle_names_its_last_residual() -> None:
    """No cycle at μ < 0 on the supercritical form: the error gives the iterations and residual."""
    with pytest.raises(
        ShootingError, match=r"did not converge in 3 Newton iterations.*residual 0\."
    ):
        periodic_orbit(_closed_form(), np.array([0.4, 0.0, 0.0]), PERIOD, -0.04, max_iter=3)


@pytest.mark.parametrize("blocks", [False, True])
def test_the_matrix_free_path_agrees_with_the_dense_one(blocks: bool) -> None:
    """Five linear modes beside the cycle, once dense and once by GMRES and Arnoldi
    (dense_max = 1): the same orbit to 1e-9, and Arnoldi's three largest multipliers are
    the dense ones, {1, exp(−2μT), exp(−λ_min T)}."""
    decay = (0.3, 0.9, 1.5, 2.0, 3.0)
    mu = 0.04
    guess = np.concatenate([ELLIPSE @ [0.22, 0.02], 1e-3 * np.ones(5)])
    dense = periodic_orbit(
        _closed_form(decay=decay, tangent=True, blocks=blocks), guess, PERIOD, mu
    )
    free = periodic_orbit(_closed_form(decay=decay, dense_max=1), guess, PERIOD, mu, multipliers=3)
    np.testing.assert_allclose(free.state, dense.state, atol=1e-9)
    assert free.period == pytest.approx(dense.period, rel=1e-10)
    assert dense.multipliers.size == 7 and free.multipliers.size == 3
    want = np.array([1.0, math.exp(-2 * mu * PERIOD), math.exp(-0.3 * PERIOD)])
    np.testing.assert_allclose(np.abs(free.multipliers), want, rtol=1e-6)
    np.testing.assert_allclose(np.abs(dense.multipliers[:3]), want, rtol=1e-6)


def test_the_bordered_solve_is_the_block_system_dense_and_by_gmres() -> None:
    """On a linear flow (M = exp(AT) exactly), with borders 1e6 apart in scale: the dense
    and the GMRES solutions both satisfy [[M − I, C], [R, D]] x = b to 1e-8."""
    rng = np.random.default_rng(7)
    n = 4
    A = rng.normal(size=(n, n)) - 2.0 * np.eye(n)
    w, V = np.linalg.eig(A)

    def advance(y0: np.ndarray, T: float, p: float) -> np.ndarray:
        return np.real(V @ (np.exp(w * T) * np.linalg.solve(V, y0)))

    M = np.column_stack([advance(e, 0.8, 0.0) for e in np.eye(n)])
    cols = np.column_stack([rng.normal(size=n), 1e6 * rng.normal(size=n)])
    rows = np.vstack([rng.normal(size=n), 1e-3 * rng.normal(size=n)])
    corner = np.array([[0.5, 2e3], [0.0, 1e-3]])
    rhs = rng.normal(size=n + 2)
    block = np.block([[M - np.eye(n), cols], [rows, corner]])
    y0 = rng.normal(size=n)
    end = advance(y0, 0.8, 0.0)
    for dense_max in (64, 1):
        flow = FlowMap(advance, lambda y, p: -y, fd_step=1e-6, dense_max=dense_max)
        x = bordered_solve(flow, y0, 0.8, 0.0, end, cols, rows, corner, rhs)
        np.testing.assert_allclose(block @ x, rhs, atol=1e-7 * np.linalg.norm(rhs))


def test_gmres_on_noisy_products_refuses_the_step_and_says_why() -> None:
    """Products that are noise (no monodromy): GMRES cannot reduce the residual, and the
    step is refused with the residual it left, the tolerance asked and the cure."""
    rng = np.random.default_rng(3)
    n = 6

    def noise(y0, T, p, v):  # type: ignore[no-untyped-def]
        return rng.normal(size=n) * np.linalg.norm(v)

    flow = FlowMap(lambda y, T, p: y, lambda y, p: y, tangent=noise, dense_max=1)
    with pytest.raises(ShootingError, match=r"GMRES left .* \(asked 1e-08, taken below 0.001\)"):
        bordered_solve(
            flow, np.ones(n), 1.0, 0.0, np.ones(n), np.ones((n, 1)), np.ones((1, n)),
            np.zeros((1, 1)), np.ones(n + 1),
        )  # fmt: skip


def test_the_monodromy_of_a_zero_direction_is_zero_and_blocks_are_columns() -> None:
    """M·0 = 0 exactly (the flow's derivative is linear), and M V by one block call equals
    M V column by column (the finite differences of the flow)."""
    flow = _closed_form(decay=(0.5, 1.0))
    y0 = np.array([0.3, 0.1, 0.01, 0.02])
    end = flow.advance(y0, 1.0, 0.04)
    assert np.array_equal(flow.apply(y0, 1.0, 0.04, np.zeros(4), end), np.zeros(4))
    V = np.eye(4)[:, :2]
    fd = flow.apply_block(y0, 1.0, 0.04, V, end)
    exact = _closed_form(decay=(0.5, 1.0), tangent=True, blocks=True)
    np.testing.assert_allclose(exact.apply_block(y0, 1.0, 0.04, V, end), fd, atol=1e-6)
    values = floquet_multipliers(flow, y0, 1.0, 0.0)
    # at μ = 0 off the cycle: the linear modes' exp(−λ) are among the multipliers
    assert np.min(np.abs(np.abs(values) - math.exp(-1.0))) < 1e-6


# -------------------------------------------------------------------------------- branch


@pytest.mark.parametrize(("s", "kind"), [(-1.0, "supercritical"), (1.0, "subcritical")])
def test_the_branch_follows_r_squared_equal_to_mu_over_minus_s(s: float, kind: str) -> None:
    """Both signs of the cubic term: the type from p(2a) − p(a), every orbit on
    μ = −s r² to 1e-7, stable only when supercritical, the first orbit on the section
    along Re q̂ at distance a, the second at 2a; no fold."""
    flow = _closed_form(s=s)
    a = 0.02
    branch = hopf_branch(
        flow, _hopf(3), _zero(3), amplitude=a, steps=5, ds=0.5, p_scale=0.01, tol=1e-11
    )
    assert branch.bifurcation_type == kind
    r = np.array([_radius(o.state) for o in branch.orbits])
    np.testing.assert_allclose(branch.parameters, -s * r**2, atol=1e-9)
    np.testing.assert_allclose(branch.amplitudes, [np.linalg.norm(o.state) for o in branch.orbits])
    assert len(branch.orbits) == 7 and branch.message == "5 steps done"
    assert np.all(branch.stable) == (s < 0) and not np.any(branch.stable) == (s > 0)
    assert branch.folds == []
    # the section: Re q̂ is the ellipse's long axis through the first two orbits
    first, second = branch.orbits[0].state, branch.orbits[1].state
    assert np.linalg.norm(second) == pytest.approx(2 * np.linalg.norm(first), rel=1e-9)
    assert np.linalg.norm(first) == pytest.approx(a, rel=1e-9)
    assert abs(first @ second) == pytest.approx(np.linalg.norm(first) * np.linalg.norm(second))
    # the branch moves away from the Hopf point, in steps of about ds (scaled)
    assert np.all(np.diff(np.abs(branch.parameters)) > 0.0)


def test_the_section_does_not_depend_on_the_eigenvector_s_phase() -> None:
    """An eigenvector is known up to a complex factor: the branch's first orbit is the
    same for q, i q, −q and e^(0.7i) q / 3, and it lies on the ellipse's longer semi-axis
    direction (|Re q̂| ≥ |Im q̂|)."""
    flow = _closed_form()
    firsts = [
        hopf_branch(flow, _hopf(3, turn), _zero(3), amplitude=0.02, steps=0).orbits[0].state
        for turn in (1.0, 1j, -1.0, np.exp(0.7j) / 3.0)
    ]
    for state in firsts[1:]:
        np.testing.assert_allclose(state, firsts[0], atol=1e-10)
    # the first orbit (radius r on the ellipse) is where the ellipse is farthest from 0
    r = _radius(firsts[0])
    t = np.linspace(0, 2 * np.pi, 20001)
    farthest = np.max(np.hypot(*(ELLIPSE @ np.vstack([np.cos(t), np.sin(t)]))))
    assert np.linalg.norm(firsts[0]) == pytest.approx(r * farthest, rel=1e-7)
    assert firsts[0][np.argmax(np.abs(firsts[0]))] > 0.0


def test_the_resolution_of_the_hopf_type_is_the_flow_s_derivative_s() -> None:
    """At a = 0.002 along the ellipse's long semi-axis σ (r = a/σ) the two first cycles
    differ by 3(a/σ)² = 2.9e-6 in μ: above the finite differences' resolution
    (10 fd_step = 1e-6), below the exact derivative's (1e-5)."""
    a = 0.002
    sigma = np.linalg.norm(ELLIPSE, 2)
    fd = hopf_branch(_closed_form(), _hopf(3), _zero(3), amplitude=a, steps=0, tol=1e-12)
    exact = hopf_branch(
        _closed_form(tangent=True), _hopf(3), _zero(3), amplitude=a, steps=0, tol=1e-12
    )
    assert fd.bifurcation_type == "supercritical"
    assert exact.bifurcation_type == "degenerate"
    assert fd.parameters[1] - fd.parameters[0] == pytest.approx(3 * (a / sigma) ** 2, rel=1e-5)
    # the quintic form r' = r(μ − r⁴): 15a⁴ apart, below either resolution at a = 0.01
    quintic = hopf_branch(_closed_form(k=2), _hopf(3), _zero(3), amplitude=0.01, steps=0)
    assert quintic.bifurcation_type == "degenerate"


def test_a_hopf_point_with_the_other_unstable_side_swaps_the_type() -> None:
    """The type is the side of the cycles against the side where the equilibrium is
    unstable: told that side is μ < 0, the same cycles (at μ > 0) are subcritical."""
    branch = hopf_branch(
        _closed_form(), _hopf(3, unstable_side=-1), _zero(3), amplitude=0.02, steps=0
    )
    assert branch.bifurcation_type == "subcritical"


def test_the_branch_ends_where_it_should_and_says_where() -> None:
    """It ends on leaving the parameter range, on the stop condition, and where no flow
    exists (the corrector fails down to ds/64), each with the parameter in its message."""
    common = dict(amplitude=0.02, steps=30, ds=0.5, p_scale=0.01)
    out = hopf_branch(_closed_form(), _hopf(3), _zero(3), p_bounds=(-1.0, 0.01), **common)
    assert out.message.startswith("left the parameter range at p = ")
    assert out.parameters[-1] > 0.01 and np.all(out.parameters[:-1] <= 0.01)
    stop = hopf_branch(
        _closed_form(), _hopf(3), _zero(3), stop=lambda o: o.parameter > 0.005,
        describe=lambda mu: f"mu = {mu:.4f}", **common,
    )  # fmt: skip
    assert stop.message == f"stopped at mu = {stop.parameters[-1]:.4f} (the stop condition)"
    assert stop.parameters[-1] > 0.005 and np.all(stop.parameters[:-1] <= 0.005)
    wall = hopf_branch(_closed_form(no_flow_above=0.02), _hopf(3), _zero(3), **common)
    assert wall.message.startswith(f"the corrector failed at p = {wall.parameters[-1]:g}")
    left = float(wall.message.split("step down to ")[1].split(":")[0])
    assert 0.5 / 128 <= left < 0.5 / 64  # halved until below ds / 64
    assert wall.parameters[-1] <= 0.02
    # the branch reached the wall: the next step, ds/64 long, would have crossed it
    assert wall.parameters[-1] > 0.015


def test_an_equilibrium_that_moves_with_the_parameter_carries_the_section() -> None:
    """y_e(μ) = μ·c (the form shifted by a parameter-dependent offset): the cycles are the
    same about their moving centre, so μ = r² still holds, and the default amplitude is
    measured from y_e(μ)."""
    base = _closed_form()
    c = np.array([0.5, -0.2, 0.1])
    flow = FlowMap(
        advance=lambda y, T, mu: base.advance(y - mu * c, T, mu) + mu * c,
        field=lambda y, mu: base.field(y - mu * c, mu),
    )
    branch = hopf_branch(
        flow, _hopf(3), lambda mu: mu * c, amplitude=0.02, steps=3, ds=0.5, p_scale=0.01
    )
    r = np.array([_radius(o.state - o.parameter * c) for o in branch.orbits])
    np.testing.assert_allclose(branch.parameters, r**2, atol=1e-8)
    np.testing.assert_allclose(
        branch.amplitudes, [np.linalg.norm(o.state - o.parameter * c) for o in branch.orbits]
    )
    assert np.linalg.norm(branch.orbits[0].state - branch.orbits[0].parameter * c) == pytest.approx(
        0.02, rel=1e-8
    )


def _quintic_rk4(steps: int = 160) -> FlowMap:
    """ṙ = r(μ + r² − r⁴), θ̇ = ω on a fixed-step RK4 flow (a smooth map of y₀, T and μ:
    shooting sees its cycles, within O(h⁴) of the ODE's)."""

    def field(y: np.ndarray, mu: float) -> np.ndarray:
        r2 = y[0] * y[0] + y[1] * y[1]
        g = mu + r2 - r2 * r2
        return np.array([g * y[0] - OMEGA * y[1], OMEGA * y[0] + g * y[1]])

    def advance(y0: np.ndarray, T: float, mu: float) -> np.ndarray:
        y, h = np.array(y0, float), T / steps
        for _ in range(steps):
            k1 = field(y, mu)
            k2 = field(y + 0.5 * h * k1, mu)
            k3 = field(y + 0.5 * h * k2, mu)
            k4 = field(y + h * k3, mu)
            y = y + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        return y

    return FlowMap(advance=advance, field=field)


def test_the_subcritical_branch_turns_at_its_fold_and_regains_stability() -> None:
    """ṙ = μr + r³ − r⁵: the branch leaves μ = 0 backwards (unstable), turns at the fold
    μ = −1/4, r² = 1/2 (found within the branch's spacing), and comes back stable on the
    large cycles, every orbit on μ + r² − r⁴ = 0 to 1e-5 (the RK4 flow's error)."""
    q = np.array([1.0, -1j])
    branch = hopf_branch(
        _quintic_rk4(),
        HopfPoint(0.0, OMEGA, q, 1),
        _zero(2),
        amplitude=0.1,
        steps=14,
        ds=0.6,
        p_scale=0.05,
        p_bounds=(-1.0, 0.02),
    )
    assert branch.bifurcation_type == "subcritical"
    mu, r = branch.parameters, branch.amplitudes
    np.testing.assert_allclose(mu + r**2 - r**4, 0.0, atol=1e-5)
    assert len(branch.folds) == 1
    spacing = np.max(np.abs(np.diff(mu)))
    assert branch.folds[0] == pytest.approx(-0.25, abs=spacing)
    assert branch.folds[0] == mu[np.argmin(mu)]
    small, large = r**2 < 0.5 - 1e-3, r**2 > 0.5 + 1e-3
    assert small.any() and large.any()
    assert not np.any(branch.stable[small]) and np.all(branch.stable[large])


# ------------------------------------------------------ scales, defaults and the section


def test_a_cycle_far_from_the_origin_and_a_fast_one_are_found_alike() -> None:
    """The residual and the step are judged relative to 1 + ‖y‖ (the state's own scale):
    about an equilibrium at 1e4 in every component the cycle of μ = 0.04 is found to the
    same radius; and a fast cycle (T = 0.3) is found with its period 2π/ω."""
    far = _closed_form(centre=1e4)
    guess = 1e4 + np.concatenate([ELLIPSE @ [0.21, 0.0], [0.0]])
    orbit = periodic_orbit(far, guess, PERIOD, 0.04)
    assert _radius(orbit.state - 1e4) == pytest.approx(0.2, abs=1e-6)
    branch = hopf_branch(
        far, _hopf(3), lambda mu: np.full(3, 1e4), amplitude=0.02, steps=2, ds=0.5, p_scale=0.01
    )
    r = np.array([_radius(o.state - 1e4) for o in branch.orbits])
    np.testing.assert_allclose(branch.parameters, r**2, atol=1e-6)
    omega = 2 * math.pi / 0.3
    fast = _closed_form(omega=omega)
    orbit = periodic_orbit(fast, np.concatenate([ELLIPSE @ [0.21, 0.0], [0.0]]), 0.3, 0.04)
    assert orbit.period == pytest.approx(0.3, rel=1e-9)
    assert _radius(orbit.state) == pytest.approx(0.2, abs=1e-8)
    fast_branch = hopf_branch(
        fast, _hopf(3, omega=omega), _zero(3), amplitude=0.02, steps=2, ds=0.5, p_scale=0.01
    )
    np.testing.assert_allclose([o.period for o in fast_branch.orbits], 0.3, rtol=1e-9)


def test_an_integer_guess_and_a_given_section() -> None:
    """A guess given in integers is a state like any other (at μ = 1/4 the cycle r = 1/2
    passes through (1, 0, 0)); a given section normal holds the orbit on that section."""
    flow = _closed_form()
    orbit = periodic_orbit(flow, [1, 0, 0], PERIOD, 0.25)
    assert _radius(orbit.state) == pytest.approx(0.5, abs=1e-9)
    normal = np.array([0.0, 1.0, 0.0])
    guess = np.concatenate([ELLIPSE @ [0.21, 0.02], [0.0]])
    held = periodic_orbit(flow, guess, PERIOD, 0.04, normal=normal)
    assert held.state[1] == pytest.approx(guess[1], abs=1e-10)
    assert _radius(held.state) == pytest.approx(0.2, abs=1e-8)


def test_newton_s_iteration_count_is_the_one_it_needed() -> None:
    """The orbit reports the iterations it took: allowed exactly that many it converges,
    one fewer it does not; with none allowed the error says so (residual inf)."""
    flow = _closed_form()
    guess = np.concatenate([ELLIPSE @ [0.21, 0.0], [0.01]])
    orbit = periodic_orbit(flow, guess, PERIOD, 0.04)
    again = periodic_orbit(flow, guess, PERIOD, 0.04, max_iter=orbit.iterations)
    np.testing.assert_array_equal(again.state, orbit.state)
    with pytest.raises(ShootingError):
        periodic_orbit(flow, guess, PERIOD, 0.04, max_iter=orbit.iterations - 1)
    with pytest.raises(ShootingError, match=r"in 0 Newton iterations .*residual inf"):
        periodic_orbit(flow, guess, PERIOD, 0.04, max_iter=0)
    with pytest.raises(ShootingError, match=r"in 25 Newton iterations.*from a longer transient$"):
        periodic_orbit(flow, guess, PERIOD, -0.04)  # no cycle: the default 25 iterations
    with pytest.raises(ShootingError, match=r"^continuation corrector did not converge"):
        hopf_branch(flow, _hopf(3), _zero(3), amplitude=0.02, max_iter=0)


def test_the_number_of_multipliers_of_a_large_system() -> None:
    """Arnoldi returns the asked number of multipliers (default 6), at most n − 2; at
    n = dense_max the monodromy is still dense (all n)."""
    guess = np.concatenate([ELLIPSE @ [0.21, 0.0], 1e-3 * np.ones(7)])
    decay = (0.3, 0.5, 0.9, 1.2, 1.5, 2.0, 3.0)
    large = periodic_orbit(_closed_form(decay=decay, dense_max=4), guess, PERIOD, 0.04)
    assert large.multipliers.size == 6
    small = periodic_orbit(_closed_form(decay=decay[:3], dense_max=4), guess[:5], PERIOD, 0.04)
    assert small.multipliers.size == 3  # n − 2 of n = 5 > dense_max
    edge = periodic_orbit(_closed_form(decay=decay[:2], dense_max=4), guess[:4], PERIOD, 0.04)
    assert edge.multipliers.size == 4
    np.testing.assert_allclose(
        np.abs(edge.multipliers),
        [1.0, math.exp(-0.08 * PERIOD), math.exp(-0.3 * PERIOD), math.exp(-0.5 * PERIOD)],
        rtol=1e-6,
    )
    no_blocks = FlowMap(
        _closed_form().advance, _closed_form().field, tangent=None, tangent_blocks=True
    )
    orbit = periodic_orbit(no_blocks, guess[:3], PERIOD, 0.04)
    assert _radius(orbit.state) == pytest.approx(0.2, abs=1e-8)


def test_the_branch_record_each_orbit_on_the_last_one_s_section() -> None:
    """Past the first two, each orbit lies on the section through the previous one normal
    to the flow there (the corrector's phase condition), at the Hopf period, with its
    residual within tol; the branch keeps its Hopf point; a measure given is the amplitude."""
    flow = _closed_form()
    hopf = _hopf(3)
    branch = hopf_branch(
        flow, hopf, _zero(3), amplitude=0.02, steps=4, ds=0.5, p_scale=0.01,
        measure=lambda o: o.period,
    )  # fmt: skip
    assert branch.hopf is hopf
    orbits = branch.orbits
    for prev, this in itertools.pairwise(orbits[1:]):
        normal = flow.field(prev.state, prev.parameter)
        assert normal @ (this.state - prev.state) == pytest.approx(0.0, abs=1e-8)
    np.testing.assert_allclose([o.period for o in orbits], PERIOD, rtol=1e-9)
    np.testing.assert_allclose(branch.amplitudes, [o.period for o in orbits])
    assert all(0.0 <= o.residual <= 1e-9 for o in orbits)


def test_the_type_s_resolution_is_relative_to_the_hopf_parameter() -> None:
    """The same cycles (p(2a) − p(a) = 2e-6) are resolved at p_H = 0 (10 fd_step = 1e-6)
    but not at p_H = 2 (3e-6, the resolution relative to 1 + |p_H|); a subcritical Hopf at
    p_H = 2 is subcritical, and with the exact derivative a = 0.02 is resolved."""
    sigma = np.linalg.norm(ELLIPSE, 2)
    a = sigma * math.sqrt(2e-6 / 3.0)
    at_0 = hopf_branch(_closed_form(), _hopf(3), _zero(3), amplitude=a, steps=0, tol=1e-12)
    at_2 = hopf_branch(
        _closed_form(p_hopf=2.0), _hopf(3, p_hopf=2.0), _zero(3), amplitude=a, steps=0, tol=1e-12
    )
    assert at_0.parameters[1] - at_0.parameters[0] == pytest.approx(2e-6, rel=1e-4)
    assert at_0.bifurcation_type == "supercritical"
    assert at_2.bifurcation_type == "degenerate"
    sub = hopf_branch(
        _closed_form(s=1.0, p_hopf=2.0), _hopf(3, p_hopf=2.0), _zero(3), amplitude=0.02, steps=0
    )
    assert sub.bifurcation_type == "subcritical"
    assert sub.parameters[0] < 2.0
    exact = hopf_branch(_closed_form(tangent=True), _hopf(3), _zero(3), amplitude=0.02, steps=0)
    assert exact.bifurcation_type == "supercritical"


def test_the_section_s_sign_follows_the_largest_component() -> None:
    """With the ellipse's long axis along y₁, q and −q give the same first orbit, and its
    largest component (y₁) is positive."""
    tall = np.array([[0.5, 0.0], [0.3, 2.0]])
    flow = _closed_form(ellipse=tall)
    firsts = [
        hopf_branch(flow, _hopf(3, turn, ellipse=tall), _zero(3), amplitude=0.02, steps=0)
        .orbits[0]
        .state
        for turn in (1.0, -1.0, 1j)
    ]
    assert int(np.argmax(np.abs(firsts[0]))) == 1 and firsts[0][1] > 0.0
    for state in firsts[1:]:
        np.testing.assert_allclose(state, firsts[0], atol=1e-10)
