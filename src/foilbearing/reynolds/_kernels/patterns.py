"""Sparsity patterns of the film's Jacobians: the CSR pattern of the film stencil (5 points, or
7 at axial order 4), the dense-block pattern of the foil-coupled Jacobian, and the compiled
slot map of a row in the 5-point pattern. The kernels of :mod:`.flux` and :mod:`.bdf` fill
only the ``data`` arrays of these patterns."""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

IntArray = NDArray[np.int64]


def stencil_pattern(
    n_theta: int, n_z: int, axial_order: int = 2
) -> tuple[IntArray, IntArray, IntArray]:
    """CSR pattern of the film stencil, periodic in θ, columns sorted.

    Order 2: the 5-point stencil; order 4: 7 points, ``(i, j−2 .. j+2)`` axially.

    Parameters
    ----------
    n_theta, n_z : int
        Grid size (``n_theta >= 3`` so that W, C, E are distinct; ``n_z >= 2``).
    axial_order : int
        2 or 4 (:class:`~foilbearing.reynolds.grid.AxialStencil`).

    Returns
    -------
    indptr : ndarray, shape (n_theta*n_z + 1,)
    indices : ndarray, shape (nnz,), ``nnz = n_theta (5 n_z − 2)`` at order 2
    slots : ndarray, shape (n_theta, n_z, 5) at order 2, (n_theta, n_z, 7) at order 4
        Position in ``data`` of the entry of row ``(i, j)`` in direction
        W, S, C, N, E (see module constants; order 4: W, j−2, j−1, C, j+1, j+2, E),
        ``-1`` where absent (S on the mid-plane row ``j = 0``, N on the end row
        ``j = n_z−1``). The order-2 kernels compute the same positions in place
        (:func:`_row_slots`).
    """
    reach = 1 if axial_order == 2 else 2
    i = np.repeat(np.arange(n_theta), n_z)
    j = np.tile(np.arange(n_z), n_theta)
    row = i * n_z + j
    axial = [np.where((j + d >= 0) & (j + d < n_z), row + d, -1) for d in range(-reach, reach + 1)]
    cols = np.stack(
        [((i - 1) % n_theta) * n_z + j, *axial, ((i + 1) % n_theta) * n_z + j],
        axis=1,
    )
    width = cols.shape[1]
    present = cols >= 0
    big = n_theta * n_z + 1
    key = np.where(present, cols, big)
    order = np.argsort(key, axis=1, kind="stable")
    rank = np.empty_like(order)
    np.put_along_axis(rank, order, np.arange(width)[None, :].repeat(len(row), 0), axis=1)
    counts = present.sum(axis=1)
    indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    sorted_key = np.take_along_axis(key, order, axis=1)
    indices = sorted_key[sorted_key < big].astype(np.int64)
    slots = np.where(present, indptr[:-1, None] + rank, -1).astype(np.int64)
    return indptr, indices, slots.reshape(n_theta, n_z, width)


def coupled_pattern(n_theta: int, n_z: int) -> tuple[IntArray, IntArray]:
    """CSR pattern of the foil-coupled Jacobian: dense blocks on 3 θ-diagonals.

    Row ``(i, j)`` holds every column of the θ-blocks ``i−1, i, i+1``
    (periodic), blocks in increasing column order, ``3 n_z`` entries per row.

    Returns
    -------
    indptr : ndarray, shape (n_theta*n_z + 1,)
    indices : ndarray, shape (3 n_z · n_theta n_z,)
    """
    n = n_theta * n_z
    i = np.repeat(np.arange(n_theta), n_z)
    blocks = np.sort(np.stack([(i - 1) % n_theta, i, (i + 1) % n_theta], axis=1), axis=1)
    indices = (blocks[:, :, None] * n_z + np.arange(n_z)[None, None, :]).reshape(-1)
    indptr = np.arange(n + 1, dtype=np.int64) * (3 * n_z)
    return indptr, indices.astype(np.int64)


@njit(cache=True)
def _row_slots(i: int, j: int, n_theta: int, n_z: int) -> tuple[int, int, int, int, int]:
    """Positions (W, S, C, N, E) of row (i, j) in the data of :func:`stencil_pattern`.

    Rows of one θ-block hold ``5 n_z − 2`` entries; row ``j`` starts at
    ``0`` (``j = 0``) or ``5 j − 1``. Sorted columns put W after the block for
    ``i = 0`` and E before it for ``i = n_theta − 1`` (periodic wrap).
    """
    start = i * (5 * n_z - 2) + (0 if j == 0 else 5 * j - 1)
    has_s = j > 0
    has_n = j < n_z - 1
    k = start
    w = -1
    e = -1
    if i == n_theta - 1:
        e = k
        k += 1
        w = k
        k += 1
    elif i > 0:
        w = k
        k += 1
    s = -1
    if has_s:
        s = k
        k += 1
    c = k
    k += 1
    nn = -1
    if has_n:
        nn = k
        k += 1
    if i == 0:
        e = k
        k += 1
        w = k
    elif i < n_theta - 1:
        e = k
    return w, s, c, nn, e
