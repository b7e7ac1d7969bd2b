"""The voltage schedule in speed: actuator voltages against rotor speed, V_n(Ω), followed in
time through the amplifier's slew rate.

A ``SpeedSchedule`` is what a controller follows as the rotor speeds up; along a speed
profile it becomes a program in time, a :class:`~foilbearing.control.programs.VoltageSchedule`
(:meth:`SpeedSchedule.program`). The search that chooses one, the least-drag voltages that
keep the rotor stable, is :func:`foilbearing.design.schedule_search.voltage_schedule`; its
file is :mod:`foilbearing.control.schedule_file`. Speeds in rad/s, voltages in V, times in s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.constants import RPM
from foilbearing.control.programs import VoltageSchedule

__all__ = ["DEFAULT_SLEW_RATE", "SpeedSchedule"]

FloatArray = NDArray[np.float64]

#: Amplifier slew-rate limit, V/s: the paper's control ramp, 0 to 150 V in 0.5 s.
DEFAULT_SLEW_RATE = 300.0


@dataclass(frozen=True)
class SpeedSchedule:
    """Actuator voltages against rotor speed, with what the analysis found at each speed.

    Between the grid speeds the voltages are interpolated linearly; below the
    first and above the last speed they are held.

    Attributes
    ----------
    speeds
        Grid speeds, rad/s, increasing.
    voltages
        Voltage of each actuator at each speed, V, shape (n_speeds, n_actuators).
    slew_rate
        Amplifier slew-rate limit, V/s: the orbit follows the schedule at most this fast.
    acceleration
        Speed-up rate the smoothness was set for, rad/s² (None: not stated).
    margin
        Least log decrement asked for (None: not stated, e.g. a hand-written file).
    power_loss, log_decrement, whirl_frequency, min_film
        At the scheduled voltages, per speed: W, -, rad/s, m (None: not computed).
    power_loss_reference
        Power loss at a constant 150 V on every actuator (the paper's constant voltage,
        ``PAPER_CONSTANT_VOLTAGE`` of :mod:`foilbearing.design.schedule_search`), W.
    midpoint_log_decrement
        δ halfway between consecutive grid speeds at the interpolated voltages
        (n_speeds − 1; NaN where no equilibrium was found).
    limit_speed
        Speed above which no voltage keeps the rotor stable, rad/s; None when it
        is stable to the top speed (or the schedule was not computed).
    evaluations
        Equilibria with whirl modes computed to make the schedule.
    source
        Where the schedule came from (case file or schedule file), for messages.
    """

    speeds: FloatArray
    voltages: FloatArray
    slew_rate: float = DEFAULT_SLEW_RATE
    acceleration: float | None = None
    margin: float | None = None
    power_loss: FloatArray | None = None
    log_decrement: FloatArray | None = None
    whirl_frequency: FloatArray | None = None
    min_film: FloatArray | None = None
    power_loss_reference: FloatArray | None = None
    midpoint_log_decrement: FloatArray | None = None
    limit_speed: float | None = None
    evaluations: int = 0
    source: str | None = None

    @property
    def meets_margin(self) -> NDArray[np.bool_] | None:
        """Per speed: whether the scheduled voltages meet the margin (None: not known)."""
        if self.margin is None or self.log_decrement is None:
            return None
        return np.asarray(self.log_decrement >= self.margin - 1e-12)

    @property
    def n_actuators(self) -> int:
        """Number of actuators (columns of ``voltages``)."""
        return int(self.voltages.shape[1])

    def command(self, speed: float | FloatArray) -> FloatArray:
        """Scheduled voltages at ``speed`` (rad/s), V: shape (n_actuators,) or (n, n_actuators)."""
        w = np.asarray(speed, float)
        out = np.stack([np.interp(w, self.speeds, col) for col in self.voltages.T], axis=-1)
        return np.asarray(out, dtype=float)

    def program(self, profile: Any, dt: float = 1e-3) -> Any:
        """The schedule along a speed profile as a time program, through the slew-rate limit.

        The command V(ω(t)) is sampled every ``dt`` seconds and followed from its
        value at t = 0 at most at ``slew_rate`` V/s. Returns a
        :class:`foilbearing.control.VoltageSchedule` (piecewise linear in t), so a
        run is reproducible and can be resumed.
        """
        n = max(math.ceil(profile.duration / dt), 1)
        times = np.linspace(0.0, profile.duration, n + 1)
        # and the instants the speed passes a grid speed: there the command has its kinks
        for t0, t1, w0, w1 in zip(
            profile.times[:-1],
            profile.times[1:],
            profile.speeds[:-1],
            profile.speeds[1:],
            strict=True,
        ):
            if w1 != w0:
                frac = (self.speeds - w0) / (w1 - w0)
                times = np.concatenate([times, t0 + frac[(frac > 0) & (frac < 1)] * (t1 - t0)])
        times = np.unique(times)
        speeds, _ = profile.speed_and_phase(times)
        command = self.command(speeds)
        applied = np.empty_like(command)
        applied[0] = command[0]
        step = self.slew_rate * np.diff(times)
        for k in range(1, times.size):
            applied[k] = applied[k - 1] + np.clip(
                command[k] - applied[k - 1], -step[k - 1], step[k - 1]
            )
        return VoltageSchedule(times, applied)

    def headline(self) -> dict[str, Any]:
        """The schedule with unit-named keys (the CLI's ``--json``)."""

        def per_speed(a: FloatArray | None, scale: float = 1.0) -> list[float | None] | None:
            if a is None:
                return None
            return [float(x) * scale if math.isfinite(x) else None for x in a]

        return {
            "speeds_rpm": [float(w / RPM) for w in self.speeds],
            "voltages_V": [[float(v) for v in row] for row in self.voltages],
            "power_loss_W": per_speed(self.power_loss),
            "power_loss_150V_W": per_speed(self.power_loss_reference),
            "log_decrement": per_speed(self.log_decrement),
            "whirl_frequency_Hz": per_speed(self.whirl_frequency, 1.0 / (2.0 * math.pi)),
            "min_film_um": per_speed(self.min_film, 1e6),
            "meets_margin": None
            if self.meets_margin is None
            else [bool(b) for b in self.meets_margin],
            "midpoint_log_decrement": per_speed(self.midpoint_log_decrement),
            "limit_speed_rpm": None if self.limit_speed is None else self.limit_speed / RPM,
            "margin": self.margin,
            "slew_rate_V_per_s": self.slew_rate,
            "acceleration_rad_per_s2": self.acceleration,
            "evaluations": self.evaluations,
        }
