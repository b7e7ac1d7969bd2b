"""The paper's speed-ups (Figs. 13-15) beside ours: linear onsets and orbit runs.

Each row says how far apart (a percentage, or in words where the paper gives no number),
and in one sentence why, with the section of the theory pages that explains it; the
paper's values are comparison targets only (:mod:`foilbearing.paper`).
"""

from __future__ import annotations

import math
from typing import Any

from foilbearing.paper import (
    DEFAULT_CASE,
    LIMIT_CYCLES,
    PROTOCOL,
    READINGS,
    REPORTED,
    Row,
    _agrees,
    _dev,
)

__all__ = ["orbit_comparison", "stability_comparison"]

#: How the study names the paper's reading of the actuator in its rows' titles.
PAPERS = "the paper's: "


#: The paper's speed-ups (Figs. 13-15) at each final voltage: what it says, the speed (krpm)
#: where its run diverged (None: none to 90 krpm), its whip frequency (Hz) and whip onset.
_PAPER_RUNS: dict[float, tuple[str, float | None, float | None, float | None]] = {
    0.0: ("whirl from ~15 krpm at 123-147 Hz, gone by ~19 krpm; whip diverges at ~33 krpm",
          33.0, None, None),
    50.0: ("whip ~105 Hz, diverges at 44.4 krpm", 44.4, 105.0, None),
    100.0: ("no divergence up to 90 krpm; bounded whip ~127 Hz", None, 127.0, None),
    150.0: ("no divergence up to 90 krpm; whip onset 79.1 krpm, ~143 Hz", None, 143.0, 79.1),
}  # fmt: skip


def stability_comparison(
    onsets: dict[str, dict[float, Any]],
    errors: dict[str, dict[float, dict[str, Any]]] | None = None,
) -> list[Row]:
    """Linear onset speeds beside the paper's nonlinear orbit observations (Figs. 13-15).

    ``errors`` (kind → voltage → :func:`~foilbearing.study.converged.published_onsets`'
    entry): where given, each kind (the C-GFB, its shimmed twin, both with the suction
    retained, the paper's reading, lobe + held) is printed at the published resolution (the
    grid refined by 2, κ ≤ 0.02) with its error, and the C-GFB's grid value beside it.
    """
    errors = errors or {}
    why = {
        0.0: ("at 0 V no reading of the actuator enters (no preload): a linear onset against "
              "a divergence in a speed-up, with the viscosity and rotor mass assumed",
              DEFAULT_CASE),
        50.0: ("the paper's 44.4 krpm is where its ramped run diverged, past its onset; ours "
               "is where the whirl starts to grow, with 50 V held from the start", REPORTED),
        100.0: ("the paper gives no onset at 100 V, only a whip that stays bounded: whether "
                "ours would is the limit cycles' question", LIMIT_CYCLES),
        150.0: ("the case reads the actuator as local + compliant, its stack giving way at "
                "the whirl; the paper's dynamic prediction reads it as lobe + held", READINGS),
    }  # fmt: skip
    rows = []
    for volt, res in onsets.get("C-GFB", {}).items():
        h = res.headline()
        shim_txt = ""
        for kind, label in (
            ("shimmed", "shimmed twin"),
            ("C-GFB, suction retained", "suction retained"),
            ("shimmed, suction retained", "shimmed, suction retained"),
            ("C-GFB, lobe+held", "the paper's reading (lobe + held)"),
        ):
            other = onsets.get(kind, {}).get(volt)
            conv = errors.get(kind, {}).get(volt, {})
            if conv.get("refined_grid"):
                shim_txt += f"; {label} {conv['onset_refined_text_krpm']} krpm{_at(conv)}"
            elif other is not None and other.onset_speed is not None:
                shim_txt += f"; {label} {other.headline()['onset_speed_rpm'] / 1e3:.1f} krpm"
        onset, whirl, ratio = h["onset_speed_rpm"], h["whirl_frequency_Hz"], h["whirl_ratio"]
        own = errors.get("C-GFB", {}).get(volt, {})
        whirl_text = None if whirl is None else f"{whirl:.0f}"
        if own.get("refined_grid"):  # set beside the paper at the published resolution
            whirl = own["whirl_frequency_refined_Hz"]
            ratio = whirl / (own["onset_refined_rpm"] / 60.0)
            whirl_text = own.get("whirl_refined_text_Hz") or f"{whirl:.0f}"
        value = (
            f"{own['onset_refined_text_krpm']} krpm{_at(own)} ({own['onset_text_krpm']} on "
            f"the case's grid, {own['onset_error_source']} the larger part)"
            if own.get("refined_grid")
            else f"{0.0 if onset is None else onset / 1e3:.1f} krpm"
        )
        ours = (
            "stable over the scan"
            if onset is None
            else f"{value}, {whirl_text} Hz (ratio {ratio:.2f})"
        )
        text, diverges, whip, whip_onset = _PAPER_RUNS.get(volt, ("", None, None, None))
        if own.get("refined_grid"):  # set beside the paper at the published resolution
            onset = own["onset_refined_rpm"]
        reason, where = why.get(
            volt, (f"the paper has no run at {volt:g} V to set a linear onset against", REPORTED)
        )
        rows.append(
            Row(
                f"onset of instability, C-GFB at {volt:g} V",
                text or f"(no run at {volt:g} V)",
                ours + shim_txt,
                _onset_deviation(volt, onset, whirl, diverges, whip, whip_onset),
                "linear onset: " + reason,
                where,
            )
        )
    return rows


def _at(entry: dict[str, Any]) -> str:
    """ " on 192 × 24, κ 0.02": where a published onset was solved."""
    n, m = entry["refined_grid"]
    return f" on {n} × {m}, κ {entry.get('refined_kappa', 0.0):g}"


def _onset_deviation(
    volt: float,
    onset_rpm: float | None,
    whirl_hz: float | None,
    diverges: float | None,
    whip: float | None,
    whip_onset: float | None,
) -> str:
    """A linear onset against the paper's speed-up at the same voltage, in numbers or words."""
    if volt not in _PAPER_RUNS:
        return f"not in the paper: no run at {volt:g} V"
    if onset_rpm is None:
        return (
            f"contradicts: paper diverges at {diverges:g} krpm; ours stable over the scan"
            if diverges is not None
            else "agrees: stable, as the paper's run stays bounded"
        )
    parts = []
    if whip_onset is not None:
        parts.append(f"onset {_dev(onset_rpm / 1e3, whip_onset)} (its whip onset)")
    elif diverges is not None:
        parts.append(f"onset {_dev(onset_rpm / 1e3, diverges)} (its divergence)")
    if whip is not None and whirl_hz is not None:
        parts.append(f"whirl {_dev(whirl_hz, whip)} (its whip)")
    return "; ".join(parts)


def orbit_comparison(
    runs: list[dict[str, Any]],
    linear_onsets_rpm: dict[float, float | None] | None = None,
    disturbance_rms: float = 0.0,
    reading: str | None = None,
    onset_texts_krpm: dict[float, str] | None = None,
) -> list[Row]:
    """The speed-up runs beside the paper's Figs. 13-15 (docs/model.md §6).

    ``reading`` names the reading of the actuator in the film that made the runs
    (for example ``"local + compliant"``, docs/model.md §3.8) in each row.

    ``linear_onsets_rpm`` (final voltage → linear onset, rpm) places each run's
    divergence against the linear onset at its final voltage: an onset read from a
    ramped nonlinear run is not a linear onset (like with like). ``disturbance_rms``
    (N) is the case's random force on the rotor, the seed of the whirls (0: none).
    ``onset_texts_krpm`` (final voltage → the linear onset with its error, krpm, e.g.
    ``"71.1 ± 1.2"``) prints those in place of the onset to 0.1 krpm.
    """
    rows = []
    for run in runs:
        v = float(run["voltage_V"])
        parts = [
            f"sub-synchronous {a / 1e3:.1f}-{b / 1e3:.1f} krpm at {f:.0f} Hz"
            for a, b, f in run.get("subsync_intervals_rpm_Hz", [])
        ]
        seeds = run.get("subsync_onset_seeds") or {}
        if seeds.get("range_rpm"):
            lo, hi = seeds["range_rpm"]
            parts.append(
                f"sub-synchronous onset {lo / 1e3:.1f}-{hi / 1e3:.1f} krpm over "
                f"{len(seeds['seeds'])} seeds of the disturbance"
            )
        diverged = [d for d in seeds.get("divergence_speed_rpm") or [] if d is not None]
        if len(diverged) > 1:
            parts.append(
                f"divergence {min(diverged) / 1e3:.1f}-{max(diverged) / 1e3:.1f} krpm over "
                f"{len(diverged)} seeds"
                + (
                    f" ({len(seeds['seeds']) - len(diverged)} without one)"
                    if len(diverged) < len(seeds["seeds"])
                    else ""
                )
            )
        div = run.get("divergence_speed_rpm")
        parts.append(
            _diverges(run)
            if div
            else f"no divergence up to {(run.get('end_speed_rpm') or 0) / 1e3:.0f} krpm"
        )
        grid_error = (run.get("theta_refined") or run.get("grid_floor") or {}).get("text")
        if grid_error:  # the readouts with their grid error (study.orbits.readout_errors,
            # or floor_errors for a run that was not refined)
            parts.append(grid_error)
        seed_floor = (run.get("seed_floor") or {}).get("text")
        if seed_floor:  # a controlled run under one seed (study.orbits.seed_floor)
            parts.append(seed_floor)
        lin = (linear_onsets_rpm or {}).get(v)
        if lin and div:
            lin_text = (onset_texts_krpm or {}).get(v) or f"{lin / 1e3:.1f}"
            parts.append(
                f"{100.0 * (div / lin - 1.0):+.0f} % from the linear onset at {v:g} V "
                f"({lin_text} krpm)"
            )
        half = run.get("half_order")
        if v == 0.0:
            parts.insert(
                0,
                "0.5X component below 1 µm throughout"
                if not half
                else f"0.5X component > 1 µm from {half['from_rpm'] / 1e3:.1f} to "
                f"{half['to_rpm'] / 1e3:.1f} krpm, peak {half['peak_um']:.1f} µm at "
                f"{half['peak_frequency_Hz']:.0f} Hz",
            )
        series = run.get("series")
        ramp = run.get("control_ramp_s")
        as_published = ramp is None or [round(x, 2) for x in ramp] == [6.0, 6.5]
        text = _PAPER_RUNS.get(v, ("",))[0]
        if series == "paper protocol" and text:
            ref = text
        elif series == "1 g·mm" and as_published and text:
            ref = "(protocol as published, with 1 g·mm) " + text
        else:
            ref = (
                f"not in the paper; its {v:g} V run, ramp at 6.0-6.5 s: {text}"
                if text
                else "not in the paper"
            )
        tag = f" ({reading})" if reading else ""
        why, where = _orbit_why(run, lin, disturbance_rms)
        rows.append(
            Row(
                f"orbit{tag}: {run.get('description', v)}",
                ref,
                "; ".join(parts),
                _orbit_deviation(run),
                (f"under {reading.removeprefix(PAPERS)}: " if reading else "") + why,
                where,
            )
        )
    for series in dict.fromkeys(r.get("series") for r in runs):
        members = [r for r in runs if r.get("series") == series]
        if series != "1 g·mm":
            members = [
                r
                for r in runs
                if float(r["voltage_V"]) == 0.0 and r.get("series") == "paper protocol"
            ] + members
            members = list({id(m): m for m in members}.values())
        if len(members) < 2:
            continue
        members.sort(key=lambda r: float(r["voltage_V"]))
        div = [r.get("divergence_speed_rpm") or math.inf for r in members]
        shown = " / ".join("none" if d == math.inf else f"{d / 1e3:.1f}" for d in div)
        volts = " / ".join(f"{float(r['voltage_V']):g}" for r in members)
        delayed = div == sorted(div)
        rows.append(
            Row(
                f"orbit trend ({series}{', ' + reading if reading else ''}): divergence "
                "delayed by the voltage",
                "yes (33 / 44.4 / none / none krpm)",
                ("yes: " if delayed else "NO: ") + shown + " krpm at " + volts + " V",
                _agrees(delayed, "yes", f"not delayed at every step of {volts} V"),
                f"the divergences of the {series} runs above"
                + (f" under {reading}" if reading else "")
                + ", in the order of their final voltage",
                REPORTED,
            )
        )
    return rows


def _orbit_deviation(run: dict[str, Any]) -> str:
    """A run's divergence (and whip) against the paper's run at the same final voltage."""
    v = float(run["voltage_V"])
    if v not in _PAPER_RUNS:
        return f"not in the paper: no run at {v:g} V"
    _, diverges, whip, whip_onset = _PAPER_RUNS[v]
    div = run.get("divergence_speed_rpm")
    ours_whip = run.get("whip_frequency_Hz")
    if diverges is not None:
        if not div:
            return (
                f"contradicts: paper diverges at {diverges:g} krpm; ours no divergence up to "
                f"{(run.get('end_speed_rpm') or 0) / 1e3:.0f} krpm"
            )
        text = f"divergence {_dev(div / 1e3, diverges)}"
        if whip is not None and ours_whip:
            text += f"; whip {_dev(ours_whip, whip)}"
        return text
    if div:
        return f"contradicts: paper no divergence up to 90 krpm; ours {_diverges(run)}"
    parts = ["agrees: no divergence up to 90 krpm"]
    onset = run.get("onset_after_control_rpm") or run.get("onset_speed_rpm")
    if whip_onset is not None and onset:
        parts.append(f"whip onset {_dev(onset / 1e3, whip_onset)}")
    if whip is not None and ours_whip:
        parts.append(f"whip {_dev(ours_whip, whip)}")
    return "; ".join(parts)


#: Speed (rpm) gained per second of the protocol's speed-up: 500 rad/s².
_RPM_PER_S = 500.0 * 30.0 / math.pi
_START_RPM = 3000.0


def _orbit_why(run: dict[str, Any], lin: float | None, disturbance_rms: float) -> tuple[str, str]:
    """One sentence on why a speed-up differs from the paper's, and the section explaining it."""
    v = float(run["voltage_V"])
    div = run.get("divergence_speed_rpm")
    ramp = run.get("control_ramp_s")
    imb = float(run.get("imbalance_g_mm") or 0.0)
    paper_div = _PAPER_RUNS.get(v, ("", None))[1]
    if not div:
        end = (run.get("end_speed_rpm") or 0.0) / 1e3
        whip = run.get("whip_frequency_Hz")
        if not whip:
            return f"no whirl was sustained up to {end:.0f} krpm, nor grew to contact", PROTOCOL
        return (
            f"a whirl at {whip:.0f} Hz stays bounded up to {end:.0f} krpm"
            + (f", past the linear onset ({lin / 1e3:.1f} krpm)" if lin else "")
            + ", as past a supercritical Hopf bifurcation",
            LIMIT_CYCLES,
        )
    t_div = (div - _START_RPM) / _RPM_PER_S
    if ramp is not None and lin is not None and div < 0.95 * lin and ramp[1] < t_div:
        ramp_end = _START_RPM + ramp[1] * _RPM_PER_S
        short = (
            f"; {t_div:.2f} s long, under the 1 s a sub-synchronous reading needs, it "
            "has no Fig. 15 curve"
            if t_div < 1.0
            else ""
        )
        event = "an orbit over 0.9 C" if run.get("divergence_by") == "orbit radius" else "contact"
        return (
            f"{event} {t_div - ramp[1]:.2f} s after the ramp ended at "
            f"{ramp_end / 1e3:.1f} krpm, far below the linear onset ({lin / 1e3:.1f} krpm): "
            f"the {imb:g} g·mm imbalance orbit meets the film the rising preload lobes "
            f"narrow, a forced contact, not a whirl{short}",
            READINGS,
        )
    if lin is not None and div < 0.95 * lin:
        return (
            f"{_diverges(run)}, {100 * (1 - div / lin):.0f} % below "
            f"the linear onset ({lin / 1e3:.1f} krpm): forced by the {imb:g} g·mm imbalance "
            "response (our reading of the paper's '8.5 g'), not a whirl",
            DEFAULT_CASE,
        )
    if lin is not None:
        seed = (
            f"from the case's {disturbance_rms * 1e3:.3g} mN disturbance"
            if disturbance_rms > 0
            else "from a numerical seed"
        )
        return (
            f"a whirl past the linear onset ({lin / 1e3:.1f} krpm) grows {seed} and "
            f"{_diverges(run)}; the paper's run "
            + (f"diverged at {paper_div:g} krpm" if paper_div else "stayed bounded to 90 krpm"),
            LIMIT_CYCLES if v in (100.0, 150.0) else PROTOCOL,
        )
    return f"{_diverges(run)}, no linear onset to set it against", PROTOCOL


def _diverges(run: dict[str, Any]) -> str:
    """How a run diverged, by the readout that set its divergence speed
    (:func:`foilbearing.signals.divergence`): contact, or an orbit of radius over 0.9 C
    and then contact (after a sustained large orbit, when it was one), or none to the end."""
    div = run["divergence_speed_rpm"] / 1e3
    if run.get("divergence_by") != "orbit radius":
        return f"diverges at {div:.1f} krpm (contact)"
    contact = run.get("contact_speed_rpm")
    if contact is None:
        end = (run.get("end_speed_rpm") or 0.0) / 1e3
        then = f"no contact up to {end:.1f} krpm"
    elif run.get("contact_after_large_orbit"):
        then = f"contact at {contact / 1e3:.1f} krpm after a sustained large orbit"
    else:
        then = f"contact at {contact / 1e3:.1f} krpm"
    return f"diverges at {div:.1f} krpm (orbit radius over 0.9 C; {then})"
