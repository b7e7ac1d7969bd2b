"""Speed profiles, actuator voltage programs and a closed-loop preload controller.

All times in s, speeds in rad/s, voltages in V. A program answers "what is the
value at time t" from what has happened up to t only: the closed-loop
controller sees the displacement samples the simulation has produced so far,
never the future (no look-ahead).
"""

from __future__ import annotations

import bisect
import math
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from foilbearing.errors import InputError
from foilbearing.units import QuantityLike, as_si

__all__ = [
    "SpeedProfile",
    "SubsyncController",
    "VoltageProgram",
    "VoltageSchedule",
    "constant_speed",
    "linear_ramp",
    "voltage_ramp",
]

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


class VoltageProgram(Protocol):
    """What the orbit asks of a voltage program, open loop or closed loop.

    ``observes`` says whether it wants the displacement samples (``observe`` is
    then called with each new one); ``checkpoint`` and ``restore`` carry its
    state across a stopped and resumed run.
    """

    observes: ClassVar[bool]

    def __call__(self, t: float) -> FloatArray: ...

    def check(self, max_voltage: float, n_actuators: int) -> None: ...

    def observe(self, t: float, e_x: float, phase: float) -> None: ...

    def checkpoint(self) -> dict[str, float]: ...

    def restore(self, checkpoint: Mapping[str, Any]) -> None: ...


@dataclass(frozen=True)
class VoltageSchedule:
    """Open-loop voltage program: piecewise-linear V_n(t) per actuator.

    Attributes
    ----------
    times
        Breakpoints, s, non-decreasing; a repeated time makes a step (the later
        row applies from that instant).
    volts
        Voltages, V, shape (n_times, n_actuators).
    """

    times: FloatArray
    volts: FloatArray
    #: An open-loop program needs no samples and has no state to checkpoint.
    observes: ClassVar[bool] = False

    def observe(self, t: float, e_x: float, phase: float) -> None:
        """Open loop: the samples change nothing."""

    def checkpoint(self) -> dict[str, float]:
        """Open loop: no state."""
        return {}

    def restore(self, checkpoint: Mapping[str, Any]) -> None:
        """Open loop: no state."""

    def __post_init__(self) -> None:
        t = np.asarray(self.times, float)
        v = np.atleast_2d(np.asarray(self.volts, float))
        if v.shape[0] != t.size or t.size < 1 or np.any(np.diff(t) < 0):
            raise InputError("voltage program: times must be non-decreasing, one row per time")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "volts", v)
        # Called once per time step: breakpoints as a list (bisect) and which
        # segments hold the voltage (no arithmetic there).
        object.__setattr__(self, "_times_list", t.tolist())
        object.__setattr__(self, "_held", np.all(v[1:] == v[:-1], axis=1).tolist())

    def __call__(self, t: float) -> FloatArray:
        """Voltages at time t, V, shape (n_actuators,)."""
        k = bisect.bisect_right(self._times_list, t)  # type: ignore[attr-defined]
        if k == 0:
            return self.volts[0].copy()
        if k >= len(self._times_list) or self._held[k - 1]:  # type: ignore[attr-defined]
            return self.volts[k - 1].copy()
        t0, t1 = self.times[k - 1], self.times[k]
        w = (t - t0) / (t1 - t0)
        return (1.0 - w) * self.volts[k - 1] + w * self.volts[k]

    def check(self, max_voltage: float, n_actuators: int) -> None:
        """Errors for a program that exceeds the stack's limit or has the wrong width."""
        if self.volts.shape[1] not in (1, n_actuators):
            raise InputError(
                f"voltage program has {self.volts.shape[1]} columns; the case has "
                f"{n_actuators} actuators"
            )
        if np.any(self.volts < 0) or np.any(self.volts > max_voltage):
            raise InputError(
                f"voltage program reaches {self.volts.max():g} V (min {self.volts.min():g} V): "
                f"allowed 0 to {max_voltage:g} V (max_voltage)"
            )


def voltage_ramp(
    start_time: float, end_time: float, final: ArrayLike, initial: ArrayLike = 0.0
) -> VoltageSchedule:
    """From ``initial`` to ``final`` volts between ``start_time`` and ``end_time`` (s).

    The paper ramps all actuators from 0 to 50/100/150 V between 6.0 and 6.5 s.
    """
    if end_time < start_time or start_time < 0:
        raise InputError(f"voltage ramp {start_time:g} s to {end_time:g} s: need 0 <= start <= end")
    v0 = np.atleast_1d(np.asarray(initial, float))
    v1 = np.atleast_1d(np.asarray(final, float))
    v0, v1 = np.broadcast_arrays(v0, v1)
    return VoltageSchedule(np.array([start_time, end_time]), np.vstack([v0, v1]))


@dataclass
class SubsyncController:
    """Closed-loop preload control: raise the voltage when sub-synchronous motion appears.

    Every control period it estimates the sub-synchronous amplitude of e_X over
    the last ``window`` seconds of samples: a least-squares fit of
    [1, cos φ, sin φ] (offset and the synchronous 1X component, order tracking
    with the known rotation angle φ) is removed and √2 × RMS of the remainder
    is the amplitude. When it exceeds ``threshold`` the command jumps to
    ``target`` volts (and stays: a latch, as a protective controller would);
    the applied voltage follows the command at most at ``slew_rate`` V/s.

    Attributes
    ----------
    threshold
        Sub-synchronous amplitude that triggers the control, m.
    target
        Commanded voltage once triggered, V (≤ the stack's max_voltage).
    slew_rate
        Amplifier slew-rate limit, V/s.
    window
        Length of the analysis window, s.
    period
        Control period, s.
    initial
        Voltage before triggering, V.
    """

    threshold: float = 2e-6
    target: float = 150.0
    slew_rate: float = 1000.0
    window: float = 0.1
    period: float = 0.01
    initial: float = 0.0
    n_actuators: int = 3
    triggered_at: float | None = None
    _samples: deque = field(default_factory=deque, repr=False)
    _last_control: float = -math.inf
    _volts: float = math.nan
    _last_time: float = 0.0
    amplitude: float = 0.0
    #: The controller reads the displacement samples as the run produces them.
    observes: ClassVar[bool] = True

    def checkpoint(self) -> dict[str, float]:
        """The latch (when the control triggered, NaN: not yet) and the applied voltage.

        The analysis window is not kept: a run resumed before the trigger refills
        it from the samples that follow.
        """
        return {
            "triggered_at": math.nan if self.triggered_at is None else self.triggered_at,
            "controller_volts": self._volts,
            "controller_time": self._last_time,
        }

    def restore(self, checkpoint: Mapping[str, Any]) -> None:
        """Take the latch and the applied voltage back (older checkpoints may lack them)."""

        def value(key: str) -> float | None:
            return float(np.ravel(checkpoint[key])[0]) if key in checkpoint else None

        trig = value("triggered_at")
        if trig is not None:
            self.triggered_at = None if math.isnan(trig) else trig
        volts, last = value("controller_volts"), value("controller_time")
        if volts is not None and last is not None:
            self._volts, self._last_time = volts, last

    def __post_init__(self) -> None:
        if self.threshold <= 0 or self.slew_rate <= 0 or self.window <= 0 or self.period <= 0:
            raise InputError("controller: threshold, slew_rate, window and period must be > 0")
        self._volts = self.initial

    def check(self, max_voltage: float, n_actuators: int) -> None:
        """Errors for a target beyond the stack's limit."""
        if not 0.0 <= self.target <= max_voltage or not 0.0 <= self.initial <= max_voltage:
            raise InputError(
                f"controller target {self.target:g} V / initial {self.initial:g} V: allowed 0 to "
                f"{max_voltage:g} V (max_voltage)"
            )
        self.n_actuators = n_actuators

    def observe(self, t: float, e_x: float, phase: float) -> None:
        """Feed one displacement sample (m) at time t with rotation angle φ."""
        self._samples.append((t, e_x, phase))
        while self._samples and self._samples[0][0] < t - self.window:
            self._samples.popleft()
        if t - self._last_control >= self.period and len(self._samples) >= 16:
            self._last_control = t
            arr = np.array(self._samples)
            basis = np.column_stack([np.ones(len(arr)), np.cos(arr[:, 2]), np.sin(arr[:, 2])])
            coef, *_ = np.linalg.lstsq(basis, arr[:, 1], rcond=None)
            rest = arr[:, 1] - basis @ coef
            self.amplitude = float(math.sqrt(2.0) * np.sqrt(np.mean(rest**2)))
            if self.triggered_at is None and self.amplitude > self.threshold:
                self.triggered_at = t

    def __call__(self, t: float) -> FloatArray:
        """Applied voltage at time t (slew-limited towards the command)."""
        command = self.target if self.triggered_at is not None else self.initial
        dt = max(t - self._last_time, 0.0)
        step = self.slew_rate * dt
        self._volts += float(np.clip(command - self._volts, -step, step))
        self._last_time = t
        return np.full(self.n_actuators, self._volts)
