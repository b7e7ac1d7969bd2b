"""The branch of periodic orbits born at a Hopf point, by pseudo-arclength continuation.

At a Hopf point p_H the equilibrium y_e(p) has a pair of eigenvalues ±iω on the
imaginary axis with eigenvector q. The branch starts with orbits of a set small
amplitude a on the section through y_e along Re q̂ (q̂ = q turned so that Re q̂ ⊥ Im q̂,
and scaled to ‖Re q̂‖ = 1): the unknowns (y₀, T, p) solve

    φ_T(y₀; p) − y₀ = 0,   ⟨Im q̂, y₀ − y_e(p)⟩ = 0,   ⟨Re q̂, y₀ − y_e(p)⟩ = a,

so p(a) says on which side of p_H the small cycles live (read from the two first
orbits, at a and 2a, so that it does not depend on how closely p_H is known). Cycles on the side where
the equilibrium is unstable are born stable (a supercritical Hopf bifurcation: the
whirl past the onset stays bounded); cycles on the stable side are unstable (a
subcritical one: a large enough disturbance below the onset already throws the
journal onto a large orbit). From the two first orbits the branch goes on by
pseudo-arclength in (y₀, T, p) (secant predictor, Newton corrector with a phase
condition through the last orbit), which follows it round folds; a fold is where
the parameter's direction along the branch changes sign.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from foilbearing.bifurcation.shooting import (
    FlowMap,
    PeriodicOrbit,
    ShootingError,
    bordered_solve,
    floquet_multipliers,
)

__all__ = ["Branch", "HopfPoint", "hopf_branch"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class HopfPoint:
    """A Hopf point of the equilibria y_e(p).

    Attributes
    ----------
    parameter
        p_H.
    frequency
        ω of the critical pair, rad per unit of the system's time.
    eigenvector
        q, complex, shape (n,), of the linearisation at y_e(p_H) for the eigenvalue iω.
    unstable_side
        +1 if the equilibrium is unstable for p > p_H, −1 if for p < p_H.
    """

    parameter: float
    frequency: float
    eigenvector: NDArray[np.complex128]
    unstable_side: int


@dataclass(frozen=True)
class Branch:
    """Periodic orbits along a branch, from its Hopf point.

    Attributes
    ----------
    hopf
        The Hopf point the branch starts from.
    orbits
        The orbits in the order of the branch.
    amplitudes
        ``measure(orbit)`` of each orbit (default ‖y₀ − y_e(p)‖ on its section).
    folds
        Parameters where the branch turns back (between two orbits, linearly).
    bifurcation_type
        ``"supercritical"`` (small cycles on the unstable side, born stable),
        ``"subcritical"`` or ``"degenerate"`` (p(2a) − p(a) below the resolution: 10
        finite-difference steps, or 1e-5 of p_H with the flow's exact derivative).
    message
        Why the branch ended.
    """

    hopf: HopfPoint
    orbits: list[PeriodicOrbit] = field(repr=False)
    amplitudes: FloatArray
    folds: list[float]
    bifurcation_type: str
    message: str

    @property
    def parameters(self) -> FloatArray:
        return np.array([o.parameter for o in self.orbits])

    @property
    def stable(self) -> NDArray[np.bool_]:
        return np.array([o.stable for o in self.orbits])


def _turned(q: NDArray[np.complex128]) -> tuple[FloatArray, FloatArray]:
    """(Re q̂, Im q̂): q turned so that its real and imaginary parts are orthogonal, the real
    part the longer one and of unit length, and its largest component positive (an
    eigenvector's phase is arbitrary: the turn makes the section the same whatever
    phase the eigensolver returned)."""
    u, w = q.real, q.imag
    alpha = 0.5 * np.arctan2(-2.0 * (u @ w), u @ u - w @ w)
    turned = q * np.exp(1j * alpha)
    if np.linalg.norm(turned.imag) > np.linalg.norm(turned.real):
        turned = turned * 1j
    if turned.real[np.argmax(np.abs(turned.real))] < 0.0:
        turned = -turned
    scale = np.linalg.norm(turned.real)
    return turned.real / scale, turned.imag / scale


def _arclength(
    z_last: FloatArray, normal: FloatArray, tangent: FloatArray, scale: FloatArray, step: float
) -> tuple[Callable[..., FloatArray], Callable[..., tuple[FloatArray, ...]]]:
    """The two constraints of a pseudo-arclength corrector from the branch's last point
    ``z_last`` = (y₀, T, p), and their gradients: the section through its state normal to
    the flow there, and the step along the scaled tangent."""
    n = z_last.size - 2
    state = z_last[:n]

    def constraints(y: FloatArray, T: float, p: float) -> FloatArray:
        z_now = np.concatenate([y, [T, p]])
        return np.array([normal @ (y - state), tangent @ ((z_now - z_last) * scale) - step])

    def gradient(y: FloatArray, T: float, p: float) -> tuple[FloatArray, ...]:
        t_scaled = tangent * scale
        rows = np.vstack([normal, t_scaled[:n]])
        return rows, np.array([0.0, t_scaled[n]]), np.array([0.0, t_scaled[n + 1]])

    return constraints, gradient


def hopf_branch(
    flow: FlowMap,
    hopf: HopfPoint,
    equilibrium: Callable[[float], FloatArray],
    *,
    amplitude: float,
    steps: int = 20,
    ds: float = 0.1,
    p_bounds: tuple[float, float] = (-np.inf, np.inf),
    p_scale: float = 1.0,
    measure: Callable[[PeriodicOrbit], float] | None = None,
    stop: Callable[[PeriodicOrbit], bool] | None = None,
    tol: float = 1e-9,
    max_iter: int = 15,
    describe: Callable[[float], str] | None = None,
) -> Branch:
    """The branch of periodic orbits from ``hopf``, continued by pseudo-arclength.

    Parameters
    ----------
    flow
        The system.
    hopf
        Its Hopf point.
    equilibrium
        ``equilibrium(p)``: y_e(p), shape (n,).
    amplitude
        a of the first orbit on the section along Re q̂ (the second has 2a); small
        enough that the cycle is near its Hopf limit, large enough to be resolved.
    steps
        Orbits after the first two.
    ds
        Arclength step in the scaled (y₀, T, p) (state by the first orbit's amplitude,
        period by the Hopf period, parameter by ``p_scale``); halved on a failed
        step (down to ds/64), grown by 1.5 after a quick one.
    p_bounds
        The branch ends when p leaves them.
    measure
        The amplitude of an orbit for the branch's record; default ‖y₀ − y_e(p)‖.
    stop
        ``stop(orbit)``: True ends the branch after that orbit (contact, say).
    tol, max_iter
        Newton convergence (as :func:`~foilbearing.bifurcation.shooting.periodic_orbit`).
    describe
        ``describe(p)``: the parameter as the branch's message shows it (default ``p = …``).
    """
    said = describe or (lambda value: f"p = {value:g}")
    re_q, im_q = _turned(np.asarray(hopf.eigenvector, np.complex128))
    p_h = hopf.parameter
    period_h = 2.0 * np.pi / hopf.frequency
    fd = flow.fd_step

    def measured(orbit: PeriodicOrbit) -> float:
        if measure is not None:
            return measure(orbit)
        return float(np.linalg.norm(orbit.state - equilibrium(orbit.parameter)))

    def d_equilibrium(p: float) -> FloatArray:
        h = fd * (1.0 + abs(p))
        return (equilibrium(p + h) - equilibrium(p)) / h

    def solve(
        y: FloatArray,
        T: float,
        p: float,
        constraints: Callable[..., FloatArray],
        gradient: Callable[..., tuple[FloatArray, ...]],
    ) -> PeriodicOrbit:
        """Newton on [φ_T(y; p) − y; constraints] for (y, T, p) (two constraints)."""
        y = np.array(y, float)
        res = np.inf
        for it in range(1, max_iter + 1):
            end = flow.advance(y, T, p)
            res = float(np.linalg.norm(end - y)) / (1.0 + float(np.linalg.norm(y)))
            if not np.isfinite(res):  # no flow there (contact, or a speed off the case's)
                break
            g = constraints(y, T, p)
            hp = fd * (1.0 + abs(p))
            dphi_dp = (flow.advance(y, T, p + hp) - end) / hp
            cols = np.column_stack([flow.field(end, p), dphi_dp])
            rows, d_t, d_p = gradient(y, T, p)
            corner = np.column_stack([d_t, d_p])
            rhs = -np.concatenate([end - y, g])
            step = bordered_solve(flow, y, T, p, end, cols, rows, corner, rhs)
            n = y.size
            y += step[:n]
            T += step[n]
            p += step[n + 1]
            small = np.linalg.norm(step[:n]) <= np.sqrt(tol) * (1.0 + np.linalg.norm(y))
            if res <= tol and small and np.max(np.abs(g)) <= np.sqrt(tol):
                values = floquet_multipliers(flow, y, T, p)
                return PeriodicOrbit(y, T, p, values, it, res)
            if not (np.isfinite(T) and T > 0.0 and np.isfinite(p)):
                break
        raise ShootingError(f"continuation corrector did not converge (residual {res:.3g})")

    def on_amplitude(a: float, guess: tuple[FloatArray, float, float]) -> PeriodicOrbit:
        def constraints(y: FloatArray, T: float, p: float) -> FloatArray:
            d = y - equilibrium(p)
            return np.array([im_q @ d, re_q @ d - a])

        def gradient(y: FloatArray, T: float, p: float) -> tuple[FloatArray, ...]:
            de = d_equilibrium(p)
            return np.vstack([im_q, re_q]), np.zeros(2), np.array([-im_q @ de, -re_q @ de])

        return solve(*guess, constraints, gradient)

    y_h = equilibrium(p_h)
    first = on_amplitude(amplitude, (y_h + amplitude * re_q, period_h, p_h))
    second = on_amplitude(
        2.0 * amplitude, (first.state + amplitude * re_q, first.period, first.parameter)
    )
    # The direction of p(a) between the two first orbits (p − p_H ≈ c a²): it does not
    # depend on how closely p_H itself is known.
    shift = second.parameter - first.parameter
    # Resolution of a cycle's parameter: the finite differences' step, or, with the
    # flow's exact derivative (``tangent``), the shooting's own convergence.
    resolution = (10.0 * fd if flow.tangent is None else 1e-5) * (1.0 + abs(p_h))
    kind = (
        "degenerate"
        if abs(shift) <= resolution
        else "supercritical"
        if np.sign(shift) == hopf.unstable_side
        else "subcritical"
    )

    n = y_h.size
    scale = np.concatenate(
        [np.full(n, 1.0 / max(amplitude, 1e-300)), [1.0 / period_h], [1.0 / p_scale]]
    )

    def packed(o: PeriodicOrbit) -> FloatArray:
        return np.concatenate([o.state, [o.period, o.parameter]])

    orbits = [first, second]
    folds: list[float] = []
    message = f"{steps} steps done"
    step = ds
    for _ in range(steps):
        prev, last = orbits[-2], orbits[-1]
        if stop is not None and stop(last):
            message = f"stopped at {said(last.parameter)} (the stop condition)"
            break
        if not p_bounds[0] <= last.parameter <= p_bounds[1]:
            message = f"left the parameter range at {said(last.parameter)}"
            break
        secant = (packed(last) - packed(prev)) * scale
        tangent = secant / np.linalg.norm(secant)
        normal = flow.field(last.state, last.parameter)
        normal = normal / np.linalg.norm(normal)
        z_last = packed(last)
        done = None
        while step >= ds / 64.0:
            z = z_last + step * tangent / scale

            constraints, gradient = _arclength(z_last, normal, tangent, scale, step)
            try:
                done = solve(z[:n], float(z[n]), float(z[n + 1]), constraints, gradient)
                break
            except ShootingError:
                step *= 0.5
        if done is None:
            message = (
                f"the corrector failed at {said(last.parameter)} with the step down to "
                f"{step:.3g}: shorten ds, or tighten the flow's tolerances"
            )
            break
        turn = (done.parameter - last.parameter) * (last.parameter - prev.parameter)
        if turn < 0.0:
            folds.append(last.parameter)
        orbits.append(done)
        if done.iterations <= 3:
            step = min(1.5 * step, 4.0 * ds)
    amplitudes = np.array([measured(o) for o in orbits])
    return Branch(hopf, orbits, amplitudes, folds, kind, message)
