"""Is the whirl past the onset bounded? The Hopf branch of the default C-GFB, with its cost
(issue 31). Prints its figures.

Run: .venv/bin/python benchmarks/bench_bifurcation.py [GRID ...] [--volts V] [--steps N]
     [--retained] [--reading RESPONSE+DYNAMICS] [--steps-per-rev K]

For each grid (default 32x4), the default case at the voltage given (default 0 V), under
top-foil lift-off (``--retained``: suction retained as well), under the case's reading of
the actuator or ``--reading`` (e.g. ``lobe+held``, the paper's): the linear onset on that
grid, the semi-discrete eigenvalue there, the branch of limit cycles from it (type, each
cycle's speed, amplitude, frequency, stability and largest nontrivial multiplier), the
flow runs it took and its wall time. For a subcritical branch, transients at the speed
of its second cycle, started at 0.6 and 1.5 times that cycle's distance from the
equilibrium, say whether a small kick decays and a large one grows; for a branch of stable
cycles past the onset, transients from 0.5 and 1.5 times a stable cycle settle on it (the
type confirmed by the orbit itself). ``--steps-per-rev K``: the stepper's time step (step
convergence; default 24). About 1-2 minutes a grid at 32 x 4 or 96 x 12.
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import replace

import numpy as np

from foilbearing.bifurcation.bearing import bearing_flow, whirl_branch
from foilbearing.case import Grid, default_case

RPM = math.pi / 30.0


def _extent(parts, y, period: float, speed: float) -> float:  # type: ignore[no-untyped-def]
    res = parts.run(y, period, speed)
    if res.status not in ("stopped", "completed"):
        return math.inf
    return float(max(np.ptp(res.e_x), np.ptp(res.e_y)) / 2.0)


def one(
    grid: tuple[int, int],
    volts: float,
    subambient: str,
    steps: int,
    reading: str | None,
    per_rev: int | None = None,
) -> None:
    case = replace(default_case().with_voltages(volts), grid=Grid(*grid)).with_subambient(
        subambient
    )
    if reading is not None:
        case = case.with_actuator_reading(*reading.split("+"))
    start = 5000 if volts == 0.0 else 15000  # a 150 V C-GFB cannot carry 5 krpm on 32 x 4
    scan = [r * RPM for r in range(start, 120001, 2500)]
    t0 = time.perf_counter()
    wb = whirl_branch(case, scan=scan, steps=steps, steps_per_rev=per_rev)
    wall = time.perf_counter() - t0
    head = wb.headline()
    print(
        f"{grid[0]} x {grid[1]}, {volts:g} V, {subambient}, {reading or 'the case reading'}, "
        f"{per_rev or 24} steps a revolution: "
        "linear onset "
        f"{head['hopf_speed_rpm']:.0f} rpm at {head['linear_whirl_frequency_Hz']:.2f} Hz; "
        f"semi-discrete eigenvalue there {wb.eigenvalue.real:+.3g} {wb.eigenvalue.imag:+.5g}i "
        f"1/s; {head['bifurcation_type']}; {wall:.0f} s ({head['message']})"
    )
    for s, a, f, st, m in zip(
        head["speeds_rpm"],
        head["amplitude_um"],
        head["whirl_frequency_Hz"],
        head["stable"],
        head["largest_multiplier"],
        strict=True,
    ):
        print(
            f"  {s:8.0f} rpm ({s / head['hopf_speed_rpm']:.4f} of the onset): cycle {a:7.3f} "
            f"µm, {f:6.2f} Hz, {'stable' if st else 'unstable'} (largest multiplier {m:.4f})"
        )
    if len(wb.branch.orbits) < 2:
        return
    _flow, parts = bearing_flow(case, wb.whirl_frequency, 1e-4, per_rev)
    if head["bifurcation_type"] == "subcritical":
        # below the onset: a kick inside the unstable cycle decays, one outside it grows
        orbit, factors, periods = wb.branch.orbits[1], (0.6, 1.5), 60
    else:
        # past the onset: kicks inside and outside a stable cycle settle on it
        stable = [o for o in wb.branch.orbits if o.stable and o.parameter > wb.hopf_speed]
        if not stable:
            return
        orbit, factors, periods = stable[len(stable) // 2], (0.5, 1.5), 150
    y_e = parts.equilibrium(orbit.parameter)
    cycle = _extent(parts, orbit.state, orbit.period, orbit.parameter)
    for factor in factors:
        y = y_e + factor * (orbit.state - y_e)
        start = _extent(parts, y, orbit.period, orbit.parameter)
        later = parts.advance(y, periods * orbit.period, orbit.parameter)
        end = (
            math.inf
            if np.isnan(later).any()
            else _extent(parts, later, orbit.period, orbit.parameter)
        )
        print(
            f"  transient at {orbit.parameter / RPM:.0f} rpm from {factor:g} x the "
            f"{'stable' if orbit.stable else 'unstable'} cycle ({cycle * 1e6:.3f} µm): "
            f"{start * 1e6:.3f} µm, after {periods} whirl periods "
            + ("contact" if math.isinf(end) else f"{end * 1e6:.3f} µm")
        )


if __name__ == "__main__":
    args = sys.argv[1:]
    volts = float(args[args.index("--volts") + 1]) if "--volts" in args else 0.0
    steps = int(args[args.index("--steps") + 1]) if "--steps" in args else 4
    reading = args[args.index("--reading") + 1] if "--reading" in args else None
    per_rev = int(args[args.index("--steps-per-rev") + 1]) if "--steps-per-rev" in args else None
    grids = [tuple(int(x) for x in a.split("x")) for a in args if "x" in a and a[0].isdigit()]
    for g in grids or [(32, 4)]:
        one(g, volts, "lift-off", steps, reading, per_rev)  # type: ignore[arg-type]
        if "--retained" in args:
            one(g, volts, "retained", steps, reading, per_rev)  # type: ignore[arg-type]
