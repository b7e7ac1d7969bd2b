"""Finite-volume Reynolds residual and Jacobians: Bernoulli function, face fluxes,
sparsity patterns and the compiled kernels (NumPy twins in :mod:`foilbearing.reynolds.reference`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.laws.lift_off import smoothed_edge_kernel

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: Real or complex data (the complex one for the perturbation at a frequency).
DataArray = NDArray[Any]  # float64, or complex128 (the perturbation at a frequency)
#: An argument group as a kernel takes it (a plain tuple; here the AxialStencil).
Group = tuple[Any, ...]

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

    Twin: :func:`~foilbearing.reynolds.reference.bernoulli_py`. Negative arguments use
    ``B(x) = B(−x) − x``, which is exact and free of overflow.
    """
    if x >= 0.0:
        return _bern_pos(x)[0]
    return _bern_pos(-x)[0] - x


@njit(cache=True)
def bernoulli_deriv(x: float) -> float:
    """Derivative ``B'(x)``; twin :func:`~foilbearing.reynolds.reference.bernoulli_deriv_py`.

    Negative arguments use ``B'(x) = −B'(−x) − 1``.
    """
    if x >= 0.0:
        return _bern_pos(x)[1]
    return -_bern_pos(-x)[1] - 1.0


# ---------------------------------------------------------------------------
# Sparsity patterns
# ---------------------------------------------------------------------------


def stencil_pattern(
    n_theta: int, n_z: int, axial_order: int = 2
) -> tuple[IntArray, IntArray, IntArray]:
    """CSR pattern of the film stencil, periodic in θ, columns sorted.

    Order 2: the 5-point stencil; order 4: 7 points, ``(i, j−2 .. j+2)`` axially.

    Parameters
    ----------
    n_theta, n_z : int
        Grid size (``n_theta >= 3`` so that W, C, E are distinct; ``n_z >= 2``).
    axial_order : int
        2 or 4 (:class:`~foilbearing.reynolds.grid.AxialStencil`).

    Returns
    -------
    indptr : ndarray, shape (n_theta*n_z + 1,)
    indices : ndarray, shape (nnz,), ``nnz = n_theta (5 n_z − 2)`` at order 2
    slots : ndarray, shape (n_theta, n_z, 5) at order 2, (n_theta, n_z, 7) at order 4
        Position in ``data`` of the entry of row ``(i, j)`` in direction
        W, S, C, N, E (see module constants; order 4: W, j−2, j−1, C, j+1, j+2, E),
        ``-1`` where absent (S on the mid-plane row ``j = 0``, N on the end row
        ``j = n_z−1``). The order-2 kernels compute the same positions in place
        (:func:`_row_slots`).
    """
    reach = 1 if axial_order == 2 else 2
    i = np.repeat(np.arange(n_theta), n_z)
    j = np.tile(np.arange(n_z), n_theta)
    row = i * n_z + j
    axial = [np.where((j + d >= 0) & (j + d < n_z), row + d, -1) for d in range(-reach, reach + 1)]
    cols = np.stack(
        [((i - 1) % n_theta) * n_z + j, *axial, ((i + 1) % n_theta) * n_z + j],
        axis=1,
    )
    width = cols.shape[1]
    present = cols >= 0
    big = n_theta * n_z + 1
    key = np.where(present, cols, big)
    order = np.argsort(key, axis=1, kind="stable")
    rank = np.empty_like(order)
    np.put_along_axis(rank, order, np.arange(width)[None, :].repeat(len(row), 0), axis=1)
    counts = present.sum(axis=1)
    indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    sorted_key = np.take_along_axis(key, order, axis=1)
    indices = sorted_key[sorted_key < big].astype(np.int64)
    slots = np.where(present, indptr[:-1, None] + rank, -1).astype(np.int64)
    return indptr, indices, slots.reshape(n_theta, n_z, width)


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
def _axial_flux4(
    P: FloatArray, H: FloatArray, i: int, f: int, d_z: float, axial: Group
) -> tuple[float, float]:
    """Fourth-order axial flux through face f of θ-row i, and its H-factor ``3 H_f² ψ_f/ΔZ``.

    ``q = H_f³ (Σ_m c_m ψ_m + c)/ΔZ`` with ``ψ = P²`` (:class:`~..grid.AxialStencil`).
    """
    cols, coef, const = axial[1], axial[2], axial[3]
    n_z = P.shape[1]
    acc = const[f]
    for m in range(4):
        c = coef[f, m]
        if c != 0.0:
            p = P[i, cols[f, m]]
            acc += c * p * p
    hf = H[i, f] if f == n_z - 1 else 0.5 * (H[i, f] + H[i, f + 1])
    hf2 = hf * hf
    return hf2 * hf * acc / d_z, 3.0 * hf2 * acc / d_z


@njit(cache=True)
def residual(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: Group,
    out: FloatArray,
) -> None:
    """Finite-volume residual of Eq. (4), cell-integrated.

    Twin: :func:`~foilbearing.reynolds.reference.residual_py`.

    Parameters
    ----------
    P, H : ndarray, shape (n_theta, n_z)
        Dimensionless pressure ``p/p_a`` (> 0) and film ``h/C`` (> 0).
    lam : float
        Bearing number ``Λ = 6 μ ω R²/(p_a C²)`` (any sign).
    d_theta, d_z : float
        Cell sizes Δθ, ΔZ.
    axial : AxialStencil (as a plain tuple)
        The axial discretisation (:attr:`~foilbearing.reynolds.grid.FilmGrid.axial`).
    out : ndarray, shape (n_theta, n_z)
        Filled with ``R[i, j]`` (net outflow of q through the cell faces).
    """
    n_theta, n_z = P.shape
    second = axial[0] == 2
    out[:, :] = 0.0
    for i in range(n_theta):
        ie = i + 1 if i < n_theta - 1 else 0
        for j in range(n_z):
            q = _theta_flux(P[i, j], P[ie, j], H[i, j], H[ie, j], lam, d_theta)
            out[i, j] += d_z * q
            out[ie, j] -= d_z * q
        if second:
            for j in range(n_z - 1):
                q = _z_face(P[i, j], P[i, j + 1], H[i, j], H[i, j + 1], d_z)[0]
                out[i, j] += d_theta * q
                out[i, j + 1] -= d_theta * q
            out[i, n_z - 1] += d_theta * _end_face(P[i, n_z - 1], H[i, n_z - 1], d_z)[0]
        else:
            for f in range(n_z):
                q = _axial_flux4(P, H, i, f, d_z, axial)[0]
                out[i, f] += d_theta * q
                if f < n_z - 1:
                    out[i, f + 1] -= d_theta * q


@njit(cache=True, inline="always")
def _wce(i: int, j: int, n_theta: int, n_z: int, axial: Group) -> tuple[int, int, int]:
    """Positions (W, C, E) of row (i, j) in the stencil data, at either axial order."""
    if axial[0] == 2:
        w, _, c, _, e = _row_slots(i, j, n_theta, n_z)
        return w, c, e
    slots = axial[4]
    return slots[i, j, 0], slots[i, j, 3], slots[i, j, 6]


@njit(cache=True)
def _axial_jacobian4(
    P: FloatArray,
    H: FloatArray,
    i: int,
    d_theta: float,
    d_z: float,
    axial: Group,
    data_p: FloatArray,
    data_h: FloatArray,
    want_p: bool,
    want_h: bool,
) -> None:
    """Add the fourth-order axial fluxes' derivatives of θ-row i (∂R/∂P and/or ∂R/∂H)."""
    cols, coef, slots = axial[1], axial[2], axial[4]
    n_z = P.shape[1]
    for f in range(n_z):
        _, dqh = _axial_flux4(P, H, i, f, d_z, axial)
        hf = H[i, f] if f == n_z - 1 else 0.5 * (H[i, f] + H[i, f + 1])
        h3 = hf * hf * hf / d_z
        last = f == n_z - 1
        if want_p:
            for m in range(4):
                c = coef[f, m]
                if c == 0.0:
                    continue
                col = cols[f, m]
                d = d_theta * h3 * 2.0 * c * P[i, col]
                data_p[slots[i, f, 3 + col - f]] += d
                if not last:
                    data_p[slots[i, f + 1, 3 + col - f - 1]] -= d
        if want_h:
            if last:
                data_h[slots[i, f, 3]] += d_theta * dqh
            else:
                d = d_theta * 0.5 * dqh
                data_h[slots[i, f, 3]] += d
                data_h[slots[i, f, 4]] += d
                data_h[slots[i, f + 1, 2]] -= d
                data_h[slots[i, f + 1, 3]] -= d


@njit(cache=True)
def _jacobian(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: Group,
    data: FloatArray,
    wrt_h: bool,
) -> None:
    n_theta, n_z = P.shape
    second = axial[0] == 2
    data[:] = 0.0
    for i in range(n_theta):
        ie = i + 1 if i < n_theta - 1 else 0
        for j in range(n_z):
            _, dqa, dqb, dqh = _theta_face(P[i, j], P[ie, j], H[i, j], H[ie, j], lam, d_theta)
            if wrt_h:
                dqa = dqh
                dqb = dqh
            _, ca, ea = _wce(i, j, n_theta, n_z, axial)
            wb, cb, _ = _wce(ie, j, n_theta, n_z, axial)
            data[ca] += d_z * dqa
            data[ea] += d_z * dqb
            data[wb] -= d_z * dqa
            data[cb] -= d_z * dqb
        if not second:
            _axial_jacobian4(P, H, i, d_theta, d_z, axial, data, data, not wrt_h, wrt_h)
            continue
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
    axial: Group,
    data_p: FloatArray,
    data_h: FloatArray,
) -> None:
    """:func:`jacobian_P` and :func:`jacobian_H` in one pass over the faces (same values)."""
    n_theta, n_z = P.shape
    second = axial[0] == 2
    data_p[:] = 0.0
    data_h[:] = 0.0
    for i in range(n_theta):
        ie = i + 1 if i < n_theta - 1 else 0
        for j in range(n_z):
            _, dqa, dqb, dqh = _theta_face(P[i, j], P[ie, j], H[i, j], H[ie, j], lam, d_theta)
            _, ca, ea = _wce(i, j, n_theta, n_z, axial)
            wb, cb, _ = _wce(ie, j, n_theta, n_z, axial)
            data_p[ca] += d_z * dqa
            data_p[ea] += d_z * dqb
            data_p[wb] -= d_z * dqa
            data_p[cb] -= d_z * dqb
            data_h[ca] += d_z * dqh
            data_h[ea] += d_z * dqh
            data_h[wb] -= d_z * dqh
            data_h[cb] -= d_z * dqh
        if not second:
            _axial_jacobian4(P, H, i, d_theta, d_z, axial, data_p, data_h, True, True)
            continue
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
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: Group,
    data: FloatArray,
) -> None:
    """Fill ``data`` of the CSR ``dR/dP`` (pattern :func:`stencil_pattern`).

    Exact derivatives, including those of ``B(Pe)`` through ``Pe(P_f, H_f)``.
    Twin: :func:`~foilbearing.reynolds.reference.jacobian_P_py`. Arguments as :func:`residual`;
    ``data`` has shape ``(nnz,)`` and is overwritten.
    """
    _jacobian(P, H, lam, d_theta, d_z, axial, data, False)


@njit(cache=True)
def jacobian_H(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: Group,
    data: FloatArray,
) -> None:
    """Fill ``data`` of the CSR ``dR/dH`` (pattern :func:`stencil_pattern`).

    Twin: :func:`~foilbearing.reynolds.reference.jacobian_H_py`. Arguments as :func:`jacobian_P`.
    """
    _jacobian(P, H, lam, d_theta, d_z, axial, data, True)


@njit(cache=True)
def coupled_jacobian(
    jp_data: DataArray,
    jh_data: DataArray,
    s: DataArray,
    n_z: int,
    axial: Group,
    out: DataArray,
) -> None:
    """Assemble ``dR/dP + dR/dH · dH/dP`` on the pattern of :func:`coupled_pattern`.

    The foil couples ``H[i, :]`` to the axial mean of ``P[i, :]``:
    ``dH[i, j]/dP[i, k] = s[i] w_k`` for every ``j, k``, with ``s[i] = c_i`` (the
    row's compliance) where ``p̄_i > 0`` and ``0`` elsewhere, and ``w_k`` the
    axial-mean weights (``1/n_z`` at second order, :attr:`AxialStencil.mean_w` at
    fourth). Row ``(i, j)`` of the product in column block ``i' ∈ {i−1, i, i+1}`` is
    ``s[i'] w_k · Σ_{j'} dR[i, j]/dH[i', j']``.
    Twin: :func:`~foilbearing.reynolds.reference.coupled_jacobian_py`.

    Parameters
    ----------
    jp_data, jh_data : ndarray, shape (nnz,)
        Data of ``dR/dP`` and ``dR/dH`` on :func:`stencil_pattern`.
    s : ndarray, shape (n_theta,)
    n_z : int
    axial : AxialStencil (as a plain tuple)
    out : ndarray, shape (3 n_z · n_theta n_z,)
    """
    n_theta = s.shape[0]
    width = 3 * n_z
    second = axial[0] == 2
    slots = axial[4]
    mean_w = axial[5]
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
            base = (i * n_z + j) * width
            if second:
                w, so, c, no, e = _row_slots(i, j, n_theta, n_z)
                hc = jh_data[c]
                if so >= 0:
                    hc += jh_data[so]
                if no >= 0:
                    hc += jh_data[no]
                vw = s[iw] / n_z * jh_data[w]
                vc = s[i] / n_z * hc
                ve = s[ie] / n_z * jh_data[e]
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
                continue
            w = slots[i, j, 0]
            e = slots[i, j, 6]
            hc = jh_data[slots[i, j, 3]]
            for d in (1, 2, 4, 5):
                sl = slots[i, j, d]
                if sl >= 0:
                    hc += jh_data[sl]
            vw = s[iw] * jh_data[w]
            vc = s[i] * hc
            ve = s[ie] * jh_data[e]
            for k in range(n_z):
                wk = mean_w[k]
                out[base + rw * n_z + k] = vw * wk
                out[base + rc * n_z + k] = vc * wk
                out[base + re * n_z + k] = ve * wk
            out[base + rw * n_z + j] += jp_data[w]
            out[base + re * n_z + j] += jp_data[e]
            for d in range(1, 6):
                sl = slots[i, j, d]
                if sl >= 0:
                    out[base + rc * n_z + j + d - 3] += jp_data[sl]


@njit(cache=True, inline="always")
def unit_coupled_row(data: DataArray, k: int, value: Any, n_theta: int, n_z: int) -> None:
    """Make row k of a matrix on :func:`coupled_pattern` ``value·e_k`` (in place).

    Row ``k = i n_z + j`` holds 3 n_z entries, θ-blocks in sorted column order:
    its own block is first for i = 0, last for i = n_theta − 1, in the middle
    otherwise. Twin: :func:`foilbearing.reynolds.assembly.set_unit_rows`.
    """
    width = 3 * n_z
    i = k // n_z
    own = 0 if i == 0 else (2 if i == n_theta - 1 else 1)
    base = k * width
    for c in range(width):
        data[base + c] = 0.0
    data[base + own * n_z + k - i * n_z] = value


@njit(cache=True)
def lift_off_rows(
    P: FloatArray,
    res: FloatArray,
    jp_data: FloatArray,
    jh_data: FloatArray,
    coupled_data: FloatArray,
    diag_slots: IntArray,
    indptr: IntArray,
    coupled: bool,
    held: NDArray[np.bool_],
    delta: float = 0.0,
    d_ref: float = 1.0,
) -> int:
    """Top-foil lift-off rows of the steady system, in place; the number of held cells.

    The complementarity ``min(d (P − 1), −R) = 0`` of each cell (d = |∂R_k/∂P_k|;
    :mod:`foilbearing.reynolds.steady`): a cell with ``d (P − 1) < −R`` is held
    at ambient, its residual becomes ``−d (P − 1)`` and its matrix row ``−d e_k``
    (on the coupled pattern if ``coupled``, else on the stencil pattern), and
    its row of ∂R/∂H is zero. Twin: :func:`~foilbearing.reynolds.reference.lift_off_rows_py`.

    With ``delta`` > 0, the smoothed law of width ``delta`` = δ√Λ
    (:meth:`~foilbearing.reynolds.grid.FilmGrid.lift_off_width`; docs/lift-off.md, "The
    smoothed edge"): every cell's equation is ``G = −(d_ref/2) φ(x, y) = 0``, ``φ(x, y) =
    x + y − √((x − y)² + 4 delta²)``, ``x = P − 1``, ``y = −R/d_ref`` (so ``x y =
    delta²``); its rows are the Reynolds
    rows times ``α = (1 + (x − y)/√(…))/2`` with ``−(1 − α) d_ref`` added on the diagonal,
    and ``held`` marks the cells nearer the ambient branch (α < 1/2).

    Parameters
    ----------
    P, res : ndarray, shape (n_theta, n_z)
        Pressure and Reynolds residual R (net inflow, cell-integrated); res is
        overwritten on held cells.
    jp_data, jh_data : ndarray, shape (nnz,)
        ∂R/∂P and ∂R/∂H on :func:`stencil_pattern` (jp read for d, and
        rewritten on held rows when not ``coupled``; jh rows of held cells zeroed).
    coupled_data : ndarray, shape (3 n_z · n,)
        The matrix on :func:`coupled_pattern` (rewritten on held rows when ``coupled``).
    diag_slots : ndarray, shape (n,)
        Position of each cell's diagonal entry in the stencil data.
    indptr : ndarray, shape (n + 1,)
        Stencil row pointers.
    coupled : bool
        Which matrix holds the system.
    held : ndarray of bool, shape (n,)
        Filled with the held cells.
    delta : float
        Width δ√Λ of the smoothed complementarity, pressure units (0: the sharp law).
    d_ref : float
        Scale of the residual in pressure units, ``2 ΔZ/Δθ`` (used with δ > 0 only).
    """
    n_theta, n_z = P.shape
    n = n_theta * n_z
    count = 0
    if delta > 0.0:
        width = 3 * n_z
        for k in range(n):
            i = k // n_z
            j = k - i * n_z
            half_phi, alpha = smoothed_edge_kernel(P[i, j] - 1.0, -res[i, j] / d_ref, delta * delta)
            res[i, j] = -d_ref * half_phi
            held[k] = alpha < 0.5
            if held[k]:
                count += 1
            for e in range(indptr[k], indptr[k + 1]):
                jh_data[e] *= alpha
            if coupled:
                own = 0 if i == 0 else (2 if i == n_theta - 1 else 1)
                base = k * width
                for c in range(width):
                    coupled_data[base + c] *= alpha
                coupled_data[base + own * n_z + j] -= (1.0 - alpha) * d_ref
            else:
                for e in range(indptr[k], indptr[k + 1]):
                    jp_data[e] *= alpha
                jp_data[diag_slots[k]] -= (1.0 - alpha) * d_ref
        return count
    for k in range(n):
        i = k // n_z
        j = k - i * n_z
        d = abs(jp_data[diag_slots[k]])
        if d == 0.0:
            d = 1.0
        gauge = P[i, j] - 1.0
        held[k] = d * gauge < -res[i, j]
        if not held[k]:
            continue
        count += 1
        res[i, j] = -d * gauge
        for e in range(indptr[k], indptr[k + 1]):
            jh_data[e] = 0.0
        if coupled:
            unit_coupled_row(coupled_data, k, -d, n_theta, n_z)
        else:
            for e in range(indptr[k], indptr[k + 1]):
                jp_data[e] = 0.0
            jp_data[diag_slots[k]] = -d
    return count
