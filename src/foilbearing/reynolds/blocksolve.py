"""Direct solver for the foil-coupled Reynolds matrix: block cyclic tridiagonal LU.

The Newton matrices of the transient and static solvers live on
:func:`foilbearing.reynolds._kernels.coupled_pattern`: block tridiagonal and
periodic in θ with dense ``n_z × n_z`` blocks. :class:`BlockCyclicLU`
factorises such a matrix from its CSR ``data`` in ``O(n_theta n_z³)`` and
solves in ``O(n_theta n_z²)`` (kernels :func:`~foilbearing.reynolds._kernels.block_cyclic_factor`
and :func:`~foilbearing.reynolds._kernels.block_cyclic_solve`), a drop-in for
``scipy.sparse.linalg.splu(B).solve``.

There is no pivoting between θ-blocks, so the method needs pivot blocks that
stay well conditioned through the elimination (block diagonal dominance, as in
``c0·diag(H) + …`` with ``c0 = α₀/Δt``). Failure is detected, not hidden:
a singular or ill-conditioned pivot block, large pivot growth or non-finite
data raise :class:`FloatingPointError`, on which a caller falls back to
``splu``.

The ring of θ-blocks is cut by two separator rows into two chains that are
eliminated independently, then the separators (see the kernels' comment).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.sparse.linalg import splu

from foilbearing.reynolds import _kernels as kern

__all__ = ["BlockCyclicLU", "TransposedSuperLU", "factor_coupled"]

FloatArray = NDArray[np.float64]
DataArray = NDArray[Any]  # float64, or complex128 (the perturbation at a frequency)


class BlockCyclicLU:
    """LU factors of B (CSR data on the coupled pattern) with a SuperLU-like ``solve``.

    Parameters
    ----------
    data : ndarray, shape (3 n_z · n_theta n_z,), real or complex
        CSR data of B on ``coupled_pattern(n_theta, n_z)``: row
        ``k = i*n_z + j`` holds the ``3 n_z`` columns of θ-blocks ``i−1, i, i+1``
        (periodic) in increasing column order. Not kept: the factors are a copy.
    n_theta, n_z : int
        Grid size, ``n_theta >= 3``.
    rcond_min : float, optional
        Smallest accepted reciprocal 1-norm condition number of any pivot block.
    growth_max : float, optional
        Largest accepted ratio of the largest Schur-complemented pivot-block
        entry to the largest entry of B.

    Raises
    ------
    FloatingPointError
        If a pivot block is singular or ill conditioned, the pivot growth is
        too large, or ``data`` holds inf/NaN (use ``splu`` instead).
    ValueError
        If ``data`` has the wrong size or ``n_theta < 3``.

    Attributes
    ----------
    shape : tuple of int
        ``(n, n)`` with ``n = n_theta n_z``.
    rcond : float
        Smallest reciprocal 1-norm condition number ``1/(‖D‖₁ ‖D⁻¹‖₁)`` of the
        pivot blocks (exact: the blocks are inverted explicitly).
    growth : float
        Pivot growth of the block elimination (about 1 when B is block
        diagonally dominant).
    """

    def __init__(
        self,
        data: DataArray,
        n_theta: int,
        n_z: int,
        *,
        rcond_min: float = 1e-12,
        growth_max: float = 1e8,
    ) -> None:
        n = n_theta * n_z
        dtype = np.complex128 if np.iscomplexobj(data) else np.float64
        data = np.ascontiguousarray(data, dtype=dtype)
        if data.shape != (3 * n_z * n,):
            raise ValueError(
                f"data has shape {data.shape}; the coupled pattern of a "
                f"{n_theta}×{n_z} grid has {3 * n_z * n} entries"
            )
        self.n_theta, self.n_z = n_theta, n_z
        self.shape = (n, n)
        self._fac: Any = kern.block_cyclic_alloc(n_theta, n_z, dtype)
        status, block, rcond, growth = kern.block_cyclic_factor(data, n_theta, n_z, self._fac)
        self.rcond, self.growth = float(rcond), float(growth)
        p = (n_theta - 1) // 2
        where = f"θ-block {block} of {n_theta} ({p} and {n_theta - 1} are the separators)"
        if status == kern.BC_NOT_FINITE:
            raise FloatingPointError("block cyclic LU: the matrix data holds inf or NaN")
        if status == kern.BC_ZERO_PIVOT:
            raise FloatingPointError(
                f"block cyclic LU: pivot block is singular (zero pivot) at {where}; "
                "the matrix is singular or needs pivoting between θ-blocks, use splu"
            )
        if not rcond >= rcond_min:
            raise FloatingPointError(
                f"block cyclic LU: pivot block ill conditioned at {where}: reciprocal "
                f"condition number {rcond:.3g} < rcond_min = {rcond_min:.3g}; use splu"
            )
        if not growth <= growth_max:
            raise FloatingPointError(
                f"block cyclic LU: pivot growth {growth:.3g} > growth_max = {growth_max:.3g} "
                "(elimination without θ-block pivoting is unstable here); use splu"
            )

    def solve(self, rhs: FloatArray) -> FloatArray:
        """Solve ``B x = rhs``.

        Parameters
        ----------
        rhs : ndarray, shape (n,) or (n, k)

        Returns
        -------
        ndarray
            ``x``, same shape as ``rhs``; float64, or complex128 if B or rhs is complex.
        """
        dtype = np.result_type(self._fac, np.asarray(rhs), np.float64)
        b = np.asarray(rhs, dtype=dtype)
        n = self.shape[0]
        if b.ndim not in (1, 2) or b.shape[0] != n:
            raise ValueError(f"rhs has shape {b.shape}; expected ({n},) or ({n}, k)")
        b2 = np.ascontiguousarray(b.reshape(n, -1))
        out = np.empty_like(b2)
        kern.block_cyclic_solve(self._fac, b2, out)
        return out.reshape(b.shape)


class TransposedSuperLU:
    """SuperLU of B from its CSR arrays read as CSC (= Bᵀ), solving B x = b.

    Any CSR pattern; reading the arrays as Bᵀ and solving transposed avoids a
    CSR → CSC conversion per factorisation.
    """

    def __init__(self, data: DataArray, indices: NDArray, indptr: NDArray, n: int) -> None:
        bt = sp.csc_matrix((data, indices, indptr), shape=(n, n))
        # Minimum degree on Bᵀ + B suits the structurally symmetric pattern.
        self.lu = splu(bt, permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})

    def solve(self, rhs: FloatArray) -> FloatArray:
        return self.lu.solve(rhs, trans="T")


def factor_coupled(
    data: DataArray,
    indices: NDArray,
    indptr: NDArray,
    n_theta: int,
    n_z: int,
) -> Any:
    """Factorise B from its CSR arrays on the foil-coupled pattern, for ``.solve(rhs)``.

    The compiled :class:`BlockCyclicLU`, or SuperLU (of the same arrays read as
    Bᵀ, solved transposed) when a pivot block is ill conditioned or the
    elimination without θ-block pivoting is unstable.

    Raises
    ------
    RuntimeError
        If B is exactly singular (from SuperLU).
    """
    try:
        return BlockCyclicLU(data, n_theta, n_z)
    except FloatingPointError:
        return TransposedSuperLU(data, indices, indptr, n_theta * n_z)
