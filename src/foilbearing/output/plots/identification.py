"""Figures of the PZT stack identification: no-load curves (paper Fig. 5b), stiffness (Figs. 6b-c).

The figures are built on :class:`matplotlib.figure.Figure` directly, without
pyplot, so no GUI backend is ever selected; save them with ``fig.savefig``.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from foilbearing.identification import (
    MANUFACTURER_D33,
    NoLoadData,
    NoLoadFit,
    StiffnessData,
    StiffnessFit,
)

__all__ = ["plot_no_load", "plot_stiffness"]

_UM = 1e-6


def plot_no_load(data: NoLoadData, fit: NoLoadFit) -> Figure:
    """Stack displacement against voltage with no load (paper Fig. 5b).

    One axes: the readings of each stack (markers), its quadratic fit (dashed,
    same colour), the pooled fit ``δ = D33,1 V² + D33,2 V`` (black) and the
    manufacturer's linear ``δ = 0.467 µm/V · V`` (grey dash-dot): ``2 n_stacks + 2`` lines.
    """
    fig = Figure(figsize=(6.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    v = np.linspace(0.0, float(np.max(data.voltage)), 201)
    for i, s in enumerate(data.stacks):
        (points,) = ax.plot(
            data.voltage, data.displacement[i] / _UM, "o", ms=4, label=f"stack #{s} (measured)"
        )
        ax.plot(v, fit.stacks[s].displacement(v) / _UM, "--", color=points.get_color(), lw=1.0)
    p = fit.pooled
    ax.plot(
        v,
        p.displacement(v) / _UM,
        "k-",
        lw=2.0,
        label=(
            f"fit δ = {p.d33_1_um_per_V2:.4f} V² + {p.d33_2_um_per_V:.4f} V"
            f" (R² = {p.r_squared:.4f})"
        ),
    )
    ax.plot(
        v,
        MANUFACTURER_D33 * v / _UM,
        "-.",
        color="0.5",
        label=f"manufacturer D33 = {MANUFACTURER_D33 / _UM:.3f} µm/V",
    )
    ax.set_xlabel("driving voltage V [V]")
    ax.set_ylabel("stack displacement δ [µm]")
    ax.set_title("PZT stack displacement, no load (dashed: per-stack fits)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig


def plot_stiffness(data: StiffnessData, fit: StiffnessFit, stack: str | None = None) -> Figure:
    """Stack displacement against load (paper Fig. 6b) and K_p per stack (Fig. 6c).

    Left axes: readings of ``stack`` (default: the first) at each voltage with
    the fitted lines (``2 n_voltages`` lines). Right axes: bar chart of K_p per
    stack with standard-error bars and the mean over the stacks (one line).
    """
    stack = data.stacks[0] if stack is None else stack
    if stack not in data.stacks:
        raise ValueError(f"stack {stack!r} is not in the data (stacks: {', '.join(data.stacks)})")
    fig = Figure(figsize=(10.0, 4.2), layout="constrained")
    ax_line, ax_bar = fig.subplots(1, 2, gridspec_kw={"width_ratios": [3, 2]})
    for line in (f for f in fit.lines if f.stack == stack):
        mask = (data.stack == stack) & (data.voltage == line.voltage)
        load = data.load[mask]
        (points,) = ax_line.plot(
            load, data.displacement[mask] / _UM, "o", ms=4, label=f"{line.voltage:g} V"
        )
        f = np.array([0.0, float(np.max(load))])
        ax_line.plot(f, (line.intercept + line.slope * f) / _UM, "-", color=points.get_color())
    ax_line.set_xlabel("static load F [N]")
    ax_line.set_ylabel("stack displacement δ [µm]")
    ax_line.set_title(f"stack #{stack}: lines δ = δ0(V) − F/K_p")
    ax_line.grid(True, alpha=0.3)
    ax_line.legend(title="voltage", fontsize="small")

    labels = list(fit.stack_stiffness)
    values = np.array([fit.stack_stiffness[s] for s in labels]) / 1e6
    errors = np.array([fit.stack_stiffness_se[s] for s in labels]) / 1e6
    ax_bar.bar([f"#{s}" for s in labels], values, yerr=errors, capsize=4, color="tab:blue")
    mean = fit.mean_stiffness / 1e6
    ax_bar.axhline(mean, color="k", ls="--", label=f"mean {mean:.3f}e6 N/m")
    ax_bar.set_xlabel("PZT stack")
    ax_bar.set_ylabel("stack stiffness K_p [1e6 N/m]")
    ax_bar.set_title(f"K_p per stack; k_p = K_p/A_c = {fit.k_p / 1e9:.2f}e9 N/m³")
    ax_bar.legend(fontsize="small", loc="lower right")
    return fig
