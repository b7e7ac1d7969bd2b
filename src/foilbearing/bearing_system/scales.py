"""The scales of a bearing: the paper's non-dimensionalisation, computed once.

docs/model.md §2 writes the film in P = p/p_a, H = h/C, Z = z/R and τ = ω t, so that
the steady Reynolds equation (Eq. 4 of the paper) carries one parameter, the bearing
number Λ = 6 μ ω R²/(p_a C²), and the film force is ``p_a R²`` times the integral of
P − 1. The orbit integrates in physical time: the unsteady term 2Λ ∂/∂τ of Eq. (4) is
σ ∂/∂t with σ = 12 μ R²/(p_a C²), and the film force accelerates the journal's ε = e/C
by ``p_a R²/(m C)`` per unit of that integral.

Every analysis takes these numbers from :class:`Scales` (``Scales.from_case(case)``);
no other module writes their formulas. This module imports nothing of the package but
its errors: the case layer (``Case.bearing_number``, the reader's bound on Λ) uses it too, so it
reads a case through the few attributes it needs (:class:`CaseLike`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from foilbearing.errors import InputError

__all__ = ["BearingLike", "CaseLike", "GasLike", "Scales"]


class BearingLike(Protocol):
    """The geometry :class:`Scales` reads: ``Case.bearing``."""

    @property
    def radius(self) -> float: ...  # m
    @property
    def length(self) -> float: ...  # m
    @property
    def clearance(self) -> float: ...  # m


class GasLike(Protocol):
    """The gas :class:`Scales` reads: ``Case.gas``."""

    @property
    def viscosity(self) -> float: ...  # Pa·s
    @property
    def ambient_pressure(self) -> float: ...  # Pa


class RotorLike(Protocol):
    """The rotor :class:`Scales` reads: ``Case.rotor``."""

    @property
    def mass(self) -> float: ...  # kg


class CaseLike(Protocol):
    """What :meth:`Scales.from_case` reads of a :class:`~foilbearing.case.Case`."""

    @property
    def bearing(self) -> BearingLike: ...
    @property
    def gas(self) -> GasLike: ...
    @property
    def rotor(self) -> RotorLike: ...


@dataclass(frozen=True)
class Scales:
    """The bearing's scales (SI), and the dimensionless groups built from them.

    Attributes
    ----------
    ambient_pressure
        p_a, Pa: the pressure scale (P = p/p_a).
    radius
        R, m: the length scale of θ and Z = z/R.
    clearance
        C, m: the film scale (H = h/C, ε = e/C).
    length
        L, m: the bearing's axial length (the grid's half length is L/(2R)).
    viscosity
        μ, Pa·s.
    mass
        m, kg: the rotor mass this bearing carries, or None (then
        :attr:`film_force_per_mass` is None).
    sigma
        σ = 12 μ R²/(p_a C²), s: the unsteady term of Eq. (4) in physical time,
        2Λ ∂/∂τ = σ ∂/∂t (docs/model.md §5).
    lambda_per_speed
        Λ/ω = 6 μ R²/(p_a C²), s/rad: the bearing number of Eq. (4) per unit speed.
    force
        p_a R², N: the film force per unit of the dimensionless force ∫∫ (P − 1) (cos θ,
        sin θ) dθ dZ (docs/model.md §2).
    film_force_per_mass
        p_a R²/(m C), 1/s²: that force as an acceleration of ε = e/C (the orbit's
        journal rows); None without a mass.
    pressure_shear
        p_a C/(2R), Pa: the Poiseuille shear on the journal, h/(2R) ∂p/∂θ, per unit of
        H ∂P/∂θ (the drag torque, docs/model.md §2).
    torque
        R³, m³: the torque on the journal, N·m, per unit of the shear stress (Pa)
        integrated over θ and Z = z/R.
    """

    ambient_pressure: float
    radius: float
    clearance: float
    length: float
    viscosity: float
    mass: float | None = None
    sigma: float = field(init=False)
    lambda_per_speed: float = field(init=False)
    force: float = field(init=False)
    film_force_per_mass: float | None = field(init=False)
    pressure_shear: float = field(init=False)
    torque: float = field(init=False)

    def __post_init__(self) -> None:
        for name in ("ambient_pressure", "radius", "clearance", "length", "viscosity", "mass"):
            value = getattr(self, name)
            if value is None and name == "mass":
                continue
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0):
                raise InputError(f"Scales.{name} = {value!r}: expected a finite number > 0 (SI)")
        pa, r, c, mu = self.ambient_pressure, self.radius, self.clearance, self.viscosity
        # Written as the analyses wrote them before they moved here, so every number is
        # the same to the last bit (tests/test_numbers_unchanged.py).
        set_ = object.__setattr__
        set_(self, "sigma", 12.0 * mu * r**2 / (pa * c**2))
        set_(self, "lambda_per_speed", self.bearing_number(1.0))
        set_(self, "force", pa * r**2)
        per_mass = None if self.mass is None else pa * r**2 / (self.mass * c)
        set_(self, "film_force_per_mass", per_mass)
        set_(self, "pressure_shear", c * pa / (2.0 * r))
        set_(self, "torque", r**3)

    @classmethod
    def from_parts(cls, bearing: BearingLike, gas: GasLike, mass: float | None = None) -> Scales:
        """The scales of a bearing geometry and a gas (and a rotor mass, kg, if given)."""
        return cls(
            ambient_pressure=gas.ambient_pressure,
            radius=bearing.radius,
            clearance=bearing.clearance,
            length=bearing.length,
            viscosity=gas.viscosity,
            mass=mass,
        )

    @classmethod
    def from_case(cls, case: CaseLike) -> Scales:
        """The scales of a case, with the rotor mass it carries (``case.rotor.mass``)."""
        return cls.from_parts(case.bearing, case.gas, case.rotor.mass)

    def bearing_number(self, speed: float) -> float:
        """Λ = 6 μ ω R²/(p_a C²) at the speed ω (rad/s): the parameter of Eq. (4)."""
        pa, r, c, mu = self.ambient_pressure, self.radius, self.clearance, self.viscosity
        return 6.0 * mu * speed * r**2 / (pa * c**2)

    def compliance(self, stiffness: ArrayLike) -> NDArray[np.float64]:
        """c = p_a/(C k): the foil's deflection in units of C per unit gauge pressure
        P − 1, for a stiffness k in N/m³ (a number or per θ-row; docs/model.md §3)."""
        return self.ambient_pressure / (self.clearance * np.asarray(stiffness, float))

    def couette_shear(self, speed: float) -> float:
        """μ ω R/C, Pa: the Couette shear on the journal at the speed ω (rad/s) across
        the clearance; divided by H where the film is H = h/C (the drag torque)."""
        return self.viscosity * speed * self.radius / self.clearance

    @property
    def half_length(self) -> float:
        """L/(2R): the grid's half length in Z = z/R."""
        return self.length / (2.0 * self.radius)
