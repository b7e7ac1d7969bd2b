"""Held stingers in the orbit: the stacks' quasi-static compression along a run.

Under ``[actuators] dynamics = "held"`` (docs/model.md §3.8) the stinger keeps
the position the stack takes at the present speed and voltages in equilibrium:
a voltage ramp or the speed still moves it, the whirl does not. Its compression
enters the film as a prescribed input, the opening it adds to the rigid film
(units of C, per θ-cell):

- ``preload_response = "local"``: the pocket ``(1/k(θ) − 1/k_b) p_a max(q_s, 0)/C``
  of the quasi-static pressure q_s;
- ``"lobe"``: the lowered lobes ``Σ_n D_n,s lobe_n(θ)``.

The quasi-static film comes from :func:`foilbearing.analysis.equilibrium.solve_equilibrium`
at knots in time, each started from the last, placed so that between two knots
the speed changes by at most ``speed_step`` and every voltage by at most
``voltage_step``; between knots the opening is interpolated linearly in time.
Knots are laid from t = 0 forward, whatever time is asked first, so a resumed
run sees the same input as the uninterrupted one.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from foilbearing.analysis.equilibrium import solve_equilibrium
from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import SolverError

__all__ = ["HeldStingers"]

FloatArray = NDArray[np.float64]


class HeldStingers:
    """The opening (h/C, per θ-cell) that the held stacks' compression adds to the film.

    Parameters
    ----------
    case
        The run's case (its actuator reading decides pocket or lobes).
    speed, volts
        ω(t) in rad/s and the actuator voltages V(t), known ahead of time
        (open-loop programs).
    duration
        The run's end, s.
    speed_step, voltage_step
        Largest change of ω (rad/s) and of any voltage (V) between two knots.
    max_interval
        Largest time between two knots, s.
    """

    def __init__(
        self,
        case: Case,
        speed: Callable[[float], float],
        volts: Callable[[float], FloatArray],
        duration: float,
        *,
        speed_step: float = 50.0,
        voltage_step: float = 2.0,
        max_interval: float = 0.25,
    ) -> None:
        self.case = case
        self.speed, self.volts, self.duration = speed, volts, duration
        self.speed_step, self.voltage_step, self.max_interval = (
            speed_step,
            voltage_step,
            max_interval,
        )
        self.times: list[float] = []
        self.openings: list[FloatArray] = []
        self._start: tuple[float, float, FloatArray] | None = None

    def _opening_at(self, t: float) -> FloatArray:
        """The held compression's opening at the equilibrium of ω(t), V(t)."""
        volts = tuple(float(v) for v in self.volts(t))
        case = self.case.with_voltages(volts)
        st = solve_equilibrium(case, speed=self.speed(t), model=None, start=self._start)
        if not st.converged:
            raise SolverError(
                f"no static equilibrium for the held stingers at t = {t:.4g} s "
                f"({self.speed(t) / RPM:.0f} rpm, {volts} V): {st.message}; "
                "try dynamics = 'compliant' or a lower load"
            )
        self._start = (st.eps_x, st.eps_y, st.P)
        m = st.model
        if m.lobe:
            assert m.lobe_shapes is not None
            return m.stack_compression(st.P) @ m.lobe_shapes
        return m.actuator_compliance * np.maximum(m.grid.gauge_mean(st.P), 0.0)

    def _next_time(self, t: float) -> float:
        """The next knot after ``t``: halve the interval until ω and V change little."""
        h = self.max_interval
        w0, v0 = self.speed(t), np.asarray(self.volts(t), float)
        while h > 1e-4:
            t1 = min(t + h, self.duration)
            dw = abs(self.speed(t1) - w0)
            dv = float(np.max(np.abs(np.asarray(self.volts(t1), float) - v0), initial=0.0))
            if dw <= self.speed_step and dv <= self.voltage_step:
                return t1
            h *= 0.5
        return min(t + h, self.duration)

    def __call__(self, t: float) -> FloatArray:
        """The opening at time t (s), shape (n_theta,), in units of C."""
        if not self.times:
            self.times.append(0.0)
            self.openings.append(self._opening_at(0.0))
        while self.times[-1] < min(t, self.duration):
            t_next = self._next_time(self.times[-1])
            self.times.append(t_next)
            self.openings.append(self._opening_at(t_next))
        if t >= self.times[-1]:
            return self.openings[-1]
        k = max(bisect.bisect_right(self.times, t) - 1, 0)
        t0, t1 = self.times[k], self.times[k + 1]
        f = (t - t0) / (t1 - t0)
        return (1.0 - f) * self.openings[k] + f * self.openings[k + 1]
