"""Benchmark of the orbit's grid: which orbit grid the paper's readouts need, and what a step
costs on it. Prints its figures.

Run: .venv/bin/python benchmarks/bench_orbit_grids.py [--grid] [--axial-order]
     [--orbit-grid G ...] [--seeds S,S,... [--run K] [--stop T] G ...]


- ``--grid`` (the default): the grid the orbit needs: cost per step of the full speed-up's orbit (shimmed GFB,
  150 V, 8.5 g·mm, 0.1 s at 50 krpm) and the linear onset at 0 and 150 V, against the axial
  cell count n_z at n_theta = 96, and against n_theta at n_z = 12 (about 1 minute).
- ``--orbit-grid G [G ...]`` (e.g. ``96x6 96x8 96x4o4``; ``oK``: axial order K): the paper's
  speed-ups of ``--readouts`` on each orbit grid (``[grid] orbit_n_theta``, ``orbit_n_z``,
  ``orbit_axial_order``) against the case's 96 x 12: onset,
  whip frequency, divergence or contact, and the 1X amplitude at 5 and 10 krpm and at its
  peak; the issue-30 target is 1 % (two runs at a time, about 2 minutes a grid).
- ``--seeds 1,2,3 [--run K] G [G ...]`` (e.g. ``96x12 96x12k0.2 96x4o4k0.2``): the 0 V,
  1 g·mm speed-up (``--run 0``: 0 V, 8.5 g·mm; 2: the 150 V ramp) under each seed of the
  case's disturbance on each orbit grid: onset, whip and divergence, their spread over the
  seeds and each grid's means against the first grid's (two runs at a time, about 1 minute
  a run on 96 θ cells; ``--stop T``: each run stopped at T s, e.g. 11 s (55.5 krpm) past
  the 1 g·mm divergence, where a finer grid's whirl can circle at about 1.5 C for minutes of
  CPU without touching: 4 minutes a run on 384 θ cells with ``--stop 11``;
  a run).
- ``--axial-order``: route 2 of issue 30 built (``[grid] axial_order = 4``): the cost per step
  of a smooth and a large orbit on 96 x 12 (order 2) and 96 x 4, 6, 8 (order 4), and the
  linear onsets on them against 192 x 24, under lift-off and with suction retained (about
  3 minutes).

The cost model behind these figures and every route tried towards the 60 s target:
docs/development/orbit-performance.md.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from foilbearing.case import default_case
from foilbearing.control import constant_speed, linear_ramp, voltage_ramp
from foilbearing.orbit import simulate

sys.path.insert(0, str(Path(__file__).parent))
from bench_orbit import (
    READOUT_RUNS,
    RPM,
    OrbitGrid,
    _grid_label,
    _orbit_grid,
)


def _grid_readout_run(
    job: tuple,
) -> tuple[tuple, dict]:
    """One paper speed-up on an orbit grid (and, as a third item, the disturbance's seed; as
    a fourth, the time it stops at, s, None for the profile's end)."""
    from foilbearing.case import Grid
    from foilbearing.orbit.analysis import analyse_orbit
    from foilbearing.signals import subsynchronous_amplitude

    k, (n_theta, n_z, order, kappa) = job[0], job[1]
    _label, imbalance, ramp = READOUT_RUNS[k]
    base = default_case()
    if len(job) >= 3 and base.disturbance is not None:
        base = replace(base, disturbance=replace(base.disturbance, seed=job[2]))
    grid = Grid(
        base.grid.n_theta,
        base.grid.n_z,
        orbit_n_theta=n_theta,
        orbit_n_z=n_z,
        orbit_axial_order=order,
        lift_off_smoothing=kappa,
    )
    case = replace(base, rotor=replace(base.rotor, imbalance=imbalance), grid=grid)
    program = None if ramp is None else voltage_ramp(*ramp)
    stop = job[3] if len(job) == 4 else None
    res = simulate(case, linear_ramp(3e3 * RPM, 90e3 * RPM, 500.0), program, stop_time=stop)
    head = analyse_orbit(res).headline(res)
    sub = subsynchronous_amplitude(res.time, res.e_x, res.speed, res.phase)
    one_x = {
        f"1X at {r / 1e3:g} krpm, um": float(
            np.interp(r, sub.speeds_rpm, sub.synchronous_amplitude)
        )
        * 1e6
        for r in (5e3, 10e3)
    }
    one_x["1X peak, um"] = float(np.max(sub.synchronous_amplitude)) * 1e6
    return job, head | one_x | {"wall": res.wall_time}


def orbit_grid_readouts(grids: list[OrbitGrid]) -> None:
    """The paper's speed-ups on each orbit grid against the case's own (96 x 12)."""
    from concurrent.futures import ProcessPoolExecutor

    base = default_case().grid
    ref = (base.n_theta, base.n_z, base.axial_order, base.lift_off_smoothing)
    print(
        f"orbit grid: the paper's speed-ups (3-90 krpm, 500 rad/s², default settings) on each "
        f"orbit grid against {ref[0]} x {ref[1]}; two runs at a time"
    )
    grids = [ref] + [g for g in grids if g != ref]
    jobs = [(k, g) for k in range(len(READOUT_RUNS)) for g in grids]
    out: dict[tuple[int, OrbitGrid], dict] = {}
    keys = (
        ("onset_speed_rpm", "onset"),
        ("whip_frequency_Hz", "whip"),
        ("divergence_speed_rpm", "divergence/contact"),
        ("1X at 5 krpm, um", "1X at 5 krpm"),
        ("1X at 10 krpm, um", "1X at 10 krpm"),
        ("1X peak, um", "1X peak"),
    )
    with ProcessPoolExecutor(max_workers=2) as pool:
        for job, head in pool.map(_grid_readout_run, jobs):
            out[job[0], job[1]] = head
    for k, (label, _imb, _ramp) in enumerate(READOUT_RUNS):
        print(f"  {label}:")
        for g in grids:
            head, first = out[k, g], out[k, ref]
            parts = []
            for key, name in keys:
                a, b = head.get(key), first.get(key)
                if a is None:
                    parts.append(f"{name} none")
                elif g == ref or b is None:
                    parts.append(f"{name} {a:.4g}")
                else:
                    parts.append(f"{name} {a:.4g} ({100 * (a - b) / b:+.2f} %)")
            print(f"    {_grid_label(g)} ({head['wall']:.0f} s): " + ", ".join(parts))


def seed_readouts(
    seeds: list[int], grids: list[OrbitGrid], k: int = 1, stop: float | None = None
) -> None:
    """One paper speed-up (default: 0 V, 1 g·mm) under several seeds of the case's
    disturbance on each orbit grid: how far its readings move with the random force alone,
    against how far they move with the grid."""
    from concurrent.futures import ProcessPoolExecutor

    print(
        f"{READOUT_RUNS[k][0]} speed-up (3-90 krpm, 500 rad/s²) under the disturbance seeds "
        f"{', '.join(map(str, seeds))}, on each orbit grid; two runs at a time"
    )
    jobs = [(k, g, seed, stop) for g in grids for seed in seeds]
    keys = (
        ("onset_speed_rpm", "onset"),
        ("whip_frequency_Hz", "whip"),
        ("divergence_speed_rpm", "divergence/contact"),
    )
    with ProcessPoolExecutor(max_workers=2) as pool:
        out = {job[1:3]: head for job, head in pool.map(_grid_readout_run, jobs)}
    means: dict[OrbitGrid, dict[str, float]] = {}
    for g in grids:
        print(f"  {_grid_label(g)}:")
        means[g] = {}
        for key, name in keys:
            values = [out[g, seed].get(key) for seed in seeds]
            shown = ", ".join("none" if v is None else f"{v:.5g}" for v in values)
            got = np.array([v for v in values if v is not None], float)
            if got.size:
                means[g][key] = float(got.mean())
                spread = 100 * (got.max() - got.min()) / got.mean()
                shown += f" (mean {got.mean():.5g}, spread {spread:.1f} %)"
            print(f"    {name}: {shown}")
    first = grids[0]
    for g in grids[1:]:
        parts = [
            f"{name} {100 * (means[g][key] - means[first][key]) / means[first][key]:+.2f} %"
            for key, name in keys
            if key in means[g] and key in means[first]
        ]
        print(f"  means of {_grid_label(g)} against {_grid_label(first)}: " + ", ".join(parts))


def grid_study() -> None:
    """Cost per orbit step and linear onsets against the grid (route 2 of issue 13)."""
    from foilbearing.case import Grid
    from foilbearing.stability import onset_speed

    scan = [rpm * RPM for rpm in range(20_000, 100_001, 10_000)]
    runner = default_case().with_voltages(150.0).shimmed()
    print(
        "grid: orbit cost (shimmed GFB, 150 V, 8.5 g·mm, 0.1 s at 50 krpm, default settings) "
        "and linear onsets of the default case (20-100 krpm scan, Brent)"
    )
    onsets: dict[tuple[int, int], tuple[float, float]] = {}
    for grid in ((96, 4), (96, 6), (96, 8), (96, 12), (96, 24), (48, 12), (192, 12), (192, 24)):
        g = Grid(*grid)
        case = replace(runner, grid=g)
        simulate(case, constant_speed(50e3 * RPM, 5e-4), progress=False)  # compile, warm up
        res = simulate(case, constant_speed(50e3 * RPM, 0.1), progress=False)
        onset = tuple(
            onset_speed(replace(default_case().with_voltages(v), grid=g), scan).onset_speed / RPM
            for v in (0.0, 150.0)
        )
        onsets[grid] = onset
        print(
            f"  {grid[0]:3d} x {grid[1]:2d}: {1e3 * res.wall_time / res.steps:.3f} ms per step "
            f"({res.newton_iterations / res.steps:.2f} iterations, "
            f"{res.factorizations / res.steps:.3f} factorisations); onset 0 V "
            f"{onset[0] / 1e3:.2f} krpm, 150 V {onset[1] / 1e3:.2f} krpm",
            flush=True,
        )
    fine = onsets[(192, 24)]
    for grid, (a, b) in onsets.items():
        print(
            f"  {grid[0]:3d} x {grid[1]:2d}: onset from 192 x 24: 0 V "
            f"{100 * (a - fine[0]) / fine[0]:+.2f} %, 150 V {100 * (b - fine[1]) / fine[1]:+.2f} %"
        )


def axial_order_study() -> None:
    """Route 2 of issue 30 built: the orbit's cost and the linear onsets on fourth-order grids."""
    from foilbearing.case import Case, Grid
    from foilbearing.stability import onset_speed

    grids = [(96, 12, 2), (96, 4, 4), (96, 6, 4), (96, 8, 4)]
    print("cost per step, 0.05 s at constant speed, best of 3 (ms; iterations, factorisations):")
    orbits = [
        ("C-GFB, 0 V, 1 g·mm, 30 krpm", default_case(), 1e-6, 30e3),
        (
            "shimmed GFB, 150 V, 8.5 g·mm, 50 krpm",
            default_case().with_voltages(150.0).shimmed(),
            8.5e-6,
            50e3,
        ),
    ]
    for label, base, imbalance, rpm in orbits:
        print(f"  {label}:")
        for n_theta, n_z, order in grids:
            case = replace(
                base,
                rotor=replace(base.rotor, imbalance=imbalance),
                grid=Grid(n_theta, n_z, axial_order=order),
            )
            simulate(case, constant_speed(rpm * RPM, 5e-4))  # compile, warm up
            runs = [simulate(case, constant_speed(rpm * RPM, 0.05)) for _ in range(3)]
            res = min(runs, key=lambda r: r.wall_time)
            print(
                f"    {n_theta} x {n_z:2d}, order {order}: "
                f"{1e3 * res.wall_time / res.steps:.3f} ms per step "
                f"({res.newton_iterations / res.steps:.2f}, "
                f"{res.factorizations / res.steps:.3f}), e_X at the end {res.e_x[-1] * 1e6:.4f} um",
                flush=True,
            )
    print("linear onset (krpm) against 192 x 24, order 2:")
    for subambient in ("lift-off", "retained"):
        for volts in (0.0, 150.0):
            base = default_case().with_voltages(volts).with_subambient(subambient)

            def onset(n_theta: int, n_z: int, order: int, base: Case = base) -> float:
                case = replace(base, grid=Grid(n_theta, n_z, axial_order=order))
                return onset_speed(case).onset_speed / RPM / 1e3

            ref = onset(192, 24, 2)
            parts = []
            for n_theta, n_z, order in [*grids, (96, 24, 2), (192, 6, 4)]:
                x = onset(n_theta, n_z, order)
                parts.append(f"{n_theta}x{n_z} o{order} {x:.2f} ({100 * (x - ref) / ref:+.1f} %)")
            print(
                f"  {subambient}, {volts:.0f} V: 192x24 {ref:.2f}; " + ", ".join(parts), flush=True
            )


if __name__ == "__main__":
    if "--seeds" in sys.argv:
        run_k = 1
        if "--run" in sys.argv:
            run_k = int(sys.argv[sys.argv.index("--run") + 1])
            del sys.argv[sys.argv.index("--run") : sys.argv.index("--run") + 2]
        stop = None
        if "--stop" in sys.argv:
            stop = float(sys.argv[sys.argv.index("--stop") + 1])
            del sys.argv[sys.argv.index("--stop") : sys.argv.index("--stop") + 2]
        at = sys.argv.index("--seeds")
        seeds = [int(x) for x in sys.argv[at + 1].split(",")]
        seed_readouts(seeds, [_orbit_grid(g) for g in sys.argv[at + 2 :]], run_k, stop)
    elif "--orbit-grid" in sys.argv:
        names = sys.argv[sys.argv.index("--orbit-grid") + 1 :]
        orbit_grid_readouts([_orbit_grid(g) for g in names])
    elif "--axial-order" in sys.argv:
        axial_order_study()
    else:
        grid_study()
