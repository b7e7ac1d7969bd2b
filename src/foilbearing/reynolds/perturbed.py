"""First-order (complex) perturbation of the Reynolds equation about a steady film.

The semi-discrete unsteady Reynolds equation (Eq. (4) of the paper) on the
finite-volume grid reads, cell by cell (τ = ωt, ``A = Δθ ΔZ``)::

    2Λ A d(P H)/dτ = R(P, H),

with ``R`` the steady residual of :mod:`foilbearing.reynolds._kernels`. For a
small harmonic perturbation ``P = P₀ + ΔP e^{jντ}``, ``H = H₀ + ΔH e^{jντ}``
(ν = ω_e/ω the excitation frequency ratio) this gives::

    (J_P − 2jνΛA diag(H₀)) ΔP + (J_H − 2jνΛA diag(P₀)) ΔH = 0,

with ``J_P = ∂R/∂P`` and ``J_H = ∂R/∂H`` the same Jacobians the static Newton
uses. The film perturbation is the journal's part plus the foil's,
``ΔH = ΔH_journal + S ΔP``, where ``S`` maps the pressures of a θ-row to the
deflection of the foil there: ``S[(i,j),(i,k)] = c_i w_k`` (``w_k`` the axial-mean
weights, ``1/n_z`` at second order) with the complex
dynamic compliance ``c_i`` (zero where the foil is not engaged). Under top-foil
lift-off the cells held at ambient pressure by the static solution stay there,
``ΔP = 0``: their rows are the linearisation of the same complementarity
condition the static Newton solves (:mod:`foilbearing.reynolds.steady`). At
ν = 0 and real ``c`` this is exactly the linearisation of the static system,
so static and dynamic results agree by construction. With a smoothed edge
(``FilmGrid.lift_off_smoothing`` > 0) no cell is held: every row is the
linearisation of the smoothed law, the cell's dynamic row times its weight α
less ``(1 − α) d_ref`` on the diagonal (docs/lift-off.md, "The smoothed edge").
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.assembly import (
    Workspace,
    held_cells,
    lift_off_weights,
    set_unit_rows,
)
from foilbearing.reynolds.blocksolve import factor_coupled
from foilbearing.reynolds.grid import FilmGrid

__all__ = ["foil_operator", "pressure_response", "reynolds_jacobians"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


def reynolds_jacobians(
    grid: FilmGrid, P: FloatArray, H: FloatArray, lam: float, workspace: Workspace | None = None
) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """``J_P = ∂R/∂P`` and ``J_H = ∂R/∂H`` at fixed film, CSR on the stencil pattern.

    Parameters
    ----------
    grid
        The finite-volume grid.
    P, H
        Pressure p/p_a and full film h/C (foil deflection included), shape (n_theta, n_z).
    lam
        Bearing number Λ.
    """
    ws = _jacobians_into(workspace, grid, P, H, lam)
    n = grid.size
    j_p = sp.csr_matrix((ws.jp.copy(), ws.indices, ws.indptr), shape=(n, n))
    j_h = sp.csr_matrix((ws.jh.copy(), ws.indices, ws.indptr), shape=(n, n))
    return j_p, j_h


def _jacobians_into(
    workspace: Workspace | None, grid: FilmGrid, P: FloatArray, H: FloatArray, lam: float
) -> Workspace:
    """Fill ``ws.jp`` and ``ws.jh`` with the stencil data of J_P and J_H; the workspace."""
    ws = workspace if workspace is not None else Workspace(grid)
    p = np.ascontiguousarray(P, dtype=np.float64)
    h = np.ascontiguousarray(H, dtype=np.float64)
    kern.jacobian_P(p, h, lam, grid.d_theta, grid.d_z, ws.axial, ws.jp)
    kern.jacobian_H(p, h, lam, grid.d_theta, grid.d_z, ws.axial, ws.jh)
    return ws


def foil_operator(grid: FilmGrid, compliance: ComplexArray | FloatArray) -> sp.csr_matrix:
    """``S``: the film change of each cell per unit pressure change in its θ-row.

    ``ΔH[i, j] = c_i · mean_k ΔP[i, k]``: the foil responds to the axially
    averaged pressure (docs/model.md §3; the grid's axial-mean weights). ``compliance``
    is (n_theta,), zero where the foil is not engaged (p̄ <= 0).
    """
    block = np.ones((grid.n_z, 1)) * grid.axial.mean_w[None, :]
    return sp.kron(sp.diags(np.asarray(compliance)), block, format="csr")


def pressure_response(
    grid: FilmGrid,
    P: FloatArray,
    H: FloatArray,
    lam: float,
    nu: float,
    compliance: ComplexArray | FloatArray,
    dh_journal: FloatArray,
    workspace: Workspace | None = None,
    *,
    lift_off: bool = False,
) -> ComplexArray:
    """Complex pressure perturbations ΔP for given journal film perturbations.

    Parameters
    ----------
    grid
        The finite-volume grid.
    P, H
        Steady pressure and film (foil deflection included), (n_theta, n_z).
    lam
        Bearing number Λ.
    nu
        Frequency ratio ν = ω_e/ω (≥ 0).
    compliance
        Complex dynamic foil compliance c_i = p_a/(C k'(θ_i)), (n_theta,), zero
        where the foil is not engaged.
    dh_journal
        Film perturbations from the journal, shape (n_theta*n_z, m): one column
        per perturbed coordinate (e.g. cos θ and sin θ for ε_X and ε_Y).
    lift_off
        Top-foil lift-off: the cells the steady film holds at ambient
        (:func:`~foilbearing.reynolds.assembly.held_cells`) keep ΔP = 0. On a grid
        with a smoothed edge (``lift_off_smoothing`` > 0) every row is the
        linearisation of the smoothed law instead
        (:func:`~foilbearing.reynolds.assembly.lift_off_weights`).

    Returns
    -------
    ΔP, shape (n_theta*n_z, m), complex.
    """
    n = grid.size
    ws = workspace if workspace is not None else Workspace(grid)
    smoothed = lift_off and grid.lift_off_delta > 0.0
    if smoothed:
        kern.residual(
            np.ascontiguousarray(P, dtype=np.float64),
            np.ascontiguousarray(H, dtype=np.float64),
            lam, grid.d_theta, grid.d_z, ws.axial, ws.res,
        )  # fmt: skip
        alpha = lift_off_weights(grid, P, ws.res, lam)
    clamped = (
        held_cells(grid, P, H, lam, ws) if lift_off and not smoothed else np.zeros(n, dtype=bool)
    )
    ws = _jacobians_into(ws, grid, P, H, lam)
    jw = 2j * nu * lam * grid.d_theta * grid.d_z
    diag = ws.diag_slots
    j_pressure = ws.jp.astype(np.complex128)
    j_pressure[diag] -= jw * np.ravel(H)
    j_film = ws.jh.astype(np.complex128)  # ∂/∂H of R − 2Λ A jν P H
    j_film[diag] -= jw * np.ravel(P)
    if smoothed:  # each row the Reynolds row times α, less (1 − α) d_ref on the diagonal
        j_pressure *= alpha[ws.entry_rows]
        j_film *= alpha[ws.entry_rows]
        j_pressure[diag] -= (1.0 - alpha) * grid.lift_off_scale
    # The system (J_P − jw H₀) + (J_H − jw P₀) S on the foil-coupled pattern, where the
    # compiled block-cyclic LU factorises it (SuperLU if it cannot).
    s_row = np.asarray(compliance, dtype=np.complex128)
    system = np.empty(ws.c_indices.size, dtype=np.complex128)
    kern.coupled_jacobian(j_pressure, j_film, s_row, grid.n_z, ws.axial, system)
    if np.any(clamped):
        rows = np.flatnonzero(clamped)
        # Scaled like the Reynolds rows (|∂R/∂P| on the diagonal), which the block LU's
        # pivoting and conditioning checks expect; the right-hand side is zero there.
        scale = np.abs(ws.jp[diag[rows]])
        set_unit_rows(system, rows, np.where(scale > 0.0, scale, 1.0), grid.n_theta, grid.n_z)
        j_film[clamped[ws.entry_rows]] = 0.0
    lu = factor_coupled(system, ws.c_indices, ws.c_indptr, grid.n_theta, grid.n_z)
    film = sp.csr_matrix((j_film, ws.indices, ws.indptr), shape=(n, n))
    return lu.solve(-(film @ dh_journal).astype(np.complex128))
