"""NumPy twins of the compiled kernels, which the tests check the kernels against.

Each mirrors one kernel of :mod:`foilbearing.reynolds._kernels` (named in its docstring),
same arguments and results (dimensionless as there; time in s, c0 in 1/s), in NumPy/SciPy
array operations. The transient twins take the ``TransientSystem`` or ``TransientFactor``
first. The twins of the transient residual, solves and Newton loop are the production
SciPy fallback itself (:mod:`foilbearing.reynolds.fallback`, used where the block LU cannot
pivot), handed on here under the twins' names; production never imports this module.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds import fallback
from foilbearing.reynolds._kernels.flux import _SERIES_X, C, E, N, S, W
from foilbearing.reynolds._kernels.groups import BdfHistory
from foilbearing.reynolds.assembly import set_unit_rows
from foilbearing.testing.block_twins import block_cyclic_factor_py, block_cyclic_solve_py

if TYPE_CHECKING:
    from foilbearing.reynolds.transient import Inputs, TransientSystem

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
    "lobe_correct_py",
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

# The production fallback, under the names of the kernels' twins.
newton_residual_py = fallback.newton_residual
lobe_correct_py = fallback.lobe_correct
border_py = fallback.border
solve_py = fallback.solve
newton_solve_py = fallback.newton_solve
newton_step_py = fallback.newton_step
switch_branches_py = fallback.switch_branches
newton_update_py = fallback.newton_update


def smoothed_lift_off_py(
    x: FloatArray, y: FloatArray, delta: float | FloatArray, d_ref: float | FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Twin of the smoothed lift-off law (:func:`foilbearing.laws.lift_off.smoothed_edge`,
    as :func:`foilbearing.reynolds.fallback.smoothed_lift_off` calls it), written apart
    from it: the weight α and the residual ``G = −(d_ref/2)(x + y − √((x − y)² + 4δ²))``.
    """
    root = np.sqrt((x - y) ** 2 + 4.0 * np.square(delta))
    return 0.5 * (1.0 + (x - y) / root), -0.5 * d_ref * (x + y - root)


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
