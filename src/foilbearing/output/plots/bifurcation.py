"""The whirl branch's figure: limit-cycle amplitude against speed, with its stability."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = ["plot_whirl_branch"]


def plot_whirl_branch(head: dict[str, Any], title: str = "") -> Figure:
    """Amplitude (µm) and whirl frequency (Hz) against speed (krpm) of a branch's cycles.

    ``head``: :meth:`foilbearing.bifurcation.bearing.WhirlBranch.headline`. Stable cycles
    solid, unstable dashed (in the branch's order); the linear onset dotted.
    """
    speed = np.asarray(head["speeds_rpm"], float) / 1e3
    amp = np.asarray(head["amplitude_um"], float)
    freq = np.asarray(head["whirl_frequency_Hz"], float)
    stable = np.asarray(head["stable"], bool)
    fig = Figure(figsize=(10, 4.2), layout="constrained")
    ax_a, ax_f = fig.subplots(1, 2, sharex=True)
    for k in range(speed.size - 1):
        style = "-" if stable[k] and stable[k + 1] else "--"
        for ax, y in ((ax_a, amp), (ax_f, freq)):
            ax.plot(speed[k : k + 2], y[k : k + 2], style, color="C0")
    for ax, y in ((ax_a, amp), (ax_f, freq)):
        ax.plot(speed[stable], y[stable], "o", color="C0", ms=4, label="stable cycle")
        ax.plot(speed[~stable], y[~stable], "o", mfc="none", color="C0", ms=4, label="unstable")
        ax.axvline(head["hopf_speed_rpm"] / 1e3, color="0.4", ls=":", label="linear onset")
        if head.get("speed_limit_rpm"):
            ax.axvline(head["speed_limit_rpm"] / 1e3, color="C3", ls="-.", label="fold")
        ax.set_xlabel("rotor speed (krpm)")
        ax.grid(alpha=0.3)
    ax_a.set_ylabel("limit-cycle amplitude, half extent of e_X, e_Y (µm)")
    ax_f.set_ylabel("whirl frequency (Hz)")
    ax_a.legend(fontsize=8)
    fig.suptitle(
        f"{title}: {head['bifurcation_type']} Hopf bifurcation"
        if title
        else head["bifurcation_type"]
    )
    return fig
