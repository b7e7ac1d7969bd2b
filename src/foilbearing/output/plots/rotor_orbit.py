"""The nonlinear rotor's run: each bearing's journal displacement against time and speed."""

from __future__ import annotations

from typing import Any

from matplotlib.figure import Figure

from foilbearing.constants import RPM

__all__ = ["plot_rotor_orbit"]


def plot_rotor_orbit(run: Any, title: str = "") -> Figure:
    """``run``: a :class:`foilbearing.rotor.nonlinear.RotorOrbit`. Left: each bearing's
    X and Y displacement (µm) against time, with the speed (krpm) on a second axis;
    right: each journal's orbit over the last tenth of the run."""
    fig = Figure(figsize=(10.0, 4.2), layout="constrained")
    ax, orb = fig.subplots(1, 2, width_ratios=(2.2, 1.0))
    t = run.time
    for b, label in enumerate(run.labels):
        for k, axis in enumerate("XY"):
            ax.plot(t, run.journals[b, k] * 1e6, lw=0.6, label=f"{label}, {axis}")
    ax.set_xlabel("time, s")
    ax.set_ylabel("journal displacement, µm")
    ax.legend(fontsize=7, ncol=2, loc="upper left")
    if run.speed is not None:
        sp = ax.twinx()
        sp.plot(t, run.speed / RPM / 1e3, color="0.5", lw=1.0, ls="--")
        sp.set_ylabel("speed, krpm")
    last = t >= t[0] + 0.9 * (t[-1] - t[0])
    for b, label in enumerate(run.labels):
        x, y = run.journals[b, 0, last], run.journals[b, 1, last]
        orb.plot((y - y.mean()) * 1e6, (x - x.mean()) * 1e6, lw=0.7, label=label)
    orb.set_xlabel("Y, µm")
    orb.set_ylabel("X (load), µm")
    orb.set_aspect("equal", adjustable="datalim")
    orb.invert_yaxis()
    orb.legend(fontsize=7)
    orb.set_title("last tenth of the run", fontsize=9)
    fig.suptitle(title or "nonlinear rotor")
    return fig
