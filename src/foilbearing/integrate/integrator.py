"""The variable-order BDF integrator of ``dQ(y)/dt = f(y, t)`` over callables.

:func:`integrate` steps a :class:`Problem` (its arguments at t, its storage Q, the
factorised Newton matrix that also iterates its residual, the nominal step) from a
:class:`State` to an end time. It is told what to record (a callback after each
accepted step) and when to stop (stop events, the user's interrupt), and knows
nothing of the problem, as ``diffrax.diffeqsolve`` takes ``f(t, y, args)``, ``saveat``
and ``event``.

The step is the problem's nominal one, or, given a :class:`StepControl`, the one its
error test chooses (variable, error-controlled steps up to a maximum); either lands on
the end time without a sliver. The order rises during the start-up, each missing past
state halving the step, and restarts from BDF1 after a step that failed twice. Each step is one modified Newton
solve (:func:`~foilbearing.integrate.newton.solve_step`), with the factor kept from
step to step while it converges.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.integrate.bdf import bdf_error, bdf_setup, push_history
from foilbearing.integrate.events import Event, Status, StepCollapsed
from foilbearing.integrate.newton import Factorize, NewtonRule, Switching, solve_step

__all__ = ["MAX_ORDER", "Problem", "Solution", "State", "StepControl", "integrate"]

FloatArray = NDArray[np.float64]

#: Highest BDF order of the integrator.
MAX_ORDER = 4


@dataclass
class State:
    """Everything needed to continue a run: the last accepted state and those before it."""

    t: float
    y: FloatArray
    #: (step that led to the newer state, state) for the earlier accepted states, newest first.
    past: list[tuple[float, FloatArray]] = field(default_factory=list)
    #: The next step the error control chose, s (NaN: none; fixed steps keep none).
    h_next: float = math.nan

    def as_checkpoint(self) -> dict[str, Any]:
        out: dict[str, Any] = {"t": self.t, "y": self.y}
        if math.isfinite(self.h_next):
            out["h_next"] = self.h_next
        for k, (h, y) in enumerate(self.past):
            suffix = "" if k == 0 else str(k + 1)
            out[f"y_prev{suffix}"], out[f"h_prev{suffix}"] = y, h
        return out

    @classmethod
    def from_checkpoint(cls, data: dict[str, Any]) -> State:
        def scalar(key: str) -> float:
            return float(np.ravel(data[key])[0])

        past = []
        for k in range(MAX_ORDER):
            suffix = "" if k == 0 else str(k + 1)
            if f"y_prev{suffix}" not in data:
                break
            past.append((scalar(f"h_prev{suffix}"), np.asarray(data[f"y_prev{suffix}"], float)))
        h_next = scalar("h_next") if "h_next" in data else math.nan
        return cls(scalar("t"), np.asarray(data["y"], float), past, h_next)


@dataclass(frozen=True)
class Problem:
    """The implicit system dQ(y)/dt = f(y, t) as the integrator sees it.

    Attributes
    ----------
    size
        Length of the state y.
    step_size
        ``step_size(t)``: the nominal step at t.
    inputs
        ``inputs(t)``: the problem's arguments at t (handed to ``storage``, ``factorize``
        and the factor's Newton solve) and what the recording reads of that instant;
        called in time order.
    storage
        ``storage(y, args)``: the stored quantity Q(y) of the BDF history.
    factorize
        ``factorize(y, args, c0, hist, hint)``: the factorised Newton matrix of
        c0·Q(y) + hist − f(y) at y, a :class:`~foilbearing.integrate.newton.Factor`
        (which also iterates the residual to convergence); ``hint``: the switches of
        its rows to take, or None.
    atol
        Absolute tolerances of the state (shape of y) of the error weights.
    switching
        The rows of the Newton matrix that switch, or None
        (:class:`~foilbearing.integrate.newton.Switching`).
    """

    size: int
    step_size: Callable[[float], float]
    inputs: Callable[[float], tuple[Any, Any]]
    storage: Callable[[FloatArray, Any], FloatArray]
    factorize: Factorize
    atol: FloatArray
    switching: Switching | None = None


@dataclass(frozen=True)
class StepControl:
    """Variable, error-controlled steps: the step is chosen by the local error of the last.

    After each step at the full order q (past the start-up), the local truncation error
    is estimated from the predictor–corrector difference
    (:func:`~foilbearing.integrate.bdf.bdf_error`) in the weighted max-norm with relative
    tolerance ``rtol`` (the problem's absolute tolerances scaled by ``rtol`` over the
    Newton rule's). A step whose error exceeds 1 is rejected and retried at
    h·max(min_shrink, safety·err^(−1/(q+1))); an accepted one proposes the next step
    h·min(max_growth, safety·err^(−1/(q+1))) when that grows it by ``hold`` or more,
    else keeps h (an accepted step never shrinks the next, as in CVODE: the step
    changes seldom, and the Newton factor, valid while c0 moves by less than 20 %, is
    kept), never above ``max_step(t)``, and not grown after a rejection or a failed
    Newton iteration. The BDF coefficients are the variable-step ones
    (:func:`~foilbearing.integrate.bdf.bdf_setup`, Lagrange form on the actual times), so
    the step may change at every step; the growth clamp keeps the step ratios where
    variable-step BDF up to order 4 is zero-stable (ratios below about 1.5-2).

    Attributes
    ----------
    rtol
        Relative tolerance of the local error test.
    max_step
        ``max_step(t)``: the longest step at t, s.
    rows
        The rows of the state the error test reads (all by default), as IDA's
        ``suppressalg`` leaves algebraic rows out of it.
    safety, max_growth, min_shrink, hold
        The controller's safety factor and clamps (ratios of successive steps).
    """

    rtol: float
    max_step: Callable[[float], float]
    rows: slice = slice(None)
    safety: float = 0.9
    max_growth: float = 1.5
    min_shrink: float = 0.2
    hold: float = 1.2


@dataclass(frozen=True)
class Solution:
    """How a run ended; the state and its history are in the :class:`State` it ran.

    Attributes
    ----------
    status
        :class:`~foilbearing.integrate.events.Status`.
    steps, factorizations, newton_iterations
        Accepted steps, factorisations and Newton iterations, from the counts given.
    event
        Index of the stop event that fired, or None.
    monitor
        The problem's monitor of the last accepted state (NaN before the first step).
    error
        The numerical failure that ended the run, or None.
    rejected
        Steps rejected by the error test of a :class:`StepControl` (this call's).
    """

    status: Status
    steps: int
    factorizations: int
    newton_iterations: int
    event: int | None = None
    monitor: float = math.nan
    error: ArithmeticError | None = None
    rejected: int = 0


#: ``record(t, y, args, extra, monitor, order)``: after each accepted state, with the
#: two items of ``inputs(t)`` (``order`` 0 and ``monitor`` None for the starting state).
Record = Callable[[float, FloatArray, Any, Any, float | None, int], None]


def integrate(
    problem: Problem,
    st: State,
    t1: float,
    order: int,
    newton: NewtonRule,
    record: Record,
    events: Sequence[Event] = (),
    progress: Callable[[float], None] | None = None,
    checkpoint: Callable[[Solution], None] | None = None,
    checkpoint_every: float = 30.0,
    interrupted: Callable[[], bool] = lambda: False,
    counts: tuple[int, int, int] = (0, 0, 0),
    control: StepControl | None = None,
) -> Solution:
    """Integrate ``problem`` from the state ``st`` to t1, a stop event, a failure or Ctrl-C.

    Parameters
    ----------
    problem
        The system, as callables and arrays.
    st
        The state to start from (and its BDF history); updated as the run goes, and its
        history (``past``) whenever a :class:`Solution` is made.
    t1
        The end time.
    order
        The BDF order (1 to :data:`MAX_ORDER`).
    newton
        The Newton iteration's rule.
    record
        Called with each accepted state (:data:`Record`).
    events
        Stop events, read in turn after each accepted step.
    progress
        Called with t after every step.
    checkpoint
        Called with the run so far (its ``st`` made whole) every ``checkpoint_every``
        seconds of wall time.
    interrupted
        Read before each step: True ends the run as interrupted (Ctrl-C held by
        :func:`~foilbearing.integrate.events.interrupt_at_step_boundary`).
    counts
        Steps, factorisations and Newton iterations before ``st`` (a resumed run's).
    control
        Variable, error-controlled steps (:class:`StepControl`); None: the problem's
        nominal step. With it, ``problem.step_size`` gives the first step (and the step
        of a run resumed from a state without ``h_next``).
    """
    last_checkpoint = time.perf_counter()
    args, extra = problem.inputs(st.t)
    # Accepted states, newest first: times, states y and storages Q (the BDF history).
    size = problem.size
    depth = order + 1
    times, ys, qs = np.empty(depth), np.empty((depth, size)), np.empty((depth, size))
    count = 1 + min(len(st.past), order)
    times[0], ys[0] = st.t, st.y
    for j, (h_j, y_j) in enumerate(st.past[: count - 1]):
        times[j + 1], ys[j + 1] = times[j] - h_j, y_j
    for j in range(count):
        qs[j] = problem.storage(ys[j], problem.inputs(times[j])[0])
    record(st.t, st.y, args, extra, None, 0)
    lu, lu_c0 = None, math.nan
    work = (np.empty(size), np.empty(size))  # Newton residual and update buffers
    guess, hist, weights = np.empty(size), np.empty(size), np.empty(size)
    atol = problem.atol
    controls = (newton.newton_tol, newton.newton_fraction, newton.max_newton)
    counters = list(counts)  # steps, factorizations, Newton iterations, from the run's start
    switching = problem.switching
    factorize = problem.factorize
    status, event, monitor, error = Status.COMPLETED, None, math.nan, None
    rejected = 0
    # The error test's norm: the weights' (rtol of the Newton rule) rescaled to its rtol.
    error_scale = math.nan if control is None else newton.rtol / control.rtol
    exponent = -1.0 / (order + 1)

    def solution(status: Status) -> Solution:
        st.past = [(float(times[j] - times[j + 1]), ys[j + 1].copy()) for j in range(count - 1)]
        steps, factorizations, iterations = counters
        return Solution(status, steps, factorizations, iterations, event, monitor, error, rejected)

    try:
        while st.t < t1 - 1e-12:
            if interrupted():
                raise KeyboardInterrupt  # held by interrupt_at_step_boundary
            t = st.t
            if control is None:
                h = h_nominal = problem.step_size(t)
            else:
                if not math.isfinite(st.h_next):
                    st.h_next = problem.step_size(t)
                h = h_nominal = min(st.h_next, control.max_step(t))
            if t1 - t < 2.0 * h:
                # Land on t1 in one step up to h, else in two equal ones: never longer
                # than the cap, and no sliver of a step, whose ratio to the next (after a
                # resume) would upset the BDF.
                h = t1 - t if t1 - t <= h else 0.5 * (t1 - t)
            if count <= order:
                # Start-up: the order rises with the history, and each missing past
                # state halves the step, so that the low-order first steps stay
                # below the error of the full-order ones.
                h *= 2.0 ** (count - 1 - order)
            err, retried, tested = math.nan, False, False
            while True:
                # The error test from the full order on (the start-up's lower-order
                # predictor would overstate the error).
                tested = control is not None and count > order
                t_new = t + h
                args, extra = problem.inputs(t_new)
                past = (times, ys, qs, count)
                c0 = bdf_setup(t_new, past, order, atol, newton.rtol, guess, hist, weights)
                hint = None
                if switching is not None:
                    h1 = t - times[1] if count > 1 else math.nan
                    h2 = times[1] - times[2] if count > 2 else math.nan
                    hint = switching.predict(h, h1, h2, count)
                ok, y_new, its, lu, lu_c0, nf, q_new, step_monitor = solve_step(
                    factorize, switching, controls, guess, args, c0, hist, weights, lu, lu_c0,
                    work, hint,
                )  # fmt: skip
                counters[2] += its
                counters[1] += nf
                if ok and tested:
                    assert control is not None
                    rows = control.rows
                    err = bdf_error(
                        y_new[rows], guess[rows], weights[rows], c0, t_new - times[order],
                        error_scale,
                    )  # fmt: skip
                    if err > 1.0:
                        # Rejected: retry shorter, from the same history, keeping the factor.
                        rejected += 1
                        retried = True
                        h *= max(control.min_shrink, control.safety * err**exponent)
                        if h < 1e-9:
                            raise StepCollapsed(t)
                        continue
                if ok:
                    break
                retried = True
                h *= 0.5
                if count > 1 and h < 0.3 * h_nominal:
                    # Failed twice: restart the order from this state (BDF1, then the
                    # start-up), as a history that the iteration can no longer follow
                    # (across a switch of many rows, say) can stall it.
                    count = 1
                if h < 1e-9:
                    raise StepCollapsed(t)
            counters[0] += 1
            taken = min(order, count)
            if switching is not None:
                switching.accepted(lu)
            if newton.refresh_after is not None and its > newton.refresh_after:
                lu = None  # a slow step: the next one takes a fresh factor at its predictor
            push_history(times, ys, qs, t_new, y_new, q_new)  # rows reused: no allocation
            count = min(count + 1, depth)
            st.t, st.y = t_new, ys[0].copy()
            if control is not None:
                if tested:
                    grow = control.safety * err**exponent if err > 0.0 else control.max_growth
                    grow = min(grow, 1.0 if retried else control.max_growth)
                    st.h_next = h if grow < control.hold else h * grow
                elif retried:
                    st.h_next = min(st.h_next, h)  # a failed Newton iteration in the start-up
            monitor = step_monitor
            record(t_new, y_new, args, extra, step_monitor, taken)
            for k, fires in enumerate(events):
                if fires(t_new, y_new, step_monitor):
                    status, event = Status.EVENT, k
                    break
            if event is not None:
                break
            if progress is not None:
                progress(t_new)
            if checkpoint is not None and time.perf_counter() - last_checkpoint > checkpoint_every:
                checkpoint(solution(Status.RUNNING))
                last_checkpoint = time.perf_counter()
    except KeyboardInterrupt:
        status = Status.INTERRUPTED
    except ArithmeticError as exc:  # a numerical failure (step collapse, singular factor)
        status, error = Status.FAILED, exc
    return solution(status)
