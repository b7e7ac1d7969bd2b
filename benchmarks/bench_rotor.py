"""Benchmark of the rotor's linear analysis (issue 32). Prints its figures.

Run: .venv/bin/python benchmarks/bench_rotor.py [--reduction]

The Campbell diagram of examples/rotor_rigid_symmetric.toml over 20 speeds (30-68 krpm,
2 krpm apart; 4 modes with matched whirl): the wall time of the two bearings' coefficient
tables (20 speeds x 12 frequencies each) and of ROSS's modal analyses. Target: <= 60 s.

``--reduction``: the onset of examples/rotor_two_disk.toml (flexible, two C-GFBs at 150 V)
on the Craig-Bampton rotor (:mod:`foilbearing.rotor.reduced`) against the number of shaft
modes kept, beside ROSS's full beam model; tables 2 krpm apart, 40-56 krpm.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from foilbearing.constants import RPM
from foilbearing.rotor import load_rotor, ross_rotor, rotor_modes
from foilbearing.rotor.linear import modes_at, refine_onset
from foilbearing.rotor.reduced import reduced_onset

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rotor_rigid_symmetric.toml"


def reduction() -> None:
    rotor = load_rotor(EXAMPLE.with_name("rotor_two_disk.toml"))
    speeds = list(np.arange(40e3, 56.01e3, 2e3) * RPM)
    model = ross_rotor(rotor, speeds)
    full = rotor_modes(rotor, speeds, model=model)
    onset, whirl = refine_onset(full, lambda w: modes_at(model, w, 4))
    assert onset is not None and whirl is not None
    print(f"ROSS's full model: onset {onset / RPM:,.0f} rpm, whirl {whirl:.2f} Hz")
    print("shaft modes kept | onset, rpm | error | whirl, Hz | wall, s")
    nodes = [b.node for b in rotor.bearings]
    for n in (0, 1, 2, 4, 6, 8, 12, 16):
        clock = time.perf_counter()
        reduced, reduced_whirl, _ = reduced_onset(model, nodes, speeds, n_modes=n)
        wall = time.perf_counter() - clock
        assert reduced is not None and reduced_whirl is not None
        print(f"{n} | {reduced / RPM:,.0f} | {100 * (reduced / onset - 1):+.4f} % | "
              f"{reduced_whirl:.2f} | {wall:.2f}")  # fmt: skip


def main() -> None:
    if "--reduction" in sys.argv[1:]:
        reduction()
        return
    rotor = load_rotor(EXAMPLE)
    speeds = list(np.arange(30e3, 68.01e3, 2e3) * RPM)
    clock = time.perf_counter()
    model = ross_rotor(rotor, speeds)
    tables = time.perf_counter() - clock
    clock = time.perf_counter()
    modes = rotor_modes(rotor, speeds, model=model)
    modal = time.perf_counter() - clock
    print(
        f"Campbell diagram, {len(speeds)} speeds x 4 modes (matched whirl): "
        f"{tables + modal:.1f} s (target 60 s): the bearings' tables {tables:.1f} s, "
        f"ROSS's modal analyses {modal:.1f} s"
    )
    low = modes.least_stable()
    print(f"  least log decrement from {low[0]:+.3f} at 30 krpm to {low[-1]:+.3f} at 68 krpm")


if __name__ == "__main__":
    main()
