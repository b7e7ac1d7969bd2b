"""
Static map: the C-GFB against speed and voltage
===============================================

The journal's equilibrium in the paper's C-GFB from 10 to 90 krpm at 0, 75 and
150 V: its eccentricity and the minimum film (the paper's Figs. 11-12 show the
same trends). Coarse grid: 72 × 6 cells (the built-in 96 × 12 moves these by
about 1 %).
"""

import dataclasses

import matplotlib.pyplot as plt

import foilbearing as fb
from foilbearing.case.model import Grid

case = dataclasses.replace(fb.default_case(), grid=Grid(n_theta=72, n_z=6))
speeds_krpm = [10, 30, 50, 70, 90]
fig, (ax_e, ax_h) = plt.subplots(1, 2, figsize=(9, 3.5), layout="constrained")
for volts in (0.0, 75.0, 150.0):
    points = [
        fb.solve_equilibrium(case.with_voltages(volts), speed=f"{k} krpm") for k in speeds_krpm
    ]
    ax_e.plot(speeds_krpm, [p.eccentricity for p in points], "o-", label=f"{volts:.0f} V")
    ax_h.plot(speeds_krpm, [p.min_film * 1e6 for p in points], "o-", label=f"{volts:.0f} V")
    print(f"{volts:5.0f} V: e/C from {points[0].eccentricity:.3f} to {points[-1].eccentricity:.3f}")
ax_e.set(xlabel="speed (krpm)", ylabel="eccentricity e/C")
ax_h.set(xlabel="speed (krpm)", ylabel="minimum film (µm)")
ax_e.legend()
plt.show()
