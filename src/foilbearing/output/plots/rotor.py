"""The rotor's figures: the Campbell diagram (each mode's frequency against speed, coloured
by its log decrement, matched whirl, with the onset), the unbalance response at the
bearings and disks, and the mode shapes along the shaft."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from foilbearing.constants import RPM

__all__ = ["plot_campbell", "plot_mode_shapes", "plot_unbalance_response"]


def plot_campbell(modes: Any, onset: float | None = None, title: str = "") -> Figure:
    """``modes``: a :class:`foilbearing.rotor.RotorModes`; ``onset`` in rad/s."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    rpm = modes.speeds / RPM
    dec = modes.log_decrement
    lim = float(np.nanmax(np.abs(dec))) if np.isfinite(dec).any() else 1.0
    lim = min(lim, 1.0)
    for j in range(modes.frequency.shape[1]):
        ax.plot(rpm, modes.frequency[:, j], color="0.8", lw=0.8, zorder=1)
    for mask, marker in ((modes.forward, "o"), (~modes.forward, "v")):
        sc = ax.scatter(
            np.broadcast_to(rpm[:, None], mask.shape)[mask], modes.frequency[mask],
            c=dec[mask], cmap="RdBu", vmin=-lim, vmax=lim, marker=marker, s=18, zorder=2,
        )  # fmt: skip
    ax.plot(rpm, rpm / 60.0, "k--", lw=0.8, label="1X")
    if onset is not None:
        ax.axvline(onset / RPM, color="C3", lw=1.0, label=f"onset {onset / RPM:.0f} rpm")
    ax.set_xlabel("speed (rpm)")
    ax.set_ylabel("damped natural frequency (Hz)")
    ax.set_title(title or "Campbell diagram, matched whirl (o forward, v backward)")
    ax.legend(loc="upper left")
    fig.colorbar(sc, ax=ax, label="log decrement")
    return fig


def plot_unbalance_response(response: Any, title: str = "") -> Figure:
    """``response``: a :class:`foilbearing.rotor.response.UnbalanceResponse`. The major
    semi-axis of each bearing's and disk's orbit against speed; a log scale when it spans
    more than a decade."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    rpm = response.speeds / RPM
    amp = response.amplitude_um()
    for j, label in enumerate(response.labels):
        style = "o-" if label.startswith("disk") else "s-"
        ax.plot(rpm, amp[:, j], style, ms=3.5, lw=1.0, label=label)
    positive = amp[amp > 0.0]
    if positive.size and positive.max() > 10.0 * positive.min():
        ax.set_yscale("log")
    unbalances = ", ".join(
        f"{m * 1e6:.3g} g·mm at node {n}, {math.degrees(p):.0f}°" for n, m, p in response.unbalances
    )
    ax.set_xlabel("speed (rpm)")
    ax.set_ylabel("orbit's major semi-axis (µm)")
    ax.set_title(title or f"unbalance response ({unbalances})")
    ax.legend(loc="best")
    return fig


def plot_mode_shapes(shapes: Any, title: str = "") -> Figure:
    """``shapes``: a :class:`foilbearing.rotor.response.ModeShapes`. Each mode's major
    semi-axis along the shaft, signed by its phase (largest 1), the bearings marked."""
    fig = Figure(figsize=(8.0, 4.5), layout="constrained")
    ax = fig.subplots()
    z_mm = 1e3 * shapes.axial
    along = shapes.amplitude_along()
    for i in range(along.shape[0]):
        whirl = "forward" if shapes.forward[i] else "backward"
        ax.plot(
            z_mm, along[i], lw=1.2, ls="-" if shapes.forward[i] else "--",
            label=f"{shapes.frequency[i]:.1f} Hz, δ = {shapes.log_decrement[i]:.3f}, {whirl}",
        )  # fmt: skip
    ax.axhline(0.0, color="0.6", lw=0.8, zorder=0)
    at_bottom = ax.get_xaxis_transform()  # x in data, y in axes fraction
    for node, label in zip(shapes.bearing_nodes, shapes.bearing_labels, strict=True):
        z = 1e3 * shapes.positions[node]
        ax.axvline(z, color="0.85", lw=6.0, zorder=0)
        ax.plot([z], [0.0], marker="^", color="k", ms=10, transform=at_bottom, clip_on=False)
        ax.text(z, 0.05, label, transform=at_bottom, ha="center", va="bottom", fontsize=8,
                bbox={"fc": "white", "ec": "none", "alpha": 0.8})  # fmt: skip
    ax.set_ylim(-1.25, 1.15)
    ax.set_xlabel("axial position (mm)")
    ax.set_ylabel("major semi-axis, signed by phase")
    ax.set_title(title or f"mode shapes at {shapes.speed / RPM:.0f} rpm, matched whirl")
    ax.legend(loc="best", fontsize=8)
    return fig
