"""
The paper's C-GFB: what a voltage buys
======================================

The controllable gas foil bearing (C-GFB) of Park, Kim and Sim (2021) has three PZT
stacks at 60°, 180° and 300° that push the foil towards the journal. The voltage on
them sets this mechanical preload while the rotor runs. We look at what it changes:
the preloads, the journal's equilibrium, and above all the speed at which the rotor
starts to whirl, beside the shimmed bearing (the same preloads, made by rigid shims).

The built-in case runs on 96 × 12 cells; this page runs on 72 × 6 to build in
seconds. Its onsets lie within about 1-2 % of the default grid's (43.9 and 55.2 krpm
at 0 and 150 V; the user guide's results beside the paper).
"""

# %%
# The case and its preloads
# -------------------------
# :func:`foilbearing.default_case` is the paper's bearing (R = 20 mm, L = 35 mm,
# C = 100 µm). Each stack's free stroke, held back by its springs, gives the base
# preload at its voltage (paper Eq. 3).

import dataclasses

import matplotlib.pyplot as plt

import foilbearing as fb
from foilbearing.case.model import Grid
from foilbearing.output.plots.dynamics import plot_stability_map

case = dataclasses.replace(fb.default_case(), grid=Grid(n_theta=72, n_z=6))  # coarse
for volts in (0, 50, 100, 150):
    preloads = case.with_voltages(float(volts)).actuators.base_preloads() * 1e6
    print(f"{volts:3d} V: base preloads {', '.join(f'{p:.2f}' for p in preloads)} µm")

# %%
# The equilibrium at 50 krpm
# --------------------------
# With the stacks at rest the journal sits low in a loose bearing; at 150 V the three
# lobes close around it: a smaller eccentricity, a thinner film and more drag.

for volts in (0.0, 150.0):
    st = fb.solve_equilibrium(case.with_voltages(volts), speed="50 krpm")
    print(
        f"{volts:5.0f} V: e/C = {st.eccentricity:.3f}, h_min = {st.min_film * 1e6:5.2f} µm, "
        f"loss {st.power_loss:.1f} W"
    )
fig = st.plot()  # the film at 150 V

# %%
# The onset of whirl at 0 and 150 V
# ---------------------------------
# The linear onset: the speed at which the least stable whirl mode of the rigid rotor
# loses its damping. The shimmed bearing is the reference the paper compares with.

scan = [k * 1e3 * fb.RPM for k in range(20, 101, 10)]
onsets = {}
for volts in (0.0, 150.0):
    c_gfb = fb.onset_speed(case.with_voltages(volts), scan)
    shimmed = fb.onset_speed(case.with_voltages(volts).shimmed(), scan)
    onsets[volts] = c_gfb.onset_speed / fb.RPM / 1e3
    print(
        f"{volts:5.0f} V: C-GFB onset {onsets[volts]:.1f} krpm "
        f"(whirl {c_gfb.whirl_ratio:.2f} of the speed), "
        f"shimmed {shimmed.onset_speed / fb.RPM / 1e3:.1f} krpm"
    )
print(f"150 V raises the onset by {100 * (onsets[150.0] / onsets[0.0] - 1):.0f} %")

# %%
# The stability map
# -----------------
# The log decrement over speed and voltage: blue is stable, the black line its onset.
# The onset does not rise steadily with the voltage. The stacks' own compliance,
# in series with the foil, takes back part of what the preload gives.

speeds = [k * 1e3 * fb.RPM for k in range(20, 91, 5)]
voltages = [0.0, 25.0, 50.0, 75.0, 100.0, 125.0, 150.0]
stability = fb.stability_map(case, speeds, voltages)
fig = plot_stability_map(stability)
plt.show()
