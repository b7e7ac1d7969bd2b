"""The closed-loop preload controller: raise the voltage when sub-synchronous motion appears.

Times in s, displacements in m, voltages in V. The controller sees the displacement samples
the simulation has produced so far, never the future (no look-ahead).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from foilbearing.errors import InputError

__all__ = ["SubsyncController"]

FloatArray = NDArray[np.float64]


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
