"""The whirl branch's figure: limit-cycle amplitude against speed, with its stability."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = ["plot_whirl_branch", "plot_whirl_branches"]


def plot_whirl_branch(
    head: dict[str, Any],
    title: str = "",
    envelope: tuple[np.ndarray, np.ndarray] | None = None,
) -> Figure:
    """Amplitude (µm) and whirl frequency (Hz) against speed (krpm) of a branch's cycles.

    ``head``: :meth:`foilbearing.bifurcation.bearing.WhirlBranch.headline`. Stable cycles
    solid, unstable dashed (in the branch's order); the linear onset dotted.
    ``envelope``: a speed-up's sub-synchronous amplitude, (rpm, m), laid over the
    amplitudes over the branch's speeds and 10 % around them.
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
            ax.axvline(head["speed_limit_rpm"] / 1e3, color="C3", ls="-.", label="speed limit")
        ax.set_xlabel("rotor speed (krpm)")
        ax.grid(alpha=0.3)
    if envelope is not None and speed.size:
        rpm, amp_m = (np.asarray(a, float) for a in envelope)
        near = (rpm >= 0.9e3 * speed.min()) & (rpm <= 1.1e3 * speed.max())
        ax_a.plot(rpm[near] / 1e3, amp_m[near] * 1e6, color="0.45", lw=1.2,
                  label="speed-up: sub-synchronous amplitude")  # fmt: skip
    ax_a.set_ylabel("limit-cycle amplitude, half extent of e_X, e_Y (µm)")
    ax_f.set_ylabel("whirl frequency (Hz)")
    ax_a.legend(fontsize=8)
    fig.suptitle(
        f"{title}: {head['bifurcation_type']} Hopf bifurcation"
        if title
        else head["bifurcation_type"]
    )
    return fig


def plot_whirl_branches(branches: dict[str, dict[str, dict[str, Any]]]) -> Figure:
    """Each reading's branches in a panel: cycle amplitude (µm) against speed over the
    linear onset, one colour a voltage, stable cycles solid and filled, unstable dashed
    and open.

    ``branches``: ``{reading: {voltage: headline}}`` (a headline without a Hopf point,
    or a failed one, draws nothing).
    """
    fig = Figure(figsize=(5.2 * max(len(branches), 1), 4.4), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, max(len(branches), 1), sharey=True))
    for ax, (reading, per_volt) in zip(axes, branches.items(), strict=False):
        for c, (volts, head) in enumerate(per_volt.items()):
            if not head.get("speeds_rpm") or not head.get("hopf_speed_rpm"):
                continue
            ratio = np.asarray(head["speeds_rpm"], float) / float(head["hopf_speed_rpm"])
            amp = np.asarray(head["amplitude_um"], float)
            stable = np.asarray(head["stable"], bool)
            colour = f"C{c}"
            for k in range(ratio.size - 1):
                style = "-" if stable[k] and stable[k + 1] else "--"
                ax.plot(ratio[k : k + 2], amp[k : k + 2], style, color=colour)
            kind = head.get("bifurcation_type") or ""
            ax.plot(ratio[stable], amp[stable], "o", color=colour, ms=4,
                    label=f"{volts} V: {kind}")  # fmt: skip
            ax.plot(ratio[~stable], amp[~stable], "o", mfc="none", color=colour, ms=4)
        ax.axvline(1.0, color="0.4", ls=":")
        ax.set_title(reading.replace("+", " + "))
        ax.set_xlabel("rotor speed / linear onset")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("limit-cycle amplitude, half extent of e_X, e_Y (µm)")
    fig.suptitle("Whirl limit cycles from the linear onset: filled stable, open unstable")
    return fig
