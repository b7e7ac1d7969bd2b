"""The orbit on variable, error-controlled steps (``OrbitSettings(steps="adaptive")``):
its accuracy against a fine fixed-step run, its stop event and its resume."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from foilbearing.case import Grid, default_case
from foilbearing.control import constant_speed
from foilbearing.orbit import OrbitSettings, simulate

RPM = math.pi / 30.0


def coarse(volts: float, imbalance: float):
    """The default case at ``volts`` on the 32 × 4 grid, without its random disturbance."""
    case = default_case().with_voltages(volts)
    grid = Grid(n_theta=32, n_z=4, lift_off_smoothing=0.0, orbit_n_z=None, orbit_axial_order=None)
    return replace(
        case,
        grid=grid,
        disturbance=None,
        rotor=replace(case.rotor, imbalance=imbalance),
    )


def adaptive(rtol: float = OrbitSettings.step_rtol, **kw: float) -> OrbitSettings:
    return OrbitSettings(steps="adaptive", step_rtol=rtol, **kw)


def test_adaptive_steps_meet_the_accuracy_of_the_default_against_128_steps_a_revolution() -> None:
    # Issue 49's target: 0.05 s at 20 krpm, 100 V, 8.5 g·mm from the static equilibrium,
    # the largest deviation of e_X from 128 steps a revolution within 1.2 % of its
    # peak-to-peak (the default's accuracy: fixed BDF3 at 24 a revolution, 1.20 %).
    # Measured: rtol 3e-3 / 1e-3 / 3e-4 give 3.9 / 1.00 / 0.66 % at 272 / 356 / 472 steps
    # (the default 403): the tolerance sets the error, and the default rtol meets the
    # target in fewer steps.
    case = default_case().with_voltages(100.0)
    prof = constant_speed(20e3 * RPM, 0.05)
    ref = simulate(case, prof, settings=OrbitSettings(steps_per_rev=128, sample_rate=20_000))
    fixed = simulate(case, prof, settings=OrbitSettings(sample_rate=20_000))
    amp = float(np.ptp(ref.e_x))
    errors, steps = [], []
    for rtol in (3e-3, 1e-3, 3e-4):
        res = simulate(case, prof, settings=adaptive(rtol, sample_rate=20_000))
        assert res.status == "completed" and res.time.size == ref.time.size
        errors.append(float(np.max(np.abs(res.e_x - ref.e_x))) / amp)
        steps.append(res.steps)
    assert errors[0] > errors[1] > errors[2] and steps[0] < steps[1] < steps[2]
    assert errors[1] < 0.012 and steps[1] < fixed.steps


def test_adaptive_steps_stop_at_contact_with_the_fixed_steps() -> None:
    # 0 V at 60 krpm is linearly unstable on this grid (onset 45.5 krpm): the whirl grows
    # to contact within 0.04 s, and the contact event ends the adaptive run as it ends the
    # fixed one. Measured: contact at 37.53 ms against 37.81 ms (−0.7 %, a quarter of a
    # revolution in a whirl that grows from 1 g·mm), in 474 steps against 910.
    case = coarse(0.0, 1e-6)
    prof = constant_speed(60e3 * RPM, 0.5)
    fixed = simulate(case, prof)
    res = simulate(case, prof, settings=adaptive())
    assert fixed.contact is not None and res.status == "contact" and res.contact is not None
    assert 0.0 < res.contact["min_film_um"] < 2.0 and "contact at" in res.message
    assert res.contact["time_s"] == pytest.approx(fixed.contact["time_s"], rel=0.02)
    assert res.steps < fixed.steps


def test_an_adaptive_run_resumes_to_the_run_in_one_go() -> None:
    # Stopped at 0.01 s and resumed from its result: the resumed run takes the step the
    # error control had chosen (kept in the checkpoint) and ends on the run in one go's
    # orbit within the Newton tolerance, its step count the whole run's within a few.
    case = coarse(100.0, 1e-6)
    prof = constant_speed(20e3 * RPM, 0.02)
    whole = simulate(case, prof, settings=adaptive())
    first = simulate(case, prof, settings=adaptive(), stop_time=0.01)
    assert "h_next" in first.checkpoint
    rest = simulate(case, prof, settings=adaptive(), resume=first)
    assert rest.status == "completed" and rest.time.size == whole.time.size
    assert rest.steps - first.steps < 0.6 * whole.steps and abs(rest.steps - whole.steps) <= 6
    # Measured: 2.9e-4 C at most; 97 steps against 93 (the stop's landing step and the
    # steps after it).
    np.testing.assert_allclose(rest.e_x, whole.e_x, atol=1e-3 * case.bearing.clearance)


def test_the_samples_between_long_steps_follow_a_whirl_and_are_the_ones_a_controller_saw() -> None:
    # A 1X orbit recorded on irregular steps of 10-20 a revolution: the backward cubic
    # misses it by at most 0.04 (ωΔt)⁴ of its amplitude (0.6 % at ωΔt = 2π/10; linear
    # interpolation would miss by up to (ωΔt)²/8 = 5 %), and the samples handed out one
    # step at a time (Samples.new_samples, for a controller) equal the stored ones.
    from foilbearing.orbit.sampling import Samples, backward_cubic

    omega = 2 * math.pi * 300.0
    rng = np.random.default_rng(49)
    steps = 2 * math.pi / omega / rng.uniform(10.0, 20.0, 200)
    t = np.concatenate([[0.0], np.cumsum(steps)])
    x = np.cos(omega * t)
    ts = np.arange(0.0, t[-1], 1e-4)
    cubic = backward_cubic(ts, t, x)
    late = ts > t[3]
    bound = 0.04 * (omega * steps.max()) ** 4
    assert np.max(np.abs(cubic - np.cos(omega * ts))[late]) < bound
    assert np.max(np.abs(np.interp(ts, t, x) - np.cos(omega * ts))) > 5 * bound
    out = Samples(1e-4, cubic=True)
    seen = []
    for tk, xk in zip(t, x, strict=True):
        out.t.append(float(tk))
        out.ex.append(float(xk))
        seen += out.new_samples()
    got = np.array(seen)
    np.testing.assert_allclose(got[:, 0], ts[: len(got)], atol=1e-12)
    np.testing.assert_allclose(got[:, 1], cubic[: len(got)], atol=1e-12)
