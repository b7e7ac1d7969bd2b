"""The rotor's Campbell diagram: each mode's frequency against speed, coloured by its log
decrement (matched whirl), with the onset."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from foilbearing.constants import RPM

__all__ = ["plot_campbell"]


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
