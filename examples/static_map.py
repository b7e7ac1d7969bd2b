"""Static map of the paper's C-GFB: the journal equilibrium against speed and voltage.

For 0, 75 and 150 V on the three actuators and speeds from 10 to 90 krpm, the
equilibrium under the case's load: eccentricity (in units of the clearance C), attitude angle, minimum film,
power loss and the actuators' preloads (paper Figs. 10-12).

    python examples/static_map.py          (about 5 s)
"""

from __future__ import annotations

import math
from typing import Any

import foilbearing as fb

SPEEDS_KRPM = (10, 30, 50, 70, 90)
VOLTAGES = (0.0, 75.0, 150.0)


def main() -> dict[tuple[float, int], Any]:
    case = fb.default_case()
    points = {}
    print("volts  krpm   e/C  attitude (deg)  h_min (µm)  loss (W)  preloads (µm)")
    for volts in VOLTAGES:
        for krpm in SPEEDS_KRPM:
            st = fb.solve_equilibrium(case.with_voltages(volts), speed=krpm * 1e3 * fb.RPM)
            points[(volts, krpm)] = st
            preloads = ", ".join(f"{p * 1e6:.1f}" for p in st.preload)
            print(
                f"{volts:5.0f} {krpm:5d} {st.eccentricity:5.3f} "
                f"{math.degrees(st.attitude_angle):15.1f} {st.min_film * 1e6:11.2f} "
                f"{st.power_loss:9.2f}  {preloads}"
            )
    return points


if __name__ == "__main__":
    main()
