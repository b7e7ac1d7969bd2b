"""Cell-centred finite-volume grid of the half bearing (mid-plane symmetry).

The journal is aligned with the bearing, so the film is symmetric about the
axial mid-plane and only ``Z = z/R`` in ``[0, Z_end]``, ``Z_end = L/(2R)``, is
solved. Index conventions used by every array of the Reynolds solvers:

* ``i = 0 .. n_theta-1`` is the circumferential cell, centre
  ``θ_i = (i + 1/2) Δθ``, ``Δθ = 2π/n_theta``, periodic (cell ``n_theta`` is
  cell ``0``); θ is measured counter-clockwise from the −X axis (docs/model.md §2).
* ``j = 0 .. n_z-1`` is the axial cell, centre ``Z_j = (j + 1/2) ΔZ``,
  ``ΔZ = Z_end/n_z``. The face ``j = -1/2`` lies on the mid-plane (symmetry,
  zero flux); the face ``j = n_z - 1/2`` lies on the bearing end, where
  ``P = 1`` is imposed, at ``ΔZ/2`` from the last centre.
* Fields are ``(n_theta, n_z)`` arrays; the unknown vector is their C-order
  flattening, ``k = i*n_z + j``.

The axial term ``H³ ∂²(P²)/∂Z²`` is taken at second order (``axial_order = 2``: the
3-point flux difference, the default) or at fourth order (``axial_order = 4``: the face
flux ``(ψ_{j−1} − 15ψ_j + 15ψ_{j+1} − ψ_{j+2})/(12ΔZ)`` of ``ψ = P²``, whose difference
is the 5-point fourth-order second derivative at the centres, with mirrored ghosts at the
mid-plane and, beyond the end, the cubic through the last three centres and ``ψ = 1`` on
the end face). The axial means and the force quadrature follow the order: the plain mean
at second order, a cubic-spline quadrature (the mirror image and ``P = 1`` at the end
included) at fourth order (docs/development/orbit-performance.md, "Route 2 built").
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from foilbearing.laws.lift_off import LiftOff

__all__ = ["AXIAL_ORDERS", "AxialStencil", "FilmGrid"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: The axial orders of the film's discretisation.
AXIAL_ORDERS = (2, 4)


class AxialStencil(NamedTuple):
    """The axial discretisation of a grid, as the compiled kernels take it (``tuple(...)``).

    Attributes
    ----------
    order : int
        2 or 4. At order 2 the kernels use their own 3-point loops (the tables below
        describe the same flux and are used by the twins and the tests).
    face_cols : ndarray of int64, shape (n_z, 4)
        Face ``f`` lies between the centres ``f`` and ``f + 1`` (``f = n_z − 1``: the
        bearing's end). Its flux is ``q_f = H_f³ (Σ_m face_coef[f, m] ψ[face_cols[f, m]]
        + face_const[f]) / ΔZ`` with ``ψ = P²``; unused entries have coefficient 0.
    face_coef : ndarray, shape (n_z, 4)
    face_const : ndarray, shape (n_z,)
    slots : ndarray of int64, shape (n_theta, n_z, 7)
        Position in the stencil data (:func:`~.kernels.stencil_pattern`) of the entry of
        row ``(i, j)`` in column ``(i−1, j)``, ``(i, j−2 .. j+2)``, ``(i+1, j)``; −1 where
        absent (order 2: the ±2 entries are absent).
    mean_w : ndarray, shape (n_z,)
        Axial-mean weights: ``p̄_i − 1 = Σ_j mean_w[j] (P[i, j] − 1)`` (ambient at the end).
    """

    order: int
    face_cols: IntArray
    face_coef: FloatArray
    face_const: FloatArray
    slots: IntArray
    mean_w: FloatArray


def _face_table(n_z: int, order: int) -> tuple[IntArray, FloatArray, FloatArray]:
    """Axial face fluxes as combinations of ``ψ = P²`` at the centres (see AxialStencil)."""
    cols = np.zeros((n_z, 4), dtype=np.int64)
    coef = np.zeros((n_z, 4))
    const = np.zeros(n_z)
    if order == 2:
        for f in range(n_z - 1):
            cols[f, :2] = (f, f + 1)
            coef[f, :2] = (-0.5, 0.5)
        # P_f (1 − P_a) with P = 1 on the end face, ΔZ/2 away: (1 − ψ)/ΔZ.
        cols[n_z - 1, 0] = n_z - 1
        coef[n_z - 1, 0] = -1.0
        const[n_z - 1] = 1.0
        return cols, coef, const
    # Ghosts beyond the end: the cubic through the centres n−3, n−2, n−1 and ψ = 1 on the
    # end face (positions in cells from the mid-plane: j + 1/2, and n for the end).
    xs = np.array([n_z - 2.5, n_z - 1.5, n_z - 0.5, float(n_z)])

    def ghost(x: float) -> FloatArray:
        w = np.ones(4)
        for a in range(4):
            for b in range(4):
                if a != b:
                    w[a] *= (x - xs[b]) / (xs[a] - xs[b])
        return w

    def expand(j: int) -> tuple[dict[int, float], float]:
        """ψ_j (j may be a ghost) as {centre: weight} and a constant."""
        if j < 0:
            return {-1 - j: 1.0}, 0.0
        if j < n_z:
            return {j: 1.0}, 0.0
        w = ghost(j + 0.5)
        return {n_z - 3: w[0], n_z - 2: w[1], n_z - 1: w[2]}, float(w[3])

    for f in range(n_z):
        acc: dict[int, float] = {}
        c = 0.0
        for j, a in zip((f - 1, f, f + 1, f + 2), (1.0, -15.0, 15.0, -1.0), strict=True):
            terms, k = expand(j)
            for col, wt in terms.items():
                acc[col] = acc.get(col, 0.0) + a * wt / 24.0
            c += a * k / 24.0
        items = sorted(acc.items())
        if len(items) > 4:
            raise AssertionError("a fourth-order face reaches more than 4 centres")
        for m, (col, wt) in enumerate(items):
            cols[f, m] = col
            coef[f, m] = wt
        const[f] = c
    return cols, coef, const


def _mean_weights(n_z: int, order: int) -> FloatArray:
    """Weights of the axial mean of a gauge field that vanishes on the end face."""
    if order == 2:
        return np.full(n_z, 1.0 / n_z)
    from scipy.interpolate import CubicSpline

    # Cubic spline through the mirror image, the centres and 0 at both ends, in units of
    # the half length; it is linear in the data, so the weights are its unit responses.
    z = (np.arange(n_z) + 0.5) / n_z
    zs = np.concatenate([[-1.0], -z[::-1], z, [1.0]])
    w = np.empty(n_z)
    for j in range(n_z):
        g = np.zeros(n_z)
        g[j] = 1.0
        ext = np.concatenate([[0.0], g[::-1], g, [0.0]])
        w[j] = CubicSpline(zs, ext).integrate(0.0, 1.0)
    return w


@dataclass(frozen=True)
class FilmGrid:
    """Finite-volume grid on ``θ ∈ [0, 2π)`` × ``Z ∈ [0, L/(2R)]``.

    Parameters
    ----------
    n_theta : int
        Number of circumferential cells (periodic), at least 8.
    n_z : int
        Number of axial cells on the half bearing, at least 2 (3 at fourth order).
    half_length : float
        ``Z_end = L/(2R)``, the dimensionless half length (> 0).
    axial_order : int
        Order of the axial discretisation, 2 (default) or 4 (module docstring).
    lift_off_smoothing : float
        κ >= 0, the smoothing of the lifted-off edge under top-foil lift-off: each cell
        obeys ``(P − 1)·q/Λ = δ²`` (q its net outflow in pressure units, ``−R/d_ref``,
        Λ the bearing number), ``δ = κ Δθ²``, in place of the sharp ``min(P − 1, q) = 0``;
        0 (default) is the sharp law (docs/lift-off.md, "The smoothed edge").
    """

    n_theta: int
    n_z: int
    half_length: float
    axial_order: int = 2
    lift_off_smoothing: float = 0.0

    def __post_init__(self) -> None:
        if int(self.n_theta) != self.n_theta or self.n_theta < 8:
            raise ValueError(
                f"FilmGrid.n_theta must be an integer >= 8 (periodic 5-point stencil), "
                f"got {self.n_theta!r}"
            )
        if int(self.n_z) != self.n_z or self.n_z < 2:
            raise ValueError(f"FilmGrid.n_z must be an integer >= 2, got {self.n_z!r}")
        if not (np.isfinite(self.half_length) and self.half_length > 0.0):
            raise ValueError(
                f"FilmGrid.half_length = L/(2R) must be finite and > 0, got {self.half_length!r}"
            )
        if self.axial_order not in AXIAL_ORDERS:
            raise ValueError(f"FilmGrid.axial_order must be 2 or 4, got {self.axial_order!r}")
        if not (np.isfinite(self.lift_off_smoothing) and self.lift_off_smoothing >= 0.0):
            raise ValueError(
                f"FilmGrid.lift_off_smoothing must be finite and >= 0, got "
                f"{self.lift_off_smoothing!r}"
            )
        if self.axial_order == 4 and self.n_z < 3:
            raise ValueError(
                f"FilmGrid.n_z must be >= 3 at axial order 4 (the end's cubic), got {self.n_z}"
            )

    @property
    def d_theta(self) -> float:
        """Circumferential cell width ``Δθ = 2π/n_theta`` (rad)."""
        return 2.0 * np.pi / self.n_theta

    @property
    def d_z(self) -> float:
        """Axial cell width ``ΔZ = Z_end/n_z`` (dimensionless, units of R)."""
        return self.half_length / self.n_z

    @cached_property
    def lift_off(self) -> LiftOff:
        """The top-foil lift-off law of this grid (:class:`foilbearing.laws.LiftOff`, κ)."""
        return LiftOff(self.lift_off_smoothing)

    @property
    def lift_off_delta(self) -> float:
        """δ = κ Δθ² of the smoothed lift-off law (0: sharp); the law at bearing number Λ
        has the width :meth:`lift_off_width` (:meth:`foilbearing.laws.LiftOff.delta`)."""
        return self.lift_off.delta(self.d_theta)

    def lift_off_width(self, lam: float) -> float:
        """``δ √Λ``: the smoothed law ``(P − 1)·y = δ² Λ`` at bearing number Λ, in the
        form ``(P − 1)·y = width²`` (y the outflow in pressure units, ``−R/d_ref``;
        :meth:`foilbearing.laws.LiftOff.width`)."""
        return self.lift_off.width(self.d_theta, lam)

    @property
    def lift_off_scale(self) -> float:
        """``d_ref = 2 ΔZ/Δθ``: a cell's residual R per unit of the pressure it stands for.

        ``−R/d_ref = −(R/A)·Δθ²/2``, with ``A = Δθ ΔZ``: the circumferential part of the
        diagonal of ∂R/∂P at P = H = 1, so the scale does not change with n_z.
        """
        return 2.0 * self.d_z / self.d_theta

    @property
    def size(self) -> int:
        """Number of unknowns, ``n_theta * n_z``."""
        return self.n_theta * self.n_z

    @property
    def shape(self) -> tuple[int, int]:
        """Field shape ``(n_theta, n_z)``."""
        return (self.n_theta, self.n_z)

    @property
    def theta(self) -> FloatArray:
        """Cell-centre angles ``θ_i = (i + 1/2) Δθ``, shape ``(n_theta,)``, rad."""
        return (np.arange(self.n_theta, dtype=np.float64) + 0.5) * self.d_theta

    @property
    def z(self) -> FloatArray:
        """Cell-centre axial positions ``Z_j = (j + 1/2) ΔZ``, shape ``(n_z,)``."""
        return (np.arange(self.n_z, dtype=np.float64) + 0.5) * self.d_z

    def mirror_index(self) -> NDArray[np.int64]:
        """Index map of the reflection ``θ → −θ``: cell ``i`` maps to ``n_theta-1-i``."""
        return np.arange(self.n_theta - 1, -1, -1, dtype=np.int64)

    @cached_property
    def axial(self) -> AxialStencil:
        """The axial discretisation as the kernels take it (:class:`AxialStencil`)."""
        from foilbearing.reynolds._kernels import stencil_pattern

        cols, coef, const = _face_table(self.n_z, self.axial_order)
        slots = stencil_pattern(self.n_theta, self.n_z, self.axial_order)[2]
        if slots.shape[2] == 5:
            full = np.full((self.n_theta, self.n_z, 7), -1, dtype=np.int64)
            full[:, :, [0, 2, 3, 4, 6]] = slots
            slots = full
        return AxialStencil(
            self.axial_order, cols, coef, const, slots, _mean_weights(self.n_z, self.axial_order)
        )

    def gauge_mean(self, P: FloatArray) -> FloatArray:
        """Axial mean of the gauge pressure ``p̄_i − 1`` of each θ-row.

        Second order: the plain mean over ``j`` (the midpoint rule); fourth order: the
        weights :attr:`AxialStencil.mean_w`, with ``P = 1`` on the end face. With
        mid-plane symmetry the mean over the full length equals the mean over the half.

        Parameters
        ----------
        P : ndarray, shape (n_theta, n_z) or (n_theta, n_z, m)
            Pressure ``p/p_a`` (or m columns of it).

        Returns
        -------
        ndarray, shape (n_theta,) or (n_theta, m)
        """
        g = np.asarray(P)
        if self.axial_order == 2:
            return g.mean(axis=1) - 1.0
        return np.tensordot(g - 1.0, self.axial.mean_w, axes=([1], [0]))

    def mean_rows(self, rows: FloatArray) -> FloatArray:
        """``rows`` (k, n_theta) of θ-row weights spread over the cells: the (k, n) matrix
        that maps ``P − 1`` (flat, ``k = i n_z + j``) to ``rows @ gauge_mean(P)``."""
        spread = np.repeat(np.asarray(rows, dtype=np.float64), self.n_z, axis=1)
        if self.axial_order == 2:
            return spread / self.n_z
        return spread * np.tile(self.axial.mean_w, self.n_theta)

    def axial_mean(self, field: FloatArray) -> FloatArray:
        """Axial mean ``(1/L)∫ G dz`` of a field that vanishes on the end face.

        The plain mean over ``j`` at second order (the midpoint rule); the weights
        :attr:`AxialStencil.mean_w` at fourth order. Linear, so it also maps a change
        of pressure to the change of its mean.

        Parameters
        ----------
        field : ndarray, shape (n_theta, n_z) or (n_theta, n_z, m)

        Returns
        -------
        ndarray, shape (n_theta,) or (n_theta, m)
        """
        g = np.asarray(field)
        if g.shape[:2] != self.shape:
            raise ValueError(f"field must have shape {self.shape}, got {g.shape}")
        if self.axial_order == 2:
            return g.mean(axis=1)
        return np.tensordot(g, self.axial.mean_w, axes=([1], [0]))

    def force_weights(self) -> tuple[FloatArray, FloatArray]:
        """Quadrature weights of the film force over the full bearing length.

        ``Σ wX·(P − 1) = ∫∫ (P − 1) cos θ dθ dZ = F_X/(p_a R²)`` and likewise
        ``wY`` with ``sin θ`` (docs/model.md §2). The factor 2 accounts for the
        mirrored half ``Z < 0``.

        Returns
        -------
        wX, wY : ndarray, shape (n_theta, n_z)
        """
        if self.axial_order == 2:
            area = 2.0 * self.d_theta * self.d_z
            ones = np.ones(self.n_z)
        else:
            area = 2.0 * self.d_theta * self.half_length
            ones = self.axial.mean_w
        w_x = np.outer(area * np.cos(self.theta), ones)
        w_y = np.outer(area * np.sin(self.theta), ones)
        return w_x, w_y
