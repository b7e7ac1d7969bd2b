"""Stiffness and damping of the paper's C-GFB against the excitation frequency.

At 50 krpm and 150 V: the equilibrium, then K and C (N/m, N·s/m) of the
perturbed Reynolds equation, coupled to the foil with its damping law, at
excitation frequencies from 0.1 to 2 times the running speed. The gas film
stiffens with frequency and its damping falls (the compressibility of the film).

    python examples/coefficients.py          (about 3 s)
"""

from __future__ import annotations

import numpy as np

import foilbearing as fb

RATIOS = (0.1, 0.25, 0.5, 1.0, 1.5, 2.0)


def main() -> dict[str, np.ndarray]:
    case = fb.default_case().with_voltages(150.0)
    speed = 50_000 * fb.RPM
    st = fb.solve_equilibrium(case, speed=speed)
    fc = fb.force_coefficients(st, [r * speed for r in RATIOS])
    print(
        f"C-GFB at 50 krpm, 150 V: e/C = {st.eccentricity:.3f}, h_min = {st.min_film * 1e6:.2f} µm"
    )
    print(
        "ω_e/ω   K_XX     K_XY     K_YX     K_YY  (MN/m)    C_XX    C_XY    C_YX    C_YY  (N·s/m)"
    )
    for r, k, c in zip(RATIOS, fc.K, fc.C, strict=True):
        print(
            f"{r:5.2f} "
            + " ".join(f"{x / 1e6:8.3f}" for x in k.ravel())
            + "     "
            + " ".join(f"{x:7.1f}" for x in c.ravel())
        )
    return {"ratios": np.array(RATIOS), "K": fc.K, "C": fc.C}


if __name__ == "__main__":
    main()
