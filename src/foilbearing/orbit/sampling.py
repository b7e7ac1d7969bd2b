"""Output of an orbit run: the samples at a fixed rate, interpolated between steps, and the progress bar."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from foilbearing.bearing_system import Scales
from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.control import SpeedProfile
from foilbearing.film import drag_torque
from foilbearing.orbit.result import OrbitResult
from foilbearing.reynolds.transient import Inputs, TransientSystem

__all__ = ["POWER_INTERVAL", "Samples", "backward_cubic", "progress_bar"]

FloatArray = NDArray[np.float64]

#: Simulated time between two evaluations of the film's power loss, s (it is
#: averaged over runs of seconds; 1 ms keeps its cost below 1 % of a step's).
POWER_INTERVAL = 1e-3


def backward_cubic(ts: FloatArray, t: FloatArray, x: FloatArray) -> FloatArray:
    """x at the times ``ts`` by the cubic through the recorded step that ends at or after
    each time and the three before it (the BDF3 interpolant of that step), linear before
    the fourth recorded step; ``t`` increasing, ``ts`` within [t[0], t[-1]]. A sample
    depends on no step after the one that covers it, so that a controller reading the
    samples as the run goes (:meth:`Samples.new_samples`) sees the stored ones.

    Of the error-controlled steps, up to a tenth of a revolution long: linear
    interpolation would miss a 1X orbit by up to (ωΔt)²/8 = 5 % of its amplitude there,
    the cubic by 0.04 (ωΔt)⁴ = 0.6 % (0.04 % at 20 steps a revolution).
    """
    if t.size < 4:
        return np.interp(ts, t, x)
    after = np.searchsorted(t, ts - 1e-12, side="left")
    at = np.clip(after, 3, t.size - 1)
    nodes = at[:, None] - np.arange(4)[None, :]  # the step after, then the three before
    tn, xn = t[nodes], x[nodes]
    out = np.zeros(ts.size)
    for j in range(4):
        weight = np.ones(ts.size)
        for i in range(4):
            if i != j:
                weight *= (ts - tn[:, i]) / (tn[:, j] - tn[:, i])
        out += weight * xn[:, j]
    early = after < 3
    out[early] = np.interp(ts[early], t, x)
    return out


class Samples:
    """Uniformly sampled output, by linear interpolation between accepted steps.

    The accepted states are recorded (time, journal position, minimum film,
    voltages); the uniform samples are interpolated from them at once when the
    result is made (vectorised), and one step at a time only for a controller
    that watches the signal as it comes (:meth:`new_samples`). A sample takes
    the minimum film and voltages of the first step at or after it. With ``cubic``
    (the error-controlled steps), e_X and e_Y are interpolated by :func:`backward_cubic`.
    """

    def __init__(self, dt: float, cubic: bool = False) -> None:
        self.dt = dt
        self.cubic = cubic
        self.start = 0.0  # time of the first sample to come from the recorded steps
        self.next = 0.0  # next sample for new_samples()
        self.done: tuple[FloatArray, ...] | None = None  # samples of the run resumed
        self.t: list[float] = []
        self.ex: list[float] = []
        self.ey: list[float] = []
        self.h_min: list[float] = []
        self.volts: list[FloatArray] = []
        self.power_t: list[float] = []  # times of the power-loss evaluations, s
        self.power: list[float] = []  # W
        self.next_power = 0.0
        #: Whether the power's evaluations go on from a stopped run's (:meth:`from_result`).
        self.resumed_power = False
        self._scales: Scales | None = None  # the case's, for the torque (set at first use)

    def add(
        self,
        t: float,
        y: FloatArray,
        system: TransientSystem,
        case: Case,
        volts: FloatArray,
        inp: Inputs,
        min_film: float | None = None,
    ) -> None:
        """Record the accepted state y at t of ``system`` (the film of ``case``).

        ``min_film`` is h/C of y if known; the power loss is evaluated every
        :data:`POWER_INTERVAL` at the speed ``inp.omega``.
        """
        sys_ = system
        c = case.bearing.clearance
        k = sys_.n + sys_.nt
        if min_film is None:
            min_film = sys_.min_film(y, inp.preload)
        self.t.append(t)
        self.ex.append(float(y[k]) * c)
        self.ey.append(float(y[k + 1]) * c)
        self.h_min.append(min_film * c)
        self.volts.append(volts)
        if t >= self.next_power:
            w = inp.omega
            P = sys_.split(y)[0]
            H = sys_.film(y, inp.preload)[0]
            self.power_t.append(t)
            if self._scales is None:
                self._scales = Scales.from_parts(case.bearing, case.gas)
            self.power.append(drag_torque(case, sys_.grid, P, H, w, self._scales) * w)
            self.next_power = t + POWER_INTERVAL

    def checkpoint(self) -> dict[str, float]:
        """Where the power loss's evaluations stand: the last one (time, W) and when the
        next is due, so that a resumed run evaluates and interpolates it as the run in
        one go does (:meth:`from_result`)."""
        m = min(len(self.power_t), len(self.power))
        if not m:
            return {}
        return {
            "power_next": self.next_power,
            "power_last_t": self.power_t[m - 1],
            "power_last": self.power[m - 1],
        }

    @classmethod
    def from_result(cls, res: OrbitResult) -> Samples:
        """Continue the samples of a stopped run.

        With the power loss's state in the checkpoint (:meth:`checkpoint`), its next
        evaluation is at the time the stopped run had set, and the samples between its
        last evaluation and the stop (held at that value when it stopped) are
        interpolated again towards the next one: the power loss is then the
        uninterrupted run's. Files without that state start the evaluations afresh.
        """
        out = cls(1.0 / res.settings.sample_rate, res.settings.steps == "adaptive")
        out.done = (
            res.time,
            res.e_x,
            res.e_y,
            res.speed,
            res.phase,
            res.min_film,
            np.asarray(res.voltages, float),
            np.full(res.time.size, np.nan) if res.power_loss is None else res.power_loss,
        )
        out.start = float(res.time[-1]) + out.dt if res.time.size else 0.0
        out.next = out.next_power = out.start
        cp = res.checkpoint
        if res.power_loss is not None and {"power_next", "power_last_t", "power_last"} <= set(cp):
            out.next_power = float(np.ravel(cp["power_next"])[0])
            out.power_t.append(float(np.ravel(cp["power_last_t"])[0]))
            out.power.append(float(np.ravel(cp["power_last"])[0]))
            out.resumed_power = True
        return out

    def new_samples(self) -> list[tuple[float, float]]:
        """(time, e_X) of the samples between the last two recorded steps (for a controller)."""
        fresh: list[tuple[float, float]] = []
        t1, x1 = self.t[-1], self.ex[-1]
        t0, x0 = (self.t[-2], self.ex[-2]) if len(self.t) > 1 else (t1, x1)
        if self.cubic and len(self.t) >= 4:
            due = max(0, math.floor((t1 + 1e-12 - self.next) / self.dt) + 1)
            times: FloatArray = self.next + self.dt * np.arange(due, dtype=np.float64)
            if due:
                xs = backward_cubic(times, np.asarray(self.t[-4:]), np.asarray(self.ex[-4:]))
                fresh = [(float(a), float(b)) for a, b in zip(times, xs, strict=True)]
                self.next = float(times[-1]) + self.dt
            return fresh
        while self.next <= t1 + 1e-12:
            ts = self.next
            w = (ts - t0) / (t1 - t0) if t1 > t0 else 1.0
            fresh.append((ts, (1 - w) * x0 + w * x1))
            self.next = ts + self.dt
        return fresh

    def arrays(self, n_act: int, profile: SpeedProfile) -> tuple[FloatArray, ...]:
        """Samples (time, e_x, e_y, speed, phase, min_film, voltages, power_loss), SI.

        A run interrupted (Ctrl-C) inside :meth:`add` leaves the last step recorded in
        some lists only: the step is dropped from all of them.
        """
        n = min(len(self.t), len(self.ex), len(self.ey), len(self.h_min), len(self.volts))
        del self.t[n:], self.ex[n:], self.ey[n:], self.h_min[n:], self.volts[n:]
        m = min(len(self.power_t), len(self.power))
        del self.power_t[m:], self.power[m:]
        t = np.asarray(self.t, dtype=float)
        if t.size and t[-1] + 1e-12 >= self.start:
            count = math.floor((t[-1] + 1e-12 - self.start) / self.dt) + 1
        else:
            count = 0
        ts: FloatArray = self.start + self.dt * np.arange(count, dtype=np.float64)
        between = backward_cubic if self.cubic else np.interp
        ex = between(ts, t, np.asarray(self.ex)) if count else np.empty(0)
        ey = between(ts, t, np.asarray(self.ey)) if count else np.empty(0)
        at = np.searchsorted(t, ts - 1e-12, side="left")
        h_min = np.asarray(self.h_min, dtype=float)[at] if count else np.empty(0)
        volts = (
            np.asarray(self.volts, dtype=float).reshape(len(self.volts), n_act)[at]
            if n_act
            else np.zeros((count, 0))
        )
        speed, phase = profile.speed_and_phase(ts)
        power = np.interp(ts, self.power_t, self.power) if self.power_t else np.full(count, np.nan)
        new = (ts, ex, ey, speed, phase, h_min, volts, power)
        if self.done is None:
            return new
        done = self.done
        if self.resumed_power and len(self.power_t) > 1:
            # The stopped run's samples after its last evaluation held that value: they
            # now lie between it and the next one.
            old_t, old_power = done[0], done[7].copy()
            after = old_t > self.power_t[0]
            old_power[after] = np.interp(old_t[after], self.power_t, self.power)
            done = (*done[:7], old_power)
        return tuple(np.concatenate([old, fresh]) for old, fresh in zip(done, new, strict=True))


def progress_bar(
    progress: bool | Callable[[float, float], None], t_end: float, t_start: float = 0.0
) -> Callable[[float | None, float | None], None] | None:
    if progress is False:
        return None
    if callable(progress):
        cb = progress

        def call(t: float | None, w: float | None) -> None:
            if t is not None and w is not None:
                cb(t, w)

        return call
    from tqdm import tqdm

    bar = tqdm(
        total=t_end,
        unit="s",
        unit_scale=False,
        desc="orbit",
        dynamic_ncols=True,
        bar_format="{l_bar}{bar}| {n:.3f}/{total:.3f} s simulated [{elapsed}<{remaining}{postfix}]",
    )
    last = [t_start]

    def update(t: float | None, w: float | None) -> None:
        if t is None:
            bar.close()
            return
        if t - last[0] >= 0.002 * t_end:
            bar.update(t - last[0])
            last[0] = t
            bar.set_postfix_str(f"{(w or 0.0) / RPM:,.0f} rpm")

    return update
