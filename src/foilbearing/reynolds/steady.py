"""Steady compressible Reynolds equation with a compliant foil: Newton solver.

The film at a given journal position; the static analysis (the journal's equilibrium under
load, Newton on film and position) is :mod:`foilbearing.analysis.equilibrium`, which calls
this, and the study's sweep of it over speeds and voltages is :mod:`foilbearing.study.static`.

Solves the steady form of Eq. (4) of the paper (docs/model.md §4)::

    ∂/∂θ(P H³ ∂P/∂θ − Λ P H) + ∂/∂Z(P H³ ∂P/∂Z) = 0,

P = 1 at the bearing end, zero flux at the mid-plane, periodic in θ, on a
:class:`~foilbearing.reynolds.grid.FilmGrid`, with the film (docs/model.md §2-3)::

    H[i, j] = h_rigid[i, j] + c_i · max(p̄_i, 0),     p̄_i = axial_mean(P − 1)[i],

``c_i = p_a/(C k(θ_i))`` the dimensionless foil compliance. Sub-ambient mean
pressure does not pull the foil towards the journal: bumps carry no tension,
so ``max(p̄, 0)`` (``H = h_rigid`` wherever ``p̄_i <= 0``).

Top-foil lift-off (``lift_off=True``, docs/model.md §3): the top foil only
rests on the bumps, so where the film would fall below ambient it is pulled
off them until the suction is relieved, and the film holds no sub-ambient
pressure. Each cell then satisfies the complementarity conditions

    P − 1 >= 0,   −R >= 0,   (P − 1)·R = 0

(R the cell's net inflow, the residual of Eq. (4)): either the Reynolds
equation holds with P >= 1, or the cell sits at ambient with a net outflow,
which the lifting foil supplies (a Gümbel-type condition written as a
complementarity problem, as Swift-Stieber cavitation is). It is solved as
the non-smooth equation ``min(d·(P − 1), −R) = 0`` (d = −∂R_k/∂P_k > 0, the
diagonal of the Jacobian, which only scales the two branches alike) by a
semismooth Newton method: a cell on the ambient branch has the row
``−d·ΔP = d·(P − 1)``, i.e. ΔP = 1 − P, in place of its Reynolds row. The
same rows give the linearisation (ΔP = 0 on clamped cells) used by the
dynamic coefficients, and the orbit's BDF step solves the same condition.
On a grid with ``lift_off_smoothing`` κ > 0 each cell obeys the smoothed law
``(P − 1)(−R/d_ref)/Λ = δ²`` (δ = κΔθ²) instead, solved as
``−(d_ref/2)(x + y − √((x − y)² + 4δ²Λ)) = 0`` with the same Newton iteration
(:func:`~foilbearing.reynolds._kernels.lift_off_rows`; docs/lift-off.md).

The functions take arrays, not domain objects; all quantities are
dimensionless (P = p/p_a, H = h/C, forces in units of p_a R²). The film and
the residual and Jacobians it solves with (:class:`Workspace`,
:func:`coupled_system`, ...) are assembled in :mod:`foilbearing.reynolds.assembly`
and re-exported here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from foilbearing.reynolds.assembly import (
    Workspace,
    _as_field,
    _assemble,
    _check_film_inputs,
    coupled_system,
    film_force,
    film_thickness,
    held_cells,
    set_unit_rows,
)
from foilbearing.reynolds.blocksolve import TransposedSuperLU, factor_coupled
from foilbearing.reynolds.grid import FilmGrid

__all__ = [
    "NewtonOptions",
    "SteadyFilm",
    "Workspace",
    "coupled_system",
    "film_force",
    "film_thickness",
    "held_cells",
    "set_unit_rows",
    "solve_steady",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class NewtonOptions:
    """Settings of the damped Newton solver (safe defaults).

    Parameters
    ----------
    tol : float
        Convergence threshold on ``max |R[i, j]|/(Δθ ΔZ)``, the max-norm of
        the cell-averaged residual of Eq. (4) (dimensionless; the terms of the
        equation are of order Λ·P·H and P H³ ∂²P).
    max_iter : int
        Newton iterations allowed per solve (per continuation step).
    armijo : float
        Sufficient-decrease constant c of the line search on ``½‖R‖²``.
    backtrack : float
        Step reduction factor of the line search, in (0, 1).
    max_backtracks : int
        Line-search reductions before the step is declared stalled.
    max_drop : float
        Largest relative decrease of P in one step, in (0, 1): keeps P > 0.
    continuation : bool
        Fall back to continuation in Λ when plain Newton fails.
    max_continuation_steps : int
        Λ steps allowed in the fallback (the step adapts: halved on failure).
    """

    tol: float = 1e-10
    max_iter: int = 40
    armijo: float = 1e-4
    backtrack: float = 0.5
    max_backtracks: int = 20
    max_drop: float = 0.5
    continuation: bool = True
    max_continuation_steps: int = 40

    def __post_init__(self) -> None:
        if not self.tol > 0.0:
            raise ValueError(f"NewtonOptions.tol must be > 0, got {self.tol!r}")
        if self.max_iter < 1:
            raise ValueError(f"NewtonOptions.max_iter must be >= 1, got {self.max_iter!r}")
        if not 0.0 < self.armijo < 0.5:
            raise ValueError(f"NewtonOptions.armijo must be in (0, 0.5), got {self.armijo!r}")
        if not 0.0 < self.backtrack < 1.0:
            raise ValueError(f"NewtonOptions.backtrack must be in (0, 1), got {self.backtrack!r}")
        if self.max_backtracks < 0:
            raise ValueError(
                f"NewtonOptions.max_backtracks must be >= 0, got {self.max_backtracks!r}"
            )
        if not 0.0 < self.max_drop < 1.0:
            raise ValueError(f"NewtonOptions.max_drop must be in (0, 1), got {self.max_drop!r}")
        if self.max_continuation_steps < 1:
            raise ValueError(
                "NewtonOptions.max_continuation_steps must be >= 1, "
                f"got {self.max_continuation_steps!r}"
            )


@dataclass(frozen=True)
class SteadyFilm:
    """Steady film solution.

    Attributes
    ----------
    P : ndarray, shape (n_theta, n_z)
        Pressure ``p/p_a`` at the cell centres (half bearing, ``Z >= 0``).
    H : ndarray, shape (n_theta, n_z)
        Film thickness ``h/C`` including the foil deflection.
    p_mean : ndarray, shape (n_theta,)
        Axially averaged gauge pressure ``p_A/p_a = axial_mean(P − 1)``.
    iterations : int
        Newton iterations, summed over continuation steps.
    residual : float
        Final ``max |R|/(Δθ ΔZ)``.
    converged : bool
    message : str
        What happened; on failure, what did not converge and what to try.
    continuation_steps : int
        Λ steps used by the continuation fallback (0: plain Newton sufficed).
    """

    P: FloatArray
    H: FloatArray
    p_mean: FloatArray
    iterations: int
    residual: float
    converged: bool
    message: str
    continuation_steps: int = 0


# ---------------------------------------------------------------------------
# Newton solver
# ---------------------------------------------------------------------------


def _opening_start(h_rigid: FloatArray, comp: FloatArray, floor: float = 0.05) -> FloatArray:
    """Initial P = 1, raised where the journal reaches into a compliant foil so that H >= floor."""
    h_min = h_rigid.min(axis=1)
    lift = np.where(
        (h_min < floor) & (comp > 0.0), (floor - h_min) / np.where(comp > 0, comp, 1.0), 0.0
    )
    return np.repeat((1.0 + lift)[:, None], h_rigid.shape[1], axis=1)


@dataclass
class _FilmOutcome:
    P: FloatArray
    iterations: int
    residual: float
    converged: bool
    reason: str


def _film_newton(
    ws: Workspace,
    P: FloatArray,
    h_rigid: FloatArray,
    comp: FloatArray,
    lam: float,
    opts: NewtonOptions,
    lift_off: bool = False,
) -> _FilmOutcome:
    """Damped (semismooth, with lift-off) Newton with positivity-preserving step limit and
    Armijo backtracking."""
    g = ws.grid
    n = g.size
    scale = 1.0 / (g.d_theta * g.d_z)
    coupled = bool(np.any(comp != 0.0))
    indptr, indices = (ws.c_indptr, ws.c_indices) if coupled else (ws.indptr, ws.indices)
    P = P.copy()
    trial = np.empty_like(P)
    data = _assemble(ws, P, h_rigid, comp, lam, coupled, lift_off)
    res = float(np.max(np.abs(ws.res))) * scale
    merit = float(np.sum(ws.res**2))
    for it in range(opts.max_iter):
        if not np.isfinite(res):
            return _FilmOutcome(P, it, res, False, "residual is not finite")
        if res <= opts.tol:
            return _FilmOutcome(P, it, res, True, "converged")
        try:
            if coupled:  # the compiled block-cyclic LU (SuperLU if it cannot pivot)
                lu = factor_coupled(data, indices, indptr, g.n_theta, g.n_z)
            else:
                lu = TransposedSuperLU(data, indices, indptr, n)
            step = -lu.solve(ws.res.ravel()).reshape(g.shape)
        except RuntimeError as exc:  # exactly singular Jacobian
            return _FilmOutcome(P, it, res, False, f"singular Jacobian ({exc})")
        if not np.all(np.isfinite(step)):
            return _FilmOutcome(P, it, res, False, "Newton step is not finite")
        # Step limit: no cell loses more than max_drop of its pressure.
        ratio = float(np.min(step / P))
        alpha = min(1.0, opts.max_drop / -ratio) if ratio < 0.0 else 1.0
        for _ in range(opts.max_backtracks + 1):
            np.add(P, alpha * step, out=trial)
            data = _assemble(ws, trial, h_rigid, comp, lam, coupled, lift_off)
            new_merit = float(np.sum(ws.res**2))
            # A trial that closes the film (possible only over a compliant foil) is refused.
            if ws.h.min() > 0.0 and new_merit <= (1.0 - 2.0 * opts.armijo * alpha) * merit:
                break
            alpha *= opts.backtrack
        else:
            # The residual no longer decreases: accept as converged only when
            # it is already at the round-off floor of the residual.
            _assemble(ws, P, h_rigid, comp, lam, coupled, lift_off)
            if res <= 100.0 * opts.tol:
                return _FilmOutcome(P, it + 1, res, True, "converged (at the round-off floor)")
            return _FilmOutcome(P, it + 1, res, False, "line search stalled")
        P, trial = trial, P
        merit = new_merit
        res = float(np.max(np.abs(ws.res))) * scale
    if res <= opts.tol:
        return _FilmOutcome(P, opts.max_iter, res, True, "converged")
    return _FilmOutcome(
        P, opts.max_iter, res, False, f"no convergence in {opts.max_iter} iterations"
    )


def solve_steady(
    grid: FilmGrid,
    h_rigid: ArrayLike,
    compliance: ArrayLike,
    lam: float,
    p0: ArrayLike | None = None,
    *,
    options: NewtonOptions | None = None,
    workspace: Workspace | None = None,
    lift_off: bool = False,
) -> SteadyFilm:
    """Solve the steady foil-coupled Reynolds equation (Eq. (4), ∂/∂τ = 0).

    Newton's method on all ``n_theta*n_z`` pressures with the exact coupled
    Jacobian (film and foil included), factorised by the compiled block-cyclic
    LU when a foil couples the film (SuperLU otherwise, or where it cannot pivot), a step limit that
    keeps P positive and an Armijo backtracking line search on ``½‖R‖²``. If
    plain Newton from ``p0`` fails, the solve restarts from P = 1 (the exact
    solution at Λ = 0) and continues in Λ with adaptive steps; this is
    reported in ``message`` and ``continuation_steps``.

    Parameters
    ----------
    grid : FilmGrid
    h_rigid : array_like, shape (n_theta, n_z) or (n_theta,)
        Film thickness ``h/C`` without foil deflection (journal position,
        preload and housing), > 0 everywhere.
    compliance : array_like, shape (n_theta,) or scalar
        Foil compliance ``c_i = p_a/(C k(θ_i))`` (0: rigid bearing). The film
        is ``H = h_rigid + c_i max(p̄_i, 0)``: sub-ambient mean pressure does
        not pull the foil (bumps carry no tension).
    lam : float
        Bearing number ``Λ = 6 μ ω R²/(p_a C²)``.
    p0 : array_like, shape (n_theta, n_z), optional
        Initial pressure (> 0); default P = 1.
    options : NewtonOptions, optional
    workspace : Workspace, optional
        Reused buffers of this grid (saves the pattern set-up).
    lift_off : bool
        Top-foil lift-off: no sub-ambient film pressure (P >= 1 as a
        complementarity condition, module docstring). Default False: the film
        keeps its sub-ambient pressure (a rigid surface, or the suction-retained foil).

    Returns
    -------
    SteadyFilm
        Never NaN silently: on failure ``converged`` is False and ``message``
        says what did not converge and what to try.
    """
    opts = options if options is not None else NewtonOptions()
    if not np.isfinite(lam):
        raise ValueError(f"lam (bearing number) must be finite, got {lam!r}")
    h_r, comp = _check_film_inputs(grid, h_rigid, compliance)
    ws = workspace if workspace is not None else Workspace(grid)
    if ws.grid != grid:
        raise ValueError("workspace was created for another grid")
    if p0 is None:
        start = _opening_start(h_r, comp)
    else:
        start = _as_field(grid, p0, "p0")
        if not np.all(np.isfinite(start)) or start.min() <= 0.0:
            raise ValueError("p0 must be finite and > 0 everywhere")

    out = _film_newton(ws, start, h_r, comp, lam, opts, lift_off)
    total = out.iterations
    steps = 0
    message = out.reason
    if not out.converged and opts.continuation and lam != 0.0 and h_r.min() > 0.0:
        first_reason = out.reason
        out, n_it, steps, detail = _continuation(ws, h_r, comp, lam, opts, lift_off)
        total += n_it
        if out.converged:
            message = (
                f"plain Newton failed ({first_reason}); converged by continuation "
                f"in Λ ({steps} steps)"
            )
        else:
            message = f"plain Newton failed ({first_reason}); continuation in Λ failed: {detail}"
    if not out.converged:
        message += (
            f". Not converged: max |R|/(ΔθΔZ) = {out.residual:.3e} > tol = {opts.tol:.1e} "
            f"at Λ = {lam:g}, min h_rigid = {h_r.min():.3g}, grid {grid.n_theta}×{grid.n_z}. "
            "Try a better p0 (e.g. the solution at a nearby Λ or eccentricity), a finer "
            "grid, more max_iter / max_continuation_steps, or check that the film "
            "stays positive."
        )
    P = out.P
    H, p_mean = film_thickness(grid, h_r, comp, P)
    return SteadyFilm(
        P=P,
        H=H,
        p_mean=p_mean,
        iterations=total,
        residual=out.residual,
        converged=out.converged,
        message=message,
        continuation_steps=steps,
    )


def _continuation(
    ws: Workspace,
    h_r: FloatArray,
    comp: FloatArray,
    lam: float,
    opts: NewtonOptions,
    lift_off: bool = False,
) -> tuple[_FilmOutcome, int, int, str]:
    """Adaptive continuation from Λ = 0 (P = 1 exact) to ``lam``."""
    done = 0.0
    P = np.ones(ws.grid.shape)
    delta = lam / 4.0
    total = 0
    last = _FilmOutcome(P, 0, np.inf, False, "no step taken")
    for k in range(opts.max_continuation_steps):
        target = lam if abs(done + delta) >= abs(lam) else done + delta
        last = _film_newton(ws, P, h_r, comp, target, opts, lift_off)
        total += last.iterations
        if last.converged:
            done, P = target, last.P
            if done == lam:
                return last, total, k + 1, "converged"
            delta *= 2.0
        else:
            delta *= 0.25
            if abs(delta) < 1e-6 * abs(lam):
                return last, total, k + 1, f"stuck at Λ = {done:g} ({last.reason})"
    return last, total, opts.max_continuation_steps, f"reached Λ = {done:g} only ({last.reason})"
