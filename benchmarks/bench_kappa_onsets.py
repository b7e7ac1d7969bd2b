"""Which κ is no knob: the linear onsets at κ = 0, 0.02, 0.05, 0.1, 0.2 on 96 × 12 and
192 × 24 (issue 49, item 2). Prints one line per reading and voltage.

Run: .venv/bin/python benchmarks/bench_kappa_onsets.py [--kappas 0,0.02,0.05,0.1,0.2] [--factors 1,2]
     [--shimmed]

The default reading (local + compliant) and the paper's (lobe + held) at 0/50/100/150 V;
each onset by :func:`foilbearing.check.onset_near` in a ±8 % bracket around the 192 × 24
κ = 0.1 onset of docs/lift-off.md (the full scan, 20-100 krpm every 4 krpm, where it is
not inside), Brent to 1e-4. ``--factors 4`` adds 384 × 48 (about a minute or two an
onset). κ's effect on a grid is f(κ) − f(0) there; each onset with its whirl frequency. About 2 minutes for the defaults on an
idle core. The figures and the choice they support: docs/lift-off.md, "Choosing κ for
the published onsets". ``--shimmed``: the shimmed GFB at the four voltages instead (its
brackets around its 96 × 12, κ = 0.1 onsets), for the errors of the study's shimmed column.
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import replace

from foilbearing.case import default_case
from foilbearing.check import onset_near, refined

RPM = math.pi / 30.0

#: The 192 × 24, κ = 0.1 onsets (krpm) of docs/lift-off.md: the brackets' centres.
NEAR = {
    ("local", "compliant", 0): 44.084,
    ("local", "compliant", 50): 42.806,
    ("local", "compliant", 100): 57.118,
    ("local", "compliant", 150): 54.920,
    ("lobe", "held", 0): 44.085,
    ("lobe", "held", 50): 33.626,
    ("lobe", "held", 100): 71.063,
    ("lobe", "held", 150): 79.717,
}

#: The shimmed GFB's 96 × 12, κ = 0.1 onsets (krpm) of the study: its brackets' centres.
NEAR_SHIMMED = {0: 36.3, 50: 39.5, 100: 85.6, 150: 90.9}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kappas", default="0,0.02,0.05,0.1,0.2")
    ap.add_argument("--factors", default="1,2", help="grid refinements of 96 × 12")
    ap.add_argument("--shimmed", action="store_true", help="the shimmed GFB instead")
    args = ap.parse_args()
    kappas = [float(k) for k in args.kappas.split(",")]
    factors = [int(f) for f in args.factors.split(",")]
    scan = [s * 1e3 * RPM for s in range(20, 101, 4)]
    print("onset (krpm) at its whirl frequency [CPU s]; effect = f(κ) − f(0) on the same grid")
    runs = (
        {("shimmed", "GFB", v): near for v, near in NEAR_SHIMMED.items()} if args.shimmed else NEAR
    )
    for (response, dynamics, volts), near in runs.items():
        base = default_case().with_voltages(float(volts))
        if args.shimmed:
            base = base.shimmed()
        else:
            base = base.with_actuator_reading(response, dynamics)
        for f in factors:
            onsets: dict[float, float | None] = {}
            cells = []
            for kappa in kappas:
                case = replace(base, grid=replace(base.grid, lift_off_smoothing=kappa))
                case = refined(case, f) if f > 1 else case
                t0 = time.process_time()
                on = onset_near(case, scan, near * 1e3 * RPM, rel_tol=1e-4, bracket=0.08)
                cpu = time.process_time() - t0
                onsets[kappa] = None if on.onset_speed is None else on.onset_speed / RPM / 1e3
                value = onsets[kappa]
                sharp = onsets.get(0.0)
                effect = (
                    f" {100 * (value - sharp) / sharp:+.2f} %"
                    if value is not None and sharp and kappa
                    else ""
                )
                whirl = (on.whirl_frequency or 0.0) / (2 * math.pi)
                shown = "none" if value is None else f"{value:.3f} at {whirl:.3f} Hz"
                cells.append(f"κ {kappa:g}: {shown}{effect} [{cpu:.0f}]")
            grid = f"{96 * f} × {12 * f}"
            print(f"{response}+{dynamics} {volts:3d} V {grid}: " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main()
