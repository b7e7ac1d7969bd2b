"""The variable-step BDF stepper of the orbit, its modified Newton iteration and its checkpoint.

See :mod:`foilbearing.orbit` for the method and docs/numerics.md §8 for the details.
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
from foilbearing.orbit.result import OrbitResult, RunStatus
from foilbearing.orbit.sampling import Samples, progress_bar
from foilbearing.orbit.settings import MAX_ORDER
from foilbearing.orbit.system import OrbitSimulation
from foilbearing.reynolds._kernels import MAX_MOVED_KEPT
from foilbearing.reynolds.transient import (
    NEWTON_CONVERGED,
    NEWTON_REFRESH,
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
    sim: OrbitSimulation,
    st: State,
    out: Samples,
    progress: bool | Callable[[float, float], None],
    stop_time: float | None,
    checkpoint: Callable[[OrbitResult], None] | None,
    checkpoint_every: float,
    interrupted: Callable[[], bool] = lambda: False,
) -> OrbitResult:
    s, sys_ = sim.settings, sim.system
    t_end = sim.profile.duration if stop_time is None else min(stop_time, sim.profile.duration)
    clock = time.perf_counter()
    last_checkpoint = clock
    bar = progress_bar(progress, t_end, st.t)
    volts = sim.volts(st.t)
    inp = sim.inputs(st.t, volts)
    # Accepted states, newest first: times, states y and storages Q (the BDF history).
    depth = s.order + 1
    times, ys, qs = np.empty(depth), np.empty((depth, sys_.size)), np.empty((depth, sys_.size))
    count = 1 + min(len(st.past), s.order)
    times[0], ys[0] = st.t, st.y
    for j, (h_j, y_j) in enumerate(st.past[: count - 1]):
        times[j + 1], ys[j + 1] = times[j] - h_j, y_j
    for j in range(count):
        qs[j] = sys_.storage(ys[j], sim.inputs(times[j], sim.volts(float(times[j]))))
    out.add(st.t, st.y, sim, volts, inp)
    lu, lu_c0 = None, math.nan
    work = (np.empty(sys_.size), np.empty(sys_.size))  # Newton residual and update buffers
    guess, hist, weights = np.empty(sys_.size), np.empty(sys_.size), np.empty(sys_.size)
    atol = sim.atol()
    counters = [0, 0, 0]  # steps, factorizations, Newton iterations
    # Lift-off boundary coordinate at the last three accepted steps (None: unknown).
    lift_s: list[FloatArray | None] = [None, None, None]
    status, message, contact = RunStatus.COMPLETED, "", None
    # A closed-loop program reads the displacement samples as they are produced.
    observer = sim.voltage if sim.voltage is not None and sim.voltage.observes else None

    def result(status: RunStatus, message: str) -> OrbitResult:
        st.past = [(float(times[j] - times[j + 1]), ys[j + 1].copy()) for j in range(count - 1)]
        cp = st.as_checkpoint()
        if sim.voltage is not None:
            cp.update(sim.voltage.checkpoint())
        t_s, e_x, e_y, speed, phase, h_min, volts_s, power = out.arrays(sim.n_act, sim.profile)
        return OrbitResult(
            sim.case,
            s,
            t_s,
            e_x,
            e_y,
            speed,
            phase,
            h_min,
            volts_s,
            power_loss=power,
            status=status,
            message=message,
            wall_time=time.perf_counter() - clock,
            steps=counters[0],
            factorizations=counters[1],
            newton_iterations=counters[2],
            contact=contact,
            checkpoint=cp,
        )

    try:
        while st.t < t_end - 1e-12:
            if interrupted():
                raise KeyboardInterrupt  # held by interrupt_at_step_boundary
            t = st.t
            omega = sim.profile.state(t)[0]
            h = h_nominal = min(s.max_step, 2 * math.pi / (omega * s.steps_per_rev))
            if t_end - t < 2.0 * h:
                # Land on t_end in one step up to h, else in two equal ones: never longer
                # than the cap, and no sliver of a step, whose ratio to the next (after a
                # resume) would upset the BDF.
                h = t_end - t if t_end - t <= h else 0.5 * (t_end - t)
            if count <= s.order:
                # Start-up: the order rises with the history, and each missing past
                # state halves the step, so that the low-order first steps stay
                # below the error of the full-order ones.
                h *= 2.0 ** (count - 1 - s.order)
            while True:
                t_new = t + h
                volts = sim.volts(t_new)
                inp = sim.inputs(t_new, volts)
                c0 = bdf_setup(
                    t_new, times, ys, qs, count, s.order, atol, s.rtol, guess, hist, weights
                )
                branches = _predicted_branches(
                    lift_s[0], lift_s[1], lift_s[2], h,
                    t - times[1] if count > 1 else None,
                    times[1] - times[2] if count > 2 else None,
                )  # fmt: skip
                ok, y_new, its, lu, lu_c0, nf, q_new, h_min = _step_newton(
                    sim, guess, inp, c0, hist, weights, lu, lu_c0, work, branches
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
            lift_s = [_lift_coordinate(lu, sys_._slack), lift_s[0], lift_s[1]]
            # Shift the history by one (rows are reused: no allocation).
            times[1:], ys[1:], qs[1:] = times[:-1], ys[:-1], qs[:-1]
            times[0], ys[0], qs[0] = t_new, y_new, q_new
            count = min(count + 1, depth)
            st.t, st.y = t_new, ys[0].copy()
            out.add(t_new, y_new, sim, volts, inp, min_film=h_min)
            if observer is not None:
                for t_s, ex in out.new_samples():
                    observer.observe(t_s, ex, sim.profile.phase(t_s))
            if h_min < s.contact_film:
                w = sim.profile.omega(t_new)
                k = sys_.n + sys_.nt
                contact = {
                    "time_s": t_new,
                    "speed_rpm": w / RPM,
                    "angle_deg": math.degrees(math.atan2(y_new[k + 1], y_new[k])),
                    "min_film_um": h_min * sim.case.bearing.clearance * 1e6,
                }
                status = RunStatus.CONTACT
                message = (
                    f"contact at t = {t_new:.4f} s, {w / RPM:.0f} rpm: minimum film "
                    f"{h_min:.3f} C < {s.contact_film} C, journal at "
                    f"{contact['angle_deg']:.1f} deg from +X"
                )
                break
            if bar is not None:
                bar(t_new, sim.profile.omega(t_new))
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
        if st.t < sim.profile.duration - 1e-9:
            status = RunStatus.STOPPED  # at stop_time: the profile goes on, the run can be resumed
        message = (
            f"{status} at {st.t:.4f} s ({sim.profile.omega(st.t) / RPM:.0f} rpm) after "
            f"{counters[0]} steps"
        )
    return result(status, message)


#: Factor refreshes at the iterate within one step before the step is retried or halved.
_MAX_REFRESH = 3


def _step_newton(
    sim: OrbitSimulation,
    y0: FloatArray,
    inp: Inputs,
    c0: float,
    hist: FloatArray,
    weights: FloatArray,
    lu: Any,
    lu_c0: float,
    work: tuple[FloatArray, FloatArray],
    branches: FloatArray | None = None,
) -> tuple[bool, FloatArray, int, Any, float, int, FloatArray, float]:
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
    s, sys_ = sim.settings, sim.system
    controls = (s.newton_tol, s.newton_fraction, s.max_newton)
    q_new = np.empty(sys_.size)
    buffers = (work[0], work[1], q_new)
    factorizations = 0
    its = 0
    refreshes = 0
    for attempt in range(2):
        y = y0.copy()
        fresh = lu is None or attempt == 1 or abs(c0 - lu_c0) > 0.2 * c0
        if not fresh and branches is not None and lu is not None:
            moved = np.count_nonzero((lu.lift_state > 0.0) != (branches > 0.0))
            if moved > MAX_MOVED_KEPT:
                fresh = True  # the factor's held cells are too far from this step's
            elif moved:
                lu.lift_state[:] = np.where(branches > 0.0, 1.0, -1.0) * np.abs(lu.lift_state)
        if fresh:
            # Lift-off branches: those predicted for the step, or decided afresh at
            # the guess when the step starts over.
            lu = sys_.factorize(y, inp, c0, hist, branches if attempt == 0 else None)
            lu_c0 = c0
            factorizations += 1
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
            lu = sys_.factorize(y, inp, c0, hist, lu.lift_state)
            lu_c0 = c0
            factorizations += 1
            fresh = True
        if fresh:
            break
    return False, y0, its, None, math.nan, factorizations, np.empty(0), math.nan


def _lift_coordinate(lu: Any, slack: FloatArray) -> FloatArray | None:
    """The signed distance of each cell from the lift-off boundary at a converged step.

    ``P − 1 − G/d``: ``P − 1 >= 0`` on a free cell, ``−G/d <= 0`` on a held one
    (the slack of the residual kernel, sign-corrected); it moves smoothly as
    the boundary moves, so its extrapolation predicts the next step's branches.
    None without lift-off.
    """
    if lu is None or not np.any(lu.lift_state):
        return None
    return np.where(lu.lift_state > 0.0, slack, -slack)


def _predicted_branches(
    s0: FloatArray | None,
    s1: FloatArray | None,
    s2: FloatArray | None,
    h: float,
    h1: float | None,
    h2: float | None,
) -> FloatArray | None:
    """Lift-off branches predicted for a step of h: +1 held, −1 free (None: no history).

    Extrapolates the boundary coordinate of the last accepted steps (t_n, t_n − h1,
    t_n − h1 − h2) to t_n + h with the predictor's Lagrange weights.
    """
    if s0 is None:
        return None
    if s1 is None or h1 is None:
        pred = s0
    elif s2 is None or h2 is None:
        pred = s0 + (h / h1) * (s0 - s1)
    else:
        t1, t2 = -h1, -h1 - h2
        l0 = (h - t1) * (h - t2) / (t1 * t2)
        l1 = h * (h - t2) / (t1 * (t1 - t2))
        l2 = h * (h - t1) / (t2 * (t2 - t1))
        pred = l0 * s0 + l1 * s1 + l2 * s2
    return np.where(pred < 0.0, 1.0, -1.0)
