"""Benchmark of the rotor's linear analysis (issue 32). Prints its figures.

Run: .venv/bin/python benchmarks/bench_rotor.py

The Campbell diagram of examples/rotor_rigid_symmetric.toml over 20 speeds (30-68 krpm,
2 krpm apart; 4 modes with matched whirl): the wall time of the two bearings' coefficient
tables (20 speeds x 12 frequencies each) and of ROSS's modal analyses. Target: <= 60 s.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from foilbearing.constants import RPM
from foilbearing.rotor import load_rotor, ross_rotor, rotor_modes

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "rotor_rigid_symmetric.toml"


def main() -> None:
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
