"""Figures of the linear analysis: coefficients against frequency, the stability map."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = ["plot_coefficients", "plot_stability_map"]

LABELS = (("XX", 0, 0), ("XY", 0, 1), ("YX", 1, 0), ("YY", 1, 1))


def plot_coefficients(fc: Any) -> Figure:
    """Stiffness K_ij (MN/m) and damping C_ij (kN·s/m) against excitation frequency."""
    f = fc.frequencies / (2 * np.pi)
    fig = Figure(figsize=(11, 4.2), layout="constrained")
    ax_k, ax_c = fig.subplots(1, 2, sharex=True)
    for name, i, j in LABELS:
        style = "-" if i == j else "--"
        ax_k.plot(f, fc.K[:, i, j] / 1e6, style, marker="o", ms=3, label=f"K_{name}")
        ax_c.plot(f, fc.C[:, i, j] / 1e3, style, marker="o", ms=3, label=f"C_{name}")
    sync = fc.static.speed / (2 * np.pi)
    for ax in (ax_k, ax_c):
        ax.axvline(sync, color="0.5", lw=0.8, ls=":")
        ax.set_xlabel("excitation frequency (Hz); dotted: synchronous")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    ax_k.set_ylabel("stiffness (MN/m)")
    ax_c.set_ylabel("damping (kN·s/m)")
    h = fc.static.headline()
    fig.suptitle(
        f"{h['bearing']} at {h['speed_rpm']:.0f} rpm, "
        f"{', '.join(f'{v:g}' for v in h['voltages_V']) or '–'} V: ε = {h['eccentricity']:.3f}"
    )
    return fig


def plot_stability_map(ds: Any, onsets: Sequence[float | None] | None = None) -> Figure:
    """Speed × voltage coloured by the log decrement of the least stable whirl mode."""
    fig = Figure(figsize=(8.5, 4.2), layout="constrained")
    ax = fig.subplots()
    dec = ds.log_decrement.values
    lim = float(np.nanmax(np.abs(dec))) if np.isfinite(dec).any() else 1.0
    mesh = ax.pcolormesh(
        ds.speed, ds.voltage, dec, cmap="RdBu", vmin=-lim, vmax=lim, shading="nearest"
    )
    ax.contour(ds.speed, ds.voltage, dec, levels=[0.0], colors="k", linewidths=1.5)
    if onsets is not None:
        xs = [o / 1e3 for o in onsets if o is not None]
        ys = [v for v, o in zip(ds.voltage.values, onsets, strict=True) if o is not None]
        ax.plot(xs, ys, "k*", ms=10, label="onset (Brent)")
        ax.legend(loc="upper right", fontsize=8)
    fig.colorbar(mesh, ax=ax, label="log decrement δ (> 0 stable, blue)")
    ax.set_xlabel("speed (krpm)")
    ax.set_ylabel("actuator voltage (V)")
    ax.set_title(
        f"Linear stability map, {ds.attrs.get('bearing', '')}, rigid rotor "
        f"{ds.attrs.get('rotor_mass_kg', 0):.3g} kg per bearing"
    )
    return fig
