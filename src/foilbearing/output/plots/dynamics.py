"""Figures of the linear analysis: coefficients against frequency, the stability map."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = [
    "plot_coefficients",
    "plot_coefficients_over_speed",
    "plot_stability_map",
    "plot_stack_design",
]

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
    volts = ", ".join(f"{v:g}" for v in h["voltages_V"])  # none on a bearing without actuators
    fig.suptitle(
        f"{h['bearing']} at {h['speed_rpm']:.0f} rpm"
        + (f", {volts} V" if volts else "")
        + f": ε = {h['eccentricity']:.3f}"
    )
    return fig


def plot_coefficients_over_speed(sweep: Any) -> Figure:
    """Stiffness K_ij (MN/m) and damping C_ij (kN·s/m) against rotor speed, at the
    sweep's first excitation frequency (or ratio ω_e/ω)."""
    rpm = sweep.speeds * 30 / np.pi
    K = np.array([fc.K[0] for fc in sweep.points])
    C = np.array([fc.C[0] for fc in sweep.points])
    fig = Figure(figsize=(11, 4.2), layout="constrained")
    ax_k, ax_c = fig.subplots(1, 2, sharex=True)
    for name, i, j in LABELS:
        style = "-" if i == j else "--"
        ax_k.plot(rpm, K[:, i, j] / 1e6, style, marker="o", ms=3, label=f"K_{name}")
        ax_c.plot(rpm, C[:, i, j] / 1e3, style, marker="o", ms=3, label=f"C_{name}")
    for ax in (ax_k, ax_c):
        ax.set_xlabel("rotor speed (rpm)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    ax_k.set_ylabel("stiffness (MN/m)")
    ax_c.set_ylabel("damping (kN·s/m)")
    first = sweep.points[0]
    at = (
        f"ω_e/ω = {sweep.frequency_ratios[0]:.3g}"
        if sweep.frequency_ratios is not None
        else f"{first.frequencies[0] / (2 * np.pi):.4g} Hz"
    )
    case = first.static.case
    fig.suptitle(f"{case.kind}, {case.operation.load:.4g} N, at {at}")
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


def plot_stack_design(design: Any) -> Figure:
    """Onset against the stack stiffness under each reading, with the shimmed GFB's onset and
    the target fraction of it (:class:`foilbearing.design.StackDesign`)."""
    rpm = np.pi / 30.0
    fig = Figure(figsize=(8.5, 4.5), layout="constrained")
    ax = fig.subplots()
    k_p = design.stack_stiffness * design.factors / 1e6
    top = design.max_speed / rpm / 1e3
    styles = {"compliant": "-", "held": "--"}
    for key, onsets in design.onsets.items():
        response, dynamics = key.split("+")
        y = np.where(np.isnan(onsets), top, onsets / rpm / 1e3)
        ax.semilogx(k_p, y, styles[dynamics], marker="o" if response == "local" else "s", label=key)
    if design.shimmed_onset is not None:
        shim = design.shimmed_onset / rpm / 1e3
        ax.axhline(shim, color="k", lw=1.2, label="shimmed GFB (ideal positioner)")
        ax.axhline(
            design.target * shim, color="k", lw=0.8, ls=":", label=f"{design.target:.0%} of it"
        )
    ax.axvline(design.stack_stiffness / 1e6, color="0.5", lw=0.8, ls="-.", label="identified K_p")
    ax.set_xlabel("stack stiffness K_p (MN/m)")
    ax.set_ylabel(f"linear onset (krpm; {top:.0f} = stable over the scan)")
    ax.set_title(f"What the stack's stiffness buys at {design.voltage:g} V")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    return fig
