"""What a speed-up run shows: waterfall, sub-synchronous amplitude, onset, whip, divergence.

Glue between :mod:`foilbearing.orbit` (the run) and :mod:`foilbearing.signals`
(the arrays): the analysis of the paper's Figs. 13-15 applied to e_X (the load
direction, the paper's "vertical" motion), with the headline numbers that
``foilbearing orbit --json`` prints, and the figures.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.orbit import OrbitResult
from foilbearing.orbit.result import synchronous_amplitude
from foilbearing.output.summary import grid_used
from foilbearing.signals import (
    Divergence,
    Onset,
    SubsyncResult,
    Waterfall,
    divergence,
    onset,
    subsynchronous_amplitude,
    waterfall,
)

__all__ = [
    "OrbitAnalysis",
    "analyse_orbit",
    "mean_power_loss",
    "orbit_panel_speeds",
    "synchronous_amplitude",
    "write_orbit_figures",
]

#: Sub-synchronous amplitude that counts as onset: 1 µm, 1 % of the paper's clearance.
ONSET_THRESHOLD = 1e-6


@dataclass(frozen=True)
class OrbitAnalysis:
    """Signal analysis of one run (None where the run is too short to analyse)."""

    waterfall: Waterfall | None
    subsync: SubsyncResult | None
    onset: Onset | None
    divergence_speed_rpm: float | None
    max_subsync_amplitude: float | None
    #: A constant-speed run: the 1X (synchronous) amplitudes in X and Y, 0-pk, m, and the
    #: window (s) they are read over; None for a speed ramp or a run under two revolutions.
    one_x: tuple[float, float] | None = None
    one_x_window: tuple[float, float] | None = None
    #: The divergence read in full: by the orbit's radius or by contact, and how long a
    #: large orbit lasted before a contact (`foilbearing.signals.divergence`).
    divergence: Divergence | None = None

    def headline(self, result: OrbitResult) -> dict[str, Any]:
        """Unit-named keys: onset_speed_rpm, whip_frequency_Hz, divergence_speed_rpm, ...;
        ``grid``: [n_theta, n_z] of the grid the run was on (the case's orbit grid);
        ``actuator_reading``: the actuator in the film (``"lobe+compliant"``, docs/model.md
        §3.8), None without actuators. A constant-speed run adds its 1X amplitude in X and
        Y, 0-pk and pk-pk (µm), and the window it is read over."""
        o, d = self.onset, self.divergence
        act = result.case.actuators
        one_x = {}
        if self.one_x is not None and self.one_x_window is not None:
            one_x = {
                "one_x_amplitude_0pk_um": [a * 1e6 for a in self.one_x],
                "one_x_amplitude_pkpk_um": [2e6 * a for a in self.one_x],
                "one_x_window_s": list(self.one_x_window),
            }
        return one_x | {
            "onset_speed_rpm": None if o is None else o.onset_speed_rpm,
            "whip_frequency_Hz": None if o is None else o.whirl_frequency_hz,
            "subsync_intervals_rpm_Hz": [] if o is None else [list(iv) for iv in o.intervals],
            "divergence_speed_rpm": self.divergence_speed_rpm,
            "divergence_by": None if d is None else d.by,
            "contact_speed_rpm": None if d is None else d.contact_speed_rpm,
            "contact_after_large_orbit": None if d is None else d.contact_after_large_orbit,
            "max_subsync_amplitude_um": (
                None if self.max_subsync_amplitude is None else self.max_subsync_amplitude * 1e6
            ),
            "wall_time_s": result.wall_time,
            "status": result.status,
            "message": result.message,
            "load_N": result.case.operation.load,
            "end_speed_rpm": float(result.speed[-1] * 30 / math.pi) if result.speed.size else None,
            "mean_power_loss_W": mean_power_loss(result),
            "steps": result.steps,
            **grid_used(result.case),
            "actuator_reading": (None if act is None else act.reading.label),
        }


def mean_power_loss(result: OrbitResult, until_rpm: float | None = None) -> float | None:
    """Time average of the film's power loss over the run (up to ``until_rpm``), W.

    None for a run without the power loss recorded or without samples.
    """
    p = result.power_loss
    if p is None or result.time.size < 2:
        return None
    keep = np.isfinite(p)
    if until_rpm is not None:
        keep &= result.speed * 30 / math.pi <= until_rpm
    if keep.sum() < 2:
        return None
    from scipy.integrate import trapezoid  # numpy >= 1.26 (the floor) has no np.trapezoid

    return float(trapezoid(p[keep], result.time[keep]) / np.ptp(result.time[keep]))


def analyse_orbit(result: OrbitResult, *, threshold: float = ONSET_THRESHOLD) -> OrbitAnalysis:
    """Waterfall, sub-synchronous amplitude (1X removed by order tracking), onset, divergence;
    the 1X amplitude of a constant-speed run (:func:`synchronous_amplitude`)."""
    sync = synchronous_amplitude(result) if result.time.size >= 2 else None
    one_x = {} if sync is None else {"one_x": sync[0], "one_x_window": sync[1]}
    t = result.time
    c = result.case.bearing.clearance
    if t.size < 8 or t[-1] - t[0] < 1.0:
        # Too short for 0.25 s windows with the sustain rule: report what can be said.
        div = None
        if result.status == "contact" and t.size < 2:
            # Contact before a second sample (the first steps closed the film): no time
            # series to read, but the stepper noted the speed at contact.
            contact = result.contact or {}
            speed = contact.get("speed_rpm")
            if speed is not None:
                at = float(contact.get("time_s", t[-1] if t.size else 0.0))
                div = Divergence(float(speed), at, "contact", float(speed), 0.0)
        elif result.status == "contact":
            div = divergence(
                t,
                result.e_x,
                result.e_y,
                result.speed,
                c,
                stopped_by_contact=True,
                contact_time=None,
            )
        return OrbitAnalysis(
            None, None, None, None if div is None else div.speed_rpm, None, **one_x, divergence=div
        )
    wf = waterfall(
        t, result.e_x, result.speed, fmax_hz=min(2000.0, 0.45 * result.settings.sample_rate)
    )
    sub = subsynchronous_amplitude(t, result.e_x, result.speed, result.phase)
    contact = result.contact or {}
    div = divergence(
        t,
        result.e_x,
        result.e_y,
        result.speed,
        c,
        stopped_by_contact=result.status == "contact",
        contact_time=contact.get("time_s"),
    )
    ons = onset(sub, threshold=threshold, diverged_s=None if div is None else div.time_s)
    amp = float(np.nanmax(sub.amplitude)) if sub.amplitude.size else None
    speed_rpm = None if div is None else div.speed_rpm
    return OrbitAnalysis(wf, sub, ons, speed_rpm, amp, **one_x, divergence=div)


def orbit_panel_speeds(speed: np.ndarray) -> list[float]:
    """The speeds (rpm) of the orbit plot's panels: up to four of 10, 20, 30, 50, 70 and
    90 krpm that the run went through (``speed`` in rad/s), the highest ones; a run that
    went through none of them (a constant-speed run) gets one panel at its top speed."""
    rpm = np.asarray(speed, float) * 30 / math.pi
    if rpm.size == 0:
        return [0.0]
    low, top = float(rpm.min()), float(rpm.max())
    marks = [s for s in (10e3, 20e3, 30e3, 50e3, 70e3, 90e3) if low * (1 - 1e-9) <= s <= top]
    return marks[-4:] or [top]


def write_orbit_figures(
    result: OrbitResult,
    analysis: OrbitAnalysis,
    folder: Path,
    label: str = "orbit",
    *,
    onset_whirl_hz: float | None = None,
) -> list[Path]:
    """Transient (Fig. 13a/14), waterfall colour map and 3-D (Fig. 13b), orbits; PNG files.

    ``onset_whirl_hz``, the linear onset's whirl frequency (Hz), is marked on the
    colour map when given.
    """
    from foilbearing.io import save_figure
    from foilbearing.output.plots import orbit as po

    c = result.case.bearing.clearance
    paths = [
        save_figure(
            po.plot_transient(result.time, result.e_x, result.e_y, result.speed, c),
            folder / f"{label}_transient.png",
        )
    ]
    if analysis.waterfall is not None:
        paths.append(
            save_figure(
                po.plot_waterfall(analysis.waterfall, onset_whirl_hz=onset_whirl_hz),
                folder / f"{label}_waterfall.png",
            )
        )
        paths.append(
            save_figure(
                po.plot_waterfall_3d(analysis.waterfall), folder / f"{label}_waterfall3d.png"
            )
        )
    marks = orbit_panel_speeds(result.speed)
    paths.append(
        save_figure(
            po.plot_orbits(result.time, result.e_x, result.e_y, result.speed, marks, c),
            folder / f"{label}_orbits.png",
        )
    )
    return paths
