"""Benchmark of the cost of calling the compiled transient kernels from Python. Prints its
figures.

Run: .venv/bin/python benchmarks/bench_kernel_calls.py

On an 8 × 2 grid the work inside a kernel is tiny, so the time of a call is mostly numba's
dispatch: typing the arguments (the kernels take grouped plain tuples,
``reynolds/_kernels/groups.py``) and unpacking the result. It prints the median and the
minimum over 7 repeats of 20,000 calls of the compiled Newton step, the Newton solve with one
factor and the BDF set-up. docs/development/orbit-performance.md ("Grouped kernel arguments") compares
these with the kernels' earlier separate arguments.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from foilbearing.case import Grid, default_case
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSimulation
from foilbearing.reynolds.transient import BdfHistory, bdf_setup

RPM = math.pi / 30.0
CALLS = 20_000


def _time(call: Callable[[], object]) -> tuple[float, float]:
    per = []
    for _ in range(7):
        t = time.perf_counter()
        for _ in range(CALLS):
            call()
        per.append((time.perf_counter() - t) / CALLS * 1e6)
    return statistics.median(per), min(per)


def main() -> None:
    case = replace(default_case().with_voltages(100.0), grid=Grid(n_theta=8, n_z=2))
    sim = OrbitSimulation(case, constant_speed(20e3 * RPM, 0.01))
    sys_ = sim.system
    y0 = sim.initial_state()
    inp = sim.inputs(1e-4, sim.volts(1e-4))
    c0 = 3000.0
    hist = -c0 * sys_.storage(y0, inp)
    factor = sys_.factorize(y0, inp, c0, hist)
    weights = np.ones(sys_.size)
    g, dy, q = (np.empty(sys_.size) for _ in range(3))
    y = y0.copy()

    def newton_step() -> object:
        y[:] = y0
        return factor.newton_step(y, inp, c0, hist, weights, g, dy)

    def newton_solve() -> object:
        y[:] = y0
        return factor.newton_solve(
            y, inp, c0, hist, weights, (g, dy, q), (0.3, 1e-3, 4), True, math.inf
        )

    times = np.array([0.0, -1e-4, -2e-4, -3e-4])
    ys = np.tile(y0, (4, 1))
    qs = np.tile(sys_.storage(y0, inp), (4, 1))
    atol = np.full(sys_.size, 1e-5)
    guess, hist_out, w_out = (np.empty(sys_.size) for _ in range(3))

    def setup() -> object:
        past = tuple(BdfHistory(times, ys, qs, 3))
        return bdf_setup(1e-4, past, 3, atol, 1e-4, guess, hist_out, w_out)

    print(
        f"compiled kernel calls on a {sys_.grid.n_theta} x {sys_.grid.n_z} grid "
        f"({sys_.size} unknowns), {CALLS} calls, median (min) of 7 repeats:"
    )
    for name, call in (("Newton step", newton_step), ("Newton solve", newton_solve),
                       ("BDF set-up", setup)):  # fmt: skip
        call()
        med, low = _time(call)
        print(f"  {name:<13} {med:6.2f} µs  ({low:.2f})")


if __name__ == "__main__":
    main()
