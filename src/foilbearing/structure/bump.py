"""Bump-foil stiffness per unit area from the foil geometry.

A bump is a circular arc of half chord ``l_0`` and height ``h_b`` made of a foil
of thickness ``t_b``; bumps repeat with pitch ``s``. The stiffness per unit
area is the force per unit bump width per unit deflection, divided by the pitch.
"""

from __future__ import annotations

import math

__all__ = ["bump_half_angle", "iordanoff_bump_stiffness", "walowit_anno_bump_stiffness"]


def bump_half_angle(height: float, half_length: float) -> float:
    """Half the angle subtended by the bump arc, rad.

    For a circular arc of radius r with half chord l_0 = r sin(α/2) and height
    h_b = r (1 − cos(α/2)), tan(α/4) = h_b / l_0.
    """
    return 2.0 * math.atan(height / half_length)


def iordanoff_bump_stiffness(
    thickness: float,
    height: float,
    pitch: float,
    half_length: float,
    youngs_modulus: float,
    poisson_ratio: float,
    friction_coefficient: float = 0.0,
) -> float:
    """Stiffness per unit area of a free-free bump, Iordanoff's curved-beam formula, N/m³.

    Iordanoff, I. (1999) "Analysis of an aerodynamic compliant foil thrust
    bearing: method for a rapid design", ASME J. Tribol. 121(4), 816-822 (the
    paper's ref. 21). The bump is a circular arc of half angle a = α/2, loaded
    by F at its crown and resting on its two feet, which slide on the housing
    against a friction force μ_f F/2 each. Castigliano's theorem on the bending
    energy of the arc (plate modulus E/(1 − ν²), I = t_b³/12 per unit width) gives
    the stiffness per unit bump width

        K = E t_b³ sin³(a) / (6 (1 − ν²) l_0³ J(a, μ_f)),
        J = ∫₀^a [sin a − sin φ − μ_f (cos φ − cos a)]² dφ,

    and the stiffness per unit area k_b = K / s. With μ_f = 0 (the
    frictionless free-free bump used by the paper) the default foil gives
    8.70e9 N/m³ (the paper gives 8.69e9, 0.1 % less).

    Parameters
    ----------
    thickness, height, pitch, half_length
        t_b, h_b, s, l_0 in m.
    youngs_modulus
        E in Pa.
    poisson_ratio
        ν, dimensionless.
    friction_coefficient
        μ_f between the bump feet and the housing (0 = frictionless).
    """
    a = bump_half_angle(height, half_length)
    sa, ca = math.sin(a), math.cos(a)
    mu = friction_coefficient
    # Closed form of J: expand the square and integrate term by term on [0, a].
    i_1 = a
    i_sin = 1.0 - ca
    i_cos = sa
    i_sin2 = a / 2.0 - math.sin(2.0 * a) / 4.0
    i_cos2 = a / 2.0 + math.sin(2.0 * a) / 4.0
    i_sincos = sa**2 / 2.0
    c0 = sa + mu * ca  # the constant part of the bracket
    j = (
        c0**2 * i_1
        + i_sin2
        + mu**2 * i_cos2
        - 2.0 * c0 * i_sin
        - 2.0 * c0 * mu * i_cos
        + 2.0 * mu * i_sincos
    )
    per_width = (
        youngs_modulus
        * thickness**3
        * sa**3
        / (6.0 * (1.0 - poisson_ratio**2) * half_length**3 * j)
    )
    return per_width / pitch


def walowit_anno_bump_stiffness(
    thickness: float,
    pitch: float,
    half_length: float,
    youngs_modulus: float,
    poisson_ratio: float,
) -> float:
    """Stiffness per unit area of a bump foil, Walowit and Anno's simple formula, N/m³.

    k_b = E t_b³ / (2 s l_0³ (1 − ν²)) (Walowit, J. A. and Anno, J. N., 1975,
    *Modern Developments in Lubrication Mechanics*, Applied Science). The
    default foil gives 8.83e9 N/m³.
    """
    return youngs_modulus * thickness**3 / (2.0 * pitch * half_length**3 * (1.0 - poisson_ratio**2))
