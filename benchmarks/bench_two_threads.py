"""Does the second core pay inside one orbit? The two chains of the block-cyclic LU on two
threads, in isolation and inside the orbit (issue 30, route 5). Prints its figures.

Run: .venv/bin/python benchmarks/bench_two_threads.py [--orbit]

- (always) the factorisation of the transient Newton matrix (default case, 150 V, 30 krpm,
  ``bench_block_solver.newton_matrix``) on 96 x 6, 96 x 8 and 96 x 12: the kernel as it is
  (the two chains one after the other), one chain alone, the two chains in a ``prange`` of
  numba's threading layer, and the two chains on two Python threads (nogil kernels), best of
  7 x 50 calls each.
- ``--orbit``: ms per step of the full speed-up's orbit (shimmed GFB, 150 V, 8.5 g·mm, 0.05 s
  at 50 krpm) with the kernel as it is and with the ``prange`` factorisation patched in,
  alternated, three runs each (about 2 minutes).

The ``prange`` version is compiled here (not cached); it is not used by the package:
docs/development/orbit-performance.md, "The second core", says why.
"""

from __future__ import annotations

import math
import sys
import threading
from dataclasses import replace
from pathlib import Path

import numpy as np
from numba import njit, prange, threading_layer

sys.path.insert(0, str(Path(__file__).parent))
from bench_block_solver import best_ms, newton_matrix

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds._kernels import blockcyclic as bc

RPM = math.pi / 30.0


@njit(parallel=True)
def two_thread_factor(data, n_theta, n_z, fac):  # type: ignore[no-untyped-def]
    """:func:`block_cyclic_factor` with its two chains in a ``prange``."""
    bmax = bc._check_data(data)
    if bmax != bmax:
        return bc.BC_NOT_FINITE, -1, 0.0, np.inf
    d4 = data.reshape((n_theta, n_z, 3, n_z))
    sc = np.empty((2, 2 * n_z, 2 * n_z), dtype=fac.dtype)
    stats = np.empty((2, 3))
    status = np.empty(2, dtype=np.int64)
    for k in prange(2):
        first, last, left, right = bc._chain(k, n_theta)
        status[k] = bc._chain_factor(d4, fac, first, last, left, right, sc[k], stats[k])
    return bc._separator_factor(d4, fac, sc, stats, status, bmax)


def _factor_times(n_z: int) -> str:
    """The factorisation four ways on 96 x n_z, as one printed line."""
    data, _indices, _indptr = newton_matrix(96, n_z)
    fac = bc.block_cyclic_alloc(96, n_z)
    d4 = data.reshape((96, n_z, 3, n_z))
    sc, stats = np.empty((2, 2 * n_z, 2 * n_z)), np.empty((2, 3))
    chain_a, chain_b = bc._chain(0, 96), bc._chain(1, 96)
    serial = best_ms(lambda: bc.block_cyclic_factor(data, 96, n_z, fac))
    one = best_ms(lambda: bc._chain_factor(d4, fac, *chain_a, sc[0], stats[0]))
    par = best_ms(lambda: two_thread_factor(data, 96, n_z, fac))
    go, done, stop = threading.Event(), threading.Event(), [False]

    def worker() -> None:
        while True:
            go.wait()
            go.clear()
            if stop[0]:
                return
            bc._chain_factor(d4, fac, *chain_b, sc[1], stats[1])
            done.set()

    threading.Thread(target=worker, daemon=True).start()

    def both() -> None:
        go.set()
        bc._chain_factor(d4, fac, *chain_a, sc[0], stats[0])
        done.wait()
        done.clear()

    python = best_ms(both)
    stop[0] = True
    go.set()
    return (
        f"  96 x {n_z:2d}: as it is {serial:.3f}, one chain {one:.3f}, prange(2) {par:.3f} "
        f"({threading_layer()} layer), two Python threads {python:.3f} (chains only)"
    )


def isolation() -> None:
    print("block-cyclic LU of the transient Newton matrix, best of 7 x 50 calls, ms")
    for n_z in (6, 8, 12):
        print(_factor_times(n_z), flush=True)


def in_the_orbit() -> None:
    from foilbearing.case import Grid, default_case
    from foilbearing.control import constant_speed
    from foilbearing.orbit import simulate

    serial = kern.block_cyclic_factor
    case = default_case().with_voltages(150.0).shimmed()
    print("ms per step of 0.05 s of the full speed-up's orbit at 50 krpm, alternated")
    for n_z in (12, 6):
        c = replace(case, grid=Grid(96, n_z))
        simulate(c, constant_speed(50e3 * RPM, 5e-4))
        kern.block_cyclic_factor = two_thread_factor
        simulate(c, constant_speed(50e3 * RPM, 5e-4))
        runs: dict[str, list[float]] = {"as it is": [], "prange(2)": []}
        for _ in range(3):
            for name, fn in (("as it is", serial), ("prange(2)", two_thread_factor)):
                kern.block_cyclic_factor = fn
                res = simulate(c, constant_speed(50e3 * RPM, 0.05))
                runs[name].append(1e3 * res.wall_time / res.steps)
        kern.block_cyclic_factor = serial
        print(
            f"  96 x {n_z:2d}: "
            + "; ".join(f"{k} {', '.join(f'{v:.3f}' for v in vals)}" for k, vals in runs.items()),
            flush=True,
        )


if __name__ == "__main__":
    isolation()
    if "--orbit" in sys.argv:
        in_the_orbit()
