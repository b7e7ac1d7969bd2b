"""The onset scan and the stability map, rule by rule, on a coarse grid (32 x 4).

Each readout of ``onset_speed`` and ``stability_map`` is checked against whirl modes
found on their own (``whirl_mode`` at equilibria solved from the centre). The grid is
coarse so that these tests stay fast enough to run against every mutant of
``stability.py`` (``make mutation``); the physics on the default grid is in
``test_stability.py``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import default_case
from foilbearing.stability import onset_speed, stability_map, whirl_mode
from foilbearing.static import solve_equilibrium

RPM = math.pi / 30.0


def _coarse(volts: float = 100.0):
    from foilbearing.case import Grid

    return replace(
        default_case().with_voltages(volts),
        grid=Grid(
            n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None
        ),
    )


def test_onset_scan_bracket_and_brent_on_a_coarse_grid() -> None:
    """The scan's record and the Brent refinement, checked against whirl modes found on
    their own (32 x 4 grid): the speeds scanned are the sorted input up to the first
    unstable one; their log decrements and whirl ratios are those of ``whirl_mode`` at
    equilibria solved from the centre; the onset lies in the bracket and its log decrement
    is zero to Brent's tolerance; the whirl ratio and frequency are the onset's; one
    progress line per speed scanned; the messages say what was found."""
    from foilbearing.errors import InputError, SolverError
    from foilbearing.stability import OnsetResult

    case = _coarse()
    m = case.rotor.mass
    scan = [80e3 * RPM, 20e3 * RPM, 40e3 * RPM, 60e3 * RPM, 100e3 * RPM]  # unsorted
    lines: list[str] = []
    res = onset_speed(case, scan, progress=lines.append, rel_tol=1e-6)
    assert res.onset_speed is not None
    k = len(res.speeds) - 1
    np.testing.assert_array_equal(res.speeds, sorted(scan)[: k + 1])
    assert len(lines) == k + 1
    assert lines[0] == (
        f"{20000:8.0f} rpm: log dec {res.log_decrement[0]:+.4f}, "
        f"whirl ratio {res.whirl_ratios[0]:.3f}"
    )
    for w, dec, ratio in zip(res.speeds, res.log_decrement, res.whirl_ratios, strict=True):
        mode = whirl_mode(solve_equilibrium(case, speed=w), m)
        assert dec == pytest.approx(mode.log_decrement, rel=1e-5, abs=1e-7)
        assert ratio == pytest.approx(mode.whirl_ratio, rel=1e-5)
    assert np.all(res.log_decrement[:-1] > 0) and res.log_decrement[-1] < 0
    lo, hi = res.speeds[-2], res.speeds[-1]
    assert lo < res.onset_speed < hi
    at = whirl_mode(solve_equilibrium(case, speed=res.onset_speed), m)
    assert abs(at.log_decrement) < 1e-3
    assert res.whirl_ratio == pytest.approx(at.whirl_ratio, rel=1e-4)
    assert res.whirl_frequency == pytest.approx(at.whirl_frequency, rel=1e-4)
    assert res.whirl_frequency == pytest.approx(res.whirl_ratio * res.onset_speed, rel=1e-9)
    assert (
        res.message
        == f"onset between {lo / RPM:.0f} and {hi / RPM:.0f} rpm, refined by Brent's method"
    )
    head = res.headline()
    assert set(head) == {"onset_speed_rpm", "whirl_frequency_Hz", "whirl_ratio", "message"}
    assert head["onset_speed_rpm"] == pytest.approx(res.onset_speed / RPM, rel=1e-12)
    assert head["whirl_frequency_Hz"] == pytest.approx(res.whirl_frequency / (2 * math.pi))
    assert head["whirl_ratio"] == res.whirl_ratio and head["message"] == res.message
    # the default scan (5 to 150 krpm by 5 krpm; a light load, carried at 5 krpm) and
    # Brent's default tolerance
    light = replace(case, operation=replace(case.operation, load=1.0))
    default = onset_speed(light)
    np.testing.assert_allclose(default.speeds[:2] / RPM, [5000, 10000], rtol=1e-12)
    assert default.onset_speed is not None
    on = whirl_mode(solve_equilibrium(light, speed=default.onset_speed), m)
    assert abs(on.log_decrement) < 1e-2

    first = onset_speed(case, [hi, 1.1 * hi])
    assert first.onset_speed == hi and first.speeds.tolist() == [hi]
    assert first.message == "unstable already at the lowest speed of the scan"
    assert first.log_decrement.tolist() == [pytest.approx(res.log_decrement[-1], rel=1e-5)]
    assert first.whirl_ratios.tolist() == [pytest.approx(res.whirl_ratios[-1], rel=1e-5)]
    assert first.whirl_ratio == pytest.approx(res.whirl_ratios[-1], rel=1e-5)
    assert first.whirl_frequency == pytest.approx(first.whirl_ratio * hi, rel=1e-9)
    stable = onset_speed(case, [20e3 * RPM, 25e3 * RPM, 30e3 * RPM])
    assert stable.onset_speed is None and stable.speeds.size == 3
    expected = [
        whirl_mode(solve_equilibrium(case, speed=w), case.rotor.mass).log_decrement
        for w in (20e3 * RPM, 25e3 * RPM, 30e3 * RPM)
    ]
    np.testing.assert_allclose(stable.log_decrement, expected, rtol=1e-5)
    assert stable.whirl_ratios.size == 3 and np.all(stable.whirl_ratios > 0)
    assert stable.message == "stable up to 30000 rpm"
    assert stable.headline()["onset_speed_rpm"] is None
    assert isinstance(stable, OnsetResult) and stable.whirl_frequency is None
    assert stable.whirl_ratio is None
    needs = (
        r"^no static equilibrium at 1000 rpm \(.*\); the linear stability analysis needs "
        r"one: narrow the speed range$"
    )
    with pytest.raises(SolverError, match=needs):
        onset_speed(case.with_voltages(150.0), [1000 * RPM, 20e3 * RPM])
    for bad in ([20e3 * RPM], [0.0, 20e3 * RPM]):
        with pytest.raises(InputError, match=r"^the onset search needs at least two speeds > 0$"):
            onset_speed(case, bad)


def test_stability_map_entries_are_the_whirl_modes_at_their_points() -> None:
    """Each entry of the map is the least stable mode at that speed and voltage (32 x 4),
    on the C-GFB and, with ``shimmed``, on the shimmed bearing; speeds are sorted and
    given in krpm; one progress line per voltage; a case without actuators is refused."""
    from foilbearing.errors import InputError

    case = _coarse()
    speeds, volts = [60e3 * RPM, 20e3 * RPM], [0.0, 150.0]
    lines: list[str] = []
    for shimmed in (False, True):
        ds = stability_map(case, speeds, volts, shimmed=shimmed, progress=lines.append)
        assert ds.speed.values.tolist() == [20.0, 60.0] and ds.voltage.values.tolist() == volts
        assert ds.attrs["bearing"] == ("shimmed" if shimmed else "C-GFB")
        assert ds.attrs["rotor_mass_kg"] == case.rotor.mass
        for v in volts:
            c = case.with_voltages(v)
            c = c.shimmed() if shimmed else c
            for w in sorted(speeds):
                mode = whirl_mode(solve_equilibrium(c, speed=w), c.rotor.mass)
                point = ds.sel(voltage=v, speed=w / RPM / 1e3)
                assert float(point.log_decrement) == pytest.approx(mode.log_decrement, rel=1e-5)
                assert float(point.whirl_ratio) == pytest.approx(mode.whirl_ratio, rel=1e-5)
    assert lines == ["stability map: 0 V done", "stability map: 150 V done"] * 2
    # integer voltages, the default (C-GFB), units; a speed without equilibrium is NaN
    # and the scan goes on past it
    ds = stability_map(case, [1000 * RPM, 20e3 * RPM], [0, 150])
    assert ds.attrs["bearing"] == "C-GFB" and ds.voltage.dtype == float
    assert ds.voltage.attrs["units"] == "V" and ds.speed.attrs["units"] == "krpm"
    assert ds.log_decrement.dtype == float and ds.whirl_ratio.dtype == float
    assert np.all(np.isnan(ds.log_decrement.sel(speed=1.0)))
    assert np.all(np.isnan(ds.whirl_ratio.sel(speed=1.0)))
    assert np.all(np.isfinite(ds.log_decrement.sel(speed=20.0)))
    passive = replace(case, actuators=None)
    with pytest.raises(
        InputError, match=r"^a stability map over voltages needs a case with \[actuators\]$"
    ):
        stability_map(passive, speeds, volts)


def test_onsets_per_voltage_are_the_onsets_of_each_case() -> None:
    """The onset per voltage (32 x 4) is onset_speed of the case at that voltage, on the C-GFB
    and with shimmed on its shimmed twin; one progress line per voltage; a case without
    actuators is refused."""
    from foilbearing.errors import InputError
    from foilbearing.stability import onsets_per_voltage

    case = _coarse()
    scan = [20e3 * RPM, 60e3 * RPM, 100e3 * RPM]
    lines: list[str] = []
    got = onsets_per_voltage(case, [0.0, 150.0], scan, progress=lines.append)
    shim = onsets_per_voltage(case, [150.0], scan, shimmed=True)
    assert list(got) == [0.0, 150.0] and len(lines) == 2 and lines[1].startswith("150 V: ")
    for volt, res in got.items():
        assert res.onset_speed == onset_speed(case.with_voltages(volt), scan).onset_speed
    assert (
        shim[150.0].onset_speed
        == onset_speed(case.with_voltages(150.0).shimmed(), scan).onset_speed
    )
    with pytest.raises(
        InputError, match=r"^the onset over voltages needs a case with \[actuators\]$"
    ):
        onsets_per_voltage(replace(case, actuators=None), [0.0], scan)


def test_whirl_eigenvalues_of_a_damped_oscillator_in_closed_form() -> None:
    """m s² + c s + k = 0 in X and Y (m = 2 kg): s = −c/2m ± j √(k/m − (c/2m)²); only the
    roots with Im s > 0 are whirl modes. An over-damped direction has none, and a mode
    whirling below 1 rad/s is still one."""
    from foilbearing.stability import _whirl_eigenvalues

    m = 2.0
    K, C = np.diag([8e5, 2e6]), np.diag([300.0, 100.0])
    got = np.sort_complex(_whirl_eigenvalues(m, K, C))
    want = [complex(-c / (2 * m), math.sqrt(k / m - (c / (2 * m)) ** 2)) for k, c in
            ((8e5, 300.0), (2e6, 100.0))]  # fmt: skip
    np.testing.assert_allclose(got, np.sort_complex(np.array(want)), rtol=1e-12)
    over = _whirl_eigenvalues(m, np.diag([8e5, 1.0]), np.diag([300.0, 1e4]))
    assert over.size == 1 and over[0].real == pytest.approx(-75.0)  # Y over-damped
    slow = _whirl_eigenvalues(m, np.diag([0.5, 0.5]), np.zeros((2, 2)))  # √(k/m) = 0.5 rad/s
    np.testing.assert_allclose(slow, [0.5j, 0.5j], atol=1e-12)


class _Coefficients:
    """Stand-in for the film's coefficients, as a function of the whirl frequency."""

    def __init__(self, K, C) -> None:
        self.K_of, self.C_of, self.calls = K, C, 0

    def __call__(self, static, w_e, workspace=None):
        from types import SimpleNamespace

        self.calls += 1
        w = float(np.ravel(w_e)[0])
        return SimpleNamespace(K=np.array([self.K_of(w)]), C=np.array([self.C_of(w)]))


def _point(speed: float):
    from types import SimpleNamespace

    from foilbearing.reynolds import FilmGrid

    return SimpleNamespace(speed=speed, model=SimpleNamespace(grid=FilmGrid(8, 2, 0.875)))


def test_whirl_mode_with_constant_cross_coupled_coefficients(monkeypatch) -> None:
    """K = [[k, q], [−q, k]], C = c I (m = 2 kg): the forward and backward whirls solve
    m s² + c s + k ∓ jq = 0 (the complex form, another route than the 4 x 4 state
    matrix). The least stable mode is the forward one, δ = −2π Re s / Im s; coefficients
    that do not depend on frequency are consistent at the first iteration."""
    import foilbearing.stability as stab

    m, k, q, c = 2.0, 1e6, 3e5, 200.0
    coeffs = _Coefficients(lambda w: np.array([[k, q], [-q, k]]), lambda w: c * np.eye(2))
    monkeypatch.setattr(stab, "force_coefficients", coeffs)
    mode = whirl_mode(_point(1000.0), m)
    roots = np.concatenate([np.roots([m, c, k - 1j * q]), np.roots([m, c, k + 1j * q])])
    whirls = roots[roots.imag > 0]
    dec = -2 * math.pi * whirls.real / whirls.imag
    assert mode.eigenvalue == pytest.approx(whirls[np.argmin(dec)], rel=1e-10)
    assert mode.log_decrement == pytest.approx(dec.min(), rel=1e-10) and dec.min() < 0
    assert mode.whirl_ratio == pytest.approx(mode.eigenvalue.imag / 1000.0, rel=1e-12)
    assert mode.iterations == 1 and mode.speed == 1000.0
    np.testing.assert_array_equal(mode.K, [[k, q], [-q, k]])
    np.testing.assert_array_equal(mode.C, c * np.eye(2))


def test_whirl_mode_iteration_converges_past_a_two_cycle(monkeypatch) -> None:
    """A stiffness whose natural frequency falls 1.2 times as fast as the whirl frequency
    rises, √(K(ω_e)/m) = 520 − 1.2 (ω_e − 520) rad/s: the plain fixed-point iteration
    ω_e ← Im s oscillates with growing amplitude; damped after 10 iterations it converges
    to the consistent mode, Im s(ω_e) = ω_e, found here by Brent's method on the 2 x 2
    problem in closed form. Y is over-damped, so one whirl mode is followed."""
    from scipy.optimize import brentq

    import foilbearing.stability as stab

    m, c = 1.0, 20.0

    def natural(w: float) -> float:
        return 520.0 - 1.2 * (w - 520.0)

    # X whirls; Y is over-damped (no whirl), so each iteration has one eigenvalue to follow
    coeffs = _Coefficients(
        lambda w: np.diag([m * natural(w) ** 2, 1.0]), lambda w: np.diag([c, 1e4])
    )
    monkeypatch.setattr(stab, "force_coefficients", coeffs)
    mode = whirl_mode(_point(1000.0), m)

    def im_s(w: float) -> float:
        return math.sqrt(natural(w) ** 2 - (c / (2 * m)) ** 2)

    consistent = brentq(lambda w: im_s(w) - w, 400.0, 650.0, xtol=1e-12)
    assert mode.whirl_frequency == pytest.approx(consistent, rel=1e-5)
    assert mode.eigenvalue.real == pytest.approx(-c / (2 * m), rel=1e-9)
    assert 10 < mode.iterations < 40
