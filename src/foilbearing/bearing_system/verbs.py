"""The bearing system built once from a case, and its three verbs.

One object holds what every analysis of one bearing needs: the case, its scales
(:class:`~foilbearing.bearing_system.scales.Scales`), and its film model
(:class:`~foilbearing.film.FilmModel`: the grid, the structure k(θ) and r_p(θ), and the
laws the case states, from :mod:`foilbearing.laws`). Its verbs are the three analyses,
which delegate to the existing solvers, so a verb and its function give the same numbers:

- :meth:`BearingSystem.equilibrium`: the static equilibrium under load (docs/model.md §2,
  :func:`foilbearing.analysis.equilibrium.solve_equilibrium`);
- :meth:`BearingSystem.coefficients` and :meth:`BearingSystem.linearise`: the film's
  stiffness and damping at whirl frequencies about it (docs/model.md §4,
  :func:`foilbearing.analysis.coefficients.force_coefficients`);
- :meth:`BearingSystem.transient`: the semi-discrete system the BDF steps (docs/model.md
  §5, :class:`foilbearing.reynolds.transient.TransientSystem`), which the orbit
  (:class:`foilbearing.orbit.system.OrbitSimulation`) builds through this verb.

The three share the film model and the scales, so the static, linear and transient
bearing are one bearing by construction (tests/test_bearing_system.py checks it).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from foilbearing.analysis.coefficients import ForceCoefficients, force_coefficients
from foilbearing.analysis.equilibrium import (
    EquilibriumOptions,
    StaticResult,
    film_at_position,
    solve_equilibrium,
)
from foilbearing.bearing_system.scales import Scales
from foilbearing.case import Case
from foilbearing.errors import InputError
from foilbearing.film import FilmModel, film_model
from foilbearing.laws import ActuatorReading, FoilDamping, LiftOff
from foilbearing.reynolds import FilmGrid
from foilbearing.reynolds.transient import TransientSystem
from foilbearing.units import QuantityLike

__all__ = ["BearingSystem"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class BearingSystem:
    """One bearing, built once from a case: its scales, its film model and three verbs.

    Build it with :meth:`from_case`. Everything is SI at the verbs' edges (speeds in
    rad/s or quantities such as ``"50 krpm"``, loads in N or ``"20 N"``).

    Attributes
    ----------
    case
        The bearing case.
    film
        Its film model on the grid (:func:`foilbearing.film.film_model`).
    scales
        Its scales: p_a, R, C, L, μ, σ, Λ per rad/s, the force scale p_a R² and the film
        force per unit rotor mass.
    """

    case: Case
    film: FilmModel
    scales: Scales

    @classmethod
    def from_case(
        cls, case: Case, *, n_theta: int | None = None, n_z: int | None = None
    ) -> BearingSystem:
        """The bearing system of a case, on its grid (or on ``n_theta`` × ``n_z``)."""
        return cls(case, film_model(case, n_theta, n_z), Scales.from_case(case))

    # ------------------------------------------------------------- what it holds
    @property
    def grid(self) -> FilmGrid:
        """The finite-volume grid of the half bearing."""
        return self.film.grid

    @property
    def stiffness(self) -> FloatArray | None:
        """The structural stiffness k(θ_i), N/m³, shape (n_theta,); None for a rigid bearing."""
        return self.film.stiffness

    @property
    def preload(self) -> FloatArray:
        """The preload shape r_p(θ_i)/C at the case's voltages (or shims), shape (n_theta,)."""
        return self.film.preload

    @property
    def lift_off(self) -> LiftOff | None:
        """The top-foil lift-off law (sharp or smoothed edge); None if the film keeps
        sub-ambient pressure (a rigid bearing, or ``[foil] subambient = "retained"``)."""
        return self.grid.lift_off if self.film.lift_off else None

    @property
    def foil_damping(self) -> FoilDamping:
        """The foil damping law (``Foil.damping_law``; no damping without a foil)."""
        return self.film.foil_damping

    @property
    def actuator(self) -> ActuatorReading:
        """The actuator reading (preload response × dynamics)."""
        return self.film.actuator

    def at(
        self, *, load: QuantityLike | None = None, voltages: ArrayLike | None = None
    ) -> BearingSystem:
        """The same bearing under another load (N, or ``"20 N"``) or at other actuator
        voltages (V, one for all or one each): the film model is rebuilt only for new
        voltages, which move the preload."""
        system = self
        if voltages is not None:
            case = self.case.with_voltages(voltages)
            n_theta, n_z = self.grid.n_theta, self.grid.n_z
            system = BearingSystem.from_case(case, n_theta=n_theta, n_z=n_z)
        if load is not None:
            system = replace(system, case=system.case.with_load(load))
        return system

    # ------------------------------------------------------------------ the verbs
    def equilibrium(
        self,
        speed: QuantityLike | None = None,
        load: QuantityLike | None = None,
        *,
        voltages: ArrayLike | None = None,
        start: tuple[float, float, FloatArray | None] | None = None,
        options: EquilibriumOptions | None = None,
    ) -> StaticResult:
        """The journal's static equilibrium at a speed under a load (load along +X).

        ``speed`` and ``load`` default to the case's; ``voltages`` (V) to the case's.
        The solver and its result are
        :func:`~foilbearing.analysis.equilibrium.solve_equilibrium`'s.
        """
        system = self.at(load=load, voltages=voltages)
        return solve_equilibrium(
            system.case, speed=speed, model=system.film, start=start, options=options
        )

    def film_at(
        self,
        eps_x: float,
        eps_y: float,
        speed: QuantityLike | None = None,
        *,
        options: EquilibriumOptions | None = None,
    ) -> StaticResult:
        """The film and its force with the journal held at (ε_X, ε_Y), in units of C
        (:func:`~foilbearing.analysis.equilibrium.film_at_position`)."""
        return film_at_position(
            self.case, eps_x, eps_y, speed=speed, model=self.film, options=options
        )

    def linearise(
        self,
        static: StaticResult,
        whirl_frequencies: QuantityLike | ArrayLike,
        *,
        loss_factor: float | None = None,
    ) -> ForceCoefficients:
        """The film's stiffness K (N/m) and damping C (N·s/m) about a static point of this
        bearing at whirl frequencies ω_e (rad/s or ``"100 Hz"``): K + jω_e C = −∂F/∂e
        (:func:`~foilbearing.analysis.coefficients.force_coefficients`)."""
        if static.model.grid.shape != self.grid.shape:
            raise InputError(
                f"static point on a {static.model.grid.shape} grid: this bearing system's "
                f"grid is {self.grid.shape}; solve it with this system's equilibrium"
            )
        return force_coefficients(static, whirl_frequencies, loss_factor=loss_factor)

    def coefficients(
        self,
        speed: QuantityLike | None,
        whirl_frequencies: QuantityLike | ArrayLike,
        *,
        load: QuantityLike | None = None,
        voltages: ArrayLike | None = None,
        loss_factor: float | None = None,
    ) -> ForceCoefficients:
        """K and C at whirl frequencies about the equilibrium at ``speed`` (and ``load``,
        ``voltages``): :meth:`equilibrium`, then :meth:`linearise`. Raises
        :class:`~foilbearing.errors.SolverError` if no equilibrium is found."""
        static = self.equilibrium(speed, load, voltages=voltages)
        return self.linearise(static, whirl_frequencies, loss_factor=loss_factor)

    def transient(self, mass: float | None = None) -> TransientSystem:
        """The semi-discrete film, foil and journal system the BDF steps (docs/model.md §5).

        ``mass`` (kg) is the rotor mass the film accelerates (default: the case's
        ``rotor.mass``). Held stingers do not yield to the film's motion (their
        compression is an input of the orbit); lobes that follow their stacks
        (``"lobe"`` and ``"compliant"``) carry their compression D_n(P) in the film.
        """
        scales = self.scales if mass is None else replace(self.scales, mass=mass)
        if scales.film_force_per_mass is None:
            raise InputError("transient: no rotor mass; give mass (kg) > 0")
        model = self.film
        lobes_move = model.lobe and model.actuator.lobes_move
        return TransientSystem(
            model.grid,
            sigma=scales.sigma,
            c_act=model.actuator.motion_compliance(model.actuator_compliance),
            c_bump=model.bump_compliance,
            loss_factor=model.foil_damping,
            film_force_scale=scales.film_force_per_mass,
            lift_off=model.lift_off,
            lobes=model.lobe_shapes if lobes_move else None,
            lobe_rows=model.actuator_rows,
            stack_compliance=model.stack_compliance,
        )
