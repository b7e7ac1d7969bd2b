"""Benchmark for route 2 of issue 30: does a fourth-order axial stencil on 4-6 cells give the
accuracy of 12 second-order ones? Prints its figures.

Run: .venv/bin/python benchmarks/bench_axial_order.py

A measurement before any kernel is rewritten. It uses a stand-alone finite-difference
solver, not the project's kernels. The solver takes the compressible Reynolds equation on
the default case's bearing:

- a rigid, aligned journal at eccentricity 0.5, so H = 1 + ε cos θ;
- suction retained;
- the half bearing with mid-plane symmetry, like the project's grid;
- Λ at 30 and 90 krpm.

In θ it is second order, with n_θ = 96 for every n_z, so only the axial error changes.
Because H does not depend on Z (aligned journal; the foil deflects by the axially averaged
pressure), the axial term is H³ ∂²(P²/2)/∂Z². It is discretised at the cell centres two
ways:

- **second order**: the 3-point difference, with the mid-plane and the ambient edge as
  ghost cells (P² = 1 on the edge face);
- **fourth order**: the 5-point difference, with mirrored ghosts at the mid-plane and ghosts
  beyond the edge from the cubic through the last three centres and the edge value.

The load W and its derivative dW/dε (central differences, ε ± 0.01) are
printed. The load is integrated in Z through a cubic spline of each θ-row (fourth order, the
mirror image and the edge value included); in θ by the periodic midpoint rule. Each result
is compared with the Richardson extrapolation of the fourth-order runs on 48 and 96 cells.

The answer is in docs/development/orbit-performance.md ("Route 2 measured").
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.interpolate import CubicSpline

from foilbearing.case import default_case

N_THETA = 96
ECC = 0.5
RPM = math.pi / 30.0


def _axial_second(psi: np.ndarray, dz: float) -> np.ndarray:
    """∂²ψ/∂Z² at the centres, second order (ψ = P²; ψ = 1 on the edge face)."""
    ext = np.concatenate([psi[:, :1], psi, 2.0 - psi[:, -1:]], axis=1)
    return (ext[:, 2:] - 2.0 * ext[:, 1:-1] + ext[:, :-2]) / dz**2


def _axial_fourth(psi: np.ndarray, dz: float) -> np.ndarray:
    """∂²ψ/∂Z² at the centres, fourth order (mirrored ghosts at the mid-plane; beyond the
    edge, the cubic through the last three centres and ψ = 1 on the edge face)."""
    n = psi.shape[1]
    # Cubic through (x, ψ) at x = n-3, n-2, n-1 (centres, in cells) and n - 1/2 (edge).
    xs = np.array([n - 3.0, n - 2.0, n - 1.0, n - 0.5])

    def lagrange(x: float) -> np.ndarray:
        w = np.ones(4)
        for a in range(4):
            for b in range(4):
                if a != b:
                    w[a] *= (x - xs[b]) / (xs[a] - xs[b])
        return w

    g1, g2 = lagrange(n), lagrange(n + 1.0)
    last = np.concatenate([psi[:, -3:], np.ones((psi.shape[0], 1))], axis=1)
    ghost1 = last @ g1
    ghost2 = last @ g2
    ext = np.concatenate([psi[:, 1:2], psi[:, :1], psi, ghost1[:, None], ghost2[:, None]], axis=1)
    c = ext[:, 2:-2]
    return (-ext[:, 4:] + 16.0 * ext[:, 3:-1] - 30.0 * c + 16.0 * ext[:, 1:-3] - ext[:, :-4]) / (
        12.0 * dz**2
    )


def _residual(
    p: np.ndarray, n_z: int, lam: float, z_end: float, order: int, ecc: float = ECC
) -> np.ndarray:
    P = p.reshape(N_THETA, n_z)
    dt = 2.0 * math.pi / N_THETA
    dz = z_end / n_z
    theta = (np.arange(N_THETA) + 0.5) * dt
    H = (1.0 + ecc * np.cos(theta))[:, None] * np.ones((1, n_z))
    Hf = 1.0 + ecc * np.cos(theta + 0.5 * dt)  # face i+1/2
    Pe = np.roll(P, -1, axis=0)
    Pf = 0.5 * (P + Pe)
    q = Pf * Hf[:, None] ** 3 * (Pe - P) / dt - lam * Hf[:, None] * Pf  # θ-flux at i+1/2
    r_theta = (q - np.roll(q, 1, axis=0)) / dt
    psi = P * P
    lap = _axial_second(psi, dz) if order == 2 else _axial_fourth(psi, dz)
    return (r_theta + 0.5 * H**3 * lap).ravel()


def _jacobian(
    p: np.ndarray, n_z: int, lam: float, z_end: float, order: int, ecc: float
) -> sp.csr_matrix:
    """Finite-difference Jacobian by colouring (θ stencil 3 wide, Z stencil 5 wide)."""
    n = p.size
    r0 = _residual(p, n_z, lam, z_end, order, ecc)
    ii, jj = np.divmod(np.arange(n), n_z)
    rows, cols, vals = [], [], []
    eps = 1e-7
    for ci in range(3):
        for cj in range(5):
            cols_c = np.flatnonzero((ii % 3 == ci) & (jj % 5 == cj))
            if cols_c.size == 0:
                continue
            dp = p.copy()
            dp[cols_c] += eps
            dr = (_residual(dp, n_z, lam, z_end, order, ecc) - r0) / eps
            for col in cols_c:
                i, j = divmod(col, n_z)
                for di in (-1, 0, 1):
                    for dj in range(-2, 3):
                        jr = j + dj
                        if 0 <= jr < n_z:
                            row = ((i + di) % N_THETA) * n_z + jr
                            rows.append(row)
                            cols.append(col)
                            vals.append(dr[row])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, n))


def _solve(n_z: int, lam: float, z_end: float, order: int, ecc: float = ECC) -> np.ndarray:
    p = np.ones(N_THETA * n_z)
    for _ in range(40):
        r = _residual(p, n_z, lam, z_end, order, ecc)
        dp = spla.spsolve(_jacobian(p, n_z, lam, z_end, order, ecc).tocsc(), r)
        p = p - dp
        if np.max(np.abs(dp)) < 1e-12:
            break
    else:
        raise RuntimeError(f"no convergence on n_z = {n_z}, order {order}")
    return p.reshape(N_THETA, n_z)


def _load(P: np.ndarray, z_end: float) -> tuple[float, float]:
    """(W_X, W_Y) of the half bearing, dimensionless: ∫∫ (P − 1)(cos θ, sin θ) dθ dZ."""
    n_z = P.shape[1]
    dz = z_end / n_z
    z = (np.arange(n_z) + 0.5) * dz
    zs = np.concatenate([[-z_end], -z[::-1], z, [z_end]])
    g = P - 1.0
    ext = np.concatenate([np.zeros((g.shape[0], 1)), g[:, ::-1], g, np.zeros((g.shape[0], 1))], 1)
    axial = np.array([CubicSpline(zs, row).integrate(0.0, z_end) for row in ext])
    theta = (np.arange(P.shape[0]) + 0.5) * 2.0 * math.pi / P.shape[0]
    dt = 2.0 * math.pi / P.shape[0]
    return float(np.sum(axial * np.cos(theta)) * dt), float(np.sum(axial * np.sin(theta)) * dt)


def _readouts(n_z: int, lam: float, z_end: float, order: int) -> np.ndarray:
    """(W_X, W_Y) at ε = ECC, and the stiffness −dW/dε by central differences (±0.01)."""
    w = np.array(_load(_solve(n_z, lam, z_end, order), z_end))
    up = np.array(_load(_solve(n_z, lam, z_end, order, ECC + 0.01), z_end))
    down = np.array(_load(_solve(n_z, lam, z_end, order, ECC - 0.01), z_end))
    return np.concatenate([w, (up - down) / 0.02])


def main() -> None:
    case = default_case()
    b = case.bearing
    z_end = b.length / (2.0 * b.radius)
    print(
        f"rigid aligned journal, ε = {ECC}, suction retained, n_θ = {N_THETA}, "
        f"Z_end = {z_end:.3f}; |Δ|/|ref| of the load W and of its derivative dW/dε, against "
        "the fourth-order runs on 48 and 96 cells extrapolated (Richardson, p = 4):",
        flush=True,
    )
    for rpm in (30e3, 90e3):
        lam = case.bearing_number(rpm * RPM)
        fine = _readouts(48, lam, z_end, 4)
        finer = _readouts(96, lam, z_end, 4)
        ref = finer + (finer - fine) / 15.0
        print(f"  {rpm / 1e3:.0f} krpm (Λ = {lam:.2f}):")
        for order in (2, 4):
            line = []
            for n_z in (3, 4, 6, 8, 12, 24):
                got = _readouts(n_z, lam, z_end, order)
                e_w = np.hypot(*(got[:2] - ref[:2])) / np.hypot(*ref[:2])
                e_k = np.hypot(*(got[2:] - ref[2:])) / np.hypot(*ref[2:])
                line.append(f"{n_z}: {100 * e_w:.3f} / {100 * e_k:.3f} %")
            print(f"    order {order}, n_z " + ", ".join(line), flush=True)


if __name__ == "__main__":
    main()
