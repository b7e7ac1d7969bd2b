"""Compiled kernels of the transient Newton iteration against their NumPy twins."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.sparse.linalg import spsolve

from foilbearing.case import Grid, default_case
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSimulation
from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds import transient
from foilbearing.reynolds.grid import FilmGrid
from foilbearing.testing import twins

RPM = math.pi / 30.0


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def _setup(
    loss_factor: float | None,
    subambient: str,
    response: str = "local",
    order: int = 2,
    smoothing: float = 0.0,
) -> tuple[OrbitSimulation, np.ndarray, transient.Inputs]:
    """A coarse default case, its start state perturbed (some θ-rows engaged, some not;
    under lift-off some cells held at ambient, some free). ``response = "lobe"``: the
    lobes follow their stacks (lobe + compliant), the film's rank-3 border. ``order``:
    the axial order of the grid; ``smoothing``: its lift-off smoothing κ."""
    case = default_case().with_voltages(100.0).with_actuator_reading(response, "compliant")
    grid = Grid(
        n_theta=32,
        n_z=4,
        axial_order=order,
        lift_off_smoothing=smoothing,
        orbit_n_z=None,
        orbit_axial_order=None,
    )
    case = replace(case, grid=grid)
    assert case.foil is not None
    case = replace(case, foil=replace(case.foil, subambient=subambient))
    if loss_factor is not None:
        case = replace(case, foil=replace(case.foil, loss_factor=loss_factor))
    sim = OrbitSimulation(case, constant_speed(20e3 * RPM, 0.01))
    y = sim.initial_state()
    sys_ = sim.system
    rng = np.random.default_rng(3)
    y[: sys_.n] *= 1.0 + 0.02 * rng.standard_normal(sys_.n)
    y[sys_.n :] += 1e-3 * rng.standard_normal(sys_.nt + 4)
    inp = sim.inputs(1e-4, sim.volts(1e-4))
    if response == "lobe":
        gain = sys_.lobe_gain(sys_.split(y)[0])
        assert sys_.n_lobe == 3 and np.any(gain > 0)  # loaded stacks move their lobes
    return sim, y, inp


@pytest.fixture(
    scope="module",
    params=[
        (None, "lift-off"),
        (0.0, "lift-off"),
        (None, "retained"),
        (0.0, "retained"),
        (None, "lift-off", "lobe"),
        (0.0, "retained", "lobe"),
        (None, "lift-off", "local", 4),
        (0.0, "retained", "lobe", 4),
        (None, "lift-off", "local", 2, 0.2),
        (0.0, "lift-off", "lobe", 4, 0.2),
    ],
    ids=[
        "viscoelastic-lift-off",
        "elastic-lift-off",
        "viscoelastic-retained",
        "elastic-retained",
        "lobe-viscoelastic-lift-off",
        "lobe-elastic-retained",
        "order4-viscoelastic-lift-off",
        "order4-lobe-elastic-retained",
        "smoothed-viscoelastic-lift-off",
        "order4-lobe-smoothed-elastic-lift-off",
    ],
)
def setup(request: pytest.FixtureRequest) -> tuple[OrbitSimulation, np.ndarray, transient.Inputs]:
    return _setup(*request.param)


def _hist(sim: OrbitSimulation, y: np.ndarray, inp: transient.Inputs, c0: float) -> np.ndarray:
    """BDF1 history from y with a small perturbation: both lift-off branches occur."""
    rng = np.random.default_rng(4)
    return -c0 * sim.system.storage(y, inp) + 1e-3 * c0 * rng.standard_normal(sim.system.size)


def test_residual_and_storage_match_twins(setup) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    active = sys_.split(y)[0].mean(axis=1) > 1.0
    assert active.any() and not active.all()  # both branches of q = max(p̄ − 1, 0)
    c0 = 3000.0
    hist = _hist(sim, y, inp, c0)
    buf = np.empty(sys_.size)
    branches = sys_.lift_state(y, inp, c0, hist)
    if sys_.lift_off:
        assert np.any(branches > 0) and np.any(branches < 0)  # held and free cells
    else:
        assert not np.any(branches)
    g, h_min = sys_.newton_residual(y, inp, c0, hist, buf)
    g_py, h_min_py = twins.newton_residual_py(sys_, y, inp, c0, hist)
    assert g is buf
    assert _rel(g, g_py) < 1e-12
    assert h_min == pytest.approx(h_min_py, rel=1e-14)
    q, h = sys_.storage_min_film(y, inp.preload)
    assert _rel(q, sys_.storage(y, inp)) < 1e-12
    assert h == pytest.approx(sys_.min_film(y, inp.preload), rel=1e-14)


def test_solve_matches_twin_and_jacobian(setup) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    hist = _hist(sim, y, inp, c0)
    factor = sys_.factorize(y, inp, c0, hist)
    assert factor._fac is not None  # the compiled path
    rhs = np.random.default_rng(5).standard_normal(sys_.size)
    out = np.empty(sys_.size)
    dy = factor.solve(rhs, out)
    assert dy is out
    assert _rel(dy, twins.solve_py(factor, rhs)) < 1e-12
    jac = sys_.jacobian(y, inp, c0, hist, lift_state=factor.lift_state)
    assert _rel(dy, spsolve(jac, rhs)) < 1e-9
    # A block of right-hand sides in one solve equals the column-by-column solves.
    block = np.column_stack([rhs, np.random.default_rng(8).standard_normal(sys_.size)])
    both = factor.solve_block(block)
    assert _rel(both[:, 0], dy) < 1e-12
    assert _rel(both[:, 1], factor.solve(np.ascontiguousarray(block[:, 1]))) < 1e-12


def test_newton_matrix_is_the_derivative_of_the_bdf_residual(setup) -> None:
    # The Newton matrix (the sparse twin that the compiled factor solves with, above) is the
    # derivative of the BDF residual, column by column by central differences, with the
    # lift-off branches held fixed: the lobes' rank-3 coupling (lobe + compliant)
    # included, whose compression D_n moves every θ-row of its lobe with the pressure at
    # its stinger. Under the smoothed law, on the law's scale and on a factor's own scale
    # of each cell.
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    hist = _hist(sim, y, inp, c0)
    states = [sys_.lift_state(y, inp, c0, hist)]
    if sys_.lift_delta > 0.0:
        states.append(sys_.factorize(y, inp, c0, hist).lift_state)
    for branches in states:
        jac = sys_.jacobian(y, inp, c0, hist, lift_state=branches).toarray()
        fd = np.empty_like(jac)
        for k in range(sys_.size):
            step = 1e-7 * max(1.0, abs(y[k]))
            up, down = y.copy(), y.copy()
            up[k] += step
            down[k] -= step
            g_up = sys_.newton_residual(up, inp, c0, hist, lift_state=branches)[0].copy()
            g_down = sys_.newton_residual(down, inp, c0, hist, lift_state=branches)[0]
            fd[:, k] = (g_up - g_down) / (2.0 * step)
        assert np.max(np.abs(jac - fd)) < 1e-6 * np.max(np.abs(jac))
    if sys_.n_lobe:  # the lobes' columns: a stinger row's pressure moves the whole lobe
        rows = np.flatnonzero(sys_.lobe_rows[np.argmax(sys_.lobe_gain(sys_.split(y)[0]))])
        col = rows[0] * sys_.grid.n_z
        far = np.flatnonzero(np.abs(np.arange(sys_.nt) - rows[0]) > 3)
        assert np.any(np.abs(fd[far * sys_.grid.n_z, col]) > 1e-6 * np.max(np.abs(jac)))


def test_superlu_fallback_uses_the_twin(setup, monkeypatch: pytest.MonkeyPatch) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    hist0 = _hist(sim, y, inp, c0)
    ref = sys_.factorize(y, inp, c0, hist0)

    class Refuse:
        def __init__(self, *args: object, **kwargs: object) -> None:
            raise FloatingPointError("refused")

    monkeypatch.setattr(transient, "BlockCyclicLU", Refuse)
    factor = sys_.factorize(y, inp, c0, hist0)
    assert factor._fac is None
    rhs = np.random.default_rng(6).standard_normal(sys_.size)
    out = np.empty(sys_.size)
    assert factor.solve(rhs, out) is out
    assert _rel(out, ref.solve(rhs)) < 1e-10
    # The Newton iteration on the fallback: its twin, equal to the compiled one.
    hist = 1e-3 * np.random.default_rng(9).standard_normal(sys_.size)
    w = sim.weights(y)
    y_a, y_b = y.copy(), y.copy()
    bufs_a = (np.empty(sys_.size), np.empty(sys_.size))
    bufs_b = (np.empty(sys_.size), np.empty(sys_.size))
    res_a = factor.newton_step(y_a, inp, c0, hist, w, *bufs_a)
    res_b = ref.newton_step(y_b, inp, c0, hist, w, *bufs_b)
    assert res_a[0] == pytest.approx(res_b[0], rel=1e-14)
    assert res_a[1] == pytest.approx(res_b[1], rel=1e-8)
    assert _rel(y_a, y_b) < 1e-10


def test_newton_update_matches_twin() -> None:
    rng = np.random.default_rng(7)
    y = rng.uniform(0.5, 2.0, 50)
    dy = 1e-2 * rng.standard_normal(50)
    w = rng.uniform(1.0, 1e4, 50)
    y_py = y.copy()
    err, p_min = kern.newton_update(y, dy, w, 40)
    err_py, p_min_py = twins.newton_update_py(y_py, dy, w, 40)
    np.testing.assert_array_equal(y, y_py)
    assert err == pytest.approx(err_py, rel=1e-15)
    assert p_min == p_min_py
    dy[3] = np.nan
    assert math.isnan(kern.newton_update(y, dy, w, 40)[0])


@pytest.mark.parametrize("known", [1, 2, 3])
def test_lift_off_branch_prediction_matches_twins(known: int) -> None:
    # The stepper's prediction of the next step's lift-off branches: the boundary
    # coordinate of a converged step, its extrapolation, and a kept factor adopting the
    # prediction (only when at most `most` cells move), each bit for bit its NumPy twin.
    rng = np.random.default_rng(known)
    n = 60
    state = np.where(rng.random(n) < 0.4, 1.0, -1.0) * rng.uniform(0.5, 2.0, n)
    slack = rng.uniform(0.0, 1.0, n)
    coord, coord_py = np.empty(n), np.empty(n)
    assert kern.lift_coordinate(state, slack, coord)
    assert twins.lift_coordinate_py(state, slack, coord_py)
    np.testing.assert_array_equal(coord, coord_py)
    assert not kern.lift_coordinate(np.zeros(n), slack, coord)  # suction retained
    s = [coord, coord + 0.1 * rng.standard_normal(n), coord + 0.2 * rng.standard_normal(n)]
    weights = (1.7, -0.9, 0.2) if known == 3 else (0.8, 0.0, 0.0)
    out, out_py = np.empty(n), np.empty(n)
    kern.predict_branches(*s, known, weights, out)
    twins.predict_branches_py(*s, known, weights, out_py)
    np.testing.assert_array_equal(out, out_py)
    assert set(np.unique(out)) <= {-1.0, 1.0}
    # a prediction that moves few cells is adopted, one that moves many is not
    for flips, most in ((3, 8), (12, 8)):
        branches = np.where(state > 0.0, 1.0, -1.0)
        branches[:flips] *= -1.0
        kept, kept_py = state.copy(), state.copy()
        moved = kern.adopt_branches(kept, branches, most)
        assert moved == twins.adopt_branches_py(kept_py, branches, most) == flips
        np.testing.assert_array_equal(kept, kept_py)
        np.testing.assert_array_equal(np.abs(kept), np.abs(state))
        adopted = np.array_equal(np.sign(kept), branches)
        assert adopted == (flips <= most)


def test_jacobian_blocks_match_twin(setup) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    g = sys_.grid
    n = sys_.n
    blocks = kern.JacobianBlocks(
        film=np.empty(g.shape),
        jp=np.empty(sys_.ws.jp.size),
        jh=np.empty(sys_.ws.jh.size),
        active=np.empty(sys_.nt),
        jc=np.empty(sys_.c_indices.size),
        a_pe=np.empty((n, 2)),
        lift_state=np.empty(n),
        a_pl=np.empty((n, sys_.n_lobe)),
        lobe_gain=np.empty(sys_.n_lobe),
    )
    H, jp, jh, active, jc, a_pe, lift_state, a_pl, gain = blocks
    hist = _hist(sim, y, inp, c0)
    step = sys_.step_inputs(inp, c0, hist)
    held = kern.transient_jacobian(
        y, tuple(step), *sys_.kernel_groups, sys_.lift_off, True, tuple(blocks)
    )
    (H_py, jp_py, jh_py, active_py, jc_py, a_pe_py, state_py, held_py, a_pl_py, gain_py) = (
        twins.jacobian_blocks_py(sys_, y, inp, c0, hist)
    )
    assert active.any() and not active.all()
    np.testing.assert_array_equal(active, active_py)
    np.testing.assert_array_equal(lift_state > 0, held_py)
    assert held == held_py.sum() and (held > 0) == sys_.lift_off
    np.testing.assert_array_equal(gain, gain_py)
    pairs = [(H, H_py), (jp, jp_py), (jh, jh_py), (jc, jc_py), (a_pe, a_pe_py)]
    for got, want in pairs + ([(a_pl, a_pl_py)] if sys_.n_lobe else []):
        assert _rel(got, want) < 1e-12
    if sys_.lift_off or sys_.lift_delta > 0.0:  # branches, or the smoothed rows' scales
        assert _rel(lift_state, state_py) < 1e-12
    else:
        assert not np.any(lift_state)


def test_border_matches_twin(setup) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    factor = sys_.factorize(y, inp, c0, _hist(sim, y, inp, c0))
    a = factor.arrays
    lobe = (a.lobe_border, a.lobe_inv, a.lobe_gain)
    y_border, small_inv = twins.border_py(sys_, factor.lu, a.a_pe, c0, lobe)
    assert _rel(factor.arrays.y_border, y_border) < 1e-12
    assert _rel(factor.arrays.small_inv, small_inv) < 1e-12


@pytest.mark.parametrize("stale", [False, True], ids=["fresh", "stale"])
def test_newton_step_matches_twin(setup, stale: bool) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    hist = _hist(sim, y, inp, c0)
    factor = sys_.factorize(y, inp, 2500.0 if stale else c0, hist)
    w = sim.weights(y)
    y_c, y_py = y.copy(), y.copy()
    g, dy = np.empty(sys_.size), np.empty(sys_.size)
    g_py, dy_py = np.empty(sys_.size), np.empty(sys_.size)
    h_min, err, p_min = factor.newton_step(y_c, inp, c0, hist, w, g, dy)
    h_py, err_py, p_py = twins.newton_step_py(factor, y_py, inp, c0, hist, w, g_py, dy_py)
    assert h_min == pytest.approx(h_py, rel=1e-14)
    assert err == pytest.approx(err_py, rel=1e-9)
    assert p_min == pytest.approx(p_py, rel=1e-12)
    assert _rel(g, g_py) < 1e-12
    assert _rel(dy, dy_py) < 1e-9
    assert _rel(y_c, y_py) < 1e-12


def test_newton_step_leaves_a_closed_film(setup) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    factor = sys_.factorize(y, inp, 3000.0, _hist(sim, y, inp, 3000.0))
    closed = y.copy()
    closed[sys_.n + sys_.nt] = 5.0  # ε_X = 5 C: the film closes
    before = closed.copy()
    g, dy = np.empty(sys_.size), np.empty(sys_.size)
    w = sim.weights(y)
    hist = np.zeros(sys_.size)
    h_min, err, p_min = factor.newton_step(closed, inp, 3000.0, hist, w, g, dy)
    assert h_min <= 0.0 and math.isnan(err) and math.isnan(p_min)
    np.testing.assert_array_equal(closed, before)
    twin = twins.newton_step_py(factor, closed, inp, 3000.0, hist, w, g, dy)[0]
    assert twin == pytest.approx(h_min, rel=1e-14)  # the axial means summed in another order
    np.testing.assert_array_equal(closed, before)


@pytest.mark.parametrize("order", [2, 4])
def test_fused_jacobians_equal_the_separate_kernels(order: int) -> None:
    rng = np.random.default_rng(10)
    n_theta, n_z = 16, 5
    P = rng.uniform(0.8, 2.0, (n_theta, n_z))
    H = rng.uniform(0.3, 1.5, (n_theta, n_z))
    nnz = kern.stencil_pattern(n_theta, n_z, order)[1].size
    axial = tuple(FilmGrid(n_theta, n_z, 0.5, axial_order=order).axial)
    jp, jh, jp2, jh2 = (np.empty(nnz) for _ in range(4))
    for lam in (0.5, 30.0):
        kern.jacobian_P(P, H, lam, 0.2, 0.1, axial, jp)
        kern.jacobian_H(P, H, lam, 0.2, 0.1, axial, jh)
        kern._jacobian_both(P, H, lam, 0.2, 0.1, axial, jp2, jh2)
        np.testing.assert_array_equal(jp2, jp)
        np.testing.assert_array_equal(jh2, jh)


def test_newton_solve_matches_twin(setup) -> None:
    # The compiled Newton loop and its NumPy twin: same outcome, iterations, iterate and
    # lift-off branches. Under lift-off the perturbed start moves many cells to the other
    # branch, so the factor is refreshed at the iterate (with those branches) until the
    # iteration converges.
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    hist = -c0 * sys_.storage(y, inp)  # BDF1 from y: the step's own change is small
    w = sim.weights(y)
    controls = (3.0, 0.1, 6)
    results = []
    for newton_solve in (transient.TransientFactor.newton_solve, twins.newton_solve_py):
        factor = sys_.factorize(y, inp, c0, hist)
        y_k = y.copy()
        work = (np.empty(sys_.size), np.empty(sys_.size), np.empty(sys_.size))
        outcomes = []
        for _ in range(6):
            out = newton_solve(factor, y_k, inp, c0, hist, w, work, controls, True, math.inf)
            outcomes.append(out)
            if out[0] != transient.NEWTON_REFRESH:
                break
            factor = sys_.factorize(y_k, inp, c0, hist, factor.lift_state)
        results.append((outcomes, y_k, work[2], factor.lift_state.copy()))
    (a, y_a, q_a, s_a), (b, y_b, _q_b, s_b) = results
    assert [o[:2] for o in a] == [o[:2] for o in b]
    assert a[-1][0] == transient.NEWTON_CONVERGED
    assert a[-1][3] == pytest.approx(b[-1][3], rel=1e-12)
    assert _rel(y_a, y_b) < 1e-10
    np.testing.assert_array_equal(s_a > 0, s_b > 0)
    assert _rel(q_a, sys_.storage(y_a, inp)) < 1e-12
    # The error left (weighted, against a tightly converged iterate) is within the tolerance.
    factor = sys_.factorize(y_a, inp, c0, hist, s_a)
    y_t = y_a.copy()
    work = (np.empty(sys_.size), np.empty(sys_.size), np.empty(sys_.size))
    for _ in range(8):  # the smoothed law's kink (width δ) may ask for fresh factors
        tight = factor.newton_solve(y_t, inp, c0, hist, w, work, (1e-6, 1e-9, 40), True, math.inf)
        if tight[0] not in (transient.NEWTON_REFRESH, kern.NEWTON_TOO_SLOW):
            break
        factor = sys_.factorize(y_t, inp, c0, hist, factor.lift_state)
    assert tight[0] == transient.NEWTON_CONVERGED
    if sys_.lift_delta > 0.0:  # the smoothed law: every cell above ambient
        assert np.all(y_t[: sys_.n] > 1.0)
    tol = max(controls[0], controls[1] * a[-1][2])
    # The same branches, but for a cell on the border between them: at ambient within the
    # tolerance (one cell of the order-4 lift-off set-up).
    moved = np.flatnonzero((factor.lift_state > 0) != (s_a > 0))
    assert moved.size <= 1
    assert np.all(np.abs(y_t[moved] - 1.0) * w[moved] < tol)
    # Under the smoothed law the contraction measured across its kink is optimistic: the
    # error left is up to 2.5 tol there (measured, κ = 0.2 on 32 × 4); 2 tol elsewhere.
    assert np.max(np.abs(y_a - y_t) * w) < (3 if sys_.lift_delta > 0.0 else 2) * tol
    if sys_.lift_off:  # the complementarity holds: P >= 1 on free cells, P = 1 on held ones
        p, s_t = y_t[: sys_.n], factor.lift_state
        assert np.all(p[s_t < 0] > 1.0 - 1e-6) and np.all(np.abs(p[s_t > 0] - 1.0) < 1e-12)


def test_slowly_contracting_fresh_factor_is_refreshed_not_abandoned(setup) -> None:
    # A factor taken away from the solution (here: with the journal 0.02-0.04 C off in Y)
    # contracts slowly; the iteration asks for a refresh at its iterate instead of giving up (which
    # would halve the time step), both twins alike, and the refreshed factor converges.
    sim, y, inp = setup
    sys_ = sim.system
    if sys_.n_lobe:
        pytest.skip(
            "the iteration's control does not depend on the reading; the factor's "
            "contraction from 0.02 C away does (set up on the local readings)"
        )
    c0 = 3000.0
    k = sys_.n + sys_.nt
    far = y.copy()
    # Under the smoothed law each cell's row keeps its size across the kink (the factor's
    # own scales), and a factor from 0.02 C away converges (6 iterations): 0.04 C there.
    far[k + 1] += 0.04 if sys_.lift_delta > 0.0 else 0.02
    hist = -c0 * sys_.storage(y, inp)
    w = sim.weights(y)
    controls = (0.3, 0.001, 10)
    outcomes = []
    for newton_solve in (transient.TransientFactor.newton_solve, twins.newton_solve_py):
        factor = sys_.factorize(far, inp, c0, hist)
        y_k = y.copy()
        work = (np.empty(sys_.size), np.empty(sys_.size), np.empty(sys_.size))
        out = newton_solve(factor, y_k, inp, c0, hist, w, work, controls, True, math.inf)
        outcomes.append((out, y_k))
    (a, y_a), (b, y_b) = outcomes
    assert a[0] == b[0] == transient.NEWTON_REFRESH
    # Rates above 0.5, not yet diverging; under the smoothed law a second iteration that
    # diverges (cells across its kink) is taken back and refreshed at once.
    assert a[1] == b[1] >= (2 if sys_.lift_delta > 0.0 else 3)
    assert _rel(y_a, y_b) < 1e-10
    work = (np.empty(sys_.size), np.empty(sys_.size), np.empty(sys_.size))
    branches = None
    for _ in range(6):  # under lift-off, refreshed again while cells change branch
        factor = sys_.factorize(y_a, inp, c0, hist, branches)
        again = factor.newton_solve(y_a, inp, c0, hist, w, work, controls, True, a[2])
        if again[0] != transient.NEWTON_REFRESH:
            break
        branches = factor.lift_state
    assert again[0] == transient.NEWTON_CONVERGED


@pytest.mark.parametrize("order", [1, 2, 3, 4])
@pytest.mark.parametrize("count", [1, 2, 3, 5])
def test_bdf_setup_is_exact_for_polynomials_of_its_order(order: int, count: int) -> None:
    # Variable steps. With k = min(order, count) past storages, c0 Q(t_new) + hist is the
    # derivative of the interpolant, exact for polynomials of degree k; the predictor through
    # min(k + 1, count) past states is exact for polynomials of degree min(k + 1, count) − 1.
    # Compiled kernel and NumPy twin (np.poly derivatives) agree.
    rng = np.random.default_rng(8 + order + count)
    n, t_new = 7, 1e-3
    times = t_new - np.cumsum([1e-4, 2e-4, 1.5e-4, 3e-4, 2.5e-4])
    k = min(order, count)
    deg_q, deg_y = k, min(k + 1, count) - 1
    cq, cy = rng.standard_normal((deg_q + 1, n)), rng.standard_normal((deg_y + 1, n))

    def poly(c: np.ndarray, t: float) -> np.ndarray:
        return sum(c[j] * t**j for j in range(c.shape[0]))

    def dpoly(c: np.ndarray, t: float) -> np.ndarray:
        return sum(j * c[j] * t ** (j - 1) for j in range(1, c.shape[0]))

    ys = np.array([poly(cy, t) for t in times])
    qs = np.array([poly(cq, t) for t in times])
    atol = np.full(n, 1e-5)
    outs = [np.empty((3, n)) for _ in range(2)]
    c0s = [
        setup_(t_new, tuple(kern.BdfHistory(times, ys, qs, count)), order, atol, 1e-4, *out)
        for setup_, out in zip((kern.bdf_setup, twins.bdf_setup_py), outs, strict=True)
    ]
    assert c0s[0] == pytest.approx(c0s[1], rel=1e-12)
    np.testing.assert_allclose(outs[0], outs[1], rtol=1e-9, atol=1e-9)
    guess, hist, weights = outs[0]
    np.testing.assert_allclose(c0s[0] * poly(cq, t_new) + hist, dpoly(cq, t_new), rtol=1e-8)
    np.testing.assert_allclose(guess, poly(cy, t_new), rtol=1e-8, atol=1e-10)
    np.testing.assert_allclose(weights, 1.0 / (atol + 1e-4 * np.abs(guess)), rtol=1e-14)
    h, h1 = t_new - times[0], times[0] - times[1]
    if k == 1:  # implicit Euler
        assert c0s[0] == pytest.approx(1 / h, rel=1e-14)
    elif k == 2:  # variable-step BDF2, ρ = h/h1: c0 = (1 + 2ρ)/((1 + ρ) h)
        rho = h / h1
        assert c0s[0] == pytest.approx((1 + 2 * rho) / ((1 + rho) * h), rel=1e-14)
