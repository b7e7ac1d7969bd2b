"""Benchmark of the test oracle of the lift-off orbit (``testing/ivp_orbit.py``, solve_ivp
BDF): its cost must not swing with round-off or threads. Prints its figures.

Run: .venv/bin/python benchmarks/bench_ivp_orbit.py [--runs N]

The segment of ``tests/test_orbit.py::test_fast_stepper_agrees_with_solve_ivp_bdf``
(lift-off): the default case at 100 V on the 32 × 4 grid, 1 g·mm, 0.01 s at 20 krpm from
the static equilibrium. Each run is a fresh process whose compliances are moved by k ulp
(k = 0, 1, −1, 2, 3, ...), once with one thread and once with two (NUMBA_NUM_THREADS,
OMP_NUM_THREADS, OPENBLAS_NUM_THREADS). Printed per run: the reference's CPU time, its
right-hand-side and Jacobian evaluations, and its distance from the fast stepper in % of
the orbit's extent; then the spread of the CPU time about its median (issue 28: ±30 %).
About 10 s a run.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time
from dataclasses import replace

import numpy as np

RPM = math.pi / 30.0


def one_run(ulp: int) -> dict[str, float]:
    """The test's segment with the compliances moved by ``ulp`` units in the last place."""
    from foilbearing.case import Grid, default_case
    from foilbearing.control import constant_speed
    from foilbearing.orbit import OrbitSettings, OrbitSimulation, simulate
    from foilbearing.testing.ivp_orbit import reference_orbit

    case = default_case().with_voltages(100.0)
    case = replace(case, grid=Grid(n_theta=32, n_z=4), disturbance=None)
    case = replace(case, rotor=replace(case.rotor, imbalance=1e-6)).with_subambient("lift-off")
    prof = constant_speed(20e3 * RPM, 0.01)
    settings = OrbitSettings(steps_per_rev=96, sample_rate=20_000)
    fast = simulate(case, prof, settings=settings)
    sim = OrbitSimulation(case, prof, settings=settings)
    scale = 1.0 + ulp * np.finfo(float).eps
    sim.system.c_act[:] *= scale
    sim.system.c_bump[:] *= scale
    start = time.process_time()
    ref = reference_orbit(sim, 0.01, rtol=1e-6, atol=1e-8)
    cpu = time.process_time() - start
    err = max(
        float(np.max(np.abs(fast.e_x - ref["e_x"])) / np.ptp(ref["e_x"])),
        float(np.max(np.abs(fast.e_y - ref["e_y"])) / np.ptp(ref["e_y"])),
    )
    return {"cpu": cpu, "nfev": ref["nfev"], "njev": ref["njev"], "error": err}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5, help="perturbations per thread count")
    parser.add_argument("--child", type=int, default=None, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        print(json.dumps(one_run(args.child)))
        return
    ulps = [0, 1, -1, 2, 3, -2, 4, -3][: args.runs]
    cpus, nfevs = [], []
    print("threads  ulp   CPU (s)   nfev   njev   |Δe|/extent (%)")
    for threads in (1, 2):
        env = dict(os.environ)
        for var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
            env[var] = str(threads)
        for ulp in ulps:
            out = subprocess.run(
                [sys.executable, __file__, "--child", str(ulp)],
                env=env,
                capture_output=True,
                text=True,
                check=True,
            )
            r = json.loads(out.stdout.strip().splitlines()[-1])
            cpus.append(r["cpu"])
            nfevs.append(r["nfev"])
            print(
                f"{threads:7d} {ulp:4d} {r['cpu']:9.2f} {r['nfev']:6d} {r['njev']:6d} "
                f"{100 * r['error']:12.3f}"
            )
    for name, values in (("CPU time (s)", cpus), ("right-hand sides", nfevs)):
        med = float(np.median(values))
        lo, hi = min(values) / med - 1.0, max(values) / med - 1.0
        print(
            f"{name}: median {med:.5g}, spread {100 * lo:+.0f} % / {100 * hi:+.0f} % (target ±30 %)"
        )


if __name__ == "__main__":
    main()
