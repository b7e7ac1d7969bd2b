"""
An uncertainty study on Dask
============================

Nobody knows their own bearing exactly: the clearance is a machining tolerance, the
foil's loss factor a range from the literature, the gas viscosity moves with the
temperature and the rotor's mass with what it carries. An uncertainty study puts a
distribution on each such input, runs the bearing at points drawn from them, and
reports for each prediction its 5th, 50th and 95th percentiles and which input moves
it (the user guide's uncertainty format; ``foilbearing uncertainty UQ.toml`` runs the
same file from the command line).

Here the passive bump foil bearing of the first tutorial
(``examples/bump_foil_bearing.toml``) with four uncertain inputs, on a local Dask
cluster of two workers. **This study is coarse**, so that the page builds in seconds:
64 points of a Latin hypercube with RBD-FAST first-order indices (the study's quick
plan), on a 36 × 4 grid.
A real study takes the case's own grid (96 × 12) and a few hundred points with the
Sobol' estimator, which adds total indices (the built-in file,
``examples/uncertainty_paper.toml``, runs 256 of them); its percentiles then move by a
few per cent and its indices sharpen as one over the square root of the sample.
"""

# %%
# The uncertainty file
# --------------------
# The case, the inputs with their distributions (any continuous case field by its
# dotted path, with units), the outputs and the sample. The static readouts are taken
# at three speeds; the linear onset of whirl is scanned from 10 to 100 krpm and refined.

import dataclasses
import tempfile
from pathlib import Path

import numpy as np

import foilbearing as fb
from foilbearing.case.model import Grid
from foilbearing.output.plots.uncertainty import plot_bands, plot_indices
from foilbearing.uncertainty import load_uncertainty, run_uncertainty


def repository_file(name: str) -> Path:
    """A file of the repository, wherever the page is built from."""
    here = Path.cwd()
    for folder in (here, *here.parents):
        if (folder / name).is_file():
            return folder / name
    raise FileNotFoundError(name)


case_file = repository_file("examples/bump_foil_bearing.toml")
folder = Path(tempfile.mkdtemp())
uq_file = folder / "bump_uq.toml"
text = """
title = "Bump foil bearing: what we do not know"
case = "CASE"           # the case file (here its path, filled in below)
samples = 64            # coarse: a real study takes a few hundred
sampler = "lhs"         # a Latin hypercube, as RBD-FAST wants
estimator = "rbd_fast"  # first-order indices from any sample
seed = 1

[set]                   # coarse grid for this page; the case's own is 96 x 12
"grid.n_theta" = 36
"grid.n_z" = 4

[inputs]
"bearing.clearance" = { distribution = "normal", mean = "32 um", std = "1.5 um" }
"gas.viscosity" = { distribution = "uniform", low = "1.80e-5 Pa*s", high = "1.90e-5 Pa*s" }
"foil.loss_factor" = { distribution = "uniform", low = 0.05, high = 0.2 }
"rotor.mass" = { distribution = "uniform", low = "9 kg", high = "11.4 kg" }

[outputs.static]
speeds = ["20000 rpm", "40000 rpm", "60000 rpm"]

[outputs.stability]
speed_range = ["10000 rpm", "100000 rpm", "10000 rpm"]
"""
uq_file.write_text(text.replace("CASE", case_file.as_posix()))
spec = load_uncertainty(uq_file)
print(f"{spec.n_points} points of {len(spec.inputs)} inputs: {spec.estimator}, {spec.sampler}")

# %%
# Running it on Dask
# ------------------
# :func:`foilbearing.uncertainty.run_uncertainty` runs the points on the sweep's Dask
# machinery: on the client it is given (here a cluster of two workers inside this
# process), on a scheduler's address, or on a local cluster it starts. Each finished
# point is written to ``points/`` as it completes, so that an interrupted study
# resumes (``resume=True``); at the end ``uncertainty.nc`` holds the percentiles and
# the indices.

from distributed import Client, LocalCluster

with (
    # its HTTP port: any free one on this machine (8787, Dask's default, may be taken)
    LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address="127.0.0.1:0"
    ) as cluster,
    Client(cluster) as client,
):
    ds, summary = run_uncertainty(spec, folder / "result", client=client)
n_ok = int((ds["status"].values == "ok").sum())
print(f"{n_ok} of {ds.sizes['sample']} points computed")

# %%
# The envelope
# ------------
# The median and the 5-95 % band of each output against speed, and of the onset.
# The nominal bearing, the case file as it stands on the same grid, is computed
# once more beside the study to show where it falls.

nominal = dataclasses.replace(fb.load_case(case_file), grid=Grid(n_theta=36, n_z=4))
nominal_film = fb.solve_equilibrium(nominal, speed="40 krpm").min_film * 1e6
nominal_onset = fb.onset_speed(nominal, [k * 1e3 * fb.RPM for k in range(10, 101, 10)])
nominal_krpm = nominal_onset.onset_speed / fb.RPM / 1e3


def output(quantity: str, krpm: float = np.nan) -> str:
    """The name of the output of ``quantity`` at ``krpm`` (NaN: not at a speed)."""
    at = ds["speed_krpm"].values
    match = (ds["quantity"].values == quantity) & ((at == krpm) | (np.isnan(at) & np.isnan(krpm)))
    return str(ds["output"].values[match][0])


film_name, onset_name = output("min_film_um", 40.0), output("onset_speed_krpm")
film = ds["percentile"].sel(output=film_name).values  # 5th, 50th, 95th
onset = ds["percentile"].sel(output=onset_name).values
print(
    f"minimum film at 40 krpm: {film[0]:.2f} to {film[2]:.2f} µm (median {film[1]:.2f}); "
    f"nominal {nominal_film:.2f} µm"
)
print(
    f"onset of whirl: {onset[0]:.1f} to {onset[2]:.1f} krpm (median {onset[1]:.1f}); "
    f"nominal {nominal_krpm:.1f} krpm"
)
fig_bands = plot_bands(ds)

# %%
# Which input matters
# -------------------
# The first-order index of an input is the share of the output's variance it explains
# on its own (bars: filled; whiskers: 95 % bootstrap half-widths, about ±0.3 at 64
# points, so this ranks the inputs and no more). A static equilibrium does not see the
# rotor's mass or the foil's loss factor (the load is given): the film is set by the
# clearance and the viscosity. The onset of whirl is set mostly by the clearance, then
# by the loss factor, which damps the foil; the rotor's mass over this range moves it
# by less than the estimator can resolve.

first = ds["first_order"]
for name in (film_name, onset_name):
    ranked = first.sel(output=name).to_series().sort_values(ascending=False)
    print(f"{name}: " + ", ".join(f"{k} {v:.2f}" for k, v in ranked.items()))
fig_indices = plot_indices(ds)
