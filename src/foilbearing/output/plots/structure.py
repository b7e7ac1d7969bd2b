"""Structure figures: the stiffness function (paper Fig. 7) and C-GFB vs shimmed preloads (Fig. 8)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure

from foilbearing.case import Case
from foilbearing.structure import (
    base_preload,
    preload_shape,
    stack_displacement,
    stiffness_function,
)

__all__ = ["plot_preloads", "plot_stiffness_function"]


def plot_stiffness_function(
    case: Case, smoothness: Sequence[float | None] = (5.0, 20.0, 50.0, 200.0, None)
) -> Figure:
    """k(θ) around the bearing for several smoothness constants α (paper Fig. 7)."""
    act, foil = case.actuators, case.foil
    if act is None or foil is None:
        raise ValueError("the stiffness function needs a case with [foil] and [actuators]")
    k_assy = case.assembly_stiffness()
    assert k_assy is not None
    theta = np.linspace(0.0, 2.0 * np.pi, 2001)
    fig = Figure(figsize=(7.5, 4.0), layout="constrained")
    ax = fig.subplots()
    for alpha in smoothness:
        k = stiffness_function(
            theta, foil.bump_stiffness, k_assy, act.angles, act.stinger_arc, alpha
        )
        label = "original (step)" if alpha is None else f"α = {alpha:g} /rad"
        style = {"color": "k", "lw": 1.0, "ls": "--"} if alpha is None else {"lw": 1.5}
        ax.plot(np.degrees(theta), k / 1e9, label=label, **style)
    ax.set_xlabel("θ (deg, counter-clockwise from −X)")
    ax.set_ylabel("k(θ) (10⁹ N/m³)")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 60))
    ax.set_title(
        f"Structural stiffness function: k_b = {foil.bump_stiffness / 1e9:.3g}e9, "
        f"k_assy = {k_assy / 1e9:.3g}e9 N/m³"
    )
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(alpha=0.3)
    return fig


def plot_preloads(case: Case, voltages: Sequence[float] = (0.0, 50.0, 100.0, 150.0)) -> Figure:
    """Stack stroke, base piezoelectric preload and shim thickness vs voltage, and r_p(θ) (Fig. 8)."""
    act = case.actuators
    if act is None:
        raise ValueError("the preload figure needs a case with [actuators]")
    v = np.linspace(0.0, act.max_voltage, 151)
    stroke = stack_displacement(v, act.d33_quadratic, act.d33_linear)
    base = base_preload(
        v,
        act.d33_quadratic,
        act.d33_linear,
        act.k_p,
        act.holder_spring_stiffness,
        act.holder_pre_extension,
    )
    fig = Figure(figsize=(11, 4.0), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    ax1.plot(v, stroke * 1e6, label="PZT stack free stroke (Eq. 2)")
    ax1.plot(v, base * 1e6, "--", label="base piezoelectric preload (Eq. 3b) = shim thickness")
    vv = np.asarray(voltages, dtype=float)
    bb = base_preload(
        vv,
        act.d33_quadratic,
        act.d33_linear,
        act.k_p,
        act.holder_spring_stiffness,
        act.holder_pre_extension,
    )
    ax1.plot(vv, bb * 1e6, "o", color="C1")
    for x, y in zip(vv, bb, strict=True):
        ax1.annotate(
            f"{y * 1e6:.2f} µm",
            (x, y * 1e6),
            textcoords="offset points",
            xytext=(-25, 8),
            fontsize=8,
        )
    ax1.set_xlabel("driving voltage (V)")
    ax1.set_ylabel("displacement (µm)")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    theta = np.linspace(0.0, 2.0 * np.pi, 721)
    for volt, delta in zip(vv, bb, strict=True):
        r_p = preload_shape(theta, act.angles, np.full(len(act.angles), delta))
        ax2.plot(np.degrees(theta), r_p * 1e6, label=f"{volt:g} V")
    for a in act.angles:
        lo, hi = math.degrees(a - act.stinger_arc / 2), math.degrees(a + act.stinger_arc / 2)
        ax2.axvspan(lo, hi, color="0.85", zorder=0)
    ax2.set_xlabel("θ (deg); grey: stinger arcs")
    ax2.set_ylabel("preload r_p(θ) (µm)")
    ax2.set_xlim(0, 360)
    ax2.set_xticks(range(0, 361, 60))
    ax2.set_ylim(0.0, 1.35 * max(float(np.max(bb)) * 1e6, 1.0))
    ax2.legend(
        fontsize=8,
        ncol=len(vv),
        loc="upper center",
        title="C-GFB = shimmed GFB at no load",
        title_fontsize=8,
    )
    ax2.grid(alpha=0.3)
    return fig
