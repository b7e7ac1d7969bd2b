"""Top-foil lift-off: the film under a foil holds no sub-ambient pressure (docs/model.md §3).

The complementarity P ≥ 1, −R ≥ 0, (P − 1) R = 0 in the static solution, the
suction-retained model kept exactly as it was, the linearisation of the same
law, and the paper's Fig. 11 preloads it reproduces.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, case_from_dict, default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.errors import InputError
from foilbearing.reynolds import coupled_system
from foilbearing.stability import onset_speed
from foilbearing.static import film_at_position, solve_equilibrium

RPM = math.pi / 30.0


def _case(volts: float, subambient: str = "lift-off", **grid: int):
    """The default case under the sharp lift-off law (κ = 0), on its grid or ``grid``."""
    case = default_case().with_voltages(volts).with_subambient(subambient)
    return replace(
        case,
        grid=Grid(**grid, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None)
        if grid
        else replace(case.grid, lift_off_smoothing=0.0),
    )


def test_static_film_satisfies_the_complementarity_conditions() -> None:
    # Every cell either obeys the Reynolds equation with P >= 1, or sits exactly at
    # ambient with a net outflow (R < 0) that the lifting foil supplies.
    st = solve_equilibrium(_case(150.0), speed=50e3 * RPM)
    assert st.converged
    m = st.model
    R, _, _ = coupled_system(
        st.P, m.grid, m.h_rigid(st.eps_x, st.eps_y), m.compliance, st.bearing_number
    )
    R = R.reshape(m.grid.shape) / (m.grid.d_theta * m.grid.d_z)
    held = st.P == 1.0
    assert 0.1 < held.mean() < 0.5  # a sizeable region is held, most of the film is not
    assert np.all(st.P[~held] > 1.0)
    assert np.all(R[held] < 0.0)  # net outflow where held
    assert np.max(np.abs(R[~held])) < 1e-9  # the Reynolds equation elsewhere


def test_retained_model_is_the_suction_model_unchanged() -> None:
    # subambient = "retained" is the model before lift-off: the values below were computed
    # by the code before this change (same grid, same inputs). γ = 0: the foil damping law
    # (changed with lift-off) plays no part; 1e-9 relative leaves room for round-off only.
    case = replace(_case(150.0, "retained"), foil=replace(default_case().foil, loss_factor=0.0))
    case = case.with_subambient("retained")
    st = solve_equilibrium(case, speed=90e3 * RPM)
    assert (st.eps_x, st.eps_y) == pytest.approx(
        (0.1039401482828487, 0.11201751371099135), rel=1e-9
    )
    np.testing.assert_allclose(
        st.preload * 1e6, [69.41314027839366, 56.53282887864181, 63.31830359761934], rtol=1e-9
    )
    fc = force_coefficients(st, 0.5 * st.speed)
    np.testing.assert_allclose(
        fc.K[0],
        [[597179.9951770649, 230148.91151850822], [-425398.8541453685, 540148.981371273]],
        rtol=1e-8,
    )
    assert np.min(st.P) < 0.9  # the suction is there


def test_paper_fig11_preloads_within_two_percent() -> None:
    # Paper Fig. 11 (150 V, 90 krpm): 65.36 / 54.06 / 64.62 µm. Under lift-off our model
    # gives them within 2 % (1.1 / 1.6 / 0.9 % measured); the suction-retained model is
    # 6.2 / 4.6 / 2.0 % off. 2.5 %: the viscosity is our assumption (docs/model.md §1).
    paper = np.array([65.36, 54.06, 64.62])
    lift = solve_equilibrium(_case(150.0), speed=90e3 * RPM).preload * 1e6
    kept = solve_equilibrium(_case(150.0, "retained"), speed=90e3 * RPM).preload * 1e6
    assert np.all(np.abs(lift / paper - 1.0) < 0.025)
    assert np.max(np.abs(kept / paper - 1.0)) > 0.05


def test_lift_off_attitude_falls_with_speed_at_150V() -> None:
    # Paper Fig. 12: the attitude angle falls with speed; at 150 V the suction-retained
    # model has it rise from 10 to 50 krpm.
    att = [
        solve_equilibrium(_case(150.0), speed=rpm * RPM).attitude_angle
        for rpm in (10e3, 50e3, 90e3)
    ]
    assert att[0] > att[1] > att[2]


def test_lift_off_converges_with_the_grid() -> None:
    # Grids doubling in both directions (48×6, 96×12, 192×24), 150 V, 50 krpm. Measured
    # (docs/lift-off.md): the force at a fixed journal position converges at order 2.9 and
    # the equilibrium attitude at 2.4 (the held boundary cuts cells, which alone would give
    # order 1; asserted > 1.5); the linear onset speed on the default grid is within 0.05 %
    # of the 192×24 one (asserted 0.2 %).
    forces, attitudes, onsets = [], [], []
    for n_theta, n_z in ((48, 6), (96, 12), (192, 24)):
        case = _case(150.0, n_theta=n_theta, n_z=n_z)
        forces.append(np.array(film_at_position(case, 0.15, 0.08, speed=50e3 * RPM).force))
        attitudes.append(solve_equilibrium(case, speed=50e3 * RPM).attitude_angle)
        if n_theta > 48:
            scan = [rpm * RPM for rpm in range(50_000, 60_001, 5_000)]
            onset = onset_speed(case, scan).onset_speed
            assert onset is not None
            onsets.append(onset)
    for values in (forces, attitudes):
        d1 = np.linalg.norm(np.asarray(values[1]) - values[0])
        d2 = np.linalg.norm(np.asarray(values[2]) - values[1])
        assert math.log2(d1 / d2) > 1.5, values
    assert onsets[0] == pytest.approx(onsets[1], rel=2e-3)


def test_bad_subambient_values() -> None:
    with pytest.raises(InputError, match=r"foil\.subambient = 'gumbel'.*'lift-off', 'retained'"):
        case_from_dict(_case_dict(subambient="gumbel"))
    rigid = replace(default_case(), foil=None, actuators=None)
    with pytest.raises(InputError, match=r"no \[foil\]"):
        rigid.with_subambient("lift-off")
    with pytest.raises(InputError, match="expected one of"):
        default_case().with_subambient("clamped")


def _case_dict(**foil: object) -> dict:
    import tomllib

    from foilbearing.case import default_case_path

    data = tomllib.loads(default_case_path().read_text())
    data["foil"].update(foil)
    return data
