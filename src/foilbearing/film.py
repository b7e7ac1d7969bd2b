"""Film thickness of a case: journal position, preload shape and foil compliance on the grid.

docs/model.md §2-3: ``h(θ) = C + e_X cos θ + e_Y sin θ − r_p(θ) + w(θ)`` with
the foil deflection ``w = max(p_A, 0)/k(θ)``. Here the parts that do not
depend on the pressure are put on the Reynolds grid; the Reynolds solvers add
``w`` through the compliance ``c(θ) = p_a/(C k(θ))`` (:meth:`Scales.compliance
<foilbearing.bearing_system.Scales.compliance>`, with the grid's half length L/(2R)), kept as its two springs in
series: the bump foil's ``p_a/(C k_b)`` and, under the stingers, the
actuator's share ``p_a/C · (1/k(θ) − 1/k_b)`` (the dynamic analyses damp the
bump alone, docs/model.md §3.5). A foil bearing's film
holds no sub-ambient pressure by default (top-foil lift-off: ``lift_off``,
docs/model.md §3); a rigid bearing, or a case with ``[foil] subambient =
"retained"``, keeps it.

How the stack's compliance enters the film is a stated choice of the case,
``[actuators] preload_response`` (docs/model.md §3.8), with the compliance
counted exactly once in either:

- ``"local"`` (the default): the film uses r_p(θ) from the *base* preload, and
  the foil deflects by ``p_A/k(θ)`` with ``k = k_assy`` under the stingers: the
  stack's compression is a pocket under the stinger (``actuator_compliance``).
- ``"lobe"``: the stinger lifts the whole lobe, so its compression lowers the
  whole lobe, ``r_p(θ) = Σ_n δ_PZT,n/2 (cos 3(θ − θ_n) + 1)`` (Eqs. 3b, 5, 6),
  with ``δ_PZT,n = δ_base,n − p_A(θ_n)/(k_p + 4k_sp)`` and the bump alone under
  it: ``H`` gains ``Σ_n lobe_n(θ) D_n`` with the compression
  ``D_n = p_a max(q(θ_n), 0)/(C (k_p + 4k_sp))`` (:meth:`FilmModel.stack_compression`).

Either way the reported piezoelectric preload is ``δ_PZT,n = δ_base,n −
p_A(θ_n)/(k_p + 4k_sp)`` (Eq. 3b). The shimmed GFB has the base r_p and
``k = k_b`` everywhere (rigid shims). ``[actuators] dynamics`` says whether the
compliance acts during the motion (``"compliant"``) or the stinger keeps its
quasi-static position (``"held"``); it matters to the dynamic analyses only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.bearing_system.scales import Scales
from foilbearing.case import Case
from foilbearing.laws.actuator import ActuatorReading
from foilbearing.laws.foil_damping import FoilDamping, NoFoilDamping
from foilbearing.reynolds import FilmGrid, NewtonOptions, SteadyFilm, Workspace
from foilbearing.reynolds.assembly import coupled_system
from foilbearing.reynolds.perturbed import pressure_response
from foilbearing.reynolds.steady import solve_steady
from foilbearing.structure import preload_shape, stiffness_function

__all__ = ["FilmModel", "drag_torque", "film_model", "interpolation_rows"]

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
    actuator
        The case's reading of the actuator in the film (docs/model.md §3.8), a
        :class:`foilbearing.laws.ActuatorReading` (``preload_response`` ``"local"`` or
        ``"lobe"``, ``dynamics`` ``"compliant"`` or ``"held"``).
    lobe_shapes
        The unit preload lobe of each actuator, (cos 3(θ_i − θ_n) + 1)/2 on its
        sector, shape (n_act, n_theta); empty without actuators.
    actuator_rows
        Periodic linear interpolation at each actuator's angle, shape (n_act, n_theta):
        ``actuator_rows @ f`` is a cell field f at θ_n.
    stack_compliance
        p_a/(C (k_p + 4k_sp)) under ``"lobe"`` (the compression per unit gauge
        pressure, in C per p_a); 0 otherwise.
    foil_damping
        The foil damping law (:mod:`foilbearing.laws.foil_damping`): the case's
        ``Foil.damping_law``; :class:`~foilbearing.laws.NoFoilDamping` without a foil.
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
    actuator: ActuatorReading = field(default_factory=ActuatorReading)
    lobe_shapes: FloatArray | None = None
    actuator_rows: FloatArray | None = None
    stack_compliance: float = 0.0
    foil_damping: FoilDamping = field(default_factory=NoFoilDamping)

    @cached_property
    def compliance(self) -> FloatArray:
        """c(θ_i) = p_a/(C k(θ_i)) = bump + actuator compliance, shape (n_theta,)."""
        return self.bump_compliance + self.actuator_compliance

    @property
    def preload_response(self) -> str:
        """``"local"`` or ``"lobe"``: :attr:`actuator`'s preload response."""
        return self.actuator.preload_response

    @property
    def actuator_dynamics(self) -> str:
        """``"compliant"`` or ``"held"``: :attr:`actuator`'s dynamics."""
        return self.actuator.dynamics

    @property
    def lobe(self) -> bool:
        """Whether the stack's compression lowers the whole lobe (``preload_response = "lobe"``)."""
        return self.stack_compliance > 0.0

    def stack_compression(self, P: FloatArray) -> FloatArray:
        """D_n = p_a max(q(θ_n), 0)/(C (k_p + 4k_sp)) of each actuator under ``"lobe"``, in C.

        ``P`` is (n_theta, n_z) or flat; zeros (n_act,) under ``"local"`` or without
        actuators. Sub-ambient pressure does not pull the foil, so not the stinger.
        """
        if not self.lobe or self.actuator_rows is None:
            return np.zeros(len(self.preload_angles))
        q = self.grid.gauge_mean(np.reshape(P, self.grid.shape))
        return self.stack_compliance * np.maximum(self.actuator_rows @ q, 0.0)

    def h_rigid_loaded(self, eps_x: float, eps_y: float, compression: FloatArray) -> FloatArray:
        """:meth:`h_rigid` with the lobes lowered by ``compression`` D_n (units of C), (n_theta, n_z)."""
        h = self.h_rigid(eps_x, eps_y)
        if self.lobe and self.lobe_shapes is not None:
            h += (np.asarray(compression, float) @ self.lobe_shapes)[:, None]
        return h

    def film(self, P: FloatArray, eps_x: float, eps_y: float) -> FloatArray:
        """The film H = h/C of pressures P (n_theta, n_z) at a journal position: the rigid
        film, the lobes lowered by the stacks' compression (``"lobe"``), and the foil's
        deflection c(θ) max(q, 0)."""
        Pg = np.reshape(P, self.grid.shape)
        h = self.h_rigid_loaded(eps_x, eps_y, self.stack_compression(Pg))
        return h + (self.compliance * np.maximum(self.grid.gauge_mean(Pg), 0.0))[:, None]

    def h_rigid(self, eps_x: float, eps_y: float) -> FloatArray:
        """Film thickness without foil deflection, H_r = 1 + ε_X cos θ + ε_Y sin θ − r_p/C.

        Returns
        -------
        Array of shape (n_theta, n_z) (uniform in z: the journal is aligned).
        """
        th = self.grid.theta
        h = 1.0 + eps_x * np.cos(th) + eps_y * np.sin(th) - self.preload
        return np.repeat(h[:, None], self.grid.n_z, axis=1)

    # ----------------------------------------------- the Reynolds solvers on this film
    # The solvers keep their low-level signatures (grid, film, compliance, Λ, lift-off);
    # the analyses call them through these, so those arguments are unpacked here alone.
    def steady_film(
        self,
        h_rigid: FloatArray,
        lam: float,
        p0: FloatArray | None = None,
        *,
        options: NewtonOptions | None = None,
        workspace: Workspace | None = None,
    ) -> SteadyFilm:
        """The steady pressure of Eq. (4) on this film at the bearing number Λ, with the foil
        deflecting by :attr:`compliance` and the lift-off law of the case
        (:func:`foilbearing.reynolds.solve_steady`).

        ``h_rigid`` is the film without foil deflection, shape (n_theta, n_z), in units of
        C; ``p0`` the starting pressure P = p/p_a (default P = 1).
        """
        return solve_steady(
            self.grid,
            h_rigid,
            self.compliance,
            lam,
            p0,
            options=options,
            workspace=workspace,
            lift_off=self.lift_off,
        )

    def steady_residual(
        self, P: FloatArray, h_rigid: FloatArray, lam: float, workspace: Workspace | None = None
    ) -> tuple[FloatArray, sp.csr_matrix, sp.csr_matrix]:
        """The residual R of the steady Eq. (4) at pressures P (flat, n_theta·n_z) and its
        Jacobians ∂R/∂P and ∂R/∂H on this film (:func:`foilbearing.reynolds.coupled_system`)."""
        return coupled_system(
            P, self.grid, h_rigid, self.compliance, lam, workspace, lift_off=self.lift_off
        )

    def perturbed_pressure(
        self,
        P: FloatArray,
        H: FloatArray,
        lam: float,
        nu: float,
        compliance: NDArray[np.complex128] | FloatArray,
        dh: FloatArray,
        workspace: Workspace | None = None,
    ) -> NDArray[np.complex128]:
        """The complex pressure response ∂P/∂e to the film perturbations ``dh`` (columns,
        (n_theta·n_z, n)) at the frequency ratio ν = ω_e/ω, about the steady P and H with
        the dynamic foil compliance ``compliance`` (docs/model.md §4,
        :func:`foilbearing.reynolds.perturbed.pressure_response`)."""
        return pressure_response(
            self.grid, P, H, lam, nu, compliance, dh, workspace, lift_off=self.lift_off
        )

    def at_angles(self, field: FloatArray, angles: tuple[float, ...]) -> FloatArray:
        """Periodic linear interpolation of a (n_theta,) cell field at ``angles`` (rad)."""
        th = self.grid.theta
        x = np.concatenate([th - 2 * np.pi, th, th + 2 * np.pi])
        y = np.concatenate([field, field, field])
        return np.interp(np.mod(angles, 2 * np.pi), x, y)


def interpolation_rows(theta: FloatArray, angles: tuple[float, ...]) -> FloatArray:
    """Periodic linear interpolation of a cell field at ``angles`` as rows, (n_angles, n_theta).

    ``theta`` are the uniform cell centres; row n holds the two weights of the cells
    on either side of angles[n] (the operator of :meth:`FilmModel.at_angles`).
    """
    n = theta.size
    d = 2.0 * np.pi / n
    rows = np.zeros((len(angles), n))
    for k, a in enumerate(angles):
        x = (np.mod(a, 2.0 * np.pi) - theta[0]) / d
        i = int(np.floor(x))
        f = x - i
        rows[k, i % n] += 1.0 - f
        rows[k, (i + 1) % n] += f
    return rows


def film_model(case: Case, n_theta: int | None = None, n_z: int | None = None) -> FilmModel:
    """Build the film model of a case on its grid (or on ``n_theta`` × ``n_z``)."""
    scales = Scales.from_parts(case.bearing, case.gas)
    grid = FilmGrid(
        n_theta=n_theta or case.grid.n_theta,
        n_z=n_z or case.grid.n_z,
        half_length=scales.half_length,
        axial_order=case.grid.axial_order,
        lift_off_smoothing=case.grid.lift_off_smoothing,
    )
    theta = grid.theta
    angles: tuple[float, ...] = ()
    deltas: tuple[float, ...] = ()
    k_act = None
    if case.actuators is not None:
        angles = case.actuators.angles
        deltas = tuple(float(d) for d in case.actuators.base_preloads())
        k_act = case.actuators.stiffness
    elif case.shims is not None:
        angles, deltas = case.shims.angles, case.shims.thicknesses
    preload = (
        preload_shape(theta, angles, deltas) / scales.clearance
        if angles
        else np.zeros(grid.n_theta)
    )
    stiffness = None
    c_bump = np.zeros(grid.n_theta)
    c_act = np.zeros(grid.n_theta)
    reading = ActuatorReading()
    lobes = rows = None
    c_stack = 0.0
    if case.actuators is not None:
        act = case.actuators
        reading = act.reading
        n_act = len(act.angles)
        lobes = np.array([preload_shape(theta, act.angles, np.eye(n_act)[n]) for n in range(n_act)])
        rows = interpolation_rows(theta, act.angles)
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
            # Under "lobe" the compliance lowers the lobe instead (the stack's c_s).
            c_act = reading.static_compliance(
                np.maximum(scales.compliance(stiffness) - scales.compliance(k_b), 0.0)
            )
            c_stack = reading.stack_compliance(
                scales.ambient_pressure, scales.clearance, act.stiffness
            )
        else:
            stiffness = np.full(grid.n_theta, k_b)
        c_bump = np.full(grid.n_theta, scales.compliance(k_b))
    lift_off = case.foil is not None and case.foil.lift_off
    return FilmModel(
        grid,
        preload,
        c_bump,
        c_act,
        stiffness,
        angles,
        deltas,
        k_act,
        lift_off,
        actuator=reading,
        lobe_shapes=lobes,
        actuator_rows=rows,
        stack_compliance=c_stack,
        foil_damping=NoFoilDamping() if case.foil is None else case.foil.damping_law,
    )


def drag_torque(
    case: Case,
    g: FilmGrid,
    P: FloatArray,
    H: FloatArray,
    omega: float,
    scales: Scales | None = None,
) -> float:
    """Viscous torque on the journal, N·m (beyond the paper).

    Shear on the journal surface from the Couette-Poiseuille profile,
    τ = μ ω R/h + (h/(2R)) ∂p/∂θ, integrated over the full surface:
    T = R³ ∫∫ [μ ω R/(C H) + (C H p_a/(2R)) ∂P/∂θ] dθ dZ, its scales (μ ω R/C,
    p_a C/(2R), R³) taken from :class:`~foilbearing.bearing_system.Scales` (the case's,
    or ``scales`` where the caller holds them: an orbit evaluates the torque every
    millisecond). For a concentric rigid journal this is Petroff's 2π μ ω R³ L / C.
    """
    if scales is None:
        scales = Scales.from_parts(case.bearing, case.gas)
    # ∂P/∂θ by central differences, periodic in θ (the rows shifted by one each way).
    dp = np.empty_like(P)
    np.subtract(P[2:], P[:-2], out=dp[1:-1])
    np.subtract(P[1:2], P[-1:], out=dp[:1])
    np.subtract(P[:1], P[-2:-1], out=dp[-1:])
    dp /= 2.0 * g.d_theta
    couette = scales.couette_shear(omega) / H
    poiseuille = scales.pressure_shear * H * dp
    if g.axial_order == 2:
        return float(2.0 * scales.torque * (couette + poiseuille).sum() * g.d_theta * g.d_z)
    # Fourth order: ∂P/∂θ vanishes on the end face, where the axial-mean weights apply.
    axial = couette.sum() * g.d_z + g.half_length * float(np.sum(poiseuille @ g.axial.mean_w))
    return float(2.0 * scales.torque * axial * g.d_theta)
