"""Compile the film kernels once, ahead of the first run: ``python -m foilbearing.warmup``.

numba compiles the kernels of :mod:`foilbearing.reynolds._kernels` on first use
(about 40 s) and caches them on disk; every later process loads them. The set-up
(``scripts/setup_venv.sh``, used by ``make run`` and ``make test``) calls this at
its end, so that the first ``foilbearing static`` does not compile. It runs each
analysis once on a coarse grid of the built-in case: a static equilibrium (the
steady film and the Newton kernels), the force coefficients and a whirl mode (the
perturbed film), and a few orbit steps under both readings of the actuator (the
transient film, its BDF stepper and block-cyclic solver, and the lobe's
correction). Each path is what the analyses call on any grid: the kernels are
compiled per type, not per size. On a warm cache it takes a few seconds.
"""

from __future__ import annotations

import sys
import time
from dataclasses import replace

__all__ = ["compile_kernels", "main"]


def compile_kernels() -> float:
    """Run every analysis once on a coarse grid, compiling (or loading) each kernel.

    Returns
    -------
    float
        The wall time it took, s.
    """
    from foilbearing.analysis.coefficients import force_coefficients
    from foilbearing.analysis.equilibrium import solve_equilibrium
    from foilbearing.analysis.stability import whirl_mode
    from foilbearing.case import Grid, default_case
    from foilbearing.constants import RPM
    from foilbearing.control import constant_speed
    from foilbearing.orbit import simulate

    start = time.perf_counter()
    base = default_case()
    # The built-in case's laws and orders (static at order 2, orbit at order 4, the smoothed
    # lifted-off edge) on 32 θ cells: enough for 2 cells across a stinger.
    grid = Grid(
        n_theta=32,
        n_z=3,
        orbit_n_z=3,
        axial_order=base.grid.axial_order,
        orbit_axial_order=base.grid.orbit_order,
        lift_off_smoothing=base.grid.lift_off_smoothing,
    )
    case = replace(base, grid=grid)
    speed = 30_000 * RPM
    static = solve_equilibrium(case, speed=speed)
    force_coefficients(static, [speed])
    whirl_mode(static, case.rotor.mass)
    for reading in (("local", "compliant"), ("lobe", "held")):
        orbit_case = case.with_actuator_reading(*reading)
        simulate(orbit_case, constant_speed(speed, 1e-3), progress=False)
    return time.perf_counter() - start


def main() -> int:
    """``python -m foilbearing.warmup``: compile the kernels and say how long it took."""
    seconds = compile_kernels()
    print(f"foilbearing: film kernels ready ({seconds:.1f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
