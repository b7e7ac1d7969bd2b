"""
Stability: the onset against voltage
====================================

The linear onset of whirl of the paper's C-GFB at each voltage, beside the shimmed
bearing with the same preloads held by rigid shims. The stacks' compliance, in series
with the foil, keeps the C-GFB's onset below the shimmed bearing's at 100 and
150 V. Coarse grid: 72 × 6 cells.
"""

import dataclasses

import matplotlib.pyplot as plt

import foilbearing as fb
from foilbearing.case.model import Grid

case = dataclasses.replace(fb.default_case(), grid=Grid(n_theta=72, n_z=6))
scan = [k * 1e3 * fb.RPM for k in range(20, 101, 10)]
voltages = [0.0, 25.0, 50.0, 75.0, 100.0, 125.0, 150.0]
onsets: dict[str, list[float]] = {"C-GFB": [], "shimmed GFB": []}
for volts in voltages:
    c = case.with_voltages(volts)
    for name, bearing in (("C-GFB", c), ("shimmed GFB", c.shimmed())):
        result = fb.onset_speed(bearing, scan)
        onsets[name].append(result.onset_speed / fb.RPM / 1e3)

fig, ax = plt.subplots(figsize=(6, 3.5), layout="constrained")
for name, values in onsets.items():
    ax.plot(voltages, values, "o-", label=name)
ax.set(xlabel="actuator voltage (V)", ylabel="linear onset (krpm)")
ax.legend()
plt.show()
for name, values in onsets.items():
    print(f"{name:12s}", " ".join(f"{v:5.1f}" for v in values), "krpm")
