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
from numpy.typing import NDArray

from foilbearing.case import Disturbance

__all__ = ["DisturbanceForce"]

FloatArray = NDArray[np.float64]


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

    def __call__(self, t: float) -> FloatArray:
        """Force (F_X, F_Y) at time t (s), N."""
        return self.amplitude * np.cos(self._omega * t + self.phases).sum(axis=1)
