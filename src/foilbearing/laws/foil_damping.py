"""Foil damping: how the bump foil dissipates energy as the film squeezes it.

The bump layer is a spring k_b per unit area (``structure/bump.py`` gives k_b); a
foil damping law says what acts beside it. The law is stated once here, in each form
an analysis uses (docs/model.md §3, docs/lift-off.md):

- frequency domain (the force coefficients, :mod:`foilbearing.analysis.coefficients`): the
  bump's complex compliance at an excitation frequency ω_e, :meth:`~ViscousBump.compliance`;
- time domain (the orbit, :mod:`foilbearing.reynolds.transient` and the BDF kernels):
  the bump deflection U obeys ``dU/dt = r (c_b q − U)`` with the rate
  :meth:`~ViscousBump.rate` r (1/s); a law without a rate has no bump state, and the
  bump then follows the film at once (its compliance joins the actuator's).

Laws, peers of one another (each a frozen dataclass; pass one in place of another):

- :class:`ViscousBump` (loss factor γ): the spring with a viscous damper
  ``c = γ k_b/ω`` at the running speed ω, a Kelvin–Voigt bump. Its loss at a whirl
  ratio ν = ω_e/ω is γν. Today's law of every case with ``foil.loss_factor``.
- :class:`NoFoilDamping`: the spring alone; all damping is the film's.

A new law (a hysteretic or friction bump) is a new class here with the same methods;
the time-domain form must be one the orbit can integrate with the bump state U.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

__all__ = ["FoilDamping", "NoFoilDamping", "ViscousBump", "foil_damping_law"]


@runtime_checkable
class FoilDamping(Protocol):
    """What the analyses ask of a foil damping law."""

    @property
    def loss_factor(self) -> float:
        """γ, the loss per radian at the running speed (0: none), dimensionless."""
        ...

    @property
    def dynamic(self) -> bool:
        """Whether the bump has a state of its own in time (a finite :meth:`rate`)."""
        ...

    def compliance(self, bump_compliance: Any, frequency: float, speed: float) -> NDArray[Any]:
        """The bump's complex compliance at excitation frequency ω_e (rad/s), speed ω."""
        ...

    def rate(self, speed: float) -> float:
        """r in ``dU/dt = r (c_b q − U)`` at speed ω, 1/s (0: no bump state)."""
        ...


@dataclass(frozen=True)
class ViscousBump:
    """The bump spring k_b with a viscous damper ``c_b = γ k_b/ω`` at the running speed ω.

    Parameters
    ----------
    loss_factor : float
        γ >= 0 (0.05-0.2 is typical for bump foils); 0 is the spring alone.
    """

    loss_factor: float

    def __post_init__(self) -> None:
        if not (math.isfinite(self.loss_factor) and self.loss_factor >= 0.0):
            raise ValueError(f"ViscousBump.loss_factor must be >= 0, got {self.loss_factor!r}")

    @property
    def dynamic(self) -> bool:
        """The bump has a state U in time (γ > 0)."""
        return self.loss_factor > 0.0

    def compliance(self, bump_compliance: Any, frequency: float, speed: float) -> NDArray[Any]:
        """``c_b / (1 + jγ ω_e/ω)``: the spring k_b (1 + jγν) as a compliance.

        Parameters
        ----------
        bump_compliance : ndarray
            c_b = p_a/(C k_b) per θ-row (dimensionless).
        frequency : float
            Excitation frequency ω_e, rad/s.
        speed : float
            Running speed ω, rad/s (sets the damper γ k_b/ω).
        """
        return np.asarray(bump_compliance / (1.0 + 1j * self.loss_factor * frequency / speed))

    def rate(self, speed: float) -> float:
        """``ω/γ``, 1/s: the bump relaxes towards c_b q at the running speed over γ
        (0 for γ = 0, a spring without a state)."""
        return speed / self.loss_factor if self.dynamic else 0.0


@dataclass(frozen=True)
class NoFoilDamping:
    """The bump spring alone: the foil stores energy and dissipates none."""

    @property
    def loss_factor(self) -> float:
        """γ = 0."""
        return 0.0

    @property
    def dynamic(self) -> bool:
        """No bump state: the bump follows the film at once."""
        return False

    def compliance(self, bump_compliance: Any, frequency: float, speed: float) -> NDArray[Any]:
        """``c_b``, real at every frequency."""
        return np.asarray(bump_compliance, dtype=complex)

    def rate(self, speed: float) -> float:
        """0: no bump state."""
        return 0.0


def foil_damping_law(law: FoilDamping | float) -> FoilDamping:
    """The law itself, or :class:`ViscousBump` of a loss factor given as a number."""
    if isinstance(law, (int, float)):
        return ViscousBump(float(law))
    return law
