"""The film rows of a transient state, compiled: the axial mean of a θ-row and, per row, the
engaged mean gauge pressure and the film thickness H that the foil, the actuators and the lobes
give it (:meth:`foilbearing.film.FilmModel.film` in the state's terms). The BDF residual, storage
and Jacobian (:mod:`.bdf`, :mod:`.bdf_linear`) all read the film through these two functions."""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.reynolds._kernels.groups import Group

FloatArray = NDArray[np.float64]


@njit(cache=True, inline="always")
def _row_mean(x: FloatArray, i: int, n_z: int, axial: Group, gauge: bool) -> float:
    """Axial mean of θ-row i of the flat field x (``k = i n_z + j``), or of ``x − 1``.

    Second order: the plain mean; fourth order: the weights ``axial.mean_w``
    (:class:`~foilbearing.reynolds.grid.AxialStencil`).
    """
    acc = 0.0
    if axial[0] == 2:
        for j in range(n_z):
            acc += x[i * n_z + j]
        return acc / n_z - 1.0 if gauge else acc / n_z
    mean_w = axial[5]
    shift = 1.0 if gauge else 0.0
    for j in range(n_z):
        acc += mean_w[j] * (x[i * n_z + j] - shift)
    return acc


@njit(cache=True)
def _film_rows(
    y: FloatArray,
    preload: FloatArray,
    model: Group,
    q: FloatArray,
    h_row: FloatArray,
    q_stack: FloatArray,
) -> float:
    """Engaged mean gauge pressure q and film H per θ-row of a transient state.

    Fills ``q[i] = max(mean_j P[i, j] − 1, 0)``,
    ``h_row[i] = 1 + ε_X cos θ_i + ε_Y sin θ_i − r_p,i/C + U_i + c_a,i q_i
    + Σ_n D_n lobe_n(θ_i)`` and, for each lobe that follows its stack, the gauge
    pressure at its stinger ``q_stack[n] = lobe_rows_n @ (p̄ − 1)``, whose compression
    is ``D_n = c_stack max(q_stack[n], 0)`` (:meth:`foilbearing.film.FilmModel.film`);
    returns ``min_i h_row[i]`` (NaN if any row is NaN).
    """
    n_theta = q.shape[0]
    cos_t, sin_t, c_act, c_bump, w, force_scale, denom, d_theta, d_z, n_z = model[:10]
    lobes, lobe_rows, c_stack, axial = model[10:14]
    n = n_theta * n_z
    e_x = y[n + n_theta]
    e_y = y[n + n_theta + 1]
    n_lobe = lobes.shape[0]
    for i in range(n_theta):
        q[i] = _row_mean(y, i, n_z, axial, True)
    if n_lobe > 0:
        for a in range(n_lobe):
            acc = 0.0
            for i in range(n_theta):
                acc += lobe_rows[a, i] * q[i]
            q_stack[a] = acc
    h_min = np.inf
    bad = False
    for i in range(n_theta):
        qi = q[i]
        if qi < 0.0:
            qi = 0.0
        q[i] = qi
        h = 1.0 + e_x * cos_t[i] + e_y * sin_t[i] - preload[i] + y[n + i] + c_act[i] * qi
        for a in range(n_lobe):
            if q_stack[a] > 0.0:
                h += c_stack * q_stack[a] * lobes[a, i]
        h_row[i] = h
        if h != h:
            bad = True
        elif h < h_min:
            h_min = h
    return np.nan if bad else h_min
