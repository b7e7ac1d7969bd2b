"""NumPy twins of the compiled kernels, used by the tests to check them.

Each mirrors one kernel of :mod:`foilbearing.reynolds._kernels` (named in its docstring),
same arguments and results (dimensionless as there; time in s, c0 in 1/s), in NumPy/SciPy
array operations. The transient twins take the ``TransientSystem`` or ``TransientFactor``
first; they are also the path of its SuperLU fallback (where the block LU cannot pivot)."""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds._kernels.flux import _SERIES_X, C, E, N, S, W
from foilbearing.reynolds._kernels.groups import BdfHistory
from foilbearing.reynolds._kernels.newton import FREE_SLACK
from foilbearing.reynolds.assembly import set_unit_rows

if TYPE_CHECKING:
    from foilbearing.reynolds.transient import Inputs, TransientSystem
    from foilbearing.reynolds.transient_factor import TransientFactor

__all__ = [
    "adopt_branches_py",
    "bdf_setup_py",
    "bernoulli_deriv_py",
    "bernoulli_py",
    "block_cyclic_factor_py",
    "block_cyclic_solve_py",
    "border_py",
    "coupled_jacobian_py",
    "jacobian_H_py",
    "jacobian_P_py",
    "jacobian_blocks_py",
    "lift_coordinate_py",
    "lift_off_rows_py",
    "newton_residual_py",
    "newton_solve_py",
    "newton_step_py",
    "newton_update_py",
    "predict_branches_py",
    "residual_py",
    "smoothed_lift_off_py",
    "solve_py",
    "switch_branches_py",
]

FloatArray = NDArray[np.float64]


def bernoulli_py(x: FloatArray | float) -> FloatArray:
    """Twin of :func:`~foilbearing.reynolds._kernels.bernoulli` (vectorised)."""
    x = np.asarray(x, dtype=np.float64)
    a = np.abs(x)
    a2 = a * a
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        big = a / np.expm1(np.where(a < _SERIES_X, 1.0, a))
    series = 1.0 - 0.5 * a + a2 / 12.0 - a2 * a2 / 720.0
    b_pos = np.where(a < _SERIES_X, series, big)
    return np.where(x >= 0.0, b_pos, b_pos - x)


def bernoulli_deriv_py(x: FloatArray | float) -> FloatArray:
    """Twin of :func:`~foilbearing.reynolds._kernels.bernoulli_deriv` (vectorised)."""
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


def _axial4_py(
    P: FloatArray, H: FloatArray, d_z: float, axial: tuple[Any, ...]
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Fourth-order axial face fluxes of every θ-row: ``(Σ c ψ + c₀, H_f, q)``, each (n_theta, n_z)."""
    _order, cols, coef, const = axial[:4]
    psi = P * P
    acc = np.einsum("tfm,fm->tf", psi[:, cols], coef) + const
    hf = np.concatenate([0.5 * (H[:, :-1] + H[:, 1:]), H[:, -1:]], axis=1)
    return acc, hf, hf**3 * acc / d_z


def residual_py(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: tuple[Any, ...],
    out: FloatArray,
) -> None:
    """Twin of :func:`~foilbearing.reynolds._kernels.residual`."""
    th, zf, end = _faces_py(P, H, lam, d_theta, d_z)
    qt = th[0]
    if axial[0] == 2:
        qz = np.concatenate([np.zeros((P.shape[0], 1)), zf[0], end[0][:, None]], axis=1)
    else:
        qz = np.concatenate([np.zeros((P.shape[0], 1)), _axial4_py(P, H, d_z, axial)[2]], axis=1)
    out[:, :] = d_z * (qt - np.roll(qt, 1, axis=0)) + d_theta * (qz[:, 1:] - qz[:, :-1])


def _jacobian4_py(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: tuple[Any, ...],
    data: FloatArray,
    wrt_h: bool,
) -> None:
    """The fourth-order Jacobian, entry by entry in COO form, read on the pattern."""
    n_theta, n_z = P.shape
    n = n_theta * n_z
    th, _zf, _end = _faces_py(P, H, lam, d_theta, d_z)
    t_a, t_b = (th[3], th[3]) if wrt_h else (th[1], th[2])
    cell = np.arange(n).reshape(n_theta, n_z)
    east = np.roll(cell, -1, axis=0)
    rows: list[NDArray[np.int64]] = []
    cols: list[NDArray[np.int64]] = []
    vals: list[FloatArray] = []

    def add(r: NDArray[np.int64], c: NDArray[np.int64], v: FloatArray) -> None:
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(np.broadcast_to(v, r.shape).ravel())

    # θ-face i+1/2: +ΔZ q on cell (i, j), −ΔZ q on cell (i+1, j)
    add(cell, cell, d_z * t_a)
    add(cell, east, d_z * t_b)
    add(east, cell, -d_z * t_a)
    add(east, east, -d_z * t_b)
    acc, hf, _q = _axial4_py(P, H, d_z, axial)
    f_cols, f_coef = axial[1], axial[2]
    for f in range(n_z):
        row_in = cell[:, f]
        row_out = cell[:, f + 1] if f < n_z - 1 else None
        if wrt_h:
            if row_out is None:
                add(row_in, row_in, d_theta * 3.0 * hf[:, f] ** 2 * acc[:, f] / d_z)
                continue
            d = d_theta * 1.5 * hf[:, f] ** 2 * acc[:, f] / d_z
            for c in (cell[:, f], cell[:, f + 1]):
                add(row_in, c, d)
                add(row_out, c, -d)
            continue
        for m in range(4):
            if f_coef[f, m] == 0.0:
                continue
            col = f_cols[f, m]
            d = d_theta * hf[:, f] ** 3 / d_z * 2.0 * f_coef[f, m] * P[:, col]
            add(row_in, cell[:, col], d)
            if row_out is not None:
                add(row_out, cell[:, col], -d)
    full = sp.coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
    ).tocsr()
    indptr, indices, _ = kern.stencil_pattern(n_theta, n_z, 4)
    entry_rows = np.repeat(np.arange(n), np.diff(indptr))
    data[:] = np.asarray(full[entry_rows, indices]).ravel()


def _jacobian_py(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: tuple[Any, ...],
    data: FloatArray,
    wrt_h: bool,
) -> None:
    if axial[0] != 2:
        _jacobian4_py(P, H, lam, d_theta, d_z, axial, data, wrt_h)
        return
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
    _, _, slots = kern.stencil_pattern(n_theta, n_z)
    mask = slots >= 0
    data[:] = 0.0
    data[slots[mask]] = vals[mask]


def jacobian_P_py(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: tuple[Any, ...],
    data: FloatArray,
) -> None:
    """Twin of :func:`~foilbearing.reynolds._kernels.jacobian_P`."""
    _jacobian_py(P, H, lam, d_theta, d_z, axial, data, False)


def jacobian_H_py(
    P: FloatArray,
    H: FloatArray,
    lam: float,
    d_theta: float,
    d_z: float,
    axial: tuple[Any, ...],
    data: FloatArray,
) -> None:
    """Twin of :func:`~foilbearing.reynolds._kernels.jacobian_H`."""
    _jacobian_py(P, H, lam, d_theta, d_z, axial, data, True)


def coupled_jacobian_py(
    jp_data: FloatArray,
    jh_data: FloatArray,
    s: FloatArray,
    n_z: int,
    axial: tuple[Any, ...],
    out: FloatArray,
) -> None:
    """Twin of :func:`~foilbearing.reynolds._kernels.coupled_jacobian` (scipy.sparse products)."""
    n_theta = s.shape[0]
    n = n_theta * n_z
    indptr, indices, _ = kern.stencil_pattern(n_theta, n_z, axial[0])
    jp = sp.csr_matrix((jp_data, indices, indptr), shape=(n, n))
    jh = sp.csr_matrix((jh_data, indices, indptr), shape=(n, n))
    dhdp = sp.kron(sp.diags(s), np.ones((n_z, 1)) * axial[5][None, :], format="csr")
    full = (jp + jh @ dhdp).toarray()
    c_indptr, c_indices = kern.coupled_pattern(n_theta, n_z)
    rows = np.repeat(np.arange(n), np.diff(c_indptr))
    out[:] = full[rows, c_indices]


def smoothed_lift_off_py(
    x: FloatArray, y: FloatArray, delta: float | FloatArray, d_ref: float | FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The smoothed lift-off law of each cell: its weight α and its residual G (δ and
    d_ref one for all cells, or one a cell).

    ``x = P − 1`` and ``y`` the net outflow in pressure units (``−R/d_ref``); ``G =
    −(d_ref/2)(x + y − √((x − y)² + 4δ²))``, zero where x > 0, y > 0 and ``x y = δ²``;
    ``α = −(∂G/∂y)/d_ref`` is the weight of the Reynolds row in the cell's row
    (docs/lift-off.md, "The smoothed edge").
    """
    root = np.sqrt((x - y) ** 2 + 4.0 * delta**2)
    return 0.5 * (1.0 + (x - y) / root), -0.5 * d_ref * (x + y - root)


def lift_off_rows_py(
    P: FloatArray,
    res: FloatArray,
    jp_data: FloatArray,
    jh_data: FloatArray,
    coupled_data: FloatArray,
    diag_slots: NDArray[np.int64],
    indptr: NDArray[np.int64],
    coupled: bool,
    held: NDArray[np.bool_],
    delta: float = 0.0,
    d_ref: float = 1.0,
) -> int:
    """Twin of :func:`~foilbearing.reynolds._kernels.lift_off_rows`."""
    n_theta, n_z = P.shape
    if delta > 0.0:
        alpha, g = smoothed_lift_off_py(P.ravel() - 1.0, -res.ravel() / d_ref, delta, d_ref)
        res.ravel()[:] = g
        held[:] = alpha < 0.5
        entry_rows = np.repeat(np.arange(n_theta * n_z), np.diff(indptr))
        jh_data *= alpha[entry_rows]
        if coupled:
            block = coupled_data.reshape(n_theta * n_z, 3 * n_z)
            block *= alpha[:, None]
            k = np.arange(n_theta * n_z)
            i = k // n_z
            own = np.where(i == 0, 0, np.where(i == n_theta - 1, 2, 1))
            block[k, own * n_z + k % n_z] -= (1.0 - alpha) * d_ref
        else:
            jp_data *= alpha[entry_rows]
            jp_data[diag_slots] -= (1.0 - alpha) * d_ref
        return int(np.count_nonzero(held))
    d = np.abs(jp_data[diag_slots])
    d = np.where(d > 0.0, d, 1.0)
    gauge = P.ravel() - 1.0
    held[:] = d * gauge < -res.ravel()
    rows = np.flatnonzero(held)
    res.ravel()[rows] = -d[rows] * gauge[rows]
    entry_rows = np.repeat(np.arange(n_theta * n_z), np.diff(indptr))
    mask = held[entry_rows]
    jh_data[mask] = 0.0
    if coupled:
        block = coupled_data.reshape(n_theta * n_z, 3 * n_z)
        block[rows] = 0.0
        i = rows // n_z
        own = np.where(i == 0, 0, np.where(i == n_theta - 1, 2, 1))
        block[rows, own * n_z + rows % n_z] = -d[rows]
    else:
        jp_data[mask] = 0.0
        jp_data[diag_slots[rows]] = -d[rows]
    return int(rows.size)


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


def newton_residual_py(
    system: TransientSystem,
    y: FloatArray,
    inputs: Inputs,
    c0: float,
    hist: FloatArray,
    lift_state: FloatArray | None = None,
    slack: FloatArray | None = None,
    *,
    smooth: bool = True,
) -> tuple[FloatArray, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_residual` (of
    ``TransientSystem.newton_residual``): G = c0·Q(y) + hist − f(y) (1/s) and the
    minimum film h/C; no ``out`` buffer, fills ``slack`` if given. ``smooth=False``:
    the BDF equations before the smoothed lift-off law (if the system has one)."""
    P, U, eps, v = system.split(y)
    H, q = system.film(y, inputs.preload)
    g = system.grid
    kern.residual(
        np.ascontiguousarray(P), H, inputs.lam, g.d_theta, g.d_z, system._axial, system._res
    )
    out = np.empty(system.size)
    n, nt = system.n, system.nt
    out[:n] = c0 * (P * H).ravel() - system._res.ravel() / (system.area * system.sigma)
    f_u = inputs.omega / system.gamma * (system.c_bump * q - U) if system.dynamic_bump else 0.0
    out[n : n + nt] = c0 * U - f_u
    out[n + nt : n + nt + 2] = c0 * eps - v
    out[-2:] = c0 * v - system.force_scale * (system.w @ (P.ravel() - 1.0)) - inputs.force
    out += hist
    d = system.lift_state(y, inputs, c0, hist) if lift_state is None else lift_state
    if system.lift_delta > 0.0:
        if smooth:
            # the orbit's sign: (s_k/2)(x + G/s_k − √(…)), G ≥ 0 an outflow; s_k a
            # factor's own scale where lift_state holds one (TransientSystem.smoothed_scales)
            s = system.smoothed_scales(lift_state)
            x = P.ravel() - 1.0
            width = system.grid.lift_off_width(inputs.lam) * np.sqrt(system.smooth_scale / s)
            out[:n] = -smoothed_lift_off_py(x, out[:n] / s, width, s)[1]
        if slack is not None:
            slack[:] = 0.0
        return out, float(H.min())
    if slack is not None:
        safe = np.where(d > 0.0, d, 1.0)
        slack[:] = np.where(d > 0.0, -out[:n] / safe, np.where(d < 0.0, 1.0 - P.ravel(), 0.0))
    out[:n] = np.where(d > 0.0, d * (P.ravel() - 1.0), out[:n])
    return out, float(H.min())


def jacobian_blocks_py(
    system: TransientSystem, y: FloatArray, inputs: Inputs, c0: float, hist: FloatArray
) -> tuple[Any, ...]:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_jacobian` (its blocks).

    Returns
    -------
    H : ndarray, shape (n_theta, n_z)
        Film h/C.
    jp, jh : ndarray, shape (nnz,)
        Scaled Reynolds Jacobians ``c0·diag(H) − ∂R/∂P/(Aσ)`` and
        ``c0·diag(P) − ∂R/∂H/(Aσ)`` (stencil data).
    active : ndarray, shape (n_theta,)
        1.0 on engaged θ-rows, else 0.0.
    jc : ndarray, shape (3 n_z · n,)
        Data of the pressure block B on the coupled pattern.
    a_pe : ndarray, shape (n, 2)
        ``jh ∂H/∂ε``.
    lift_state : ndarray, shape (n,)
        Lift-off branches (``d`` held, ``−d`` free, zeros without lift-off).
    clamped : ndarray of bool, shape (n,)
        Cells held at ambient (rows ``d e_k`` in B, zero rows of jh and a_pe).
    a_pl : ndarray, shape (n, n_lobe)
        ``jh ∂H/∂D_n``: the unit lobes that follow their stacks as film columns.
    lobe_gain : ndarray, shape (n_lobe,)
        ``∂D_n/∂q(θ_n)``.
    """
    P, _U, _eps, _v = system.split(y)
    H, _q = system.film(y, inputs.preload)
    g = system.grid
    Pc = np.ascontiguousarray(P)
    ws = system.ws
    jp_raw = np.empty(ws.jp.size)
    jh_raw = np.empty(ws.jh.size)
    kern.jacobian_P(Pc, H, inputs.lam, g.d_theta, g.d_z, system._axial, jp_raw)
    kern.jacobian_H(Pc, H, inputs.lam, g.d_theta, g.d_z, system._axial, jh_raw)
    scale = 1.0 / (system.area * system.sigma)
    # Row scaling of the Reynolds block: c0·∂(PH) − ∂R/(Aσ).
    jp = -scale * jp_raw
    jh = -scale * jh_raw
    jp[system.diag_slots] += c0 * H.ravel()
    jh[system.diag_slots] += c0 * P.ravel()
    rate = system.rate(inputs)
    active = (g.gauge_mean(P) > 0.0).astype(float)
    c_eff = system.c_act + rate * system.c_bump / (c0 + rate)
    n = system.n
    d = system.lift_state(y, inputs, c0, hist)
    if system.lift_delta > 0.0:
        # the smoothed law: rows times α, (1 − α) s_k on the diagonal, s_k each row's own
        # diagonal, kept as −s_k in the branches (TransientSystem.smoothed_scales)
        s_k = np.abs(jp[system.diag_slots])
        d = -np.where(s_k > 0.0, s_k, system.smooth_scale)
        alpha = system.smoothed_weights(y, inputs, c0, hist, d)[:n]
        jp *= alpha[ws.entry_rows]
        jh *= alpha[ws.entry_rows]
        jp[system.diag_slots] += (1.0 - alpha) * -d
    clamped = d > 0.0
    jh[clamped[ws.entry_rows]] = 0.0
    jc = np.empty(system._jc.size)
    coupled_jacobian_py(jp, jh, c_eff * active, g.n_z, system._axial, jc)
    rows = np.flatnonzero(clamped)
    set_unit_rows(jc, rows, d[rows], g.n_theta, g.n_z)
    jh_mat = sp.csr_matrix((jh, ws.indices, ws.indptr), shape=(n, n))
    a_pe = jh_mat @ system.dh_de
    a_pl = jh_mat @ np.repeat(system.lobes.T, g.n_z, axis=0)
    gain = system.lobe_gain(P)
    return H, jp, jh, active, jc, np.asarray(a_pe), d, clamped, np.asarray(a_pl), gain


def lobe_correct_py(x: FloatArray, lobe: tuple[Any, ...], system: TransientSystem) -> FloatArray:
    """Twin of :func:`~foilbearing.reynolds._kernels.lobe_correct`: ``B'⁻¹ b`` from
    ``x = B⁻¹ b`` (a new array), ``lobe = (B⁻¹ a_pl, (I + L B⁻¹ a_pl)⁻¹, gain, lobe_rows, axial)``."""
    border, inv, gain = lobe[:3]
    if gain.size == 0:
        return x
    L = gain[:, None] * system.lobe_mean
    return x - border @ (inv @ (L @ x))


def border_py(
    system: TransientSystem,
    lu: Any,
    a_pe: FloatArray,
    c0: float,
    lobe: tuple[Any, ...] | None = None,
) -> tuple[FloatArray, FloatArray]:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_border`.

    ``lu`` is any LU of B with a SuperLU-like ``solve``, ``lobe`` the lobes' border
    (:meth:`TransientSystem.lobe_border`; None: no lobes). Returns
    ``y_border = B'⁻¹ a_pe / c0²`` (n, 2) and ``(I + s_vp y_border)⁻¹`` (2, 2).
    """
    y_border = np.asarray(lu.solve(np.ascontiguousarray(a_pe / c0**2)), dtype=np.float64)
    if lobe is not None:
        y_border = lobe_correct_py(y_border, lobe, system)
    small = np.eye(2) + system.s_vp @ y_border  # Woodbury: I + V^T B^-1 U, V^T = S_vp
    return y_border, np.linalg.inv(small).astype(np.float64)


def solve_py(factor: TransientFactor, g: FloatArray) -> FloatArray:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_solve` (of
    ``TransientFactor.solve``): Δy with J Δy = g (any LU with a SuperLU-like ``solve``).

    ``g`` may also be a block of right-hand sides, shape (size, m): one solve of the
    pressure block for all of them (:meth:`TransientFactor.solve_block`)."""
    s = factor.sys
    n, nt, nz = s.n, s.nt, s.grid.n_z
    arrays = factor.arrays
    c0, rate = arrays.c0, arrays.rate
    g2 = g.reshape(g.shape[0], -1)
    g_p, g_u, g_e, g_v = g2[:n], g2[n : n + nt], g2[n + nt : n + nt + 2], g2[-2:]
    # Eliminate U: (c0 + rate) dU − rate c_b q'(dP) = g_u
    rhs = g_p - factor.jh @ np.repeat(g_u / (c0 + rate), nz, axis=0)
    # Eliminate the journal: c0 de − dv = g_e, c0 dv − S_vp dP = g_v
    rhs -= arrays.a_pe @ ((g_v + c0 * g_e) / c0**2)
    z = factor.lu.solve(rhs)  # type: ignore[attr-defined]
    lobe = (arrays.lobe_border, arrays.lobe_inv, arrays.lobe_gain)
    z = lobe_correct_py(z, lobe, s)
    d_p = z - arrays.y_border @ (arrays.small_inv @ (arrays.s_vp @ z))
    d_e = (arrays.s_vp @ d_p + g_v + c0 * g_e) / c0**2
    d_v = c0 * d_e - g_e
    dq = arrays.active[:, None] * s.grid.axial_mean(d_p.reshape(nt, nz, -1))
    d_u = (g_u + rate * s.c_bump[:, None] * dq) / (c0 + rate)
    return np.concatenate([d_p, d_u, d_e, d_v]).reshape(g.shape)


def newton_solve_py(
    factor: TransientFactor,
    y: FloatArray,
    inputs: Inputs,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    work: tuple[FloatArray, FloatArray, FloatArray],
    controls: tuple[float, float, int],
    fresh: bool,
    first_change: float,
) -> tuple[int, int, float, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_newton_solve` (of
    ``TransientFactor.newton_solve``): :func:`newton_step_py` in a loop."""
    g, dy, q_out = work
    newton_tol, newton_fraction, max_newton = controls
    prev = math.inf
    k = since = switches = 0
    while True:
        k += 1
        since += 1
        h_min, err, p_min = newton_step_py(factor, y, inputs, c0, hist, weights, g, dy)
        if h_min <= 0.0:
            return kern.NEWTON_FILM_CLOSED, k, first_change, math.nan
        if not math.isfinite(err) or p_min <= 0.0:
            return kern.NEWTON_NOT_FINITE, k, first_change, math.nan
        if first_change == math.inf:
            first_change = err
        tol = max(newton_tol, newton_fraction * first_change)
        conv = err / prev if since > 1 else math.nan
        if err <= tol or (conv < 1.0 and conv / (1.0 - conv) * err <= tol):
            flipped = switch_branches_py(factor.lift_state, factor.sys._slack, weights)
            if flipped == 0:
                _q, h_new = factor.sys.storage_min_film(y, inputs.preload, q_out)
                if h_new > 0.0:
                    return kern.NEWTON_CONVERGED, k, first_change, h_new
            elif switches < kern.MAX_SWITCHES and flipped <= kern.MAX_MOVED_KEPT:
                switches += 1
                since = 0
                prev = math.inf
                continue
            else:
                return kern.NEWTON_REFRESH, k, first_change, math.nan
        if fresh:
            if factor.sys.lift_delta > 0.0 and since > 1 and conv >= 1.0:
                y += dy  # the smoothed law's kink: back to the better iterate, refresh there
                return kern.NEWTON_REFRESH, k, first_change, math.nan
            if since >= max_newton or conv >= 1.0:
                if switches > 0:
                    return kern.NEWTON_REFRESH, k, first_change, math.nan
                return kern.NEWTON_TOO_SLOW, k, first_change, math.nan
            if conv > 0.5:
                return kern.NEWTON_REFRESH, k, first_change, math.nan
        elif since >= max_newton or conv >= 1.0:
            return kern.NEWTON_DIVERGED, k, first_change, math.nan
        elif conv ** (max_newton - since) / (1.0 - conv) * err > tol:
            return kern.NEWTON_REFRESH, k, first_change, math.nan
        prev = err


def newton_step_py(
    factor: TransientFactor,
    y: FloatArray,
    inputs: Inputs,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    g: FloatArray,
    dy: FloatArray,
) -> tuple[float, float, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_newton_step` (of
    ``TransientFactor.newton_step``): residual, solve and update in sequence."""
    s = factor.sys
    g[:], h_min = newton_residual_py(s, y, inputs, c0, hist, factor.lift_state, s._slack)
    if h_min <= 0.0:
        return h_min, math.nan, math.nan
    dy[:] = solve_py(factor, g)
    err, p_min = newton_update_py(y, dy, weights, s.n)
    return h_min, err, p_min


def switch_branches_py(lift_state: FloatArray, slack: FloatArray, weights: FloatArray) -> int:
    """Twin of :func:`~foilbearing.reynolds._kernels.switch_branches`."""
    n = lift_state.shape[0]
    e = slack * weights[:n]
    move = ((lift_state > 0.0) & (e > 1.0)) | ((lift_state < 0.0) & (e > FREE_SLACK))
    lift_state[move] = -lift_state[move]
    return int(move.sum())


def bdf_setup_py(
    t_new: float,
    past: BdfHistory,
    order: int,
    atol: FloatArray,
    rtol: float,
    guess: FloatArray,
    hist: FloatArray,
    weights: FloatArray,
) -> float:
    """Twin of :func:`~foilbearing.reynolds._kernels.bdf_setup` (np.poly derivatives)."""
    times, ys, qs, count = past
    k = min(order, count)
    nodes = np.concatenate([[t_new], times[:k]])
    # Derivative at t_new of each Lagrange basis polynomial on the nodes.
    deriv = np.empty(k + 1)
    for j in range(k + 1):
        others = np.delete(nodes, j)
        basis = np.poly1d(np.poly(others)) / np.prod(nodes[j] - others)
        deriv[j] = basis.deriv()(t_new)
    hist[:] = deriv[1:] @ qs[:k] if k else 0.0
    p = min(k + 1, count)
    lw = np.array(
        [
            np.prod([(t_new - times[i]) / (times[j] - times[i]) for i in range(p) if i != j])
            for j in range(p)
        ]
    )
    guess[:] = lw @ ys[:p]
    weights[:] = 1.0 / (atol + rtol * np.abs(guess))
    return float(deriv[0])


def newton_update_py(
    y: FloatArray, dy: FloatArray, weights: FloatArray, n: int
) -> tuple[float, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.newton_update`."""
    y -= dy
    return float(np.max(np.abs(dy) * weights)), float(y[:n].min())


def lift_coordinate_py(lift_state: FloatArray, slack: FloatArray, out: FloatArray) -> bool:
    """Twin of :func:`~foilbearing.reynolds._kernels.lift_coordinate`."""
    out[:] = np.where(lift_state > 0.0, slack, -slack)
    return bool(np.any(lift_state))


def predict_branches_py(
    s0: FloatArray,
    s1: FloatArray,
    s2: FloatArray,
    known: int,
    weights: tuple[float, float, float],
    out: FloatArray,
) -> None:
    """Twin of :func:`~foilbearing.reynolds._kernels.predict_branches`."""
    l0, l1, l2 = weights
    if known == 1:
        pred = s0
    elif known == 2:
        pred = s0 + l0 * (s0 - s1)
    else:
        pred = l0 * s0 + l1 * s1 + l2 * s2
    out[:] = np.where(pred < 0.0, 1.0, -1.0)


def adopt_branches_py(lift_state: FloatArray, branches: FloatArray, most: int) -> int:
    """Twin of :func:`~foilbearing.reynolds._kernels.adopt_branches`."""
    moved = int(np.count_nonzero((lift_state > 0.0) != (branches > 0.0)))
    if 0 < moved <= most:
        lift_state[:] = np.where(branches > 0.0, 1.0, -1.0) * np.abs(lift_state)
    return moved
