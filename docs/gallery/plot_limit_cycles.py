"""
Limit cycles past the onset
===========================

Is the whirl past the linear onset bounded? From the onset (a Hopf bifurcation) the
branch of periodic orbits is followed by shooting on the orbit's own time stepper,
each cycle's stability from its Floquet multipliers. Here the paper's C-GFB at 150 V
under the paper's reading of the actuator (the whole lobe lowered, the stinger held):
the bifurcation is supercritical, a stable whip grows from the onset with speed.

Coarse grid: 32 × 4 cells, on which the onset lies about 5 % below the default grid's
79.1 krpm; four cycles (the theory page's bifurcation section follows the branch
further and on finer grids).
"""

import dataclasses

import foilbearing as fb
from foilbearing.bifurcation.bearing import whirl_branch
from foilbearing.case.model import Grid
from foilbearing.output.plots.bifurcation import plot_whirl_branch

case = fb.default_case().with_voltages(150.0).with_actuator_reading("lobe", "held")
case = dataclasses.replace(case, grid=Grid(n_theta=32, n_z=4, orbit_n_z=4))
branch = whirl_branch(case, steps=2, ds=4.0)
head = branch.headline()
print(f"{head['bifurcation_type']} Hopf bifurcation at {head['hopf_speed_rpm']:.0f} rpm")
for rpm, amp, hz, stable in zip(
    head["speeds_rpm"],
    head["amplitude_um"],
    head["whirl_frequency_Hz"],
    head["stable"],
    strict=True,
):
    print(f"  {rpm:7.0f} rpm: {amp:5.2f} µm at {hz:6.1f} Hz, {'stable' if stable else 'unstable'}")
fig = plot_whirl_branch(head, title="C-GFB, 150 V, lobe + held")
