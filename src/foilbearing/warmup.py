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

The two parts, the steady film (``--part static``) and the transient film
(``--part orbit``), compile in two processes at once where the machine has two
cores or more: about 30 s instead of 40 on 2 cores. numba replaces a cache file
whole, so two processes compiling a kernel they share leave one valid copy.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from dataclasses import replace

__all__ = ["PARTS", "compile_kernels", "main"]

#: The parts of the warm-up, each compiled by one process.
PARTS = ("static", "orbit")


def compile_kernels(part: str = "all") -> float:
    """Run every analysis once on a coarse grid, compiling (or loading) each kernel.

    Parameters
    ----------
    part
        ``"static"``: the equilibrium, the force coefficients and a whirl mode;
        ``"orbit"``: a few orbit steps under both readings of the actuator; ``"all"``:
        both, one after the other.

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
    if part in ("static", "all"):
        static = solve_equilibrium(case, speed=speed)
        force_coefficients(static, [speed])
        whirl_mode(static, case.rotor.mass)
    if part in ("orbit", "all"):
        for reading in (("local", "compliant"), ("lobe", "held")):
            orbit_case = case.with_actuator_reading(*reading)
            simulate(orbit_case, constant_speed(speed, 1e-3), progress=False)
    return time.perf_counter() - start


def _compile_in_parallel() -> int:
    """Compile the parts in one process each; the first non-zero exit status, else 0.

    The first process alone says that the kernels compile (a cold cache), not each.
    """
    command = [sys.executable, "-m", "foilbearing.warmup", "--part"]
    quiet = {**os.environ, "FOILBEARING_COMPILE_NOTICE": "0"}
    processes = [
        subprocess.Popen([*command, part], env=None if i == 0 else quiet)
        for i, part in enumerate(PARTS)
    ]
    codes = [process.wait() for process in processes]
    return next((code for code in codes if code != 0), 0)


def main(argv: list[str] | None = None) -> int:
    """``python -m foilbearing.warmup [--part P]``: compile the kernels, say how long it took."""
    parser = argparse.ArgumentParser(
        prog="python -m foilbearing.warmup", description="Compile the film kernels once."
    )
    parser.add_argument("--part", choices=[*PARTS, "all"], default=None)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    if args.part is not None:
        compile_kernels(args.part)
        return 0
    if (os.cpu_count() or 1) >= 2:
        code = _compile_in_parallel()
    else:
        compile_kernels()
        code = 0
    if code == 0:
        seconds = time.perf_counter() - start
        print(f"foilbearing: film kernels ready ({seconds:.1f} s)", file=sys.stderr)
    return code


if __name__ == "__main__":
    raise SystemExit(main())
