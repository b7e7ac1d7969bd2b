"""Finite-volume Reynolds residual and Jacobians, compiled: the residual of Eq. (4), dR/dP and
dR/dH on the stencil pattern, the foil-coupled Jacobian, and the lift-off rows (NumPy twins in
:mod:`foilbearing.testing.twins`). They sum the face fluxes of :mod:`.faces` over the cells and
fill the patterns of :mod:`.patterns`; the names of both stay importable from here."""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.laws.lift_off import smoothed_edge_kernel
from foilbearing.reynolds._kernels.faces import (
    _SERIES_X,
    C,
    E,
    N,
    S,
    W,
    _axial_flux4,
    _bern_both,
    _bern_pos,
    _end_face,
    _theta_face,
    _theta_flux,
    _z_face,
    bernoulli,
    bernoulli_deriv,
)
from foilbearing.reynolds._kernels.patterns import _row_slots, coupled_pattern, stencil_pattern

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: Real or complex data (the complex one for the perturbation at a frequency).
DataArray = NDArray[Any]  # float64, or complex128 (the perturbation at a frequency)
#: An argument group as a kernel takes it (a plain tuple; here the AxialStencil).
Group = tuple[Any, ...]

__all__ = [
    "_SERIES_X",
    "C",
    "E",
    "N",
    "S",
    "W",
    "_axial_flux4",
    "_bern_both",
    "_bern_pos",
    "_end_face",
    "_jacobian_both",
    "_row_slots",
    "_theta_face",
    "_theta_flux",
    "_z_face",
    "bernoulli",
    "bernoulli_deriv",
    "coupled_jacobian",
    "coupled_pattern",
    "jacobian_H",
    "jacobian_P",
    "lift_off_rows",
    "residual",
    "stencil_pattern",
    "unit_coupled_row",
]


# ---------------------------------------------------------------------------
# Residual and Jacobians (compiled)
# ---------------------------------------------------------------------------


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

    Twin: :func:`~foilbearing.testing.twins.residual_py`.

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
    Twin: :func:`~foilbearing.testing.twins.jacobian_P_py`. Arguments as :func:`residual`;
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

    Twin: :func:`~foilbearing.testing.twins.jacobian_H_py`. Arguments as :func:`jacobian_P`.
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
    Twin: :func:`~foilbearing.testing.twins.coupled_jacobian_py`.

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
    its row of ∂R/∂H is zero. Twin: :func:`~foilbearing.testing.twins.lift_off_rows_py`.

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
