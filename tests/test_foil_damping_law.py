"""The foil damping law is an object the analyses take from the case (foilbearing.laws).

Swapping :class:`~foilbearing.laws.NoFoilDamping` in for the case's viscous bump, by
passing another law object in ``Foil.damping`` (no patching), reaches the coefficients
and the orbit: at zero foil damping the stiffness at whirl frequency → 0 is the
derivative of the static film force, and both analyses agree with the other route to
zero damping, the viscous bump at γ = 0. On 32 x 4, in about a second.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np
import pytest

from foilbearing.case import Case, Grid, default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.control import constant_speed
from foilbearing.laws import NoFoilDamping, ViscousBump
from foilbearing.orbit import simulate
from foilbearing.orbit.system import OrbitSimulation
from foilbearing.static import film_at_position, solve_equilibrium

RPM = math.pi / 30.0


def coarse(volts: float = 150.0) -> Case:
    case = default_case().with_voltages(volts)
    return replace(case, grid=Grid(32, 4, lift_off_smoothing=0.1), disturbance=None)


def with_foil(case: Case, **changes: Any) -> Case:
    assert case.foil is not None
    return replace(case, foil=replace(case.foil, **changes))


def test_the_case_carries_its_foil_damping_law() -> None:
    case = coarse()
    assert case.foil is not None and case.foil.loss_factor > 0.0
    assert case.foil.damping_law == ViscousBump(case.foil.loss_factor)
    swapped = with_foil(case, damping=NoFoilDamping()).foil
    assert swapped is not None and swapped.damping_law == NoFoilDamping()
    with pytest.raises(ValueError, match="loss_factor must be >= 0"):
        ViscousBump(-0.1)


def test_without_foil_damping_the_quasi_static_stiffness_is_the_static_force_derivative() -> None:
    # K at ν -> 0 must be the finite-difference derivative of the static film force
    # (local compliant reading: the stacks and bumps follow the pressure).
    case = with_foil(coarse(), damping=NoFoilDamping())
    st = solve_equilibrium(case, speed=50e3 * RPM)
    assert st.converged and st.model.foil_damping == NoFoilDamping()
    k = force_coefficients(st, 1e-6 * st.speed).K[0]
    d, c = 1e-5, case.bearing.clearance
    k_fd = np.zeros((2, 2))
    for j, (dx, dy) in enumerate(((d, 0.0), (0.0, d))):
        fp, fm = (
            np.array(film_at_position(case, st.eps_x + s * dx, st.eps_y + s * dy).force)
            for s in (1, -1)
        )
        k_fd[:, j] = -(fp - fm) / (2 * d * c)
    np.testing.assert_allclose(k, k_fd, rtol=1e-3, atol=1e-3 * np.abs(k_fd).max())


def test_without_foil_damping_the_damping_is_the_films_alone() -> None:
    # The law object and the viscous bump at γ = 0 are two routes to a foil that
    # dissipates nothing: the same coefficients; the case's γ adds damping of its own.
    case = coarse()
    speed = 50e3 * RPM
    damped = solve_equilibrium(case, speed=speed)
    undamped = solve_equilibrium(with_foil(case, damping=NoFoilDamping()), speed=speed)
    w = 0.5 * speed
    ref = force_coefficients(damped, w, loss_factor=0.0)
    got = force_coefficients(undamped, w)
    for a, b in ((got.K, ref.K), (got.C, ref.C)):
        np.testing.assert_allclose(a, b, rtol=0.0, atol=1e-12 * np.abs(b).max())
    viscous = force_coefficients(damped, w)
    assert np.abs(viscous.C - ref.C).max() > 0.01 * np.abs(ref.C).max()


def test_the_orbit_takes_the_law_from_the_case() -> None:
    # No foil damping: no bump state in the orbit, the same orbit as γ = 0; the case's
    # viscous bump relaxes at ω/γ and moves the orbit.
    case = coarse(100.0)
    speed = constant_speed(20e3 * RPM, 2e-3)
    none = with_foil(case, damping=NoFoilDamping())
    sim = OrbitSimulation(none, speed)
    assert not sim.system.dynamic_bump and sim.system.foil_damping == NoFoilDamping()
    viscous = OrbitSimulation(case, speed).system
    assert case.foil is not None
    assert viscous.dynamic_bump and viscous.foil_damping == ViscousBump(case.foil.loss_factor)
    a, b = simulate(none, speed), simulate(with_foil(case, loss_factor=0.0), speed)
    extent = np.ptp(b.e_x)
    np.testing.assert_allclose(a.e_x, b.e_x, rtol=0.0, atol=1e-12 * extent)
    np.testing.assert_allclose(a.e_y, b.e_y, rtol=0.0, atol=1e-12 * np.ptp(b.e_y))
    c = simulate(case, speed)
    assert np.abs(c.e_x - b.e_x).max() > 1e-3 * extent
