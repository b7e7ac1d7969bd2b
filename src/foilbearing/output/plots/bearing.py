"""Figures of the study of any bearing: readouts against speed, load or voltage, the
preloads against voltage, synchronous coefficients against speed, and the log decrement
against speed."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = [
    "plot_against",
    "plot_log_decrement",
    "plot_onsets",
    "plot_preloads",
    "plot_synchronous",
]

#: x keys of :func:`plot_against`: scale to the shown unit, axis label.
_X_AXES = {
    "speed_rpm": (1e-3, "rotor speed (krpm)"),
    "load_N": (1.0, "load (N)"),
    "voltage_V": (1.0, "actuator voltage, all actuators (V)"),
}
_PANELS = (
    ("eccentricity", "eccentricity ratio ε"),
    ("attitude_deg", "attitude angle (°)"),
    ("min_film_um", "minimum film (µm)"),
    ("power_loss_W", "power loss (W)"),
)


def plot_against(points: list[dict[str, Any]], x_key: str) -> Figure:
    """Four readouts against ``x_key`` (``speed_rpm``, shown in krpm, ``load_N`` or
    ``voltage_V``); points without equilibrium are marked on the axis."""
    scale, label = _X_AXES[x_key]
    ok = [p for p in points if p.get("converged")]
    bad = [p[x_key] * scale for p in points if not p.get("converged")]
    fig = Figure(figsize=(8.0, 5.6), layout="constrained")
    axes = fig.subplots(2, 2, sharex=True).ravel()
    x = np.array([p[x_key] * scale for p in ok])
    for ax, (key, name) in zip(axes, _PANELS, strict=True):
        ax.plot(x, [p[key] for p in ok], marker="o", ms=3)
        if bad:
            ax.plot(bad, np.zeros(len(bad)), "rx", label="no equilibrium")
            ax.legend(fontsize=8)
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    for ax in axes[2:]:
        ax.set_xlabel(label)
    return fig


def plot_synchronous(rows: list[dict[str, Any]]) -> Figure:
    """The eight synchronous coefficients (K in N/m, C in N·s/m) against speed (krpm)."""
    fig = Figure(figsize=(8.0, 3.8), layout="constrained")
    ax_k, ax_c = fig.subplots(1, 2, sharex=True)
    krpm = np.array([r["speed_rpm"] / 1e3 for r in rows])
    for i, a in enumerate("XY"):
        for j, b in enumerate("XY"):
            ax_k.plot(
                krpm, [r["K_N_per_m"][i][j] for r in rows], marker="o", ms=3, label=f"K{a}{b}"
            )
            ax_c.plot(
                krpm, [r["C_N_s_per_m"][i][j] for r in rows], marker="o", ms=3, label=f"C{a}{b}"
            )
    ax_k.set_ylabel("stiffness (N/m)")
    ax_c.set_ylabel("damping (N·s/m)")
    for ax in (ax_k, ax_c):
        ax.set_xlabel("rotor speed (krpm), excitation at the running speed")
        ax.legend(fontsize=8, ncol=2)
        ax.grid(alpha=0.3)
    return fig


def plot_log_decrement(modes: list[dict[str, Any]], onset_rpm: float | None) -> Figure:
    """Log decrement of the least stable whirl mode against speed, with the onset."""
    fig = Figure(figsize=(7.0, 3.6), layout="constrained")
    ax = fig.subplots()
    good = [m for m in modes if "log_decrement" in m]
    ax.plot([m["speed_rpm"] / 1e3 for m in good], [m["log_decrement"] for m in good], "o-", ms=3)
    ax.axhline(0.0, color="k", lw=0.8)
    if onset_rpm is not None:
        ax.axvline(onset_rpm / 1e3, color="C3", ls=":", label=f"onset {onset_rpm / 1e3:.1f} krpm")
        ax.legend(fontsize=8)
    ax.set_xlabel("rotor speed (krpm)")
    ax.set_ylabel("log decrement (least stable whirl)")
    ax.grid(alpha=0.3)
    return fig


def plot_onsets(rows: list[dict[str, Any]], x_label: str) -> Figure:
    """Linear onset speed (krpm) against each row's ``x`` (shim thickness or voltage)."""
    fig = Figure(figsize=(6.0, 3.4), layout="constrained")
    ax = fig.subplots()
    pts = [(r["x"], r["onset_speed_rpm"] / 1e3) for r in rows if r.get("onset_speed_rpm")]
    if pts:
        ax.plot(*zip(*pts, strict=True), "o-")
    ax.set_xlabel(x_label)
    ax.set_ylabel("linear onset speed (krpm)")
    ax.grid(alpha=0.3)
    return fig


def plot_preloads(points: list[dict[str, Any]], case: Any) -> Figure:
    """Piezoelectric preload (µm) and actuator pressure (kPa) of each actuator against the
    voltage (all the same), at one speed and load."""
    import math

    fig = Figure(figsize=(8.0, 3.4), layout="constrained")
    ax_r, ax_p = fig.subplots(1, 2, sharex=True)
    ok = [p for p in points if p.get("converged")]
    volts = [p["voltage_V"] for p in ok]
    for n, angle in enumerate(case.actuators.angles):
        label = f"{math.degrees(angle):.0f}°"
        ax_r.plot(volts, [p["preload_um"][n] for p in ok], "o-", ms=3, label=label)
        ax_p.plot(volts, [p["actuator_pressure_kPa"][n] for p in ok], "o-", ms=3, label=label)
    ax_r.set_ylabel("piezoelectric preload r_p (µm)")
    ax_p.set_ylabel("actuator pressure p_A (kPa)")
    for ax in (ax_r, ax_p):
        ax.set_xlabel("actuator voltage (V)")
        ax.legend(fontsize=8, title="actuator at", title_fontsize=8)
        ax.grid(alpha=0.3)
    return fig
