"""Benchmark of the Dask sweep: 16 static points on a LocalCluster of 2 workers vs 1 worker.

Target: a speed-up of at least 1.7x with 2 workers. Each point is a static
equilibrium of the C-GFB on a 256 x 24 grid (about 0.4 s on one core), so the
scheduling overhead (a few ms per task) does not dominate. (A 512 x 32 grid
scales worse, 1.5-1.7x: its sparse LU is memory-bound and the two workers
share the memory bandwidth of the 2 cores.) The clusters are
started and warmed up (imports, numba cache) before the clock starts; the
timed part is ``run_sweep``: submit, compute, write each point, assemble.
Prints its figures; not a test.

Run: .venv/bin/python benchmarks/bench_sweep.py
"""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

SWEEP = """
title = "benchmark: 16 static points on a 256 x 24 grid"
[set]
grid.n_theta = 256
grid.n_z = 24
[parameters]
voltage = ["0 V", "50 V", "100 V", "150 V"]
speed = ["30000 rpm", "50000 rpm", "70000 rpm", "90000 rpm"]
"""


def _warm() -> None:
    from foilbearing.case import default_case
    from foilbearing.static import solve_equilibrium

    solve_equilibrium(default_case())


def _timed_run(spec: object, n_workers: int, folder: Path) -> float:
    from distributed import Client, LocalCluster

    from foilbearing.sweep.runner import run_sweep

    with (
        LocalCluster(
            n_workers=n_workers, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        Client(cluster) as client,
    ):
        client.run(_warm)
        t0 = time.perf_counter()
        summary = run_sweep(spec, folder / f"w{n_workers}", client=client)  # type: ignore[arg-type]
        wall = time.perf_counter() - t0
    assert summary["n_ok"] == 16, summary
    return wall


def main() -> None:
    from foilbearing.sweep.runner import load_sweep

    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "bench.toml").write_text(SWEEP, encoding="utf-8")
        spec = load_sweep(folder / "bench.toml")
        _warm()
        t0 = time.perf_counter()
        for i in (0, 15):
            from foilbearing.static import solve_equilibrium

            solve_equilibrium(spec.point_case(i))
        per_point = (time.perf_counter() - t0) / 2
        one = _timed_run(spec, 1, folder)
        two = _timed_run(spec, 2, folder)
    print(f"16-point static sweep, grid 256 x 24: about {per_point:.2f} s per point in-process")
    print(f"  1 worker : {one:6.2f} s  ({one / 16:.3f} s per point)")
    print(f"  2 workers: {two:6.2f} s  ({two / 16:.3f} s per point)")
    print(f"  speed-up : {one / two:.2f}x (target >= 1.7x)")
    assert math.isfinite(one / two)


if __name__ == "__main__":
    main()
