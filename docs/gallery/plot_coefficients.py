"""
Stiffness and damping against frequency
=======================================

The eight force coefficients of the paper's C-GFB at 50 krpm and 150 V, against the
excitation frequency from 0.1 to 2 times the running speed. The gas film stiffens
with frequency while its damping falls: the film's compressibility. Coarse grid:
72 × 6 cells.
"""

import dataclasses

import foilbearing as fb
from foilbearing.case.model import Grid

case = dataclasses.replace(fb.default_case(), grid=Grid(n_theta=72, n_z=6))
st = fb.solve_equilibrium(case.with_voltages(150.0), speed="50 krpm")
running = st.speed  # rad/s
fc = fb.force_coefficients(st, [r * running for r in (0.1, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0)])
print(fc)
fig = fc.plot()
