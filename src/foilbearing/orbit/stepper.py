"""The variable-step BDF stepper of the orbit, its modified Newton iteration and its checkpoint.

The stepper sees a run as a :class:`~foilbearing.orbit.problem.StepperProblem`
(callables and arrays: the inputs at t, the storage, the factorisation and
its Newton solve, the output) and its settings by role (``StepRule``,
``NewtonRule``, ``StopRule``), never the case or the programs. See
:mod:`foilbearing.orbit` for the method and docs/numerics.md §8 for the details.
"""

from __future__ import annotations

import math
import signal
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.constants import RPM
from foilbearing.orbit.problem import Factor, RunStats, StepperProblem
from foilbearing.orbit.result import OrbitResult, RunStatus
from foilbearing.orbit.sampling import Samples, progress_bar
from foilbearing.orbit.settings import MAX_ORDER, NewtonRule, StepRule, StopRule
from foilbearing.reynolds._kernels import (
    MAX_MOVED_KEPT,
    adopt_branches,
    lift_coordinate,
    predict_branches,
)
from foilbearing.reynolds.transient import (
    NEWTON_CONVERGED,
    NEWTON_REFRESH,
    BdfHistory,
    Inputs,
    bdf_setup,
)

__all__ = ["State", "interrupt_at_step_boundary", "run"]

FloatArray = NDArray[np.float64]


@dataclass
class State:
    """Everything needed to continue a run: the last accepted state and those before it."""

    t: float
    y: FloatArray
    #: (step that led to the newer state, state) for the earlier accepted states, newest first.
    past: list[tuple[float, FloatArray]] = field(default_factory=list)

    def as_checkpoint(self) -> dict[str, Any]:
        out: dict[str, Any] = {"t": self.t, "y": self.y}
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
        return cls(scalar("t"), np.asarray(data["y"], float), past)


@contextmanager
def interrupt_at_step_boundary() -> Iterator[Callable[[], bool]]:
    """Hold Ctrl-C until the step under way is committed; yields ``interrupted()``.

    A KeyboardInterrupt raised at an arbitrary line of a step (between the shift of
    the BDF history and the update of the current time, say) leaves a checkpoint
    whose state, time and history disagree, and the resumed run then departs from
    the uninterrupted one. In the main thread with Python's default handler, SIGINT
    only sets a flag that the stepper reads before each step; elsewhere (a worker
    thread, which never receives SIGINT, or a program with its own handler)
    nothing changes.
    """
    requested = [False]
    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield lambda: requested[0]
        return

    def hold(signum: int, frame: object) -> None:
        requested[0] = True

    signal.signal(signal.SIGINT, hold)
    try:
        yield lambda: requested[0]
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def run(
    problem: StepperProblem,
    st: State,
    out: Samples,
    step: StepRule,
    newton: NewtonRule,
    stop: StopRule,
    progress: bool | Callable[[float, float], None] = False,
    checkpoint: Callable[[OrbitResult], None] | None = None,
    checkpoint_every: float = 30.0,
    interrupted: Callable[[], bool] = lambda: False,
    counts: tuple[int, int, int] = (0, 0, 0),
) -> OrbitResult:
    """Integrate ``problem`` from the state ``st`` to its end, a contact, a stop or Ctrl-C.

    Parameters
    ----------
    problem
        The system, its inputs and its output, as callables and arrays.
    st
        The state to start from (and its BDF history); updated as the run goes.
    out
        The output of the run, handed to ``problem.record``/``make_result``.
    step, newton, stop
        The time-step rule, the Newton iteration, and when to stop before the
        end of the profile (:mod:`foilbearing.orbit.settings`).
    progress
        True for a tqdm bar, or a callable ``f(t, speed)`` (s, rad/s) after every step.
    checkpoint
        Called with the partial result every ``checkpoint_every`` seconds of wall time.
    interrupted
        Read before each step: True ends the run as interrupted (Ctrl-C held by
        :func:`interrupt_at_step_boundary`).
    counts
        Steps, factorisations and Newton iterations before ``st`` (a resumed run's),
        so that the result's counts are the whole run's.
    """
    t_end = problem.t_end if stop.stop_time is None else min(stop.stop_time, problem.t_end)
    clock = time.perf_counter()
    last_checkpoint = clock
    bar = progress_bar(progress, t_end, st.t)
    inp, volts = problem.inputs(st.t)
    # Accepted states, newest first: times, states y and storages Q (the BDF history).
    size, order = problem.size, step.order
    depth = order + 1
    times, ys, qs = np.empty(depth), np.empty((depth, size)), np.empty((depth, size))
    count = 1 + min(len(st.past), order)
    times[0], ys[0] = st.t, st.y
    for j, (h_j, y_j) in enumerate(st.past[: count - 1]):
        times[j + 1], ys[j + 1] = times[j] - h_j, y_j
    for j in range(count):
        qs[j] = problem.storage(ys[j], problem.inputs(times[j])[0])
    problem.record(out, st.t, st.y, volts, inp, None)
    lu, lu_c0 = None, math.nan
    work = (np.empty(size), np.empty(size))  # Newton residual and update buffers
    guess, hist, weights = np.empty(size), np.empty(size), np.empty(size)
    atol = problem.atol
    counters = list(counts)  # steps, factorizations, Newton iterations, from the run's start
    # Lift-off boundary coordinate at the last three accepted steps, newest first, of
    # which the first `known` are known; the branches predicted from them for a step.
    cells = problem.lift_slack.shape[0]
    lift_s = [np.empty(cells), np.empty(cells), np.empty(cells)]
    known = 0
    predicted = np.empty(cells)
    status, message, contact = RunStatus.COMPLETED, "", None
    # A closed-loop program reads the displacement samples as they are produced.
    observe = problem.observe
    on_step = problem.on_step

    def result(status: RunStatus, message: str) -> OrbitResult:
        st.past = [(float(times[j] - times[j + 1]), ys[j + 1].copy()) for j in range(count - 1)]
        cp = st.as_checkpoint()
        cp.update(problem.program_checkpoint())
        stats = RunStats(clock, counters[0], counters[1], counters[2], contact, cp)
        return problem.make_result(out, status, message, stats)

    try:
        while st.t < t_end - 1e-12:
            if interrupted():
                raise KeyboardInterrupt  # held by interrupt_at_step_boundary
            t = st.t
            omega = problem.speed(t)
            h = h_nominal = min(step.max_step, 2 * math.pi / (omega * step.steps_per_rev))
            if t_end - t < 2.0 * h:
                # Land on t_end in one step up to h, else in two equal ones: never longer
                # than the cap, and no sliver of a step, whose ratio to the next (after a
                # resume) would upset the BDF.
                h = t_end - t if t_end - t <= h else 0.5 * (t_end - t)
            if count <= order:
                # Start-up: the order rises with the history, and each missing past
                # state halves the step, so that the low-order first steps stay
                # below the error of the full-order ones.
                h *= 2.0 ** (count - 1 - order)
            while True:
                t_new = t + h
                inp, volts = problem.inputs(t_new)
                past = tuple(BdfHistory(times, ys, qs, count))
                c0 = bdf_setup(t_new, past, order, atol, newton.rtol, guess, hist, weights)
                branches = _predicted_branches(
                    lift_s, min(known, count), h, t - times[1] if count > 1 else math.nan,
                    times[1] - times[2] if count > 2 else math.nan, predicted,
                )  # fmt: skip
                ok, y_new, its, lu, lu_c0, nf, q_new, h_min = _step_newton(
                    problem, newton, guess, inp, c0, hist, weights, lu, lu_c0, work, branches
                )
                counters[2] += its
                counters[1] += nf
                if ok:
                    break
                h *= 0.5
                if count > 1 and h < 0.3 * h_nominal:
                    # Failed twice: restart the order from this state (BDF1, then the
                    # start-up), as a history that the film can no longer follow, e.g.
                    # across a lift-off switch near contact, can stall the iteration.
                    count = 1
                if h < 1e-9:
                    raise FloatingPointError(f"time step collapsed at t = {t:.6f} s")
            counters[0] += 1
            if on_step is not None:
                on_step(t_new, y_new, min(order, count))
            lift_s.insert(0, lift_s.pop())  # the oldest row takes the new coordinate
            if lu is not None and lift_coordinate(lu.lift_state, problem.lift_slack, lift_s[0]):
                known = min(known + 1, 3)
            else:
                known = 0
            if newton.refresh_after is not None and its > newton.refresh_after:
                lu = None  # a slow step: the next one takes a fresh factor at its predictor
            # Shift the history by one (rows are reused: no allocation).
            times[1:], ys[1:], qs[1:] = times[:-1], ys[:-1], qs[:-1]
            times[0], ys[0], qs[0] = t_new, y_new, q_new
            count = min(count + 1, depth)
            st.t, st.y = t_new, ys[0].copy()
            problem.record(out, t_new, y_new, volts, inp, h_min)
            if observe is not None:
                for t_s, ex in out.new_samples():
                    observe(t_s, ex)
            if h_min < stop.contact_film:
                w = problem.speed(t_new)
                k = problem.journal
                contact = {
                    "time_s": t_new,
                    "speed_rpm": w / RPM,
                    "angle_deg": math.degrees(math.atan2(y_new[k + 1], y_new[k])),
                    "min_film_um": h_min * problem.clearance * 1e6,
                }
                status = RunStatus.CONTACT
                message = (
                    f"contact at t = {t_new:.4f} s, {w / RPM:.0f} rpm: minimum film "
                    f"{h_min:.3f} C < {stop.contact_film} C, journal at "
                    f"{contact['angle_deg']:.1f} deg from +X"
                )
                break
            if bar is not None:
                bar(t_new, problem.speed(t_new))
            if checkpoint is not None and time.perf_counter() - last_checkpoint > checkpoint_every:
                checkpoint(result(RunStatus.RUNNING, f"checkpoint at t = {t_new:.4f} s"))
                last_checkpoint = time.perf_counter()
    except KeyboardInterrupt:
        status, message = RunStatus.INTERRUPTED, f"interrupted by the user at t = {st.t:.4f} s"
    except ArithmeticError as exc:  # a numerical failure (step collapse, singular factor)
        status, message = RunStatus.FAILED, f"the integration failed at t = {st.t:.4f} s: {exc}"
    finally:
        if bar is not None:
            bar(None, None)
    if status == RunStatus.COMPLETED:
        if st.t < problem.t_end - 1e-9:
            status = RunStatus.STOPPED  # at stop_time: the profile goes on, the run can be resumed
        message = (
            f"{status} at {st.t:.4f} s ({problem.speed(st.t) / RPM:.0f} rpm) after "
            f"{counters[0]} steps"
        )
    return result(status, message)


#: Factor refreshes at the iterate within one step before the step is retried or halved.
_MAX_REFRESH = 3


def _step_newton(
    problem: StepperProblem,
    newton: NewtonRule,
    y0: FloatArray,
    inp: Inputs,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    lu: Factor | None,
    lu_c0: float,
    work: tuple[FloatArray, FloatArray],
    branches: FloatArray | None = None,
) -> tuple[bool, FloatArray, int, Factor | None, float, int, FloatArray, float]:
    """Modified Newton on c0·Q(y) + hist − f(y) = 0 from the guess y0, reusing the factor.

    The iterations with one factor are compiled
    (:meth:`~foilbearing.reynolds.transient_factor.TransientFactor.newton_solve`). A
    factor that converges too slowly (stale, or fresh but contracting at a
    rate above 0.5) is refreshed at the current iterate and the iteration
    goes on from there, up to ``_MAX_REFRESH`` times a step; a fresh factor
    that fails (or a stale one whose iterate closes the film) restarts from
    the guess with a fresh factor, then gives up (the caller halves the step). The
    iteration stops at a fraction of the step's own change (predictor to
    corrector), as BDF codes do: the Newton error then stays well below the
    truncation error of the step. ``work`` holds two state-sized buffers
    (residual, update) reused across iterations. ``branches`` are the
    predicted lift-off branches of the step (:func:`_predicted_branches`): a
    kept factor takes them when few cells move, a new factor is taken with
    them otherwise. Returns ``(converged, y,
    iterations, factor, factor_c0, factorisations, Q(y), min film)``; on
    failure y is the guess and Q is empty.
    """
    controls = (newton.newton_tol, newton.newton_fraction, newton.max_newton)
    q_new = np.empty(problem.size)
    buffers = (work[0], work[1], q_new)
    factorizations = 0
    its = 0
    refreshes = 0
    for attempt in range(2):
        y = y0.copy()
        fresh = lu is None or attempt == 1 or abs(c0 - lu_c0) > 0.2 * c0
        if not fresh and branches is not None and lu is not None:
            # More than MAX_MOVED_KEPT cells off: the factor's held cells are too far
            # from this step's; fewer take the predicted branches.
            fresh = adopt_branches(lu.lift_state, branches, MAX_MOVED_KEPT) > MAX_MOVED_KEPT
        if fresh:
            # Lift-off branches: those predicted for the step, or decided afresh at
            # the guess when the step starts over.
            lu = problem.factorize(y, inp, c0, hist, branches if attempt == 0 else None)
            lu_c0 = c0
            factorizations += 1
        assert lu is not None  # a step without a factor takes a fresh one
        first_change = math.inf
        while True:
            outcome, k, first_change, h_new = lu.newton_solve(
                y, inp, c0, hist, weights, buffers, controls, fresh, first_change
            )
            its += k
            if outcome == NEWTON_CONVERGED:
                return True, y, its, lu, lu_c0, factorizations, q_new, h_new
            if outcome != NEWTON_REFRESH or refreshes >= _MAX_REFRESH:
                break  # closed film, NaN, too slow or diverging: restart fresh, or give up
            refreshes += 1
            # A factor that will not converge in time: refresh it here (with the
            # lift-off branches the iteration has reached), go on from y.
            lu = problem.factorize(y, inp, c0, hist, lu.lift_state)
            lu_c0 = c0
            factorizations += 1
            fresh = True
        if fresh:
            break
    return False, y0, its, None, math.nan, factorizations, np.empty(0), math.nan


def _predicted_branches(
    lift_s: list[FloatArray], known: int, h: float, h1: float, h2: float, out: FloatArray
) -> FloatArray | None:
    """Lift-off branches predicted for a step of h into ``out``: +1 held, −1 free (None:
    no history).

    Extrapolates the boundary coordinate of the last ``known`` accepted steps (at t_n,
    t_n − h1, t_n − h1 − h2; :func:`~foilbearing.reynolds._kernels.lift_coordinate`) to
    t_n + h with the predictor's Lagrange weights
    (:func:`~foilbearing.reynolds._kernels.predict_branches`).
    """
    if known == 0:
        return None
    if known == 1:
        weights = (1.0, 0.0, 0.0)
    elif known == 2:
        weights = (h / h1, 0.0, 0.0)
    else:
        t1, t2 = -h1, -h1 - h2
        weights = (
            (h - t1) * (h - t2) / (t1 * t2),
            h * (h - t2) / (t1 * (t1 - t2)),
            h * (h - t1) / (t2 * (t2 - t1)),
        )
    predict_branches(lift_s[0], lift_s[1], lift_s[2], known, weights, out)
    return out
