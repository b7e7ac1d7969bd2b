"""Linear stability: whirl eigenvalues with frequency-consistent coefficients and onset speeds."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import default_case
from foilbearing.coefficients import force_coefficients
from foilbearing.stability import onset_speed, stability_map, whirl_mode
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0
SCAN = [rpm * RPM for rpm in range(5_000, 100_001, 5_000)]


def test_whirl_eigenvalue_solves_the_characteristic_equation() -> None:
    """Two independent routes to the least stable whirl mode agree: ``whirl_mode`` (the
    eigenvalues of the 4 x 4 state matrix, iterated to a consistent frequency) and a root
    of the scalar characteristic function det(m s² I + C(Im s) s + K(Im s)) found by
    scipy's ``fsolve`` from the undamped estimate sqrt(K_YY/m) (another seed, another
    algorithm, the coefficients recomputed at every trial frequency)."""
    from scipy.optimize import fsolve

    case = default_case().with_voltages(150.0)
    st = solve_equilibrium(case, speed=30e3 * RPM)
    m = case.rotor.mass
    mode = whirl_mode(st, m)

    def char(x: np.ndarray) -> list[float]:
        s = complex(x[0], x[1])
        fc = force_coefficients(st, abs(x[1]))
        k, c = fc.K[0], fc.C[0]
        det = np.linalg.det(m * s**2 * np.eye(2) + c * s + k) / np.linalg.norm(k) ** 2
        return [det.real, det.imag]

    k0 = force_coefficients(st, 0.5 * st.speed).K[0]
    seed = [0.0, math.sqrt(abs(k0[1, 1]) / m)]
    root, _info, ok, msg = fsolve(char, seed, full_output=True, xtol=1e-10)
    assert ok == 1, msg
    assert complex(*root) == pytest.approx(mode.eigenvalue, rel=1e-5)


def test_heavier_rotor_goes_unstable_earlier() -> None:
    # A rigid rotor on gas bearings: the threshold speed falls as the mass rises.
    case = default_case().with_voltages(150.0)
    onsets = []
    for mass in (0.6, 0.897, 1.5):
        c = replace(case, rotor=replace(case.rotor, mass=mass))
        res = onset_speed(c, SCAN)
        assert res.onset_speed is not None
        onsets.append(res.onset_speed)
    assert onsets[0] > onsets[1] > onsets[2]


def test_foil_damping_raises_onset_speed() -> None:
    case = default_case().with_voltages(150.0)
    assert case.foil is not None
    low = replace(case, foil=replace(case.foil, loss_factor=0.05))
    high = replace(case, foil=replace(case.foil, loss_factor=0.2))
    a, b = onset_speed(low, SCAN), onset_speed(high, SCAN)
    assert a.onset_speed is not None and b.onset_speed is not None
    assert b.onset_speed > a.onset_speed


def test_onset_is_where_log_decrement_changes_sign() -> None:
    case = default_case().with_voltages(100.0)
    res = onset_speed(case, SCAN)
    assert res.onset_speed is not None
    for factor, sign in ((0.97, 1.0), (1.03, -1.0)):
        st = solve_equilibrium(case, speed=factor * res.onset_speed)
        assert sign * whirl_mode(st, case.rotor.mass).log_decrement > 0


def test_preload_voltage_delays_onset() -> None:
    # A strong preload (100 or 150 V) stiffens the film and delays the onset well past the
    # bearing without preload (measured 43.6 krpm at 0 V, 57.9 / 55.0 krpm at 100 / 150 V:
    # the two strong preloads differ by 5 %, in no fixed order); the shimmed GFB (rigid
    # preload) is more stable than the C-GFB at the same base preload (90.5 krpm at 150 V).
    case = default_case()
    o0 = onset_speed(case.with_voltages(0.0), SCAN).onset_speed
    o100 = onset_speed(case.with_voltages(100.0), SCAN).onset_speed
    o150 = onset_speed(case.with_voltages(150.0), SCAN).onset_speed
    shim = onset_speed(case.with_voltages(150.0).shimmed(), SCAN).onset_speed
    assert o0 is not None and o100 is not None and o150 is not None and shim is not None
    assert min(o100, o150) > 1.2 * o0
    assert shim > 1.4 * o150


def test_stability_map_dataset() -> None:
    ds = stability_map(default_case(), [10e3 * RPM, 80e3 * RPM], [0.0, 150.0])
    assert ds.log_decrement.shape == (2, 2)
    assert np.all(np.isfinite(ds.log_decrement))
    # Both bearings are stable at 10 krpm and unstable at 80 krpm (onsets 43.6 and 55.0 krpm).
    assert np.all(ds.log_decrement.sel(speed=10.0) > 0)
    assert np.all(ds.log_decrement.sel(speed=80.0) < 0)
