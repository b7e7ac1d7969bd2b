"""The linear system of a BDF Newton step, compiled: the Jacobian blocks of the transient
system (film, foil, journal and lobes), the border of the journal and lobe unknowns eliminated
through the block-cyclic factor, and the solve of a Newton correction with that factor (twins in
:mod:`foilbearing.testing.twins`). The equations themselves are in :mod:`.bdf`; the Newton
iteration that uses this system is in :mod:`.newton`."""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.laws.lift_off import smoothed_edge_kernel
from foilbearing.reynolds._kernels.blockcyclic import block_cyclic_solve
from foilbearing.reynolds._kernels.film_rows import _film_rows, _row_mean
from foilbearing.reynolds._kernels.flux import (
    _jacobian_both,
    coupled_jacobian,
    residual,
    unit_coupled_row,
)
from foilbearing.reynolds._kernels.groups import Group

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@njit(cache=True, nogil=True)
def lobe_correct(
    x: FloatArray,
    lobe_border: FloatArray,
    lobe_inv: FloatArray,
    lobe_gain: FloatArray,
    lobe_rows: FloatArray,
    axial: Group,
) -> None:
    """Turn ``x = B⁻¹ b`` into ``B'⁻¹ b`` in place, ``B' = B + a_pl L`` (the lobes' border).

    Woodbury: ``B'⁻¹ b = x − Y (I + L Y)⁻¹ L x`` with ``Y = B⁻¹ a_pl``
    (``lobe_border``), ``(I + L Y)⁻¹`` (``lobe_inv``) and
    ``L x = lobe_gain_n · lobe_rows_n @ mean_row(x)``: the change of each lobe's
    compression D_n with the pressures (:class:`~.groups.FactorArrays`). Nothing to do
    without lobes. Twin: :func:`foilbearing.testing.twins.lobe_correct_py`.

    Parameters
    ----------
    x : ndarray, shape (n, k)
        Solutions with B, corrected in place.
    lobe_border, lobe_inv, lobe_gain : ndarray
        As :class:`~.groups.FactorArrays`.
    lobe_rows : ndarray, shape (n_lobe, n_theta)
        Interpolation at the stingers (:class:`~.groups.FilmConstants`).
    axial : AxialStencil (as a plain tuple)
        The axial-mean weights.
    """
    n_lobe = lobe_gain.shape[0]
    if n_lobe == 0:
        return
    n_theta = lobe_rows.shape[1]
    n = x.shape[0]
    n_z = n // n_theta
    t = np.empty(n_lobe)
    u = np.empty(n_lobe)
    second = axial[0] == 2
    mean_w = axial[5]
    for c in range(x.shape[1]):
        for a in range(n_lobe):
            acc = 0.0
            for i in range(n_theta):
                wt = lobe_rows[a, i]
                if wt != 0.0:
                    row = 0.0
                    if second:
                        for j in range(n_z):
                            row += x[i * n_z + j, c]
                    else:
                        for j in range(n_z):
                            row += mean_w[j] * x[i * n_z + j, c]
                    acc += wt * row
            t[a] = lobe_gain[a] * acc / n_z if second else lobe_gain[a] * acc
        for a in range(n_lobe):
            acc = 0.0
            for b in range(n_lobe):
                acc += lobe_inv[a, b] * t[b]
            u[a] = acc
        for r in range(n):
            acc = 0.0
            for a in range(n_lobe):
                acc += lobe_border[r, a] * u[a]
            x[r, c] -= acc


@njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
def transient_solve(
    g: FloatArray,
    factor: Group,
    model: Group,
    pattern: Group,
    work: FloatArray,
    out: FloatArray,
) -> None:
    """Newton update ``Δy`` with ``J Δy = g`` by block elimination (factors of the transient matrix).

    Eliminates the bump states U and the journal (ε, v), solves the pressure
    block with :func:`block_cyclic_solve` (and the lobes' border, :func:`lobe_correct`)
    and applies the rank-2 Woodbury correction of the film force. Twin:
    :func:`foilbearing.testing.twins.solve_py` (same result
    up to rounding).

    Parameters
    ----------
    g : ndarray, shape (n + n_theta + 4,)
        Right-hand side (the BDF residual), ``n = n_theta n_z``.
    factor : FactorArrays (as a plain tuple)
        The factorised Newton matrix: block cyclic factors of the pressure
        block B (:func:`block_cyclic_factor`), the scaled film Jacobian in CSR
        with the θ-row of each column in place of its index (the mat-vec is with
        ``repeat(x, n_z)``), the border, the Woodbury inverse, c0 and ω/γ at
        factorisation and the engaged rows.
    model : FilmConstants (as a plain tuple)
        The bearing on its grid (its bump compliance per θ-row).
    pattern : StencilPattern (as a plain tuple)
        The film Jacobian's θ-rows and row pointers.
    work : ndarray, shape (n, 1)
        Scratch (the pressure right-hand side).
    out : ndarray, shape (n + n_theta + 4,)
        Filled with Δy.
    """
    fac, jh_data, a_pe, s_vp, y_border, small_inv, c0, rate, active, lift_state = factor[:10]
    lobe_border, lobe_inv, lobe_gain = factor[10:]
    cos_t, sin_t, c_act, c_bump, w, force_scale, denom, d_theta, d_z, n_z = model[:10]
    lobes, lobe_rows, c_stack, axial = model[10:14]
    diag_slots, jh_rows, jh_indptr = pattern
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
    lobe_correct(work, lobe_border, lobe_inv, lobe_gain, lobe_rows, axial)
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
        dq = active[i] * _row_mean(out, i, n_z, axial, False)
        out[n + i] = (g[n + i] + rate * c_bump[i] * dq) / cu


@njit(cache=True, nogil=True)
def transient_jacobian(
    y: FloatArray,
    step: Group,
    model: Group,
    pattern: Group,
    lift_off: bool,
    decide: bool,
    blocks: Group,
) -> int:
    """Blocks of the transient Newton matrix at y, all but the factorisation, in one pass.

    Fills the film, the row-scaled Reynolds Jacobians ``c0·diag(H) − ∂R/∂P/(Aσ)``
    and ``c0·diag(P) − ∂R/∂H/(Aσ)`` (pattern :func:`stencil_pattern`), the
    engaged rows, the pressure block B on :func:`coupled_pattern` (bump and
    actuator eliminated, :func:`coupled_jacobian`), the border
    ``a_pe = (c0·diag(P) − ∂R/∂H/(Aσ)) ∂H/∂ε`` and, for lobes that follow their
    stacks, the lobes' border ``a_pl = (c0·diag(P) − ∂R/∂H/(Aσ)) ∂H/∂D_n`` with
    ``∂D_n/∂q(θ_n)`` (``lobe_gain``). Twin:
    :func:`foilbearing.testing.twins.jacobian_blocks_py`
    (same result up to rounding: the axial means are summed in another order).

    Parameters
    ----------
    y : ndarray, shape (n + n_theta + 4,)
        State (see :func:`transient_residual`), ``n = n_theta n_z``.
    step : StepInputs (as a plain tuple)
        The BDF step (its history serves the lift-off test) and the inputs at
        its new time (the force is not used).
    model : FilmConstants (as a plain tuple)
        The bearing on its grid.
    pattern : StencilPattern (as a plain tuple)
        Sparsity of the film Jacobians.
    lift_off : bool
        Top-foil lift-off: the cells with ``d (P − 1) < G`` (d the diagonal of
        their Newton row), the ambient branch of ``min(d (P − 1), G)``, are
        held at ambient: row ``d e_k``, zero film Jacobian row and border.
    decide : bool
        Decide the branches by that test at y; otherwise keep the branches
        ``blocks.lift_state`` holds (their signs; the scales d are renewed).
    blocks : JacobianBlocks (as a plain tuple)
        Filled: the film h/C, the scaled pressure and film Jacobians (stencil
        data; the film rows of clamped cells zero), the engaged rows, the data
        of B, the border and the branch of each cell (``d`` held, ``−d`` free,
        0 without lift-off), as :func:`transient_residual` takes it; read first
        when not ``decide``.

    Returns
    -------
    int
        Number of cells held at ambient (0 without lift-off).
    """
    H, jp, jh, active, jc, a_pe, lift_state, a_pl, lobe_gain = blocks
    c0, hist, lam, rate, preload, force = step
    cos_t, sin_t, c_act, c_bump, w, force_scale, denom, d_theta, d_z, n_z = model[:10]
    lobes, lobe_rows, c_stack, axial = model[10:14]
    diag_slots, jh_rows, jh_indptr = pattern
    n_theta, n_z = H.shape
    n = n_theta * n_z
    q = np.empty(n_theta)
    h_row = np.empty(n_theta)
    n_lobe = lobes.shape[0]
    q_stack = np.empty(n_lobe)
    _film_rows(y, preload, model, q, h_row, q_stack)
    for a in range(n_lobe):
        lobe_gain[a] = c_stack if q_stack[a] > 0.0 else 0.0
    for i in range(n_theta):
        for j in range(n_z):
            H[i, j] = h_row[i]
    P = y[:n].reshape((n_theta, n_z))
    _jacobian_both(P, H, lam, d_theta, d_z, axial, jp, jh)
    m_scale = -(1.0 / denom)
    for k in range(jp.shape[0]):
        jp[k] = m_scale * jp[k]
        jh[k] = m_scale * jh[k]
    for k in range(n):
        d = diag_slots[k]
        jp[d] += c0 * h_row[k // n_z]
        jh[d] += c0 * y[k]
    lift_delta, lift_scale = model[14:16]
    width2 = lift_delta**2 * abs(lam)  # (δ√Λ)², the law's width at this Λ
    if lift_delta > 0.0:
        # The smoothed law's rows: the BDF row times α, plus (1 − α) s_k on the diagonal,
        # each cell on its own scale s_k, its row's diagonal here (kept as −s_k in
        # lift_state, for the residual): a cell that crosses the kink after this
        # factorisation then keeps the size of its row, as under the sharp law.
        res_s = np.empty((n_theta, n_z))
        residual(P, H, lam, d_theta, d_z, axial, res_s)
        for k in range(n):
            i = k // n_z
            s_k = abs(jp[diag_slots[k]])
            if s_k == 0.0:
                s_k = lift_scale
            lift_state[k] = -s_k
            gk = c0 * (y[k] * h_row[i]) - res_s[i, k - i * n_z] / denom + hist[k]
            alpha = smoothed_edge_kernel(y[k] - 1.0, gk / s_k, width2 * lift_scale / s_k)[1]
            for e in range(jh_indptr[k], jh_indptr[k + 1]):
                jp[e] *= alpha
                jh[e] *= alpha
            jp[diag_slots[k]] += (1.0 - alpha) * s_k
    n_clamped = 0
    clamped = np.zeros(n, dtype=np.bool_)
    if lift_off:
        res = np.empty((n_theta, n_z))
        residual(P, H, lam, d_theta, d_z, axial, res)
        for k in range(n):
            d = abs(jp[diag_slots[k]])
            if d == 0.0:
                d = 1.0
            if decide:
                gk = c0 * (y[k] * h_row[k // n_z]) - res[k // n_z, k % n_z] / denom + hist[k]
                held = d * (y[k] - 1.0) < gk
            else:
                held = lift_state[k] > 0.0
            lift_state[k] = -d
            if held:
                lift_state[k] = d
                clamped[k] = True
                n_clamped += 1
                for e in range(jh_indptr[k], jh_indptr[k + 1]):
                    jh[e] = 0.0
    elif lift_delta == 0.0:
        for k in range(n):
            lift_state[k] = 0.0
    s = np.empty(n_theta)
    for i in range(n_theta):
        active[i] = 1.0 if _row_mean(y, i, n_z, axial, True) > 0.0 else 0.0
        c_eff = c_act[i] + rate * c_bump[i] / (c0 + rate)
        s[i] = c_eff * active[i]
    coupled_jacobian(jp, jh, s, n_z, axial, jc)
    if n_clamped > 0:
        for k in range(n):
            if clamped[k]:
                unit_coupled_row(jc, k, lift_state[k], n_theta, n_z)
    for r in range(n):
        a0 = 0.0
        a1 = 0.0
        for k in range(jh_indptr[r], jh_indptr[r + 1]):
            row = jh_rows[k]
            a0 += jh[k] * cos_t[row]
            a1 += jh[k] * sin_t[row]
        a_pe[r, 0] = a0
        a_pe[r, 1] = a1
        for a in range(n_lobe):
            acc = 0.0
            for k in range(jh_indptr[r], jh_indptr[r + 1]):
                acc += jh[k] * lobes[a, jh_rows[k]]
            a_pl[r, a] = acc
    return n_clamped


@njit(cache=True, nogil=True)
def transient_border(
    fac: FloatArray,
    a_pe: FloatArray,
    s_vp: FloatArray,
    c0: float,
    lobe: Group,
    y_border: FloatArray,
    small_inv: FloatArray,
) -> None:
    """Border solve and 2×2 Woodbury inverse of the transient Newton matrix.

    ``y_border = B'⁻¹ a_pe / c0²`` with the factors of :func:`block_cyclic_factor`
    (and the lobes' border, :func:`lobe_correct`) and ``small_inv = (I + s_vp
    y_border)⁻¹`` in closed form. Twin: :func:`foilbearing.testing.twins.border_py`.

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
    lobe : tuple
        ``(lobe_border, lobe_inv, lobe_gain, lobe_rows, axial)`` (:func:`lobe_correct`).
    y_border : ndarray, shape (n, 2)
        Filled with ``B'⁻¹ a_pe / c0²``.
    small_inv : ndarray, shape (2, 2)
        Filled with the inverse of the Woodbury matrix.
    """
    lobe_border, lobe_inv, lobe_gain, lobe_rows, axial = lobe
    n = a_pe.shape[0]
    c2 = c0**2
    for r in range(n):
        y_border[r, 0] = a_pe[r, 0] / c2
        y_border[r, 1] = a_pe[r, 1] / c2
    block_cyclic_solve(fac, y_border, y_border)
    lobe_correct(y_border, lobe_border, lobe_inv, lobe_gain, lobe_rows, axial)
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
