"""Benchmark of the smoothed lift-off edge (``[grid] lift_off_smoothing``): what it does to
the linear onset's convergence, and to the orbit's cost. Prints its figures.

Run: .venv/bin/python benchmarks/bench_lift_off_edge.py [--onsets] [--steps] [--voltages]

The law: each cell obeys (P − 1)·y/Λ = δ², δ = κΔθ² (``[grid] lift_off_smoothing = κ``).

- ``--onsets`` (about 1 minute): the 0 V linear onset of the default case
  - on 96 θ cells against n_z (order 4), sharp and smoothed (κ = 0.1, 0.2, 0.3);
  - on 96 to 768 θ cells (4 axial cells, order 4), sharp and smoothed, with the ratio of
    successive differences (4: second order);
  - against κ on 96 x 4 (order 4) and 192 x 12 (order 4);
  - at 0 and 150 V on the orbit-sized grids against 192 x 24 (order 2), sharp and at
    κ = 0.2.
- ``--steps`` (about 1 minute): ms a step on a smooth orbit (C-GFB, 0 V, 1 g·mm, 30 krpm)
  and a large one (shimmed GFB, 150 V, 8.5 g·mm, 50 krpm), 0.05 s each, best of 3, on
  96 x 4 (order 4) and 96 x 12, sharp and smoothed (κ = 0.2), with the Newton iterations
  and factorisations a step.
- ``--voltages`` (about 10 minutes): the linear onsets at the study's voltages (0, 50, 100,
  150 V), C-GFB and its shimmed twin, on the old default (96 x 12, sharp), the new static
  grid (96 x 12, κ = 0.1), the new orbit grid (96 x 4 order 4, κ = 0.1), that orbit grid
  at κ = 0.2, 192 x 24 and 384 x 24 of the sharp law and 384 x 24 and 768 x 24 at κ = 0.2
  (the reference: the sharp law finds no equilibrium on 768 θ cells), each with its
  largest gap to the reference (docs/development/orbit-performance.md, "The smoothing's own error:
  κ = 0.1").

Without an option ``--onsets`` and ``--steps`` run. The figures and what they mean: docs/lift-off.md, "The
smoothed edge".
"""

from __future__ import annotations

import sys
from dataclasses import replace

from foilbearing.case import Grid, default_case
from foilbearing.constants import RPM
from foilbearing.control import constant_speed
from foilbearing.errors import SolverError
from foilbearing.orbit import simulate
from foilbearing.stability import onset_speed

#: Speeds of the onset scan around the 0 V onset (rpm): the sharp law finds no equilibrium
#: at 5 krpm on 768 θ cells, where the default scan starts.
SCAN_RPM = (30e3, 35e3, 40e3, 42e3, 44e3, 46e3, 48e3, 50e3, 55e3, 60e3, 70e3, 80e3, 90e3)
#: The smoothings compared (κ; δ = κΔθ², the law (P − 1)·y/Λ = δ²), and the one the
#: comparisons against 192 x 24 and the step costs use.
KAPPAS = (0.1, 0.2, 0.3)
CHOSEN = 0.2
SWEEP = (0.0, 0.05, 0.1, 0.2, 0.3, 0.5)


def _onset(volts: float, n_theta: int, n_z: int, order: int, kappa: float) -> float | None:
    """The linear onset in krpm (None: the scan found no equilibrium or no onset)."""
    grid = Grid(n_theta, n_z, axial_order=order, lift_off_smoothing=kappa)
    case = replace(default_case().with_voltages(volts), grid=grid)
    try:
        res = onset_speed(case, [s * RPM for s in SCAN_RPM])
    except SolverError:
        return None
    return None if res.onset_speed is None else res.onset_speed / RPM / 1e3


def _krpm(x: float | None) -> str:
    return "failed" if x is None else f"{x:.3f}"


def onsets() -> None:
    """The linear onset against the grid and κ, sharp and smoothed."""
    print("0 V linear onset (krpm), 96 θ cells, order 4, against n_z:")
    for kappa in (0.0, *KAPPAS):
        values = [_onset(0.0, 96, n_z, 4, kappa) for n_z in (3, 4, 5, 6, 8, 12, 24)]
        known = [v for v in values if v is not None]
        spread = 100 * (max(known) - min(known)) / min(known)
        print(
            f"  κ = {kappa:<4g}: " + " / ".join(_krpm(v) for v in values)
            + f" on n_z = 3/4/5/6/8/12/24 (spread {spread:.2f} %)"
        )  # fmt: skip
    print("0 V linear onset (krpm), 4 axial cells, order 4, against n_theta:")
    for kappa in (0.0, *KAPPAS):
        values = [_onset(0.0, n, 4, 4, kappa) for n in (96, 192, 384, 768)]
        text = " / ".join(_krpm(v) for v in values)
        if None not in values:
            d = [values[k] - values[k + 1] for k in range(3)]  # type: ignore[operator]
            text += f" (ratios of differences {d[0] / d[1]:.1f}, {d[1] / d[2]:.1f})"
        print(f"  κ = {kappa:<4g}: {text} on 96/192/384/768")
    print("0 V linear onset (krpm) against κ:")
    for n_theta, n_z in ((96, 4), (192, 12)):
        values = [_onset(0.0, n_theta, n_z, 4, k) for k in SWEEP]
        print(
            f"  {n_theta} x {n_z}, order 4: " + " / ".join(_krpm(v) for v in values)
            + " at κ = " + "/".join(f"{k:g}" for k in SWEEP)
        )  # fmt: skip
    print("linear onset (krpm) against 192 x 24 (order 2) of the same law:")
    for volts in (0.0, 150.0):
        for kappa in (0.0, CHOSEN):
            ref = _onset(volts, 192, 24, 2, kappa)
            parts = []
            for n_theta, n_z, order in ((96, 4, 4), (96, 6, 4), (96, 12, 2), (192, 4, 4)):
                x = _onset(volts, n_theta, n_z, order, kappa)
                gap = "" if x is None or ref is None else f" ({100 * (x - ref) / ref:+.2f} %)"
                parts.append(f"{n_theta}x{n_z} o{order} {_krpm(x)}{gap}")
            print(f"  {volts:3.0f} V, κ = {kappa:g}: 192x24 {_krpm(ref)}; " + ", ".join(parts))


#: The grids of ``--voltages``: (label, n_theta, n_z, axial order, κ).
DEFAULT_GRIDS = (
    ("96 x 12, sharp (old default)", 96, 12, 2, 0.0),
    ("96 x 12, κ = 0.1 (static)", 96, 12, 2, 0.1),
    ("96 x 4 o4, κ = 0.1 (orbit)", 96, 4, 4, 0.1),
    ("96 x 4 o4, κ = 0.2", 96, 4, 4, 0.2),
    ("192 x 24, sharp", 192, 24, 2, 0.0),
    ("384 x 24, sharp", 384, 24, 2, 0.0),
    ("384 x 24, κ = 0.2", 384, 24, 2, 0.2),
    ("768 x 24, κ = 0.2 (reference)", 768, 24, 2, 0.2),
)


def voltages() -> None:
    """The linear onsets at the study's voltages, C-GFB and shimmed, on the default's grids."""
    import numpy as np

    scan = [s * RPM for s in np.arange(30e3, 100e3 + 1.0, 2.5e3)]
    print("linear onset (krpm) at 0 / 50 / 100 / 150 V, C-GFB | shimmed twin:")
    rows = {}
    for label, n_theta, n_z, order, kappa in DEFAULT_GRIDS:
        grid = Grid(n_theta, n_z, axial_order=order, lift_off_smoothing=kappa)
        row: list[float | None] = []
        for shimmed in (False, True):
            for volts in (0.0, 50.0, 100.0, 150.0):
                case = replace(default_case(), grid=grid).with_voltages(volts)
                try:
                    res = onset_speed(case.shimmed() if shimmed else case, scan)
                except SolverError:
                    row.append(None)
                    continue
                row.append(None if res.onset_speed is None else res.onset_speed / RPM / 1e3)
        rows[label] = row
        print(
            f"  {label:30s} " + " / ".join(_krpm(v) for v in row[:4]) + " | "
            + " / ".join(_krpm(v) for v in row[4:]),
            flush=True,
        )  # fmt: skip
    ref = rows[DEFAULT_GRIDS[-1][0]]
    print("largest gap to the reference (768 x 24, κ = 0.2), % (mean of the magnitudes):")
    for label, row in rows.items():
        gaps = [100 * (x - r) / r for x, r in zip(row, ref, strict=True) if x and r]
        if gaps:
            big = max(gaps, key=abs)
            print(f"  {label:30s} {big:+.1f} % ({np.mean(np.abs(gaps)):.2f} %)")


def steps() -> None:
    """ms a step, sharp and smoothed, on a smooth and a large orbit (best of 3)."""
    base = default_case()
    runs = (
        ("C-GFB, 0 V, 1 g·mm, 30 krpm", replace(base, rotor=replace(base.rotor, imbalance=1e-6)), 30e3),
        ("shimmed GFB, 150 V, 8.5 g·mm, 50 krpm", base.with_voltages(150.0).shimmed(), 50e3),
    )  # fmt: skip
    print("cost of a step, 0.05 s of each orbit, best of 3 (iterations, factorisations a step):")
    for name, case0, rpm in runs:
        print(f"  {name}:")
        for n_theta, n_z, order in ((96, 4, 4), (96, 12, 2)):
            for kappa in (0.0, CHOSEN):
                grid = Grid(n_theta, n_z, axial_order=order, lift_off_smoothing=kappa)
                case = replace(case0, grid=grid)
                simulate(case, constant_speed(rpm * RPM, 2e-3))  # compile, warm up
                runs_k = [simulate(case, constant_speed(rpm * RPM, 0.05)) for _ in range(3)]
                res = min(runs_k, key=lambda r: r.wall_time / r.steps)
                print(
                    f"    {n_theta} x {n_z:2d} o{order}, κ = {kappa:<3g}: "
                    f"{1e3 * res.wall_time / res.steps:.3f} ms ({res.steps} steps; "
                    f"{res.newton_iterations / res.steps:.2f}, "
                    f"{res.factorizations / res.steps:.3f}); e_X at the end "
                    f"{res.e_x[-1] * 1e6:.4f} um",
                    flush=True,
                )


if __name__ == "__main__":
    options = ("--onsets", "--steps", "--voltages")
    chosen = [a for a in sys.argv[1:] if a in options] or ["--onsets", "--steps"]
    if "--onsets" in chosen:
        onsets()
    if "--steps" in chosen:
        steps()
    if "--voltages" in chosen:
        voltages()
