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
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["FilmGrid"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class FilmGrid:
    """Finite-volume grid on ``θ ∈ [0, 2π)`` × ``Z ∈ [0, L/(2R)]``.

    Parameters
    ----------
    n_theta : int
        Number of circumferential cells (periodic), at least 8.
    n_z : int
        Number of axial cells on the half bearing, at least 2.
    half_length : float
        ``Z_end = L/(2R)``, the dimensionless half length (> 0).
    """

    n_theta: int
    n_z: int
    half_length: float

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

    @property
    def d_theta(self) -> float:
        """Circumferential cell width ``Δθ = 2π/n_theta`` (rad)."""
        return 2.0 * np.pi / self.n_theta

    @property
    def d_z(self) -> float:
        """Axial cell width ``ΔZ = Z_end/n_z`` (dimensionless, units of R)."""
        return self.half_length / self.n_z

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

    def axial_mean(self, field: FloatArray) -> FloatArray:
        """Axial mean ``(1/L)∫ G dz`` of a field, by the midpoint rule.

        With mid-plane symmetry the mean over the full length equals the mean
        over the half, i.e. the plain mean over ``j``.

        Parameters
        ----------
        field : ndarray, shape (n_theta, n_z)

        Returns
        -------
        ndarray, shape (n_theta,)
        """
        g = np.asarray(field, dtype=np.float64)
        if g.shape != self.shape:
            raise ValueError(f"field must have shape {self.shape}, got {g.shape}")
        return g.mean(axis=1)

    def force_weights(self) -> tuple[FloatArray, FloatArray]:
        """Quadrature weights of the film force over the full bearing length.

        ``Σ wX·(P − 1) = ∫∫ (P − 1) cos θ dθ dZ = F_X/(p_a R²)`` and likewise
        ``wY`` with ``sin θ`` (docs/model.md §2). The factor 2 accounts for the
        mirrored half ``Z < 0``.

        Returns
        -------
        wX, wY : ndarray, shape (n_theta, n_z)
        """
        area = 2.0 * self.d_theta * self.d_z
        ones = np.ones(self.n_z)
        w_x = np.outer(area * np.cos(self.theta), ones)
        w_y = np.outer(area * np.sin(self.theta), ones)
        return w_x, w_y
