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

RPM = math.pi / 30.0


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def _setup(loss_factor: float | None) -> tuple[OrbitSimulation, np.ndarray, transient.Inputs]:
    """A coarse default case, its start state perturbed (some θ-rows engaged, some not)."""
    case = default_case().with_voltages(100.0)
    case = replace(case, grid=Grid(n_theta=32, n_z=4))
    if loss_factor is not None:
        assert case.foil is not None
        case = replace(case, foil=replace(case.foil, loss_factor=loss_factor))
    sim = OrbitSimulation(case, constant_speed(20e3 * RPM, 0.01))
    y = sim.initial_state()
    sys_ = sim.system
    rng = np.random.default_rng(3)
    y[: sys_.n] *= 1.0 + 0.02 * rng.standard_normal(sys_.n)
    y[sys_.n :] += 1e-3 * rng.standard_normal(sys_.nt + 4)
    inp = sim.inputs(1e-4, sim.volts(1e-4))
    return sim, y, inp


@pytest.fixture(scope="module", params=[None, 0.0], ids=["viscoelastic", "elastic"])
def setup(request: pytest.FixtureRequest) -> tuple[OrbitSimulation, np.ndarray, transient.Inputs]:
    return _setup(request.param)


def test_residual_and_storage_match_twins(setup) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    active = sys_.split(y)[0].mean(axis=1) > 1.0
    assert active.any() and not active.all()  # both branches of q = max(p̄ − 1, 0)
    c0 = 3000.0
    hist = np.random.default_rng(4).standard_normal(sys_.size)
    buf = np.empty(sys_.size)
    g, h_min = sys_.newton_residual(y, inp, c0, hist, buf)
    g_py, h_min_py = sys_.newton_residual_py(y, inp, c0, hist)
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
    factor = sys_.factorize(y, inp, c0)
    assert factor._fac is not None  # the compiled path
    rhs = np.random.default_rng(5).standard_normal(sys_.size)
    out = np.empty(sys_.size)
    dy = factor.solve(rhs, out)
    assert dy is out
    assert _rel(dy, factor.solve_py(rhs)) < 1e-12
    assert _rel(dy, spsolve(sys_.jacobian(y, inp, c0), rhs)) < 1e-9


def test_superlu_fallback_uses_the_twin(setup, monkeypatch: pytest.MonkeyPatch) -> None:
    sim, y, inp = setup
    sys_ = sim.system
    c0 = 3000.0
    ref = sys_.factorize(y, inp, c0)

    class Refuse:
        def __init__(self, *args: object, **kwargs: object) -> None:
            raise FloatingPointError("refused")

    monkeypatch.setattr(transient, "BlockCyclicLU", Refuse)
    factor = sys_.factorize(y, inp, c0)
    assert factor._fac is None
    rhs = np.random.default_rng(6).standard_normal(sys_.size)
    out = np.empty(sys_.size)
    assert factor.solve(rhs, out) is out
    assert _rel(out, ref.solve(rhs)) < 1e-10


def test_newton_update_matches_twin() -> None:
    rng = np.random.default_rng(7)
    y = rng.uniform(0.5, 2.0, 50)
    dy = 1e-2 * rng.standard_normal(50)
    w = rng.uniform(1.0, 1e4, 50)
    y_py = y.copy()
    err, p_min = kern.newton_update(y, dy, w, 40)
    err_py, p_min_py = kern.newton_update_py(y_py, dy, w, 40)
    np.testing.assert_array_equal(y, y_py)
    assert err == pytest.approx(err_py, rel=1e-15)
    assert p_min == p_min_py
    dy[3] = np.nan
    assert math.isnan(kern.newton_update(y, dy, w, 40)[0])
