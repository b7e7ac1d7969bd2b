"""The modified Newton iteration of a BDF step: update, one step, lift-off branch
switching and the compiled Newton loop (twins in :mod:`foilbearing.reynolds.reference`).

Built on the BDF equations of :mod:`.bdf` (:func:`~.bdf.transient_residual`,
:func:`~.bdf.transient_solve`, :func:`~.bdf.transient_storage`).
"""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.reynolds._kernels.bdf import (
    transient_residual,
    transient_solve,
    transient_storage,
)

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@njit(cache=True, nogil=True)
def transient_newton_step(
    y: FloatArray,
    c0: float,
    hist: FloatArray,
    lam: float,
    rate: float,
    preload: FloatArray,
    force: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    c_bump: FloatArray,
    lift_state: FloatArray,
    w: FloatArray,
    force_scale: float,
    denom: float,
    d_theta: float,
    d_z: float,
    H: FloatArray,
    res: FloatArray,
    g: FloatArray,
    slack: FloatArray,
    fac: FloatArray,
    jh_data: FloatArray,
    jh_rows: IntArray,
    jh_indptr: IntArray,
    a_pe: FloatArray,
    s_vp: FloatArray,
    y_border: FloatArray,
    small_inv: FloatArray,
    fac_c0: float,
    fac_rate: float,
    active: FloatArray,
    work: FloatArray,
    dy: FloatArray,
    weights: FloatArray,
) -> tuple[float, float, float]:
    """One modified-Newton iteration: residual, solve and update of y, in one call.

    :func:`~.bdf.transient_residual` into ``g``; if the film stays open (minimum
    > 0), :func:`~.bdf.transient_solve` into ``dy`` with the factor (taken at
    ``fac_c0``, ``fac_rate``) and :func:`newton_update` of y. Twin:
    :func:`foilbearing.reynolds.reference.newton_step_py`
    (those three in sequence). Arguments as in those kernels.

    Returns
    -------
    h_min : float
        Minimum film of y before the update (NaN if the film holds a NaN).
    err : float
        Weighted max-norm of dy (NaN if y was not updated: ``h_min <= 0``).
    p_min : float
        Smallest pressure after the update (NaN if not updated).
    """
    h_min = transient_residual(
        y, c0, hist, lam, rate, preload, force, cos_t, sin_t, c_act, c_bump, lift_state, w,
        force_scale, denom, d_theta, d_z, H, res, g, slack,
    )  # fmt: skip
    if h_min <= 0.0:
        return h_min, np.nan, np.nan
    transient_solve(
        g, fac, jh_data, jh_rows, jh_indptr, a_pe, s_vp, y_border, small_inv, fac_c0,
        fac_rate, active, c_bump, work, dy,
    )  # fmt: skip
    err, p_min = newton_update(y, dy, weights, H.shape[0] * H.shape[1])
    return h_min, err, p_min


#: Branch changes of the lift-off cells allowed in one :func:`transient_newton_solve`.
MAX_SWITCHES = 4
#: Cells that may change branch at once and keep the factor: more rows than this differ
#: from the factorised matrix and the iteration on it diverges (measured); refresh instead.
MAX_MOVED_KEPT = 8


#: A free cell is held once it is below ambient by this fraction of a unit of the
#: Newton norm: a looser test lets free cells sit just below ambient among held ones,
#: a chequered set of branches that solves the step within tolerance and changes
#: from step to step (measured: 200 of 1152 cells alternating between steps).
FREE_SLACK = 1e-3


@njit(cache=True, nogil=True)
def switch_branches(lift_state: FloatArray, slack: FloatArray, weights: FloatArray) -> int:
    """Move the lift-off cells that violate their branch to the other one; how many moved.

    A held cell is freed when its film has a net inflow of more than one unit
    of the Newton convergence norm (``slack · weight > 1``); a free cell is
    held as soon as it is below ambient (``slack · weight > FREE_SLACK``).
    Twin: :func:`~foilbearing.reynolds.reference.switch_branches_py`.
    """
    moved = 0
    for k in range(lift_state.shape[0]):
        d = lift_state[k]
        e = slack[k] * weights[k]
        if (d > 0.0 and e > 1.0) or (d < 0.0 and e > FREE_SLACK):
            lift_state[k] = -d
            moved += 1
    return moved


#: Outcomes of :func:`transient_newton_solve`.
NEWTON_CONVERGED, NEWTON_FILM_CLOSED, NEWTON_NOT_FINITE, NEWTON_TOO_SLOW = 0, 1, 2, 3
NEWTON_DIVERGED, NEWTON_REFRESH = 4, 5


@njit(cache=True, nogil=True)
def transient_newton_solve(
    y: FloatArray,
    c0: float,
    hist: FloatArray,
    lam: float,
    rate: float,
    preload: FloatArray,
    force: FloatArray,
    cos_t: FloatArray,
    sin_t: FloatArray,
    c_act: FloatArray,
    c_bump: FloatArray,
    lift_state: FloatArray,
    w: FloatArray,
    force_scale: float,
    denom: float,
    d_theta: float,
    d_z: float,
    H: FloatArray,
    res: FloatArray,
    g: FloatArray,
    slack: FloatArray,
    fac: FloatArray,
    jh_data: FloatArray,
    jh_rows: IntArray,
    jh_indptr: IntArray,
    a_pe: FloatArray,
    s_vp: FloatArray,
    y_border: FloatArray,
    small_inv: FloatArray,
    fac_c0: float,
    fac_rate: float,
    active: FloatArray,
    work: FloatArray,
    dy: FloatArray,
    weights: FloatArray,
    q_out: FloatArray,
    newton_tol: float,
    newton_fraction: float,
    max_newton: int,
    fresh: bool,
    first_change: float,
) -> tuple[int, int, float, float]:
    """Modified-Newton iterations with one factor until they converge or must stop.

    Repeats :func:`transient_newton_step`. Converged when the weighted update
    ``err <= tol = max(newton_tol, newton_fraction · first update)`` or when the
    error left, ``rate/(1 − rate)·err`` with the measured contraction rate, is
    below tol; the storage ``Q(y)`` then goes to ``q_out``
    (:func:`~.bdf.transient_storage`). A fresh factor (``fresh``) stops after
    ``max_newton`` iterations or when it diverges (rate >= 1), and asks for a
    refresh at its iterate when it contracts slowly (rate above 0.5: the
    iterate has left the region where this Jacobian is good); a stale one
    stops when it diverges (rate >= 1, or ``max_newton``), or asks for a
    refresh when it would not converge within ``max_newton`` iterations. Under
    lift-off the iteration solves with the factor's branches fixed; once it has
    converged, the cells that violate their branch move to the other one
    (:func:`switch_branches`) and it goes on with the same factor, up to
    ``MAX_SWITCHES`` times; more than ``MAX_MOVED_KEPT`` cells at once ask for a
    refresh, and so does a fresh factor that diverges after such a switch
    (its rows no longer fit the switched cells). Twin:
    :func:`foilbearing.reynolds.reference.newton_solve_py`.

    Returns
    -------
    outcome : int
        ``NEWTON_CONVERGED``, ``NEWTON_FILM_CLOSED`` (y not updated),
        ``NEWTON_NOT_FINITE`` (NaN update or a pressure <= 0),
        ``NEWTON_TOO_SLOW`` (fresh factor), ``NEWTON_DIVERGED`` (stale factor)
        or ``NEWTON_REFRESH`` (y is the last iterate).
    iterations : int
        Iterations done.
    first_change : float
        The first update of the step (carried over a refresh).
    h_min : float
        Minimum film of the converged y (NaN otherwise).
    """
    prev = np.inf
    k = 0
    since = 0  # iterations since the last change of branches
    switches = 0
    while True:
        k += 1
        since += 1
        h_min, err, p_min = transient_newton_step(
            y, c0, hist, lam, rate, preload, force, cos_t, sin_t, c_act, c_bump, lift_state, w,
            force_scale, denom, d_theta, d_z, H, res, g, slack, fac, jh_data, jh_rows, jh_indptr,
            a_pe, s_vp, y_border, small_inv, fac_c0, fac_rate, active, work, dy, weights,
        )  # fmt: skip
        if h_min <= 0.0:
            return NEWTON_FILM_CLOSED, k, first_change, np.nan
        if not np.isfinite(err) or p_min <= 0.0:
            return NEWTON_NOT_FINITE, k, first_change, np.nan
        if first_change == np.inf:
            first_change = err
        tol = max(newton_tol, newton_fraction * first_change)
        # Contraction rate of this factor; the error left in y is about rate/(1−rate)·err.
        conv = err / prev if since > 1 else np.nan
        if err <= tol or (conv < 1.0 and conv / (1.0 - conv) * err <= tol):
            # Converged on the present lift-off branches: cells that violate theirs
            # (a held cell with inflow, a free one below ambient) change branch and
            # the iteration goes on with the same factor.
            flipped = switch_branches(lift_state, slack, weights)
            if flipped == 0:
                h_new = transient_storage(y, preload, cos_t, sin_t, c_act, H.shape[1], q_out)
                if h_new > 0.0:
                    return NEWTON_CONVERGED, k, first_change, h_new
            elif switches < MAX_SWITCHES and flipped <= MAX_MOVED_KEPT:
                switches += 1
                since = 0
                prev = np.inf
                continue
            else:
                return NEWTON_REFRESH, k, first_change, np.nan
        if fresh:
            if since >= max_newton or conv >= 1.0:
                if switches > 0:
                    # Diverging since cells changed branch: the factor's rows no longer
                    # fit them (a cell on the lift-off boundary); refresh with them.
                    return NEWTON_REFRESH, k, first_change, np.nan
                return NEWTON_TOO_SLOW, k, first_change, np.nan
            if conv > 0.5:
                return NEWTON_REFRESH, k, first_change, np.nan
        elif since >= max_newton or conv >= 1.0:
            return NEWTON_DIVERGED, k, first_change, np.nan
        elif conv ** (max_newton - since) / (1.0 - conv) * err > tol:
            return NEWTON_REFRESH, k, first_change, np.nan
        prev = err


@njit(cache=True)
def newton_update(
    y: FloatArray, dy: FloatArray, weights: FloatArray, n: int
) -> tuple[float, float]:
    """``y −= dy`` in place; the weighted max-norm of dy and the smallest new pressure.

    Twin :func:`~foilbearing.reynolds.reference.newton_update_py`.

    Parameters
    ----------
    y, dy, weights : ndarray, shape (m,)
        Iterate (updated in place), Newton update and error weights.
    n : int
        Number of pressure unknowns (the first n entries of y).

    Returns
    -------
    err : float
        ``max |dy| · weights`` (NaN if any term is NaN).
    p_min : float
        ``min y[:n]`` after the update.
    """
    err = 0.0
    bad = False
    p_min = np.inf
    for k in range(y.shape[0]):
        y[k] -= dy[k]
        e = abs(dy[k]) * weights[k]
        if e != e:
            bad = True
        elif e > err:
            err = e
        if k < n and y[k] < p_min:
            p_min = y[k]
    return (np.nan if bad else err), p_min
