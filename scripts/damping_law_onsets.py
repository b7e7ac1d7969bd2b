"""Linear onset speeds of the default C-GFB under two foil damping laws (docs/lift-off.md).

The law the code uses is the bump's viscous damper γ k_b/ω at the running speed ω,
``k_b (1 + jγ ω_e/ω)`` at a whirl frequency ω_e, the same in the orbit. The hysteretic
``k_b (1 + jγ)`` (γ at every frequency, no causal time-domain form with the orbit's
states) is evaluated here by taking the compliance at ω_e = ω: a law object passed in the
case's ``foil.damping`` (``foilbearing.laws``), no patching. Prints one row per law.

Run: .venv/bin/python scripts/damping_law_onsets.py
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from numpy.typing import NDArray

from foilbearing.case import Case, default_case
from foilbearing.laws import ViscousBump
from foilbearing.stability import onset_speed

RPM = math.pi / 30.0


@dataclass(frozen=True)
class HystereticBump:
    """The structural law ``k_b (1 + jγ)``: the viscous bump's compliance at ω_e = ω, at
    every whirl frequency. Frequency domain only (a peer of
    :class:`foilbearing.laws.ViscousBump` for the linear analyses; no orbit)."""

    loss_factor: float
    dynamic = False

    def compliance(self, bump_compliance: Any, frequency: float, speed: float) -> NDArray[Any]:
        return ViscousBump(self.loss_factor).compliance(bump_compliance, speed, speed)

    def rate(self, speed: float) -> float:
        raise NotImplementedError("the hysteretic bump has no causal time-domain form")


def with_law(case: Case, law: Any) -> Case:
    """The case with another foil damping law (``Foil.damping``)."""
    assert case.foil is not None
    return replace(case, foil=replace(case.foil, damping=law))


def main() -> None:
    foil = default_case().foil
    assert foil is not None
    gamma = foil.loss_factor
    for name, law in (
        ("viscous γ k_b/ω (the code's)", ViscousBump(gamma)),
        ("hysteretic k_b(1+jγ)", HystereticBump(gamma)),
    ):
        row = []
        for volts in (0.0, 50.0, 100.0, 150.0):
            res = onset_speed(with_law(default_case().with_voltages(volts), law))
            row.append(
                "stable" if res.onset_speed is None else f"{res.onset_speed / RPM / 1e3:.1f}"
            )
        print(f"{name:30s} onset at 0/50/100/150 V: {' / '.join(row)} krpm")


if __name__ == "__main__":
    main()
