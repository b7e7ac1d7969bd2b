"""Linear onset speeds of the default C-GFB under two foil damping laws (docs/lift-off.md).

The law the code uses is the bump's viscous damper γ k_b/ω at the running speed ω,
``k_b (1 + jγ ω_e/ω)`` at a whirl frequency ω_e, the same in the orbit. The hysteretic
``k_b (1 + jγ)`` (γ at every frequency, no causal time-domain form with the orbit's
states) is evaluated here by taking the compliance at ω_e = ω. Prints one row per law.

Run: .venv/bin/python scripts/damping_law_onsets.py
"""

from __future__ import annotations

import math
from typing import Any

import foilbearing.coefficients as coefficients
from foilbearing.case import default_case
from foilbearing.stability import onset_speed

RPM = math.pi / 30.0


def main() -> None:
    viscous = coefficients.dynamic_compliance

    def hysteretic(static: Any, frequency: float, loss_factor: float | None = None) -> Any:
        return viscous(static, static.speed, loss_factor)

    for name, law in (
        ("viscous γ k_b/ω (the code's)", viscous),
        ("hysteretic k_b(1+jγ)", hysteretic),
    ):
        coefficients.dynamic_compliance = law  # type: ignore[assignment]
        row = []
        for volts in (0.0, 50.0, 100.0, 150.0):
            res = onset_speed(default_case().with_voltages(volts))
            row.append(
                "stable" if res.onset_speed is None else f"{res.onset_speed / RPM / 1e3:.1f}"
            )
        print(f"{name:30s} onset at 0/50/100/150 V: {' / '.join(row)} krpm")
    coefficients.dynamic_compliance = viscous  # type: ignore[assignment]


if __name__ == "__main__":
    main()
