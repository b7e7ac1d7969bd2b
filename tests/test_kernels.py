"""Compiled Reynolds kernels against their NumPy twins and finite differences."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.grid import FilmGrid
from foilbearing.testing import twins

N_THETA, N_Z = 10, 4
D_THETA = 2.0 * np.pi / N_THETA
D_Z = 0.3
LAMBDAS = [0.0, 0.1, 1.0, 3.0, 10.0, -2.0]
#: The axial orders of the discretisation (FilmGrid.axial_order); every kernel test runs both.
ORDERS = [2, 4]


def _axial(order: int) -> tuple:
    return tuple(FilmGrid(N_THETA, N_Z, N_Z * D_Z, axial_order=order).axial)


def _fields(seed: int, low_h: float = 0.3) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    P = rng.uniform(0.5, 2.0, (N_THETA, N_Z))
    H = rng.uniform(low_h, 1.5, (N_THETA, N_Z))
    return P, H


def _dense(data: np.ndarray, order: int = 2) -> np.ndarray:
    indptr, indices, _ = kern.stencil_pattern(N_THETA, N_Z, order)
    n = N_THETA * N_Z
    return sp.csr_matrix((data, indices, indptr), shape=(n, n)).toarray()


def _residual(P: np.ndarray, H: np.ndarray, lam: float, order: int = 2) -> np.ndarray:
    out = np.empty_like(P)
    kern.residual(P, H, lam, D_THETA, D_Z, _axial(order), out)
    return out.ravel()


def _fd_jacobian(
    P: np.ndarray, H: np.ndarray, lam: float, wrt_h: bool, order: int = 2
) -> np.ndarray:
    """Central finite differences of the residual, column by column."""
    n = P.size
    jac = np.empty((n, n))
    for k in range(n):
        x = H if wrt_h else P
        step = 1e-6 * max(1.0, abs(x.flat[k]))
        xp, xm = x.copy(), x.copy()
        xp.flat[k] += step
        xm.flat[k] -= step
        if wrt_h:
            jac[:, k] = (_residual(P, xp, lam, order) - _residual(P, xm, lam, order)) / (2 * step)
        else:
            jac[:, k] = (_residual(xp, H, lam, order) - _residual(xm, H, lam, order)) / (2 * step)
    return jac


def test_bernoulli_matches_definition_and_identities() -> None:
    x = np.array([-800.0, -50.0, -3.0, -0.0101, -0.0099, -1e-5, 0.0, 1e-5, 0.0099, 0.0101, 3.0])
    b = np.array([kern.bernoulli(v) for v in x])
    db = np.array([kern.bernoulli_deriv(v) for v in x])
    np.testing.assert_allclose(b, twins.bernoulli_py(x), rtol=1e-14, atol=0)
    np.testing.assert_allclose(db, twins.bernoulli_deriv_py(x), rtol=1e-14, atol=1e-300)
    nz = x != 0
    np.testing.assert_allclose(b[nz], x[nz] / np.expm1(x[nz]), rtol=1e-13)
    assert kern.bernoulli(0.0) == 1.0
    # B(−x) = B(x) + x, and no overflow for large |x|
    for v in (0.003, 0.7, 40.0, 900.0):
        assert kern.bernoulli(-v) == pytest.approx(kern.bernoulli(v) + v, rel=1e-14)
    assert kern.bernoulli(900.0) == 0.0
    # derivative against a central difference, on both sides of the series switch
    for v in (-4.0, -0.0101, -0.0099, 0.0099, 0.0101, 0.5, 4.0):
        h = 1e-6
        fd = (kern.bernoulli(v + h) - kern.bernoulli(v - h)) / (2 * h)
        assert kern.bernoulli_deriv(v) == pytest.approx(fd, rel=1e-8, abs=1e-10)


def test_stencil_pattern_of_order_4_has_the_5_point_axial_reach() -> None:
    """At axial order 4 row (i, j) reaches (i, j ± 2); the slots match the order-2 ones."""
    indptr, indices, slots = kern.stencil_pattern(N_THETA, N_Z, 4)
    for i in range(N_THETA):
        for j in range(N_Z):
            row = i * N_Z + j
            for d, dj in enumerate(range(-2, 3)):
                slot = slots[i, j, 1 + d]
                if 0 <= j + dj < N_Z:
                    assert indices[slot] == row + dj
                else:
                    assert slot == -1
            assert indices[slots[i, j, 0]] == ((i - 1) % N_THETA) * N_Z + j
            assert indices[slots[i, j, 6]] == ((i + 1) % N_THETA) * N_Z + j
            assert np.all(np.diff(indices[indptr[row] : indptr[row + 1]]) > 0)


def test_stencil_pattern_slots_point_at_neighbour_columns() -> None:
    indptr, indices, slots = kern.stencil_pattern(N_THETA, N_Z)
    assert np.all(np.diff(indices[indptr[0] : indptr[1]]) > 0)
    for i in range(N_THETA):
        for j in range(N_Z):
            row = i * N_Z + j
            expect = [
                ((i - 1) % N_THETA) * N_Z + j,
                row - 1 if j > 0 else -1,
                row,
                row + 1 if j < N_Z - 1 else -1,
                ((i + 1) % N_THETA) * N_Z + j,
            ]
            for d, col in enumerate(expect):
                slot = slots[i, j, d]
                if col < 0:
                    assert slot == -1
                else:
                    assert indptr[row] <= slot < indptr[row + 1]
                    assert indices[slot] == col
            row_cols = indices[indptr[row] : indptr[row + 1]]
            assert np.all(np.diff(row_cols) > 0), "columns sorted within each row"


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("lam", LAMBDAS)
def test_residual_kernel_equals_twin(lam: float, order: int) -> None:
    P, H = _fields(1)
    a, b = np.empty_like(P), np.empty_like(P)
    kern.residual(P, H, lam, D_THETA, D_Z, _axial(order), a)
    twins.residual_py(P, H, lam, D_THETA, D_Z, _axial(order), b)
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.abs(b).max())


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("lam", LAMBDAS)
@pytest.mark.parametrize("which", ["P", "H"])
def test_jacobian_kernels_equal_twins(lam: float, which: str, order: int) -> None:
    P, H = _fields(2)
    nnz = kern.stencil_pattern(N_THETA, N_Z, order)[1].size
    a, b = np.empty(nnz), np.empty(nnz)
    kernel, twin = (
        (kern.jacobian_P, twins.jacobian_P_py)
        if which == "P"
        else (kern.jacobian_H, twins.jacobian_H_py)
    )
    kernel(P, H, lam, D_THETA, D_Z, _axial(order), a)
    twin(P, H, lam, D_THETA, D_Z, _axial(order), b)
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.abs(b).max())


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("lam", LAMBDAS)
@pytest.mark.parametrize("which", ["P", "H"])
def test_jacobians_equal_finite_differences(lam: float, which: str, order: int) -> None:
    # thin films make the grid Péclet number large (up to ~300 for Λ = 10), so the
    # large-|x| branches of B and B' are exercised too
    P, H = _fields(3, low_h=0.15)
    nnz = kern.stencil_pattern(N_THETA, N_Z, order)[1].size
    data = np.empty(nnz)
    kernel = kern.jacobian_P if which == "P" else kern.jacobian_H
    kernel(P, H, lam, D_THETA, D_Z, _axial(order), data)
    exact = _dense(data, order)
    fd = _fd_jacobian(P, H, lam, wrt_h=(which == "H"), order=order)
    err = np.abs(exact - fd).max() / np.abs(exact).max()
    assert err < 1e-6, f"d R/d{which} differs from finite differences by {err:.2e} at Λ={lam}"


@pytest.mark.parametrize("order", ORDERS)
def test_coupled_jacobian_kernel_equals_sparse_product(order: int) -> None:
    P, H = _fields(4)
    nnz = kern.stencil_pattern(N_THETA, N_Z, order)[1].size
    jp, jh = np.empty(nnz), np.empty(nnz)
    axial = _axial(order)
    kern.jacobian_P(P, H, 1.5, D_THETA, D_Z, axial, jp)
    kern.jacobian_H(P, H, 1.5, D_THETA, D_Z, axial, jh)
    s = np.random.default_rng(5).uniform(0.0, 0.05, N_THETA)
    s[[0, 3]] = 0.0  # inactive foil (p̄ <= 0) at some angles, including the wrap
    _, c_indices = kern.coupled_pattern(N_THETA, N_Z)
    a, b = np.empty(c_indices.size), np.empty(c_indices.size)
    kern.coupled_jacobian(jp, jh, s, N_Z, axial, a)
    twins.coupled_jacobian_py(jp, jh, s, N_Z, axial, b)
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.abs(b).max())


def _lift_off_rows_both(seed: int, fields: int, above: bool, coupled: bool, law: tuple) -> tuple:
    """Pressures near ambient (all above it if ``above``), their residual and Jacobians, and
    the lift-off rows of the compiled kernel and of its twin (``law``: (δ, d_ref) or ())."""
    rng = np.random.default_rng(seed)
    P, H = _fields(fields)
    noise = rng.standard_normal(P.shape)
    P = 1.0 + 0.05 * (np.abs(noise) if above else noise)
    indptr, _, slots = kern.stencil_pattern(N_THETA, N_Z)
    diag = slots[:, :, 2].ravel()
    jp, jh = np.empty(indptr[-1]), np.empty(indptr[-1])
    kern.jacobian_P(P, H, 1.5, D_THETA, D_Z, _axial(2), jp)
    kern.jacobian_H(P, H, 1.5, D_THETA, D_Z, _axial(2), jh)
    res = _residual(P, H, 1.5).reshape(P.shape)
    jc = rng.standard_normal(kern.coupled_pattern(N_THETA, N_Z)[1].size)
    outs = []
    for kernel in (kern.lift_off_rows, twins.lift_off_rows_py):
        args = [P, res.copy(), jp.copy(), jh.copy(), jc.copy(), diag, indptr, coupled]
        held = np.zeros(P.size, dtype=bool)
        count = kernel(*args, held, *law)
        outs.append((count, held, *args[1:5]))
    return P, H, jp, jc, diag, indptr, outs


@pytest.mark.parametrize("coupled", [True, False])
def test_lift_off_rows_kernel_equals_twin(coupled: bool) -> None:
    # Cells with P near and below ambient and residuals of both signs: some held, some
    # free; the held rows become −d e_k with residual −d (P − 1), their film rows zero.
    P, _H, jp, _jc, diag, indptr, outs = _lift_off_rows_both(11, 6, False, coupled, ())
    (n_a, held_a, *arrays_a), (n_b, held_b, *arrays_b) = outs
    assert n_a == n_b == held_a.sum() and 0 < n_a < P.size
    np.testing.assert_array_equal(held_a, held_b)
    for a, b in zip(arrays_a, arrays_b, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-14)
    d = np.abs(jp[diag])
    np.testing.assert_allclose(arrays_a[0].ravel()[held_a], -d[held_a] * (P.ravel()[held_a] - 1.0))
    matrix = (
        sp.csr_matrix((arrays_a[3], *kern.coupled_pattern(N_THETA, N_Z)[::-1]), shape=(P.size,) * 2)
        if coupled
        else sp.csr_matrix(
            (arrays_a[1], kern.stencil_pattern(N_THETA, N_Z)[1], indptr), shape=(P.size,) * 2
        )
    ).toarray()
    np.testing.assert_array_equal(matrix[held_a], -np.diag(d)[held_a])


@pytest.mark.parametrize("coupled", [True, False])
def test_smoothed_lift_off_rows_equal_twin_and_are_the_derivative(coupled: bool) -> None:
    # The smoothed law G = −(d_ref/2)(x + y − √((x − y)² + 4δ²)), x = P − 1, y = −R/d_ref:
    # compiled rows against the twin, and (on the stencil pattern) the rows against central
    # differences of G(P) itself, so the Newton matrix is the derivative of what it solves.
    delta, d_ref = 0.01, 2.0 * D_Z / D_THETA
    P, H, _jp, jc, diag, indptr, outs = _lift_off_rows_both(12, 7, True, coupled, (delta, d_ref))
    indices = kern.stencil_pattern(N_THETA, N_Z)[1]
    (n_a, held_a, *arrays_a), (n_b, held_b, *arrays_b) = outs
    assert n_a == n_b and 0 < n_a < P.size  # both branches are near
    np.testing.assert_array_equal(held_a, held_b)
    for a, b in zip(arrays_a, arrays_b, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-13 * max(1.0, np.abs(b).max()))
    if coupled:
        return

    def smoothed(p: np.ndarray) -> np.ndarray:
        r = _residual(p.reshape(P.shape), H, 1.5).reshape(P.shape)
        held = np.zeros(P.size, dtype=bool)
        scratch = np.empty(indptr[-1])
        kern.lift_off_rows(p.reshape(P.shape), r, scratch, scratch.copy(), jc.copy(), diag,
                           indptr, False, held, delta, d_ref)  # fmt: skip
        return r.ravel()

    fd = np.empty((P.size, P.size))
    for k in range(P.size):
        e = np.zeros(P.size)
        e[k] = 1e-6
        fd[:, k] = (smoothed(P.ravel() + e) - smoothed(P.ravel() - e)) / 2e-6
    matrix = sp.csr_matrix((arrays_a[1], indices, indptr), shape=(P.size,) * 2).toarray()
    np.testing.assert_allclose(matrix, fd, rtol=0, atol=1e-6 * np.abs(fd).max())
