"""Benchmark of the linear analysis (issue targets: 20 frequencies in 0.5 s; an onset speed
in 10 s). Prints its figures; not a test.

Run: .venv/bin/python benchmarks/bench_dynamics.py
"""

from __future__ import annotations

import math
import time

import numpy as np

from foilbearing.case import default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.stability import onset_speed
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0


def main() -> None:
    case = default_case().with_voltages(150.0)
    st = solve_equilibrium(case, speed=50e3 * RPM)
    freqs = np.linspace(0.1, 2.0, 20) * st.speed
    force_coefficients(st, freqs[:2])  # warm-up
    best = min(_timed(lambda: force_coefficients(st, freqs)) for _ in range(3))
    print(
        f"coefficients at 50 krpm, 20 frequencies: {best:.3f} s "
        f"({1e3 * best / 20:.1f} ms per frequency, grid {case.grid.n_theta}x{case.grid.n_z})"
    )
    for volts in (0.0, 150.0):
        c = default_case().with_voltages(volts)
        t = time.perf_counter()
        res = onset_speed(c)
        wall = time.perf_counter() - t
        onset = res.headline()["onset_speed_rpm"]
        print(
            f"onset speed at {volts:5.0f} V: {onset:.0f} rpm in {wall:.2f} s "
            f"({res.speeds.size} scan speeds + Brent refinement)"
        )


def _timed(f) -> float:
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


if __name__ == "__main__":
    main()
