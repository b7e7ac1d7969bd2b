"""The orbit's reference: ``scipy.integrate.solve_ivp`` (BDF) on the same semi-discrete system.

The fast stepper of :mod:`foilbearing.orbit` integrates ``dQ(y)/dt = f(y, t)``
implicitly. Here the same system is written explicitly, ``dy/dt = M(y)⁻¹ …``:
``d(PH)/dt = H dP/dt + P dH/dt`` and the actuator part of ``dH/dt`` depends on
the row mean of ``dP/dt``, so each θ-row is a diagonal-plus-rank-one system,
solved by the Sherman–Morrison formula. Lobes that follow their stacks
(``preload_response = "lobe"``, ``dynamics = "compliant"``) add ``Σ_n lobe_n(θ)
dD_n/dt`` to ``dH/dt``, with ``dD_n/dt`` the change of the pressure at stinger n: n_lobe
further unknowns, eliminated by a small dense solve over the row solutions.
solve_ivp's BDF then integrates it with a finite-difference Jacobian on the
known sparsity pattern. It is slow and exists to check the fast stepper (a test oracle:
tests and ``benchmarks/bench_ivp_orbit.py`` import it, production never does).

Under top-foil lift-off the film holds no sub-ambient pressure: here as the
projected dynamics of that constraint, independent of the fast stepper's
complementarity rows. No cell's pressure may fall faster than a relaxation
towards ambient, ``dP/dt = max(dP/dt|free, (1 − P)/τ)``: a cell at ambient
whose pressure would fall is held there, and one below it returns. The law is
continuous in P (it has no threshold at P = 1), so which cells are held does
not jump with the round-off of a state; a law that held a cell only once it
was at or below ambient did, and solve_ivp's cost swung with it, from 14 s to
over 15 minutes on the lift-off test (docs/development/orbit-performance.md, "The
lift-off reference"). The rows' rank-one systems are solved with the held
cells' rates given. The reference converges to the fast stepper as τ → 0
(measured on the test segment, max |Δe| over the orbit's extent: 0.02 % at
τ = 1e-7 and 1e-8 s, the default, 0.1 % at 1e-9 s).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from foilbearing.orbit import OrbitSimulation

__all__ = ["reference_orbit", "state_derivative", "state_sparsity"]

FloatArray = NDArray[np.float64]


#: Relaxation time of a held cell back to ambient pressure, s (lift-off).
HOLD_TIME = 1e-8


def _row_rates(
    b: FloatArray,
    a: FloatArray,
    P: FloatArray,
    H: FloatArray,
    held: FloatArray,
    rate: FloatArray,
    w: FloatArray,
) -> FloatArray:
    """dP/dt of each cell from ``H dP/dt + P a mean_row(dP/dt) = b``, held cells given ``rate``.

    ``b``, ``P``, ``held`` (0/1), ``rate``: (n_theta, n_z); ``a`` and ``H``: (n_theta,);
    ``w`` (n_z,) the axial-mean weights (``1/n_z`` at second order). Per row:
    ``m (1 + a Σ_free w P/H) = Σ_free w b/H + Σ_held w rate``.
    """
    free = 1.0 - held
    num = (free * b) @ w / H + (held * rate) @ w
    den = 1.0 + a * ((free * P) @ w) / H
    m = num / den
    return free * (b - P * (a * m)[:, None]) / H[:, None] + held * rate


def _film_rates(
    sim: OrbitSimulation,
    b: FloatArray,
    a: FloatArray,
    P: FloatArray,
    H: FloatArray,
    held: FloatArray,
    rate: FloatArray,
) -> FloatArray:
    """dP/dt of each cell from ``H dP/dt + P (a mean_row(dP/dt) + Σ_n lobe_n ξ_n) = b``.

    ``ξ_n = dD_n/dt = gain_n · lobe_rows_n @ mean_row(dP/dt)``, the rate of the lobes
    that follow their stacks; without such lobes this is :func:`_row_rates`. The
    row solve is affine in b, so ξ solves ``(I + G M R(P lobe)) ξ = G M R(b)`` with R
    the row solve of the held cells' rates removed (:func:`_row_rates`), M the mean at
    the stingers and G the gains.
    """
    sys_ = sim.system
    w = sys_.grid.axial.mean_w
    dp = _row_rates(b, a, P, H, held, rate, w)
    if sys_.n_lobe == 0:
        return dp
    gain = sys_.lobe_gain(P)
    zero = np.zeros_like(P)
    cols = [_row_rates(P * lobe[:, None], a, P, H, held, zero, w) for lobe in sys_.lobes]
    at_stingers = gain[:, None] * sys_.lobe_rows  # ξ = at_stingers @ mean_row(dP/dt)
    small = np.eye(sys_.n_lobe) + np.column_stack([at_stingers @ (c @ w) for c in cols])
    xi = np.linalg.solve(small, at_stingers @ (dp @ w))
    return dp - sum((x * c for x, c in zip(xi, cols, strict=True)), np.zeros_like(P))


def state_derivative(sim: OrbitSimulation, t: float, y: FloatArray) -> FloatArray:
    sys_ = sim.system
    g = sys_.grid
    nt, nz = g.n_theta, g.n_z
    volts = sim.volts(t)
    inp = sim.inputs(t, volts)
    f = sys_.rhs(y, inp)
    P, _U, _eps, v = sys_.split(y)
    H, _q = sys_.film(y, inp.preload)
    dt = 1e-6
    preload_rate = (
        sim.preload_at(t + dt, sim.volts(t + dt)) - sim.preload_at(t - dt, sim.volts(t - dt))
    ) / (2 * dt)
    n = sys_.n
    du = f[n : n + nt]
    dh_known = sys_.cos_t * v[0] + sys_.sin_t * v[1] - preload_rate + du  # (nt,)
    b = f[:n].reshape(nt, nz) - P * dh_known[:, None]
    active = (g.gauge_mean(P) > 0.0).astype(float)
    a = sys_.c_act * active  # coefficient of P times the row mean of dP/dt
    h_row = H[:, 0]
    no_hold = np.zeros_like(P)
    dp = _film_rates(sim, b, a, P, h_row, no_hold, no_hold)
    if sys_.lift_off:
        relax = (1.0 - P) / HOLD_TIME
        held = (relax > dp).astype(float)
        for _ in range(8):  # holding cells changes the others' rates through the foil
            dp = _film_rates(sim, b, a, P, h_row, held, relax)
            more = ((relax > dp) & (held == 0.0)).astype(float)
            if not more.any():
                break
            held = np.maximum(held, more)
    return np.concatenate([dp.ravel(), du, f[n + nt :]])


def state_sparsity(sim: OrbitSimulation) -> sp.csr_matrix:
    sys_ = sim.system
    g = sys_.grid
    nt, nz, n = g.n_theta, g.n_z, sys_.n
    i = np.arange(nt)
    blocks = sp.csr_matrix(
        (np.ones(3 * nt), (np.repeat(i, 3), np.stack([(i - 1) % nt, i, (i + 1) % nt], 1).ravel())),
        shape=(nt, nt),
    )
    pp = sp.kron(blocks, np.ones((nz, nz)))
    pu = sp.kron(blocks, np.ones((nz, 1)))
    up = sp.kron(sp.eye(nt), np.ones((1, nz)))
    if sys_.n_lobe:  # a lobe's cells follow the pressure at its stinger
        lobe_cells = np.repeat(sys_.lobes != 0.0, nz, axis=1).T.astype(float)  # (n, n_lobe)
        stinger_cells = np.repeat(sys_.lobe_rows != 0.0, nz, axis=1).astype(float)
        pp = pp + sp.csr_matrix(lobe_cells @ stinger_cells)
    dense_cols = sp.csr_matrix(np.ones((n, 4)))
    top = sp.hstack([pp, pu, dense_cols])
    mid = sp.hstack([up, sp.eye(nt), sp.csr_matrix((nt, 4))])
    bottom = sp.hstack(
        [sp.csr_matrix(np.ones((4, n))), sp.csr_matrix((4, nt)), sp.csr_matrix(np.ones((4, 4)))]
    )
    return sp.vstack([top, mid, bottom]).tocsr()


def reference_orbit(
    sim: OrbitSimulation,
    t_end: float,
    *,
    y0: FloatArray | None = None,
    rtol: float = 1e-7,
    atol: float = 1e-9,
) -> dict[str, Any]:
    """Integrate ``sim`` from t = 0 to ``t_end`` with solve_ivp's BDF.

    Returns
    -------
    dict with ``time`` (s), ``e_x``, ``e_y`` (m) at the output sampling rate of
    ``sim.settings``, ``wall_time`` (s), ``nfev``, ``njev`` and solve_ivp's
    ``message``.
    """
    y_start = sim.initial_state() if y0 is None else y0
    times = np.arange(0.0, t_end + 1e-12, 1.0 / sim.settings.sample_rate)
    clock = time.perf_counter()
    sol = solve_ivp(
        lambda t, y: state_derivative(sim, t, y),
        (0.0, t_end),
        y_start,
        method="BDF",
        t_eval=times,
        rtol=rtol,
        atol=atol,
        jac_sparsity=state_sparsity(sim),
    )
    wall = time.perf_counter() - clock
    k = sim.system.n + sim.system.nt
    c = sim.case.bearing.clearance
    return {
        "time": sol.t,
        "e_x": sol.y[k] * c,
        "e_y": sol.y[k + 1] * c,
        "wall_time": wall,
        "nfev": sol.nfev,
        "njev": sol.njev,
        "message": sol.message,
        "success": sol.success,
    }
