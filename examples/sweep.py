"""A parameter sweep on Dask: the static C-GFB over voltage × speed, in parallel.

Runs ``sweep_voltage_speed.toml`` (4 voltages × 3 speeds, static analysis) on a
local Dask cluster of two single-thread workers. Each point is written as it
finishes (``RESULT.d/points/``), so a stopped sweep resumes; the result is one
xarray Dataset (NetCDF) with dimensions voltage × speed. The same file runs from
the command line: ``foilbearing sweep examples/sweep_voltage_speed.toml --out DIR``.

    python examples/sweep.py [OUT_DIR]          (about 15 s, most of it starting Dask)
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path
from typing import Any

import xarray as xr

import foilbearing as fb
from foilbearing.sweep.spec import load_sweep

HERE = Path(__file__).resolve().parent


def main(out_dir: str | Path | None = None) -> Any:
    spec = load_sweep(HERE / "sweep_voltage_speed.toml")
    folder = Path(out_dir) if out_dir is not None else Path(tempfile.mkdtemp())
    summary = fb.run_sweep(spec, folder / "voltage_speed", n_workers=2)
    with xr.open_dataset(summary["dataset"]) as ds:
        ds = ds.load()
    print(
        f"{summary['n_ok']} of {summary['n_points']} points ok, {summary['n_failed']} failed, "
        f"in {summary['wall_time_s']:.1f} s: {folder / 'voltage_speed.nc'}"
    )
    print("minimum film (µm), voltage down, speed across (krpm):")
    speeds = ds["speed"].values
    print("        " + "".join(f"{s:>9.0f}" for s in speeds / 1e3))
    for v in ds["voltage"].values:
        row = ds["min_film_um"].sel(voltage=v).values
        print(f"{v:6.0f} V" + "".join(f"{x:9.2f}" for x in row))
    return ds


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
