"""NumPy twins of the block cyclic factorisation and solve of the pressure block
(:mod:`foilbearing.reynolds._kernels.blockcyclic`), with LAPACK inverses of the blocks;
:mod:`foilbearing.testing.twins` hands them on with the other twins."""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg as sla
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern

__all__ = ["block_cyclic_factor_py", "block_cyclic_solve_py"]

FloatArray = NDArray[np.float64]


def block_cyclic_factor_py(
    data: FloatArray, n_theta: int, n_z: int, fac: FloatArray
) -> tuple[int, int, float, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.block_cyclic_factor` (LAPACK inverses)."""
    n_b, m = n_theta, n_z
    if not np.all(np.isfinite(data)):
        return kern.BC_NOT_FINITE, -1, 0.0, np.inf
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
    p, chains = kern.block_cyclic_chains(n_b)
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
                return kern.BC_ZERO_PIVOT, i, 0.0, dmax / bmax
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
        return kern.BC_ZERO_PIVOT, s_idx[0] if col < m else s_idx[1], 0.0, dmax / bmax
    rc_s = rcond_of(s, inv)
    if not rc_s >= rcond:
        rcond, worst = rc_s, s_idx[1]
    fac[p, :, : 2 * m] = inv[:m]
    fac[n_b - 1, :, : 2 * m] = inv[m:]
    for first, last, _left, right in chains:
        if last >= first:
            fac[right, :, 3 * m : 4 * m] = blk(right, last)
    return kern.BC_OK, worst, rcond, dmax / bmax


def block_cyclic_solve_py(fac: FloatArray, rhs: FloatArray, out: FloatArray) -> None:
    """Twin of :func:`~foilbearing.reynolds._kernels.block_cyclic_solve`."""
    n_b, m = fac.shape[0], fac.shape[1]
    dinv, vw, lo, rr = (
        fac[:, :, :m],
        fac[:, :, m : 3 * m],
        fac[:, :, 3 * m : 4 * m],
        fac[:, :, 4 * m :],
    )
    p, chains = kern.block_cyclic_chains(n_b)
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
