"""Static figures from a :func:`foilbearing.study.static.static_sweep` dataset (paper Figs. 9-12)."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = ["plot_actuator_pressure", "plot_eccentricity", "plot_midplane", "plot_preload"]

STYLE = {"C-GFB": "-", "shimmed": "--"}


def _colours(n: int) -> list[Any]:
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.85, n)]


def plot_midplane(ds: Any, speed_krpm: float = 50.0) -> Figure:
    """Mid-plane pressure and film thickness around the bearing at one speed (Fig. 9)."""
    sel = ds.sel(speed=speed_krpm, method="nearest")
    bearings = list(ds.bearing.values)
    fig = Figure(figsize=(6.0 * len(bearings), 6.5), layout="constrained")
    axes = fig.subplots(2, len(bearings), sharex=True, squeeze=False)
    colours = _colours(ds.sizes["voltage"])
    for b, name in enumerate(bearings):
        ax_p, ax_h = axes[0, b], axes[1, b]
        for v, volt in enumerate(ds.voltage.values):
            row = sel.sel(bearing=name).isel(voltage=v)
            lbl = f"{volt:g} V" if name == "C-GFB" else f"shim {volt:g} V"
            ax_p.plot(ds.theta, row.midplane_pressure, color=colours[v], label=lbl)
            ax_h.plot(ds.theta, row.midplane_film, color=colours[v], label=lbl)
        ax_p.set_title(f"{name}, {float(sel.speed):g} krpm")
        ax_p.set_ylabel("mid-plane pressure p (kPa, absolute)")
        ax_h.set_ylabel("film thickness h (µm)")
        ax_h.set_xlabel("θ (deg)")
        ax_h.set_xticks(range(0, 361, 60))
        for ax in (ax_p, ax_h):
            ax.grid(alpha=0.3)
            for a in ds.actuator.values:
                ax.axvline(a, color="0.6", lw=0.8, ls=":")
        ax_p.legend(fontsize=8)
    return fig


def _per_actuator(ds: Any, var: str, ylabel: str, title: str) -> Figure:
    n_act = ds.sizes["actuator"]
    fig = Figure(figsize=(4.2 * n_act, 4.0), layout="constrained")
    axes = fig.subplots(1, n_act, sharey=True, squeeze=False)[0]
    colours = _colours(ds.sizes["voltage"])
    for k, ax in enumerate(axes):
        for name in ds.bearing.values:
            for v, volt in enumerate(ds.voltage.values):
                y = ds[var].sel(bearing=name).isel(voltage=v, actuator=k)
                ax.plot(
                    ds.speed,
                    y,
                    STYLE.get(str(name), "-"),
                    marker="o",
                    ms=3,
                    color=colours[v],
                    label=f"{name} {volt:g} V",
                )
        ax.set_title(f"θ = {float(ds.actuator[k]):g}°")
        ax.set_xlabel("speed (krpm)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(ylabel)
    axes[-1].legend(fontsize=7, ncol=2)
    fig.suptitle(title)
    return fig


def plot_actuator_pressure(ds: Any) -> Figure:
    """Axially averaged gauge pressure at each actuator vs speed (Fig. 10)."""
    return _per_actuator(
        ds,
        "actuator_pressure",
        "p_A (kPa, gauge)",
        "Local film pressure at the actuators (solid C-GFB, dashed shimmed)",
    )


def plot_preload(ds: Any) -> Figure:
    """Piezoelectric preload at each actuator vs speed, C-GFB only (Fig. 11)."""
    return _per_actuator(
        ds.sel(bearing=["C-GFB"]),
        "preload",
        "δ_PZT (µm)",
        "Piezoelectric preload under film pressure (Eq. 3b)",
    )


def plot_eccentricity(ds: Any) -> Figure:
    """Eccentricity and attitude vs speed, and the equilibrium loci (Fig. 12)."""
    fig = Figure(figsize=(13, 4.2), layout="constrained")
    ax_e, ax_a, ax_xy = fig.subplots(1, 3)
    colours = _colours(ds.sizes["voltage"])
    for name in ds.bearing.values:
        for v, volt in enumerate(ds.voltage.values):
            row = ds.sel(bearing=name).isel(voltage=v)
            kw = {"color": colours[v], "ls": STYLE.get(str(name), "-"), "marker": "o", "ms": 3}
            label = f"{name} {volt:g} V"
            ax_e.plot(ds.speed, row.eccentricity, label=label, **kw)
            ax_a.plot(ds.speed, row.attitude, **kw)
            ax_xy.plot(row.eps_y, row.eps_x, **kw)
    ax_e.set_ylabel("eccentricity ε₀")
    ax_a.set_ylabel("attitude angle φ₀ (deg)")
    for ax in (ax_e, ax_a):
        ax.set_xlabel("speed (krpm)")
        ax.grid(alpha=0.3)
    ax_xy.set_xlabel("ε_Y")
    ax_xy.set_ylabel("ε_X (load direction, down)")
    ax_xy.invert_yaxis()
    ax_xy.set_aspect("equal", adjustable="datalim")
    ax_xy.grid(alpha=0.3)
    ax_xy.set_title("equilibrium loci (speed rising → towards centre)")
    ax_e.legend(fontsize=7, ncol=2)
    return fig


def plot_point(result: Any) -> Figure:
    """Pressure and film thickness around the bearing for one static result."""
    g = result.model.grid
    pa, c = result.case.gas.ambient_pressure, result.case.bearing.clearance
    theta = np.degrees(g.theta)
    fig = Figure(figsize=(8, 6), layout="constrained")
    ax_p, ax_h = fig.subplots(2, 1, sharex=True)
    ax_p.plot(theta, result.P[:, 0] * pa / 1e3, label="next to the mid-plane")
    ax_p.plot(theta, (g.gauge_mean(result.P) + 1.0) * pa / 1e3, "--", label="axial mean")
    ax_p.set_ylabel("p (kPa, absolute)")
    ax_p.legend(fontsize=8)
    ax_h.plot(theta, result.H[:, 0] * c * 1e6, label="film h")
    ax_h.plot(theta, result.model.preload * c * 1e6, ":", label="preload shape r_p")
    ax_h.set_ylabel("µm")
    ax_h.set_xlabel("θ (deg)")
    ax_h.set_xticks(range(0, 361, 60))
    ax_h.legend(fontsize=8)
    for ax in (ax_p, ax_h):
        ax.grid(alpha=0.3)
    h = result.headline()
    ax_p.set_title(
        f"{h['bearing']} at {h['speed_rpm']:.0f} rpm: ε = {h['eccentricity']:.3f}, "
        f"φ = {h['attitude_deg']:.1f}°, h_min = {h['min_film_um']:.1f} µm"
    )
    return fig
