"""Benchmark of the nonlinear rotor (issue 32): its cost per step against the single
bearing's. Prints its figures.

Run: .venv/bin/python benchmarks/bench_rotor_orbit.py [--grid 96x12] [--duration 0.1]

examples/rotor_rigid_symmetric.toml at 30 krpm on the default bearing grid, an unbalance of
8.5 g·mm at its disk (the paper's largest), 0.1 s from the static state; beside it, one
bearing carrying half the rotor with half the unbalance (the rigid limit of the same run),
both on the orbit's stepper. Each run is done once untimed first (compilation). Target: the
rotor's step costs at most 2.5 times the single bearing's. The rotor's synchronous orbit
(lock-in over the last 40 ms) is printed beside the single bearing's: they are one motion.
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from foilbearing.case.model import Grid
from foilbearing.constants import RPM
from foilbearing.control import constant_speed
from foilbearing.orbit import simulate
from foilbearing.rotor import load_rotor, ross_rotor
from foilbearing.rotor.nonlinear import RotorOrbitSystem, Unbalance
from foilbearing.rotor.stepper import run_rotor

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rotor_rigid_symmetric.toml"
UNBALANCE = 8.5e-6  # kg·m


def _lock_in(t: np.ndarray, x: np.ndarray, omega: float, window: float) -> float:
    sel = t > t[-1] - window
    t, x = t[sel], x[sel] - x[sel].mean()
    return float(abs(2 * np.trapezoid(x * np.exp(-1j * omega * t), t) / (t[-1] - t[0])))


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--grid", default="96x12")
    parser.add_argument("--duration", type=float, default=0.1)
    args = parser.parse_args()
    n_theta, n_z = (int(v) for v in args.grid.split("x"))
    rotor = load_rotor(EXAMPLE)
    grid = Grid(n_theta, n_z)
    rotor = replace(
        rotor, bearings=tuple(replace(b, case=replace(b.case, grid=grid)) for b in rotor.bearings)
    )
    speed, duration = 30e3 * RPM, args.duration
    model = ross_rotor(rotor, [speed - 1e3 * RPM, speed], frequencies=[100.0, 1000.0])
    unbalance = [Unbalance(rotor.disks[0].node, UNBALANCE)]
    profile = constant_speed(speed, duration)
    system = RotorOrbitSystem(rotor, model, profile, n_modes=2, unbalances=unbalance)
    case = rotor.loaded_cases()[0]
    case = replace(case, rotor=replace(case.rotor, imbalance=UNBALANCE / 2))
    run_rotor(system, 0.002)
    simulate(case, constant_speed(speed, 0.002))

    clock = time.perf_counter()
    fast = run_rotor(system, duration)
    rotor_wall = time.perf_counter() - clock
    clock = time.perf_counter()
    single = simulate(case, profile)
    single_wall = time.perf_counter() - clock
    per_rotor = rotor_wall / fast.steps * 1e3
    per_single = single_wall / single.steps * 1e3
    print(f"grid {args.grid}, {duration} s at 30 krpm, {UNBALANCE * 1e6:.1f} g·mm at the disk")
    print(
        f"  rotor (two bearings, {system.m} rotor coordinates): {rotor_wall:.2f} s, "
        f"{fast.steps} steps, {fast.factorizations} factorisations, "
        f"{fast.newton_iterations / fast.steps:.2f} iterations a step: {per_rotor:.3f} ms a step"
    )
    print(
        f"  one bearing: {single_wall:.2f} s, {single.steps} steps, "
        f"{single.factorizations} factorisations, "
        f"{single.newton_iterations / single.steps:.2f} iterations a step: "
        f"{per_single:.3f} ms a step"
    )
    print(f"  rotor / one bearing per step: {per_rotor / per_single:.2f} (target 2.5)")
    window = min(0.04, duration / 2)
    amp_rotor = _lock_in(fast.time, fast.journals[0, 0], speed, window)
    amp_single = _lock_in(single.time, single.e_x, speed, window)
    print(
        f"  1X amplitude along X at bearing A: {amp_rotor * 1e6:.3f} µm (rotor), "
        f"{amp_single * 1e6:.3f} µm (one bearing), {100 * (amp_rotor / amp_single - 1):+.2f} %"
    )
    assert math.isfinite(per_rotor)


if __name__ == "__main__":
    main()
