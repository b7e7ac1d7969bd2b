"""
A passive bump foil bearing: from case file to onset and orbit
===============================================================

A first-generation bump foil bearing, D = L = 38.1 mm with a 32 µm clearance, carries
a 10.2 kg rotor (100 N). We read its case file, find where the journal sits at a few
speeds, how stiff and damped the film is, from what speed the rotor whirls, and how
the journal moves at 30 krpm.

The built-in numerics of the case are 96 × 12 cells; this page runs on 48 × 6 (the
orbit on 48 × 4) to build in seconds. The numbers move by about 1 % (the static
equilibrium) to 2 % (the onset); ``foilbearing check`` measures that for any case.
"""

# %%
# The case file
# -------------
# ``examples/bump_foil_bearing.toml`` states the bearing with units: geometry, gas,
# the bump foil, the rotor and the operating point (format: the user guide's case
# format). :func:`foilbearing.load_case` reads and checks it; every number inside is
# SI. Here we also set the coarse grid of this page.

import dataclasses
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import foilbearing as fb
from foilbearing.case.model import Grid


def repository_file(name: str) -> Path:
    """A file of the repository, wherever the page is built from."""
    here = Path.cwd()
    for folder in (here, *here.parents):
        if (folder / name).is_file():
            return folder / name
    raise FileNotFoundError(name)


case = fb.load_case(repository_file("examples/bump_foil_bearing.toml"))
case = dataclasses.replace(case, grid=Grid(n_theta=48, n_z=6))  # coarse: see above
print(case.title)
print(f"clearance {case.bearing.clearance * 1e6:.0f} µm, load {case.operation.load:.0f} N")

# %%
# Where the journal sits
# ----------------------
# The static equilibrium balances the film's force against the load. An eccentricity
# above 1 means the foil gives way under the journal. The film thickens and the
# power loss grows with speed.

speeds_krpm = [10, 20, 30, 40, 50, 60]
points = [fb.solve_equilibrium(case, speed=f"{k} krpm") for k in speeds_krpm]
for k, st in zip(speeds_krpm, points, strict=True):
    print(
        f"{k:3d} krpm: e/C = {st.eccentricity:.3f}, "
        f"h_min = {st.min_film * 1e6:5.2f} µm, loss {st.power_loss:5.1f} W"
    )

fig_map, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3.2), layout="constrained")
ax1.plot(speeds_krpm, [st.min_film * 1e6 for st in points], "o-")
ax1.set(xlabel="speed (krpm)", ylabel="minimum film (µm)")
ax2.plot(speeds_krpm, [st.power_loss for st in points], "o-")
ax2.set(xlabel="speed (krpm)", ylabel="power loss (W)")

# %%
# The film at 30 krpm: the pressure around the bearing and the film thickness.

st30 = points[2]
print(st30)
fig = st30.plot()

# %%
# Stiffness and damping
# ---------------------
# The perturbed film gives eight coefficients at each excitation frequency. The gas
# film stiffens and its damping falls as the frequency rises.

frequencies = [f"{f} Hz" for f in (100, 250, 500, 1000)]
fc = fb.force_coefficients(st30, frequencies)
fig = fc.plot()

# %%
# Onset of whirl
# --------------
# The log decrement of the least stable whirl mode of the rigid rotor, against speed.
# Where it crosses zero the rotor starts to whirl at a fraction of its speed.

onset = fb.onset_speed(case)
print(onset)
fig = onset.plot()

# %%
# The orbit at 30 krpm
# --------------------
# The nonlinear orbit integrates film, foil and journal in time. The imbalance
# (10 g·mm) drives a synchronous (1X) orbit of about 1 µm. Well below the onset
# it stays small.

run = fb.simulate(case, fb.constant_speed("30 krpm", "0.1 s"))
print(run)
assert run.status.value == "completed"
amplitude = np.asarray(run.summary()["one_x_amplitude_0pk_um"])
print(f"1X amplitude, X and Y: {amplitude.round(2)} µm")
fig = run.plot()
