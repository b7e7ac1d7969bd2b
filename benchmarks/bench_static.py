"""Benchmark of the static analysis (issue targets: 30 ms per equilibrium, 3 s and 300 MB for
the sweep of Figs. 10-12). Prints its figures; not a test.

Run: .venv/bin/python benchmarks/bench_static.py
"""

from __future__ import annotations

import math
import resource
import time

from foilbearing.case import default_case
from foilbearing.film import film_model
from foilbearing.static import solve_equilibrium
from foilbearing.study.static import PAPER_SPEEDS_RPM, PAPER_VOLTAGES, static_sweep

RPM = math.pi / 30.0


def main() -> None:
    case = default_case().with_voltages(150.0)
    model = film_model(case)
    solve_equilibrium(case, speed=50e3 * RPM, model=model)  # warm-up (numba cache, imports)
    for volts, rpm in ((0.0, 50e3), (150.0, 50e3), (150.0, 90e3), (0.0, 10e3)):
        c = default_case().with_voltages(volts)
        m = film_model(c)
        times, iters = [], 0
        for _ in range(5):
            t = time.perf_counter()
            res = solve_equilibrium(c, speed=rpm * RPM, model=m)
            times.append(time.perf_counter() - t)
            iters = res.iterations
        print(
            f"equilibrium {volts:5.0f} V {rpm / 1e3:4.0f} krpm from the centre: "
            f"{1e3 * min(times):6.1f} ms (best of 5), {iters} Newton iterations, "
            f"grid {c.grid.n_theta}x{c.grid.n_z}"
        )
    t = time.perf_counter()
    ds = static_sweep(default_case(), [s * RPM for s in PAPER_SPEEDS_RPM], PAPER_VOLTAGES)
    wall = time.perf_counter() - t
    n = ds.converged.size
    print(
        f"static sweep of Figs. 10-12: {n} equilibria ({int(ds.converged.sum())} converged) "
        f"in {wall:.2f} s, {1e3 * wall / n:.1f} ms per point (with continuation in speed)"
    )
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak memory (max RSS of this process): {peak:.0f} MB")


if __name__ == "__main__":
    main()
