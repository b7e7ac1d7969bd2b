"""Speed profiles, voltage programs and the closed-loop controller, against closed forms.

These run in milliseconds: they are the tests ``make mutation`` runs against the
mutants of ``control/``. The speed profile's angle is checked against a quadrature of
its speed, the voltage program against linear interpolation written out, and the
controller's sub-synchronous amplitude against the amplitude of a synthetic sinusoid.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from foilbearing.control import (
    SpeedProfile,
    SubsyncController,
    VoltageSchedule,
    constant_speed,
    linear_ramp,
    voltage_ramp,
)
from foilbearing.errors import InputError

RPM = math.pi / 30.0


def _profile() -> SpeedProfile:
    # Up at 200 rad/s², down at 50 rad/s², up at 50 rad/s²: three segments, so that every
    # breakpoint's angle but the last is used inside the profile.
    return SpeedProfile(np.array([0.0, 1.0, 3.0, 4.0]), np.array([100.0, 300.0, 200.0, 250.0]))


@pytest.mark.parametrize("t", [0.0, 0.25, 0.999, 1.0, 1.7, 2.5, 3.0, 3.5, 4.0])
def test_speed_profile_angle_is_the_integral_of_its_speed(t: float) -> None:
    """ω and dω/dt are the piecewise-linear profile's; φ(t) = ∫₀ᵗ ω dt (quadrature, 1e-10);
    the vectorised ``speed_and_phase`` gives the same (ω, φ) as ``state``."""
    prof = _profile()
    w, a, phi = prof.state(t)
    w_ref = float(np.interp(t, prof.times, prof.speeds))
    assert w == pytest.approx(w_ref, rel=1e-14)
    assert a == (200.0 if t < 1.0 else -50.0 if t < 3.0 else 50.0)
    phi_ref = quad(lambda s: np.interp(s, prof.times, prof.speeds), 0.0, t, points=[1.0, 3.0])[0]
    assert phi == pytest.approx(phi_ref, rel=1e-10, abs=1e-12)
    assert prof.omega(t) == w and prof.phase(t) == phi
    w_v, phi_v = prof.speed_and_phase(np.array([t, 0.5]))
    assert w_v[0] == pytest.approx(w, rel=1e-14)
    assert phi_v[0] == pytest.approx(phi, rel=1e-14, abs=1e-14)
    assert phi_v[1] == pytest.approx(prof.phase(0.5), rel=1e-14)


def test_speed_profile_holds_its_end_speeds() -> None:
    """Outside the profile ω is held at its end values; the slope is that of the nearest
    segment; the duration is the last breakpoint."""
    prof = _profile()
    assert prof.duration == 4.0
    assert prof.state(5.0)[0] == 250.0 and prof.state(5.0)[1] == 50.0
    assert prof.state(-0.5)[0] == 100.0 and prof.state(-0.5)[1] == 200.0
    w_v, phi_v = prof.speed_and_phase(np.array([-0.5, 5.0]))
    np.testing.assert_array_equal(w_v, [100.0, 250.0])
    np.testing.assert_allclose(phi_v, [prof.state(-0.5)[2], prof.state(5.0)[2]], rtol=1e-14)


def test_profiles_and_programs_store_float_arrays() -> None:
    """Breakpoints given as lists of ints are stored as float arrays (a program of ints
    must still interpolate in volts, not truncate)."""
    prof = SpeedProfile([0, 2], [100, 300])  # type: ignore[arg-type]
    assert isinstance(prof.times, np.ndarray) and isinstance(prof.speeds, np.ndarray)
    assert prof.times.dtype == float and prof.speeds.dtype == float
    assert prof.state(1.0) == pytest.approx((200.0, 100.0, 150.0), rel=1e-14)
    prog = VoltageSchedule([0, 3], [[0, 10], [1, 20]])  # type: ignore[arg-type]
    assert isinstance(prog.times, np.ndarray) and prog.times.dtype == float
    assert prog.volts.dtype == float and prog.volts.shape == (2, 2)
    np.testing.assert_allclose(prog(1.0), [1 / 3, 40 / 3], rtol=1e-14)
    assert linear_ramp(10.0, 20.0, 0.5).duration == 20.0  # a slow ramp is allowed


def test_voltage_schedule_hold_is_per_segment() -> None:
    """A segment holds only where its two rows are equal: up, hold, down and up again."""
    prog = VoltageSchedule(
        np.array([0.0, 1.0, 2.0, 3.0, 4.0]), np.array([[0.0], [100.0], [100.0], [0.0], [100.0]])
    )
    for t, v in [(0.5, 50.0), (1.5, 100.0), (2.5, 50.0), (3.25, 25.0), (3.75, 75.0)]:
        np.testing.assert_allclose(prog(t), [v], rtol=1e-14)
    back = VoltageSchedule(np.array([0.0, 1.0, 2.0]), np.array([[0.0], [0.0], [100.0]]))
    np.testing.assert_allclose(back(1.5), [50.0], rtol=1e-14)
    np.testing.assert_array_equal(back(0.5), [0.0])


def test_paper_ramp_and_constant_speed() -> None:
    """The paper's speed-up, 3 to 90 krpm at 500 rad/s², lasts 18.22 s; a constant speed
    turns through ω t."""
    ramp = linear_ramp(3000 * RPM, 90_000 * RPM, 500.0)
    assert ramp.duration == pytest.approx(87_000 * RPM / 500.0, rel=1e-14)
    assert ramp.duration == pytest.approx(18.22, abs=0.005)
    assert ramp.state(ramp.duration / 2)[0] == pytest.approx(46_500 * RPM, rel=1e-12)
    const = constant_speed(2000.0, 0.5)
    assert const.state(0.3) == pytest.approx((2000.0, 0.0, 600.0), rel=1e-14)
    assert const.duration == 0.5


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (
            lambda: SpeedProfile(np.array([0.0]), np.array([1.0])),
            "speed profile: need matching times and speeds, at least two",
        ),
        (
            lambda: SpeedProfile(np.array([0.0, 1.0]), np.array([1.0, 2.0, 3.0])),
            "speed profile: need matching times and speeds, at least two",
        ),
        (
            lambda: SpeedProfile(np.array([0.1, 1.0]), np.array([1.0, 2.0])),
            "speed profile: times must start at 0 s and increase",
        ),
        (
            lambda: SpeedProfile(np.array([0.0, 1.0, 1.0]), np.array([1.0, 2.0, 3.0])),
            "speed profile: times must start at 0 s and increase",
        ),
        (
            lambda: SpeedProfile(np.array([0.0, 1.0]), np.array([1.0, 0.0])),
            "speed profile: speeds must be > 0 rad/s, got 0",
        ),
        (
            lambda: SpeedProfile(np.array([0.0, 1.0]), np.array([1.0, np.inf])),
            "speed profile: speeds must be > 0 rad/s, got 1",
        ),
        (lambda: constant_speed(100.0, 0.0), "duration = 0.0 s: must be > 0"),
        (
            lambda: linear_ramp(100.0, 200.0, 0.0),
            "speed ramp: acceleration 0.0 rad/s² must be > 0",
        ),
        (
            lambda: linear_ramp(3000 * RPM, 3000 * RPM, 500.0),
            "speed ramp: ends at 3000 rpm, below or at its start 3000 rpm",
        ),
    ],
)
def test_bad_speed_profiles_are_one_line_errors(make, message: str) -> None:
    with pytest.raises(InputError) as err:
        make()
    assert str(err.value) == message


def test_voltage_schedule_interpolates_holds_and_steps() -> None:
    """Linear between breakpoints, held before the first and after the last, held on a
    segment of equal rows, and a repeated time is a step: the later row applies from it."""
    prog = VoltageSchedule(
        np.array([1.0, 2.0, 3.0, 3.0, 4.0]),
        np.array([[0.0, 10.0], [100.0, 30.0], [100.0, 30.0], [50.0, 0.0], [150.0, 0.0]]),
    )
    np.testing.assert_array_equal(prog(0.0), [0.0, 10.0])
    np.testing.assert_allclose(prog(1.25), [25.0, 15.0], rtol=1e-14)
    np.testing.assert_allclose(prog(1.5), [50.0, 20.0], rtol=1e-14)
    np.testing.assert_array_equal(prog(2.0), [100.0, 30.0])
    np.testing.assert_array_equal(prog(2.5), [100.0, 30.0])
    np.testing.assert_array_equal(prog(2.999), [100.0, 30.0])
    np.testing.assert_array_equal(prog(3.0), [50.0, 0.0])
    np.testing.assert_allclose(prog(3.75), [125.0, 0.0], rtol=1e-14)
    np.testing.assert_array_equal(prog(9.0), [150.0, 0.0])
    # The program's arrays are never handed out to be written.
    prog(9.0)[0] = -1.0
    prog(0.0)[0] = -1.0
    prog(2.5)[0] = -1.0
    assert prog.volts[-1, 0] == 150.0 and prog.volts[0, 0] == 0.0 and prog.volts[1, 0] == 100.0
    assert not prog.observes and prog.checkpoint() == {}
    prog.observe(1.0, 1e-6, 0.0)
    prog.restore({"triggered_at": 1.0})
    np.testing.assert_allclose(prog(1.5), [50.0, 20.0], rtol=1e-14)


def test_voltage_ramp_is_the_papers_protocol() -> None:
    """0 to 150 V between 6.0 and 6.5 s; a per-actuator initial voltage broadcasts."""
    ramp = voltage_ramp(6.0, 6.5, 150.0)
    np.testing.assert_array_equal(ramp(5.0), [0.0])
    np.testing.assert_allclose(ramp(6.25), [75.0], rtol=1e-14)
    np.testing.assert_array_equal(ramp(7.0), [150.0])
    ramp3 = voltage_ramp(0.0, 1.0, 100.0, initial=[0.0, 20.0, 40.0])
    np.testing.assert_allclose(ramp3(0.5), [50.0, 60.0, 70.0], rtol=1e-14)
    step = voltage_ramp(2.0, 2.0, 50.0)
    np.testing.assert_array_equal(step(1.999), [0.0])
    np.testing.assert_array_equal(step(2.0), [50.0])


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (
            lambda: VoltageSchedule(np.array([0.0, 1.0]), np.array([[0.0], [1.0], [2.0]])),
            "voltage program: times must be non-decreasing, one row per time",
        ),
        (
            lambda: VoltageSchedule(np.array([1.0, 0.5]), np.array([[0.0], [1.0]])),
            "voltage program: times must be non-decreasing, one row per time",
        ),
        (
            lambda: VoltageSchedule(np.zeros(0), np.zeros((0, 1))),
            "voltage program: times must be non-decreasing, one row per time",
        ),
        (
            lambda: voltage_ramp(2.0, 1.0, 50.0),
            "voltage ramp 2 s to 1 s: need 0 <= start <= end",
        ),
        (
            lambda: voltage_ramp(-1.0, 1.0, 50.0),
            "voltage ramp -1 s to 1 s: need 0 <= start <= end",
        ),
    ],
)
def test_bad_voltage_programs_are_one_line_errors(make, message: str) -> None:
    with pytest.raises(InputError) as err:
        make()
    assert str(err.value) == message


def test_voltage_program_check_names_the_limit() -> None:
    """A program is checked against the stack's limit (0 to max_voltage, both ends allowed)
    and the number of actuators (one column, or one per actuator)."""
    ok = VoltageSchedule(np.array([0.0, 1.0]), np.array([[0.0, 150.0, 0.0], [150.0, 0.0, 0.0]]))
    ok.check(150.0, 3)
    VoltageSchedule(np.array([0.0]), np.array([[150.0]])).check(150.0, 3)
    with pytest.raises(InputError) as err:
        ok.check(150.0, 2)
    assert str(err.value) == "voltage program has 3 columns; the case has 2 actuators"
    with pytest.raises(InputError) as err:
        ok.check(149.0, 3)
    assert str(err.value) == (
        "voltage program reaches 150 V (min 0 V): allowed 0 to 149 V (max_voltage)"
    )
    neg = VoltageSchedule(np.array([0.0]), np.array([[-1.0, 10.0]]))
    with pytest.raises(InputError) as err:
        neg.check(150.0, 2)
    assert str(err.value) == (
        "voltage program reaches 10 V (min -1 V): allowed 0 to 150 V (max_voltage)"
    )


def _feed(ctrl: SubsyncController, t_end: float, e_x, dt: float = 1e-4, t0: float = 0.0):
    """Samples of e_x(t, φ) at 10 kHz, φ = ω t at 1000 rad/s (159 Hz)."""
    omega = 1000.0
    for t in np.arange(t0, t_end, dt):
        ctrl.observe(float(t), e_x(t, omega * t), omega * t)


def test_controller_reads_the_subsynchronous_amplitude_of_a_sinusoid() -> None:
    """Over a window of whole periods, the offset and the 1X component are removed and the
    remainder's √2·RMS is the sub-synchronous amplitude: 3 µm at 0.43X reads 3 µm (2 %, a
    0.1 s window holds 6.8 of its periods); 1X and offset alone read below 1 % of the 1X."""
    ctrl = SubsyncController(threshold=5e-6, window=0.1, period=0.01)
    ctrl.check(150.0, 3)

    def motion(t, phi):
        return 20e-6 + 8e-6 * np.cos(phi + 0.3) + 3e-6 * np.sin(0.43 * phi + 1.0)

    _feed(ctrl, 0.3, motion)
    assert ctrl.amplitude == pytest.approx(3e-6, rel=0.02)
    assert ctrl.triggered_at is None  # 3 µm < 5 µm
    clean = SubsyncController(threshold=5e-6)
    _feed(clean, 0.3, lambda t, phi: 20e-6 + 8e-6 * np.cos(phi + 0.3))
    assert clean.amplitude < 0.01 * 8e-6


def test_controller_latches_and_slews_to_its_target() -> None:
    """It triggers at the first control instant (every ``period``, once 16 samples are in)
    where the amplitude exceeds the threshold, and stays triggered; the applied voltage,
    asked at every sample as the orbit does, moves towards the target at the slew rate and
    stops there."""
    ctrl = SubsyncController(threshold=2e-6, target=120.0, slew_rate=1000.0, initial=10.0)
    ctrl.check(150.0, 3)
    dt, omega = 1e-4, 1000.0
    times = np.arange(0.0, 0.6, dt)
    volts = np.empty(times.size)
    for i, t in enumerate(times):
        v = ctrl(float(t))
        assert v.shape == (3,) and np.all(v == v[0])
        volts[i] = v[0]
        e_x = 5e-6 * math.sin(0.5 * omega * t) if 0.2 <= t < 0.4 else 0.0
        ctrl.observe(float(t), e_x, omega * t)
    t_trig = ctrl.triggered_at
    # 5 µm over a fraction f of the 0.1 s window reads about 5√f µm: above 2 µm from f ≈ 0.16
    assert t_trig is not None and 0.215 < t_trig < 0.24
    np.testing.assert_array_equal(volts[times <= t_trig], 10.0)
    # 1000 V/s: 50 V in 50 ms (to one sample's 0.1 V), the target 110 ms on, and held there
    # after the motion stops (the latch).
    assert np.interp(t_trig + 0.05, times, volts) == pytest.approx(60.0, abs=0.11)
    np.testing.assert_allclose(np.diff(volts)[times[1:] <= t_trig + 0.1], 0.0, atol=0.1 + 1e-9)
    np.testing.assert_array_equal(volts[times >= t_trig + 0.111], 120.0)
    assert ctrl.triggered_at == t_trig


def test_controller_window_and_period() -> None:
    """Only the last ``window`` seconds of samples count: a burst that ended more than a
    window ago reads nothing at the next control instant; at most one estimate per period."""
    ctrl = SubsyncController(threshold=1.0, window=0.05, period=0.02)  # never triggers

    def burst(t, phi):
        return 4e-6 * np.sin(0.5 * phi) if t < 0.1 else 0.0 * phi

    _feed(ctrl, 0.1, burst)
    assert ctrl.amplitude == pytest.approx(4e-6, rel=0.05)
    _feed(ctrl, 0.17, burst, t0=0.1)  # the last estimate, at 0.1615 s, sees no burst
    assert ctrl.amplitude == pytest.approx(0.0, abs=1e-12)
    ctrl.observe(0.175, 1.0, 175.0)  # within the period: no new estimate
    assert ctrl.amplitude == pytest.approx(0.0, abs=1e-12)
    ctrl.observe(0.182, 0.0, 182.0)  # a period on: the 1 m sample is in the estimate
    assert ctrl.amplitude > 0.01


def test_controller_checkpoint_restores_latch_and_voltage() -> None:
    """A controller restored from a checkpoint applies the same voltages from then on; an
    untriggered checkpoint stores NaN and restores no latch; a checkpoint without the keys
    (an older file) changes nothing."""
    ctrl = SubsyncController(threshold=2e-6, target=150.0, slew_rate=100.0, initial=20.0)
    ctrl.check(150.0, 2)
    ctrl(0.0)
    _feed(ctrl, 0.3, lambda t, phi: 5e-6 * np.sin(0.5 * phi))
    assert ctrl.triggered_at is not None
    ctrl(0.2)
    ctrl(0.35)
    state = ctrl.checkpoint()
    assert state["triggered_at"] == ctrl.triggered_at and state["controller_time"] == 0.35
    assert 20.0 < state["controller_volts"] < 150.0  # mid-slew
    other = SubsyncController(threshold=2e-6, target=150.0, slew_rate=100.0, initial=20.0)
    other.check(150.0, 2)
    other.restore({k: np.array([v]) for k, v in state.items()})
    for t in (0.36, 0.4, 0.6, 2.0):
        np.testing.assert_array_equal(other(t), ctrl(t))
    fresh = SubsyncController()
    assert math.isnan(fresh.checkpoint()["triggered_at"])
    fresh.restore({"triggered_at": math.nan, "controller_volts": 5.0, "controller_time": 1.0})
    assert fresh.triggered_at is None
    np.testing.assert_array_equal(fresh(1.0), np.full(3, 5.0))
    old = SubsyncController(initial=7.0)
    old.restore({})
    assert old.triggered_at is None
    np.testing.assert_array_equal(old(1.0), np.full(3, 7.0))
    partial = SubsyncController(initial=7.0)
    partial.restore({"controller_volts": 99.0})
    np.testing.assert_array_equal(partial(1.0), np.full(3, 7.0))


@pytest.mark.parametrize(
    "kwargs",
    [{"threshold": 0.0}, {"slew_rate": 0.0}, {"window": 0.0}, {"period": 0.0}],
)
def test_bad_controller_settings(kwargs) -> None:
    with pytest.raises(InputError) as err:
        SubsyncController(**kwargs)
    assert str(err.value) == "controller: threshold, slew_rate, window and period must be > 0"
    SubsyncController(threshold=0.5, slew_rate=0.5, window=0.5, period=0.5)  # small is fine


@pytest.mark.parametrize(("target", "initial"), [(151.0, 0.0), (-1.0, 0.0), (100.0, 151.0)])
def test_controller_check_names_the_limit(target: float, initial: float) -> None:
    ctrl = SubsyncController(target=target, initial=initial)
    with pytest.raises(InputError) as err:
        ctrl.check(150.0, 3)
    assert str(err.value) == (
        f"controller target {target:g} V / initial {initial:g} V: allowed 0 to 150 V (max_voltage)"
    )
    SubsyncController(target=150.0, initial=150.0).check(150.0, 3)
    SubsyncController(target=0.0, initial=0.0).check(150.0, 3)
