"""Timing of the steady foil-coupled Reynolds solver on the default-like grid.

Run: ``python benchmarks/bench_reynolds.py`` (prints its figures; not a test).

Case: 96×12 half-bearing grid, L/(2R) = 0.875, Λ = 0.23 (about 50 krpm),
three sinusoidal preload lobes of 0.6 C at 60/180/300° (docs/model.md §3, r_p),
bump compliance c = p_a/(C k_b) = 101325/(100e-6 · 8.69e9). The journal sits
at ε_X = 0.15: with ε_X = 0.5 the 0.6 C lobe at 180° would close the film
(h_rigid = 1 − 0.5 − 0.6 < 0), so ε_X is chosen to give H_min = 0.25 C, the
"quarter of C" of docs/model.md §4.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from foilbearing.reynolds import FilmGrid, Workspace, film_force, solve_steady
from foilbearing.reynolds.assembly import _assemble


def default_like_film(grid: FilmGrid, eps_x: float = 0.15, preload: float = 0.6) -> np.ndarray:
    th = grid.theta
    h = 1.0 + eps_x * np.cos(th)
    for centre in np.radians([60.0, 180.0, 300.0]):
        d = np.angle(np.exp(1j * (th - centre)))
        h -= np.where(np.abs(d) <= np.pi / 3, 0.5 * preload * (np.cos(3 * d) + 1.0), 0.0)
    return np.repeat(h[:, None], grid.n_z, axis=1)


def best_ms(fn: Callable[[], object], repeat: int = 7, number: int = 20) -> float:
    """Best-of-``repeat`` mean time of ``number`` calls, in ms (robust to load)."""
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t0) / number)
    return 1e3 * min(times)


def main() -> None:
    grid = FilmGrid(96, 12, 0.875)
    h_rigid = default_like_film(grid)
    compliance = np.full(grid.n_theta, 101325.0 / (100e-6 * 8.69e9))
    lam = 0.23
    ws = Workspace(grid)

    sol = solve_steady(grid, h_rigid, compliance, lam, workspace=ws)  # warm-up (JIT)
    fx, fy = film_force(grid, sol.P)
    t_solve = best_ms(lambda: solve_steady(grid, h_rigid, compliance, lam, workspace=ws))
    t_solve_rigid = best_ms(lambda: solve_steady(grid, h_rigid, 0.0, lam, workspace=ws))
    rigid = solve_steady(grid, h_rigid, 0.0, lam, workspace=ws)

    P = sol.P
    t_assemble = best_ms(lambda: _assemble(ws, P, h_rigid, compliance, lam, True), number=200)
    n = grid.size
    jt = sp.csc_matrix((ws.jc, ws.c_indices, ws.c_indptr), shape=(n, n))
    opts = {"permc_spec": "MMD_AT_PLUS_A", "options": {"SymmetricMode": True}}
    t_factor = best_ms(lambda: splu(jt, **opts))
    lu = splu(jt, **opts)
    t_back = best_ms(lambda: lu.solve(ws.res.ravel(), trans="T"), number=200)
    jt5 = sp.csc_matrix((ws.jp, ws.indices, ws.indptr), shape=(n, n))
    t_factor5 = best_ms(lambda: splu(jt5, **opts))

    print(f"grid {grid.n_theta}x{grid.n_z}, L/(2R) = {grid.half_length}, Λ = {lam}")
    print(
        f"film: H_min = {sol.H.min():.3f} (rigid {h_rigid.min():.3f}), P_max = {sol.P.max():.3f}, "
        f"F = ({fx:.4f}, {fy:.4f}) p_a R²"
    )
    print(
        f"foil-coupled solve: {t_solve:.2f} ms, {sol.iterations} Newton iterations, "
        f"residual {sol.residual:.1e}, converged={sol.converged}"
    )
    print(f"rigid solve:        {t_solve_rigid:.2f} ms, {rigid.iterations} Newton iterations")
    print(f"assembly (residual + dR/dP + dR/dH + coupled blocks): {t_assemble:.3f} ms")
    print(
        f"sparse LU, coupled J ({jt.nnz} nnz, L+U {lu.L.nnz + lu.U.nnz}): {t_factor:.3f} ms; "
        f"back-substitution {t_back:.3f} ms"
    )
    print(f"sparse LU, 5-point J ({jt5.nnz} nnz): {t_factor5:.3f} ms")


if __name__ == "__main__":
    main()
