"""Block cyclic tridiagonal LU against its NumPy twin, spsolve and SuperLU."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import splu, spsolve

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.blocksolve import BlockCyclicLU
from foilbearing.testing import twins

SIZES = [(3, 1), (3, 2), (4, 3), (8, 4), (96, 12)]


def _random_coupled(n_theta: int, n_z: int, seed: int) -> tuple[np.ndarray, sp.csr_matrix]:
    """Random dense blocks on the coupled pattern plus a dominant diagonal."""
    rng = np.random.default_rng(seed)
    indptr, indices = kern.coupled_pattern(n_theta, n_z)
    n = n_theta * n_z
    data = rng.uniform(-1.0, 1.0, indices.size)
    rows = np.repeat(np.arange(n), 3 * n_z)
    data[rows == indices] += 3.0 * n_z
    return data, sp.csr_matrix((data, indices, indptr), shape=(n, n))


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


@pytest.mark.parametrize(("n_theta", "n_z"), SIZES)
def test_kernel_matches_twin_and_spsolve(n_theta: int, n_z: int) -> None:
    data, mat = _random_coupled(n_theta, n_z, seed=n_theta * 100 + n_z)
    fac = kern.block_cyclic_alloc(n_theta, n_z)
    fac_py = kern.block_cyclic_alloc(n_theta, n_z)
    res = kern.block_cyclic_factor(data, n_theta, n_z, fac)
    res_py = twins.block_cyclic_factor_py(data, n_theta, n_z, fac_py)
    assert res[0] == res_py[0] == kern.BC_OK
    assert res[1] == res_py[1]
    np.testing.assert_allclose(res[2:], res_py[2:], rtol=1e-12)
    assert _rel(fac, fac_py) < 1e-12
    n = n_theta * n_z
    rng = np.random.default_rng(1)
    for ncol in (1, 2):
        rhs = rng.normal(size=(n, ncol))
        out = np.empty_like(rhs)
        out_py = np.empty_like(rhs)
        kern.block_cyclic_solve(fac, rhs, out)
        twins.block_cyclic_solve_py(fac_py, rhs, out_py)
        assert _rel(out, out_py) < 1e-12
        ref = spsolve(mat.tocsc(), rhs).reshape(n, ncol)
        assert _rel(out, ref) < 1e-10
    lu = BlockCyclicLU(data, n_theta, n_z)
    b1 = rng.normal(size=n)
    x1 = lu.solve(b1)
    assert x1.shape == (n,)
    assert _rel(x1, spsolve(mat.tocsc(), b1)) < 1e-10


@pytest.mark.parametrize(("n_theta", "n_z"), [(3, 2), (8, 4), (96, 12)])
def test_complex_matrix_matches_spsolve(n_theta: int, n_z: int) -> None:
    # The perturbation at a frequency is complex: the same kernels, pivoting by modulus.
    data, mat = _random_coupled(n_theta, n_z, seed=7)
    rng = np.random.default_rng(8)
    cdata = data + 1j * rng.uniform(-1.0, 1.0, data.size)
    cmat = sp.csr_matrix((cdata, mat.indices, mat.indptr), shape=mat.shape)
    rhs = rng.standard_normal((mat.shape[0], 2)) + 1j * rng.standard_normal((mat.shape[0], 2))
    x = BlockCyclicLU(cdata, n_theta, n_z).solve(rhs)
    assert x.dtype == np.complex128
    assert _rel(x, spsolve(cmat.tocsc(), rhs)) < 1e-12
    # a real matrix with a complex right-hand side
    x_real = BlockCyclicLU(data, n_theta, n_z).solve(rhs)
    assert _rel(x_real, spsolve(mat.tocsc(), rhs)) < 1e-12


def test_real_newton_matrix_matches_splu() -> None:
    """The transient Newton matrix of the default case (as TransientSystem.factorize builds it)."""
    from foilbearing.case import default_case
    from foilbearing.control import constant_speed
    from foilbearing.orbit import OrbitSimulation

    sim = OrbitSimulation(
        default_case().with_voltages(150.0), constant_speed(30000 * math.pi / 30, 0.1)
    )
    y = sim.initial_state()
    inp = sim.inputs(0.0, sim.volts(0.0))
    system = sim.system
    hist = -5000.0 * system.storage(y, inp)
    data = system.factorize(y, inp, 5000.0, hist).coupled_data
    assert data is not None
    n_theta, n_z = system.grid.n_theta, system.grid.n_z
    n = n_theta * n_z
    # CSR data read as CSC is B^T: splu of it with trans="T" solves B x = b.
    ref_lu = splu(
        sp.csc_matrix((data, system.c_indices, system.c_indptr), shape=(n, n)),
        permc_spec="MMD_AT_PLUS_A",
        options={"SymmetricMode": True},
    )
    lu = BlockCyclicLU(data, n_theta, n_z)
    assert lu.rcond > 1e-6
    assert lu.growth < 10.0
    rhs = np.random.default_rng(2).normal(size=(n, 2))
    assert _rel(lu.solve(rhs), ref_lu.solve(rhs, trans="T")) < 1e-10
    assert _rel(lu.solve(rhs[:, 0]), ref_lu.solve(rhs[:, 0], trans="T")) < 1e-10


def test_singular_matrix_raises() -> None:
    n_theta, n_z = 6, 3
    data, _ = _random_coupled(n_theta, n_z, seed=5)
    d4 = data.reshape(n_theta, n_z, 3, n_z)
    d4[1, 1, :, :] = 0.0  # an empty row in a chain: B is singular
    with pytest.raises(FloatingPointError, match="singular"):
        BlockCyclicLU(data, n_theta, n_z)
    fac = kern.block_cyclic_alloc(n_theta, n_z)
    assert kern.block_cyclic_factor(data, n_theta, n_z, fac)[:2] == (kern.BC_ZERO_PIVOT, 1)
    assert twins.block_cyclic_factor_py(data, n_theta, n_z, fac)[:2] == (kern.BC_ZERO_PIVOT, 1)
    d4[1, 1, :, :] = 1.0
    d4[5, 0, :, :] = 0.0  # an empty row in a separator: S is singular
    for factor in (kern.block_cyclic_factor, twins.block_cyclic_factor_py):
        status, block = factor(data, n_theta, n_z, fac)[:2]
        assert status == kern.BC_ZERO_PIVOT and block in (2, 5)


def test_ill_conditioned_and_non_finite_raise() -> None:
    n_theta, n_z = 5, 2
    data, _ = _random_coupled(n_theta, n_z, seed=7)
    d4 = data.reshape(n_theta, n_z, 3, n_z)
    d4[0, 1, 0, :] = d4[0, 0, 0, :] * (1.0 + 1e-15)  # nearly equal rows in the pivot block
    with pytest.raises(FloatingPointError, match="ill conditioned"):
        BlockCyclicLU(data, n_theta, n_z)
    data, _ = _random_coupled(n_theta, n_z, seed=7)
    data[3] = np.nan
    with pytest.raises(FloatingPointError, match="inf or NaN"):
        BlockCyclicLU(data, n_theta, n_z)
    with pytest.raises(ValueError, match="entries"):
        BlockCyclicLU(data[:-1], n_theta, n_z)
