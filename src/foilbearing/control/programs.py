"""Actuator voltage programs in time: what the orbit asks of one, and the open-loop one.

All times in s, voltages in V. A program answers "what is the voltage at time t" from
what has happened up to t only. ``VoltageSchedule`` is the open-loop program in time
(piecewise linear V_n(t)); a voltage schedule in *speed*, chosen by optimisation, is
:class:`foilbearing.control.speed_schedule.SpeedSchedule`, which turns itself into one.
"""

from __future__ import annotations

import bisect
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from foilbearing.errors import InputError

__all__ = ["VoltageProgram", "VoltageSchedule", "voltage_ramp"]

FloatArray = NDArray[np.float64]


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
    """Open-loop voltage program: piecewise-linear V_n(t) per actuator, in time.

    Not the schedule in speed that :func:`foilbearing.design.schedule_search.voltage_schedule`
    chooses (a ``SpeedSchedule``, V_n(Ω)): that one becomes a program of this kind for a
    given speed profile (``SpeedSchedule.program``).

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
