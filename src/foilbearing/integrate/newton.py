"""The modified Newton iteration of an implicit step: its policy, in one place.

A step solves ``c0·Q(y) + hist − f(y) = 0`` for y with a factorised Newton matrix that
may be old (kept from an earlier step) or fresh (taken at this step). Two levels:

- the iterations with one factor (:func:`newton_progress`, :func:`newton_verdict` and
  :func:`switch_verdict`): when the iteration has converged, and when it must stop and
  why (too slow on a fresh factor, diverging on a kept one, or a refresh asked at the
  iterate). They are compiled, so that a compiled iteration calls them from inside its
  loop, and their Python originals (``.py_func``) serve an iteration written in Python:
  both follow the same rules;
- the step (:func:`solve_step`): keep the factor or take a fresh one, refresh it at the
  iterate up to ``MAX_REFRESH`` times, restart from the guess with a fresh factor once,
  then give up (the integrator halves the step).

A problem whose Newton matrix holds rows that switch (a complementarity condition, say)
passes a :class:`Switching`: it predicts the switches of a step, says whether a kept
factor may take them, and learns from each accepted step. Nothing here knows what the
rows mean.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numba import njit
from numpy.typing import NDArray

__all__ = [
    "MAX_REFRESH",
    "NEWTON_CONTINUE",
    "NEWTON_CONVERGED",
    "NEWTON_DIVERGED",
    "NEWTON_INFEASIBLE",
    "NEWTON_NOT_FINITE",
    "NEWTON_REFRESH",
    "NEWTON_RETREAT",
    "NEWTON_SWITCHED",
    "NEWTON_TOO_SLOW",
    "Factor",
    "NewtonRule",
    "Switching",
    "newton_progress",
    "newton_verdict",
    "solve_step",
    "switch_verdict",
]

FloatArray = NDArray[np.float64]

#: Outcomes of an iteration with one factor (``Factor.newton_solve``): converged; the
#: residual could not be evaluated at the iterate (outside the problem's domain); a NaN
#: or inadmissible update; a fresh factor too slow; a kept factor diverging; a refresh
#: asked at the iterate.
NEWTON_CONVERGED, NEWTON_INFEASIBLE, NEWTON_NOT_FINITE, NEWTON_TOO_SLOW = 0, 1, 2, 3
NEWTON_DIVERGED, NEWTON_REFRESH = 4, 5
#: Verdicts inside an iteration, never returned by it: go on; the switched rows were
#: taken, go on with the same factor; take the last update back, then refresh.
NEWTON_CONTINUE, NEWTON_SWITCHED, NEWTON_RETREAT = -1, -2, -3

#: Factor refreshes at the iterate within one step before the step is retried or halved.
MAX_REFRESH = 3


@dataclass(frozen=True)
class NewtonRule:
    """The modified Newton iteration of each step.

    Attributes
    ----------
    newton_tol
        Convergence of the Newton update in the weighted max-norm (1 = tolerance met).
    newton_fraction
        The iteration also stops at this fraction of its first update.
    max_newton
        Iterations per attempt before the Jacobian is refreshed.
    rtol
        Relative tolerance of the error weights 1/(atol + rtol |y|) (the absolute
        tolerances are per state: the problem's ``atol``).
    refresh_after
        A step that took more iterations than this leaves no factor to the next one,
        which takes a fresh factor at its predictor (None: the factor is kept until
        it fails or asks for a refresh).
    """

    newton_tol: float
    newton_fraction: float
    max_newton: int
    rtol: float
    refresh_after: int | None = None


@njit(cache=True, nogil=True)
def newton_progress(
    err: float,
    prev: float,
    since: int,
    first_change: float,
    newton_tol: float,
    newton_fraction: float,
) -> tuple[bool, float, float, float]:
    """Whether the iteration has converged after an update of weighted norm ``err``.

    Converged when ``err <= tol = max(newton_tol, newton_fraction · first update)`` or
    when the error left, ``rate/(1 − rate)·err`` with the measured contraction rate
    ``err/prev``, is below tol: BDF codes stop at a fraction of the step's own change,
    so the Newton error stays well below the truncation error of the step.

    Parameters
    ----------
    err, prev
        This update's and the previous one's weighted max-norms.
    since
        Iterations since the factor (or its switched rows) last changed; the rate is
        measured from the second on.
    first_change
        The step's first update so far (``inf`` at the start of a step).
    newton_tol, newton_fraction
        As in :class:`NewtonRule`.

    Returns
    -------
    converged : bool
    rate : float
        The contraction rate (NaN at the first iteration).
    tol : float
        The tolerance of this step.
    first_change : float
        The step's first update (``err`` if it was ``inf``).
    """
    if first_change == np.inf:
        first_change = err
    tol = max(newton_tol, newton_fraction * first_change)
    rate = err / prev if since > 1 else np.nan
    converged = err <= tol or (rate < 1.0 and rate / (1.0 - rate) * err <= tol)
    return converged, rate, tol, first_change


@njit(cache=True, nogil=True)
def newton_verdict(
    err: float,
    rate: float,
    tol: float,
    since: int,
    max_newton: int,
    fresh: bool,
    switched: bool,
    retreat: bool,
) -> int:
    """What an iteration that has not converged does next.

    A fresh factor stops after ``max_newton`` iterations or when it diverges (rate >= 1):
    ``NEWTON_TOO_SLOW``, or a refresh when rows have switched since it was taken (its
    rows no longer fit them); it asks for a refresh at its iterate when it contracts
    slowly (rate above 0.5: the iterate has left the region where this matrix is good).
    With ``retreat``, a fresh factor that diverges asks to take its last update back
    before the refresh (a kink of the residual crossed in the factor's own step). A kept
    factor stops when it diverges (rate >= 1, or ``max_newton``: ``NEWTON_DIVERGED``), and
    asks for a refresh when it would not converge within ``max_newton`` iterations.

    Returns
    -------
    int
        ``NEWTON_CONTINUE``, ``NEWTON_TOO_SLOW``, ``NEWTON_DIVERGED``, ``NEWTON_REFRESH``
        or ``NEWTON_RETREAT``.
    """
    if fresh:
        if retreat and since > 1 and rate >= 1.0:
            return NEWTON_RETREAT
        if since >= max_newton or rate >= 1.0:
            if switched:
                return NEWTON_REFRESH
            return NEWTON_TOO_SLOW
        if rate > 0.5:
            return NEWTON_REFRESH
    elif since >= max_newton or rate >= 1.0:
        return NEWTON_DIVERGED
    elif rate ** (max_newton - since) / (1.0 - rate) * err > tol:
        return NEWTON_REFRESH
    return NEWTON_CONTINUE


@njit(cache=True, nogil=True)
def switch_verdict(moved: int, switches: int, max_switches: int, most_moved: int) -> int:
    """What a converged iteration does after ``moved`` rows switched at its solution.

    None moved: ``NEWTON_CONVERGED``. A few (at most ``most_moved``, and no more than
    ``max_switches`` times a call): ``NEWTON_SWITCHED``, the iteration goes on with the
    same factor. More: ``NEWTON_REFRESH`` (too many rows differ from the factorised
    matrix, and the iteration on it would diverge).
    """
    if moved == 0:
        return NEWTON_CONVERGED
    if switches < max_switches and moved <= most_moved:
        return NEWTON_SWITCHED
    return NEWTON_REFRESH


class Factor(Protocol):
    """A factorised Newton matrix of one step and its modified-Newton iteration."""

    def newton_solve(
        self,
        y: FloatArray,
        args: Any,
        c0: float,
        hist: FloatArray,
        weights: FloatArray,
        work: tuple[FloatArray, FloatArray, FloatArray],
        controls: tuple[float, float, int],
        fresh: bool,
        first_change: float,
    ) -> tuple[int, int, float, float]:
        """Iterate on c0·Q(y) + hist − f(y) = 0 in place of y, by the rules above.

        ``work`` holds the residual, update and storage buffers; on convergence the
        storage Q(y) is in ``work[2]``. Returns ``(outcome, iterations, first change,
        monitor)``: an outcome ``NEWTON_*``, and the problem's monitor of the converged
        state (a scalar its stop events read; NaN otherwise).
        """
        ...


class Switching(Protocol):
    """Rows of the Newton matrix that switch, seen from the step (e.g. active sets)."""

    def predict(self, h: float, h1: float, h2: float, count: int) -> FloatArray | None:
        """The switches predicted for a step of h after steps h1, h2 (NaN when the
        history is shorter), ``count`` accepted states known; None: no prediction."""
        ...

    def adopt(self, factor: Any, hint: FloatArray) -> bool:
        """Whether a kept factor may take the predicted switches (and takes them)."""
        ...

    def reached(self, factor: Any) -> FloatArray:
        """The switches the factor's iteration has reached (a refresh takes them)."""
        ...

    def accepted(self, factor: Any | None) -> None:
        """Learn from the accepted step solved with ``factor`` (None: none kept)."""
        ...


Factorize = Callable[[FloatArray, Any, float, FloatArray, FloatArray | None], Any]


def solve_step(
    factorize: Factorize,
    switching: Switching | None,
    controls: tuple[float, float, int],
    y0: FloatArray,
    args: Any,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    factor: Any | None,
    factor_c0: float,
    work: tuple[FloatArray, FloatArray],
    hint: FloatArray | None,
) -> tuple[bool, FloatArray, int, Any | None, float, int, FloatArray, float]:
    """Modified Newton on c0·Q(y) + hist − f(y) = 0 from the guess y0, reusing the factor.

    A kept factor (taken at a c0 within 20 %, and able to take the step's predicted
    switches ``hint``) iterates first. A factor that converges too slowly (stale, or
    fresh but contracting at a rate above 0.5) is refreshed at the current iterate and
    the iteration goes on from there, up to ``MAX_REFRESH`` times a step; a fresh factor
    that fails (or a stale one whose iterate leaves the domain) restarts from the guess
    with a fresh factor, then gives up (the caller halves the step).

    Parameters
    ----------
    factorize
        ``factorize(y, args, c0, hist, hint)``: a fresh :class:`Factor` at y, taking the
        switches ``hint`` (None: decided at y).
    switching
        The problem's switched rows, or None.
    controls
        ``(newton_tol, newton_fraction, max_newton)``.
    y0, args, c0, hist, weights
        The guess, the problem's arguments at the new time, the BDF coefficient and
        history, and the error weights of the Newton norm.
    factor, factor_c0
        The kept factor and the c0 it was taken at (None, NaN: none).
    work
        Two state-sized buffers (residual, update) reused across iterations.
    hint
        The switches predicted for the step (:meth:`Switching.predict`), or None.

    Returns
    -------
    tuple
        ``(converged, y, iterations, factor, factor_c0, factorisations, Q(y), monitor)``;
        on failure y is the guess and Q is empty.
    """
    q_new = np.empty(y0.shape[0])
    buffers = (work[0], work[1], q_new)
    factorizations = 0
    its = 0
    refreshes = 0
    lu = factor
    lu_c0 = factor_c0
    for attempt in range(2):
        y = y0.copy()
        fresh = lu is None or attempt == 1 or abs(c0 - lu_c0) > 0.2 * c0
        if not fresh and hint is not None and lu is not None and switching is not None:
            fresh = not switching.adopt(lu, hint)
        if fresh:
            # The switches predicted for the step, or decided afresh at the guess when
            # the step starts over.
            lu = factorize(y, args, c0, hist, hint if attempt == 0 else None)
            lu_c0 = c0
            factorizations += 1
        assert lu is not None  # a step without a factor takes a fresh one
        first_change = math.inf
        while True:
            outcome, k, first_change, monitor = lu.newton_solve(
                y, args, c0, hist, weights, buffers, controls, fresh, first_change
            )
            its += k
            if outcome == NEWTON_CONVERGED:
                return True, y, its, lu, lu_c0, factorizations, q_new, monitor
            if outcome != NEWTON_REFRESH or refreshes >= MAX_REFRESH:
                break  # outside the domain, NaN, too slow or diverging: restart, or give up
            refreshes += 1
            # A factor that will not converge in time: refresh it here (with the
            # switches the iteration has reached), go on from y.
            reached = None if switching is None else switching.reached(lu)
            lu = factorize(y, args, c0, hist, reached)
            lu_c0 = c0
            factorizations += 1
            fresh = True
        if fresh:
            break
    return False, y0, its, None, math.nan, factorizations, np.empty(0), math.nan
