"""The SciPy path of the transient Newton: where the block LU of the pressure block cannot
pivot, :meth:`~foilbearing.reynolds.transient.TransientSystem.factorize` falls back on a
SuperLU factorisation, and the residual, solves and Newton loop run here in NumPy/SciPy
array operations instead of the compiled kernels (which need the block cyclic factors).

Each function is the NumPy form of one kernel of :mod:`foilbearing.reynolds._kernels` (named
in its docstring), with the same arguments and results (dimensionless as there; time in s,
c0 in 1/s), and so also its twin: :mod:`foilbearing.testing.twins` hands them to the tests
under the twins' names. :func:`newton_residual` also gives the system its lift-off branches
and smoothed weights (:meth:`~foilbearing.reynolds.transient.TransientSystem.lift_state`,
:meth:`~foilbearing.reynolds.transient.TransientSystem.smoothed_weights`), and
:func:`smoothed_lift_off` is the smoothed lift-off law of a cell (docs/lift-off.md).
The system and its factor are named through :mod:`foilbearing.reynolds.transient_protocol`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.laws.lift_off import smoothed_edge
from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds._kernels.newton import FREE_SLACK
from foilbearing.reynolds.transient_protocol import FactorLike, InputsLike, SystemLike

__all__ = [
    "border",
    "lobe_correct",
    "newton_residual",
    "newton_solve",
    "newton_step",
    "newton_update",
    "smoothed_lift_off",
    "solve",
    "switch_branches",
]

FloatArray = NDArray[np.float64]


def smoothed_lift_off(
    x: FloatArray, y: FloatArray, delta: float | FloatArray, d_ref: float | FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The smoothed lift-off law of each cell: its weight α and its residual G (δ and
    d_ref one for all cells, or one a cell).

    ``x = P − 1`` and ``y`` the net outflow in pressure units (``−R/d_ref``); ``G =
    −(d_ref/2)(x + y − √((x − y)² + 4δ²))``, zero where x > 0, y > 0 and ``x y = δ²``;
    ``α = −(∂G/∂y)/d_ref`` is the weight of the Reynolds row in the cell's row
    (docs/lift-off.md, "The smoothed edge").
    """
    half_phi, alpha = smoothed_edge(x, y, np.square(delta))
    return alpha, -d_ref * half_phi


def newton_residual(
    system: SystemLike,
    y: FloatArray,
    inputs: InputsLike,
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
            out[:n] = -smoothed_lift_off(x, out[:n] / s, width, s)[1]
        if slack is not None:
            slack[:] = 0.0
        return out, float(H.min())
    if slack is not None:
        safe = np.where(d > 0.0, d, 1.0)
        slack[:] = np.where(d > 0.0, -out[:n] / safe, np.where(d < 0.0, 1.0 - P.ravel(), 0.0))
    out[:n] = np.where(d > 0.0, d * (P.ravel() - 1.0), out[:n])
    return out, float(H.min())


def lobe_correct(x: FloatArray, lobe: tuple[Any, ...], system: SystemLike) -> FloatArray:
    """Twin of :func:`~foilbearing.reynolds._kernels.lobe_correct`: ``B'⁻¹ b`` from
    ``x = B⁻¹ b`` (a new array), ``lobe = (B⁻¹ a_pl, (I + L B⁻¹ a_pl)⁻¹, gain, lobe_rows, axial)``."""
    border, inv, gain = lobe[:3]
    if gain.size == 0:
        return x
    L = gain[:, None] * system.lobe_mean
    return x - border @ (inv @ (L @ x))


def border(
    system: SystemLike,
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
        y_border = lobe_correct(y_border, lobe, system)
    small = np.eye(2) + system.s_vp @ y_border  # Woodbury: I + V^T B^-1 U, V^T = S_vp
    return y_border, np.linalg.inv(small).astype(np.float64)


def solve(factor: FactorLike, g: FloatArray) -> FloatArray:
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
    z = lobe_correct(z, lobe, s)
    d_p = z - arrays.y_border @ (arrays.small_inv @ (arrays.s_vp @ z))
    d_e = (arrays.s_vp @ d_p + g_v + c0 * g_e) / c0**2
    d_v = c0 * d_e - g_e
    dq = arrays.active[:, None] * s.grid.axial_mean(d_p.reshape(nt, nz, -1))
    d_u = (g_u + rate * s.c_bump[:, None] * dq) / (c0 + rate)
    return np.concatenate([d_p, d_u, d_e, d_v]).reshape(g.shape)


def newton_solve(
    factor: FactorLike,
    y: FloatArray,
    inputs: InputsLike,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    work: tuple[FloatArray, FloatArray, FloatArray],
    controls: tuple[float, float, int],
    fresh: bool,
    first_change: float,
) -> tuple[int, int, float, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_newton_solve` (of
    ``TransientFactor.newton_solve``): :func:`newton_step` in a loop."""
    g, dy, q_out = work
    newton_tol, newton_fraction, max_newton = controls
    prev = math.inf
    k = since = switches = 0
    while True:
        k += 1
        since += 1
        h_min, err, p_min = newton_step(factor, y, inputs, c0, hist, weights, g, dy)
        if h_min <= 0.0:
            return kern.NEWTON_FILM_CLOSED, k, first_change, math.nan
        if not math.isfinite(err) or p_min <= 0.0:
            return kern.NEWTON_NOT_FINITE, k, first_change, math.nan
        if first_change == math.inf:
            first_change = err
        tol = max(newton_tol, newton_fraction * first_change)
        conv = err / prev if since > 1 else math.nan
        if err <= tol or (conv < 1.0 and conv / (1.0 - conv) * err <= tol):
            flipped = switch_branches(factor.lift_state, factor.sys._slack, weights)
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


def newton_step(
    factor: FactorLike,
    y: FloatArray,
    inputs: InputsLike,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    g: FloatArray,
    dy: FloatArray,
) -> tuple[float, float, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.transient_newton_step` (of
    ``TransientFactor.newton_step``): residual, solve and update in sequence."""
    s = factor.sys
    g[:], h_min = newton_residual(s, y, inputs, c0, hist, factor.lift_state, s._slack)
    if h_min <= 0.0:
        return h_min, math.nan, math.nan
    dy[:] = solve(factor, g)
    err, p_min = newton_update(y, dy, weights, s.n)
    return h_min, err, p_min


def switch_branches(lift_state: FloatArray, slack: FloatArray, weights: FloatArray) -> int:
    """Twin of :func:`~foilbearing.reynolds._kernels.switch_branches`."""
    n = lift_state.shape[0]
    e = slack * weights[:n]
    move = ((lift_state > 0.0) & (e > 1.0)) | ((lift_state < 0.0) & (e > FREE_SLACK))
    lift_state[move] = -lift_state[move]
    return int(move.sum())


def newton_update(
    y: FloatArray, dy: FloatArray, weights: FloatArray, n: int
) -> tuple[float, float]:
    """Twin of :func:`~foilbearing.reynolds._kernels.newton_update`."""
    y -= dy
    return float(np.max(np.abs(dy) * weights)), float(y[:n].min())
