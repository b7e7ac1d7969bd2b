"""Figure of a voltage schedule: voltage per actuator, log decrement and power loss against speed."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from foilbearing.constants import RPM

__all__ = ["plot_run_power", "plot_schedule"]


def plot_schedule(schedule: Any, angles_deg: list[float] | None = None) -> Figure:
    """Three panels against speed (krpm): the voltages, the log decrement with the margin and
    the limit speed, and the power loss beside the constant 150 V one."""
    krpm = schedule.speeds / RPM / 1e3
    panels = 1 + (schedule.log_decrement is not None) + (schedule.power_loss is not None)
    fig = Figure(figsize=(7.0, 2.4 * panels + 0.6), layout="constrained")
    axes = fig.subplots(panels, 1, sharex=True, squeeze=False)[:, 0]
    ax = axes[0]
    for n in range(schedule.n_actuators):
        where = f" at {angles_deg[n]:.0f}°" if angles_deg else ""
        ax.plot(krpm, schedule.voltages[:, n], marker="o", ms=3, label=f"actuator {n + 1}{where}")
    ax.set_ylabel("voltage (V)")
    ax.legend(fontsize=8, loc="best")
    ax.set_title(
        f"Voltage schedule (slew-rate limit {schedule.slew_rate:g} V/s"
        + (f" at {schedule.acceleration:g} rad/s²)" if schedule.acceleration is not None else ")"),
        fontsize=10,
    )
    k = 1
    if schedule.log_decrement is not None:
        ax = axes[k]
        k += 1
        ax.plot(krpm, schedule.log_decrement, marker="o", ms=3, color="C3", label="scheduled")
        mid = schedule.midpoint_log_decrement
        if mid is not None and mid.size:
            ax.plot(
                0.5 * (krpm[1:] + krpm[:-1]),
                mid,
                ls="none",
                marker="x",
                ms=4,
                color="C3",
                label="halfway, interpolated voltages",
            )
        if schedule.margin is not None:
            ax.axhline(
                schedule.margin, color="0.4", ls="--", lw=1, label=f"margin {schedule.margin:g}"
            )
        ax.axhline(0.0, color="k", lw=0.8)
        if schedule.limit_speed is not None:
            ax.axvline(
                schedule.limit_speed / RPM / 1e3,
                color="C3",
                ls=":",
                label=f"limit {schedule.limit_speed / RPM / 1e3:.1f} krpm",
            )
        ax.set_ylabel("log decrement")
        ax.legend(fontsize=8, loc="best")
    if schedule.power_loss is not None:
        ax = axes[k]
        ax.plot(krpm, schedule.power_loss, marker="o", ms=3, label="scheduled")
        ref = schedule.power_loss_reference
        if ref is not None and np.any(np.isfinite(ref)):
            ax.plot(krpm, ref, ls="--", color="0.4", label="constant 150 V")
        ax.set_ylabel("power loss (W)")
        ax.legend(fontsize=8, loc="best")
    axes[-1].set_xlabel("rotor speed (krpm)")
    return fig


def plot_run_power(runs: dict[str, tuple[np.ndarray, np.ndarray]]) -> Figure:
    """Power loss of the film (W) against speed (krpm) for speed-up runs: label -> (rpm, W)."""
    fig = Figure(figsize=(7.0, 3.6), layout="constrained")
    ax = fig.subplots()
    for label, (rpm, watts) in runs.items():
        step = max(rpm.size // 4000, 1)  # a few thousand points draw the same line
        ax.plot(rpm[::step] / 1e3, watts[::step], lw=1.2, label=label)
    ax.set_xlabel("rotor speed (krpm)")
    ax.set_ylabel("power loss (W)")
    ax.set_title("Film power loss during the speed-up", fontsize=10)
    ax.legend(fontsize=8, loc="best")
    return fig
