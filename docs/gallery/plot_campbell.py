"""
Campbell diagram of a rotor on two bearings
===========================================

The damped natural frequencies of the two-disk rotor on two C-GFBs at 150 V
(``examples/rotor_two_disk.toml``) against its speed, from 15 to 60 krpm (at 10 krpm
and below the bearings find no static equilibrium on this grid), each mode with its bearing
coefficients at its own whirl frequency (ROSS, ``matched_whirl``). Where the 1X line
crosses a mode, an imbalance excites it: a critical speed. The gas films stiffen with
speed, so the lowest mode's frequency rises with it; the colour is each mode's log
decrement, negative past the onset. Coarse grid: 36 × 4 cells per bearing, eight
whirl frequencies per table; needs the ``ross`` extra.
"""

import dataclasses
from pathlib import Path

import numpy as np

import foilbearing as fb
from foilbearing.case.model import Grid
from foilbearing.output.plots.rotor import plot_campbell
from foilbearing.rotor import load_rotor, ross_rotor, rotor_modes
from foilbearing.rotor.linear import modes_at


def repository_file(name: str) -> Path:
    """A file of the repository, wherever the page is built from."""
    here = Path.cwd()
    for folder in (here, *here.parents):
        if (folder / name).is_file():
            return folder / name
    raise FileNotFoundError(name)


rotor = load_rotor(repository_file("examples/rotor_two_disk.toml"))
coarse = Grid(n_theta=36, n_z=4)
rotor = dataclasses.replace(
    rotor,
    bearings=tuple(
        dataclasses.replace(s, case=dataclasses.replace(s.case, grid=coarse))
        for s in rotor.bearings
    ),
)
krpm = [15, 20, 25, 30, 35, 40, 45, 50, 55, 60]
speeds = [k * 1e3 * fb.RPM for k in krpm]
model = ross_rotor(rotor, speeds, frequencies=2 * np.pi * np.geomspace(20.0, 1200.0, 8))
modes = rotor_modes(rotor, speeds, model=model, num_modes=6)
print("lowest mode (Hz):", " ".join(f"{f:.0f}" for f in modes.frequency[:, 0]))

# %%
# The shaft's first bending mode is a pair, a backward and a forward whirl. The disks'
# gyroscopic moments split it: with speed the backward one falls and the forward one
# rises.

for j in (4, 5):
    whirl = "forward" if modes.forward[-1, j] else "backward"
    print(f"mode {j + 1} ({whirl}): {modes.frequency[0, j]:.0f} Hz at {krpm[0]} krpm, "
          f"{modes.frequency[-1, j]:.0f} Hz at {krpm[-1]} krpm")  # fmt: skip

# %%
# The critical speeds: where each mode's frequency meets the running speed, read off
# the diagram between its speeds and checked by ROSS's modes at that speed.

one_x = modes.speeds / (2 * np.pi)  # Hz
for j in range(modes.frequency.shape[1]):
    gap = modes.frequency[:, j] - one_x
    k = np.flatnonzero(np.sign(gap[:-1]) != np.sign(gap[1:]))
    if k.size == 0:
        continue
    k = int(k[0])
    w = modes.speeds[k] - gap[k] * (modes.speeds[k + 1] - modes.speeds[k]) / (gap[k + 1] - gap[k])
    direct = modes_at(model, w, modes.frequency.shape[1])[0][j] / (2 * np.pi)
    print(f"mode {j + 1} meets 1X at {w / fb.RPM:.0f} rpm ({w / (2 * np.pi):.1f} Hz); "
          f"ROSS at that speed: {direct:.1f} Hz")  # fmt: skip
fig = plot_campbell(modes, title="Two-disk rotor on two C-GFBs at 150 V (36 x 4 grid)")
