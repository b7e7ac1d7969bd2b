"""Signal analysis of a speed-up orbit: waterfall, sub-synchronous amplitude, onset, divergence.

Pure functions on uniformly sampled arrays (the paper's Figs. 13–15, docs/model.md
section 5): ``t`` (s), a journal displacement ``x`` (m, usually e_X, along the
static load), the rotor speed ``speed`` = ω(t) (rad/s) and the rotor angle
``phase`` = φ(t) = ∫ω dt (rad). Speeds are reported in rpm, as in the paper.

Why the defaults
----------------
Windows are 0.25 s long (Hann, 75 % overlap). The sub-synchronous components
of interest are locked near 100–150 Hz (whip at 105 / 127 / 143 Hz for
50 / 100 / 150 V), so the bins must be about 4 Hz (1/0.25 s) to tell them
apart. The price is paid by the 1X ridge: at 500 rad/s² it sweeps
α·T/2π ≈ 20 Hz (1.2 krpm) within one window, so on the waterfall it is
smeared over about five bins and its peak reads low, though in the right
place. (The window that balances the two, T = √(2π/α) ≈ 0.11 s, would blur
the whip frequencies.) The sub-synchronous amplitude does not suffer from the
sweep because 1X is removed by order tracking first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.signal import ShortTimeFFT
from scipy.signal.windows import hann

from foilbearing.constants import RPM
from foilbearing.errors import InputError

__all__ = [
    "Divergence",
    "Onset",
    "SubsyncResult",
    "Waterfall",
    "divergence",
    "divergence_speed",
    "onset",
    "order_amplitude",
    "order_interval",
    "subsynchronous_amplitude",
    "waterfall",
]

WINDOW_S = 0.25
OVERLAP = 0.75
PAD = 4  # zero padding: bins 1/(4T) apart, so a tone between bins reads within 1 %


@dataclass(frozen=True)
class Waterfall:
    """Short-time amplitude spectra of one signal.

    Attributes
    ----------
    times
        Window centres, s, shape (m,).
    speeds_rpm
        Rotor speed at the window centres, rpm, shape (m,).
    frequencies_hz
        Frequencies, Hz, shape (k,); 1/(4·window_s) apart (zero padded).
    amplitude
        Amplitude spectrum, the signal's units, shape (m, k): a sinusoid of
        amplitude A steady over a window reads A at its frequency.
    window_s
        Window length, s; the frequency resolution is about 1/window_s.
    """

    times: np.ndarray
    speeds_rpm: np.ndarray
    frequencies_hz: np.ndarray
    amplitude: np.ndarray
    window_s: float


@dataclass(frozen=True)
class SubsyncResult:
    """Sub-synchronous motion per window (see `subsynchronous_amplitude`).

    Attributes
    ----------
    times
        Window centres, s, shape (m,).
    speeds_rpm
        Rotor speed at the window centres, rpm, shape (m,).
    amplitude
        Sub-synchronous amplitude, m, shape (m,): √2 × the RMS of the remainder
        within the band [f_min_hz, band·X].
    frequency_hz
        Dominant sub-synchronous frequency, Hz, shape (m,); NaN where no peak
        stands above the noise floor.
    synchronous_amplitude
        Amplitude of the removed 1X component at the window centres, m, shape (m,).
    window_s
        Window length, s.
    """

    times: np.ndarray
    speeds_rpm: np.ndarray
    amplitude: np.ndarray
    frequency_hz: np.ndarray
    synchronous_amplitude: np.ndarray
    window_s: float


@dataclass(frozen=True)
class Onset:
    """Onset of sustained sub-synchronous motion (see `onset`).

    Attributes
    ----------
    onset_speed_rpm, onset_time_s
        Where the amplitude first crosses the threshold in the first sustained
        interval (linear interpolation between windows); None if none.
    whirl_frequency_hz
        Median dominant frequency over that first interval (over its windows before the
        divergence, where it diverged: see `onset`), Hz; None if none.
    intervals
        Every sustained interval as (start_rpm, end_rpm, median frequency Hz), the
        frequency read the same way.
    threshold
        The amplitude threshold used, m.
    """

    onset_speed_rpm: float | None
    onset_time_s: float | None
    whirl_frequency_hz: float | None
    intervals: list[tuple[float, float, float]]
    threshold: float


def _sampling(t: np.ndarray, *arrays: np.ndarray) -> float:
    """Sampling rate (Hz) of a uniform time base; checks shapes.

    Uniform means every step within 1e-6 of the median step (plus 1e-12 s): what
    rounding leaves of ``t0 + k·dt``, far below a step's jitter that would bias a
    spectrum.
    """
    if t.ndim != 1 or t.size < 2:
        raise InputError(f"t must be 1-D with at least 2 samples, got shape {t.shape}")
    for a in arrays:
        if a.shape != t.shape:
            raise InputError(f"signal of shape {a.shape} does not match t of shape {t.shape}")
    dt = np.diff(t)
    step = float(np.median(dt))
    if step <= 0 or np.max(np.abs(dt - step)) > 1e-6 * step + 1e-12:
        raise InputError("t must be uniformly sampled and increasing (resample the orbit first)")
    return 1.0 / step


def _moving_mean(x: np.ndarray, n: int) -> np.ndarray:
    """Centred moving mean over n samples; the window shrinks at the ends."""
    half = max(n, 1) // 2
    c = np.concatenate([np.zeros(1, dtype=x.dtype), np.cumsum(x)])
    i = np.arange(x.size)
    lo = np.clip(i - half, 0, x.size)
    hi = np.clip(i + half + 1, 0, x.size)
    return (c[hi] - c[lo]) / (hi - lo)


def _low_pass(x: np.ndarray, n: int) -> np.ndarray:
    # Two passes of a boxcar (a triangle): sidelobes fall as 1/(π f T)², so a
    # component 5/T away leaks < 0.5 % into the slow part.
    return _moving_mean(_moving_mean(x, n), n)


def _frames(n: int, fs: float, window_s: float, overlap: float, magnitude: bool):
    """A ShortTimeFFT with a Hann window and the range of slices inside the record:
    scaled to amplitude (``magnitude``) or, with Σw² = 1, for Parseval's power sums."""
    if not 0.0 <= overlap < 1.0:
        raise InputError(f"overlap must be in [0, 1), got {overlap}")
    nwin = round(window_s * fs)
    if nwin < 8 or nwin > n:
        raise InputError(
            f"window_s = {window_s} s gives {nwin} samples; need 8 … {n} (the record length)"
        )
    hop = max(1, round(nwin * (1.0 - overlap)))
    win = hann(nwin, sym=False)
    if magnitude:
        sft = ShortTimeFFT(
            win, hop, fs, fft_mode="onesided2X", mfft=PAD * nwin, scale_to="magnitude"
        )
    else:
        win = win / np.sqrt(np.sum(win**2))  # Σw² = 1, for Parseval
        sft = ShortTimeFFT(win, hop, fs, fft_mode="onesided", mfft=PAD * nwin)
    # Only slices wholly inside the record: those sticking out are zero padded and read low.
    p0 = sft.lower_border_end[1]
    p1 = sft.upper_border_begin(n)[1]
    if p1 <= p0:
        raise InputError(f"record of {n / fs:.3g} s is too short for {window_s} s windows")
    return sft, p0, p1, nwin


def waterfall(
    t: np.ndarray,
    x: np.ndarray,
    speed: np.ndarray,
    *,
    window_s: float | None = None,
    overlap: float = OVERLAP,
    fmax_hz: float | None = None,
) -> Waterfall:
    """Waterfall of a signal by short-time Fourier transform (Fig. 13b, 14).

    Each window is linearly detrended (the static eccentricity drifts with
    speed), Hann weighted and zero padded ×4; the spectrum is scaled to
    amplitude (``scale_to="magnitude"``, one-sided doubled), so a sinusoid of
    amplitude A steady over the window reads A. Only windows wholly inside the
    record are kept.

    Parameters
    ----------
    t
        Uniform time base, s, shape (n,).
    x
        Signal, any units (m for e_X), shape (n,).
    speed
        Rotor speed ω, rad/s, shape (n,).
    window_s
        Window length, s; None for 0.25 s (module docstring: why).
    overlap
        Fraction of overlap between windows, [0, 1).
    fmax_hz
        Highest frequency kept, Hz; None for all up to Nyquist.

    Returns
    -------
    Waterfall
    """
    t, x, speed = (np.asarray(a, dtype=float) for a in (t, x, speed))
    fs = _sampling(t, x, speed)
    window_s = WINDOW_S if window_s is None else window_s
    sft, p0, p1, _ = _frames(t.size, fs, window_s, overlap, magnitude=True)
    spec = np.abs(sft.stft_detrend(x, "linear", p0=p0, p1=p1)).T
    times = t[0] + sft.t(t.size, p0=p0, p1=p1)
    freqs = sft.f
    keep = freqs <= (fmax_hz if fmax_hz is not None else np.inf)
    return Waterfall(
        times=times,
        speeds_rpm=np.interp(times, t, speed) / RPM,
        frequencies_hz=freqs[keep],
        amplitude=spec[:, keep],
        window_s=float(window_s),
    )


def subsynchronous_amplitude(
    t: np.ndarray,
    x: np.ndarray,
    speed: np.ndarray,
    phase: np.ndarray,
    *,
    window_s: float = WINDOW_S,
    overlap: float = OVERLAP,
    track_s: float = 0.1,
    band: float = 0.9,
    f_min_hz: float = 10.0,
    peak_ratio: float = 20.0,
    noise_floor: float | None = None,
) -> SubsyncResult:
    """Sub-synchronous amplitude and frequency against time and speed (Fig. 15).

    1. The slow part (static eccentricity, drift) is removed: ``x₀ = x − L[x]``,
       where L is a centred moving mean of ``track_s`` applied twice.
    2. 1X is removed by order tracking: its complex amplitude is
       ``a₁(t) = 2 L[x₀ e^{−jφ}]``, and ``r = x₀ − Re(a₁ e^{jφ})``. Demodulating by
       the rotor angle itself makes 1X a slowly varying a₁ however fast the
       speed ramps; a component at f lands at f − ω/2π and is rejected by L
       when that offset is ≫ 1/track_s.
    3. Each window of ``r`` (Hann, as in `waterfall`) gives a power spectrum;
       the amplitude is √2 × the RMS of r within the band
       ``f_min_hz ≤ f ≤ band·ω/2π`` (Parseval over those bins), so a
       sub-synchronous sinusoid of amplitude A reads A. The band drops
       super-synchronous harmonics and the residue of 1X.
    4. The dominant frequency is the band's peak (parabolic interpolation of
       log power between bins); NaN where the peak is under ``peak_ratio`` ×
       the band's median power or the amplitude under ``noise_floor``.

    Parameters
    ----------
    t, x, speed, phase
        Time (s), signal (m), ω (rad/s) and φ = ∫ω dt (rad), shape (n,), uniform in t.
    window_s, overlap
        Analysis windows, s and fraction; 0.25 s gives 4 Hz resolution.
    track_s
        Length of the moving mean L, s; the 1X amplitude may change on this
        time scale (0.1 s is 50 rad/s, 480 rpm, at 500 rad/s²).
    band
        Upper band edge as a fraction of the running frequency.
    f_min_hz
        Lower band edge, Hz, above what step 1 leaves of the slow part.
    peak_ratio
        Peak to median power ratio for a frequency to be reported (20 ≈ 13 dB).
    noise_floor
        Amplitude, m, under which no frequency is reported; None for 10⁻³ of
        the largest amplitude of the run (60 dB).

    Returns
    -------
    SubsyncResult
    """
    t, x, speed, phase = (np.asarray(a, dtype=float) for a in (t, x, speed, phase))
    fs = _sampling(t, x, speed, phase)
    n_track = max(1, round(track_s * fs))
    x0 = x - _low_pass(x, n_track)
    rot = np.exp(1j * phase)
    a1 = 2.0 * _low_pass(x0 * rot.conj(), n_track)
    r = x0 - np.real(a1 * rot)

    sft, p0, p1, _ = _frames(t.size, fs, window_s, overlap, magnitude=False)
    power = np.abs(sft.stft_detrend(r, "constant", p0=p0, p1=p1).T) ** 2  # (m, k)
    times = t[0] + sft.t(t.size, p0=p0, p1=p1)
    run_hz = np.interp(times, t, speed) / (2 * np.pi)
    f = sft.f
    inband = (f >= f_min_hz) & (f[None, :] <= band * run_hz[:, None])
    band_power = np.where(inband, power, 0.0)
    # Parseval with Σw² = 1: mean square = (2/mfft) Σ_one-sided |Y|².
    amplitude = np.sqrt(2.0 * 2.0 / sft.mfft * band_power.sum(axis=1))

    k = np.argmax(band_power, axis=1)
    rows = np.arange(k.size)
    km, kp = np.clip(k - 1, 0, f.size - 1), np.clip(k + 1, 0, f.size - 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        lm, l0, lp = (np.log(power[rows, j]) for j in (km, k, kp))
        delta = np.clip(0.5 * (lm - lp) / (lm - 2 * l0 + lp), -0.5, 0.5)
        peak = band_power[rows, k]
        median = np.nanmedian(np.where(inband, power, np.nan), axis=1)
        floor = 1e-3 * np.max(amplitude) if noise_floor is None else noise_floor
        ok = (peak > peak_ratio * median) & (amplitude >= floor) & inband.any(axis=1)
    frequency = np.where(ok, f[k] + np.nan_to_num(delta) * sft.delta_f, np.nan)
    return SubsyncResult(
        times=times,
        speeds_rpm=run_hz * 60.0,
        amplitude=amplitude,
        frequency_hz=frequency,
        synchronous_amplitude=np.interp(times, t, np.abs(a1)),
        window_s=float(window_s),
    )


def order_amplitude(
    t: np.ndarray,
    x: np.ndarray,
    phase: np.ndarray,
    order: float,
    *,
    track_s: float = 0.1,
) -> np.ndarray:
    """Amplitude of the component of x locked to ``order`` × the rotor speed (m, per sample).

    Order tracking, as for 1X in :func:`subsynchronous_amplitude`: after the
    slow part is removed, ``a(t) = 2 L[x₀ e^{−j·order·φ}]`` with L the moving
    mean of ``track_s`` applied twice, and the amplitude is |a|. A component at
    another frequency f lands at f − order·ω/2π and is rejected by L when that
    offset is ≫ 1/track_s. ``order = 0.5`` reads the half-frequency
    subharmonic the paper reports at 0 V (123-147 Hz at 14.8-17.6 krpm),
    which a sub-synchronous whirl at another ratio does not feed.

    Parameters
    ----------
    t, x, phase
        Time (s), signal (m) and rotor angle φ (rad), uniform in t, shape (n,).
    order
        Multiple of the running frequency, > 0 (0.5 for 0.5X).
    track_s
        Length of the moving mean, s.
    """
    t, x, phase = (np.asarray(a, dtype=float) for a in (t, x, phase))
    fs = _sampling(t, x, phase)
    if not order > 0.0:
        raise InputError(f"order = {order!r}: expected a multiple of the speed > 0, e.g. 0.5")
    n_track = max(1, round(track_s * fs))
    x0 = x - _low_pass(x, n_track)
    return np.abs(2.0 * _low_pass(x0 * np.exp(-1j * order * phase), n_track))


def order_interval(
    speed: np.ndarray, amplitude: np.ndarray, threshold: float
) -> tuple[float, float, float, float] | None:
    """Where an order component exceeds ``threshold`` (m): first and last speed (rpm), its
    peak amplitude (m) and the speed at the peak (rpm); None if it never does."""
    above = np.flatnonzero(amplitude > threshold)
    if above.size == 0:
        return None
    k = int(np.argmax(amplitude))
    return (
        float(speed[above[0]] / RPM),
        float(speed[above[-1]] / RPM),
        float(amplitude[k]),
        float(speed[k] / RPM),
    )


def onset(
    sub: SubsyncResult,
    *,
    threshold: float = 1e-6,
    clearance: float | None = None,
    fraction: float | None = None,
    sustain_s: float = 0.5,
    release: float = 0.5,
    diverged_s: float | None = None,
) -> Onset:
    """Onset speed of sustained sub-synchronous motion, and every unstable interval.

    The motion is "on" from a window whose amplitude exceeds ``threshold``
    until one falls below ``release × threshold`` (hysteresis, so ripple about
    the threshold does not split an interval). An interval counts only if it
    lasts at least ``sustain_s``. Since each amplitude is a window average, a
    burst of duration d reads above threshold for up to d + window_s: the
    default sustain of 0.5 s (two windows) rejects bursts shorter than about
    0.25 s. The onset is the upward threshold crossing of the first sustained
    interval, interpolated linearly between window centres; its error against
    the true crossing is at most half a window (α·window_s/2 in speed: 600 rpm
    at 500 rad/s² and 0.25 s).

    Parameters
    ----------
    sub
        From `subsynchronous_amplitude`.
    threshold
        Amplitude, m (1 µm by default).
    clearance, fraction
        If ``fraction`` is given, the threshold is ``fraction × clearance`` (m).
    sustain_s
        Shortest interval that counts, s.
    release
        Lower hysteresis level as a fraction of the threshold, (0, 1].
    diverged_s
        When the run diverged (s; :func:`divergence`), or None. The frequency of an
        interval that began before it is read over the windows centred before it: the whirl
        that grew, not the orbit of radius about 1.5 C it jumped to (whose frequency, and
        how long it lasts before contact, the film's θ resolution decides: a 0 V, 1 g·mm
        speed-up read 63 Hz on 96 θ cells and 235 Hz on 192 over the whole interval).

    Returns
    -------
    Onset
    """
    if fraction is not None:
        if clearance is None or clearance <= 0:
            raise InputError(f"fraction = {fraction} needs a positive clearance, got {clearance}")
        threshold = fraction * clearance
    if threshold <= 0 or not 0 < release <= 1:
        raise InputError(f"need threshold > 0 and 0 < release ≤ 1, got {threshold}, {release}")
    a = np.nan_to_num(sub.amplitude)
    # Hysteresis without a loop: the state is that of the last set (+1) or reset (−1) event.
    event = np.where(a > threshold, 1, np.where(a < release * threshold, -1, 0))
    last = np.maximum.accumulate(np.where(event != 0, np.arange(a.size), 0))
    on = (event[last] == 1).astype(int)
    edges = np.diff(np.concatenate([[0], on, [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
    intervals: list[tuple[float, float, float]] = []
    first: tuple[int, int] | None = None
    for i0, i1 in zip(starts, stops, strict=True):  # loops over intervals, a handful
        if sub.times[i1] - sub.times[i0] < sustain_s:
            continue
        end = int(i1)  # the last window the frequency is read over
        if diverged_s is not None and sub.times[i0] < diverged_s:
            before = int(np.searchsorted(sub.times, diverged_s, side="left")) - 1
            end = min(max(int(i0), before), end)
        freqs = sub.frequency_hz[i0 : end + 1]
        fmed = float(np.nanmedian(freqs)) if np.isfinite(freqs).any() else math.nan
        intervals.append((float(sub.speeds_rpm[i0]), float(sub.speeds_rpm[i1]), fmed))
        first = first or (int(i0), int(i1))
    if first is None:
        return Onset(None, None, None, [], float(threshold))
    k = first[0]
    t_on = float(sub.times[k])
    if k > 0 and a[k] > a[k - 1]:
        w = (threshold - a[k - 1]) / (a[k] - a[k - 1])
        t_on = float(sub.times[k - 1] + np.clip(w, 0, 1) * (sub.times[k] - sub.times[k - 1]))
    return Onset(
        onset_speed_rpm=float(np.interp(t_on, sub.times, sub.speeds_rpm)),
        onset_time_s=t_on,
        whirl_frequency_hz=None if math.isnan(intervals[0][2]) else intervals[0][2],
        intervals=intervals,
        threshold=float(threshold),
    )


#: A contact that followed an orbit of radius over the divergence fraction of C for at least
#: this long (s) "follows a sustained large orbit": its speed is set by how the film's grid
#: resolves a near-touching orbit, not by the whirl's growth (docs/lift-off.md).
LARGE_ORBIT_SUSTAIN_S = 0.5


@dataclass(frozen=True)
class Divergence:
    """Where a speed-up diverges: the first of the orbit-radius criterion and contact.

    Attributes
    ----------
    speed_rpm, time_s
        Speed (rpm) and time (s) of the divergence.
    by
        ``"orbit radius"`` (the orbit's radius first exceeded the fraction of C) or
        ``"contact"`` (the run touched before the radius criterion met).
    contact_speed_rpm
        Speed at contact (rpm), None for a run that did not touch.
    large_orbit_before_contact_s
        How long the orbit's radius stayed over the fraction of C before contact, s
        (0 when it touched first, or did not touch).
    """

    speed_rpm: float
    time_s: float
    by: str
    contact_speed_rpm: float | None
    large_orbit_before_contact_s: float

    @property
    def contact_after_large_orbit(self) -> bool:
        """A contact that followed a sustained large orbit (``LARGE_ORBIT_SUSTAIN_S``): the
        contact speed is then not a converged readout; the orbit-radius one is."""
        return self.large_orbit_before_contact_s >= LARGE_ORBIT_SUSTAIN_S


def divergence(
    t: np.ndarray,
    e_x: np.ndarray,
    e_y: np.ndarray,
    speed: np.ndarray,
    clearance: float,
    *,
    stopped_by_contact: bool,
    contact_time: float | None = None,
    fraction: float = 0.9,
    window_s: float = WINDOW_S,
) -> Divergence | None:
    """Where the journal motion diverges: the first of two events; None if neither.

    - the orbit's radius exceeds ``fraction × clearance``: the radius is the distance of
      the journal centre from the orbit's centre, a centred moving mean of (e_x, e_y)
      over ``window_s`` (so a static eccentricity, however large, does not count);
    - contact, at ``contact_time`` (the last sample if None) of a run that stopped there.

    The radius criterion is the well-posed readout: a whirl that has jumped to an orbit
    of radius about 1.5 C touches at a speed that the film's θ resolution decides (the
    minimum film of such an orbit is a fraction of a micrometre), while the speed at which
    its radius passes 0.9 C converges with the grid. A contact that followed such an orbit
    for ``LARGE_ORBIT_SUSTAIN_S`` or longer is marked as such.

    Parameters
    ----------
    t, e_x, e_y, speed
        Time (s), journal position (m), ω (rad/s), shape (n,), uniform in t.
    clearance
        Radial clearance C, m.
    stopped_by_contact, contact_time
        Whether and when (s) the simulation stopped at contact.
    fraction
        Orbit radius, as a fraction of C, taken as divergence (0.9).
    window_s
        Averaging length for the orbit centre, s.
    """
    t, e_x, e_y, speed = (np.asarray(a, dtype=float) for a in (t, e_x, e_y, speed))
    fs = _sampling(t, e_x, e_y, speed)
    n = max(1, round(window_s * fs))
    z = e_x + 1j * e_y
    radius = np.abs(z - _moving_mean(z, n))
    over = np.flatnonzero(radius > fraction * clearance)
    t_radius = float(t[over[0]]) if over.size else None
    if not stopped_by_contact:
        if t_radius is None:
            return None
        return Divergence(float(speed[over[0]] / RPM), t_radius, "orbit radius", None, 0.0)
    t_contact = float(t[-1] if contact_time is None else contact_time)
    contact_rpm = float(np.interp(t_contact, t, speed) / RPM)
    if t_radius is None or t_radius >= t_contact:
        return Divergence(contact_rpm, t_contact, "contact", contact_rpm, 0.0)
    return Divergence(
        float(speed[over[0]] / RPM), t_radius, "orbit radius", contact_rpm, t_contact - t_radius
    )


def divergence_speed(
    t: np.ndarray,
    e_x: np.ndarray,
    e_y: np.ndarray,
    speed: np.ndarray,
    clearance: float,
    **options: Any,
) -> float | None:
    """Speed (rpm) at which the journal motion diverges (`divergence`); None if it does
    not. Parameters and keyword options as for `divergence`."""
    d = divergence(t, e_x, e_y, speed, clearance, **options)
    return None if d is None else d.speed_rpm
