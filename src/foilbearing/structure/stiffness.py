"""Assembly stiffness under a stinger and the structural stiffness function k(θ).

Paper Eqs. (7) and (8), in the per-actuator form of docs/model.md §3.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from foilbearing.structure._angles import wrap_angle
from foilbearing.structure.pzt import actuator_stiffness

__all__ = ["assembly_stiffness", "stiffness_function"]


def assembly_stiffness(k_b: float, k_p: float, k_sp: float) -> float:
    """Stiffness per unit area under a stinger, Eq. (7), N/m³.

    The bump (k_b) in series with the actuator (k_p + 4k_sp):
    k_assy = k_b (k_p + 4k_sp) / (k_b + k_p + 4k_sp). The default case gives
    1.14e9 N/m³.
    """
    k_act = actuator_stiffness(k_p, k_sp)
    return k_b * k_act / (k_b + k_act)


def stiffness_function(
    theta: ArrayLike,
    k_b: float,
    k_assy: float | Sequence[float],
    angles: Sequence[float],
    stinger_arc: float,
    smoothness: float | None = 50.0,
) -> NDArray:
    """Structural stiffness per unit area around the bearing, k(θ), Eq. (8), N/m³.

    k_b away from the stingers and k_assy over each stinger arc
    [θ_n − θ_s/2, θ_n + θ_s/2], joined by arctangent steps:

        k(θ) = k_b − Σ_n (k_b − k_assy,n)/π · [atan(α(d_n + θ_s/2)) − atan(α(d_n − θ_s/2))],

    with d_n = θ − θ_n wrapped into [−π, π). This is the paper's Eq. (8)
    written once per actuator, valid for any number and placement of actuators.

    Parameters
    ----------
    theta
        Angles in rad, measured counter-clockwise from −X.
    k_b
        Bump stiffness per unit area, N/m³.
    k_assy
        Assembly stiffness under the stingers, N/m³ (one value, or one per actuator).
    angles
        Actuator (stinger centre) angles θ_n in rad.
    stinger_arc
        Angular length θ_s of a stinger, rad.
    smoothness
        α in 1/rad (50 in the paper); ``None`` or ``inf`` gives the unsmoothed step.

    Returns
    -------
    k(θ) in N/m³, same shape as ``theta``.
    """
    th = np.asarray(theta, dtype=float)
    k_a = np.broadcast_to(np.asarray(k_assy, dtype=float), (len(angles),))
    k = np.full(th.shape, float(k_b))
    half = 0.5 * stinger_arc
    for theta_n, k_n in zip(angles, k_a, strict=True):
        d = wrap_angle(th - theta_n)
        if smoothness is None or np.isinf(smoothness):
            # The limit α → ∞ of the bracket: 1 inside, 1/2 on the edges, 0 outside.
            bracket = np.where(np.abs(d) < half, 1.0, np.where(np.abs(d) == half, 0.5, 0.0))
        else:
            bracket = (
                np.arctan(smoothness * (d + half)) - np.arctan(smoothness * (d - half))
            ) / np.pi
        k -= (k_b - k_n) * bracket
    return k
