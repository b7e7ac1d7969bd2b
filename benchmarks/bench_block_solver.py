"""Timing of the block cyclic LU against SuperLU on the transient Newton matrix.

Run: ``python benchmarks/bench_block_solver.py`` (prints its figures; not a test).

Matrix: B of :meth:`TransientSystem.factorize` (Reynolds block with the foil
coupling, on the coupled pattern) for the default case at 150 V, 30 krpm,
initial state, c0 = 5000 1/s, on the default 96×12 grid and on 192×24.
SuperLU is called as in ``factorize`` (``permc_spec="MMD_AT_PLUS_A"``,
``SymmetricMode``, B^T in CSC and ``trans="T"``). Targets at 96×12: factor
< 0.3 ms, solve < 0.03 ms (one right-hand side).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from foilbearing.case import Grid, default_case
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSimulation
from foilbearing.reynolds.blocksolve import BlockCyclicLU


def best_ms(fn: Callable[[], object], repeat: int = 7, number: int = 50) -> float:
    """Best-of-``repeat`` mean time of ``number`` calls, in ms (robust to load)."""
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t0) / number)
    return 1e3 * min(times)


def newton_matrix(n_theta: int, n_z: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(data, indices, indptr) of B on the coupled pattern for an n_theta × n_z grid."""
    case = replace(default_case().with_voltages(150.0), grid=Grid(n_theta, n_z))
    sim = OrbitSimulation(case, constant_speed(30000 * math.pi / 30, 0.1))
    y = sim.initial_state()
    inp = sim.inputs(0.0, sim.volts(0.0))
    factor = sim.system.factorize(y, inp, 5000.0, -5000.0 * sim.system.storage(y, inp))
    assert factor.coupled_data is not None
    return factor.coupled_data.copy(), sim.system.c_indices, sim.system.c_indptr


def main() -> None:
    print(f"{'grid':>8} {'':>6} {'factor ms':>10} {'solve ms':>9} {'solve(n,2) ms':>14}")
    for n_theta, n_z in [(96, 12), (192, 24)]:
        data, indices, indptr = newton_matrix(n_theta, n_z)
        n = n_theta * n_z
        b1 = np.random.default_rng(0).normal(size=n)
        b2 = np.random.default_rng(1).normal(size=(n, 2))
        bt = sp.csc_matrix((data, indices, indptr), shape=(n, n))  # B^T, as in factorize

        def superlu(bt: sp.csc_matrix = bt) -> object:
            return splu(bt, permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})

        ref = superlu()
        ours = BlockCyclicLU(data, n_theta, n_z)
        err = np.abs(ours.solve(b2) - ref.solve(b2, trans="T")).max()
        err /= np.abs(ref.solve(b2, trans="T")).max()
        rows = [
            (
                "block",
                best_ms(lambda: BlockCyclicLU(data, n_theta, n_z), number=20),  # noqa: B023
                best_ms(lambda: ours.solve(b1), number=500),  # noqa: B023
                best_ms(lambda: ours.solve(b2), number=500),  # noqa: B023
            ),
            (
                "splu",
                best_ms(superlu, number=5),
                best_ms(lambda: ref.solve(b1, trans="T"), number=500),  # noqa: B023
                best_ms(lambda: ref.solve(b2, trans="T"), number=500),  # noqa: B023
            ),
        ]
        for name, t_f, t_1, t_2 in rows:
            grid = f"{n_theta}x{n_z}"
            print(f"{grid:>8} {name:>6} {t_f:10.3f} {t_1:9.4f} {t_2:14.4f}")
        print(
            f"{'':>8} rel. difference to splu {err:.1e}, rcond {ours.rcond:.2g}, "
            f"growth {ours.growth:.3g}"
        )


if __name__ == "__main__":
    main()
