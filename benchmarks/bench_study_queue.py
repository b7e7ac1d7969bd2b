"""How well the study's speed-ups fill the two cores: the timeline of the queue's runs in
an output folder of ``foilbearing study``, and the stage's wall time against its bound.

Each speed-up's NetCDF holds its run's wall time (``wall_time_s``) and is written as the
run ends, so its modification time less its wall time is when it started. Prints every
run's start, end and length (s, from the first run's start), the runs' total, and the
bound no order of the runs can beat on ``--cores`` cores: the total over the cores, or
the longest chain of runs one decides (a 0 V run, then its controlled or refined run),
whichever is longer. The study's own work beside the queue (the voltage schedule, about
40 s in the study's process, and its grid check, 30 s in a process of its own) is not in
the NetCDFs; ``--beside S`` adds it to the total. Prints its figures; not a test.

Run: .venv/bin/python benchmarks/bench_study_queue.py OUT [--cores 2] [--beside 70]
     (OUT: the folder of a finished `foilbearing study --out OUT`)
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path


def main() -> None:
    import xarray as xr

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--cores", type=int, default=2)
    parser.add_argument("--beside", type=float, default=0.0, help="CPU s of the study's own work")
    args = parser.parse_args()
    runs = []
    for path in sorted(args.out.glob("orbit_*.nc")):
        with xr.open_dataset(path) as ds:
            wall = float(ds.attrs.get("wall_time_s", 0.0))
        end = os.path.getmtime(path)
        runs.append((end - wall, end, wall, path.stem.removeprefix("orbit_")))
    if not runs:
        raise SystemExit(f"{args.out}: no orbit_*.nc; run `foilbearing study --out {args.out}`")
    t0 = min(r[0] for r in runs)
    print(f"{'start':>7s} {'end':>7s} {'run':>6s}  speed-up (s, from the first start)")
    for start, end, wall, label in sorted(runs):
        print(f"{start - t0:7.1f} {end - t0:7.1f} {wall:6.1f}  {label}")
    total = sum(r[2] for r in runs)
    stage = max(r[1] for r in runs) - t0
    # the longest chain: a run and the refined or controlled run that waits for it
    by = {r[3]: r[2] for r in runs}
    chain = max(
        by.get(label.split("_theta")[0], 0.0) + wall if "_theta" in label else wall
        for label, wall in by.items()
    )
    bound = max((total + args.beside) / args.cores, chain)
    print(
        f"\n{len(runs)} runs, {total:.0f} s of run time; stage {stage:.0f} s wall on "
        f"{args.cores} cores; bound {bound:.0f} s (the run time"
        + (f" and {args.beside:.0f} s beside it" if args.beside else "")
        + f" over the cores; the longest chain {chain:.0f} s): "
        f"{100 * (stage / bound - 1):.0f} % above it"
    )


if __name__ == "__main__":
    main()
