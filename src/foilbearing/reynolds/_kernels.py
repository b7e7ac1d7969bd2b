"""Compiled kernels of the finite-volume Reynolds equation (the only numba module).

Discretisation of the steady, dimensionless, isothermal Reynolds equation
(Eq. (4) of the paper, MODEL.md §4, written in conservative flux form)::

    ∂q_θ/∂θ + ∂q_Z/∂Z = 0,
    q_θ = P H³ ∂P/∂θ − Λ P H,      q_Z = P H³ ∂P/∂Z,

on the cell-centred grid of :class:`foilbearing.reynolds.grid.Grid` (fields of
shape ``(n_theta, n_z)``, unknown ``k = i*n_z + j``).

Scaling of the residual
-----------------------
``R[i, j]`` is the left side integrated over cell ``(i, j)``, i.e. the net
outflow of the flux ``q`` through its four faces::

    R[i, j] = ΔZ (q_θ[i+1/2, j] − q_θ[i−1/2, j]) + Δθ (q_Z[i, j+1/2] − q_Z[i, j−1/2])

so ``R/(Δθ ΔZ)`` is the cell average of the left side of Eq. (4).

Face fluxes
-----------
θ-face ``i+1/2`` between cells ``a = (i, j)`` and ``b = (i+1, j)`` (periodic):
``D = P_f H_f³``, ``V = Λ H_f``, with arithmetic face means ``P_f``, ``H_f``;
grid Péclet number ``Pe = V Δθ / D = Λ Δθ / (P_f H_f²)``; exponentially fitted
(Scharfetter–Gummel / Il'in–Allen–Southwell) flux::

    q_θ = (D/Δθ) [B(Pe) P_b − B(−Pe) P_a]  =  (D/Δθ) B(Pe) (P_b − P_a) − V P_a,

``B(x) = x/(eˣ − 1)`` (Bernoulli function; ``B(−x) = B(x) + x``). It is exact
for constant coefficients, reduces to central differences for ``Pe → 0`` and
to upwinding for ``|Pe| → ∞``, so no oscillation appears at the grid Péclet
numbers reached when the local bearing number Λ/H² is 50 or more.

Z-faces: pure diffusion, ``q_Z = P_f H_f³ (P_b − P_a)/ΔZ``; zero flux on the
mid-plane face ``j = −1/2``; on the end face ``P = 1`` at ``ΔZ/2`` from the
last centre, ``q_Z = P_f H³ (1 − P)/(ΔZ/2)`` with ``P_f = (P + 1)/2`` and the
last cell's ``H``.

Jacobians
---------
``dR/dP`` and ``dR/dH`` share one fixed CSR pattern (5-point stencil, periodic
in θ, column indices sorted within rows), built once per grid by
:func:`stencil_pattern`; the kernels fill only the ``data`` array. The coupled
foil Jacobian has dense ``n_z × n_z`` blocks on three θ block-diagonals
(:func:`coupled_pattern`, :func:`coupled_jacobian`); that matrix is
factorised by block cyclic elimination (:func:`block_cyclic_factor`,
:func:`block_cyclic_solve`; wrapped by :mod:`foilbearing.reynolds.blocksolve`).

Every kernel has a plain-NumPy twin (suffix ``_py``) with the same signature;
``tests/test_kernels.py`` checks each kernel against its twin. The kernels of
the transient Newton iteration (:func:`transient_residual`,
:func:`transient_storage`, :func:`transient_solve`, :func:`transient_jacobian`,
:func:`transient_border`, :func:`transient_newton_step`) have their twins in
:mod:`foilbearing.reynolds.transient` (the methods they replace, named in
each docstring), checked by ``tests/test_transient_kernels.py``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

__all__ = [
    "BC_NOT_FINITE",
    "BC_OK",
    "BC_ZERO_PIVOT",
    "bdf2_setup",
    "bdf2_setup_py",
    "bernoulli",
    "bernoulli_deriv",
    "bernoulli_deriv_py",
    "bernoulli_py",
    "block_cyclic_alloc",
    "block_cyclic_factor",
    "block_cyclic_factor_py",
    "block_cyclic_solve",
    "block_cyclic_solve_py",
    "coupled_jacobian",
    "coupled_jacobian_py",
    "coupled_pattern",
    "jacobian_H",
    "jacobian_H_py",
    "jacobian_P",
    "jacobian_P_py",
    "newton_update",
    "newton_update_py",
    "residual",
    "residual_py",
    "stencil_pattern",
    "transient_border",
    "transient_jacobian",
    "transient_newton_solve",
    "transient_newton_step",
    "transient_residual",
    "transient_solve",
    "transient_storage",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

# Below this |x| the Bernoulli function and its derivative use their Taylor
# series: x/expm1(x) loses digits to cancellation in B'(x) = B(1−B)/x − B.
_SERIES_X = 1e-2

# Stencil directions, in the order of the slot maps: W = (i−1, j),
# S = (i, j−1), C = (i, j), N = (i, j+1), E = (i+1, j).
W, S, C, N, E = 0, 1, 2, 3, 4


# ---------------------------------------------------------------------------
# Bernoulli function
# ---------------------------------------------------------------------------


@njit(cache=True)
def _bern_pos(x: float) -> tuple[float, float]:
    """B(x) and B'(x) for x >= 0."""
    if x < _SERIES_X:
        x2 = x * x
        b = 1.0 - 0.5 * x + x2 / 12.0 - x2 * x2 / 720.0
        db = -0.5 + x / 6.0 - x2 * x / 180.0 + x2 * x2 * x / 5040.0
        return b, db
    b = x / np.expm1(x)  # → 0 (not NaN) when expm1 overflows to inf
    return b, b * (1.0 - b) / x - b


@njit(cache=True)
def bernoulli(x: float) -> float:
    """Bernoulli function ``B(x) = x/(eˣ − 1)``, robust for all real x.

    Twin: :func:`bernoulli_py`. Negative arguments use ``B(x) = B(−x) − x``,
    which is exact and free of overflow.
    """
    if x >= 0.0:
        return _bern_pos(x)[0]
    return _bern_pos(-x)[0] - x


@njit(cache=True)
def bernoulli_deriv(x: float) -> float:
    """Derivative ``B'(x)``; twin :func:`bernoulli_deriv_py`.

    Negative arguments use ``B'(x) = −B'(−x) − 1``.
    """
    if x >= 0.0:
        return _bern_pos(x)[1]
    return -_bern_pos(-x)[1] - 1.0


def bernoulli_py(x: FloatArray | float) -> FloatArray:
    """NumPy twin of :func:`bernoulli` (vectorised)."""
    x = np.asarray(x, dtype=np.float64)
    a = np.abs(x)
    a2 = a * a
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        big = a / np.expm1(np.where(a < _SERIES_X, 1.0, a))
    series = 1.0 - 0.5 * a + a2 / 12.0 - a2 * a2 / 720.0
    b_pos = np.where(a < _SERIES_X, series, big)
    return np.where(x >= 0.0, b_pos, b_pos - x)


def bernoulli_deriv_py(x: FloatArray | float) -> FloatArray:
    """NumPy twin of :func:`bernoulli_deriv` (vectorised)."""
    x = np.asarray(x, dtype=np.float64)
    a = np.abs(x)
    a2 = a * a
    safe = np.where(a < _SERIES_X, 1.0, a)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        b = safe / np.expm1(safe)
    big = b * (1.0 - b) / safe - b
    series = -0.5 + a / 6.0 - a2 * a / 180.0 + a2 * a2 * a / 5040.0
    d_pos = np.where(a < _SERIES_X, series, big)
    return np.where(x >= 0.0, d_pos, -d_pos - 1.0)


# ---------------------------------------------------------------------------
# Sparsity patterns
# ---------------------------------------------------------------------------


def stencil_pattern(n_theta: int, n_z: int) -> tuple[IntArray, IntArray, IntArray]:
    """CSR pattern of the 5-point stencil, periodic in θ, columns sorted.

    Parameters
    ----------
    n_theta, n_z : int
        Grid size (``n_theta >= 3`` so that W, C, E are distinct; ``n_z >= 2``).

    Returns
    -------
    indptr : ndarray, shape (n_theta*n_z + 1,)
    indices : ndarray, shape (nnz,), ``nnz = n_theta (5 n_z − 2)``
    slots : ndarray, shape (n_theta, n_z, 5)
        Position in ``data`` of the entry of row ``(i, j)`` in direction
        W, S, C, N, E (see module constants), ``-1`` where absent (S on the
        mid-plane row ``j = 0``, N on the end row ``j = n_z−1``). The kernels
        compute the same positions in place (:func:`_row_slots`).
    """
    i = np.repeat(np.arange(n_theta), n_z)
    j = np.tile(np.arange(n_z), n_theta)
    row = i * n_z + j
    cols = np.stack(
        [
            ((i - 1) % n_theta) * n_z + j,
            np.where(j > 0, row - 1, -1),
            row,
            np.where(j < n_z - 1, row + 1, -1),
            ((i + 1) % n_theta) * n_z + j,
        ],
        axis=1,
    )
    present = cols >= 0
    big = n_theta * n_z + 1
    key = np.where(present, cols, big)
    order = np.argsort(key, axis=1, kind="stable")
    rank = np.empty_like(order)
    np.put_along_axis(rank, order, np.arange(5)[None, :].repeat(len(row), 0), axis=1)
    counts = present.sum(axis=1)
    indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    sorted_key = np.take_along_axis(key, order, axis=1)
    indices = sorted_key[sorted_key < big].astype(np.int64)
    slots = np.where(present, indptr[:-1, None] + rank, -1).astype(np.int64)
    return indptr, indices, slots.reshape(n_theta, n_z, 5)


def coupled_pattern(n_theta: int, n_z: int) -> tuple[IntArray, IntArray]:
    """CSR pattern of the foil-coupled Jacobian: dense blocks on 3 θ-diagonals.

    Row ``(i, j)`` holds every column of the θ-blocks ``i−1, i, i+1``
    (periodic), blocks in increasing column order, ``3 n_z`` entries per row.

    Returns
    -------
    indptr : ndarray, shape (n_theta*n_z + 1,)
    indices : ndarray, shape (3 n_z · n_theta n_z,)
    """
    n = n_theta * n_z
    i = np.repeat(np.arange(n_theta), n_z)
    blocks = np.sort(np.stack([(i - 1) % n_theta, i, (i + 1) % n_theta], axis=1), axis=1)
    indices = (blocks[:, :, None] * n_z + np.arange(n_z)[None, None, :]).reshape(-1)
    indptr = np.arange(n + 1, dtype=np.int64) * (3 * n_z)
    return indptr, indices.astype(np.int64)


@njit(cache=True)
def _row_slots(i: int, j: int, n_theta: int, n_z: int) -> tuple[int, int, int, int, int]:
    """Positions (W, S, C, N, E) of row (i, j) in the data of :func:`stencil_pattern`.

    Rows of one θ-block hold ``5 n_z − 2`` entries; row ``j`` starts at
    ``0`` (``j = 0``) or ``5 j − 1``. Sorted columns put W after the block for
    ``i = 0`` and E before it for ``i = n_theta − 1`` (periodic wrap).
    """
    start = i * (5 * n_z - 2) + (0 if j == 0 else 5 * j - 1)
    has_s = j > 0
    has_n = j < n_z - 1
    k = start
    w = -1
    e = -1
    if i == n_theta - 1:
        e = k
        k += 1
        w = k
        k += 1
    elif i > 0:
        w = k
        k += 1
    s = -1
    if has_s:
        s = k
        k += 1
    c = k
    k += 1
    nn = -1
    if has_n:
        nn = k
        k += 1
    if i == 0:
        e = k
        k += 1
        w = k
    elif i < n_theta - 1:
        e = k
    return w, s, c, nn, e


# ---------------------------------------------------------------------------
# Face fluxes and their derivatives
# ---------------------------------------------------------------------------


@njit(cache=True)
def _bern_both(x: float) -> tuple[float, float]:
    """``(bernoulli(x), bernoulli_deriv(x))`` from one exponential (same values)."""
    if x >= 0.0:
        return _bern_pos(x)
    b, db = _bern_pos(-x)
    return b - x, -db - 1.0


@njit(cache=True)
def _theta_flux(pa: float, pb: float, ha: float, hb: float, lam: float, dth: float) -> float:
    """The flux of :func:`_theta_face` alone (same value, no derivatives)."""
    pf = 0.5 * (pa + pb)
    hf = 0.5 * (ha + hb)
    hf2 = hf * hf
    hf3 = hf2 * hf
    pe = lam * dth / (pf * hf2)
    b = bernoulli(pe)
    dp = pb - pa
    g = pf * hf3 * b / dth
    return g * dp - lam * hf * pa


@njit(cache=True)
def _theta_face(
    pa: float, pb: float, ha: float, hb: float, lam: float, dth: float
) -> tuple[float, float, float, float]:
    """Fitted θ-flux and (dq/dP_a, dq/dP_b, dq/dH_a = dq/dH_b)."""
    pf = 0.5 * (pa + pb)
    hf = 0.5 * (ha + hb)
    hf2 = hf * hf
    hf3 = hf2 * hf
    pe = lam * dth / (pf * hf2)
    b, db = _bern_both(pe)
    dp = pb - pa
    g = pf * hf3 * b / dth
    q = g * dp - lam * hf * pa
    # g = (P_f H_f³/Δθ) B(Pe) with Pe ∝ 1/(P_f H_f²): chain rule through Pe.
    g_pf = hf3 * (b - pe * db) / dth
    g_hf = pf * hf2 * (3.0 * b - 2.0 * pe * db) / dth
    dqa = 0.5 * g_pf * dp - g - lam * hf
    dqb = 0.5 * g_pf * dp + g
    dqh = 0.5 * (g_hf * dp - lam * pa)
    return q, dqa, dqb, dqh


@njit(cache=True)
def _z_face(
    pa: float, pb: float, ha: float, hb: float, dz: float
) -> tuple[float, float, float, float]:
    """Axial diffusive flux and (dq/dP_a, dq/dP_b, dq/dH_a = dq/dH_b)."""
    pf = 0.5 * (pa + pb)
    hf = 0.5 * (ha + hb)
    hf2 = hf * hf
    d = pf * hf2 * hf
    dp = pb - pa
    q = d * dp / dz
    dqa = (0.5 * hf2 * hf * dp - d) / dz
    dqb = (0.5 * hf2 * hf * dp + d) / dz
    dqh = 1.5 * pf * hf2 * dp / dz
    return q, dqa, dqb, dqh


@njit(cache=True)
def _end_face(pa: float, ha: float, dz: float) -> tuple[float, float, float]:
    """Flux through the end face (P = 1 at ΔZ/2) and (dq/dP_a, dq/dH_a)."""
    h3 = ha * ha * ha
    # P_f (1 − P_a) = (1 − P_a²)/2
    q = h3 * (1.0 - pa * pa) / dz
    dqa = -2.0 * h3 * pa / dz
    dqh = 3.0 * ha * ha * (1.0 - pa * pa) / dz
    return q, dqa, dqh


# ---------------------------------------------------------------------------
# Residual and Jacobians (compiled)
# ---------------------------------------------------------------------------


@njit(cache=True)
def residual(
    P: FloatArray, H: FloatArray, lam: float, d_theta: float, d_z: float, out: FloatArray
) -> None:
    """Finite-volume residual of Eq. (4), cell-integrated; twin :func:`residual_py`.

    Parameters
    ----------
    P, H : ndarray, shape (n_theta, n_z)
        Dimensionless pressure ``p/p_a`` (> 0) and film ``h/C`` (> 0).
    lam : float
        Bearing number ``Λ = 6 μ ω R²/(p_a C²)`` (any sign).
    d_theta, d_z : float
        Cell sizes Δθ, ΔZ.
    out : ndarray, shape (n_theta, n_z)
        Filled with ``R[i, j]`` (net outflow of q through the cell faces).
    """
    n_theta, n_z = P.shape
    out[:, :] = 0.0
    for i in range(n_theta):
        ie = i + 1 if i < n_theta - 1 else 0
        for j in range(n_z):
            q = _theta_flux(P[i, j], P[ie, j], H[i, j], H[ie, j], lam, d_theta)
            out[i, j] += d_z * q
            out[ie, j] -= d_z * q
        for j in range(n_z - 1):
            q = _z_face(P[i, j], P[i, j + 1], H[i, j], H[i, j + 1], d_z)[0]
            out[i, j] += d_theta * q
            out[i, j + 1] -= d_theta * q
        out[i, n_z - 1] += d_theta * _end_face(P[i, n_z - 1], H[i, n_z - 1], d_z)[0]


@njit(cache=True)
def _jacobian(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    data: FloatArray,
    wrt_h: bool,
) -> None:
    n_theta, n_z = P.shape
    data[:] = 0.0
    for i in range(n_theta):
        ie = i + 1 if i < n_theta - 1 else 0
        for j in range(n_z):
            _, dqa, dqb, dqh = _theta_face(P[i, j], P[ie, j], H[i, j], H[ie, j], lam, d_theta)
            if wrt_h:
                dqa = dqh
                dqb = dqh
            _, _, ca, _, ea = _row_slots(i, j, n_theta, n_z)
            wb, _, cb, _, _ = _row_slots(ie, j, n_theta, n_z)
            data[ca] += d_z * dqa
            data[ea] += d_z * dqb
            data[wb] -= d_z * dqa
            data[cb] -= d_z * dqb
        for j in range(n_z - 1):
            _, dqa, dqb, dqh = _z_face(P[i, j], P[i, j + 1], H[i, j], H[i, j + 1], d_z)
            if wrt_h:
                dqa = dqh
                dqb = dqh
            _, _, ca, na, _ = _row_slots(i, j, n_theta, n_z)
            _, sb, cb, _, _ = _row_slots(i, j + 1, n_theta, n_z)
            data[ca] += d_theta * dqa
            data[na] += d_theta * dqb
            data[sb] -= d_theta * dqa
            data[cb] -= d_theta * dqb
        _, dqa, dqh = _end_face(P[i, n_z - 1], H[i, n_z - 1], d_z)
        ca = _row_slots(i, n_z - 1, n_theta, n_z)[2]
        data[ca] += d_theta * (dqh if wrt_h else dqa)


@njit(cache=True)
def _jacobian_both(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    data_p: FloatArray,
    data_h: FloatArray,
) -> None:
    """:func:`jacobian_P` and :func:`jacobian_H` in one pass over the faces (same values)."""
    n_theta, n_z = P.shape
    data_p[:] = 0.0
    data_h[:] = 0.0
    for i in range(n_theta):
        ie = i + 1 if i < n_theta - 1 else 0
        for j in range(n_z):
            _, dqa, dqb, dqh = _theta_face(P[i, j], P[ie, j], H[i, j], H[ie, j], lam, d_theta)
            _, _, ca, _, ea = _row_slots(i, j, n_theta, n_z)
            wb, _, cb, _, _ = _row_slots(ie, j, n_theta, n_z)
            data_p[ca] += d_z * dqa
            data_p[ea] += d_z * dqb
            data_p[wb] -= d_z * dqa
            data_p[cb] -= d_z * dqb
            data_h[ca] += d_z * dqh
            data_h[ea] += d_z * dqh
            data_h[wb] -= d_z * dqh
            data_h[cb] -= d_z * dqh
        for j in range(n_z - 1):
            _, dqa, dqb, dqh = _z_face(P[i, j], P[i, j + 1], H[i, j], H[i, j + 1], d_z)
            _, _, ca, na, _ = _row_slots(i, j, n_theta, n_z)
            _, sb, cb, _, _ = _row_slots(i, j + 1, n_theta, n_z)
            data_p[ca] += d_theta * dqa
            data_p[na] += d_theta * dqb
            data_p[sb] -= d_theta * dqa
            data_p[cb] -= d_theta * dqb
            data_h[ca] += d_theta * dqh
            data_h[na] += d_theta * dqh
            data_h[sb] -= d_theta * dqh
            data_h[cb] -= d_theta * dqh
        _, dqa, dqh = _end_face(P[i, n_z - 1], H[i, n_z - 1], d_z)
        ca = _row_slots(i, n_z - 1, n_theta, n_z)[2]
        data_p[ca] += d_theta * dqa
        data_h[ca] += d_theta * dqh


@njit(cache=True)
def jacobian_P(
    P: FloatArray, H: FloatArray, lam: float, d_theta: float, d_z: float, data: FloatArray
) -> None:
    """Fill ``data`` of the CSR ``dR/dP`` (pattern :func:`stencil_pattern`).

    Exact derivatives, including those of ``B(Pe)`` through ``Pe(P_f, H_f)``.
    Twin: :func:`jacobian_P_py`. Arguments as :func:`residual`;
    ``data`` has shape ``(nnz,)`` and is overwritten.
    """
    _jacobian(P, H, lam, d_theta, d_z, data, False)


@njit(cache=True)
def jacobian_H(
    P: FloatArray, H: FloatArray, lam: float, d_theta: float, d_z: float, data: FloatArray
) -> None:
    """Fill ``data`` of the CSR ``dR/dH`` (pattern :func:`stencil_pattern`).

    Twin: :func:`jacobian_H_py`. Arguments as :func:`jacobian_P`.
    """
    _jacobian(P, H, lam, d_theta, d_z, data, True)


@njit(cache=True)
def coupled_jacobian(
    jp_data: FloatArray, jh_data: FloatArray, s: FloatArray, n_z: int, out: FloatArray
) -> None:
    """Assemble ``dR/dP + dR/dH · dH/dP`` on the pattern of :func:`coupled_pattern`.

    The foil couples ``H[i, :]`` to the axial mean of ``P[i, :]``:
    ``dH[i, j]/dP[i, k] = s[i]`` for every ``j, k``, with
    ``s[i] = c_i/n_z`` where ``p̄_i > 0`` and ``0`` elsewhere. Row ``(i, j)``
    of the product is therefore constant over ``k`` in each column block
    ``i' ∈ {i−1, i, i+1}``: ``s[i'] · Σ_{j'} dR[i, j]/dH[i', j']``.
    Twin: :func:`coupled_jacobian_py`.

    Parameters
    ----------
    jp_data, jh_data : ndarray, shape (nnz,)
        Data of ``dR/dP`` and ``dR/dH`` on :func:`stencil_pattern`.
    s : ndarray, shape (n_theta,)
    n_z : int
    out : ndarray, shape (3 n_z · n_theta n_z,)
    """
    n_theta = s.shape[0]
    width = 3 * n_z
    for i in range(n_theta):
        iw = i - 1 if i > 0 else n_theta - 1
        ie = i + 1 if i < n_theta - 1 else 0
        # rank of the blocks (W, C, E) in sorted column order
        if i == 0:
            rw, rc, re = 2, 0, 1
        elif i == n_theta - 1:
            rw, rc, re = 1, 2, 0
        else:
            rw, rc, re = 0, 1, 2
        for j in range(n_z):
            w, so, c, no, e = _row_slots(i, j, n_theta, n_z)
            base = (i * n_z + j) * width
            hc = jh_data[c]
            if so >= 0:
                hc += jh_data[so]
            if no >= 0:
                hc += jh_data[no]
            vw = s[iw] * jh_data[w]
            vc = s[i] * hc
            ve = s[ie] * jh_data[e]
            for k in range(n_z):
                out[base + rw * n_z + k] = vw
                out[base + rc * n_z + k] = vc
                out[base + re * n_z + k] = ve
            out[base + rw * n_z + j] += jp_data[w]
            out[base + re * n_z + j] += jp_data[e]
            out[base + rc * n_z + j] += jp_data[c]
            if so >= 0:
                out[base + rc * n_z + j - 1] += jp_data[so]
            if no >= 0:
                out[base + rc * n_z + j + 1] += jp_data[no]


# ---------------------------------------------------------------------------
# NumPy twins
# ---------------------------------------------------------------------------


def _faces_py(
    P: FloatArray, H: FloatArray, lam: float, d_theta: float, d_z: float
) -> tuple[tuple[FloatArray, ...], tuple[FloatArray, ...], tuple[FloatArray, ...]]:
    """Vectorised face fluxes and derivatives: θ-faces (n_theta, n_z),
    interior Z-faces (n_theta, n_z−1), end faces (n_theta,)."""
    pa, pb = P, np.roll(P, -1, axis=0)
    ha, hb = H, np.roll(H, -1, axis=0)
    pf = 0.5 * (pa + pb)
    hf = 0.5 * (ha + hb)
    pe = lam * d_theta / (pf * hf**2)
    b = bernoulli_py(pe)
    db = bernoulli_deriv_py(pe)
    dp = pb - pa
    g = pf * hf**3 * b / d_theta
    g_pf = hf**3 * (b - pe * db) / d_theta
    g_hf = pf * hf**2 * (3.0 * b - 2.0 * pe * db) / d_theta
    th = (
        g * dp - lam * hf * pa,
        0.5 * g_pf * dp - g - lam * hf,
        0.5 * g_pf * dp + g,
        0.5 * (g_hf * dp - lam * pa),
    )
    pa, pb = P[:, :-1], P[:, 1:]
    ha, hb = H[:, :-1], H[:, 1:]
    pf = 0.5 * (pa + pb)
    hf = 0.5 * (ha + hb)
    dp = pb - pa
    d = pf * hf**3
    zf = (
        d * dp / d_z,
        (0.5 * hf**3 * dp - d) / d_z,
        (0.5 * hf**3 * dp + d) / d_z,
        1.5 * pf * hf**2 * dp / d_z,
    )
    pl, hl = P[:, -1], H[:, -1]
    end = (
        hl**3 * (1.0 - pl**2) / d_z,
        -2.0 * hl**3 * pl / d_z,
        3.0 * hl**2 * (1.0 - pl**2) / d_z,
    )
    return th, zf, end


def residual_py(
    P: FloatArray, H: FloatArray, lam: float, d_theta: float, d_z: float, out: FloatArray
) -> None:
    """NumPy twin of :func:`residual`."""
    th, zf, end = _faces_py(P, H, lam, d_theta, d_z)
    qt = th[0]
    qz = np.concatenate([np.zeros((P.shape[0], 1)), zf[0], end[0][:, None]], axis=1)
    out[:, :] = d_z * (qt - np.roll(qt, 1, axis=0)) + d_theta * (qz[:, 1:] - qz[:, :-1])


def _jacobian_py(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    data: FloatArray,
    wrt_h: bool,
) -> None:
    n_theta, n_z = P.shape
    th, zf, end = _faces_py(P, H, lam, d_theta, d_z)
    if wrt_h:
        t_a, t_b = th[3], th[3]
        z_a, z_b = zf[3], zf[3]
        e_a = end[2]
    else:
        t_a, t_b = th[1], th[2]
        z_a, z_b = zf[1], zf[2]
        e_a = end[1]
    zeros = np.zeros((n_theta, 1))
    # derivative of R[i, j] w.r.t. each stencil neighbour
    vals = np.zeros((n_theta, n_z, 5))
    vals[:, :, E] = d_z * t_b
    vals[:, :, W] = -d_z * np.roll(t_a, 1, axis=0)
    vals[:, :, N] = d_theta * np.concatenate([z_b, zeros], axis=1)
    vals[:, :, S] = -d_theta * np.concatenate([zeros, z_a], axis=1)
    z_out = np.concatenate([z_a, e_a[:, None]], axis=1)
    z_in = np.concatenate([zeros, z_b], axis=1)
    vals[:, :, C] = d_z * (t_a - np.roll(t_b, 1, axis=0)) + d_theta * (z_out - z_in)
    _, _, slots = stencil_pattern(n_theta, n_z)
    mask = slots >= 0
    data[:] = 0.0
    data[slots[mask]] = vals[mask]


def jacobian_P_py(
    P: FloatArray, H: FloatArray, lam: float, d_theta: float, d_z: float, data: FloatArray
) -> None:
    """NumPy twin of :func:`jacobian_P`."""
    _jacobian_py(P, H, lam, d_theta, d_z, data, False)


def jacobian_H_py(
    P: FloatArray, H: FloatArray, lam: float, d_theta: float, d_z: float, data: FloatArray
) -> None:
    """NumPy twin of :func:`jacobian_H`."""
    _jacobian_py(P, H, lam, d_theta, d_z, data, True)


def coupled_jacobian_py(
    jp_data: FloatArray, jh_data: FloatArray, s: FloatArray, n_z: int, out: FloatArray
) -> None:
    """NumPy twin of :func:`coupled_jacobian` (via scipy.sparse products)."""
    import scipy.sparse as sp

    n_theta = s.shape[0]
    n = n_theta * n_z
    indptr, indices, _ = stencil_pattern(n_theta, n_z)
    jp = sp.csr_matrix((jp_data, indices, indptr), shape=(n, n))
    jh = sp.csr_matrix((jh_data, indices, indptr), shape=(n, n))
    dhdp = sp.kron(sp.diags(s), np.ones((n_z, n_z)), format="csr")
    full = (jp + jh @ dhdp).toarray()
    c_indptr, c_indices = coupled_pattern(n_theta, n_z)
    rows = np.repeat(np.arange(n), np.diff(c_indptr))
    out[:] = full[rows, c_indices]


# ---------------------------------------------------------------------------
# Block cyclic tridiagonal LU (the matrix on the coupled pattern)
# ---------------------------------------------------------------------------
#
# B (n = n_theta·n_z) on :func:`coupled_pattern` is block tridiagonal and
# periodic in θ with dense n_z × n_z blocks: block row i couples to the rows
# i−1 and i+1 (indices mod N, N = n_theta). Two separator rows, p = (N−1)//2
# and N−1, cut the ring into two chains, A = 0 … p−1 and B = p+1 … N−2, that
# are eliminated independently; the separators are then solved from their
# 2 n_z × 2 n_z Schur complement S. (The chains could go to two threads: with
# numba's OpenMP layer that halves the factorisation in isolation, but it
# gained nothing measurable inside the orbit on a 2-core machine, and GNU
# OpenMP is not fork-safe for the study's process pool, so it is not done.)
#
# In a chain with first row f, last row e, left separator l (coupled to f)
# and right separator r (coupled to e; r = e + 1), block Gaussian elimination
# in θ order (no pivoting between blocks; partial pivoting inside each pivot
# block) carries the fill to l in a column G_i and a row R_i. For i = f … e,
# with D_i the current pivot block and U_i = B[i, i+1] (U_e couples to r):
#
#     [V_i | W_i] = D_i⁻¹ [U_i | G_i]
#     [D_{i+1} | G_{i+1}] −= L_{i+1} [V_i | W_i]          (i < e, L_{i+1} = B[i+1, i])
#     R_{i+1} = −R_i V_i,   S_ll −= R_i W_i                 (i < e)
#     S_lr −= R_e V_e,  S_ll −= R_e W_e,  S_rl −= L_r W_e,  S_rr −= L_r V_e
#
# from D_i = B[i, i], G_f = B[f, l], R_f = B[l, f], L_r = B[r, e]; cost
# O(N n_z³). Chain A has l = N−1, r = p; chain B has l = p, r = N−1. S starts
# from B[p, p] and B[N−1, N−1] (and B[p, N−1], B[N−1, p] when N = 3 and the
# separators touch). The pivot blocks are inverted explicitly (Gauss-Jordan on
# [D_i | U_i | G_i | I], which gives [V_i | W_i] in the same sweep): the solve
# is then a handful of n_z-long dot products per row, O(N n_z²).
#
# Factor storage ``fac`` of shape (N, n_z, 5 n_z): chain row i holds the five
# n_z × n_z slots [D_i⁻¹ | V_i | W_i | L_i | R_i] side by side (column
# offsets 0, n_z, 2 n_z, 3 n_z, 4 n_z; L_f = 0). The separator rows hold S⁻¹
# in their first 2 n_z columns (rows of p: the first n_z rows of S⁻¹, rows of
# N−1: the last n_z) and the L_r of the chain that ends at them in slot 3.

BC_OK, BC_ZERO_PIVOT, BC_NOT_FINITE = 0, 1, 2


def block_cyclic_alloc(n_theta: int, n_z: int) -> FloatArray:
    """Factor storage for :func:`block_cyclic_factor`, shape (n_theta, n_z, 5 n_z).

    ``n_theta >= 3`` (the three θ-blocks of a row are distinct), ``n_z >= 1``.
    """
    if n_theta < 3 or n_z < 1:
        raise ValueError(f"block cyclic LU needs n_theta >= 3 and n_z >= 1, got {n_theta}, {n_z}")
    return np.empty((n_theta, n_z, 5 * n_z))  # every entry is written by the factorisation


def block_cyclic_chains(n_theta: int) -> tuple[int, tuple[tuple[int, int, int, int], ...]]:
    """Separator p and the two chains ``(first, last, left separator, right separator)``."""
    p = (n_theta - 1) // 2
    return p, ((0, p - 1, n_theta - 1, p), (p + 1, n_theta - 2, p, n_theta - 1))


@njit(cache=True, fastmath={"contract"})
def _gauss_jordan(aug: FloatArray, m: int, width: int, row: FloatArray) -> int:
    """Gauss-Jordan elimination with partial pivoting of ``aug[:, :width]`` to ``[I | D⁻¹ X]``.

    ``aug`` (m, ≥ width) holds ``[D | X]`` with D the m × m pivot block; row
    swaps act on whole rows, so ``[D | X | I]`` yields ``D⁻¹ X`` and ``D⁻¹``
    together. ``row`` (≥ width) is scratch: the scaled pivot row is copied
    there so that every update is one contiguous, vectorised row operation
    (about 3× faster than an LU, its explicit inverse and a product). Returns
    −1, or the column of the first exactly zero pivot (``aug`` is then
    undefined).
    """
    for k in range(m):
        p = k
        best = abs(aug[k, k])
        for r in range(k + 1, m):
            v = abs(aug[r, k])
            if v > best:
                best = v
                p = r
        if best == 0.0:
            return k
        rk = 1.0 / aug[p, k]
        for c in range(width):
            row[c] = aug[p, c] * rk
        if p != k:
            for c in range(width):
                aug[p, c] = aug[k, c]
        for c in range(width):
            aug[k, c] = row[c]
        for r in range(m):
            if r != k:
                f = aug[r, k]
                for c in range(width):
                    aug[r, c] -= f * row[c]
    return -1


@njit(cache=True, fastmath={"contract"})
def _gemm_acc(
    c: FloatArray,
    c0: int,
    a: FloatArray,
    b: FloatArray,
    m: int,
    w: int,
    alpha: float,
) -> None:
    """``c[:, c0:c0+w] += alpha · a @ b[:, :w]`` for ``a`` of shape (m, m).

    Column offset into full C-contiguous rows keeps the inner loop contiguous;
    four rows at a time reuse each row of ``b`` (the register blocking that
    lets the compiler vectorise it: 3× faster than two rows at a time).
    ``a``, ``b`` must not overlap ``c``.
    """
    r = 0
    while r + 4 <= m:
        for k in range(m):
            a0 = alpha * a[r, k]
            a1 = alpha * a[r + 1, k]
            a2 = alpha * a[r + 2, k]
            a3 = alpha * a[r + 3, k]
            for q in range(w):
                bq = b[k, q]
                c[r, c0 + q] += a0 * bq
                c[r + 1, c0 + q] += a1 * bq
                c[r + 2, c0 + q] += a2 * bq
                c[r + 3, c0 + q] += a3 * bq
        r += 4
    while r < m:
        for k in range(m):
            ark = alpha * a[r, k]
            for q in range(w):
                c[r, c0 + q] += ark * b[k, q]
        r += 1


@njit(cache=True, inline="always", fastmath={"reassoc", "contract"})
def _gemv_acc(
    a: FloatArray, c0: int, m: int, w: int, x: FloatArray, y: FloatArray, alpha: float
) -> None:
    """``y[:m] += alpha · a[:, c0:c0+w] @ x[:w]``; ``x`` must not overlap ``y``.

    Four rows at a time: four independent dot products share each load of x
    (twice as fast as one row at a time on 12 × 12 blocks).
    """
    r = 0
    while r + 4 <= m:
        a0 = 0.0
        a1 = 0.0
        a2 = 0.0
        a3 = 0.0
        for c in range(w):
            xc = x[c]
            a0 += a[r, c0 + c] * xc
            a1 += a[r + 1, c0 + c] * xc
            a2 += a[r + 2, c0 + c] * xc
            a3 += a[r + 3, c0 + c] * xc
        y[r] += alpha * a0
        y[r + 1] += alpha * a1
        y[r + 2] += alpha * a2
        y[r + 3] += alpha * a3
        r += 4
    while r < m:
        acc = 0.0
        for c in range(w):
            acc += a[r, c0 + c] * x[c]
        y[r] += alpha * acc
        r += 1


@njit(cache=True)
def _block_ranks(i: int, n_theta: int) -> tuple[int, int, int]:
    """Ranks (W, C, E) of blocks i−1, i, i+1 in block row i of the coupled data."""
    if i == 0:
        return 2, 0, 1
    if i == n_theta - 1:
        return 1, 2, 0
    return 0, 1, 2


@njit(cache=True)
def _rank(i: int, j: int, n_theta: int) -> int:
    """Rank of block column j (i−1, i or i+1 mod N) in block row i of the coupled data."""
    j = j % n_theta
    rw, rc, re = _block_ranks(i, n_theta)
    if j == i:
        return rc
    if j == (i + 1) % n_theta:
        return re
    return rw


@njit(cache=True)
def _norm1(a: FloatArray, c0: int, m: int) -> float:
    """1-norm (largest column sum) of the m × m block ``a[:m, c0:c0+m]``."""
    best = 0.0
    for c in range(m):
        s = 0.0
        for r in range(m):
            s += abs(a[r, c0 + c])
        best = max(best, s)
    return best


@njit(cache=True, nogil=True)
def _chain_factor(
    d4: FloatArray,
    fac: FloatArray,
    first: int,
    last: int,
    left: int,
    right: int,
    sc: FloatArray,
    stats: FloatArray,
) -> int:
    """Eliminate the chain rows ``first … last`` (see the comment above :data:`BC_OK`).

    Fills their factor rows, the chain's contribution ``sc`` (2 m × 2 m, in
    the order [left, right]) to the separators' Schur complement, and
    ``stats = [largest pivot-block entry, smallest rcond, its block row]``.
    Returns a ``BC_*`` status (``stats[2]`` is then the failing row).
    """
    n_b, m = d4.shape[0], d4.shape[1]
    sc[:, :] = 0.0
    stats[0] = 0.0
    stats[1] = np.inf
    stats[2] = first
    if last < first:
        return BC_OK
    aug = np.empty((m, 4 * m))  # [D_i | U_i | G_i | I] → [I | V_i | W_i | D_i⁻¹]
    row = np.empty(4 * m)
    lo = np.empty((m, m))
    vw = np.empty((m, 2 * m))  # [V_i | W_i]
    t = np.zeros((m, 2 * m))  # [R_i | S_ll]
    tmp = np.empty((m, 2 * m))
    for i in range(first, last + 1):
        x = fac[i]
        rc = _rank(i, i, n_b)
        rw = _rank(i, i - 1, n_b)
        for r in range(m):
            for c in range(m):
                x[r, c] = d4[i, r, rc, c]  # D_i
                x[r, m + c] = 0.0  # G_i
                x[r, 3 * m + c] = d4[i, r, rw, c] if i > first else 0.0  # L_i
    rg = _rank(first, left, n_b)
    rr = _rank(left, first, n_b)
    for r in range(m):
        for c in range(m):
            fac[first, r, m + c] = d4[first, r, rg, c]  # G_f = B[f, l]
            t[r, c] = d4[left, r, rr, c]  # R_f = B[l, f]
    for i in range(first, last + 1):
        x = fac[i]
        re = _rank(i, i + 1, n_b)
        dmax = stats[0]
        for r in range(m):
            for c in range(m):
                v = x[r, c]
                dmax = max(dmax, abs(v))
                aug[r, c] = v
                aug[r, m + c] = d4[i, r, re, c]
                aug[r, 2 * m + c] = x[r, m + c]
                aug[r, 3 * m + c] = 1.0 if r == c else 0.0
        stats[0] = dmax
        dnorm = _norm1(x, 0, m)
        if _gauss_jordan(aug, m, 4 * m, row) >= 0:
            stats[2] = i
            return BC_ZERO_PIVOT
        rc_i = 1.0 / (dnorm * _norm1(aug, 3 * m, m))
        if not rc_i >= stats[1]:
            stats[1] = rc_i
            stats[2] = i
        for r in range(m):
            for c in range(m):
                x[r, c] = aug[r, 3 * m + c]
            for c in range(2 * m):
                v = aug[r, m + c]
                x[r, m + c] = v
                vw[r, c] = v
        if i < last:
            x1 = fac[i + 1]
            for r in range(m):
                for c in range(m):
                    lo[r, c] = x1[r, 3 * m + c]
            _gemm_acc(x1, 0, lo, vw, m, 2 * m, -1.0)
        for r in range(m):
            for c in range(m):
                x[r, 4 * m + c] = t[r, c]
                lo[r, c] = t[r, c]
        if i < last:
            for r in range(m):
                for c in range(m):
                    t[r, c] = 0.0
            _gemm_acc(t, 0, lo, vw, m, 2 * m, -1.0)  # R_{i+1}, S_ll
        else:
            tmp[:, :] = 0.0
            _gemm_acc(tmp, 0, lo, vw, m, 2 * m, -1.0)  # −R_e [V_e | W_e]
            for r in range(m):
                for c in range(m):
                    sc[r, m + c] = tmp[r, c]  # S_lr
                    sc[r, c] = t[r, m + c] + tmp[r, m + c]  # S_ll
    rl = _rank(right, last, n_b)
    for r in range(m):
        for c in range(m):
            lo[r, c] = d4[right, r, rl, c]  # L_r = B[r, e]
    tmp[:, :] = 0.0
    _gemm_acc(tmp, 0, lo, vw, m, 2 * m, -1.0)  # −L_r [V_e | W_e]
    for r in range(m):
        for c in range(m):
            sc[m + r, m + c] = tmp[r, c]  # S_rr
            sc[m + r, c] = tmp[r, m + c]  # S_rl
    return BC_OK


@njit(cache=True, nogil=True)
def _separator_factor(
    d4: FloatArray,
    fac: FloatArray,
    sc: FloatArray,
    stats: FloatArray,
    status: IntArray,
    bmax: float,
) -> tuple[int, int, float, float]:
    """Assemble and invert the separators' Schur complement; the result of the factorisation."""
    n_b, m = d4.shape[0], d4.shape[1]
    p = (n_b - 1) // 2
    s_idx = (p, n_b - 1)
    dmax = max(stats[0, 0], stats[1, 0])
    for k in range(2):
        if status[k] != BC_OK:
            return int(status[k]), int(stats[k, 2]), 0.0, dmax / bmax
    rcond = stats[0, 1]
    worst = int(stats[0, 2])
    if not stats[1, 1] >= rcond:
        rcond = stats[1, 1]
        worst = int(stats[1, 2])
    m2 = 2 * m
    aug = np.zeros((m2, 2 * m2))  # [S | I] → [I | S⁻¹]
    row = np.empty(2 * m2)
    for a in range(2):
        for b in range(2):
            i, j = s_idx[a], s_idx[b]
            if i == j or j == (i + 1) % n_b or j == (i - 1) % n_b:
                rk = _rank(i, j, n_b)
                for r in range(m):
                    for c in range(m):
                        aug[a * m + r, b * m + c] = d4[i, r, rk, c]
    for k in range(2):
        # chain A: [left, right] = [N−1, p] → S indices (1, 0); chain B: (0, 1)
        il, ir = (1, 0) if k == 0 else (0, 1)
        for r in range(m):
            for c in range(m):
                aug[il * m + r, il * m + c] += sc[k, r, c]
                aug[il * m + r, ir * m + c] += sc[k, r, m + c]
                aug[ir * m + r, il * m + c] += sc[k, m + r, c]
                aug[ir * m + r, ir * m + c] += sc[k, m + r, m + c]
    for r in range(m2):
        for c in range(m2):
            dmax = max(dmax, abs(aug[r, c]))
        aug[r, m2 + r] = 1.0
    snorm = 0.0
    for c in range(m2):
        col = 0.0
        for r in range(m2):
            col += abs(aug[r, c])
        snorm = max(snorm, col)
    k = _gauss_jordan(aug, m2, 2 * m2, row)
    if k >= 0:
        return BC_ZERO_PIVOT, s_idx[0] if k < m else s_idx[1], 0.0, dmax / bmax
    inorm = 0.0
    for c in range(m2):
        col = 0.0
        for r in range(m2):
            col += abs(aug[r, m2 + c])
        inorm = max(inorm, col)
    rc_s = 1.0 / (snorm * inorm)
    if not rc_s >= rcond:
        rcond = rc_s
        worst = s_idx[1]
    for a in range(2):
        x = fac[s_idx[a]]
        x[:, :] = 0.0
        for r in range(m):
            for c in range(m2):
                x[r, c] = aug[a * m + r, m2 + c]
    for k in range(2):
        first, last, right = (0, p - 1, p) if k == 0 else (p + 1, n_b - 2, n_b - 1)
        if last >= first:
            rl = _rank(right, last, n_b)
            for r in range(m):
                for c in range(m):
                    fac[right, r, 3 * m + c] = d4[right, r, rl, c]  # L_r of the chain
    return BC_OK, worst, rcond, dmax / bmax


@njit(cache=True)
def _check_data(data: FloatArray) -> float:
    """Largest |entry| of the matrix data, or NaN if it holds inf or NaN (branch-free loop)."""
    bmax = 0.0
    nonfinite = 0.0  # v − v is 0 for finite v, NaN for inf or NaN
    for v in data:
        nonfinite += v - v
        av = abs(v)
        bmax = av if av > bmax else bmax
    return bmax if nonfinite == 0.0 else np.nan


@njit(cache=True, nogil=True)
def block_cyclic_factor(
    data: FloatArray, n_theta: int, n_z: int, fac: FloatArray
) -> tuple[int, int, float, float]:
    """Block LU of the periodic block-tridiagonal matrix on :func:`coupled_pattern`.

    Two chains eliminated in turn and their separators (see the comment above
    :data:`BC_OK`); partial pivoting inside each ``n_z × n_z`` pivot block,
    none between blocks, so it is meant for block-diagonally dominant
    matrices such as the BDF Newton matrix ``c0·diag(H) + …``. Cost
    ``O(n_theta n_z³)``. Replaces ``scipy.sparse.linalg.splu`` of the CSR
    matrix; twin :func:`block_cyclic_factor_py`.

    Parameters
    ----------
    data : ndarray, shape (3 n_z · n_theta n_z,)
        CSR data of B on :func:`coupled_pattern` (row ``k = i*n_z + j``,
        ``3 n_z`` entries, θ-blocks in increasing column order).
    n_theta, n_z : int
        Grid size, ``n_theta >= 3``.
    fac : ndarray, shape (n_theta, n_z, 5 n_z)
        Overwritten with the factors (layout above; see :func:`block_cyclic_alloc`).

    Returns
    -------
    status : int
        :data:`BC_OK`; :data:`BC_ZERO_PIVOT` (a pivot block or S is exactly
        singular, ``fac`` is incomplete); :data:`BC_NOT_FINITE` (``data``
        holds inf or NaN, nothing done).
    block : int
        Block row of the worst-conditioned pivot block (the failing one for
        ``BC_ZERO_PIVOT``; a separator row for S).
    rcond : float
        Smallest reciprocal 1-norm condition number ``1/(‖D‖₁ ‖D⁻¹‖₁)`` of
        the pivot blocks and S (exact, from the explicit inverses; 0 if singular).
    growth : float
        Largest entry of the pivot blocks and S after elimination over the
        largest entry of B (about 1 for block diagonally dominant B; large
        values mean that elimination without block pivoting is unstable).
    """
    bmax = _check_data(data)
    if bmax != bmax:
        return BC_NOT_FINITE, -1, 0.0, np.inf
    d4 = data.reshape((n_theta, n_z, 3, n_z))
    p = (n_theta - 1) // 2
    firsts = (0, p + 1)
    lasts = (p - 1, n_theta - 2)
    lefts = (n_theta - 1, p)
    rights = (p, n_theta - 1)
    sc = np.empty((2, 2 * n_z, 2 * n_z))
    stats = np.empty((2, 3))
    status = np.empty(2, dtype=np.int64)
    for k in range(2):  # independent: the place for two threads (not worth it on 2 cores)
        status[k] = _chain_factor(
            d4, fac, firsts[k], lasts[k], lefts[k], rights[k], sc[k], stats[k]
        )
    return _separator_factor(d4, fac, sc, stats, status, bmax)


@njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
def block_cyclic_solve(fac: FloatArray, rhs: FloatArray, out: FloatArray) -> None:
    """Solve ``B x = rhs`` with the factors of :func:`block_cyclic_factor`.

    Cost ``O(n_theta n_z²)`` per right-hand side; twin
    :func:`block_cyclic_solve_py`. Dot products may be reassociated
    (vectorised), which changes results only at rounding level.

    Parameters
    ----------
    fac : ndarray, shape (n_theta, n_z, 5 n_z)
        Output of a successful :func:`block_cyclic_factor`.
    rhs : ndarray, shape (n, k)
        Right-hand sides, ``n = n_theta n_z``, row ``i*n_z + j``.
    out : ndarray, shape (n, k)
        Filled with the solutions (may be ``rhs`` itself).
    """
    n_b = fac.shape[0]
    m = fac.shape[1]
    ncol = rhs.shape[1]
    last_b = n_b - 1
    p = (n_b - 1) // 2
    # (column, block, n_z): block vectors contiguous for the products
    z = np.empty((ncol, n_b, m))
    x = np.empty(2 * m)
    acc = np.empty((2, 2, m))  # per chain: right-hand side updates of [left, right]
    for i in range(n_b):
        for j in range(m):
            for q in range(ncol):
                z[q, i, j] = rhs[i * m + j, q]
    for q in range(ncol):
        zq = z[q]
        acc[:, :, :] = 0.0
        for k in range(2):
            first, last, right = (0, p - 1, p) if k == 0 else (p + 1, n_b - 2, last_b)
            if last < first:
                continue
            # forward: y_i = b_i − L_i z_{i−1}, z_i = D_i⁻¹ y_i, b_l −= R_i z_i, b_r −= L_r z_e
            for i in range(first, last + 1):
                if i > first:
                    _gemv_acc(fac[i], 3 * m, m, m, zq[i - 1], zq[i], -1.0)
                for c in range(m):
                    x[c] = zq[i, c]
                    zq[i, c] = 0.0
                _gemv_acc(fac[i], 0, m, m, x, zq[i], 1.0)
                _gemv_acc(fac[i], 4 * m, m, m, zq[i], acc[k, 0], -1.0)
            _gemv_acc(fac[right], 3 * m, m, m, zq[last], acc[k, 1], -1.0)
        # separators p (chain A's right, chain B's left) and N−1 (A's left, B's right)
        for c in range(m):
            x[c] = zq[p, c] + acc[0, 1, c] + acc[1, 0, c]
            x[m + c] = zq[last_b, c] + acc[0, 0, c] + acc[1, 1, c]
            zq[p, c] = 0.0
            zq[last_b, c] = 0.0
        _gemv_acc(fac[p], 0, m, 2 * m, x, zq[p], 1.0)
        _gemv_acc(fac[last_b], 0, m, 2 * m, x, zq[last_b], 1.0)
        # backward: x_i = z_i − [V_i | W_i] [x_{i+1}; x_l]
        for k in range(2):
            first, last, left = (0, p - 1, last_b) if k == 0 else (p + 1, n_b - 2, p)
            for c in range(m):
                x[m + c] = zq[left, c]
            for i in range(last, first - 1, -1):
                for c in range(m):
                    x[c] = zq[i + 1, c]
                _gemv_acc(fac[i], m, m, 2 * m, x, zq[i], -1.0)
    for i in range(n_b):
        for j in range(m):
            for q in range(ncol):
                out[i * m + j, q] = z[q, i, j]


def block_cyclic_factor_py(
    data: FloatArray, n_theta: int, n_z: int, fac: FloatArray
) -> tuple[int, int, float, float]:
    """NumPy twin of :func:`block_cyclic_factor` (LAPACK inverses of the pivot blocks)."""
    import warnings

    import scipy.linalg as sla

    n_b, m = n_theta, n_z
    if not np.all(np.isfinite(data)):
        return BC_NOT_FINITE, -1, 0.0, np.inf
    bmax = float(np.abs(data).max())
    d4 = data.reshape(n_b, m, 3, m)

    def blk(i: int, j: int) -> FloatArray:
        ranks = (2, 0, 1) if i == 0 else (1, 2, 0) if i == n_b - 1 else (0, 1, 2)
        rank = ranks[1] if j == i else ranks[2] if j == (i + 1) % n_b else ranks[0]
        return d4[i, :, rank, :]

    def invert(a: FloatArray) -> FloatArray | None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", sla.LinAlgWarning)
            lu = sla.lu_factor(a, check_finite=False)[0]
        return None if np.any(np.diag(lu) == 0.0) else np.asarray(np.linalg.inv(a), np.float64)

    def rcond_of(a: FloatArray, inv: FloatArray) -> float:
        return float(1.0 / (np.abs(a).sum(axis=0).max() * np.abs(inv).sum(axis=0).max()))

    fac[:] = 0.0
    p, chains = block_cyclic_chains(n_b)
    dmax, rcond, worst = 0.0, np.inf, 0
    sc = []
    for first, last, left, right in chains:
        contrib = np.zeros((2 * m, 2 * m))
        sc.append(contrib)
        if last < first:
            continue
        d = blk(first, first).copy()
        g = blk(first, left).copy()
        r_cur = blk(left, first).copy()
        s_ll = np.zeros((m, m))
        for i in range(first, last + 1):
            dmax = max(dmax, float(np.abs(d).max()))
            inv = invert(d)
            if inv is None:
                return BC_ZERO_PIVOT, i, 0.0, dmax / bmax
            rc_i = rcond_of(d, inv)
            if not rc_i >= rcond:
                rcond, worst = rc_i, i
            vw = inv @ np.concatenate([blk(i, i + 1), g], axis=1)
            fac[i, :, :m], fac[i, :, m : 3 * m], fac[i, :, 4 * m :] = inv, vw, r_cur
            if i > first:
                fac[i, :, 3 * m : 4 * m] = blk(i, i - 1)
            upd = r_cur @ vw
            if i < last:
                low = blk(i + 1, i)
                d = blk(i + 1, i + 1) - low @ vw[:, :m]
                g = -low @ vw[:, m:]
                r_cur = -upd[:, :m]
                s_ll -= upd[:, m:]
            else:
                contrib[:m, m:] = -upd[:, :m]
                contrib[:m, :m] = s_ll - upd[:, m:]
                upd_r = blk(right, last) @ vw
                contrib[m:, m:] = -upd_r[:, :m]
                contrib[m:, :m] = -upd_r[:, m:]
    s_idx = (p, n_b - 1)
    s = np.zeros((2 * m, 2 * m))
    for a in range(2):
        for b in range(2):
            i, j = s_idx[a], s_idx[b]
            if i == j or j in ((i + 1) % n_b, (i - 1) % n_b):
                s[a * m : (a + 1) * m, b * m : (b + 1) * m] = blk(i, j)
    for k, (il, ir) in enumerate(((1, 0), (0, 1))):
        for a, sa in ((0, il), (1, ir)):
            for b, sb in ((0, il), (1, ir)):
                s[sa * m : (sa + 1) * m, sb * m : (sb + 1) * m] += sc[k][
                    a * m : (a + 1) * m, b * m : (b + 1) * m
                ]
    dmax = max(dmax, float(np.abs(s).max()))
    inv = invert(s)
    if inv is None:
        # the failing column as Gauss-Jordan finds it: the first zero pivot of an LU
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", sla.LinAlgWarning)
            col = int(np.flatnonzero(np.diag(sla.lu_factor(s, check_finite=False)[0]) == 0)[0])
        return BC_ZERO_PIVOT, s_idx[0] if col < m else s_idx[1], 0.0, dmax / bmax
    rc_s = rcond_of(s, inv)
    if not rc_s >= rcond:
        rcond, worst = rc_s, s_idx[1]
    fac[p, :, : 2 * m] = inv[:m]
    fac[n_b - 1, :, : 2 * m] = inv[m:]
    for first, last, _left, right in chains:
        if last >= first:
            fac[right, :, 3 * m : 4 * m] = blk(right, last)
    return BC_OK, worst, rcond, dmax / bmax


def block_cyclic_solve_py(fac: FloatArray, rhs: FloatArray, out: FloatArray) -> None:
    """NumPy twin of :func:`block_cyclic_solve`."""
    n_b, m = fac.shape[0], fac.shape[1]
    dinv, vw, lo, rr = (
        fac[:, :, :m],
        fac[:, :, m : 3 * m],
        fac[:, :, 3 * m : 4 * m],
        fac[:, :, 4 * m :],
    )
    p, chains = block_cyclic_chains(n_b)
    z = rhs.reshape(n_b, m, -1).copy()
    sep = np.zeros((2, 2, *z.shape[1:]))  # per chain: updates of [left, right]
    for k, (first, last, _left, right) in enumerate(chains):
        if last < first:
            continue
        for i in range(first, last + 1):
            if i > first:
                z[i] -= lo[i] @ z[i - 1]
            z[i] = dinv[i] @ z[i]
            sep[k, 0] -= rr[i] @ z[i]
        sep[k, 1] -= lo[right] @ z[last]
    x = np.concatenate([z[p] + sep[0, 1] + sep[1, 0], z[n_b - 1] + sep[0, 0] + sep[1, 1]])
    z[p] = fac[p, :, : 2 * m] @ x
    z[n_b - 1] = fac[n_b - 1, :, : 2 * m] @ x
    for first, last, left, _right in chains:
        for i in range(last, first - 1, -1):
            z[i] -= vw[i] @ np.concatenate([z[i + 1], z[left]])
    out[:] = z.reshape(out.shape)


# ---------------------------------------------------------------------------
# Transient Newton iteration (compiled; NumPy twins in reynolds.transient)
# ---------------------------------------------------------------------------


@njit(cache=True)
def _film_rows(
    y: FloatArray,
    preload: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    n_z: int,
    q: FloatArray,
    h_row: FloatArray,
) -> float:
    """Engaged mean gauge pressure q and film H per θ-row of a transient state.

    Fills ``q[i] = max(mean_j P[i, j] − 1, 0)`` and
    ``h_row[i] = 1 + ε_X cos θ_i + ε_Y sin θ_i − r_p,i/C + U_i + c_a,i q_i``;
    returns ``min_i h_row[i]`` (NaN if any row is NaN).
    """
    n_theta = q.shape[0]
    n = n_theta * n_z
    e_x = y[n + n_theta]
    e_y = y[n + n_theta + 1]
    h_min = np.inf
    bad = False
    for i in range(n_theta):
        acc = 0.0
        for j in range(n_z):
            acc += y[i * n_z + j]
        qi = acc / n_z - 1.0
        if qi < 0.0:
            qi = 0.0
        q[i] = qi
        h = 1.0 + e_x * cos_t[i] + e_y * sin_t[i] - preload[i] + y[n + i] + c_act[i] * qi
        h_row[i] = h
        if h != h:
            bad = True
        elif h < h_min:
            h_min = h
    return np.nan if bad else h_min


@njit(cache=True, nogil=True)
def transient_residual(
    y: FloatArray,
    c0: float,
    hist: FloatArray,
    lam: float,
    rate: float,
    preload: FloatArray,
    force: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    c_bump: FloatArray,
    w: FloatArray,
    force_scale: float,
    denom: float,
    d_theta: float,
    d_z: float,
    H: FloatArray,
    res: FloatArray,
    out: FloatArray,
) -> float:
    """BDF equations ``G = c0·Q(y) + hist − f(y)`` and the minimum film, in one pass.

    Twin: :meth:`foilbearing.reynolds.transient.TransientSystem.newton_residual_py`
    (same result up to rounding: dot products are summed in another order).

    Parameters
    ----------
    y : ndarray, shape (n + n_theta + 4,)
        State ``[P (n), U (n_theta), ε_X, ε_Y, v_X, v_Y]``, ``n = n_theta n_z``,
        P cell ``k = i*n_z + j``.
    c0 : float
        BDF leading coefficient α₀/Δt, 1/s.
    hist : ndarray, shape (n + n_theta + 4,)
        History part of the BDF equations.
    lam : float
        Bearing number Λ(t).
    rate : float
        ω/γ of the viscoelastic bump, 1/s (0 for a purely elastic bump).
    preload : ndarray, shape (n_theta,)
        r_p(θ_i, t)/C.
    force : ndarray, shape (2,)
        External force on the journal in units of m·C, 1/s².
    cos_t, sin_t : ndarray, shape (n_theta,)
        cos θ_i, sin θ_i.
    c_act, c_bump : ndarray, shape (n_theta,)
        Actuator and bump compliances per θ-row, p_a/(C k).
    w : ndarray, shape (2, n)
        Force weights (X, Y) of the cells.
    force_scale : float
        p_a R²/(m C), 1/s².
    denom : float
        ``A σ = ΔθΔZ · 12 μ R²/(p_a C²)``, s.
    d_theta, d_z : float
        Cell sizes Δθ, ΔZ.
    H, res : ndarray, shape (n_theta, n_z)
        Filled with the film h/C and the finite-volume residual :func:`residual`.
    out : ndarray, shape (n + n_theta + 4,)
        Filled with G.

    Returns
    -------
    float
        Minimum film ``min H`` (NaN if the film holds a NaN).
    """
    n_theta, n_z = H.shape
    n = n_theta * n_z
    q = np.empty(n_theta)
    h_row = np.empty(n_theta)
    h_min = _film_rows(y, preload, cos_t, sin_t, c_act, n_z, q, h_row)
    for i in range(n_theta):
        for j in range(n_z):
            H[i, j] = h_row[i]
    P = y[:n].reshape((n_theta, n_z))
    residual(P, H, lam, d_theta, d_z, res)
    fx = 0.0
    fy = 0.0
    for i in range(n_theta):
        h = h_row[i]
        for j in range(n_z):
            k = i * n_z + j
            p = y[k]
            out[k] = c0 * (p * h) - res[i, j] / denom + hist[k]
            fx += w[0, k] * (p - 1.0)
            fy += w[1, k] * (p - 1.0)
        u = y[n + i]
        out[n + i] = c0 * u - rate * (c_bump[i] * q[i] - u) + hist[n + i]
    m = n + n_theta
    for k in range(2):
        out[m + k] = c0 * y[m + k] - y[m + 2 + k] + hist[m + k]
    out[m + 2] = c0 * y[m + 2] - force_scale * fx - force[0] + hist[m + 2]
    out[m + 3] = c0 * y[m + 3] - force_scale * fy - force[1] + hist[m + 3]
    return h_min


@njit(cache=True, nogil=True)
def transient_storage(
    y: FloatArray,
    preload: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    n_z: int,
    out: FloatArray,
) -> float:
    """Stored quantities ``Q(y) = [P·H, U, ε, v]`` and the minimum film, in one pass.

    Twin: :meth:`foilbearing.reynolds.transient.TransientSystem.storage` and
    :meth:`~foilbearing.reynolds.transient.TransientSystem.min_film`.

    Parameters
    ----------
    y : ndarray, shape (n + n_theta + 4,)
        State (see :func:`transient_residual`).
    preload, cos_t, sin_t, c_act : ndarray, shape (n_theta,)
        As in :func:`transient_residual`.
    n_z : int
        Cells per θ-row.
    out : ndarray, shape (n + n_theta + 4,)
        Filled with Q(y).

    Returns
    -------
    float
        Minimum film ``min H`` (NaN if the film holds a NaN).
    """
    n_theta = preload.shape[0]
    q = np.empty(n_theta)
    h_row = np.empty(n_theta)
    h_min = _film_rows(y, preload, cos_t, sin_t, c_act, n_z, q, h_row)
    for i in range(n_theta):
        h = h_row[i]
        for j in range(n_z):
            k = i * n_z + j
            out[k] = y[k] * h
    for k in range(n_theta * n_z, y.shape[0]):
        out[k] = y[k]
    return h_min


@njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
def transient_solve(
    g: FloatArray,
    fac: FloatArray,
    jh_data: FloatArray,
    jh_rows: IntArray,
    jh_indptr: IntArray,
    a_pe: FloatArray,
    s_vp: FloatArray,
    y_border: FloatArray,
    small_inv: FloatArray,
    c0: float,
    rate: float,
    active: FloatArray,
    c_bump: FloatArray,
    work: FloatArray,
    out: FloatArray,
) -> None:
    """Newton update ``Δy`` with ``J Δy = g`` by block elimination (factors of the transient matrix).

    Eliminates the bump states U and the journal (ε, v), solves the pressure
    block with :func:`block_cyclic_solve` and applies the rank-2 Woodbury
    correction of the film force. Twin:
    :meth:`foilbearing.reynolds.transient.TransientFactor.solve_py` (same result
    up to rounding).

    Parameters
    ----------
    g : ndarray, shape (n + n_theta + 4,)
        Right-hand side (the BDF residual), ``n = n_theta n_z``.
    fac : ndarray, shape (n_theta, n_z, 5 n_z)
        Block cyclic factors of the pressure block B (:func:`block_cyclic_factor`).
    jh_data, jh_rows, jh_indptr : ndarray
        CSR arrays of the scaled film Jacobian ``c0·diag(P) − ∂R/∂H/(Aσ)``, (n, n),
        with the θ-row ``indices // n_z`` of each column in place of its index
        (the mat-vec is with ``repeat(x, n_z)``).
    a_pe : ndarray, shape (n, 2)
        Its product with ``∂H/∂ε`` (columns cos θ, sin θ per cell).
    s_vp : ndarray, shape (2, n)
        Film force per unit P as an acceleration, 1/s².
    y_border : ndarray, shape (n, 2)
        ``B⁻¹ a_pe / c0²``.
    small_inv : ndarray, shape (2, 2)
        Inverse of the Woodbury matrix ``I + s_vp y_border``.
    c0 : float
        BDF leading coefficient at factorisation, 1/s.
    rate : float
        ω/γ of the bump (0 for an elastic bump), 1/s.
    active : ndarray, shape (n_theta,)
        1.0 on θ-rows where the mean gauge pressure is engaged, else 0.0.
    c_bump : ndarray, shape (n_theta,)
        Bump compliance per θ-row.
    work : ndarray, shape (n, 1)
        Scratch (the pressure right-hand side).
    out : ndarray, shape (n + n_theta + 4,)
        Filled with Δy.
    """
    n_theta = active.shape[0]
    n = work.shape[0]
    n_z = n // n_theta
    m = n + n_theta
    cu = c0 + rate
    c2 = c0**2
    b0 = (g[m + 2] + c0 * g[m]) / c2
    b1 = (g[m + 3] + c0 * g[m + 1]) / c2
    g_u = np.empty(n_theta)
    for i in range(n_theta):
        g_u[i] = g[n + i] / cu
    for r in range(n):
        acc = 0.0
        for s in range(jh_indptr[r], jh_indptr[r + 1]):
            acc += jh_data[s] * g_u[jh_rows[s]]
        work[r, 0] = g[r] - acc - (a_pe[r, 0] * b0 + a_pe[r, 1] * b1)
    block_cyclic_solve(fac, work, work)
    t0 = 0.0
    t1 = 0.0
    for r in range(n):
        t0 += s_vp[0, r] * work[r, 0]
        t1 += s_vp[1, r] * work[r, 0]
    u0 = small_inv[0, 0] * t0 + small_inv[0, 1] * t1
    u1 = small_inv[1, 0] * t0 + small_inv[1, 1] * t1
    f0 = 0.0
    f1 = 0.0
    for r in range(n):
        d = work[r, 0] - (y_border[r, 0] * u0 + y_border[r, 1] * u1)
        out[r] = d
        f0 += s_vp[0, r] * d
        f1 += s_vp[1, r] * d
    for k in range(2):
        d_e = ((f0 if k == 0 else f1) + g[m + 2 + k] + c0 * g[m + k]) / c2
        out[m + k] = d_e
        out[m + 2 + k] = c0 * d_e - g[m + k]
    for i in range(n_theta):
        acc = 0.0
        for j in range(n_z):
            acc += out[i * n_z + j]
        dq = active[i] * (acc / n_z)
        out[n + i] = (g[n + i] + rate * c_bump[i] * dq) / cu


@njit(cache=True, nogil=True)
def transient_jacobian(
    y: FloatArray,
    c0: float,
    lam: float,
    rate: float,
    preload: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    c_bump: FloatArray,
    denom: float,
    d_theta: float,
    d_z: float,
    diag_slots: IntArray,
    jh_rows: IntArray,
    jh_indptr: IntArray,
    H: FloatArray,
    jp: FloatArray,
    jh: FloatArray,
    active: FloatArray,
    jc: FloatArray,
    a_pe: FloatArray,
) -> None:
    """Blocks of the transient Newton matrix at y, all but the factorisation, in one pass.

    Fills the film, the row-scaled Reynolds Jacobians ``c0·diag(H) − ∂R/∂P/(Aσ)``
    and ``c0·diag(P) − ∂R/∂H/(Aσ)`` (pattern :func:`stencil_pattern`), the
    engaged rows, the pressure block B on :func:`coupled_pattern` (bump and
    actuator eliminated, :func:`coupled_jacobian`) and the border
    ``a_pe = (c0·diag(P) − ∂R/∂H/(Aσ)) ∂H/∂ε``. Twin:
    :meth:`foilbearing.reynolds.transient.TransientSystem.jacobian_blocks_py`
    (same result up to rounding: the axial means are summed in another order).

    Parameters
    ----------
    y : ndarray, shape (n + n_theta + 4,)
        State (see :func:`transient_residual`), ``n = n_theta n_z``.
    c0 : float
        BDF leading coefficient α₀/Δt, 1/s.
    lam, rate : float
        Bearing number Λ(t) and ω/γ of the bump (0 for an elastic bump), 1/s.
    preload, cos_t, sin_t, c_act, c_bump : ndarray, shape (n_theta,)
        As in :func:`transient_residual`.
    denom : float
        ``A σ``, s.
    d_theta, d_z : float
        Cell sizes Δθ, ΔZ.
    diag_slots : ndarray, shape (n,)
        Position of the diagonal entry of each row in the stencil data.
    jh_rows, jh_indptr : ndarray
        θ-row of each stencil column and the stencil row pointers.
    H : ndarray, shape (n_theta, n_z)
        Filled with the film h/C.
    jp, jh : ndarray, shape (nnz,)
        Filled with the scaled pressure and film Jacobians (stencil data).
    active : ndarray, shape (n_theta,)
        Filled with 1.0 where the mean gauge pressure is engaged, else 0.0.
    jc : ndarray, shape (3 n_z · n,)
        Filled with the data of B.
    a_pe : ndarray, shape (n, 2)
        Filled with the border.
    """
    n_theta, n_z = H.shape
    n = n_theta * n_z
    q = np.empty(n_theta)
    h_row = np.empty(n_theta)
    _film_rows(y, preload, cos_t, sin_t, c_act, n_z, q, h_row)
    for i in range(n_theta):
        for j in range(n_z):
            H[i, j] = h_row[i]
    P = y[:n].reshape((n_theta, n_z))
    _jacobian_both(P, H, lam, d_theta, d_z, jp, jh)
    m_scale = -(1.0 / denom)
    for k in range(jp.shape[0]):
        jp[k] = m_scale * jp[k]
        jh[k] = m_scale * jh[k]
    for k in range(n):
        d = diag_slots[k]
        jp[d] += c0 * h_row[k // n_z]
        jh[d] += c0 * y[k]
    s = np.empty(n_theta)
    for i in range(n_theta):
        acc = 0.0
        for j in range(n_z):
            acc += y[i * n_z + j]
        active[i] = 1.0 if acc / n_z - 1.0 > 0.0 else 0.0
        c_eff = c_act[i] + rate * c_bump[i] / (c0 + rate)
        s[i] = c_eff * active[i] / n_z
    coupled_jacobian(jp, jh, s, n_z, jc)
    for r in range(n):
        a0 = 0.0
        a1 = 0.0
        for k in range(jh_indptr[r], jh_indptr[r + 1]):
            row = jh_rows[k]
            a0 += jh[k] * cos_t[row]
            a1 += jh[k] * sin_t[row]
        a_pe[r, 0] = a0
        a_pe[r, 1] = a1


@njit(cache=True, nogil=True)
def transient_border(
    fac: FloatArray,
    a_pe: FloatArray,
    s_vp: FloatArray,
    c0: float,
    y_border: FloatArray,
    small_inv: FloatArray,
) -> None:
    """Border solve and 2×2 Woodbury inverse of the transient Newton matrix.

    ``y_border = B⁻¹ a_pe / c0²`` with the factors of :func:`block_cyclic_factor`
    and ``small_inv = (I + s_vp y_border)⁻¹`` in closed form. Twin:
    :meth:`foilbearing.reynolds.transient.TransientSystem.border_py`.

    Parameters
    ----------
    fac : ndarray, shape (n_theta, n_z, 5 n_z)
        Block cyclic factors of B.
    a_pe : ndarray, shape (n, 2)
        Border (:func:`transient_jacobian`).
    s_vp : ndarray, shape (2, n)
        Film force per unit P as an acceleration, 1/s².
    c0 : float
        BDF leading coefficient, 1/s.
    y_border : ndarray, shape (n, 2)
        Filled with ``B⁻¹ a_pe / c0²``.
    small_inv : ndarray, shape (2, 2)
        Filled with the inverse of the Woodbury matrix.
    """
    n = a_pe.shape[0]
    c2 = c0**2
    for r in range(n):
        y_border[r, 0] = a_pe[r, 0] / c2
        y_border[r, 1] = a_pe[r, 1] / c2
    block_cyclic_solve(fac, y_border, y_border)
    m00 = 1.0
    m01 = 0.0
    m10 = 0.0
    m11 = 1.0
    for r in range(n):
        m00 += s_vp[0, r] * y_border[r, 0]
        m01 += s_vp[0, r] * y_border[r, 1]
        m10 += s_vp[1, r] * y_border[r, 0]
        m11 += s_vp[1, r] * y_border[r, 1]
    det = m00 * m11 - m01 * m10
    small_inv[0, 0] = m11 / det
    small_inv[0, 1] = -m01 / det
    small_inv[1, 0] = -m10 / det
    small_inv[1, 1] = m00 / det


@njit(cache=True, nogil=True)
def transient_newton_step(
    y: FloatArray,
    c0: float,
    hist: FloatArray,
    lam: float,
    rate: float,
    preload: FloatArray,
    force: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    c_bump: FloatArray,
    w: FloatArray,
    force_scale: float,
    denom: float,
    d_theta: float,
    d_z: float,
    H: FloatArray,
    res: FloatArray,
    g: FloatArray,
    fac: FloatArray,
    jh_data: FloatArray,
    jh_rows: IntArray,
    jh_indptr: IntArray,
    a_pe: FloatArray,
    s_vp: FloatArray,
    y_border: FloatArray,
    small_inv: FloatArray,
    fac_c0: float,
    fac_rate: float,
    active: FloatArray,
    work: FloatArray,
    dy: FloatArray,
    weights: FloatArray,
) -> tuple[float, float, float]:
    """One modified-Newton iteration: residual, solve and update of y, in one call.

    :func:`transient_residual` into ``g``; if the film stays open (minimum
    > 0), :func:`transient_solve` into ``dy`` with the factor (taken at
    ``fac_c0``, ``fac_rate``) and :func:`newton_update` of y. Twin:
    :meth:`foilbearing.reynolds.transient.TransientFactor.newton_step_py`
    (those three in sequence). Arguments as in those kernels.

    Returns
    -------
    h_min : float
        Minimum film of y before the update (NaN if the film holds a NaN).
    err : float
        Weighted max-norm of dy (NaN if y was not updated: ``h_min <= 0``).
    p_min : float
        Smallest pressure after the update (NaN if not updated).
    """
    h_min = transient_residual(
        y, c0, hist, lam, rate, preload, force, cos_t, sin_t, c_act, c_bump, w,
        force_scale, denom, d_theta, d_z, H, res, g,
    )  # fmt: skip
    if h_min <= 0.0:
        return h_min, np.nan, np.nan
    transient_solve(
        g, fac, jh_data, jh_rows, jh_indptr, a_pe, s_vp, y_border, small_inv, fac_c0,
        fac_rate, active, c_bump, work, dy,
    )  # fmt: skip
    err, p_min = newton_update(y, dy, weights, H.shape[0] * H.shape[1])
    return h_min, err, p_min


#: Outcomes of :func:`transient_newton_solve`.
NEWTON_CONVERGED, NEWTON_FILM_CLOSED, NEWTON_NOT_FINITE, NEWTON_TOO_SLOW = 0, 1, 2, 3
NEWTON_DIVERGED, NEWTON_REFRESH = 4, 5


@njit(cache=True, nogil=True)
def transient_newton_solve(
    y: FloatArray,
    c0: float,
    hist: FloatArray,
    lam: float,
    rate: float,
    preload: FloatArray,
    force: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    c_bump: FloatArray,
    w: FloatArray,
    force_scale: float,
    denom: float,
    d_theta: float,
    d_z: float,
    H: FloatArray,
    res: FloatArray,
    g: FloatArray,
    fac: FloatArray,
    jh_data: FloatArray,
    jh_rows: IntArray,
    jh_indptr: IntArray,
    a_pe: FloatArray,
    s_vp: FloatArray,
    y_border: FloatArray,
    small_inv: FloatArray,
    fac_c0: float,
    fac_rate: float,
    active: FloatArray,
    work: FloatArray,
    dy: FloatArray,
    weights: FloatArray,
    q_out: FloatArray,
    newton_tol: float,
    newton_fraction: float,
    max_newton: int,
    fresh: bool,
    first_change: float,
) -> tuple[int, int, float, float]:
    """Modified-Newton iterations with one factor until they converge or must stop.

    Repeats :func:`transient_newton_step`. Converged when the weighted update
    ``err <= tol = max(newton_tol, newton_fraction · first update)`` or when the
    error left, ``rate/(1 − rate)·err`` with the measured contraction rate, is
    below tol; the storage ``Q(y)`` then goes to ``q_out``
    (:func:`transient_storage`). A fresh factor (``fresh``) stops after
    ``max_newton`` iterations or at a rate above 0.5; a stale one when it
    diverges (rate >= 1, or ``max_newton``), or asks for a refresh when it
    would not converge within ``max_newton`` iterations. Twin:
    :meth:`foilbearing.reynolds.transient.TransientFactor.newton_solve_py`.

    Returns
    -------
    outcome : int
        ``NEWTON_CONVERGED``, ``NEWTON_FILM_CLOSED`` (y not updated),
        ``NEWTON_NOT_FINITE`` (NaN update or a pressure <= 0),
        ``NEWTON_TOO_SLOW`` (fresh factor), ``NEWTON_DIVERGED`` or
        ``NEWTON_REFRESH`` (stale factor; y is the last iterate).
    iterations : int
        Iterations done.
    first_change : float
        The first update of the step (carried over a refresh).
    h_min : float
        Minimum film of the converged y (NaN otherwise).
    """
    prev = np.inf
    k = 0
    while True:
        k += 1
        h_min, err, p_min = transient_newton_step(
            y, c0, hist, lam, rate, preload, force, cos_t, sin_t, c_act, c_bump, w,
            force_scale, denom, d_theta, d_z, H, res, g, fac, jh_data, jh_rows, jh_indptr,
            a_pe, s_vp, y_border, small_inv, fac_c0, fac_rate, active, work, dy, weights,
        )  # fmt: skip
        if h_min <= 0.0:
            return NEWTON_FILM_CLOSED, k, first_change, np.nan
        if not np.isfinite(err) or p_min <= 0.0:
            return NEWTON_NOT_FINITE, k, first_change, np.nan
        if first_change == np.inf:
            first_change = err
        tol = max(newton_tol, newton_fraction * first_change)
        # Contraction rate of this factor; the error left in y is about rate/(1−rate)·err.
        conv = err / prev if k > 1 else np.nan
        if err <= tol or (conv < 1.0 and conv / (1.0 - conv) * err <= tol):
            h_new = transient_storage(y, preload, cos_t, sin_t, c_act, H.shape[1], q_out)
            if h_new > 0.0:
                return NEWTON_CONVERGED, k, first_change, h_new
        if fresh:
            if k >= max_newton or conv > 0.5:
                return NEWTON_TOO_SLOW, k, first_change, np.nan
        elif k >= max_newton or conv >= 1.0:
            return NEWTON_DIVERGED, k, first_change, np.nan
        elif conv ** (max_newton - k) / (1.0 - conv) * err > tol:
            return NEWTON_REFRESH, k, first_change, np.nan
        prev = err


@njit(cache=True, nogil=True)
def bdf2_setup(
    y: FloatArray,
    y1: FloatArray,
    y2: FloatArray,
    q_now: FloatArray,
    q_prev: FloatArray,
    h: float,
    h1: float,
    h2: float,
    atol: FloatArray,
    rtol: float,
    guess: FloatArray,
    hist: FloatArray,
    weights: FloatArray,
) -> float:
    """Variable-step BDF2 coefficient, history, predictor and error weights of one step.

    With the last step h1 (NaN: none, BDF1 from y) and the one before, h2
    (NaN: none, linear extrapolation): ``c0 = (1 + 2ρ)/((1 + ρ) h)``,
    ``hist = (−(1 + ρ) Q_n + ρ²/(1 + ρ) Q_{n−1})/h`` (ρ = h/h1), the predictor
    extrapolates through y (t_n), y1 (t_n − h1) and y2 (t_n − h1 − h2), and
    ``weights = 1/(atol + rtol |guess|)``. Twin: :func:`bdf2_setup_py`.

    Returns
    -------
    float
        c0, 1/s.
    """
    n = y.shape[0]
    if h1 != h1:
        c0 = 1.0 / h
        for k in range(n):
            hist[k] = -q_now[k] / h
            guess[k] = y[k]
    else:
        rho = h / h1
        c0 = (1.0 + 2.0 * rho) / ((1.0 + rho) * h)
        a = -(1.0 + rho) / h
        b = rho * rho / (1.0 + rho) / h
        for k in range(n):
            hist[k] = a * q_now[k] + b * q_prev[k]
        if h2 != h2:
            for k in range(n):
                guess[k] = y[k] + rho * (y[k] - y1[k])
        else:
            # Lagrange extrapolation on the nodes 0, −h1, −h1 − h2 to +h
            t1 = -h1
            t2 = -h1 - h2
            l0 = (h - t1) * (h - t2) / (t1 * t2)
            l1 = h * (h - t2) / (t1 * (t1 - t2))
            l2 = h * (h - t1) / (t2 * (t2 - t1))
            for k in range(n):
                guess[k] = l0 * y[k] + l1 * y1[k] + l2 * y2[k]
    for k in range(n):
        weights[k] = 1.0 / (atol[k] + rtol * abs(guess[k]))
    return c0


def bdf2_setup_py(
    y: FloatArray,
    y1: FloatArray,
    y2: FloatArray,
    q_now: FloatArray,
    q_prev: FloatArray,
    h: float,
    h1: float,
    h2: float,
    atol: FloatArray,
    rtol: float,
    guess: FloatArray,
    hist: FloatArray,
    weights: FloatArray,
) -> float:
    """NumPy twin of :func:`bdf2_setup`."""
    if math.isnan(h1):
        c0 = 1.0 / h
        hist[:] = -q_now / h
        guess[:] = y
    else:
        rho = h / h1
        c0 = (1 + 2 * rho) / ((1 + rho) * h)
        hist[:] = (-(1 + rho) * q_now + rho * rho / (1 + rho) * q_prev) / h
        if math.isnan(h2):
            guess[:] = y + rho * (y - y1)
        else:
            t1, t2 = -h1, -h1 - h2
            l0 = (h - t1) * (h - t2) / (t1 * t2)
            l1 = h * (h - t2) / (t1 * (t1 - t2))
            l2 = h * (h - t1) / (t2 * (t2 - t1))
            guess[:] = l0 * y + l1 * y1 + l2 * y2
    weights[:] = 1.0 / (atol + rtol * np.abs(guess))
    return c0


@njit(cache=True)
def newton_update(
    y: FloatArray, dy: FloatArray, weights: FloatArray, n: int
) -> tuple[float, float]:
    """``y −= dy`` in place; the weighted max-norm of dy and the smallest new pressure.

    Twin :func:`newton_update_py`.

    Parameters
    ----------
    y, dy, weights : ndarray, shape (m,)
        Iterate (updated in place), Newton update and error weights.
    n : int
        Number of pressure unknowns (the first n entries of y).

    Returns
    -------
    err : float
        ``max |dy| · weights`` (NaN if any term is NaN).
    p_min : float
        ``min y[:n]`` after the update.
    """
    err = 0.0
    bad = False
    p_min = np.inf
    for k in range(y.shape[0]):
        y[k] -= dy[k]
        e = abs(dy[k]) * weights[k]
        if e != e:
            bad = True
        elif e > err:
            err = e
        if k < n and y[k] < p_min:
            p_min = y[k]
    return (np.nan if bad else err), p_min


def newton_update_py(
    y: FloatArray, dy: FloatArray, weights: FloatArray, n: int
) -> tuple[float, float]:
    """NumPy twin of :func:`newton_update`."""
    y -= dy
    return float(np.max(np.abs(dy) * weights)), float(y[:n].min())
