"""The finite-volume fluxes through one cell face, compiled: the Bernoulli function of the
exponentially fitted θ-flux, the θ-, Z- and end-face fluxes with their derivatives, and the
order-4 axial flux (docs/numerics.md §1; the scheme is described in
:mod:`foilbearing.reynolds._kernels`). The residual and Jacobians that sum them over the
cells are in :mod:`.flux`; NumPy twins in :mod:`foilbearing.testing.twins`."""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
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

    Twin: :func:`~foilbearing.testing.twins.bernoulli_py`. Negative arguments use
    ``B(x) = B(−x) − x``, which is exact and free of overflow.
    """
    if x >= 0.0:
        return _bern_pos(x)[0]
    return _bern_pos(-x)[0] - x


@njit(cache=True)
def bernoulli_deriv(x: float) -> float:
    """Derivative ``B'(x)``; twin :func:`~foilbearing.testing.twins.bernoulli_deriv_py`.

    Negative arguments use ``B'(x) = −B'(−x) − 1``.
    """
    if x >= 0.0:
        return _bern_pos(x)[1]
    return -_bern_pos(-x)[1] - 1.0


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
