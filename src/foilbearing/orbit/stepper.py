"""The orbit on the BDF integrator: its lift-off branches, its contact and its result.

:func:`run` hands a :class:`~foilbearing.orbit.problem.StepperProblem` to the generic
integrator (:func:`foilbearing.integrate.integrate`: the variable-order BDF, the one
modified-Newton policy, stop events and a record callback) with the orbit's own parts:
the time step from the speed (a number of steps a revolution), the lift-off branches
predicted for each step (:class:`LiftOffBranches`), the contact as a stop event, and the
words and units of its messages and of its :class:`~foilbearing.orbit.result.OrbitResult`.
See :mod:`foilbearing.orbit` for the method and docs/numerics.md §8 for the details.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from foilbearing.constants import RPM
from foilbearing.integrate import (
    Problem,
    Solution,
    State,
    Status,
    StepCollapsed,
    StepControl,
    integrate,
    interrupt_at_step_boundary,
)
from foilbearing.orbit.problem import Factor, RunStats, StepperProblem
from foilbearing.orbit.result import OrbitResult, RunStatus
from foilbearing.orbit.sampling import Samples, progress_bar
from foilbearing.orbit.settings import ADAPTIVE_MAX_STEP_REV, NewtonRule, StepRule, StopRule
from foilbearing.reynolds._kernels import (
    MAX_MOVED_KEPT,
    adopt_branches,
    lift_coordinate,
    predict_branches,
)
from foilbearing.reynolds.transient import Inputs

__all__ = ["LiftOffBranches", "State", "ending", "interrupt_at_step_boundary", "run"]

FloatArray = NDArray[np.float64]


class LiftOffBranches:
    """The lift-off branches of the film's cells as the integrator's switched rows.

    Keeps the boundary coordinate (:func:`~foilbearing.reynolds._kernels.lift_coordinate`)
    of the last three accepted steps, newest first, of which the first ``known`` are
    known, and extrapolates it to predict the branches of the next step; a kept factor
    takes them when few cells (``MAX_MOVED_KEPT``) move.

    Parameters
    ----------
    slack
        The residual's lift-off slack of each cell (−G/d on a held cell, P − 1 on a free
        one) at the last iterate, an array the residual writes in place.
    """

    def __init__(self, slack: FloatArray) -> None:
        self.slack = slack
        cells = slack.shape[0]
        self.coordinates = [np.empty(cells), np.empty(cells), np.empty(cells)]
        self.known = 0
        self.predicted = np.empty(cells)

    def predict(self, h: float, h1: float, h2: float, count: int) -> FloatArray | None:
        """Branches predicted for a step of h into ``predicted``: +1 held, −1 free (None:
        no history).

        Extrapolates the boundary coordinate of the last known accepted steps (at t_n,
        t_n − h1, t_n − h1 − h2) to t_n + h with the predictor's Lagrange weights
        (:func:`~foilbearing.reynolds._kernels.predict_branches`).
        """
        known = min(self.known, count)
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
        s = self.coordinates
        predict_branches(s[0], s[1], s[2], known, weights, self.predicted)
        return self.predicted

    def adopt(self, factor: Factor, hint: FloatArray) -> bool:
        """A kept factor takes the predicted branches unless more than ``MAX_MOVED_KEPT``
        cells are off them (its held cells are then too far from this step's)."""
        return adopt_branches(factor.lift_state, hint, MAX_MOVED_KEPT) <= MAX_MOVED_KEPT

    def reached(self, factor: Factor) -> FloatArray:
        """The branches the factor's iteration has reached."""
        return factor.lift_state

    def accepted(self, factor: Factor | None) -> None:
        """The boundary coordinate of the accepted step (none known without a factor or
        without branches: suction retained)."""
        s = self.coordinates
        s.insert(0, s.pop())  # the oldest row takes the new coordinate
        if factor is not None and lift_coordinate(factor.lift_state, self.slack, s[0]):
            self.known = min(self.known + 1, 3)
        else:
            self.known = 0


def ending(
    sol: Solution, t: float, t_end: float, speed: Callable[[float], float]
) -> tuple[RunStatus, str]:
    """The run's status and message for an integration that ended at t without a stop
    event (the caller words its contact): ``t_end`` is the end of the speed profile (s)
    and ``speed(t)`` the speed (rad/s)."""
    if sol.status == Status.INTERRUPTED:
        return RunStatus.INTERRUPTED, f"interrupted by the user at t = {t:.4f} s"
    if sol.status == Status.FAILED:
        exc = sol.error
        why = f"time step collapsed at t = {exc.t:.6f} s" if isinstance(exc, StepCollapsed) else exc
        return RunStatus.FAILED, f"the integration failed at t = {t:.4f} s: {why}"
    if sol.status == Status.RUNNING:
        return RunStatus.RUNNING, f"checkpoint at t = {t:.4f} s"
    # At stop_time the profile goes on: the run can be resumed.
    status = RunStatus.STOPPED if t < t_end - 1e-9 else RunStatus.COMPLETED
    return status, f"{status} at {t:.4f} s ({speed(t) / RPM:.0f} rpm) after {sol.steps} steps"


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
        :func:`~foilbearing.integrate.interrupt_at_step_boundary`).
    counts
        Steps, factorisations and Newton iterations before ``st`` (a resumed run's),
        so that the result's counts are the whole run's.
    """
    t_end = problem.t_end if stop.stop_time is None else min(stop.stop_time, problem.t_end)
    clock = time.perf_counter()
    bar = progress_bar(progress, t_end, st.t)
    speed, steps_per_rev, max_step = problem.speed, step.steps_per_rev, step.max_step
    record, observe, on_step = problem.record, problem.observe, problem.on_step
    contact_film = stop.contact_film

    def step_size(t: float) -> float:
        """Steps per revolution at the speed of t, capped."""
        return min(max_step, 2 * math.pi / (speed(t) * steps_per_rev))

    def longest_step(t: float) -> float:
        """The longest error-controlled step: a tenth of a revolution, capped."""
        return min(max_step, 2 * math.pi * ADAPTIVE_MAX_STEP_REV / speed(t))

    # The error test reads the journal's position and velocity (the orbit's output): the
    # film's pressures, stiff and with kinks where cells lift off, would ask for 2-3
    # times more steps for the same orbit (0.05 s at 20 krpm, 100 V, 8.5 g·mm: e_X
    # within 1.2 % of 128 steps a revolution at about 1000 steps on every row, 356 on these).
    journal = slice(problem.journal, problem.journal + 4)
    control = None if step.rtol is None else StepControl(step.rtol, longest_step, rows=journal)

    def recorded(
        t: float,
        y: FloatArray,
        inp: Inputs,
        volts: FloatArray,
        h_min: float | None,
        order: int,
    ) -> None:
        if on_step is not None and order > 0:
            on_step(t, y, order)
        record(out, t, y, volts, inp, h_min)
        if observe is not None and order > 0:
            # A closed-loop program reads the displacement samples as they are produced.
            for t_s, ex in out.new_samples():
                observe(t_s, ex)

    def contact(t: float, y: FloatArray, h_min: float) -> bool:
        return h_min < contact_film

    def result(sol: Solution) -> OrbitResult:
        touched = None
        if sol.status == Status.EVENT:
            w = speed(st.t)
            k = problem.journal
            touched = {
                "time_s": st.t,
                "speed_rpm": w / RPM,
                "angle_deg": math.degrees(math.atan2(st.y[k + 1], st.y[k])),
                "min_film_um": sol.monitor * problem.clearance * 1e6,
            }
            status = RunStatus.CONTACT
            message = (
                f"contact at t = {st.t:.4f} s, {w / RPM:.0f} rpm: minimum film "
                f"{sol.monitor:.3f} C < {contact_film} C, journal at "
                f"{touched['angle_deg']:.1f} deg from +X"
            )
        else:
            status, message = ending(sol, st.t, problem.t_end, speed)
        cp = st.as_checkpoint()
        cp.update(problem.program_checkpoint())
        stats = RunStats(clock, sol.steps, sol.factorizations, sol.newton_iterations, touched, cp)
        return problem.make_result(out, status, message, stats)

    def save(sol: Solution) -> None:
        assert checkpoint is not None
        checkpoint(result(sol))

    generic = Problem(
        size=problem.size,
        step_size=step_size,
        inputs=problem.inputs,
        storage=problem.storage,
        factorize=problem.factorize,
        atol=problem.atol,
        switching=LiftOffBranches(problem.lift_slack),
    )
    try:
        sol = integrate(
            generic,
            st,
            t_end,
            step.order,
            newton,
            recorded,
            events=(contact,),
            progress=None if bar is None else lambda t: bar(t, speed(t)),
            checkpoint=None if checkpoint is None else save,
            checkpoint_every=checkpoint_every,
            interrupted=interrupted,
            counts=counts,
            control=control,
        )
    finally:
        if bar is not None:
            bar(None, None)
    return result(sol)
