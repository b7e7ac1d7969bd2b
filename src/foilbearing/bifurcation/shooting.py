"""Periodic orbits of an autonomous system by shooting, and their Floquet multipliers.

A periodic orbit of ``dy/dt = f(y; p)`` is a state y₀ and a period T with
``φ_T(y₀) = y₀``, φ the flow. Shooting solves

    G(y₀, T) = [φ_T(y₀) − y₀ ;  ⟨n, y₀ − y_ref⟩] = 0

by Newton. The second row, a phase condition (a Poincaré section through y_ref
normal to n, by default ``n = f(y_ref)``), removes the orbit's free shift in time.
The Newton matrix is the bordered ``[[M − I, f(φ_T(y₀))], [nᵀ, 0]]`` with the
monodromy ``M = ∂φ_T/∂y₀``; the eigenvalues of M at the solution are the orbit's
Floquet multipliers, one of them 1 (along the flow), and the orbit is stable when
all others lie inside the unit circle.

The numerics see a :class:`FlowMap` (callables and arrays, no bearing): the flow
over a time, the vector field, and optionally the flow's derivative along a
direction (finite differences of the flow by default). Small systems
(``n <= dense_max``) build M column by column; larger ones solve the Newton
systems matrix-free by GMRES and take the multipliers by Arnoldi
(:func:`scipy.sparse.linalg.eigs`) on the same products.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.sparse.linalg import LinearOperator, eigs, gmres

__all__ = [
    "FlowMap",
    "PeriodicOrbit",
    "ShootingError",
    "bordered_solve",
    "floquet_multipliers",
    "periodic_orbit",
]

FloatArray = NDArray[np.float64]


class ShootingError(ArithmeticError):
    """Shooting did not converge: the message says how far it got and what to try."""


@dataclass(frozen=True)
class FlowMap:
    """An autonomous system as shooting sees it (SI or nondimensional, as the caller's).

    Attributes
    ----------
    advance
        ``advance(y0, T, p)``: the state at time T from y0 at parameter p, shape (n,).
    field
        ``field(y, p)``: the vector field f(y; p), shape (n,).
    tangent
        ``tangent(y0, T, p, v)``: the flow's derivative ``M v = ∂φ_T/∂y₀ · v``; None:
        one-sided finite differences of ``advance`` with step ``fd_step`` (relative).
    fd_step
        Relative step of the finite differences (of ``tangent`` when None, and of the
        parameter derivative in continuation).
    dense_max
        Largest n for which the monodromy is built as a dense matrix.
    krylov_rtol
        Relative residual GMRES aims at on a larger system.
    krylov_accept
        The relative residual a GMRES step must reach to be taken (an inexact Newton
        step: convergence is judged on the orbit's own residual); above it, an error.
    tangent_blocks
        ``tangent`` also takes a block of directions V, shape (n, m), in one call.
    """

    advance: Callable[[FloatArray, float, float], FloatArray]
    field: Callable[[FloatArray, float], FloatArray]
    tangent: Callable[[FloatArray, float, float, FloatArray], FloatArray] | None = None
    fd_step: float = 1e-7
    dense_max: int = 64
    krylov_rtol: float = 1e-8
    krylov_accept: float = 1e-3
    tangent_blocks: bool = False

    def apply(
        self, y0: FloatArray, period: float, p: float, v: FloatArray, end: FloatArray
    ) -> FloatArray:
        """M v, with ``end = advance(y0, period, p)`` already known (for the differences)."""
        if self.tangent is not None:
            return self.tangent(y0, period, p, v)
        norm = float(np.linalg.norm(v))
        if norm == 0.0:
            return np.zeros_like(v)
        h = self.fd_step * (1.0 + float(np.linalg.norm(y0))) / norm
        return (self.advance(y0 + h * v, period, p) - end) / h

    def apply_block(
        self, y0: FloatArray, period: float, p: float, block: FloatArray, end: FloatArray
    ) -> FloatArray:
        """M V for the columns of V (n, m): one call of a block ``tangent``, else by columns."""
        if self.tangent is not None and self.tangent_blocks:
            return np.asarray(self.tangent(y0, period, p, block), float).reshape(block.shape)
        return np.column_stack([self.apply(y0, period, p, c, end) for c in block.T])


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit: a state on it, its period, its parameter and its stability.

    Attributes
    ----------
    state
        y₀, a state on the orbit (on the phase condition's section), shape (n,).
    period
        T, in the system's time unit.
    parameter
        p of the orbit.
    multipliers
        Floquet multipliers, largest modulus first (all n for a dense monodromy, the
        leading few by Arnoldi otherwise), complex.
    iterations
        Newton iterations taken.
    residual
        ``‖φ_T(y₀) − y₀‖ / (1 + ‖y₀‖)`` at the solution.
    """

    state: FloatArray
    period: float
    parameter: float
    multipliers: NDArray[np.complex128] = field(repr=False)
    iterations: int
    residual: float

    @property
    def nontrivial_multipliers(self) -> NDArray[np.complex128]:
        """The multipliers less the trivial one (the one nearest 1, along the flow)."""
        m = self.multipliers
        if m.size == 0:
            return m
        return np.delete(m, int(np.argmin(np.abs(m - 1.0))))

    @property
    def stable(self) -> bool:
        """All nontrivial multipliers inside the unit circle."""
        rest = self.nontrivial_multipliers
        return bool(rest.size == 0 or np.max(np.abs(rest)) < 1.0)


def floquet_multipliers(
    flow: FlowMap, y0: FloatArray, period: float, p: float, count: int = 6
) -> NDArray[np.complex128]:
    """Eigenvalues of the monodromy at (y₀, T, p), largest modulus first.

    All n of them for ``n <= flow.dense_max``; otherwise the ``count`` largest by
    Arnoldi on matrix-free products.
    """
    end = flow.advance(y0, period, p)
    n = y0.size
    if n <= flow.dense_max:
        values = np.linalg.eigvals(flow.apply_block(y0, period, p, np.eye(n), end))
    else:
        op = LinearOperator((n, n), matvec=lambda v: flow.apply(y0, period, p, np.ravel(v), end))
        values = eigs(op, k=min(count, n - 2), which="LM", return_eigenvectors=False)
    return values[np.argsort(-np.abs(values))].astype(np.complex128)


def bordered_solve(
    flow: FlowMap,
    y0: FloatArray,
    period: float,
    p: float,
    end: FloatArray,
    cols: FloatArray,
    rows: FloatArray,
    corner: FloatArray,
    rhs: FloatArray,
) -> FloatArray:
    """Solve ``[[M − I, C], [R, D]] x = rhs`` (n + k unknowns), dense or by GMRES.

    M is the monodromy at (y₀, T, p) (``end = advance(y0, period, p)``), C the border
    columns (n, k), R the border rows (k, n) and D the corner (k, k).
    """
    n, k = y0.size, corner.shape[0]
    # Equilibrate the border (the parameter's column can be orders of magnitude off the
    # state's): unit columns and rows, undone on the solution.
    col_scale = 1.0 / np.maximum(np.linalg.norm(np.vstack([cols, corner]), axis=0), 1e-300)
    row_scale = 1.0 / np.maximum(np.linalg.norm(np.hstack([rows, corner]), axis=1), 1e-300)
    cols, corner = cols * col_scale, corner * col_scale
    rows, corner = rows * row_scale[:, None], corner * row_scale[:, None]
    rhs = np.concatenate([rhs[:n], rhs[n:] * row_scale])

    def matvec(x: FloatArray) -> FloatArray:
        x = np.ravel(x)
        top = flow.apply(y0, period, p, x[:n], end) - x[:n] + cols @ x[n:]
        return np.concatenate([top, rows @ x[:n] + corner @ x[n:]])

    if n <= flow.dense_max:
        mat = np.block(
            [[flow.apply_block(y0, period, p, np.eye(n), end) - np.eye(n), cols], [rows, corner]]
        )
        # A state the flow leaves where it is, whatever the start and the parameter (the
        # foil's of a bearing without one): its row of [M − I, C] and its residual are
        # zero, and nothing fixes its correction. It stays put (correction 0): its row
        # and column leave the system, which is otherwise singular (exactly or to
        # round-off, as the platform's BLAS decides).
        keep = np.ones(n + k, dtype=bool)
        keep[:n] = np.any(mat[:n] != 0.0, axis=1) | (rhs[:n] != 0.0)
        x = np.zeros(n + k)
        try:
            x[keep] = np.linalg.solve(mat[np.ix_(keep, keep)], rhs[keep])
        except np.linalg.LinAlgError as exc:
            raise ShootingError(
                f"the shooting system is singular at T = {period:.6g} s ({exc}): the orbit "
                "is not isolated there; try a smaller continuation step or another amplitude"
            ) from exc
        return np.concatenate([x[:n], x[n:] * col_scale])
    op = LinearOperator((n + k, n + k), matvec=matvec)
    rtol = flow.krylov_rtol
    x, info = gmres(op, rhs, rtol=rtol, atol=0.0, restart=min(n + k, 60), maxiter=10)
    if info != 0:
        left = float(np.linalg.norm(matvec(x) - rhs) / np.linalg.norm(rhs))
        if left > flow.krylov_accept:
            raise ShootingError(
                f"GMRES left {left:.2g} of the shooting system's residual (asked {rtol:g}, "
                f"taken below {flow.krylov_accept:g}): "
                "the flow's products may be noisy; tighten its Newton tolerance or raise "
                "fd_step"
            )
    x = np.asarray(x, float)
    return np.concatenate([x[:n], x[n:] * col_scale])


def periodic_orbit(
    flow: FlowMap,
    y0: FloatArray,
    period: float,
    p: float,
    *,
    normal: FloatArray | None = None,
    tol: float = 1e-9,
    max_iter: int = 25,
    multipliers: int = 6,
) -> PeriodicOrbit:
    """The periodic orbit near the guess (y₀, T) at parameter p, by Newton shooting.

    Parameters
    ----------
    flow
        The system.
    y0, period
        Guess of a state on the orbit and of its period.
    p
        The parameter, held.
    normal
        Normal n of the phase condition's section through the guess; default f(y₀).
    tol
        Converged when ``‖φ_T(y₀) − y₀‖ <= tol (1 + ‖y₀‖)`` and the last update is below
        ``sqrt(tol)`` relative to the state and the period.
    max_iter
        Newton iterations before :class:`ShootingError`.
    multipliers
        How many Floquet multipliers to return for a large system (Arnoldi).

    Raises
    ------
    ShootingError
        No convergence in ``max_iter`` iterations (the message gives the last residual).
    """
    y = np.array(y0, dtype=float)
    ref = y.copy()
    n_vec = np.asarray(flow.field(ref, p) if normal is None else normal, float)
    n_vec = n_vec / np.linalg.norm(n_vec)
    T = float(period)
    res = np.inf
    for it in range(1, max_iter + 1):
        end = flow.advance(y, T, p)
        res = float(np.linalg.norm(end - y)) / (1.0 + float(np.linalg.norm(y)))
        if not np.isfinite(res):  # no flow from this iterate (contact, say)
            break
        rhs = -np.concatenate([end - y, [n_vec @ (y - ref)]])
        cols, rows = flow.field(end, p)[:, None], n_vec[None, :]
        step = bordered_solve(flow, y, T, p, end, cols, rows, np.zeros((1, 1)), rhs)
        y += step[:-1]
        T += step[-1]
        small = np.linalg.norm(step[:-1]) <= np.sqrt(tol) * (1.0 + np.linalg.norm(y))
        if res <= tol and small and abs(step[-1]) <= np.sqrt(tol) * T:
            values = floquet_multipliers(flow, y, T, p, multipliers)
            return PeriodicOrbit(y, T, p, values, it, res)
        if not (np.isfinite(T) and T > 0.0):
            break
    raise ShootingError(
        f"shooting did not converge in {max_iter} Newton iterations at p = {p:g} (last "
        f"residual {res:.3g}, period {T:.6g}): start nearer the orbit, or from a longer "
        "transient"
    )
