"""
A sweep on Dask
===============

Any analysis over any case field, speed and voltage runs as a sweep on a Dask
cluster, every point written as it finishes, so that an interrupted sweep resumes
where it stopped. Here: the onset of the paper's C-GFB against its voltage and its
clearance, on a local cluster of two workers. The same file runs from the command
line, ``foilbearing sweep SWEEP.toml --out RESULT`` (the user guide's sweep format;
a remote cluster: ``--scheduler ADDRESS``).

The sweep sets the grid to 48 × 6 (the built-in 96 × 12 moves these onsets by
about 1 %), so that its eight points take seconds.
"""

# %%
# The sweep file
# --------------
# A sweep is a TOML file: the case, the analysis, fixed edits (``[set]``) and the
# swept parameters, whose Cartesian product is the grid of points.

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import xarray as xr

import foilbearing as fb
from foilbearing.sweep.spec import load_sweep

folder = Path(tempfile.mkdtemp())
sweep_file = folder / "onset.toml"
sweep_file.write_text(
    """
title = "C-GFB: onset against voltage and clearance"
case = "default"
analysis = "stability"

[set]
"grid.n_theta" = 48
"grid.n_z" = 6

[stability]
speed_range = ["20000 rpm", "100000 rpm", "10000 rpm"]

[parameters]
voltage = ["0 V", "50 V", "100 V", "150 V"]
"bearing.clearance" = ["90 um", "110 um"]
"""
)
spec = load_sweep(sweep_file)

# %%
# Running it
# ----------
# :func:`foilbearing.run_sweep` runs on the Dask client it is given, or on a
# scheduler's address, or else starts a local cluster of worker processes (on
# 127.0.0.1 only). It writes each point to ``RESULT.d/points/`` as it finishes; at
# the end one NetCDF file holds them all. This page gives it a cluster of two workers
# inside its own process (a script that starts worker processes must guard its top
# level with ``if __name__ == "__main__":``, as ``examples/sweep.py`` does).

from distributed import Client, LocalCluster

with (
    # its HTTP port: any free one on this machine (8787, Dask's default, may be taken)
    LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address="127.0.0.1:0"
    ) as cluster,
    Client(cluster) as client,
):
    summary = fb.run_sweep(spec, folder / "onset", client=client)
print(f"{summary['n_ok']} of {summary['n_points']} points, {summary['n_failed']} failed")
with xr.open_dataset(summary["dataset"]) as ds:
    onset = ds["onset_speed_rpm"].load()
print(onset.to_pandas().round(0))  # rows: voltage (V); columns: clearance (µm)

# %%
# The onset against the voltage, one line per clearance (a swept case field is a
# coordinate named after it, in the unit it reports). The clearance moves the onset as
# much as the voltage does.

fig, ax = plt.subplots(figsize=(6, 3.5), layout="constrained")
unit = onset["bearing_clearance"].attrs.get("units", "")
for clearance in onset["bearing_clearance"].values:
    line = onset.sel(bearing_clearance=clearance)
    ax.plot(line["voltage"], line / 1e3, "o-", label=f"C = {clearance:g} {unit}")
ax.set(xlabel="voltage (V)", ylabel="linear onset (krpm)")
ax.legend()
