"""Block cyclic tridiagonal LU of the foil-coupled matrix (compiled; NumPy twins in
:mod:`foilbearing.testing.block_twins`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
DataArray = NDArray[Any]  # float64, or complex128 (the perturbation at a frequency)


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
# numba's OpenMP layer that halves the factorisation in isolation, 0.22 against
# 0.47 ms on 96 × 12, but it gained nothing measurable inside the orbit
# (benchmarks/bench_two_threads.py; docs/development/orbit-performance.md, "The second
# core"). GNU OpenMP is also not fork-safe for the study's process pool, and
# the study's runs already fill both cores, so it is not done.)
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


def block_cyclic_alloc(n_theta: int, n_z: int, dtype: type = np.float64) -> DataArray:
    """Factor storage for :func:`block_cyclic_factor`, shape (n_theta, n_z, 5 n_z).

    ``n_theta >= 3`` (the three θ-blocks of a row are distinct), ``n_z >= 1``;
    ``dtype`` that of the matrix data (float64 or complex128).
    """
    if n_theta < 3 or n_z < 1:
        raise ValueError(f"block cyclic LU needs n_theta >= 3 and n_z >= 1, got {n_theta}, {n_z}")
    return np.empty((n_theta, n_z, 5 * n_z), dtype=dtype)  # all written by the factorisation


@njit(cache=True)
def _chain(k: int, n_theta: int) -> tuple[int, int, int, int]:
    """Chain k (0: A, 1: B) as ``(first, last, left separator, right separator)``."""
    p = (n_theta - 1) // 2
    if k == 0:
        return 0, p - 1, n_theta - 1, p
    return p + 1, n_theta - 2, p, n_theta - 1


def block_cyclic_chains(n_theta: int) -> tuple[int, tuple[tuple[int, int, int, int], ...]]:
    """Separator p and the two chains ``(first, last, left separator, right separator)``."""
    return (n_theta - 1) // 2, (_chain(0, n_theta), _chain(1, n_theta))


@njit(cache=True, fastmath={"contract"})
def _gauss_jordan(aug: DataArray, m: int, width: int, row: DataArray) -> int:
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
    c: DataArray,
    c0: int,
    a: DataArray,
    b: DataArray,
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
    a: DataArray, c0: int, m: int, w: int, x: DataArray, y: DataArray, alpha: float
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
def _norm1(a: DataArray, c0: int, m: int) -> float:
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
    d4: DataArray,
    fac: DataArray,
    first: int,
    last: int,
    left: int,
    right: int,
    sc: DataArray,
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
    dt = fac.dtype
    aug = np.empty((m, 4 * m), dtype=dt)  # [D_i | U_i | G_i | I] → [I | V_i | W_i | D_i⁻¹]
    row = np.empty(4 * m, dtype=dt)
    lo = np.empty((m, m), dtype=dt)
    vw = np.empty((m, 2 * m), dtype=dt)  # [V_i | W_i]
    t = np.zeros((m, 2 * m), dtype=dt)  # [R_i | S_ll]
    tmp = np.empty((m, 2 * m), dtype=dt)
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
    d4: DataArray,
    fac: DataArray,
    sc: DataArray,
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
    aug = np.zeros((m2, 2 * m2), dtype=fac.dtype)  # [S | I] → [I | S⁻¹]
    row = np.empty(2 * m2, dtype=fac.dtype)
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
    snorm = _norm1(aug, 0, m2)
    k = _gauss_jordan(aug, m2, 2 * m2, row)
    if k >= 0:
        return BC_ZERO_PIVOT, s_idx[0] if k < m else s_idx[1], 0.0, dmax / bmax
    rc_s = 1.0 / (snorm * _norm1(aug, m2, m2))
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
        first, last, _left, right = _chain(k, n_b)
        if last >= first:
            rl = _rank(right, last, n_b)
            for r in range(m):
                for c in range(m):
                    fac[right, r, 3 * m + c] = d4[right, r, rl, c]  # L_r of the chain
    return BC_OK, worst, rcond, dmax / bmax


@njit(cache=True)
def _check_data(data: DataArray) -> float:
    """Largest |entry| of the matrix data, or NaN if it holds inf or NaN (branch-free loop)."""
    bmax = 0.0
    nonfinite = 0.0  # |v| − |v| is 0 for finite v, NaN for inf or NaN (real or complex)
    for v in data:
        av = abs(v)
        nonfinite += av - av
        bmax = av if av > bmax else bmax
    return bmax if nonfinite == 0.0 else np.nan


@njit(cache=True, nogil=True)
def block_cyclic_factor(
    data: DataArray, n_theta: int, n_z: int, fac: DataArray
) -> tuple[int, int, float, float]:
    """Block LU of the periodic block-tridiagonal matrix on :func:`coupled_pattern`.

    Two chains eliminated in turn and their separators (see the comment above
    :data:`BC_OK`); partial pivoting inside each ``n_z × n_z`` pivot block,
    none between blocks, so it is meant for block-diagonally dominant
    matrices such as the BDF Newton matrix ``c0·diag(H) + …``. Cost
    ``O(n_theta n_z³)``. Replaces ``scipy.sparse.linalg.splu`` of the CSR
    matrix; twin :func:`~foilbearing.testing.twins.block_cyclic_factor_py`.
    Real or complex: ``data`` and ``fac`` of one dtype (float64 or complex128;
    the pivots by modulus).

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
    sc = np.empty((2, 2 * n_z, 2 * n_z), dtype=fac.dtype)
    stats = np.empty((2, 3))
    status = np.empty(2, dtype=np.int64)
    for k in range(2):  # independent: the place for two threads (not worth it on 2 cores)
        first, last, left, right = _chain(k, n_theta)
        status[k] = _chain_factor(d4, fac, first, last, left, right, sc[k], stats[k])
    return _separator_factor(d4, fac, sc, stats, status, bmax)


@njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
def block_cyclic_solve(fac: DataArray, rhs: DataArray, out: DataArray) -> None:
    """Solve ``B x = rhs`` with the factors of :func:`block_cyclic_factor`.

    Cost ``O(n_theta n_z²)`` per right-hand side; twin
    :func:`~foilbearing.testing.twins.block_cyclic_solve_py`. Dot products may be reassociated
    (vectorised), which changes results only at rounding level.

    Parameters
    ----------
    fac : ndarray, shape (n_theta, n_z, 5 n_z)
        Output of a successful :func:`block_cyclic_factor`.
    rhs : ndarray, shape (n, k)
        Right-hand sides, ``n = n_theta n_z``, row ``i*n_z + j``.
    out : ndarray, shape (n, k)
        Filled with the solutions (may be ``rhs`` itself); complex if the
        factors or ``rhs`` are.
    """
    n_b = fac.shape[0]
    m = fac.shape[1]
    ncol = rhs.shape[1]
    last_b = n_b - 1
    p = (n_b - 1) // 2
    # (column, block, n_z): block vectors contiguous for the products
    dt = out.dtype  # that of the factors or of rhs, whichever is complex
    z = np.empty((ncol, n_b, m), dtype=dt)
    x = np.empty(2 * m, dtype=dt)
    acc = np.empty((2, 2, m), dtype=dt)  # per chain: right-hand side updates of [left, right]
    for i in range(n_b):
        for j in range(m):
            for q in range(ncol):
                z[q, i, j] = rhs[i * m + j, q]
    for q in range(ncol):
        zq = z[q]
        acc[:, :, :] = 0.0
        for k in range(2):
            first, last, _left, right = _chain(k, n_b)
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
            first, last, left, _right = _chain(k, n_b)
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
