"""Film thickness of a case: journal position, preload shape and foil compliance on the grid.

docs/model.md §2-3: ``h(θ) = C + e_X cos θ + e_Y sin θ − r_p(θ) + w(θ)`` with
the foil deflection ``w = max(p_A, 0)/k(θ)``. Here the parts that do not
depend on the pressure are put on the Reynolds grid; the Reynolds solvers add
``w`` through the compliance ``c(θ) = p_a/(C k(θ))``, kept as its two springs in
series: the bump foil's ``p_a/(C k_b)`` and, under the stingers, the
actuator's share ``p_a/C · (1/k(θ) − 1/k_b)`` (the dynamic analyses damp the
bump alone, docs/model.md §3.5). A foil bearing's film
holds no sub-ambient pressure by default (top-foil lift-off: ``lift_off``,
docs/model.md §3); a rigid bearing, or a case with ``[foil] subambient =
"retained"``, keeps it.

The reading of the paper used throughout (docs/model.md §3): the film uses
r_p(θ) from the *base* preload, and the foil deflects by ``p_A/k(θ)`` with
``k = k_assy`` under the stingers, so the actuator's compliance is counted
exactly once; the reported piezoelectric preload is
``δ_PZT,n = δ_base,n − p_A(θ_n)/(k_p + 4k_sp)`` (Eq. 3b). The shimmed GFB has
the same r_p and ``k = k_b`` everywhere (rigid shims).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from foilbearing.case import Case
from foilbearing.reynolds import FilmGrid
from foilbearing.structure import preload_shape, stiffness_function

__all__ = ["FilmModel", "drag_torque", "film_model"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class FilmModel:
    """What the Reynolds solvers need of a case, on a grid (dimensionless unless stated).

    Attributes
    ----------
    grid
        The finite-volume grid (half bearing).
    preload
        r_p(θ_i)/C at the cell centres, shape (n_theta,).
    bump_compliance
        p_a/(C k_b) at the cell centres, shape (n_theta,); zeros for a rigid bearing.
    actuator_compliance
        The actuators' share p_a/C · (1/k(θ_i) − 1/k_b) (stinger and holder springs
        in series with the bump), shape (n_theta,); zeros without actuators.
    stiffness
        k(θ_i) in N/m³, shape (n_theta,), or None for a rigid bearing.
    preload_angles
        Angles (rad) of the actuators or shims, empty if none.
    base_preloads
        Base preload (actuators) or shim thickness at each angle, m.
    actuator_stiffness
        k_p + 4k_sp in N/m³ for a C-GFB, None otherwise (shims are rigid).
    lift_off
        Whether sub-ambient film pressure lifts the top foil off the bumps, so
        that the film holds none (P ≥ 1, a complementarity condition).
    """

    grid: FilmGrid
    preload: FloatArray
    bump_compliance: FloatArray
    actuator_compliance: FloatArray
    stiffness: FloatArray | None
    preload_angles: tuple[float, ...]
    base_preloads: tuple[float, ...]
    actuator_stiffness: float | None
    lift_off: bool = False

    @cached_property
    def compliance(self) -> FloatArray:
        """c(θ_i) = p_a/(C k(θ_i)) = bump + actuator compliance, shape (n_theta,)."""
        return self.bump_compliance + self.actuator_compliance

    def h_rigid(self, eps_x: float, eps_y: float) -> FloatArray:
        """Film thickness without foil deflection, H_r = 1 + ε_X cos θ + ε_Y sin θ − r_p/C.

        Returns
        -------
        Array of shape (n_theta, n_z) (uniform in z: the journal is aligned).
        """
        th = self.grid.theta
        h = 1.0 + eps_x * np.cos(th) + eps_y * np.sin(th) - self.preload
        return np.repeat(h[:, None], self.grid.n_z, axis=1)

    def at_angles(self, field: FloatArray, angles: tuple[float, ...]) -> FloatArray:
        """Periodic linear interpolation of a (n_theta,) cell field at ``angles`` (rad)."""
        th = self.grid.theta
        x = np.concatenate([th - 2 * np.pi, th, th + 2 * np.pi])
        y = np.concatenate([field, field, field])
        return np.interp(np.mod(angles, 2 * np.pi), x, y)


def film_model(case: Case, n_theta: int | None = None, n_z: int | None = None) -> FilmModel:
    """Build the film model of a case on its grid (or on ``n_theta`` × ``n_z``)."""
    grid = FilmGrid(
        n_theta=n_theta or case.grid.n_theta,
        n_z=n_z or case.grid.n_z,
        half_length=case.bearing.length / (2.0 * case.bearing.radius),
    )
    theta = grid.theta
    c = case.bearing.clearance
    angles: tuple[float, ...] = ()
    deltas: tuple[float, ...] = ()
    k_act = None
    if case.actuators is not None:
        angles = case.actuators.angles
        deltas = tuple(float(d) for d in case.actuators.base_preloads())
        k_act = case.actuators.stiffness
    elif case.shims is not None:
        angles, deltas = case.shims.angles, case.shims.thicknesses
    preload = preload_shape(theta, angles, deltas) / c if angles else np.zeros(grid.n_theta)
    stiffness = None
    c_bump = np.zeros(grid.n_theta)
    c_act = np.zeros(grid.n_theta)
    pa = case.gas.ambient_pressure
    if case.foil is not None:
        k_b = case.foil.bump_stiffness
        if case.actuators is not None:
            act = case.actuators
            k_assy = case.assembly_stiffness()
            assert k_assy is not None
            stiffness = stiffness_function(
                theta, k_b, k_assy, act.angles, act.stinger_arc, act.smoothness
            )
            # k ≤ k_b (springs in series); the clip only absorbs round-off. Written as the
            # total less the bump's: the lift-off reference orbit's cost (solve_ivp) is
            # sensitive to round-off in these (measured 12 s against 231 s on one test).
            c_act = np.maximum(pa / (c * stiffness) - pa / (c * k_b), 0.0)
        else:
            stiffness = np.full(grid.n_theta, k_b)
        c_bump = np.full(grid.n_theta, pa / (c * k_b))
    lift_off = case.foil is not None and case.foil.lift_off
    return FilmModel(grid, preload, c_bump, c_act, stiffness, angles, deltas, k_act, lift_off)


def drag_torque(case: Case, g: FilmGrid, P: FloatArray, H: FloatArray, omega: float) -> float:
    """Viscous torque on the journal, N·m (beyond the paper).

    Shear on the journal surface from the Couette-Poiseuille profile,
    τ = μ ω R/h + (h/(2R)) ∂p/∂θ, integrated over the full surface:
    T = R³ ∫∫ [μ ω R/(C H) + (C H p_a/(2R)) ∂P/∂θ] dθ dZ. For a concentric rigid
    journal this is Petroff's 2π μ ω R³ L / C.
    """
    mu, pa = case.gas.viscosity, case.gas.ambient_pressure
    r, c = case.bearing.radius, case.bearing.clearance
    dp = (np.roll(P, -1, axis=0) - np.roll(P, 1, axis=0)) / (2.0 * g.d_theta)
    integrand = mu * omega * r / (c * H) + c * H * pa / (2.0 * r) * dp
    return float(2.0 * r**3 * integrand.sum() * g.d_theta * g.d_z)
