"""Figures of the speed-up orbit: transient, waterfalls, sub-synchronous amplitude, orbits.

The paper's Figs. 13–15. Inputs are arrays (SI: s, m, rad/s) and the results
of `foilbearing.signals`; displacements are drawn in µm, speeds in krpm.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = [
    "WATERFALL_FLOOR_DB",
    "plot_orbits",
    "plot_subsync",
    "plot_transient",
    "plot_waterfall",
    "plot_waterfall_3d",
]

UM = 1e6
KRPM = 30.0 / np.pi / 1e3  # rad/s → krpm


def plot_transient(
    t: np.ndarray, e_x: np.ndarray, e_y: np.ndarray, speed: np.ndarray, clearance: float
) -> Figure:
    """e_X and e_Y (µm) against time, with the speed (krpm) on a twin axis (Figs. 13a, 14)."""
    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.subplots()
    ax.plot(t, np.asarray(e_x) * UM, lw=0.6, label="e_X (along load)")
    ax.plot(t, np.asarray(e_y) * UM, lw=0.6, label="e_Y")
    for s in (-1, 1):
        ax.axhline(s * clearance * UM, color="0.4", lw=0.8, ls=":")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("journal eccentricity (µm); dotted: ±C")
    ax.grid(alpha=0.3)
    ax_s = ax.twinx()
    ax_s.plot(t, np.asarray(speed) * KRPM, color="k", lw=1.2, label="speed")
    ax_s.set_ylabel("speed (krpm)")
    lines = ax.get_legend_handles_labels()
    lines_s = ax_s.get_legend_handles_labels()
    ax.legend(lines[0] + lines_s[0], lines[1] + lines_s[1], loc="upper left", fontsize=8)
    return fig


#: Bottom of the waterfall's colour scale, dB re the largest amplitude shown.
WATERFALL_FLOOR_DB = -60.0


def plot_waterfall(
    wf: Any,
    *,
    fmax_hz: float | None = None,
    vmax_um: float | None = None,
    floor_db: float = WATERFALL_FLOOR_DB,
    onset_whirl_hz: float | None = None,
) -> Figure:
    """Waterfall as a colour map: frequency against speed, amplitude in dB as colour, 1X and 0.5X.

    The colour is the amplitude in dB re the largest amplitude shown,
    ``20 log10(A / A_max)``, from ``floor_db`` to 0 dB, as rotordynamic
    waterfalls are drawn: a sub-synchronous whirl 40 dB below the 1X line takes
    a third of the colours, where on a linear scale it would take 1 %. The
    reference amplitude is in the colour bar's label.

    Parameters
    ----------
    wf
        The waterfall (:class:`foilbearing.signals.Waterfall`; amplitude in m).
    fmax_hz
        Top of the frequency axis, Hz (default 1.2 × the highest running frequency).
    vmax_um
        Reference amplitude of 0 dB, µm, instead of the largest one, so that a
        diverging whip does not push the rest down to the floor; above it the
        colour is that of 0 dB.
    floor_db
        Bottom of the colour scale, dB (< 0); smaller amplitudes, and zero, take its colour.
    onset_whirl_hz
        Whirl frequency at the linear onset of instability, Hz, drawn as a
        horizontal line (None: not drawn).
    """
    if not floor_db < 0.0:
        raise ValueError(f"floor_db = {floor_db!r}: expected a level below 0 dB")
    fmax = fmax_hz if fmax_hz is not None else 1.2 * float(np.max(wf.speeds_rpm)) / 60.0
    keep = wf.frequencies_hz <= fmax
    amp_um = wf.amplitude[:, keep].T * UM
    finite = amp_um[np.isfinite(amp_um)]
    ref = vmax_um if vmax_um is not None else (float(finite.max()) if finite.size else 0.0)
    if not ref > 0.0:
        ref = 1.0  # nothing to show: all at the floor
    with np.errstate(invalid="ignore"):
        ratio = np.clip(amp_um / ref, 10 ** (floor_db / 20), 1.0)
    fig = Figure(figsize=(8.5, 4.5), layout="constrained")
    ax = fig.subplots()
    mesh = ax.pcolormesh(
        wf.speeds_rpm / 1e3,
        wf.frequencies_hz[keep],
        20.0 * np.log10(ratio),
        shading="nearest",
        cmap="viridis",
        vmin=floor_db,
        vmax=0.0,
    )
    for order, style in ((1.0, "--"), (0.5, ":")):
        ax.plot(
            wf.speeds_rpm / 1e3,
            order * wf.speeds_rpm / 60.0,
            "w" + style,
            lw=1,
            label=f"{order:g}X",
        )
    if onset_whirl_hz is not None:
        ax.axhline(
            onset_whirl_hz,
            color="tab:red",
            ls="-.",
            lw=1,
            label=f"linear onset whirl, {onset_whirl_hz:.0f} Hz",
        )
    ax.set_ylim(0, fmax)
    ax.set_xlabel("speed (krpm)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title(f"Waterfall (Hann, {wf.window_s:g} s windows)")
    ax.legend(loc="upper left", fontsize=8)
    largest = "" if vmax_um is not None else ", the largest"
    fig.colorbar(
        mesh, ax=ax, label=f"amplitude (dB re {ref:.3g} µm{largest}; floor {floor_db:g} dB)"
    )
    return fig


def plot_waterfall_3d(wf: Any, *, max_lines: int = 60, fmax_hz: float | None = None) -> Figure:
    """3-D waterfall: one spectrum line per window (at most ``max_lines``), amplitude in µm."""
    fmax = fmax_hz if fmax_hz is not None else 1.2 * float(np.max(wf.speeds_rpm)) / 60.0
    keep = wf.frequencies_hz <= fmax
    rows = np.unique(np.linspace(0, wf.times.size - 1, min(max_lines, wf.times.size)).astype(int))
    fig = Figure(figsize=(8, 6), layout="constrained")
    ax: Any = fig.add_subplot(projection="3d")
    f = wf.frequencies_hz[keep]
    for i in rows:
        ax.plot(
            f,
            np.full(f.size, wf.speeds_rpm[i] / 1e3),
            wf.amplitude[i, keep] * UM,
            lw=0.7,
            color="C0",
        )
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("speed (krpm)")
    ax.set_zlabel("amplitude (µm)")
    ax.view_init(elev=30, azim=-60)
    return fig


def plot_subsync(results: Mapping[str, Any], onsets: Mapping[str, Any] | None = None) -> Figure:
    """Sub-synchronous amplitude (µm) against speed, one line per case, onsets marked (Fig. 15)."""
    fig = Figure(figsize=(8, 4.2), layout="constrained")
    ax = fig.subplots()
    onsets = onsets or {}
    for j, (label, sub) in enumerate(results.items()):
        color = f"C{j % 10}"
        ax.plot(sub.speeds_rpm / 1e3, sub.amplitude * UM, color=color, label=label)
        on = onsets.get(label)
        if on is not None and on.onset_speed_rpm is not None:
            freq = f", {on.whirl_frequency_hz:.0f} Hz" if on.whirl_frequency_hz else ""
            ax.plot(
                on.onset_speed_rpm / 1e3,
                on.threshold * UM,
                "v",
                color=color,
                ms=8,
                label=f"onset {on.onset_speed_rpm / 1e3:.1f} krpm{freq}",
            )
    ax.set_xlabel("speed (krpm)")
    ax.set_ylabel("sub-synchronous amplitude (µm)")
    ax.set_title("Filtered sub-synchronous amplitude (1X removed by order tracking)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def plot_orbits(
    t: np.ndarray,
    e_x: np.ndarray,
    e_y: np.ndarray,
    speed: np.ndarray,
    at_rpm: Sequence[float],
    clearance: float,
    *,
    revolutions: float = 10.0,
) -> Figure:
    """Journal orbits over ``revolutions`` turns centred on each speed in ``at_rpm``.

    Small multiples, e_Y across and e_X (along the load) up, in µm, with the
    clearance circle. A speed the run never reached is marked as such; a speed held to
    the end of the run (a constant-speed run) shows its last revolutions.
    """
    t, e_x, e_y, speed = (np.asarray(a, dtype=float) for a in (t, e_x, e_y, speed))
    n = max(len(at_rpm), 1)
    ncols = min(n, 4)
    nrows = -(-n // ncols)
    fig = Figure(figsize=(3.0 * ncols, 3.0 * nrows + 0.4), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrows, ncols, squeeze=False)).ravel()
    circle = np.linspace(0, 2 * np.pi, 200)
    c = clearance * UM
    for ax, rpm in zip(axes, at_rpm, strict=False):
        w = rpm / KRPM / 1e3
        ax.plot(c * np.cos(circle), c * np.sin(circle), color="0.5", lw=0.8)
        ax.set_aspect("equal")
        ax.set_title(f"{rpm / 1e3:.1f} krpm", fontsize=9)
        ax.set_xlabel("e_Y (µm)")
        ax.set_ylabel("e_X (µm)")
        reached = np.flatnonzero(speed >= w)
        if w <= 0 or reached.size == 0:
            ax.text(0, 0, "not reached", ha="center", va="center")
            continue
        tc = t[reached[0]]
        half = 0.5 * revolutions * 2 * np.pi / w
        if np.ptp(speed[reached[0] :]) <= 1e-9 * w:  # held to the end: its last revolutions
            tc = max(tc, t[-1] - half)
        sel = (t >= tc - half) & (t <= tc + half)
        ax.plot(e_y[sel] * UM, e_x[sel] * UM, lw=0.7)
    for ax in axes[len(at_rpm) :]:
        ax.set_visible(False)
    sep = "; " if ncols > 1 else ";\n"  # one panel is too narrow for one line
    fig.suptitle(f"Journal orbits, {revolutions:g} revolutions each{sep}circle: clearance C")
    return fig
