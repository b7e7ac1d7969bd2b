"""Reference stepper: ``scipy.integrate.solve_ivp`` (BDF) on the same semi-discrete system.

The fast stepper of :mod:`foilbearing.orbit` integrates ``dQ(y)/dt = f(y, t)``
implicitly. Here the same system is written explicitly, ``dy/dt = M(y)⁻¹ …``:
``d(PH)/dt = H dP/dt + P dH/dt`` and the actuator part of ``dH/dt`` depends on
the row mean of ``dP/dt``, so each θ-row is a diagonal-plus-rank-one system,
solved by the Sherman–Morrison formula. solve_ivp's BDF then integrates it with
a finite-difference Jacobian on the known sparsity pattern. It is slow and
exists to check the fast stepper (tests and ``benchmarks/bench_orbit.py``).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from foilbearing.orbit import OrbitSimulation

__all__ = ["reference_orbit"]

FloatArray = NDArray[np.float64]


def _derivative(sim: OrbitSimulation, t: float, y: FloatArray) -> FloatArray:
    sys_ = sim.system
    g = sys_.grid
    nt, nz = g.n_theta, g.n_z
    volts = sim.volts(t)
    inp = sim.inputs(t, volts)
    f = sys_.rhs(y, inp)
    P, _U, _eps, v = sys_.split(y)
    H, _q = sys_.film(y, inp.preload)
    dt = 1e-6
    preload_rate = (sim.preload(sim.volts(t + dt)) - sim.preload(sim.volts(t - dt))) / (2 * dt)
    n = sys_.n
    du = f[n : n + nt]
    dh_known = sys_.cos_t * v[0] + sys_.sin_t * v[1] - preload_rate + du  # (nt,)
    b = f[:n].reshape(nt, nz) - P * dh_known[:, None]
    active = (P.mean(axis=1) - 1.0 > 0.0).astype(float)
    a = P * (sys_.c_act * active)[:, None]  # coefficient of the row mean of dP/dt
    d_inv_b = b / H
    d_inv_a = a / H
    corr = d_inv_b.mean(axis=1) / (1.0 + d_inv_a.mean(axis=1))
    dp = d_inv_b - d_inv_a * corr[:, None]
    return np.concatenate([dp.ravel(), du, f[n + nt :]])


def _sparsity(sim: OrbitSimulation) -> sp.csr_matrix:
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
        lambda t, y: _derivative(sim, t, y),
        (0.0, t_end),
        y_start,
        method="BDF",
        t_eval=times,
        rtol=rtol,
        atol=atol,
        jac_sparsity=_sparsity(sim),
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
