"""Figures of an uncertainty analysis: percentile bands and sensitivity indices."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = ["plot_bands", "plot_indices"]

_STATIC = (
    ("eccentricity_ratio", "eccentricity ratio ε"),
    ("attitude_deg", "attitude angle (deg)"),
    ("min_film_um", "minimum film (µm)"),
    ("power_loss_W", "power loss (W)"),
    ("preload_um", "preload (µm)"),
)
_STABILITY = (
    ("onset_speed_krpm", "linear onset speed (krpm)"),
    ("whirl_frequency_Hz", "whirl frequency at onset (Hz)"),
    ("orbit_onset_krpm", "speed-up: sub-synchronous onset (krpm)"),
    ("orbit_whip_frequency_Hz", "speed-up: whip frequency (Hz)"),
    ("orbit_divergence_krpm", "speed-up: divergence (krpm)"),
    ("orbit_max_subsync_um", "speed-up: largest sub-synchronous (µm)"),
)


def _select(ds: Any, quantity: str) -> Any:
    return ds.isel(output=np.flatnonzero(ds["quantity"].values == quantity))


def _band(ax: Any, x: np.ndarray, pct: np.ndarray, label: str, color: Any) -> None:
    keep = np.isfinite(x) & np.isfinite(pct).all(axis=0)
    order = np.argsort(x[keep])
    x, lo, mid, hi = (a[keep][order] for a in (x, pct[0], pct[1], pct[2]))
    if x.size > 1:
        ax.fill_between(x, lo, hi, color=color, alpha=0.25, lw=0)
    ax.errorbar(
        x,
        mid,
        yerr=[mid - lo, hi - mid],
        fmt="-o",
        color=color,
        ms=3,
        capsize=3,
        lw=1.2,
        label=label,
    )


def plot_bands(ds: Any, paper: dict[str, Any] | None = None) -> Figure:
    """The 5-95 % band and the median of each output against speed and voltage.

    Static readouts against speed (one band per voltage; preloads one band per
    actuator at the highest voltage), linear onset speed and whirl frequency
    against voltage. ``paper`` (:data:`foilbearing.paper.PAPER`) adds the
    paper's points: the preloads at 150 V, 90 krpm and the whip frequencies of
    its speed-ups (read from nonlinear runs, drawn as such).
    """
    panels = [(q, lab) for q, lab in _STATIC if (ds["quantity"] == q).any()]
    panels += [(q, lab) for q, lab in _STABILITY if (ds["quantity"] == q).any()]
    ncol = min(3, max(len(panels), 1))
    nrow = -(-len(panels) // ncol) if panels else 1
    fig = Figure(figsize=(4.2 * ncol, 3.4 * nrow), layout="constrained")
    axes = np.atleast_1d(fig.subplots(nrow, ncol)).ravel()
    colors = [f"C{k}" for k in range(10)]
    for ax, (q, label) in zip(axes, panels, strict=False):
        sub = _select(ds, q)
        pct = sub["percentile"].values
        volts = sub["voltage_V"].values
        if q in dict(_STABILITY):
            x = np.where(np.isfinite(volts), volts, 0.0)
            _band(ax, x, pct, "median; band 5-95 %", "C0")
            ax.set_xlabel("actuator voltage (V)")
            if paper and q == "whirl_frequency_Hz":
                vs, fs = zip(*sorted(paper["whip_frequency_Hz"].items()), strict=True)
                ax.plot(vs, fs, "k^", mfc="none", label="paper: whip in its speed-ups (nonlinear)")
        elif q == "preload_um":
            top = np.nanmax(volts) if np.isfinite(volts).any() else np.nan
            at_top = volts == top if np.isfinite(top) else ~np.isfinite(volts)
            for a in sorted(set(sub["actuator"].values)):
                m = at_top & (sub["actuator"].values == a)
                _band(ax, sub["speed_krpm"].values[m], pct[:, m], f"actuator {a}", colors[a % 10])
            ax.set_xlabel(f"speed (krpm), {top:g} V" if np.isfinite(top) else "speed (krpm)")
            if paper and top == 150.0:
                pts = paper["preload_150V_90krpm_um"]
                for a, v in enumerate(pts, start=1):
                    ax.plot(
                        [90.0],
                        [v],
                        "k^",
                        mfc=colors[a % 10],
                        ms=7,
                        label="paper, 150 V, 90 krpm" if a == 1 else None,
                    )
        else:
            for k, v in enumerate(dict.fromkeys(volts.tolist())):
                m = (volts == v) | (np.isnan(volts) & np.isnan(v))
                name = "case voltages" if np.isnan(v) else f"{v:g} V"
                _band(ax, sub["speed_krpm"].values[m], pct[:, m], name, colors[k % 10])
            ax.set_xlabel("speed (krpm)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if not np.isfinite(pct).any():
            ax.text(
                0.5,
                0.5,
                "none in the sample\n(the points' messages say why)",
                ha="center",
                va="center",
                transform=ax.transAxes,
                color="0.4",
            )
            continue
        ax.legend(fontsize=7)
    for ax in axes[len(panels) :]:
        ax.set_visible(False)
    n_ok = int((ds["status"].values == "ok").sum())
    fig.suptitle(
        f"{ds.attrs.get('title') or 'Uncertainty'}: median and 5-95 % band "
        f"({n_ok} of {ds.sizes['sample']} points)"
    )
    return fig


def plot_indices(ds: Any, max_outputs: int = 12) -> Figure:
    """First-order (filled) and total (outlined) indices of each input, per output.

    The outputs shown are the linear ones and the static ones at the highest
    speed (at most ``max_outputs``); the whiskers are the 95 % bootstrap
    half-widths.
    """
    speeds = ds["speed_krpm"].values
    top = np.nanmax(speeds) if np.isfinite(speeds).any() else np.nan
    keep = [
        j
        for j, (q, s, a) in enumerate(
            zip(ds["quantity"].values, speeds, ds["actuator"].values, strict=True)
        )
        if (not np.isfinite(s) or s == top) and q != "attitude_deg" and a in (0, 2)
    ][:max_outputs]
    inputs = [str(i) for i in ds["input"].values]
    n_in = len(inputs)
    fig = Figure(figsize=(9.0, 0.55 * len(keep) * max(n_in, 3) / 3 + 1.6), layout="constrained")
    ax = fig.subplots()
    height = 0.8 / max(n_in, 1)
    y0 = np.arange(len(keep))[::-1]
    for k, name in enumerate(inputs):
        y = y0 + 0.4 - (k + 0.5) * height
        s1 = ds["first_order"].values[keep, k]
        s1c = ds["first_order_conf"].values[keep, k]
        ax.barh(
            y,
            s1,
            height,
            xerr=s1c,
            color=f"C{k}",
            label=f"{name}: first order",
            error_kw={"lw": 0.6},
        )
        st = ds["total_order"].values[keep, k]
        if np.isfinite(st).any():
            ax.barh(y, st, height, fill=False, edgecolor=f"C{k}", lw=1.2)
    ax.set_yticks(y0, [str(ds["output"].values[j]) for j in keep], fontsize=7)
    ax.axvline(0.0, color="0.3", lw=0.6)
    ax.set_xlim(-0.1, 1.05)
    ax.set_xlabel("sensitivity index (filled: first order; outline: total)")
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(axis="x", alpha=0.3)
    told = ds.attrs.get("indices_from") or f"{ds.attrs.get('estimator')} estimator"
    ax.set_title(f"Which input matters: {told}", fontsize=9)
    return fig
