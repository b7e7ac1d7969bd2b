"""The generic integrator on a problem that is no bearing: a linear system dy/dt = A y.

``foilbearing.integrate`` knows nothing of the film: here it integrates a damped
oscillator written in a few lines of NumPy, with a Newton iteration of its own that
decides by the integrator's one Newton policy. Its order, its stop event and its
interrupt are checked against the exact solution and against an uninterrupted run.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from foilbearing.integrate import NewtonRule, Problem, State, Status, StepControl, integrate
from foilbearing.integrate.bdf import bdf_error, bdf_setup
from foilbearing.integrate.newton import (
    NEWTON_CONTINUE,
    NEWTON_CONVERGED,
    newton_progress,
    newton_verdict,
)

#: A damped oscillator x'' + 2ζω x' + ω² x = 0 as y = (x, x'), ω = 2π, ζ = 0.1.
OMEGA, ZETA = 2.0 * math.pi, 0.1
A = np.array([[0.0, 1.0], [-(OMEGA**2), -2.0 * ZETA * OMEGA]])
Y0 = np.array([1.0, 0.0])
NEWTON = NewtonRule(newton_tol=1e-6, newton_fraction=1e-9, max_newton=8, rtol=1e-12)


def exact(t: float) -> np.ndarray:
    """y(t) from Y0: the matrix exponential through the eigenvalues of A."""
    lam, vec = np.linalg.eig(A)
    return np.real(vec @ (np.exp(lam * t) * np.linalg.solve(vec, Y0)))


class LinearFactor:
    """(c0 I − A)⁻¹ at the c0 of its step; Newton iterations under the integrator's policy."""

    def __init__(self, c0: float) -> None:
        self.inverse = np.linalg.inv(c0 * np.eye(2) - A)

    def newton_solve(
        self,
        y: np.ndarray,
        args: Any,
        c0: float,
        hist: np.ndarray,
        weights: np.ndarray,
        work: tuple[np.ndarray, np.ndarray, np.ndarray],
        controls: tuple[float, float, int],
        fresh: bool,
        first_change: float,
    ) -> tuple[int, int, float, float]:
        newton_tol, newton_fraction, max_newton = controls
        prev, k = math.inf, 0
        while True:
            k += 1
            dy = self.inverse @ (c0 * y + hist - A @ y)
            y -= dy
            err = float(np.max(np.abs(dy) * weights))
            converged, rate, tol, first_change = newton_progress.py_func(
                err, prev, k, first_change, newton_tol, newton_fraction
            )
            if converged:
                work[2][:] = y  # the storage Q(y) = y
                return NEWTON_CONVERGED, k, first_change, float(y[0])  # monitor: x
            verdict = newton_verdict.py_func(err, rate, tol, k, max_newton, fresh, False, False)
            if verdict != NEWTON_CONTINUE:
                return verdict, k, first_change, math.nan
            prev = err


def problem(step: float) -> Problem:
    return Problem(
        size=2,
        step_size=lambda t: step,
        inputs=lambda t: (None, None),
        storage=lambda y, args: y.copy(),
        factorize=lambda y, args, c0, hist, hint: LinearFactor(c0),
        atol=np.full(2, 1e-10),
    )


def run(step: float, order: int, t1: float = 1.0, **kw: Any) -> tuple[State, Any, list]:
    seen: list[tuple[float, int]] = []
    st = State(0.0, Y0.copy())

    def record(t: float, y: np.ndarray, args: Any, extra: Any, monitor: Any, k: int) -> None:
        seen.append((t, k))

    sol = integrate(problem(step), st, t1, order, NEWTON, record, **kw)
    return st, sol, seen


@pytest.mark.parametrize("order", [1, 2])
def test_the_bdf_error_falls_as_the_step_to_its_order(order: int) -> None:
    # BDF of order k: global error O(h^k), so halving the step divides the error at
    # t = 1 by 2^k. Measured ratios 2.00 and 3.99 at h = 1/200 -> 1/400.
    errors = []
    for step in (1 / 200, 1 / 400):
        st, sol, _ = run(step, order)
        assert sol.status == Status.COMPLETED and st.t == pytest.approx(1.0, abs=1e-12)
        errors.append(float(np.max(np.abs(st.y - exact(1.0)))))
    assert errors[0] / errors[1] == pytest.approx(2.0**order, rel=0.05)


def test_bdf3_beats_bdf2_and_its_start_up_keeps_a_small_second_order_error() -> None:
    # BDF3's own error falls as h³, but its start-up steps (BDF1 at h/8, BDF2 at h/4)
    # leave a second-order error with a small constant: the ratio of the errors at
    # h = 1/200 and 1/400 lies between 4 and 8 (measured 6.2), and the error is 100
    # times below BDF2's at the same step (measured 185).
    third = [float(np.max(np.abs(run(h, 3)[0].y - exact(1.0)))) for h in (1 / 200, 1 / 400)]
    second = float(np.max(np.abs(run(1 / 400, 2)[0].y - exact(1.0))))
    assert 5.0 < third[0] / third[1] < 8.0
    assert third[1] < second / 100.0


def test_the_record_sees_each_step_and_its_order_rising_through_the_start_up() -> None:
    _, sol, seen = run(1 / 100, 3)
    assert seen[0] == (0.0, 0)  # the start state, before any step
    assert [k for _, k in seen[1:5]] == [1, 2, 3, 3]
    assert len(seen) - 1 == sol.steps and [t for t, _ in seen] == sorted(t for t, _ in seen)


def test_a_stop_event_ends_the_run_at_the_first_step_past_it() -> None:
    # x first crosses zero at the quarter damped period plus the phase of the decay:
    # t* = (π/2 + atan(ζ/√(1 − ζ²)))/ω_d. The run stops at the first step past it.
    step = 1 / 400
    st, sol, _ = run(step, 3, events=(lambda t, y, monitor: monitor < 0.0,))
    omega_d = OMEGA * math.sqrt(1.0 - ZETA**2)
    crossing = (math.pi / 2 + math.atan(ZETA / math.sqrt(1.0 - ZETA**2))) / omega_d
    assert sol.status == Status.EVENT and sol.event == 0 and sol.monitor < 0.0
    assert crossing <= st.t < crossing + step


def test_an_interrupted_run_resumes_from_its_state_to_the_uninterrupted_one() -> None:
    # The state after an interrupt holds its BDF history: the resumed run takes the
    # same steps as the whole one and ends on the same state within the Newton tolerance.
    whole, done, _ = run(1 / 100, 3)
    calls = iter(range(10**6))
    part, sol, _ = run(1 / 100, 3, interrupted=lambda: next(calls) == 37)
    assert sol.status == Status.INTERRUPTED and 0.3 < part.t < 0.4 and len(part.past) == 3
    seen: list[float] = []
    rest = integrate(
        problem(1 / 100), part, 1.0, 3, NEWTON, lambda t, *a: seen.append(t), counts=(37, 0, 0)
    )
    assert rest.status == Status.COMPLETED and rest.steps == done.steps
    # The resumed run starts with a fresh factor, the whole one kept its own: their Newton
    # iterates differ within the tolerance (measured 4e-12 at the end).
    np.testing.assert_allclose(part.y, whole.y, rtol=1e-10)


def adaptive(order: int, rtol: float, **kw: Any) -> tuple[State, Any, np.ndarray]:
    """The oscillator to t = 1 on error-controlled steps (at most 0.05), first step 1/400;
    the Newton rule's weights carry the error test's rtol."""
    times: list[float] = []
    st = State(0.0, Y0.copy())
    newton = NewtonRule(newton_tol=1e-6, newton_fraction=1e-9, max_newton=8, rtol=rtol)
    control = StepControl(rtol, lambda t: 0.05)
    sol = integrate(
        problem(1 / 400), st, 1.0, order, newton, lambda t, *a: times.append(t), control=control,
        **kw,
    )  # fmt: skip
    return st, sol, np.array(times)


@pytest.mark.parametrize("order", [2, 3, 4])
def test_the_local_error_estimate_is_the_actual_local_error_of_a_variable_step(
    order: int,
) -> None:
    # On the adaptive run's own (unequal) steps, each step taken from the exact history
    # (the true local truncation error of the variable-step BDF): the estimate from the
    # predictor-corrector difference (bdf_error) against the corrector's actual error, in
    # the same weighted norm. Measured est/actual at rtol = 1e-6: 0.99-1.03 (BDF2),
    # 0.76-1.02 (BDF3), 0.94-1.16 (BDF4); it tends to 1 as the steps shrink. The error
    # test therefore holds the actual local error to the tolerance within a factor 1.5.
    rtol = 1e-6
    _, sol, ts = adaptive(order, rtol)
    assert sol.status == Status.COMPLETED and sol.steps > 50
    steps = np.diff(ts)
    assert steps.max() / steps.min() > 3.0  # the steps do vary
    atol = np.full(2, 1e-10)
    ratios, scaled = [], []
    for i in range(order + 1, ts.size):
        times = ts[i - 1 :: -1][: order + 1].copy()
        ys = np.array([exact(t) for t in times])
        guess, hist, weights = np.empty(2), np.empty(2), np.empty(2)
        c0 = bdf_setup(
            ts[i], (times, ys, ys.copy(), order + 1), order, atol, rtol, guess, hist, weights
        )
        y = np.linalg.solve(c0 * np.eye(2) - A, -hist)  # the linear BDF step, solved exactly
        estimate = bdf_error(y, guess, weights, c0, ts[i] - times[order], 1.0)
        actual = float(np.max(np.abs(y - exact(ts[i])) * weights))
        ratios.append(estimate / actual)
        scaled.append(actual)
    assert 0.6 < min(ratios) and max(ratios) < 1.4
    assert max(scaled) < 1.5  # the accepted steps' actual local errors, in units of rtol


@pytest.mark.parametrize("order", [2, 3])
def test_the_global_error_of_adaptive_steps_scales_with_the_tolerance(order: int) -> None:
    # Error per step held to tol: the steps scale as tol^(1/(q+1)) and the global error
    # as tol^(q/(q+1)), 10^(2/3) = 4.6 and 10^(3/4) = 5.6 a decade of tol (measured 4.6
    # and 4.8-5.9 over 1e-5 .. 1e-7). Each decade divides the error by 3 to 10, and the
    # steps taken grow by at most 10^(1/(q+1)) times 1.4.
    errors, steps = [], []
    for rtol in (1e-5, 1e-6, 1e-7):
        st, sol, _ = adaptive(order, rtol)
        assert sol.status == Status.COMPLETED and st.t == pytest.approx(1.0, abs=1e-12)
        errors.append(float(np.max(np.abs(st.y - exact(1.0)))))
        steps.append(sol.steps)
    for k in range(2):
        assert 3.0 < errors[k] / errors[k + 1] < 10.0
        assert 1.0 < steps[k + 1] / steps[k] < 1.4 * 10 ** (1 / (order + 1))


def test_adaptive_steps_keep_to_the_maximum_step_and_fire_the_stop_event() -> None:
    # The longest step is the one passed in; the stop event still ends the run at the
    # first step past x's zero crossing.
    _, sol, ts = adaptive(3, 1e-3)
    assert np.diff(ts).max() <= 0.05 + 1e-15
    st, sol, ts = adaptive(3, 1e-6, events=(lambda t, y, monitor: monitor < 0.0,))
    omega_d = OMEGA * math.sqrt(1.0 - ZETA**2)
    crossing = (math.pi / 2 + math.atan(ZETA / math.sqrt(1.0 - ZETA**2))) / omega_d
    assert sol.status == Status.EVENT and sol.event == 0 and sol.monitor < 0.0
    assert ts[-2] < crossing <= st.t


def test_an_interrupted_adaptive_run_resumes_with_its_next_step_to_the_same_steps() -> None:
    # The state keeps the step the error control chose (h_next, in its checkpoint): the
    # resumed run takes the uninterrupted run's steps and ends on its state.
    whole, _, ts = adaptive(3, 1e-6)
    calls = iter(range(10**6))
    part, sol, first = adaptive(3, 1e-6, interrupted=lambda: next(calls) == 40)
    assert sol.status == Status.INTERRUPTED and math.isfinite(part.h_next)
    back = State.from_checkpoint(part.as_checkpoint())
    assert back.h_next == part.h_next and len(back.past) == 3
    newton = NewtonRule(newton_tol=1e-6, newton_fraction=1e-9, max_newton=8, rtol=1e-6)
    rest: list[float] = []
    more = integrate(
        problem(1 / 400), back, 1.0, 3, newton, lambda t, *a: rest.append(t),
        control=StepControl(1e-6, lambda t: 0.05),
    )  # fmt: skip
    # The resumed run starts with a fresh factor: its Newton iterates, hence its error
    # estimates and steps, differ from the whole run's within the Newton tolerance
    # (measured: the step times by 2e-8 relative at the end).
    assert more.status == Status.COMPLETED and len(first) + len(rest) - 1 == len(ts)
    np.testing.assert_allclose(np.concatenate([first, rest[1:]]), ts, rtol=1e-6)
    np.testing.assert_allclose(back.y, whole.y, rtol=1e-6)
