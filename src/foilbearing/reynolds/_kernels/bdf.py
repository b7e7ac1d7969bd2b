"""The BDF equations of the transient system, compiled: the residual of a step and the storage
(the quantities the BDF differentiates in time) (twins in :mod:`foilbearing.testing.twins`).
The variable-step BDF set-up, ``bdf_setup``, is the integrator's
(:mod:`foilbearing.integrate.bdf`), re-exported here. The linear system of a Newton step on
them (Jacobian blocks, border, solve) is in :mod:`.bdf_linear`, the film rows they share in
:mod:`.film_rows`, both importable from here; the Newton iteration is in :mod:`.newton`."""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.integrate.bdf import bdf_setup as bdf_setup  # the integrator's, re-exported
from foilbearing.laws.lift_off import smoothed_edge_kernel
from foilbearing.reynolds._kernels.bdf_linear import (
    lobe_correct,
    transient_border,
    transient_jacobian,
    transient_solve,
)
from foilbearing.reynolds._kernels.film_rows import _film_rows, _row_mean
from foilbearing.reynolds._kernels.flux import residual
from foilbearing.reynolds._kernels.groups import Group

__all__ = [
    "_film_rows",
    "_row_mean",
    "bdf_setup",
    "lobe_correct",
    "transient_border",
    "transient_jacobian",
    "transient_residual",
    "transient_solve",
    "transient_storage",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@njit(cache=True, nogil=True)
def transient_residual(
    y: FloatArray,
    step: Group,
    model: Group,
    lift_state: FloatArray,
    film: FloatArray,
    res: FloatArray,
    out: FloatArray,
    slack: FloatArray,
) -> float:
    """BDF equations ``G = c0·Q(y) + hist − f(y)`` and the minimum film, in one pass.

    Under top-foil lift-off a pressure cell obeys the complementarity condition
    ``P ≥ 1, G ≥ 0, (P − 1) G = 0`` (:mod:`foilbearing.reynolds.transient`):
    a cell held at ambient (``lift_state = d > 0``) has the equation
    ``d (P − 1) = 0`` in place of G = 0; ``slack`` says by how much each cell
    violates the branch it is on (pressure units, > 0: violated).

    Twin: :func:`foilbearing.testing.twins.newton_residual_py`
    (same result up to rounding: dot products are summed in another order).

    Parameters
    ----------
    y : ndarray, shape (n + n_theta + 4,)
        State ``[P (n), U (n_theta), ε_X, ε_Y, v_X, v_Y]``, ``n = n_theta n_z``,
        P cell ``k = i*n_z + j``.
    step : StepInputs (as a plain tuple)
        The BDF coefficient c0 and history, and Λ, ω/γ, the preload and the
        external force at the new time.
    model : FilmConstants (as a plain tuple)
        The bearing on its grid.
    lift_state : ndarray, shape (n,)
        Branch of each pressure cell under lift-off: ``d > 0`` held at ambient,
        ``−d < 0`` free (d the diagonal of its Newton row, 1/s), 0 where the
        film may hold sub-ambient pressure (no lift-off).
    film, res : ndarray, shape (n_theta, n_z)
        Filled with the film h/C and the finite-volume residual :func:`residual`.
    out : ndarray, shape (n + n_theta + 4,)
        Filled with G.
    slack : ndarray, shape (n,)
        Filled with ``−G/d`` (held cells), ``1 − P`` (free cells under lift-off)
        or 0 (no lift-off).

    Returns
    -------
    float
        Minimum film ``min H`` (NaN if the film holds a NaN).
    """
    c0, hist, lam, rate, preload, force = step
    cos_t, sin_t, c_act, c_bump, w, force_scale, denom, d_theta, d_z, n_z = model[:10]
    lobes, lobe_rows, c_stack, axial = model[10:14]
    lift_delta, lift_scale = model[14:16]
    width2 = lift_delta**2 * abs(lam)  # (δ√Λ)², the law's width at this Λ
    n_theta, n_z = film.shape
    n = n_theta * n_z
    q = np.empty(n_theta)
    h_row = np.empty(n_theta)
    h_min = _film_rows(y, preload, model, q, h_row, np.empty(lobes.shape[0]))
    for i in range(n_theta):
        for j in range(n_z):
            film[i, j] = h_row[i]
    P = y[:n].reshape((n_theta, n_z))
    residual(P, film, lam, d_theta, d_z, axial, res)
    fx = 0.0
    fy = 0.0
    for i in range(n_theta):
        h = h_row[i]
        for j in range(n_z):
            k = i * n_z + j
            p = y[k]
            gk = c0 * (p * h) - res[i, j] / denom + hist[k]
            d = lift_state[k]
            if lift_delta > 0.0:
                # The smoothed law: (P − 1)·G = s·δ²Λ, no branches. A factor's cell is
                # measured on its own scale s_k = −d (its Reynolds diagonal at the
                # factorisation): the same root, with rows of the size its factor has.
                s_k = -d if d < 0.0 else lift_scale
                half_phi = smoothed_edge_kernel(p - 1.0, gk / s_k, width2 * lift_scale / s_k)[0]
                out[k] = s_k * half_phi
                slack[k] = 0.0
                fx += w[0, k] * (p - 1.0)
                fy += w[1, k] * (p - 1.0)
                continue
            if d > 0.0:
                slack[k] = -gk / d
                gk = d * (p - 1.0)
            elif d < 0.0:
                slack[k] = 1.0 - p
            else:
                slack[k] = 0.0
            out[k] = gk
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
def transient_storage(y: FloatArray, preload: FloatArray, model: Group, out: FloatArray) -> float:
    """Stored quantities ``Q(y) = [P·H, U, ε, v]`` and the minimum film, in one pass.

    Twin: :meth:`foilbearing.reynolds.transient.TransientSystem.storage` and
    :meth:`~foilbearing.reynolds.transient.TransientSystem.min_film`.

    Parameters
    ----------
    y : ndarray, shape (n + n_theta + 4,)
        State (see :func:`transient_residual`).
    preload : ndarray, shape (n_theta,)
        r_p(θ_i, t)/C.
    model : FilmConstants (as a plain tuple)
        The bearing on its grid.
    out : ndarray, shape (n + n_theta + 4,)
        Filled with Q(y).

    Returns
    -------
    float
        Minimum film ``min H`` (NaN if the film holds a NaN).
    """
    n_theta = preload.shape[0]
    cos_t, sin_t, c_act, c_bump, w, force_scale, denom, d_theta, d_z, n_z = model[:10]
    lobes, lobe_rows, c_stack, axial = model[10:14]
    q = np.empty(n_theta)
    h_row = np.empty(n_theta)
    h_min = _film_rows(y, preload, model, q, h_row, np.empty(lobes.shape[0]))
    for i in range(n_theta):
        h = h_row[i]
        for j in range(n_z):
            k = i * n_z + j
            out[k] = y[k] * h
    for k in range(n_theta * n_z, y.shape[0]):
        out[k] = y[k]
    return h_min
