"""Signal analysis on synthetic speed-up records with a known truth.

The record is a 4 s segment of the paper's ramp (3 krpm upwards at
500 rad/s², 20 kHz): a large synchronous response (1X, amplitude varying
slowly), a static offset, noise, and a sub-synchronous tone switched on with a
raised-cosine ramp. The tolerances follow from the analysis window T = 0.25 s:
frequency resolution 1/T = 4 Hz; a windowed amplitude can lead or lag the true
one by at most T/2, i.e. α·T/2 = 62.5 rad/s = 597 rpm of speed, plus one hop
for the discrete windows.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from foilbearing.errors import InputError
from foilbearing.signals import (
    SubsyncResult,
    divergence,
    divergence_speed,
    onset,
    subsynchronous_amplitude,
    waterfall,
)

FS = 20_000.0
ALPHA = 500.0  # rad/s²
W0 = 3000 * math.pi / 30  # rad/s
RPM = 30 / math.pi
T_WIN = 0.25
HOP = T_WIN * 0.25
A1 = 20e-6  # 1X amplitude (mean), m
AW = 5e-6  # whirl amplitude, m
F_W = 120.0  # whirl frequency, Hz
RAMP = 0.1  # switch-on ramp, s
SPEED_TOL_RPM = ALPHA * (T_WIN / 2 + HOP) * RPM  # 895 rpm


def record(duration: float = 4.0, seed: int = 0):
    t = np.arange(round(duration * FS)) / FS
    speed = W0 + ALPHA * t
    phase = W0 * t + 0.5 * ALPHA * t**2
    a1 = A1 * (1 + 0.3 * np.sin(2 * np.pi * 0.3 * t))  # through a mild "critical speed"
    noise = 0.2e-6 * np.random.default_rng(seed).standard_normal(t.size)
    return t, speed, phase, 30e-6 + a1 * np.cos(phase + 0.4) + noise


def switch(t: np.ndarray, t_on: float, t_off: float = np.inf) -> np.ndarray:
    """Raised-cosine envelope 0 → 1 over RAMP from t_on, back to 0 from t_off."""
    up = np.clip((t - t_on) / RAMP, 0, 1)
    down = np.clip((t - t_off) / RAMP, 0, 1)
    return (0.5 - 0.5 * np.cos(np.pi * up)) * (0.5 + 0.5 * np.cos(np.pi * down))


def crossing_rpm(t_on: float, level: float) -> float:
    """Speed at which the switched-on amplitude AW·env crosses ``level``."""
    tc = t_on + RAMP * math.acos(1 - 2 * level / AW) / math.pi
    return (W0 + ALPHA * tc) * RPM


@pytest.fixture(scope="module")
def whirl():
    t, speed, phase, x = record()
    t_on = 2.0
    x = x + AW * switch(t, t_on) * np.cos(2 * np.pi * F_W * t)
    return t, speed, phase, x, t_on


def test_waterfall_ridges(whirl):
    t, speed, _, x, t_on = whirl
    wf = waterfall(t, x, speed)
    assert wf.amplitude.shape == (wf.times.size, wf.frequencies_hz.size)
    run_hz = wf.speeds_rpm / 60
    np.testing.assert_allclose(wf.speeds_rpm, np.interp(wf.times, t, speed) * RPM)
    resolution = 1 / wf.window_s
    f = wf.frequencies_hz[None, :]
    # 1X ridge: the peak above 0.9X lies at the running frequency at the window centre.
    f1 = wf.frequencies_hz[np.argmax(np.where(f > 0.9 * run_hz[:, None], wf.amplitude, 0), axis=1)]
    assert np.max(np.abs(f1 - run_hz)) < resolution
    # The whirl tone: the peak below 0.9X, once it is fully on.
    after = wf.times - wf.window_s / 2 > t_on + RAMP
    fw = wf.frequencies_hz[np.argmax(np.where(f < 0.9 * run_hz[:, None], wf.amplitude, 0), axis=1)]
    assert after.sum() > 10
    assert np.max(np.abs(fw[after] - F_W)) < resolution


def test_waterfall_amplitude_of_a_sinusoid():
    t = np.arange(round(2.0 * FS)) / FS
    amp, f0 = 3.0, 77.3  # off the bin grid on purpose
    wf = waterfall(t, 5.0 + amp * np.sin(2 * np.pi * f0 * t + 1.0), np.full(t.size, 1000.0))
    peak = wf.amplitude.max(axis=1)
    np.testing.assert_allclose(peak, amp, rtol=0.05)
    assert np.all(np.abs(wf.frequencies_hz[wf.amplitude.argmax(axis=1)] - f0) < 1 / wf.window_s)
    assert wf.times[0] >= wf.window_s / 2 - 1e-9  # only windows wholly inside the record


def test_subsync_amplitude_removes_1x(whirl):
    t, speed, phase, x, t_on = whirl
    sub = subsynchronous_amplitude(t, x, speed, phase)
    before = sub.times + sub.window_s / 2 < t_on
    after = sub.times - sub.window_s / 2 > t_on + RAMP
    assert before.sum() > 10 and after.sum() > 10
    # 1X is large (14–26 µm) and tracked, yet the sub-synchronous part reads ~0.
    assert np.all(sub.synchronous_amplitude[before] > 13e-6)
    assert np.max(sub.amplitude[before]) < 0.05 * 0.7 * A1
    np.testing.assert_allclose(sub.amplitude[after], AW, rtol=0.10)
    np.testing.assert_allclose(sub.frequency_hz[after], F_W, atol=2.0)
    assert np.all(np.isnan(sub.frequency_hz[before][2:]))  # noise alone: no frequency


def test_subsync_amplitude_of_a_half_speed_whirl():
    t, speed, phase, x = record()
    x = x + AW * switch(t, 1.5) * np.cos(0.45 * phase)  # whirl tracking 0.45X
    sub = subsynchronous_amplitude(t, x, speed, phase)
    after = sub.times - sub.window_s / 2 > 1.5 + RAMP
    np.testing.assert_allclose(sub.amplitude[after], AW, rtol=0.10)
    np.testing.assert_allclose(sub.frequency_hz[after], 0.45 * sub.speeds_rpm[after] / 60, atol=4.0)


def test_onset_speed_and_frequency(whirl):
    t, speed, phase, x, t_on = whirl
    on = onset(subsynchronous_amplitude(t, x, speed, phase), threshold=1e-6)
    assert on.onset_speed_rpm is not None and on.whirl_frequency_hz is not None
    assert abs(on.onset_speed_rpm - crossing_rpm(t_on, 1e-6)) < SPEED_TOL_RPM
    assert abs(on.whirl_frequency_hz - F_W) < 2.0
    assert len(on.intervals) == 1
    # The same as a fraction of the clearance.
    on_c = onset(subsynchronous_amplitude(t, x, speed, phase), clearance=100e-6, fraction=0.01)
    assert on_c.threshold == pytest.approx(1e-6)
    assert on_c.onset_speed_rpm == pytest.approx(on.onset_speed_rpm)


def test_burst_is_not_onset_but_sustained_intervals_are():
    t, speed, phase, x = record(seed=1)
    tone = np.cos(2 * np.pi * F_W * t)
    # A ~0.1 s burst, at 1.3 s where 0.9X = 138 Hz is clear of the tone.
    burst = x + AW * switch(t, 1.3, 1.3 + 0.05) * tone
    on = onset(subsynchronous_amplitude(t, burst, speed, phase))
    assert on.onset_speed_rpm is None and on.intervals == []
    # The same burst counts once the sustain time is shorter than its windowed length.
    assert (
        len(onset(subsynchronous_amplitude(t, burst, speed, phase), sustain_s=0.1).intervals) == 1
    )

    two = burst + AW * (switch(t, 2.0, 2.7) + switch(t, 3.1, 3.9)) * tone
    on = onset(subsynchronous_amplitude(t, two, speed, phase))
    assert len(on.intervals) == 2
    (s1, e1, f1), (s2, e2, f2) = on.intervals
    assert abs(s1 - crossing_rpm(2.0, 1e-6)) < SPEED_TOL_RPM  # the burst before is skipped
    assert abs(s2 - crossing_rpm(3.1, 1e-6)) < SPEED_TOL_RPM
    assert e1 < s2 < e2 and abs(f1 - F_W) < 2.0 and abs(f2 - F_W) < 2.0
    assert on.onset_speed_rpm == pytest.approx(s1, abs=SPEED_TOL_RPM)


def test_divergence_of_a_growing_whirl():
    clearance = 100e-6
    t, speed, phase, _ = record()
    growth = 2.0  # 1/s
    a = 2e-6 * np.exp(growth * t)
    wt = 2 * np.pi * F_W * t
    e_x = 0.6 * clearance + 5e-6 * np.cos(phase) + a * np.cos(wt)  # big static eccentricity
    e_y = -0.2 * clearance + 5e-6 * np.sin(phase) + a * np.sin(wt)
    t_true = math.log(0.9 * clearance / 2e-6) / growth
    rpm_true = (W0 + ALPHA * t_true) * RPM
    rpm = divergence_speed(t, e_x, e_y, speed, clearance, stopped_by_contact=False)
    assert rpm is not None and abs(rpm - rpm_true) < ALPHA * T_WIN * RPM
    # Nothing diverges before; a contact stop is taken at its time.
    cut = t < t_true - 0.5
    no = divergence_speed(
        t[cut], e_x[cut], e_y[cut], speed[cut], clearance, stopped_by_contact=False
    )
    assert no is None
    # A contact before the radius reaches 0.9 C is the divergence, at its time.
    early = divergence(t, e_x, e_y, speed, clearance, stopped_by_contact=True, contact_time=1.5)
    assert early is not None and early.by == "contact"
    assert early.speed_rpm == pytest.approx((W0 + ALPHA * 1.5) * RPM, rel=1e-12)
    assert not early.contact_after_large_orbit
    # A contact 1.1 s after the radius passed 0.9 C: the divergence is the radius reading
    # (the first of the two), and the contact is marked as following a sustained large orbit.
    late = divergence(t, e_x, e_y, speed, clearance, stopped_by_contact=True, contact_time=3.0)
    assert late is not None and late.by == "orbit radius"
    assert late.speed_rpm == pytest.approx(rpm, rel=1e-12)
    assert late.contact_speed_rpm == pytest.approx((W0 + ALPHA * 3.0) * RPM, rel=1e-12)
    assert abs(late.large_orbit_before_contact_s - (3.0 - t_true)) < T_WIN
    assert late.contact_after_large_orbit


def test_rejects_non_uniform_time():
    t, speed, _, x = record(duration=1.0)
    t = t.copy()
    t[100] += 1e-5
    with pytest.raises(InputError, match="uniformly"):
        waterfall(t, x, speed)


def test_plots_return_figures(whirl):
    from matplotlib.figure import Figure

    from foilbearing.output.plots.orbit import (
        plot_orbits,
        plot_subsync,
        plot_transient,
        plot_waterfall,
        plot_waterfall_3d,
    )

    t, speed, phase, x, _ = whirl
    y = np.roll(x, 50)
    wf = waterfall(t, x, speed)
    sub = subsynchronous_amplitude(t, x, speed, phase)
    on = onset(sub)

    fig = plot_transient(t, x, y, speed, 100e-6)
    assert isinstance(fig, Figure) and len(fig.axes) == 2  # twin speed axis
    fig = plot_waterfall(wf)
    assert len(fig.axes) == 2 and len(fig.axes[0].lines) == 2  # map + colour bar; 1X, 0.5X
    fig = plot_waterfall_3d(wf, max_lines=20)
    assert fig.axes[0].name == "3d" and len(fig.axes[0].lines) == 20
    fig = plot_subsync({"0 V": sub, "50 V": sub}, {"0 V": on})
    assert len(fig.axes[0].lines) == 3  # two cases and one onset marker
    fig = plot_orbits(t, x, y, speed, [10_000, 20_000, 95_000], 100e-6)
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert len(visible) == 3
    assert [len(ax.lines) for ax in visible] == [2, 2, 1]  # the last speed is never reached


def test_order_tracking_reads_a_half_frequency_component_not_a_whirl_at_another_ratio() -> None:
    # Speed-up at 500 rad/s² from 1500 rad/s: 20 µm of 1X throughout, 3 µm of 0.5X between
    # 1.0 and 2.0 s, and 5 µm of a whirl at a fixed 90 Hz (ratio 0.2-0.35, not 0.5).
    from foilbearing.signals import order_amplitude, order_interval

    fs = 10_000.0
    t = np.arange(0.0, 3.0, 1.0 / fs)
    speed = 1500.0 + 500.0 * t
    phase = 1500.0 * t + 250.0 * t**2
    half = np.where((t > 1.0) & (t < 2.0), 3e-6, 0.0)
    x = 20e-6 * np.cos(phase) + half * np.cos(0.5 * phase + 0.3) + 5e-6 * np.sin(2 * np.pi * 90 * t)
    amp = order_amplitude(t, x, phase, 0.5)
    mid = (t > 1.2) & (t < 1.8)
    assert np.allclose(amp[mid], 3e-6, rtol=0.03)  # the 0.5X amplitude, within 3 %
    quiet = (t > 0.3) & (t < 0.8)
    assert np.max(amp[quiet]) < 0.3e-6  # the 90 Hz whirl and 1X leak little
    lo, hi, peak, _ = order_interval(speed, amp, 1.5e-6)
    assert lo == pytest.approx((1500 + 500 * 1.0) * 30 / np.pi, rel=0.02)
    assert hi == pytest.approx((1500 + 500 * 2.0) * 30 / np.pi, rel=0.02)
    assert peak == pytest.approx(3e-6, rel=0.05)
    assert order_interval(speed, amp, 1e-3) is None


def _windows(amp_um: list[float], freq_hz: list[float] | None = None) -> SubsyncResult:
    """Window amplitudes as `subsynchronous_amplitude` would give them: 0.25 s windows,
    the speed rising 1000 rpm per second."""
    t = 0.25 * np.arange(len(amp_um))
    freq = np.full(t.size, np.nan) if freq_hz is None else np.asarray(freq_hz, float)
    a = np.asarray(amp_um, float) * 1e-6
    return SubsyncResult(t, 1000.0 * t, a, freq, np.zeros_like(t), 0.25)


def test_onset_hysteresis_sustain_and_interpolation_on_known_windows() -> None:
    """The onset rule on window amplitudes chosen by hand (threshold 1 µm, release 0.5):
    "on" above the threshold, held between 0.5 and 1 µm, "off" below 0.5 µm; an interval
    counts when it lasts at least the sustain time (0.5 s here: exactly two windows);
    the onset is the linear crossing of the threshold between window centres."""
    nan = math.nan
    sub = _windows(
        [0.2, 0.6, 1.2, 0.5, 1.1, 0.4, 0.3, 1.5, 1.5, 1.5, 0.2],
        [nan, nan, 50.0, 52.0, 54.0, 100.0, nan, 60.0, 61.0, 62.0, nan],
    )
    sub.amplitude[3] = 0.5 * 1e-6  # exactly the release level, as the code forms it
    res = onset(sub, threshold=1e-6, sustain_s=0.5, release=0.5)
    # windows 2-4 (held through 0.5 µm) and 7-9; each exactly 0.5 s long
    assert res.intervals == [(500.0, 1000.0, 52.0), (1750.0, 2250.0, 61.0)]
    t_on = 0.25 + (1.0 - 0.6) / (1.2 - 0.6) * 0.25
    assert res.onset_time_s == pytest.approx(t_on, rel=1e-12)
    assert res.onset_speed_rpm == pytest.approx(1000.0 * t_on, rel=1e-12)
    assert res.whirl_frequency_hz == 52.0 and res.threshold == 1e-6
    # a window held before any crossing is "off"; the onset interpolates into it
    held = onset(_windows([0.6, 1.5, 1.5, 1.5, 0.2]), threshold=1e-6, sustain_s=0.5)
    assert held.intervals[0][:2] == (250.0, 750.0)
    assert held.onset_time_s == pytest.approx(0.25 * (1.0 - 0.6) / (1.5 - 0.6), rel=1e-12)
    assert held.whirl_frequency_hz is None  # no peak found in the interval's windows
    # a short burst before: the crossing is read from the window just before the interval
    after = onset(_windows([1.2, 0.3, 1.1, 1.5, 1.5, 0.2]), threshold=1e-6, sustain_s=0.5)
    assert after.onset_time_s == pytest.approx(0.25 + 0.7 / 0.8 * 0.25, rel=1e-12)
    # motion from the first window: the onset is that window, nothing to interpolate from
    first = onset(_windows([1.5, 1.5, 1.5, 0.2, 0.1]), threshold=1e-6, sustain_s=0.5)
    assert first.onset_time_s == 0.0 and first.intervals[0][:2] == (0.0, 500.0)
    # exactly at the threshold is not above it; a short burst does not count
    level = _windows([0.2, 1.0, 1.0, 1.0, 0.2])
    level.amplitude[1:4] = 1e-6  # exactly the threshold
    at = onset(level, threshold=1e-6, sustain_s=0.5)
    assert at.onset_speed_rpm is None and at.intervals == [] and at.threshold == 1e-6
    short = onset(_windows([0.2, 1.5, 1.5, 0.2]), threshold=1e-6, sustain_s=0.5)
    assert short.onset_speed_rpm is None


def test_the_whirl_frequency_is_read_before_the_divergence() -> None:
    """A whirl at 60-62 Hz that passes 0.9 C and jumps to a large orbit at 235 Hz before
    touching: over the whole interval the median is the large orbit's (which the θ grid
    decides); read up to the divergence it is the whirl's. An interval that begins after
    the divergence keeps its own frequency; a divergence before the first
    interval's first window leaves the interval's median as it was."""
    sub = _windows(
        [0.2, 1.5, 2.0, 3.0, 20.0, 40.0, 40.0, 40.0, 0.2, 0.2, 9.0, 9.0, 9.0],
        [math.nan, 60.0, 61.0, 62.0, 235.0, 235.0, 236.0, 236.0, math.nan, math.nan,
         240.0, 240.0, 240.0],
    )  # fmt: skip
    whole = onset(sub, threshold=1e-6, sustain_s=0.5)
    assert whole.whirl_frequency_hz == 235.0  # the large orbit's, four windows of seven
    # diverged between the windows at 0.75 s and 1.0 s
    read = onset(sub, threshold=1e-6, sustain_s=0.5, diverged_s=0.9)
    assert read.whirl_frequency_hz == 61.0
    assert read.onset_speed_rpm == whole.onset_speed_rpm
    assert [iv[:2] for iv in read.intervals] == [iv[:2] for iv in whole.intervals]
    assert read.intervals[1][2] == whole.intervals[1][2] == 240.0
    # a divergence before the interval's first window (a contact at 0.1 s) changes nothing
    early = onset(sub, threshold=1e-6, sustain_s=0.5, diverged_s=0.1)
    assert early.intervals == whole.intervals and early.whirl_frequency_hz == 235.0


def test_onset_rejects_bad_levels_in_one_line() -> None:
    sub = _windows([0.2, 1.5, 1.5, 1.5, 0.2])
    assert onset(sub, threshold=1e-6, release=1.0).onset_speed_rpm is not None
    for kwargs in (
        {"threshold": 0.0},
        {"threshold": 1e-6, "release": 0.0},
        {"threshold": 1e-6, "release": 1.5},
    ):
        with pytest.raises(InputError, match=r"need threshold > 0 and 0 < release ≤ 1"):
            onset(sub, **kwargs)
    for clearance in (None, 0.0):
        with pytest.raises(InputError, match="needs a positive clearance"):
            onset(sub, fraction=0.01, clearance=clearance)
    assert onset(sub, fraction=0.01, clearance=1e-4).threshold == pytest.approx(1e-6)


def test_subsync_reads_a_sinusoid_between_bins_and_only_inside_the_band() -> None:
    """At a constant 500 Hz (30 krpm), with defaults: a 5 µm sinusoid at 97.3 or 118.9 Hz
    (between the 4 Hz bins) reads 5 µm (Parseval, to 0.1 %) at its own frequency (the
    parabolic interpolation of the log power, measured within 0.001 Hz; asserted to
    0.01 Hz, a four-hundredth of a bin); at 0.88X (inside the 0.9X band) it reads 5 µm, at
    0.95X it is left out (under 0.05 µm)."""
    t = np.arange(round(2.0 * FS)) / FS
    w = 2 * np.pi * 500.0
    speed, phase = np.full(t.size, w), w * t
    inner = slice(3, -3)  # away from the record's ends
    for f in (97.3, 118.9, 440.0):
        x = 20e-6 * np.cos(phase + 0.4) + 5e-6 * np.cos(2 * np.pi * f * t)
        sub = subsynchronous_amplitude(t, x, speed, phase)
        assert sub.times[0] == pytest.approx(0.125, abs=1e-9)  # the first window's centre
        np.testing.assert_allclose(sub.speeds_rpm, 30000.0, rtol=1e-12)
        assert np.abs(sub.frequency_hz[inner] - f).max() < 0.01
        np.testing.assert_allclose(sub.amplitude[inner], 5e-6, rtol=1e-3)
    x = 20e-6 * np.cos(phase + 0.4) + 5e-6 * np.cos(2 * np.pi * 475.0 * t)
    assert subsynchronous_amplitude(t, x, speed, phase).amplitude[inner].max() < 0.05e-6


# --- Mutation testing (issue 18): the rules the readouts rest on, pinned one by one ---


def _steady(duration: float = 1.0, fs: float = 10_000.0, run_hz: float = 100.0, t0: float = 0.0):
    t = t0 + np.arange(round(duration * fs)) / fs
    w = 2 * np.pi * run_hz
    return t, np.full(t.size, w), w * (t - t0)


def test_moving_mean_is_the_centred_mean_of_the_samples_present() -> None:
    """Against a direct loop: n samples centred (half = n // 2 each side), fewer at the
    ends; over one sample it is the signal itself (the tracking filters' limit)."""
    from foilbearing.signals import _moving_mean

    x = np.random.default_rng(1).standard_normal(23) + 1j * np.arange(23)
    for n in (1, 2, 5, 8, 40):
        half = n // 2
        direct = [x[max(0, i - half) : i + half + 1].mean() for i in range(x.size)]
        np.testing.assert_allclose(_moving_mean(x, n), direct, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(_moving_mean(x.real, 1), x.real, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize(
    ("call", "text"),
    [
        (lambda t, s, p, x: waterfall(t[:-1], x, s), "does not match t"),
        (lambda t, s, p, x: waterfall(t, x[:-1], s), "does not match t"),
        (lambda t, s, p, x: waterfall(t, x, s[:-1]), "does not match t"),
        (lambda t, s, p, x: subsynchronous_amplitude(t, x[:-1], s, p), "does not match t"),
        (lambda t, s, p, x: subsynchronous_amplitude(t, x, s[:-1], p), "does not match t"),
        (lambda t, s, p, x: subsynchronous_amplitude(t, x, s, p[:-1]), "does not match t"),
        (lambda t, s, p, x: _order(t, x[:-1], p, 0.5), "does not match t"),
        (lambda t, s, p, x: _order(t, x, p[:-1], 0.5), "does not match t"),
        (lambda t, s, p, x: _order(t, x, p, 0.0), "expected a multiple of the speed > 0"),
        (lambda t, s, p, x: _diverge(t, x[:-1], x, s), "does not match t"),
        (lambda t, s, p, x: _diverge(t, x, x[:-1], s), "does not match t"),
        (lambda t, s, p, x: _diverge(t, x, x, s[:-1]), "does not match t"),
        (lambda t, s, p, x: waterfall(t[:1], x[:1], s[:1]), "at least 2 samples"),
        (lambda t, s, p, x: waterfall(np.vstack([t, t]), x, s), "1-D with at least 2"),
        (lambda t, s, p, x: waterfall(0.0 * t, x, s),
         r"^t must be uniformly sampled and increasing \(resample the orbit first\)$"),
        (lambda t, s, p, x: waterfall(t, x, s, overlap=1.0), r"overlap must be in \[0, 1\)"),
        (lambda t, s, p, x: waterfall(t, x, s, window_s=4e-4), "gives 4 samples; need 8"),
        (lambda t, s, p, x: waterfall(t, x, s, window_s=2.0), "need 8 … 10000"),
        (lambda t, s, p, x: waterfall(t[:30], x[:30], s[:30], window_s=3e-3),
         "record of 0.003 s is too short for 0.003 s windows"),
    ],
)  # fmt: skip
def test_bad_signals_are_one_line_errors_naming_what_is_wrong(call, text) -> None:
    t, speed, phase = _steady()
    x = 1e-6 * np.cos(phase)
    with pytest.raises(InputError, match=text) as err:
        call(t, speed, phase, x)
    assert "\n" not in str(err.value)


def _order(t, x, phase, order):
    from foilbearing.signals import order_amplitude

    return order_amplitude(t, x, phase, order)


def _diverge(t, e_x, e_y, speed, **kw):
    return divergence_speed(t, e_x, e_y, speed, 100e-6, stopped_by_contact=False, **kw)


def test_time_base_tolerance_and_the_limits_of_the_windows() -> None:
    """Steps uniform to 1e-6 of the step are accepted (rounding), 2e-6 is not; a record
    of two samples has a rate; overlap 0 is allowed; a window of exactly 8 samples, or
    exactly the record, is allowed and the record's one window is centred on it. Window
    times are centres, on multiples of the hop from t0 (3 s here), and only windows
    wholly inside the record are kept."""
    from foilbearing.signals import _sampling

    t = np.arange(100) * 1e-4
    assert _sampling(t[:2]) == pytest.approx(1e4)
    jitter = t.copy()
    jitter[50] += 1e-6 * 1e-4  # one step 1e-6 longer and the next 1e-6 shorter
    assert _sampling(jitter) == pytest.approx(1e4, rel=1e-5)
    jitter[50] += 1e-6 * 1e-4
    with pytest.raises(InputError, match="uniformly"):
        _sampling(jitter)
    t, speed, _phase = _steady(duration=0.5, t0=3.0)
    x = 1e-6 * np.cos(2 * np.pi * 40.0 * (t - 3.0))
    none = waterfall(t, x, speed, window_s=0.1, overlap=0.0)
    np.testing.assert_allclose(np.diff(none.times), 0.1, rtol=1e-9)  # no overlap
    assert none.times[0] == pytest.approx(3.1, abs=1e-12)  # [3.05, 3.15): the first inside
    short = waterfall(t, x, speed, window_s=8e-4)
    assert short.times[0] == pytest.approx(3.0004, abs=1e-12)
    one = waterfall(t[:320], x[:320], speed[:320], window_s=0.032)
    assert one.times.tolist() == pytest.approx([3.016], abs=1e-12)
    # hop of one sample at overlap 1 − 1/8 of an 8-sample window
    dense = waterfall(t, x, speed, window_s=8e-4, overlap=0.95)
    np.testing.assert_allclose(np.diff(dense.times), 1e-4, rtol=1e-6)


def test_waterfall_honours_window_and_fmax() -> None:
    """A 0.5 s window gives bins 1/(4 × 0.5) = 0.5 Hz apart; fmax keeps every bin up to
    and including it (1024 Hz sampling: the bins are exact binary fractions)."""
    t, speed, _phase = _steady(duration=2.0, fs=1024.0)
    x = 1e-6 * np.cos(2 * np.pi * 40.0 * t)
    wf = waterfall(t, x, speed, window_s=0.5, fmax_hz=100.0)
    assert np.diff(wf.frequencies_hz) == pytest.approx(0.5) and wf.window_s == 0.5
    assert wf.frequencies_hz[-1] == 100.0
    k = int(np.argmax(wf.amplitude[0]))
    assert wf.frequencies_hz[k] == 40.0 and wf.amplitude[0, k] == pytest.approx(1e-6, rel=1e-3)


def test_subsync_frequency_interpolates_in_hertz_and_the_peak_is_per_window() -> None:
    """With 0.5 s windows (0.5 Hz bins) a tone between bins reads its frequency (the
    interpolation is in bins, scaled by their width); a silent journal reads no
    frequency; a tone buried in broadband noise in its own window reads none, though it
    would stand 20 times above the median of the whole record's quiet windows; an
    explicit noise floor above the amplitude hides the frequency."""
    t, speed, phase = _steady(duration=4.0, run_hz=500.0)
    x = 5e-6 * np.cos(2 * np.pi * 97.3 * t)
    sub = subsynchronous_amplitude(t, x, speed, phase, window_s=0.5)
    assert np.abs(sub.frequency_hz[3:-3] - 97.3).max() < 0.01
    quiet = subsynchronous_amplitude(t, np.zeros(t.size), speed, phase)
    assert np.all(np.isnan(quiet.frequency_hz)) and np.all(quiet.amplitude == 0.0)
    loud = np.where(t > 3.0, 20e-6, 0.0) * np.random.default_rng(2).standard_normal(t.size)
    mixed = subsynchronous_amplitude(t, 1e-6 * np.cos(2 * np.pi * 97.3 * t) + loud, speed, phase)
    early, late = mixed.times < 2.8, mixed.times > 3.2
    assert np.all(np.isfinite(mixed.frequency_hz[early]))
    assert np.all(np.isnan(mixed.frequency_hz[late]))
    hidden = subsynchronous_amplitude(t, x, speed, phase, noise_floor=1e-5)
    assert np.all(np.isnan(hidden.frequency_hz))


def test_order_tracking_limits_and_a_large_static_offset() -> None:
    """At 30 Hz running speed the 0.5X component (15 Hz) of 1 µm, beside a static
    eccentricity 50 times larger (removed, not doubled, before demodulation), reads what
    the slow-part removal leaves of it: 1 − H(15 Hz), H the response of the two passes
    of the 0.1 s boxcar (N = 1001 samples), |sin(πfN/fs) / (N sin(πf/fs))|² = 0.045.
    With a tracking filter under one sample the slow part removed is the signal:
    nothing is left to track."""
    from foilbearing.signals import order_amplitude

    fs, n_box = 10_000.0, 1001
    t, _speed, phase = _steady(duration=2.0, fs=fs, run_hz=30.0)
    x = 50e-6 + 1e-6 * np.cos(0.5 * phase + 0.2)
    amp = order_amplitude(t, x, phase, 0.5)
    mid = (t > 0.4) & (t < 1.6)
    h = (math.sin(math.pi * 15.0 * n_box / fs) / (n_box * math.sin(math.pi * 15.0 / fs))) ** 2
    np.testing.assert_allclose(amp[mid], 1e-6 * (1.0 - h), rtol=1e-3)
    assert order_amplitude(t, x, phase, 0.5, track_s=0.5 / fs).max() < 1e-15  # rounding


def test_order_interval_reads_its_first_last_and_peak_samples() -> None:
    """On a hand-made amplitude profile: the first and last samples above the threshold,
    the peak and the speed at the peak (rpm), each exactly."""
    from foilbearing.signals import order_interval

    speed = np.array([100.0, 200.0, 300.0, 400.0, 500.0, 600.0, 700.0])  # rad/s
    amp = np.array([0.0, 2.0, 3.0, 5.0, 4.0, 2.0, 0.5]) * 1e-6
    lo, hi, peak, at = order_interval(speed, amp, 1.5e-6)
    assert (lo, hi, peak, at) == pytest.approx((200 * RPM, 600 * RPM, 5e-6, 400 * RPM), rel=1e-12)


def test_divergence_reads_the_first_sample_beyond_and_the_last_at_contact() -> None:
    """A whirl turning a quarter turn a sample, its radius growing by 1 µm a sample: the
    speed at the first sample whose distance from the orbit's centre (the mean over the
    three-sample window) exceeds 0.9 C is read exactly, also in a run that stopped by contact
    later (at its last sample, without a contact time). A one-sample window makes the orbit's centre the journal
    itself: no orbit."""
    t = np.arange(200) * 1e-4
    speed = 1000.0 + 10.0 * np.arange(200)
    radius = 1e-6 * np.arange(200)
    angle = 0.5 * np.pi * np.arange(200)
    e_x, e_y = radius * np.cos(angle), radius * np.sin(angle)
    rpm = _diverge(t, e_x, e_y, speed, window_s=2e-4)
    k = int(np.flatnonzero(np.abs((e_x + 1j * e_y) - _centre(e_x + 1j * e_y, 2)) > 90e-6)[0])
    assert rpm == pytest.approx(speed[k] * RPM, rel=1e-12) and k > 80
    # A contact stop without a time is at the last sample; the radius passed 0.9 C first.
    stop = divergence(t, e_x, e_y, speed, 100e-6, stopped_by_contact=True, window_s=2e-4)
    assert stop is not None and stop.by == "orbit radius"
    assert stop.speed_rpm == pytest.approx(speed[k] * RPM, rel=1e-12)
    assert stop.contact_speed_rpm == pytest.approx(speed[-1] * RPM, rel=1e-12)
    # The sustain rule at its edge: the radius over 0.9 C from sample k on, contact put
    # just under and just over LARGE_ORBIT_SUSTAIN_S later (a time grid of 1e-4 s, scaled).
    short = divergence(
        t,
        e_x,
        e_y,
        speed,
        100e-6,
        stopped_by_contact=True,
        contact_time=t[k] + 0.4 * t[1],
        window_s=2e-4,
    )
    assert short is not None and short.by == "orbit radius"
    assert short.large_orbit_before_contact_s == pytest.approx(0.4e-4, rel=1e-9)
    assert not short.contact_after_large_orbit
    assert _diverge(t, e_x, e_y, speed, window_s=0.5e-4) is None


def _centre(z: np.ndarray, n: int) -> np.ndarray:
    """Centred mean over n samples (fewer at the ends), written out."""
    half = n // 2
    return np.array([z[max(0, i - half) : i + half + 1].mean() for i in range(z.size)])


def test_waterfall_colours_a_component_40_db_below_1x_well_above_the_floor() -> None:
    from matplotlib.collections import QuadMesh

    from foilbearing.output.plots.orbit import plot_waterfall
    from foilbearing.signals import Waterfall

    speeds = np.linspace(10_000.0, 60_000.0, 26)  # rpm
    freqs = np.arange(0.0, 1200.0, 4.0)  # Hz
    amp = np.zeros((speeds.size, freqs.size))
    rows = np.arange(speeds.size)
    one_x = np.searchsorted(freqs, speeds / 60.0)
    weak = np.full(speeds.size, np.searchsorted(freqs, 200.0))  # a whirl near 200 Hz
    amp[rows, one_x] = 10e-6  # strong 1X line, 10 µm
    amp[rows, weak] = 10e-6 * 10 ** (-40 / 20)  # 40 dB weaker: 0.1 µm
    wf = Waterfall(speeds / 600.0, speeds, freqs, amp, 0.25)

    fig = plot_waterfall(wf, onset_whirl_hz=205.0)
    ax, bar = fig.axes
    (mesh,) = (c for c in ax.collections if isinstance(c, QuadMesh))
    shown = np.asarray(mesh.get_array()).reshape(-1, speeds.size)  # (frequency, speed)
    colour = np.asarray(mesh.norm(shown))
    # Linear in µm the weak line would sit at 1 % of the range, the floor's colour.
    assert colour[weak[0], :].min() > 0.3  # -40 dB of a -60 dB floor: 1/3 of the way up
    assert colour[one_x[0], 0] == pytest.approx(1.0)
    assert colour.min() == pytest.approx(0.0)  # no amplitude at all: the floor
    assert "dB" in bar.get_ylabel() and "-60" in bar.get_ylabel()
    whirl = [line for line in ax.lines if "onset" in str(line.get_label())]
    assert len(whirl) == 1 and np.allclose(whirl[0].get_ydata(), 205.0)
