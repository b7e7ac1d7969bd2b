"""PZT stack and actuator spring model (paper Eqs. (1)-(3), docs/model.md §3).

The stack (stiffness per unit area ``k_p``) sits in parallel with four holder
springs (``4 k_sp``); that pair is in series with the bump foil under the
stinger. Stiffnesses are per unit contact area (N/m³), pressures in Pa,
displacements in m, voltages in V.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["actuator_stiffness", "base_preload", "piezoelectric_preload", "stack_displacement"]


def stack_displacement(voltage: ArrayLike, d33_quadratic: float, d33_linear: float) -> NDArray:
    """Free (no-load) stroke of a PZT stack, Eq. (2) with σ₃ = 0.

    δ₃ = D33,1 V² + D33,2 V  (the paper's second-order law; D33,1 = 0 gives the
    linear law δ₃ = D33 V).

    Parameters
    ----------
    voltage
        Driving voltage V₃ in V (scalar or array).
    d33_quadratic, d33_linear
        D33,1 in m/V² and D33,2 in m/V.

    Returns
    -------
    Stroke in m, same shape as ``voltage``.
    """
    v = np.asarray(voltage, dtype=float)
    return d33_quadratic * v**2 + d33_linear * v


def actuator_stiffness(k_p: float, k_sp: float) -> float:
    """Stiffness per unit area of the actuator: stack in parallel with four holder springs, N/m³."""
    return k_p + 4.0 * k_sp


def base_preload(
    voltage: ArrayLike,
    d33_quadratic: float,
    d33_linear: float,
    k_p: float,
    k_sp: float,
    pre_extension: float = 0.0,
) -> NDArray:
    """Base piezoelectric preload: the actuator's displacement with no film pressure, Eq. (3b).

    δ_base = k_p/(k_p + 4k_sp)·(D33,1 V² + D33,2 V) − 4k_sp δ_pre/(k_p + 4k_sp)

    The factor k_p/(k_p + 4k_sp) < 1 makes it slightly smaller than the stack's
    free stroke (docs/model.md slip S6).

    Parameters
    ----------
    voltage
        Driving voltage in V.
    d33_quadratic, d33_linear
        D33,1 in m/V², D33,2 in m/V.
    k_p, k_sp
        Stack and single holder-spring stiffness per unit area, N/m³.
    pre_extension
        Holder-spring pre-extension δ_pre in m (0 in the paper).

    Returns
    -------
    Base preload in m.
    """
    k_act = actuator_stiffness(k_p, k_sp)
    stroke = stack_displacement(voltage, d33_quadratic, d33_linear)
    return (k_p * stroke - 4.0 * k_sp * pre_extension) / k_act


def piezoelectric_preload(
    base: ArrayLike, actuator_pressure: ArrayLike, k_p: float, k_sp: float
) -> NDArray:
    """Piezoelectric preload under film pressure, Eq. (3b): δ_PZT = δ_base − p_A/(k_p + 4k_sp).

    Parameters
    ----------
    base
        Base preload δ_base in m.
    actuator_pressure
        Axially averaged gauge film pressure p_A at the actuator, Pa.
    k_p, k_sp
        Stack and single holder-spring stiffness per unit area, N/m³.
    """
    return np.asarray(base, dtype=float) - np.asarray(actuator_pressure, dtype=float) / (
        actuator_stiffness(k_p, k_sp)
    )
