"""Preload shape r_p(θ): the fully sinusoidal lobe of the paper's Eq. (6).

For the paper's three actuators at 60°, 180°, 300° each sector spans
θ_n ± 60° and r_p(θ) = (δ_n/2)[cos 3(θ − θ_n) + 1]. For any number and
placement of actuators, sector n runs from the midpoint towards the previous
actuator to the midpoint towards the next one, and the lobe is a raised cosine
that falls to zero at both sector ends (on each side over its own half-width),
which reduces to Eq. (6) for equally spaced actuators.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from foilbearing.structure._angles import wrap_angle

__all__ = ["preload_shape", "sector_half_widths"]


def sector_half_widths(angles: Sequence[float]) -> tuple[NDArray, NDArray]:
    """Half-widths (rad) of each actuator's sector towards its previous and next neighbour.

    Parameters
    ----------
    angles
        Actuator angles in rad (any order, distinct).

    Returns
    -------
    (left, right): arrays in the order of ``angles``. A single actuator owns the
    whole circle (π on each side).
    """
    a = np.asarray(angles, dtype=float) % (2.0 * np.pi)
    if a.size == 1:
        return np.array([np.pi]), np.array([np.pi])
    order = np.argsort(a)
    s = a[order]
    gap_next = (np.roll(s, -1) - s) % (2.0 * np.pi)  # gap to the next actuator, counter-clockwise
    gap_prev = np.roll(gap_next, 1)
    left = np.empty_like(a)
    right = np.empty_like(a)
    left[order] = 0.5 * gap_prev
    right[order] = 0.5 * gap_next
    return left, right


def preload_shape(theta: ArrayLike, angles: Sequence[float], preloads: ArrayLike) -> NDArray:
    """Preload profile r_p(θ) in m, Eq. (6a-b) generalised to any actuator placement.

    Parameters
    ----------
    theta
        Angles in rad, measured counter-clockwise from −X.
    angles
        Actuator (or shim) angles θ_n in rad.
    preloads
        Preload magnitude δ_n of each actuator in m: the base piezoelectric
        preload (C-GFB) or the shim thickness (shimmed GFB).

    Returns
    -------
    r_p(θ) in m, same shape as ``theta``; it equals δ_n at θ_n and 0 at sector ends.
    """
    th = np.asarray(theta, dtype=float)
    delta = np.broadcast_to(np.asarray(preloads, dtype=float), (len(angles),))
    left, right = sector_half_widths(angles)
    r_p = np.zeros(th.shape)
    for theta_n, d_n, a_l, a_r in zip(angles, delta, left, right, strict=True):
        d = wrap_angle(th - theta_n)
        half_width = np.where(d < 0.0, a_l, a_r)
        inside = np.abs(d) <= half_width
        lobe = 0.5 * d_n * (np.cos(np.pi * d / half_width) + 1.0)
        r_p += np.where(inside, lobe, 0.0)
    return r_p
