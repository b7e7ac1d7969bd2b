"""The coefficients of a variable-step BDF step: c0, the history, the predictor and the
error weights (compiled).

:func:`bdf_setup` builds one step ``c0 Q(y) + hist − f(y) = 0`` of the implicit
system ``dQ(y)/dt = f(y, t)`` on the last accepted states, newest first, given as the
plain tuple ``(times, ys, qs, count)``: their times, states, storages Q and how many
rows hold accepted states.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit
from numpy.typing import NDArray

__all__ = ["bdf_error", "bdf_setup", "push_history"]

FloatArray = NDArray[np.float64]
Group = tuple[Any, ...]


@njit(cache=True, nogil=True)
def bdf_setup(
    t_new: float,
    past: Group,
    order: int,
    atol: FloatArray,
    rtol: float,
    guess: FloatArray,
    hist: FloatArray,
    weights: FloatArray,
) -> float:
    """Variable-step BDF coefficient, history, predictor and error weights of one step.

    The last ``count = past.accepted`` accepted states are ``ys[j]`` at
    ``times[j]`` (newest first) with storages ``qs[j]``. With k = min(order, count), the BDF
    equation ``c0 Q(y) + hist − f(y) = 0`` states that the derivative at
    t_new of the polynomial through (t_new, Q(y)) and the last k storages is f:
    ``c0 = Σ_{i=1..k} 1/(t_new − t_i)`` and ``hist = Σ_j l'_j(t_new) Q_j``.
    The predictor ``guess`` extrapolates the polynomial through the last
    min(k + 1, count) states to t_new, and ``weights = 1/(atol + rtol |guess|)``.
    Order 2 is the variable-step BDF2, ``c0 = (1 + 2ρ)/((1 + ρ) h)``, ρ = h/h1.

    Returns
    -------
    float
        c0, 1/s.
    """
    times, ys, qs, count = past
    n = guess.shape[0]
    k = min(order, count)
    c0 = 0.0
    for i in range(k):
        c0 += 1.0 / (t_new - times[i])
    for m in range(n):
        hist[m] = 0.0
    for j in range(k):
        # l'_j(t_new) of the node t_j among t_new, t_0 .. t_{k-1}: t_new is a root of l_j.
        num = 1.0 / (times[j] - t_new)
        for i in range(k):
            if i != j:
                num *= (t_new - times[i]) / (times[j] - times[i])
        for m in range(n):
            hist[m] += num * qs[j, m]
    p = min(k + 1, count)
    for m in range(n):
        guess[m] = 0.0
    for j in range(p):
        lj = 1.0
        for i in range(p):
            if i != j:
                lj *= (t_new - times[i]) / (times[j] - times[i])
        for m in range(n):
            guess[m] += lj * ys[j, m]
    for m in range(n):
        weights[m] = 1.0 / (atol[m] + rtol * abs(guess[m]))
    return c0


@njit(cache=True, nogil=True)
def bdf_error(
    y_new: FloatArray,
    guess: FloatArray,
    weights: FloatArray,
    c0: float,
    span: float,
    scale: float,
) -> float:
    """Weighted max-norm of the local truncation error of a full-order BDF step.

    The predictor (:func:`bdf_setup`'s ``guess``) interpolates the last k + 1 states at
    t_1 .. t_{k+1} (newest first) and misses the solution by D·Π_{i=1..k+1}(t_new − t_i),
    D = y^(k+1)/(k+1)!; the BDFk corrector misses it by −D·Π_{i=1..k}(t_new − t_i)/c0
    (for a step short beside the problem's own time scales). Their difference gives the
    corrector's error, the standard estimate from the predictor–corrector difference
    (SUNDIALS CVODE, Hindmarsh et al. 2005, §2.1), here for any step ratios:

        LTE = −(y_new − guess) / (c0·(t_new − t_{k+1}) + 1),

    1/3 of the difference for BDF1 and 2/11 for BDF2 at a constant step (their error
    constants 1/2 and 2/9 over the predictor's 3/2 and 11/9).

    Parameters
    ----------
    y_new, guess
        The corrector's solution and the predictor of the step.
    weights
        The error weights 1/(atol + rtol |guess|) of :func:`bdf_setup`.
    c0
        The step's BDF coefficient, 1/s.
    span
        t_new − t_{k+1}: from the oldest state of the predictor to the new time, s.
    scale
        Multiplies the norm (the ratio of the weights' rtol to the error test's).

    Returns
    -------
    float
        The error in units of the tolerance (≤ 1: the step is accepted).
    """
    err = 0.0
    for m in range(y_new.shape[0]):
        e = abs((y_new[m] - guess[m]) * weights[m])
        if e > err:
            err = e
    return err * scale / (c0 * span + 1.0)


@njit(cache=True, nogil=True)
def push_history(
    times: FloatArray,
    ys: FloatArray,
    qs: FloatArray,
    t_new: float,
    y_new: FloatArray,
    q_new: FloatArray,
) -> None:
    """Make the accepted state (t_new, y_new, q_new) the newest row of the history, in
    place: each row moves one older and the oldest is dropped (rows newest first, as
    :func:`bdf_setup` reads them). A copy without NumPy's temporaries for the overlapping
    slices (3-4 % of a smooth orbit's step)."""
    for j in range(times.shape[0] - 1, 0, -1):
        times[j] = times[j - 1]
        ys[j, :] = ys[j - 1, :]
        qs[j, :] = qs[j - 1, :]
    times[0] = t_new
    ys[0, :] = y_new
    qs[0, :] = q_new
