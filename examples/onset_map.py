"""Linear stability of the paper's C-GFB and of its shimmed twin against the voltage.

For each voltage, the speed at which the least stable whirl mode of the rotor on
the bearing loses its damping (log decrement zero), and that mode's whirl
frequency ratio (the linear counterpart of the paper's Fig. 13). On the default
case 100 and 150 V raise the onset well above that at 0 V, and shims of the same
thickness (rigid) raise it further; the onset is not monotone in the voltage.

    python examples/onset_map.py          (about 15 s)
"""

from __future__ import annotations

from typing import Any

import foilbearing as fb

VOLTAGES = (0.0, 50.0, 100.0, 150.0)
SCAN = [rpm * fb.RPM for rpm in range(20_000, 100_001, 10_000)]


def main() -> dict[str, list[float | None]]:
    out: dict[str, list[float | None]] = {"C-GFB": [], "shimmed": [], "whirl ratio": []}
    print("volts   C-GFB onset (krpm)  whirl ratio   shimmed onset (krpm)")
    for volts in VOLTAGES:
        case = fb.default_case().with_voltages(volts)
        c_gfb, shim = fb.onset_speed(case, SCAN), fb.onset_speed(case.shimmed(), SCAN)
        out["C-GFB"].append(None if c_gfb.onset_speed is None else c_gfb.onset_speed / fb.RPM)
        out["shimmed"].append(None if shim.onset_speed is None else shim.onset_speed / fb.RPM)
        out["whirl ratio"].append(c_gfb.whirl_ratio)

        def krpm(r: Any) -> str:
            return "stable" if r.onset_speed is None else f"{r.onset_speed / fb.RPM / 1e3:.1f}"

        ratio = "-" if c_gfb.whirl_ratio is None else f"{c_gfb.whirl_ratio:.3f}"
        print(f"{volts:5.0f} {krpm(c_gfb):>20} {ratio:>12} {krpm(shim):>22}")
    return out


if __name__ == "__main__":
    main()
