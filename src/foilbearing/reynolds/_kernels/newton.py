"""The modified Newton iteration of a BDF step: update, one step, lift-off branch
switching and the compiled Newton loop (twins in :mod:`foilbearing.testing.twins`).

Built on the BDF equations of :mod:`.bdf` (:func:`~.bdf.transient_residual`,
:func:`~.bdf.transient_solve`, :func:`~.bdf.transient_storage`).
"""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.integrate.newton import (
    NEWTON_CONTINUE,
    NEWTON_CONVERGED,
    NEWTON_INFEASIBLE,
    NEWTON_NOT_FINITE,
    NEWTON_REFRESH,
    NEWTON_RETREAT,
    NEWTON_SWITCHED,
    newton_progress,
    newton_verdict,
    switch_verdict,
)
from foilbearing.integrate.newton import (
    NEWTON_DIVERGED as NEWTON_DIVERGED,  # re-exported
)
from foilbearing.integrate.newton import (
    NEWTON_TOO_SLOW as NEWTON_TOO_SLOW,  # re-exported
)
from foilbearing.reynolds._kernels.bdf import (
    transient_residual,
    transient_solve,
    transient_storage,
)
from foilbearing.reynolds._kernels.groups import Group

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@njit(cache=True, nogil=True)
def transient_newton_step(
    y: FloatArray,
    step: Group,
    model: Group,
    pattern: Group,
    factor: Group,
    buf: Group,
    weights: FloatArray,
) -> tuple[float, float, float]:
    """One modified-Newton iteration: residual, solve and update of y, in one call.

    :func:`~.bdf.transient_residual` into ``buf.g`` on the factor's lift-off
    branches; if the film stays open (minimum > 0), :func:`~.bdf.transient_solve`
    into ``buf.dy`` with the factor and :func:`newton_update` of y. Twin:
    :func:`foilbearing.testing.twins.newton_step_py`
    (those three in sequence). Arguments as in those kernels; ``weights`` are
    the error weights of the convergence norm.

    Returns
    -------
    h_min : float
        Minimum film of y before the update (NaN if the film holds a NaN).
    err : float
        Weighted max-norm of dy (NaN if y was not updated: ``h_min <= 0``).
    p_min : float
        Smallest pressure after the update (NaN if not updated).
    """
    film, res, g, slack, work, dy, _q_out = buf
    fac, jh_data, a_pe, s_vp, y_border, small_inv, fac_c0, fac_rate, active, lift_state = factor[
        :10
    ]
    h_min = transient_residual(y, step, model, lift_state, film, res, g, slack)
    if h_min <= 0.0:
        return h_min, np.nan, np.nan
    transient_solve(g, factor, model, pattern, work, dy)
    err, p_min = newton_update(y, dy, weights, film.shape[0] * film.shape[1])
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
    Twin: :func:`~foilbearing.testing.twins.switch_branches_py`.
    """
    moved = 0
    for k in range(lift_state.shape[0]):
        d = lift_state[k]
        e = slack[k] * weights[k]
        if (d > 0.0 and e > 1.0) or (d < 0.0 and e > FREE_SLACK):
            lift_state[k] = -d
            moved += 1
    return moved


@njit(cache=True, nogil=True)
def lift_coordinate(lift_state: FloatArray, slack: FloatArray, out: FloatArray) -> bool:
    """The signed distance of each cell from the lift-off boundary at a converged step.

    ``out = P − 1 − G/d``: ``P − 1 >= 0`` on a free cell, ``−G/d <= 0`` on a held one (the
    slack of the residual kernel, sign-corrected); it moves smoothly as the boundary moves,
    so its extrapolation predicts the next step's branches (:func:`predict_branches`).
    Returns False when no cell has a branch (suction retained: ``out`` means nothing).
    Twin: :func:`~foilbearing.testing.twins.lift_coordinate_py`.
    """
    known = False
    for k in range(lift_state.shape[0]):
        d = lift_state[k]
        if d != 0.0:
            known = True
        out[k] = slack[k] if d > 0.0 else -slack[k]
    return known


@njit(cache=True, nogil=True)
def predict_branches(
    s0: FloatArray,
    s1: FloatArray,
    s2: FloatArray,
    known: int,
    weights: tuple[float, float, float],
    out: FloatArray,
) -> None:
    """Lift-off branches predicted for a step: ``out`` +1 held, −1 free.

    The boundary coordinate of the last ``known`` accepted steps (1 to 3: s0 newest),
    extrapolated to the new time: s0 itself (1), the line through s0 and s1 with
    ``weights[0] = h/h1`` (2), or the parabola through all three with the predictor's
    Lagrange weights (3). Twin: :func:`~foilbearing.testing.twins.predict_branches_py`.
    """
    l0, l1, l2 = weights
    for k in range(s0.shape[0]):
        if known == 1:
            pred = s0[k]
        elif known == 2:
            pred = s0[k] + l0 * (s0[k] - s1[k])
        else:
            pred = l0 * s0[k] + l1 * s1[k] + l2 * s2[k]
        out[k] = 1.0 if pred < 0.0 else -1.0


@njit(cache=True, nogil=True)
def adopt_branches(lift_state: FloatArray, branches: FloatArray, most: int) -> int:
    """How many cells of a kept factor are off the step's predicted ``branches``; if they
    are no more than ``most``, they take them (the factor's rows stay: the magnitude of each
    state is kept). Twin: :func:`~foilbearing.testing.twins.adopt_branches_py`.
    """
    moved = 0
    for k in range(lift_state.shape[0]):
        if (lift_state[k] > 0.0) != (branches[k] > 0.0):
            moved += 1
    if 0 < moved <= most:
        for k in range(lift_state.shape[0]):
            a = abs(lift_state[k])
            lift_state[k] = a if branches[k] > 0.0 else -a
    return moved


#: Outcomes of :func:`transient_newton_solve`: the integrator's
#: (:mod:`foilbearing.integrate.newton`); its residual cannot be evaluated on a closed film.
NEWTON_FILM_CLOSED = NEWTON_INFEASIBLE


@njit(cache=True, nogil=True)
def transient_newton_solve(
    y: FloatArray,
    step: Group,
    model: Group,
    pattern: Group,
    factor: Group,
    buf: Group,
    weights: FloatArray,
    controls: Group,
    fresh: bool,
    first_change: float,
) -> tuple[int, int, float, float]:
    """Modified-Newton iterations with one factor until they converge or must stop.

    Repeats :func:`transient_newton_step` under the integrator's Newton policy
    (:mod:`foilbearing.integrate.newton`: :func:`~foilbearing.integrate.newton.newton_progress`,
    :func:`~foilbearing.integrate.newton.newton_verdict`,
    :func:`~foilbearing.integrate.newton.switch_verdict`). Converged when the weighted update
    ``err <= tol = max(newton_tol, newton_fraction · first update)`` or when the
    error left, ``rate/(1 − rate)·err`` with the measured contraction rate, is
    below tol; the storage ``Q(y)`` then goes to ``buf.q_out``
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
    :func:`foilbearing.testing.twins.newton_solve_py`.

    Parameters
    ----------
    y, step, model, pattern, factor, buf, weights
        As in :func:`transient_newton_step`; y is updated in place.
    controls : NewtonControls (as a plain tuple)
        ``(newton_tol, newton_fraction, max_newton)``.
    fresh : bool
        Whether the factor was taken at this step.
    first_change : float
        The step's first update so far (``inf`` at the start of a step).

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
    newton_tol, newton_fraction, max_newton = controls
    fac, jh_data, a_pe, s_vp, y_border, small_inv, fac_c0, fac_rate, active, lift_state = factor[
        :10
    ]
    film, res, g, slack, work, dy, q_out = buf
    c0, hist, lam, rate, preload, force = step
    prev = np.inf
    k = 0
    smoothed = model[14] > 0.0
    since = 0  # iterations since the last change of branches
    switches = 0
    while True:
        k += 1
        since += 1
        h_min, err, p_min = transient_newton_step(y, step, model, pattern, factor, buf, weights)
        if h_min <= 0.0:
            return NEWTON_FILM_CLOSED, k, first_change, np.nan
        if not np.isfinite(err) or p_min <= 0.0:
            return NEWTON_NOT_FINITE, k, first_change, np.nan
        converged, conv, tol, first_change = newton_progress(
            err, prev, since, first_change, newton_tol, newton_fraction
        )
        if converged:
            # Converged on the present lift-off branches: cells that violate theirs
            # (a held cell with inflow, a free one below ambient) change branch and
            # the iteration goes on with the same factor.
            flipped = switch_branches(lift_state, slack, weights)
            verdict = switch_verdict(flipped, switches, MAX_SWITCHES, MAX_MOVED_KEPT)
            if verdict == NEWTON_CONVERGED:
                h_new = transient_storage(y, preload, model, q_out)
                if h_new > 0.0:
                    return NEWTON_CONVERGED, k, first_change, h_new
            elif verdict == NEWTON_SWITCHED:
                switches += 1
                since = 0
                prev = np.inf
                continue
            else:
                return NEWTON_REFRESH, k, first_change, np.nan
        # A fresh factor diverging since cells changed branch: its rows no longer fit
        # them (a cell on the lift-off boundary); refresh with them. Under the smoothed
        # law, cells that crossed its kink at ambient in the factor's own step: its next
        # step undoes the first; take that one back and refresh at the better iterate.
        verdict = newton_verdict(err, conv, tol, since, max_newton, fresh, switches > 0, smoothed)
        if verdict == NEWTON_RETREAT:
            for m in range(y.shape[0]):
                y[m] += dy[m]
            return NEWTON_REFRESH, k, first_change, np.nan
        if verdict != NEWTON_CONTINUE:
            return verdict, k, first_change, np.nan
        prev = err


@njit(cache=True)
def newton_update(
    y: FloatArray, dy: FloatArray, weights: FloatArray, n: int
) -> tuple[float, float]:
    """``y −= dy`` in place; the weighted max-norm of dy and the smallest new pressure.

    Twin :func:`~foilbearing.testing.twins.newton_update_py`.

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
