"""The fourth-order axial discretisation (``[grid] axial_order = 4``, issue 30 route 2).

Measured convergence rates (suction retained, where the film is smooth in Z), the
quadrature of the axial means, the actuator readings and the case fields. The orbit's free
whirl against its linear eigenvalue on a fourth-order grid is in tests/test_orbit.py. The kernels themselves are checked against their twins and
finite differences at both orders in tests/test_kernels.py and
tests/test_transient_kernels.py.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, default_case, default_case_path
from foilbearing.case.toml import case_from_dict
from foilbearing.errors import InputError
from foilbearing.reynolds.grid import FilmGrid
from foilbearing.stability import whirl_mode
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0


def test_axial_mean_is_exact_for_a_parabola_and_fourth_order_for_a_cosine() -> None:
    """The spline quadrature of the mean gauge pressure (ambient at the end, mirrored at the
    mid-plane) integrates 1 − (Z/Z_end)² exactly (mean 2/3) and cos(πZ/2Z_end) (mean 2/π)
    with an error falling as n_z⁻⁴; the midpoint rule of order 2 as n_z⁻²."""
    errors = {2: [], 4: []}
    for n_z in (6, 12, 24):
        for order in (2, 4):
            g = FilmGrid(8, n_z, 0.5, axial_order=order)
            z = g.z / g.half_length
            parabola = 1.0 + np.outer(np.ones(8), 1.0 - z**2)
            cosine = 1.0 + np.outer(np.ones(8), np.cos(0.5 * np.pi * z))
            if order == 4:
                assert g.gauge_mean(parabola) == pytest.approx(np.full(8, 2.0 / 3.0), abs=1e-14)
            errors[order].append(abs(g.gauge_mean(cosine)[0] - 2.0 / np.pi))
    for order, e in errors.items():
        rates = np.log2(np.array(e[:-1]) / np.array(e[1:]))
        np.testing.assert_allclose(rates, order, atol=0.15)


def test_static_equilibrium_converges_at_the_axial_order() -> None:
    """The eccentricity under the default load (suction retained: the film is smooth in Z)
    against n_z = 48 at fourth order: measured rates 1.94-1.98 at order 2 and 3.7-3.9 at
    order 4, and 3 fourth-order cells beat 12 second-order ones."""
    case = default_case().with_subambient("retained")

    def ecc(n_z: int, order: int) -> float:
        st = solve_equilibrium(
            replace(
                case,
                grid=Grid(
                    48,
                    n_z,
                    axial_order=order,
                    lift_off_smoothing=0.0,
                    orbit_n_z=None,
                    orbit_axial_order=None,
                ),
            )
        )
        assert st.converged
        return float(np.hypot(st.eps_x, st.eps_y))

    ref = ecc(48, 4)
    err = {o: np.array([abs(ecc(n, o) - ref) for n in (3, 6, 12)]) for o in (2, 4)}
    rates = {o: np.log2(e[:-1] / e[1:]) for o, e in err.items()}
    assert np.all((rates[2] > 1.8) & (rates[2] < 2.2)), rates[2]
    assert np.all((rates[4] > 3.4) & (rates[4] < 4.4)), rates[4]
    assert err[4][0] < err[2][2]


def test_order_2_grid_is_the_default_and_order_4_needs_3_cells() -> None:
    assert FilmGrid(16, 2, 0.5).axial_order == 2
    with pytest.raises(ValueError, match="n_z must be >= 3 at axial order 4"):
        FilmGrid(16, 2, 0.5, axial_order=4)
    with pytest.raises(ValueError, match="axial_order must be 2 or 4"):
        FilmGrid(16, 6, 0.5, axial_order=3)


def test_axial_order_fields_in_the_case_file_with_one_line_errors() -> None:
    """``[grid] axial_order`` sets the static and linear analyses' order,
    ``orbit_axial_order`` the orbit's (default 4 on n_z = 4, the built-in case's); the
    orbit's case carries it."""
    with default_case_path().open("rb") as fh:
        data = tomllib.load(fh)
    case = case_from_dict(data | {"grid": {"orbit_n_z": 4, "orbit_axial_order": 4}})
    assert case.grid.axial_order == 2 and case.grid.orbit_order == 4
    assert (
        case.grid.orbit_is_own
        and case.grid.orbit_label == "96 × 4 (axial order 4, lift-off smoothing 0.1)"
    )
    orbit = case.orbit_case().grid
    assert (orbit.n_theta, orbit.n_z, orbit.axial_order) == (96, 4, 4)
    default = case_from_dict(data | {"grid": {}}).grid
    assert (default.axial_order, default.orbit_order, default.orbit_shape) == (2, 4, (96, 4))
    same = case_from_dict(data | {"grid": {"axial_order": 4, "orbit_n_z": 12}})
    assert same.grid.orbit_order == 4 and not same.grid.orbit_is_own
    with pytest.raises(InputError, match=r"grid\.axial_order = 3: expected 2 or 4") as err:
        case_from_dict(data | {"grid": {"axial_order": 3}})
    assert "\n" not in str(err.value)
    with pytest.raises(InputError, match=r"grid\.orbit_n_z = 2: expected at least 3"):
        case_from_dict(data | {"grid": {"orbit_n_z": 2, "orbit_axial_order": 4}})


@pytest.mark.parametrize("response", ["local", "lobe"])
@pytest.mark.parametrize("dynamics", ["compliant", "held"])
def test_every_reading_on_4_fourth_order_cells_agrees_with_24_second_order(
    response: str, dynamics: str
) -> None:
    """Each reading of the actuator in the film (its stack's compression by the stinger's
    axial-mean pressure included) on 48 × 4 at order 4 against 48 × 24 at order 2, lift-off,
    150 V: the eccentricity within 0.1 % (measured 0.06-0.08 %), the whirl frequency within
    1 % (measured 0.02-0.65 %, the most under lobe + compliant, whose whirl is near marginal
    and moves with the held cells). The drag torque within 0.1 %."""
    from foilbearing.film import drag_torque

    base = default_case().with_voltages(150.0).with_actuator_reading(response, dynamics)
    out = []
    for n_z, order in ((4, 4), (24, 2)):
        case = replace(
            base,
            grid=Grid(
                48,
                n_z,
                axial_order=order,
                lift_off_smoothing=0.0,
                orbit_n_z=None,
                orbit_axial_order=None,
            ),
        )
        st = solve_equilibrium(case)
        assert st.converged
        mode = whirl_mode(st, case.rotor.mass)
        torque = drag_torque(case, st.model.grid, st.P, st.H, case.operation.speed)
        out.append((np.hypot(st.eps_x, st.eps_y), mode.eigenvalue.imag, torque))
    (e4, w4, t4), (e2, w2, t2) = out
    assert e4 == pytest.approx(e2, rel=1e-3)
    assert w4 == pytest.approx(w2, rel=1e-2)
    assert t4 == pytest.approx(t2, rel=1e-3)
