"""Film and system assembly of the steady foil-coupled Reynolds equation.

The pieces that :mod:`foilbearing.reynolds.steady` (the Newton solver, whose
docstring states the equations), :mod:`foilbearing.reynolds.perturbed` and
:mod:`foilbearing.reynolds.transient` share: the :class:`Workspace` of one
grid, the film with the foil deflection ``H = h_rigid + c·max(p̄, 0)``, the
residual and Jacobians of Eq. (4) filled by the compiled kernels (top-foil
lift-off rows included), the film force and the checks of the inputs. All
quantities are dimensionless (P = p/p_a, H = h/C, forces in units of p_a R²).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from foilbearing.laws.lift_off import smoothed_edge
from foilbearing.reynolds import _kernels as kern
from foilbearing.reynolds.grid import FilmGrid

__all__ = [
    "Workspace",
    "coupled_system",
    "film_force",
    "film_thickness",
    "held_cells",
    "lift_off_weights",
    "set_unit_rows",
]

FloatArray = NDArray[np.float64]


@dataclass
class Workspace:
    """Sparsity patterns and buffers of one grid, reused across solves.

    Create once per grid (``Workspace(grid)``) and pass to
    :func:`coupled_system` / :func:`~foilbearing.reynolds.steady.solve_steady`.
    Not thread-safe: one workspace per concurrent solve.
    """

    grid: FilmGrid
    indptr: NDArray[np.int64] = field(init=False, repr=False)
    indices: NDArray[np.int64] = field(init=False, repr=False)
    c_indptr: NDArray[np.int64] = field(init=False, repr=False)
    c_indices: NDArray[np.int64] = field(init=False, repr=False)
    #: The grid's axial discretisation, as the kernels take it.
    axial: tuple[Any, ...] = field(init=False, repr=False)
    #: Position of each cell's diagonal entry in the stencil data.
    diag_slots: NDArray[np.int64] = field(init=False, repr=False)
    res: FloatArray = field(init=False, repr=False)
    h: FloatArray = field(init=False, repr=False)
    s: FloatArray = field(init=False, repr=False)
    jp: FloatArray = field(init=False, repr=False)
    jh: FloatArray = field(init=False, repr=False)
    jc: FloatArray = field(init=False, repr=False)
    #: Row of each entry of the stencil data.
    entry_rows: NDArray[np.int64] = field(init=False, repr=False)
    #: Cells held at ambient by lift-off at the last assembly (all False without lift-off).
    clamped: NDArray[np.bool_] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        g = self.grid
        self.indptr, self.indices, _ = kern.stencil_pattern(g.n_theta, g.n_z, g.axial_order)
        self.axial = tuple(g.axial)
        self.diag_slots = g.axial.slots[:, :, 3].ravel()
        self.c_indptr, self.c_indices = kern.coupled_pattern(g.n_theta, g.n_z)
        self.res = np.empty(g.shape)
        self.h = np.empty(g.shape)
        self.s = np.empty(g.n_theta)
        self.jp = np.empty(self.indices.size)
        self.jh = np.empty(self.indices.size)
        self.jc = np.empty(self.c_indices.size)
        self.entry_rows = np.repeat(np.arange(g.size), np.diff(self.indptr))
        self.clamped = np.zeros(g.size, dtype=bool)


def film_thickness(
    grid: FilmGrid, h_rigid: FloatArray, compliance: FloatArray, P: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Film with foil deflection, ``H = h_rigid + c · max(p̄, 0)``.

    Parameters
    ----------
    grid : FilmGrid
    h_rigid : ndarray, shape (n_theta, n_z)
    compliance : ndarray, shape (n_theta,)
        ``c_i = p_a/(C k(θ_i))``, dimensionless.
    P : ndarray, shape (n_theta, n_z)

    Returns
    -------
    H : ndarray, shape (n_theta, n_z)
    p_mean : ndarray, shape (n_theta,)
        ``axial_mean(P − 1)`` (:meth:`FilmGrid.gauge_mean`).
    """
    p_mean = grid.gauge_mean(P)
    return h_rigid + (compliance * np.maximum(p_mean, 0.0))[:, None], p_mean


def held_cells(
    grid: FilmGrid, P: FloatArray, H: FloatArray, lam: float, workspace: Workspace | None = None
) -> NDArray[np.bool_]:
    """The cells top-foil lift-off holds at ambient in the film (P, H) (n,).

    The ambient branch of ``min(d (P − 1), −R) = 0``
    (:mod:`foilbearing.reynolds.steady`), as the Newton iteration decides it; at
    a converged solution, the cells with P = 1 and a net outflow. ``workspace``: buffers of this grid (its residual and
    Jacobian buffers are overwritten).
    """
    ws = workspace if workspace is not None else Workspace(grid)
    p = np.ascontiguousarray(P, dtype=np.float64)
    h = np.ascontiguousarray(H, dtype=np.float64)
    kern.residual(p, h, lam, grid.d_theta, grid.d_z, ws.axial, ws.res)
    kern.jacobian_P(p, h, lam, grid.d_theta, grid.d_z, ws.axial, ws.jp)
    kern.lift_off_rows(
        p, ws.res, ws.jp, ws.jh, ws.jp, ws.diag_slots, ws.indptr, False, ws.clamped,
        grid.lift_off_width(lam), grid.lift_off_scale,
    )  # fmt: skip
    return ws.clamped.copy()


def lift_off_weights(grid: FilmGrid, P: FloatArray, res: FloatArray, lam: float) -> FloatArray:
    """Weight α of each cell's Reynolds row under the smoothed lift-off law (n,).

    With ``x = P − 1``, ``y = −R/d_ref`` and the law's width ``w = δ√Λ`` at bearing
    number ``lam`` (:meth:`FilmGrid.lift_off_width`), the cell's equation ``−(d_ref/2)(x + y
    − √((x − y)² + 4w²)) = 0`` has the row ``α ∂R/∂(P, H) − (1 − α) d_ref e_k``,
    ``α = (1 + (x − y)/√((x − y)² + 4w²))/2``; at the solution ``α = x/(x + y)``:
    1 where the film is free, 0 where it is held at ambient. The same weights as the
    compiled :func:`~foilbearing.reynolds._kernels.lift_off_rows`.

    Parameters
    ----------
    grid : FilmGrid
        With ``lift_off_smoothing`` > 0.
    P, res : ndarray, shape (n_theta, n_z)
        Pressure and its Reynolds residual R (cell-integrated net inflow).
    lam : float
        Bearing number Λ.
    """
    x = np.ravel(P) - 1.0
    y = -np.ravel(res) / grid.lift_off_scale
    return np.asarray(smoothed_edge(x, y, grid.lift_off_width(lam) ** 2)[1])


def set_unit_rows(
    data: NDArray[Any], rows: NDArray[np.int64], values: ArrayLike, n_theta: int, n_z: int
) -> None:
    """Make ``rows`` of a matrix on the foil-coupled pattern ``values·e_row`` (in place).

    ``data`` is the CSR data on :func:`~foilbearing.reynolds._kernels.coupled_pattern`
    (3 n_z entries a row, θ-blocks in sorted column order: the row's own block
    is first for i = 0, last for i = n_theta − 1, in the middle otherwise).
    """
    block = data.reshape(n_theta * n_z, 3 * n_z)
    block[rows] = 0.0
    i = rows // n_z
    own = np.where(i == 0, 0, np.where(i == n_theta - 1, 2, 1))
    block[rows, own * n_z + rows % n_z] = values


def _film(ws: Workspace, P: FloatArray, h_rigid: FloatArray, comp: FloatArray) -> None:
    """Fill ``ws.h`` and ``ws.s = dH_i/dp̄_i`` (the engaged rows' compliance; ``dH_i/dP_ik``
    is ``s_i`` times the axial-mean weight of k) without allocating fields."""
    p_mean = ws.grid.gauge_mean(P)
    active = p_mean > 0.0
    np.multiply(comp, np.where(active, p_mean, 0.0), out=ws.s)
    np.add(h_rigid, ws.s[:, None], out=ws.h)
    np.multiply(comp, active, out=ws.s)


def _assemble(
    ws: Workspace,
    P: FloatArray,
    h_rigid: FloatArray,
    comp: FloatArray,
    lam: float,
    coupled: bool,
    lift_off: bool = False,
) -> FloatArray:
    """Fill residual and Jacobian buffers (lift-off rows included); return the data of ``J_PP``."""
    g = ws.grid
    _film(ws, P, h_rigid, comp)
    kern.residual(P, ws.h, lam, g.d_theta, g.d_z, ws.axial, ws.res)
    kern.jacobian_P(P, ws.h, lam, g.d_theta, g.d_z, ws.axial, ws.jp)
    if coupled or lift_off:
        kern.jacobian_H(P, ws.h, lam, g.d_theta, g.d_z, ws.axial, ws.jh)
    if coupled:
        kern.coupled_jacobian(ws.jp, ws.jh, ws.s, g.n_z, ws.axial, ws.jc)
    if lift_off:
        kern.lift_off_rows(
            P, ws.res, ws.jp, ws.jh, ws.jc, ws.diag_slots, ws.indptr, coupled, ws.clamped,
            g.lift_off_width(lam), g.lift_off_scale,
        )  # fmt: skip
    else:
        ws.clamped[:] = False
    return ws.jc if coupled else ws.jp


def coupled_system(
    P: ArrayLike,
    grid: FilmGrid,
    h_rigid: ArrayLike,
    compliance: ArrayLike,
    lam: float,
    workspace: Workspace | None = None,
    *,
    lift_off: bool = False,
) -> tuple[FloatArray, sp.csr_matrix, sp.csr_matrix]:
    """Residual and Jacobians of the foil-coupled discrete Reynolds equation.

    For a bordered Newton on ``(P, ε_X, ε_Y)``: ``dR/dε_X = J_PH @ ∂H/∂ε_X``
    with ``∂H/∂ε_X = cos θ_i`` broadcast over ``j`` (flattened in C order).

    Parameters
    ----------
    P : array_like, shape (n_theta, n_z) or (n_theta*n_z,)
        Pressure ``p/p_a`` (> 0).
    grid : FilmGrid
    h_rigid : array_like, shape (n_theta, n_z)
        Film without foil deflection (journal, preload, housing), ``h/C``.
    compliance : array_like, shape (n_theta,)
        Foil compliance ``c_i = p_a/(C k(θ_i))``.
    lam : float
        Bearing number Λ.
    workspace : Workspace, optional
        Buffers of this grid; created if omitted.
    lift_off : bool
        Top-foil lift-off: the rows of the cells held at ambient are the
        complementarity rows (:mod:`foilbearing.reynolds.steady`); ``workspace.clamped`` marks them.

    Returns
    -------
    R : ndarray, shape (n_theta*n_z,)
        Cell-integrated residual (see :mod:`foilbearing.reynolds._kernels`).
    J_PP : scipy.sparse.csr_matrix, shape (n, n)
        ``dR/dP + dR/dH · dH/dP`` (total derivative at fixed ``h_rigid``).
    J_PH : scipy.sparse.csr_matrix, shape (n, n)
        ``dR/dH`` (partial, at fixed P), 5-point pattern.

    The returned arrays are copies; the workspace may be reused at once.
    """
    ws = workspace if workspace is not None else Workspace(grid)
    p = _as_field(grid, P, "P")
    h_r, comp = _check_film_inputs(grid, h_rigid, compliance)
    n = grid.size
    _film(ws, p, h_r, comp)
    if ws.h.min() <= 0.0:
        raise ValueError(
            f"the film is closed (min H = {ws.h.min():.3g}) for this P and h_rigid: "
            "the pressure does not open the compliant foil enough"
        )
    coupled = bool(np.any(comp != 0.0))
    data = _assemble(ws, p, h_r, comp, lam, coupled, lift_off)
    if not (coupled or lift_off):
        kern.jacobian_H(p, ws.h, lam, grid.d_theta, grid.d_z, ws.axial, ws.jh)
    j_ph = sp.csr_matrix((ws.jh.copy(), ws.indices, ws.indptr), shape=(n, n))
    indices, indptr = (ws.c_indices, ws.c_indptr) if coupled else (ws.indices, ws.indptr)
    j_pp = sp.csr_matrix((data.copy(), indices, indptr), shape=(n, n))
    return ws.res.ravel().copy(), j_pp, j_ph


def film_force(grid: FilmGrid, P: ArrayLike) -> tuple[float, float]:
    """Film force on the journal, ``(F_X, F_Y)/(p_a R²)``, full bearing length.

    ``F_X = ∫∫ (P − 1) cos θ dθ dZ``, ``F_Y`` with ``sin θ`` (docs/model.md §2): a
    pressure peak near θ = 180° pushes the journal towards −X.
    """
    p = _as_field(grid, P, "P")
    w_x, w_y = grid.force_weights()
    gauge = p - 1.0
    return float(np.sum(w_x * gauge)), float(np.sum(w_y * gauge))


def _as_field(grid: FilmGrid, a: ArrayLike, name: str) -> FloatArray:
    arr = np.asarray(a, dtype=np.float64)
    if arr.shape == (grid.size,):
        arr = arr.reshape(grid.shape)
    if arr.shape != grid.shape:
        raise ValueError(f"{name} must have shape {grid.shape} (n_theta, n_z), got {arr.shape}")
    return np.ascontiguousarray(arr)


def _check_film_inputs(
    grid: FilmGrid, h_rigid: ArrayLike, compliance: ArrayLike
) -> tuple[FloatArray, FloatArray]:
    h = np.asarray(h_rigid, dtype=np.float64)
    if h.shape == (grid.n_theta,):
        h = np.repeat(h[:, None], grid.n_z, axis=1)
    h = _as_field(grid, h, "h_rigid")
    c = np.asarray(compliance, dtype=np.float64)
    if c.ndim == 0:
        c = np.full(grid.n_theta, float(c))
    if c.shape != (grid.n_theta,):
        raise ValueError(f"compliance must have shape ({grid.n_theta},), got {c.shape}")
    if not np.all(np.isfinite(c)) or c.min() < 0.0:
        raise ValueError("compliance must be finite and >= 0 (c = p_a/(C k) with k > 0)")
    # Where the foil is compliant the journal may reach into the undeformed foil
    # (h_rigid <= 0): the film pressure opens it by c·p̄. A rigid surface may not.
    rigid_h = np.where(c[:, None] > 0.0, np.inf, h)
    if not np.all(np.isfinite(h)) or rigid_h.min() <= 0.0:
        bad = np.where(np.isfinite(h), rigid_h, -np.inf)
        i, j = np.unravel_index(int(np.argmin(bad)), h.shape)
        raise ValueError(
            f"h_rigid must be finite, and > 0 where the surface is rigid (film touches or "
            f"crosses the journal): h_rigid[{i}, {j}] = {h[i, j]!r} at "
            f"θ = {np.degrees(grid.theta[i]):.1f}°; reduce the eccentricity or the preload"
        )
    return h, np.ascontiguousarray(c)
