"""The random force on the rotor of a case's ``[disturbance]``, as a function of time.

A multisine per direction (the broadband excitation of rotordynamic testing):

    F_X(t) = a Σ_k cos(2π f_k t + φ_Xk),   F_Y(t) = a Σ_k cos(2π f_k t + φ_Yk),

with ``n`` tones at frequencies f_k drawn uniformly in [f_min, f_max], phases φ
uniform in [0, 2π), both from ``numpy.random.default_rng(seed)``, and
a = F_rms √(2/n), so that each direction has the RMS F_rms (distinct tones are
orthogonal over a long time) and a flat spectrum of F_rms²/(f_max − f_min) N²/Hz
in the band. It is smooth (the BDF steps it like the imbalance) and the same
function of time in every run of a case, a resumed run included.

Why an orbit needs one: a whirl past its onset grows from a seed. Without a
disturbance the seed is what the numerics leave (the unconverged Newton residual),
and a speed-up's divergence speed then depends on the solver's tolerance, by
several per cent (a slow passage through the Hopf bifurcation is delayed by how
small the seed is). A defined disturbance larger than the numerical seed makes it
a property of the bearing again (docs/development/orbit-performance.md).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

from foilbearing.case import Disturbance

__all__ = ["DisturbanceForce", "multisine"]

FloatArray = NDArray[np.float64]

#: NumPy's pairwise summation: blocks of at most this many terms are added in eight
#: running sums; longer runs are halved (at a multiple of 8) and the halves added.
_BLOCK = 128


@njit(cache=True, nogil=True)
def _block_sum(a: FloatArray, start: int, n: int) -> float:  # pragma: no mutate block
    """Σ a[start : start + n], n <= 128, in NumPy's order (eight running sums)."""
    if n < 8:
        total = 0.0
        for i in range(start, start + n):
            total += a[i]
        return total
    r0, r1, r2, r3 = a[start], a[start + 1], a[start + 2], a[start + 3]
    r4, r5, r6, r7 = a[start + 4], a[start + 5], a[start + 6], a[start + 7]
    i = 8
    while i < n - n % 8:
        j = start + i
        r0 += a[j]
        r1 += a[j + 1]
        r2 += a[j + 2]
        r3 += a[j + 3]
        r4 += a[j + 4]
        r5 += a[j + 5]
        r6 += a[j + 6]
        r7 += a[j + 7]
        i += 8
    total = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        total += a[start + i]
        i += 1
    return total


@njit(cache=True, nogil=True)
def _pairwise_sum(a: FloatArray) -> float:  # pragma: no mutate block
    """Σ a in NumPy's order (its pairwise summation), so that the sum is NumPy's to the bit.

    NumPy halves a run longer than a block and adds the halves' sums, recursively; this is
    the same tree walked with a stack of its own (numba's disk cache cannot hold a
    recursive function: loading one crashed the process)."""
    starts = np.empty(64, np.int64)  # the frames: the run, and whether its left half is done
    counts = np.empty(64, np.int64)
    stage = np.zeros(64, np.int64)  # 0: not split; 1: left half asked; 2: right half asked
    left = np.empty(64)
    top, total = 0, 0.0
    starts[0], counts[0] = 0, a.size
    while top >= 0:
        n = counts[top]
        if n > _BLOCK:  # split: ask for the left half first
            half = n // 2 - (n // 2) % 8
            stage[top] = 1
            top += 1
            starts[top], counts[top], stage[top] = starts[top - 1], half, 0
            continue
        total = _block_sum(a, starts[top], n)
        top -= 1
        while top >= 0:  # hand the sum up: a left half asks for its right one
            if stage[top] == 1:
                left[top], stage[top] = total, 2
                half = counts[top] // 2 - (counts[top] // 2) % 8
                top += 1
                starts[top], counts[top], stage[top] = (
                    starts[top - 1] + half,
                    counts[top - 1] - half,
                    0,
                )
                break
            total = left[top] + total
            top -= 1
    return total


@njit(cache=True, nogil=True)
def multisine(
    omega: FloatArray, phases: FloatArray, amplitude: float, t: float, terms: FloatArray
) -> tuple[float, float]:  # pragma: no mutate block
    """``a Σ_k cos(ω_k t + φ_jk)`` for j = 0, 1 (X, Y), N: the force of
    :class:`DisturbanceForce` at t (s), compiled (it is evaluated every time step: in
    NumPy, 9 µs of a 0.1 ms step), equal to its NumPy form to the bit (the same
    operations in the same order; ``tests/test_disturbance.py``). ``terms``: a work array
    of the tones' number."""
    n = omega.size
    out = [0.0, 0.0]
    for j in range(2):
        for k in range(n):
            terms[k] = math.cos(omega[k] * t + phases[j, k])
        out[j] = amplitude * (0.0 + _pairwise_sum(terms[:n]))
    return out[0], out[1]


class DisturbanceForce:
    """``force(t)``: the disturbance force on the journal at t (s), N, shape (2,) (X, Y).

    Attributes
    ----------
    frequencies
        The tones' frequencies f_k, Hz, shape (n,), ascending.
    phases
        Their phases, rad, shape (2, n): row 0 for X, row 1 for Y.
    amplitude
        The amplitude a of each tone, N.
    """

    def __init__(self, disturbance: Disturbance) -> None:
        d = disturbance
        rng = np.random.default_rng(d.seed)
        self.frequencies = np.sort(rng.uniform(d.min_frequency, d.max_frequency, d.tones))
        self.phases = rng.uniform(0.0, 2.0 * math.pi, (2, d.tones))
        self.amplitude = d.force_rms * math.sqrt(2.0 / d.tones)
        self._omega = 2.0 * math.pi * self.frequencies
        self._terms = np.empty(d.tones)

    def __call__(self, t: float) -> FloatArray:
        """Force (F_X, F_Y) at time t (s), N."""
        return np.array(self.components(t))

    def components(self, t: float) -> tuple[float, float]:
        """F_X and F_Y at time t (s), N, as two floats (the orbit's inputs at each step)."""
        return multisine(self._omega, self.phases, self.amplitude, t, self._terms)
