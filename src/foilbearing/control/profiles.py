"""Speed profiles: the rotor speed ω(t), its rate and the rotation angle φ(t), in time.

All times in s, speeds in rad/s. A profile is the speed program the orbit follows; the
paper's is a linear ramp from 3 to 90 krpm at 500 rad/s².
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from foilbearing.errors import InputError
from foilbearing.units import QuantityLike, as_si

__all__ = ["SpeedProfile", "constant_speed", "linear_ramp"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class SpeedProfile:
    """Piecewise-linear rotor speed ω(t), with its rate and the rotation angle φ(t) = ∫ω dt.

    Attributes
    ----------
    times
        Breakpoints, s, increasing (first 0).
    speeds
        ω at the breakpoints, rad/s (> 0).
    """

    times: FloatArray
    speeds: FloatArray

    def __post_init__(self) -> None:
        t, w = np.asarray(self.times, float), np.asarray(self.speeds, float)
        if t.ndim != 1 or t.size < 2 or t.size != w.size:
            raise InputError("speed profile: need matching times and speeds, at least two")
        if t[0] != 0.0 or np.any(np.diff(t) <= 0):
            raise InputError("speed profile: times must start at 0 s and increase")
        if np.any(w <= 0) or not np.all(np.isfinite(w)):
            raise InputError(f"speed profile: speeds must be > 0 rad/s, got {w.min():g}")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "speeds", w)
        # Angle at each breakpoint (trapezoid is exact for a piecewise-linear ω).
        phase = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))])
        object.__setattr__(self, "_phase", phase)
        # Python floats for state(): called once per time step, it avoids NumPy's per-call cost.
        object.__setattr__(self, "_knots", (t.tolist(), w.tolist(), phase.tolist()))

    @property
    def duration(self) -> float:
        """End time, s."""
        return float(self.times[-1])

    def state(self, t: float) -> tuple[float, float, float]:
        """(ω, dω/dt, φ) at t: rad/s, rad/s², rad, from one search of the breakpoints.

        ω is held at its end values outside the profile; dω/dt is the slope of
        the segment containing t (of the first or last one outside); φ = ∫₀ᵗ ω dt.
        """
        times, speeds, phases = self._knots  # type: ignore[attr-defined]
        k = min(max(bisect.bisect_right(times, t) - 1, 0), len(times) - 2)
        t0, w0 = times[k], speeds[k]
        a = (speeds[k + 1] - w0) / (times[k + 1] - t0)
        dt = t - t0
        if t <= times[0]:
            w = speeds[0]
        elif t >= times[-1]:
            w = speeds[-1]
        else:
            w = w0 + a * dt
        return w, a, phases[k] + w0 * dt + 0.5 * a * dt * dt

    def speed_and_phase(self, t: FloatArray) -> tuple[FloatArray, FloatArray]:
        """ω and φ at many times at once (the arithmetic of :meth:`state`), rad/s and rad."""
        times, speeds = self.times, self.speeds
        t = np.asarray(t, dtype=float)
        k = np.clip(np.searchsorted(times, t, side="right") - 1, 0, times.size - 2)
        dt = t - times[k]
        a = (speeds[k + 1] - speeds[k]) / (times[k + 1] - times[k])
        phase = self._phase[k] + speeds[k] * dt + 0.5 * a * dt * dt  # type: ignore[attr-defined]
        return np.interp(t, times, speeds), phase

    def omega(self, t: float) -> float:
        """ω(t), rad/s."""
        return self.state(t)[0]

    def phase(self, t: float) -> float:
        """φ(t) = ∫₀ᵗ ω dt, rad."""
        return self.state(t)[2]


def constant_speed(speed: QuantityLike, duration: QuantityLike) -> SpeedProfile:
    """ω = ``speed`` (rad/s) for ``duration`` s; either may be a quantity (``"30 krpm"``,
    ``"0.5 s"``)."""
    speed = as_si(speed, "speed", field="speed")
    duration = as_si(duration, "time", field="duration")
    if duration <= 0:
        raise InputError(f"duration = {duration!r} s: must be > 0")
    return SpeedProfile(np.array([0.0, duration]), np.array([speed, speed]))


def linear_ramp(
    start: QuantityLike, stop: QuantityLike, acceleration: QuantityLike
) -> SpeedProfile:
    """From ``start`` to ``stop`` (rad/s) at constant ``acceleration`` (rad/s², > 0); each
    may be a quantity (``"3 krpm"``, ``"500 rad/s**2"``).

    The paper's speed-up: 3 to 90 krpm at 500 rad/s² (18.2 s).
    """
    start = as_si(start, "speed", field="start")
    stop = as_si(stop, "speed", field="stop")
    acceleration = as_si(acceleration, "angular_acceleration", field="acceleration")
    if acceleration <= 0:
        raise InputError(f"speed ramp: acceleration {acceleration!r} rad/s² must be > 0")
    if stop <= start:
        raise InputError(
            f"speed ramp: ends at {stop * 30 / math.pi:.0f} rpm, below or at its start "
            f"{start * 30 / math.pi:.0f} rpm"
        )
    return SpeedProfile(np.array([0.0, (stop - start) / acceleration]), np.array([start, stop]))
