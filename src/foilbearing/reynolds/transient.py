"""The semi-discrete unsteady system: film, foil and journal in physical time.

State ``y = [P (n), U (n_theta), ε_X, ε_Y, v_X, v_Y]`` with P = p/p_a on the
cells (n = n_theta·n_z), U = u_b/C the bump compression (a viscoelastic state)
on the θ-rows, ε the journal position in units of C and v = dε/dt (1/s). In
the implicit form used by every stepper, ``d Q(y)/dt = f(y, t)`` with

    Q = [P·H, U, ε_X, ε_Y, v_X, v_Y],
    f = [R(P, H; Λ(t))/(A σ),  (ω/γ)(c_b q − U),  v_X, v_Y,  (F + F_ext)/(m C)],

where R is the steady finite-volume residual (so steady states are exactly the
static solutions), A = ΔθΔZ, σ = 12 μ R²/(p_a C²) (unsteady term of Eq. 4 in
physical time: 2Λ ∂/∂τ = σ ∂/∂t), q = max(p̄, 0) the engaged axial-mean gauge
pressure, and the film (docs/model.md §2-3)

    H = 1 + ε_X cos θ + ε_Y sin θ − r_p(θ, t)/C + U + c_a q + Σ_n D_n lobe_n(θ).

The bump is a spring k_b in parallel with a viscous damper c_b = γ k_b/ω (the
loss factor's equivalent at the running speed, docs/model.md §3) in series
with the massless elastic actuator of compliance c_a = φ(θ) p_a/(C k_act) under
the stingers. With γ = 0 the bump is purely elastic and joins c_a. The dynamic
coefficients use the same bump, ``k_b (1 + jγ ω_e/ω)``
(:mod:`foilbearing.analysis.coefficients`).

Top-foil lift-off (``lift_off``, docs/model.md §3): the film holds no
sub-ambient pressure. Each pressure cell's BDF equation G = 0 becomes the
complementarity condition of the static solver
(:mod:`foilbearing.reynolds.steady`),

    P − 1 >= 0,   G >= 0,   (P − 1)·G = 0,

i.e. ``min(d (P − 1), G) = 0`` with d the diagonal of the cell's Newton row.
A factorisation puts each cell on the branch that this min selects at its
state (a held cell gets the Newton row ``d e_k``); the modified Newton
iteration then solves with the branches fixed, which keeps it smooth, and
when it has converged moves the cells that violate their branch (a held cell
with a net inflow, a free one below ambient) to the other branch and goes on
with the same factor (:func:`~foilbearing.reynolds._kernels.switch_branches`).
The branches are the ``lift_state`` of the factor: ``d`` held, ``−d`` free,
0 without lift-off.

On a grid with a smoothed lifted-off edge (``FilmGrid.lift_off_smoothing`` > 0) no cell
has a branch: each cell's equation is ``(s/2)(x + G/s − √((x − G/s)² + 4δ²Λ)) = 0``
(x = P − 1, s = d_ref/(Aσ)), whose rows are the BDF rows times α plus ``(1 − α) s`` on
the diagonal; ``lift_off`` is then False (no branches) and ``lift_delta`` > 0. Its source
form ``dQ/dt = f + s δ²Λ/(P − 1)`` (:meth:`TransientSystem.lift_source`) is what
:meth:`TransientSystem.rhs` gives the ``solve_ivp`` references (docs/lift-off.md, "The
smoothed edge").

The system's matrices in SciPy sparse form (the Newton matrix of :meth:`TransientSystem.jacobian`,
the storage Jacobian and its operator), which the linearisations use and the compiled factor is
checked against, are built in :mod:`foilbearing.reynolds.transient_matrices`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.laws.foil_damping import FoilDamping, foil_damping_law
from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds import fallback
from foilbearing.reynolds import transient_matrices as matrices
from foilbearing.reynolds.assembly import Workspace
from foilbearing.reynolds.blocksolve import BlockCyclicLU, factor_coupled
from foilbearing.reynolds.grid import FilmGrid
from foilbearing.reynolds.transient_factor import TransientFactor

__all__ = [
    "NEWTON_CONVERGED",
    "NEWTON_REFRESH",
    "BdfHistory",
    "Inputs",
    "TransientFactor",
    "TransientSystem",
    "bdf_setup",
]

#: Newton outcomes of :meth:`TransientFactor.newton_solve` (see the kernel).
NEWTON_CONVERGED, NEWTON_REFRESH = kern.NEWTON_CONVERGED, kern.NEWTON_REFRESH
#: Variable-step BDF coefficient, history, predictor and weights (compiled).
bdf_setup = kern.bdf_setup
#: The accepted states ``bdf_setup`` builds a step on.
BdfHistory = kern.BdfHistory

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Inputs:
    """Time-dependent inputs at one instant.

    Attributes
    ----------
    lam
        Bearing number Λ(t).
    omega
        Rotor speed ω(t), rad/s.
    preload
        r_p(θ_i, t)/C, shape (n_theta,).
    force
        External force on the journal in units of m·C (load plus imbalance
        divided by m C), 1/s², shape (2,).
    """

    lam: float
    omega: float
    preload: FloatArray
    force: FloatArray


class TransientSystem:
    """Residual pieces and Jacobian of the semi-discrete system (arrays in, arrays out).

    Parameters
    ----------
    grid
        Finite-volume grid.
    sigma
        σ = 12 μ R²/(p_a C²), s.
    c_act
        Actuator (elastic, in series) compliance per θ-row, p_a/(C k), shape (n_theta,).
    c_bump
        Bump compliance p_a/(C k_b) per θ-row (zeros: rigid surface).
    loss_factor
        The foil damping law (:mod:`foilbearing.laws.foil_damping`), or the loss factor
        γ of a :class:`~foilbearing.laws.ViscousBump`; a law without a rate (γ = 0,
        :class:`~foilbearing.laws.NoFoilDamping`) makes the bump purely elastic (no U dynamics).
    film_force_scale
        p_a R²/(m C): film force per unit Σ w(P − 1) as an acceleration of ε, 1/s².
    lift_off
        Top-foil lift-off: no sub-ambient film pressure (module docstring).
    lobes
        Unit preload lobes of the actuators whose compression lowers their whole lobe
        during the motion, shape (n_lobe, n_theta); None or empty: no such lobes.
    lobe_rows
        Interpolation at those actuators' angles, shape (n_lobe, n_theta).
    stack_compliance
        c_s = p_a/(C (k_p + 4k_sp)) of those stacks, in C per unit P.
    """

    def __init__(
        self,
        grid: FilmGrid,
        sigma: float,
        c_act: FloatArray,
        c_bump: FloatArray,
        loss_factor: FoilDamping | float,
        film_force_scale: float,
        lift_off: bool = False,
        lobes: FloatArray | None = None,
        lobe_rows: FloatArray | None = None,
        stack_compliance: float = 0.0,
    ) -> None:
        self.grid = grid
        self.n = grid.size
        self.nt = grid.n_theta
        self.sigma = sigma
        self.area = grid.d_theta * grid.d_z
        #: The foil damping law: its rate drives the bump state U.
        self.foil_damping = foil_damping_law(loss_factor)
        self.gamma = self.foil_damping.loss_factor
        #: δ of the smoothed lift-off law (0: none); with it no cell has a branch.
        self.lift_delta = grid.lift_off_delta if lift_off else 0.0
        #: s = d_ref/(Aσ): G (1/s) per unit of the pressure it stands for.
        self.smooth_scale = grid.lift_off_scale / (self.area * sigma)
        #: The sharp law's branches (lift-off without a smoothed edge).
        self.lift_off = bool(lift_off) and self.lift_delta == 0.0
        self.dynamic_bump = bool(self.foil_damping.dynamic and np.any(c_bump > 0.0))
        self.c_act = np.asarray(c_act, float) + (0.0 if self.dynamic_bump else np.asarray(c_bump))
        self.c_bump = np.asarray(c_bump, float) if self.dynamic_bump else np.zeros(self.nt)
        self.cos_t = np.cos(grid.theta)
        self.sin_t = np.sin(grid.theta)
        w_x, w_y = grid.force_weights()
        self.w = np.vstack([w_x.ravel(), w_y.ravel()])
        self.force_scale = film_force_scale
        self.size = self.n + self.nt + 4
        if lobes is None or len(lobes) == 0:
            lobes = lobe_rows = np.zeros((0, self.nt))
        assert lobe_rows is not None
        self.lobes = np.ascontiguousarray(lobes, dtype=float)
        self.lobe_rows = np.ascontiguousarray(lobe_rows, dtype=float)
        self.n_lobe = self.lobes.shape[0]
        self.c_stack = float(stack_compliance) if self.n_lobe else 0.0
        # ∂D_n/∂P per unit gain: the interpolation at the stinger of the θ-rows' mean, (n_lobe, n)
        self.lobe_mean = grid.mean_rows(self.lobe_rows)
        self.ws = Workspace(grid)
        self.expand = sp.kron(sp.eye(self.nt), np.ones((grid.n_z, 1)), format="csr")
        self.mean = sp.kron(sp.eye(self.nt), grid.axial.mean_w[None, :], format="csr")
        self._axial = tuple(grid.axial)
        self._res = np.empty(grid.shape)
        self._H = np.empty(grid.shape)
        self._slack = np.empty(self.n)
        self._work = np.empty((self.n, 1))
        self.jh_rows = self.ws.indices // grid.n_z  # θ-row of each column of dR/dH
        # ∂H/∂ε per cell (n, 2) and the film force per unit P (2, n), for factorize
        self.dh_de = np.column_stack(
            [np.repeat(self.cos_t, grid.n_z), np.repeat(self.sin_t, grid.n_z)]
        )
        self.s_vp = self.force_scale * self.w
        self.diag_slots = self.ws.diag_slots
        self.c_indptr, self.c_indices = kern.coupled_pattern(grid.n_theta, grid.n_z)
        self._jc = np.empty(self.c_indices.size)  # sizes of the factorisation's buffers
        self._jp = np.empty(self.ws.jp.size)
        #: The bearing on its grid and the film Jacobians' sparsity, as the kernels take them.
        self.constants = kern.FilmConstants(
            self.cos_t,
            self.sin_t,
            self.c_act,
            self.c_bump,
            self.w,
            self.force_scale,
            self.area * self.sigma,
            grid.d_theta,
            grid.d_z,
            grid.n_z,
            self.lobes,
            self.lobe_rows,
            self.c_stack,
            tuple(grid.axial),
            self.lift_delta,
            self.smooth_scale,
        )
        self.pattern = kern.StencilPattern(self.diag_slots, self.jh_rows, self.ws.indptr)
        # ... as the plain tuples the kernels take (kernels/groups.py says why).
        self.kernel_groups = (tuple(self.constants), tuple(self.pattern))

    def step_inputs(self, inputs: Inputs, c0: float, hist: FloatArray) -> kern.StepInputs:
        """The BDF step (c0, history) and the inputs at its new time, grouped for the kernels."""
        return kern.StepInputs(
            c0, hist, inputs.lam, self.rate(inputs), inputs.preload, inputs.force
        )

    # ----------------------------------------------------------------- pieces
    def split(self, y: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Views (P (n_theta, n_z), U, ε (2,), v (2,)) of a state vector."""
        n, nt = self.n, self.nt
        return y[:n].reshape(self.grid.shape), y[n : n + nt], y[n + nt : n + nt + 2], y[-2:]

    def film(self, y: FloatArray, preload: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Film H (n_theta, n_z) and engaged mean gauge pressure q (n_theta,)."""
        P, U, eps, _ = self.split(y)
        q = np.maximum(self.grid.gauge_mean(P), 0.0)
        row = 1.0 + eps[0] * self.cos_t + eps[1] * self.sin_t - preload + U + self.c_act * q
        if self.n_lobe:
            row = row + self.c_stack * np.maximum(self._stinger_pressure(P), 0.0) @ self.lobes
        return np.repeat(row[:, None], self.grid.n_z, axis=1), q

    def _stinger_pressure(self, P: FloatArray) -> FloatArray:
        """q(θ_n): the mean gauge pressure at the stingers of the lobes that follow their
        stacks, whose compression is D_n = c_s max(q(θ_n), 0) in C (n_lobe,)."""
        return self.lobe_rows @ self.grid.gauge_mean(np.reshape(P, self.grid.shape))

    def lobe_gain(self, P: FloatArray) -> FloatArray:
        """∂D_n/∂q(θ_n): c_s where the stack is loaded, else 0 (n_lobe,)."""
        return np.where(self._stinger_pressure(P) > 0.0, self.c_stack, 0.0)

    def storage(self, y: FloatArray, inputs: Inputs) -> FloatArray:
        """Q(y): the quantities whose time derivative the system states."""
        P, U, eps, v = self.split(y)
        H, _ = self.film(y, inputs.preload)
        return np.concatenate([(P * H).ravel(), U, eps, v])

    def lift_source(self, P: FloatArray, lam: float) -> FloatArray:
        """The smoothed lift-off law as the flow the lifting foil supplies, ``s δ²Λ/(P − 1)`` (1/s).

        ``c0 Q + hist − f = G`` with ``(P − 1)·G/s = δ²Λ`` (Λ = ``lam``) is the BDF step of
        ``dQ/dt = f + s δ²Λ/(P − 1)``: the form :meth:`rhs` gives the ``solve_ivp`` reference
        (:mod:`foilbearing.orbit.reference`), independent of the compiled rows. Infinite
        at or below ambient, which the smoothed film never reaches.
        """
        gauge = np.asarray(P, dtype=np.float64) - 1.0
        with np.errstate(divide="ignore"):
            width = self.grid.lift_off_width(lam)
            return np.where(gauge > 0.0, self.smooth_scale * width**2 / gauge, np.inf)

    def rhs(self, y: FloatArray, inputs: Inputs) -> FloatArray:
        """f(y, t): right-hand side of dQ/dt = f."""
        P, U, _eps, v = self.split(y)
        H, q = self.film(y, inputs.preload)
        g = self.grid
        kern.residual(
            np.ascontiguousarray(P), H, inputs.lam, g.d_theta, g.d_z, tuple(g.axial), self._res
        )
        f_p = self._res.ravel() / (self.area * self.sigma)
        if self.lift_delta > 0.0:
            # The smoothed law as a source: the lifting foil supplies s δ²Λ/(P − 1), 1/s.
            f_p = f_p + self.lift_source(P.ravel(), inputs.lam)
        if self.dynamic_bump:
            f_u = self.rate(inputs) * (self.c_bump * q - U)
        else:
            f_u = np.zeros(self.nt)
        accel = self.force_scale * (self.w @ (P.ravel() - 1.0)) + inputs.force
        return np.concatenate([f_p, f_u, v, accel])

    def newton_residual(
        self,
        y: FloatArray,
        inputs: Inputs,
        c0: float,
        hist: FloatArray,
        out: FloatArray | None = None,
        lift_state: FloatArray | None = None,
    ) -> tuple[FloatArray, float]:
        """G = c0·Q(y) + hist − f(y) (the BDF equations) and the minimum film, in one pass.

        Compiled (:func:`~foilbearing.reynolds._kernels.transient_residual`);
        :func:`~foilbearing.reynolds.fallback.newton_residual` is its NumPy form.

        Parameters
        ----------
        y : ndarray, shape (size,)
            State (C-contiguous float64).
        inputs : Inputs
            Inputs at the new time.
        c0 : float
            BDF leading coefficient α₀/Δt, 1/s.
        hist : ndarray, shape (size,)
            History part of the BDF equations.
        out : ndarray, shape (size,), optional
            Buffer for G (a new array if None).
        lift_state : ndarray, shape (n,), optional
            Lift-off branch of each cell (a factor's, ``d`` held, ``−d`` free);
            default :meth:`lift_state` at y (zeros without lift-off).

        Returns
        -------
        G : ndarray, shape (size,)
            ``out`` filled.
        h_min : float
            Minimum film h/C of y.
        """
        if out is None:
            out = np.empty(self.size)
        if lift_state is None:
            lift_state = self.lift_state(y, inputs, c0, hist)
        h_min = kern.transient_residual(
            y,
            tuple(self.step_inputs(inputs, c0, hist)),
            self.kernel_groups[0],
            lift_state,
            self._H,
            self._res,
            out,
            self._slack,
        )
        return out, float(h_min)

    def lift_scale(self, y: FloatArray, inputs: Inputs, c0: float) -> FloatArray:
        """d of each cell's lift-off condition at y: |diagonal of its Newton row| (n,), 1/s."""
        P, _U, _eps, _v = self.split(y)
        H, _q = self.film(y, inputs.preload)
        g = self.grid
        jp = np.empty(self.ws.jp.size)
        kern.jacobian_P(np.ascontiguousarray(P), H, inputs.lam, g.d_theta, g.d_z, self._axial, jp)
        d = np.abs(c0 * H.ravel() - jp[self.diag_slots] / (self.area * self.sigma))
        return np.where(d > 0.0, d, 1.0)

    def lift_state(self, y: FloatArray, inputs: Inputs, c0: float, hist: FloatArray) -> FloatArray:
        """Lift-off branches at y, as a factorisation decides them (n,).

        ``d`` where ``d (P − 1) < G`` (held at ambient), ``−d`` elsewhere; zeros
        without lift-off. Twin of the decision in
        :func:`~foilbearing.reynolds._kernels.transient_jacobian`.
        """
        if not self.lift_off:
            return np.zeros(self.n)
        d = self.lift_scale(y, inputs, c0)
        free = -d
        g_p = fallback.newton_residual(self, y, inputs, c0, hist, free)[0][: self.n]
        P = self.split(y)[0].ravel()
        return np.where(d * (P - 1.0) < g_p, d, free)

    def storage_min_film(
        self, y: FloatArray, preload: FloatArray, out: FloatArray | None = None
    ) -> tuple[FloatArray, float]:
        """Q(y) and the smallest film h/C, in one pass.

        Compiled (:func:`~foilbearing.reynolds._kernels.transient_storage`);
        :meth:`storage` and :meth:`min_film` are its NumPy twins.
        """
        if out is None:
            out = np.empty(self.size)
        h_min = kern.transient_storage(y, preload, self.kernel_groups[0], out)
        return out, float(h_min)

    def rate(self, inputs: Inputs) -> float:
        """The foil damping law's rate at the running speed (ω/γ of the viscoelastic bump),
        1/s (0 for a purely elastic bump)."""
        return self.foil_damping.rate(inputs.omega) if self.dynamic_bump else 0.0

    def factorize(
        self,
        y: FloatArray,
        inputs: Inputs,
        c0: float,
        hist: FloatArray,
        branches: FloatArray | None = None,
    ) -> TransientFactor:
        """Factorise the Newton matrix of :meth:`jacobian` by block elimination.

        The bump states U (diagonal rows) and the journal (ε, v: four unknowns)
        are eliminated, leaving the pressures with the foil-coupled pattern of
        the static solver (one sparse LU) plus a rank-2 Woodbury correction for
        the journal's film force. :meth:`TransientFactor.solve` equals a solve
        with :meth:`jacobian` (tested). The blocks come from one compiled call
        (:func:`~foilbearing.reynolds._kernels.transient_jacobian`, twin
        :func:`~foilbearing.testing.twins.jacobian_blocks_py`), the border solve
        and the 2×2 Woodbury inverse from another
        (:func:`~foilbearing.reynolds._kernels.transient_border`, twin
        :func:`~foilbearing.reynolds.fallback.border`, also the path of the
        SuperLU fallback). ``hist`` (the BDF history) decides which cells lift-off
        holds at ambient, unless ``branches`` (a factor's ``lift_state``, e.g. the
        last step's) gives them.
        """
        g = self.grid
        n = self.n
        step = self.step_inputs(inputs, c0, hist)
        # Buffers of its own: the factor keeps jh, a_pe, active and the matrix data.
        blocks = kern.JacobianBlocks(
            film=np.empty(g.shape),
            jp=np.empty(self._jp.size),
            jh=np.empty(self._jp.size),
            active=np.empty(self.nt),
            jc=np.empty(self._jc.size),
            a_pe=np.empty((n, 2)),
            lift_state=np.zeros(n) if branches is None else branches.copy(),
            a_pl=np.empty((n, self.n_lobe)),
            lobe_gain=np.empty(self.n_lobe),
        )
        kern.transient_jacobian(
            y, tuple(step), *self.kernel_groups, self.lift_off, branches is None, tuple(blocks)
        )
        jc, a_pe = blocks.jc, blocks.a_pe
        lu = factor_coupled(jc, self.c_indices, self.c_indptr, g.n_theta, g.n_z)
        # The compiled solves need the block cyclic factors (not the SuperLU fallback).
        fac = lu._fac if isinstance(lu, BlockCyclicLU) else None
        lobe = self.lobe_border(lu, blocks.a_pl, blocks.lobe_gain)
        if fac is not None:
            y_border = np.empty((n, 2))
            small_inv = np.empty((2, 2))
            kern.transient_border(fac, a_pe, self.s_vp, c0, lobe, y_border, small_inv)
        else:
            y_border, small_inv = fallback.border(self, lu, a_pe, c0, lobe)
        arrays = kern.FactorArrays(
            fac,  # type: ignore[arg-type]  # None for the fallback, which is not compiled
            blocks.jh,
            a_pe,
            self.s_vp,
            y_border,
            small_inv,
            c0,
            step.rate,
            blocks.active,
            blocks.lift_state,
            *lobe[:3],
        )
        factor = TransientFactor(self, lu, arrays)
        factor.coupled_data = jc
        return factor

    def lobe_border(
        self, lu: object, a_pl: FloatArray, gain: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, tuple[Any, ...]]:
        """The lobes' Woodbury border of a factorisation (:func:`~.reynolds._kernels.lobe_correct`).

        ``B' = B + a_pl L`` with ``L = gain_n · lobe_mean_n`` (∂D/∂P); returns
        ``(B⁻¹ a_pl, (I + L B⁻¹ a_pl)⁻¹, gain, lobe_rows, axial)``, empty without lobes.
        ``lu`` is the LU of B (any with a ``solve`` of (n, k) right-hand sides).
        """
        if self.n_lobe == 0:
            return np.zeros((self.n, 0)), np.zeros((0, 0)), gain, self.lobe_rows, self._axial
        solved = lu.solve(np.ascontiguousarray(a_pl))  # type: ignore[attr-defined]
        border: FloatArray = np.ascontiguousarray(solved, dtype=np.float64)
        small = np.eye(self.n_lobe) + (gain[:, None] * self.lobe_mean) @ border
        inv = np.linalg.inv(small).astype(np.float64)
        return border, inv, gain, self.lobe_rows, self._axial

    def min_film(self, y: FloatArray, preload: FloatArray) -> float:
        """Smallest film thickness h/C."""
        return float(self.film(y, preload)[0].min())

    # ------------------------------------------- sparse matrices (transient_matrices.py)
    def _film_derivatives(self, P: FloatArray) -> tuple[Any, Any, Any, Any]:
        """∂q/∂P and ∂H/∂P, ∂H/∂U, ∂H/∂ε at pressures P (:func:`.transient_matrices.film_derivatives`)."""
        return matrices.film_derivatives(self, P)

    def storage_jacobian(self, y: FloatArray, preload: FloatArray) -> sp.csr_matrix:
        """∂Q/∂y at y, sparse CSR (:func:`.transient_matrices.storage_jacobian`)."""
        return matrices.storage_jacobian(self, y, preload)

    def storage_operator(self, y: FloatArray, preload: FloatArray) -> Any:
        """``dy -> (∂Q/∂y) dy`` at y, dense and vectorised
        (:func:`.transient_matrices.storage_operator`)."""
        return matrices.storage_operator(self, y, preload)

    def smoothed_scales(self, lift_state: FloatArray | None = None) -> FloatArray:
        """s_k of each film cell's row under the smoothed lift-off law, shape (n,), 1/s.

        The law's s, or a factor's own scale of the cell where ``lift_state`` (the
        factor's) holds one: −d, the diagonal of the cell's Reynolds row at the
        factorisation. A cell's row ``G = (s_k/2)(x + g/s_k − √((x − g/s_k)² +
        4δ²Λ s/s_k))`` vanishes on the same curve ``x g = s δ²Λ`` whatever s_k, so the
        law and its solutions do not depend on it; the rows' sizes do, and a factor
        whose rows keep their size when a cell crosses the kink stays good
        (docs/development/orbit-performance.md, "One scale a cell").
        """
        s = np.full(self.n, self.smooth_scale)
        if lift_state is not None:
            own = np.asarray(lift_state, dtype=np.float64) < 0.0
            s[own] = -np.asarray(lift_state)[own]
        return s

    def smoothed_weights(
        self,
        y: FloatArray,
        inputs: Inputs,
        c0: float,
        hist: FloatArray,
        lift_state: FloatArray | None = None,
    ) -> FloatArray:
        """α of each row of the BDF equations under the smoothed lift-off law, shape (size,).

        A film cell's row ``G = (s_k/2)(x + g/s_k − √((x − g/s_k)² + 4δ²Λ s/s_k))``,
        x = P − 1 and g = c0 Q + hist − f its BDF row, depends on g, and so on y and on
        the history, through α = ∂G/∂g: 0 where the foil has lifted (P at ambient), 1
        where the film is above ambient and obeys Reynolds (docs/lift-off.md, "The
        smoothed edge"). s_k: :meth:`smoothed_scales` of ``lift_state`` (a factor's: the
        weights of its rows). The other rows' α is 1; all are 1 without the smoothed law.
        """
        a = np.ones(self.size)
        if self.lift_delta > 0.0:
            n = self.n
            g_p = fallback.newton_residual(self, y, inputs, c0, hist, np.zeros(n), smooth=False)[0]
            P = np.asarray(y[:n], dtype=np.float64)
            s = self.smoothed_scales(lift_state)
            width = self.grid.lift_off_width(inputs.lam) * np.sqrt(self.smooth_scale / s)
            a[:n] = fallback.smoothed_lift_off(P - 1.0, g_p[:n] / s, width, s)[0]
        return a

    def jacobian(
        self,
        y: FloatArray,
        inputs: Inputs,
        c0: float,
        hist: FloatArray,
        lift_state: FloatArray | None = None,
    ) -> sp.csc_matrix:
        """∂/∂y of c0·Q(y) − f(y, t), the BDF Newton matrix, sparse CSC
        (:func:`.transient_matrices.newton_matrix`)."""
        return matrices.newton_matrix(self, y, inputs, c0, hist, lift_state)
