"""Static analysis: the journal equilibrium under load, or the film at a given position.

Newton on the whole discrete system: the pressures P of the foil-coupled
Reynolds equation (paper Eq. 4, steady) and the journal position (ε_X, ε_Y),
with the force balance ``F + W = 0`` (docs/model.md §2, load W along +X) as
the two extra equations. Each iteration factorises the coupled Jacobian once
and eliminates (ε_X, ε_Y) by a 2 × 2 Schur complement. The same residual and
Jacobian (``reynolds.coupled_system``) serve the dynamic coefficients and
the orbit, so static, linear and nonlinear results agree by construction.
The result, :class:`~foilbearing.analysis.static_result.StaticResult`, and its views live in
:mod:`foilbearing.analysis.static_result` (re-exported here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from foilbearing.analysis.static_result import _SHOWN, STATIC_HEADLINE, StaticResult  # noqa: F401
from foilbearing.analysis.static_result import static_result as _result
from foilbearing.bearing_system.scales import Scales
from foilbearing.case import Case
from foilbearing.errors import InputError
from foilbearing.film import FilmModel, drag_torque, film_model
from foilbearing.reynolds import NewtonOptions, Workspace
from foilbearing.reynolds.blocksolve import TransposedSuperLU, factor_coupled
from foilbearing.units import QuantityLike, as_si

__all__ = [
    "STATIC_HEADLINE",
    "EquilibriumOptions",
    "StaticResult",
    "drag_torque",
    "film_at_position",
    "solve_equilibrium",
]

FloatArray = NDArray[np.float64]


#: The smallest force, in units of p_a R², that the force balance is measured against: a
#: lighter load (zero included, which the case allows) is tested to ``force_tol`` times this
#: absolute force (3e-10 N for the paper's bearing) instead of relative to itself, which would
#: divide by zero. 1e-3 p_a R² (0.03 N there) keeps the round-off of the film force's
#: quadrature (about 1e-16 p_a R²) far below the test.
FORCE_FLOOR = 1e-3


@dataclass(frozen=True)
class EquilibriumOptions:
    """Settings of the equilibrium Newton solver (safe defaults).

    Attributes
    ----------
    force_tol
        Converged when |F + W|/|W| is below this (and the Reynolds residual below ``newton.tol``);
        below a load of :data:`FORCE_FLOOR` p_a R² (zero included: a centred journal) the
        test is absolute, |F + W| against that floor.
    max_iter
        Newton iterations on (P, ε).
    max_step
        Largest change of ε_X or ε_Y in one iteration (units of C).
    min_film
        Smallest film H = h/C a trial step may produce; steps are shortened to keep it.
    newton
        Options of the pressure solve used for the starting point.
    """

    force_tol: float = 1e-8
    max_iter: int = 60
    max_step: float = 0.1
    min_film: float = 0.01
    newton: NewtonOptions = field(default_factory=NewtonOptions)


def _check_speed(case: Case, speed: QuantityLike | None) -> float:
    omega = case.operation.speed if speed is None else as_si(speed, "speed", field="speed")
    if not (math.isfinite(omega) and omega > 0.0):
        raise InputError(f"speed = {omega!r} rad/s: expected a speed > 0 (e.g. '50000 rpm')")
    case.check_speeds(omega)
    return omega


def film_at_position(
    case: Case,
    eps_x: float,
    eps_y: float,
    *,
    speed: QuantityLike | None = None,
    model: FilmModel | None = None,
    options: EquilibriumOptions | None = None,
) -> StaticResult:
    """The film and its force at a prescribed journal position (no equilibrium search).

    Parameters
    ----------
    case
        Bearing case.
    eps_x, eps_y
        Journal position in units of C.
    speed
        Rotor speed, rad/s (default: the case's operating speed).
    """
    opts = options or EquilibriumOptions()
    omega = _check_speed(case, speed)
    model = model or film_model(case)
    h_r = model.h_rigid(eps_x, eps_y)
    if h_r.min() <= 0.0 and not np.any(model.compliance > 0):
        raise InputError(
            f"journal position ({eps_x:g}, {eps_y:g}) closes the film (min h/C = {h_r.min():.3g}) "
            "of a rigid bearing: choose a smaller eccentricity"
        )
    lam = Scales.from_case(case).bearing_number(omega)
    if model.lobe:  # the stacks' compressions are unknowns beside P (journal fixed)
        out = _lobe_film_on_ray(_Equilibrium(model, lam, opts, journal=False), eps_x, eps_y)
        P = out.P.reshape(model.grid.shape)
        ok = out.converged
        msg = out.message if ok else f"film not found at this position: {out.message}"
        its, res = out.iterations, out.residual
    else:
        sol = model.steady_film(h_r, lam, options=opts.newton)
        P, ok, msg, its, res = sol.P, sol.converged, sol.message, sol.iterations, sol.residual
    return _result(
        case,
        model,
        omega,
        lam,
        eps_x,
        eps_y,
        P,
        model.film(P, eps_x, eps_y),
        its,
        res,
        math.nan,
        ok,
        msg,
        equilibrium=False,
    )


#: The shortest step, as a fraction of the journal's distance from the centre, that
#: :func:`_lobe_film_on_ray` takes before it gives up.
RAY_MIN_STEP = 1.0 / 256


def _lobe_film_on_ray(solver: _Equilibrium, eps_x: float, eps_y: float) -> _EquilibriumOutcome:
    """The film and the stacks' compressions D_n at a fixed journal position, under
    ``preload_response = "lobe"``.

    From P = 1 and D = 0 first. Where that fails (a journal that overlaps an
    uncompressed lobe, min h_rigid < 0, whose film only the stack's compression
    opens), the journal is walked out from the centre along its ray, s (ε_X, ε_Y) for
    s from 0 to 1, each film starting from the last (its P gives the start's D); a
    failed step is halved, down to :data:`RAY_MIN_STEP`. The equilibrium reaches the
    same positions by the same kind of path (Newton from the previous iterate), so
    both land on the same film.
    """
    eps = np.array([eps_x, eps_y], dtype=float)
    out = solver.solve(0.0, eps, None)
    if out.converged:
        return out
    first, iterations = out, out.iterations
    done, step, start = 0.0, 0.25, None
    while done < 1.0:
        s = min(1.0, done + step)
        trial = solver.solve(0.0, s * eps, start)
        iterations += trial.iterations
        if trial.converged:
            done, start, out = s, trial.P, trial
            step = min(2.0 * step, 0.5)
        elif step / 2.0 < RAY_MIN_STEP:
            return replace(
                first,
                iterations=iterations,
                message=f"{first.message}; walking out from the centre along the ray also "
                f"failed at {s:.4g} of the way ({trial.message})",
            )
        else:
            step /= 2.0
    return replace(
        out,
        iterations=iterations,
        message="converged by walking the journal out from the centre along its ray "
        "(from P = 1 at the position itself it did not)",
    )


def solve_equilibrium(
    case: Case,
    *,
    speed: QuantityLike | None = None,
    model: FilmModel | None = None,
    start: tuple[float, float, FloatArray | None] | None = None,
    options: EquilibriumOptions | None = None,
) -> StaticResult:
    """Journal equilibrium: the position where film force plus load is zero.

    Newton from ``start``; without one, on a grid of more than 96 × 12 cells, from the
    equilibrium of the grid coarsened by 2 (grid sequencing,
    :data:`SEQUENCE_ABOVE_CELLS`), else from the centre; if that fails, continuation in
    the load from a tenth of it, each step starting from the last equilibrium.

    Parameters
    ----------
    case
        Bearing case (load along +X from ``case.operation.load``).
    speed
        Rotor speed, rad/s, or a quantity such as ``"30 krpm"`` (default: the case's
        operating speed).
    model
        Film model of the case (built from the case if omitted).
    start
        (ε_X, ε_Y, P) to start from, e.g. the equilibrium at a nearby speed;
        P may be None.
    options
        Solver settings.

    Returns
    -------
    StaticResult with ``converged`` False and a message saying what did not
    converge and what to try, if no equilibrium was found; never NaN.
    """
    opts = options or EquilibriumOptions()
    omega = _check_speed(case, speed)
    model = model or film_model(case)
    scales = Scales.from_case(case)
    lam = scales.bearing_number(omega)
    load = case.operation.load / scales.force  # dimensionless load along +X
    system = _Equilibrium(model, lam, opts)
    if start is None:
        start = _from_coarser_grid(case, model, omega, options)
    eps0 = np.zeros(2) if start is None else np.array(start[:2], dtype=float)
    p0 = None if start is None else start[2]
    out = system.solve(load, eps0, p0)
    iterations = out.iterations
    note = ""
    if not out.converged and load > 0.0:
        # Load continuation from the centre: a light load is found from ε = 0,
        # and each step starts from the previous equilibrium.
        first_reason = out.message
        done, frac = 0.0, 0.1
        eps, P = np.zeros(2), None
        steps = 0
        while done < 1.0 and steps < 40:
            target = min(1.0, done + frac)
            trial = system.solve(target * load, eps, P)
            iterations += trial.iterations
            steps += 1
            if trial.converged:
                done, eps, P, out = target, trial.eps, trial.P, trial
                frac *= 1.5
            else:
                frac *= 0.3
                out = trial
                if frac < 1e-3:
                    break
        note = f"direct Newton failed ({first_reason}); load continuation in {steps} steps: "
        if done < 1.0:
            # The last trial's residual is against its part of the load: report the whole's.
            R, _, _, G = system._evaluate(out.P, out.eps, model.stack_compression(out.P), load)
            out = replace(out, converged=False, force_res=system._residuals(R, G, load)[1])
            note += f"stopped at {100 * done:.1f} % of the load; "
    if out.converged:
        message = note + f"converged in {iterations} Newton iterations"
    else:
        message = (
            f"equilibrium not found: {note}{out.message}; |F + W|/|W| = {out.force_res:.2e}, "
            f"Reynolds residual {out.residual:.2e}, at ε = ({out.eps[0]:.4f}, {out.eps[1]:.4f}), "
            f"Λ = {lam:.4g}. Try: a start from a nearby converged point, a finer grid, or check "
            "that the bearing can carry the load at this speed (the film may be closing)."
        )
    Pf = out.P.reshape(model.grid.shape)
    H = model.film(Pf, *out.eps)
    return _result(
        case,
        model,
        omega,
        lam,
        float(out.eps[0]),
        float(out.eps[1]),
        Pf,
        H,
        iterations,
        out.residual,
        out.force_res,
        out.converged,
        message,
        True,
    )


#: A cold start on a grid of more cells than this starts from the equilibrium of the grid
#: coarsened by 2 in both directions (itself found the same way), its pressures repeated
#: on the finer cells: grid sequencing. On 384 × 48 (the published onset's refinement)
#: 12 Newton iterations and 2.2 s (the coarser solves included) instead of 239 and 40 s
#: from the centre (load
#: continuation), the same equilibrium; the case's own 96 × 12 and coarser grids start
#: from the centre as before.
SEQUENCE_ABOVE_CELLS = 96 * 12


def _from_coarser_grid(
    case: Case, model: FilmModel, omega: float, options: EquilibriumOptions | None
) -> tuple[float, float, FloatArray] | None:
    """A start for a cold solve on a fine grid (:data:`SEQUENCE_ABOVE_CELLS`): the
    equilibrium on the grid coarsened by 2, P repeated 2 × 2; None where the grid is not
    that fine, does not halve, is not the case's, or the coarse solve failed (the fine
    solve then starts from the centre)."""
    grid = case.grid
    n_theta, n_z = grid.n_theta, grid.n_z
    if (
        n_theta * n_z <= SEQUENCE_ABOVE_CELLS
        or n_theta % 2
        or n_z % 2
        or n_theta < 32
        or n_z < 8  # the coarse grid at least 16 × 4 (any axial order)
        or model.grid.shape != (n_theta, n_z)
    ):
        return None
    coarse_case = replace(case, grid=replace(grid, n_theta=n_theta // 2, n_z=n_z // 2))
    coarse = solve_equilibrium(coarse_case, speed=omega, options=options)
    if not coarse.converged:
        return None
    P = np.repeat(np.repeat(np.asarray(coarse.P, float), 2, axis=0), 2, axis=1)
    return coarse.eps_x, coarse.eps_y, P.ravel()


@dataclass(frozen=True)
class _EquilibriumOutcome:
    P: FloatArray
    eps: FloatArray
    converged: bool
    iterations: int
    residual: float
    force_res: float
    message: str


class _Equilibrium:
    """The bordered system (P, ε_X, ε_Y, D) of one film model at one speed.

    The border's unknowns are the journal position ε (unless it is prescribed) and,
    under ``preload_response = "lobe"``, the stacks' compressions D_n (units of C), with
    the rows ``F + W = 0`` and ``D_n − c_s max(q(θ_n), 0) = 0`` (Eq. 3b). Newton
    eliminates them by a Schur complement of the border's size.
    """

    def __init__(
        self, model: FilmModel, lam: float, opts: EquilibriumOptions, journal: bool = True
    ) -> None:
        g = model.grid
        self.model, self.lam, self.opts, self.journal = model, lam, opts, journal
        self.ws = Workspace(g)
        self.cos_t = np.repeat(np.cos(g.theta)[:, None], g.n_z, axis=1).ravel()
        self.sin_t = np.repeat(np.sin(g.theta)[:, None], g.n_z, axis=1).ravel()
        w_x, w_y = g.force_weights()
        self.w_x, self.w_y = w_x.ravel(), w_y.ravel()
        self.scale = 1.0 / (g.d_theta * g.d_z)
        self.n_stack = len(model.preload_angles) if model.lobe else 0
        if self.n_stack:
            assert model.lobe_shapes is not None and model.actuator_rows is not None
            self.lobe_cells = np.repeat(model.lobe_shapes, g.n_z, axis=1).T  # (n, n_stack)
            self.q_rows = g.mean_rows(model.actuator_rows)  # q_n = q_rows @ (P − 1)

    def _evaluate(
        self, P: FloatArray, eps: FloatArray, D: FloatArray, load: float
    ) -> tuple[Any, ...]:
        m = self.model
        R, j_pp, j_ph = m.steady_residual(P, m.h_rigid_loaded(eps[0], eps[1], D), self.lam, self.ws)
        G = np.array([self.w_x @ (P - 1.0) + load, self.w_y @ (P - 1.0)]) if self.journal else None
        if self.n_stack:
            g_d = D - m.stack_compression(P)
            G = g_d if G is None else np.concatenate([G, g_d])
        return R, j_pp, j_ph, G

    def _border(self, j_ph: Any, P: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Columns B = dR/d(ε, D), rows C = dG/dP and block E = dG/d(ε, D) of the border."""
        cols, rows = [], []
        if self.journal:
            cols += [j_ph @ self.cos_t, j_ph @ self.sin_t]
            rows += [self.w_x, self.w_y]
        if self.n_stack:
            cols += list((j_ph @ self.lobe_cells).T)
            engaged = (self.q_rows @ (P - 1.0)) > 0.0
            rows += list(-self.model.stack_compliance * engaged[:, None] * self.q_rows)
        k = len(cols)
        E = np.zeros((k, k))
        if self.n_stack:
            E[k - self.n_stack :, k - self.n_stack :] = np.eye(self.n_stack)
        return np.column_stack(cols), np.array(rows), E

    def _factor(self, j_pp: Any) -> Any:
        """LU of dR/dP for ``.solve``: the block-cyclic LU on the foil-coupled pattern."""
        g = self.model.grid
        if j_pp.nnz == 3 * g.n_z * g.size:  # foil-coupled pattern (coupled_system)
            return factor_coupled(j_pp.data, j_pp.indices, j_pp.indptr, g.n_theta, g.n_z)
        return TransposedSuperLU(j_pp.data, j_pp.indices, j_pp.indptr, g.size)

    def _film_min(self, P: FloatArray, eps: FloatArray, D: FloatArray) -> float:
        m = self.model
        p_mean = m.grid.gauge_mean(P.reshape(m.grid.shape))
        h = m.h_rigid_loaded(eps[0], eps[1], D)[:, 0] + m.compliance * np.maximum(p_mean, 0.0)
        return float(h.min())

    def _residuals(
        self, R: FloatArray, G: FloatArray | None, load_ref: float
    ) -> tuple[float, float]:
        """max|R|/(ΔθΔZ), and |F + W|/|W| with the stacks' rows (units of C) beside it."""
        res = float(np.max(np.abs(R))) * self.scale
        if G is None:
            return res, 0.0
        force = float(np.hypot(*G[:2])) / load_ref if self.journal else 0.0
        stack = float(np.max(np.abs(G[-self.n_stack :]))) if self.n_stack else 0.0
        return res, max(force, stack)

    def _merit(self, R: FloatArray, G: FloatArray | None, load_ref: float) -> float:
        r = R * self.scale
        if G is None:
            return float(r @ r)
        g = G.copy()
        if self.journal:
            g[:2] /= load_ref
        return _merit(r, g)

    def solve(self, load: float, eps: FloatArray, P0: FloatArray | None) -> _EquilibriumOutcome:
        """Damped Newton on (P, ε, D) for a dimensionless load along +X (ε fixed if not
        ``journal``)."""
        m, opts = self.model, self.opts
        eps = np.asarray(eps, dtype=float).copy()
        D = m.stack_compression(P0) if P0 is not None else np.zeros(self.n_stack)
        D = D[: self.n_stack]
        first = m.steady_film(
            m.h_rigid_loaded(eps[0], eps[1], D),
            self.lam,
            P0,
            options=opts.newton,
            workspace=self.ws,
        )
        P = first.P.ravel().copy()
        load_ref = max(abs(load), FORCE_FLOOR)
        if not first.converged:
            return _EquilibriumOutcome(
                P,
                eps,
                False,
                first.iterations,
                first.residual,
                np.inf,
                "pressure solve at the starting position failed: " + first.message,
            )
        iterations = first.iterations
        if not self.journal and not self.n_stack:
            res = first.residual
            return _EquilibriumOutcome(P, eps, True, iterations, res, 0.0, "converged")
        R, j_pp, j_ph, G = self._evaluate(P, eps, D, load)
        merit = self._merit(R, G, load_ref)
        n_j = 2 if self.journal else 0
        for it in range(opts.max_iter):
            res, force_res = self._residuals(R, G, load_ref)
            if res <= opts.newton.tol and force_res <= opts.force_tol:
                return _EquilibriumOutcome(
                    P, eps, True, iterations + it, res, force_res, "converged"
                )
            try:
                lu = self._factor(j_pp)
            except RuntimeError:
                return _EquilibriumOutcome(
                    P, eps, False, iterations + it, res, force_res, "singular Jacobian"
                )
            # Schur complement: dP = a − Y dx with J a = −R, J Y = B; (E − C Y) dx = −G − C a.
            B, C, E = self._border(j_ph, P)
            a = -lu.solve(R)
            y = lu.solve(B)
            dx = np.linalg.solve(E - C @ y, -G - C @ a)
            d_p = a - y @ dx
            d_eps, d_d = dx[:n_j], dx[n_j:]
            # Step control: limit the journal move, keep P > 0 and the film open, backtrack.
            step = 1.0
            if self.journal:
                step = min(1.0, opts.max_step / max(float(np.max(np.abs(d_eps))), 1e-300))
            neg = d_p < 0
            if np.any(neg):
                step = min(step, 0.9 * float(np.min(-P[neg] / d_p[neg])))
            for _ in range(30):
                P_t = P + step * d_p
                eps_t = eps + step * d_eps if self.journal else eps
                D_t = D + step * d_d
                if self._film_min(P_t, eps_t, D_t) > opts.min_film:
                    R_t, jpp_t, jph_t, G_t = self._evaluate(P_t, eps_t, D_t, load)
                    m_t = self._merit(R_t, G_t, load_ref)
                    if m_t < (1.0 - 1e-4 * step) * merit or step < 1e-3:
                        break
                step *= 0.5
            else:
                return _EquilibriumOutcome(
                    P,
                    eps,
                    False,
                    iterations + it + 1,
                    res,
                    force_res,
                    f"line search failed (the film would close below h/C = {opts.min_film}, "
                    "or the residual did not decrease)",
                )
            P, eps, D, R, j_pp, j_ph, G, merit = P_t, eps_t, D_t, R_t, jpp_t, jph_t, G_t, m_t
        res, force_res = self._residuals(R, G, load_ref)
        converged = res <= opts.newton.tol and force_res <= opts.force_tol  # after the last step
        return _EquilibriumOutcome(
            P,
            eps,
            converged,
            iterations + opts.max_iter,
            res,
            force_res,
            "converged" if converged else f"no convergence in {opts.max_iter} iterations",
        )


def _merit(r: FloatArray, g: FloatArray) -> float:
    return float(r @ r + g @ g)
