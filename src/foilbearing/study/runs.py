"""One speed-up of the study's orbit stages, as a worker process runs it.

:class:`OrbitRun` names a run (final voltage, ramp or schedule, imbalance) and
:func:`run_one` simulates it from 3000 to 90000 rpm at 500 rad/s², writes its NetCDF and
returns its analysis. The study's queue (:class:`foilbearing.study.queue.OrbitQueue`) hands
runs to worker processes; the stages that decide which runs to make
(:mod:`foilbearing.study.orbits`, :mod:`foilbearing.study.schedule`) build on both.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from foilbearing.case import Case
from foilbearing.constants import RPM

__all__ = ["OrbitRun", "run_one"]


@dataclass(frozen=True)
class OrbitRun:
    """One speed-up: final voltage, its ramp (None: no control) and the imbalance (kg·m).

    A ramp of (0, 0) holds the final voltage from the start. With ``schedule`` (a
    :class:`foilbearing.control.speed_schedule.SpeedSchedule`) the voltages follow it instead,
    and ``volts`` and ``ramp`` are not used. ``seed`` (None: the case's) is the seed of
    the case's random disturbance force (:mod:`foilbearing.orbit.disturbance`): another
    draw of its tones' frequencies and phases, for the spread of a readout over seeds.
    ``theta_refine`` runs it on the case's orbit grid with that many times the θ cells (the
    axial cells, order and κ held), for the readouts' discretisation error.
    """

    volts: float
    ramp: tuple[float, float] | None
    imbalance: float
    series: str
    schedule: Any = None
    #: Prefix of the label (and so of its files): a reading's runs beside the case's own.
    tag: str = ""
    seed: int | None = None
    theta_refine: int = 1

    @property
    def constant(self) -> bool:
        """The final voltage is held from the start."""
        return self.ramp == (0.0, 0.0)

    @property
    def label(self) -> str:
        if self.schedule is not None:
            head = "schedule"
        elif self.constant:
            head = f"{self.volts:g}V_constant"
        else:
            tail = "" if self.ramp is None else f"_ramp{self.ramp[0]:.2f}s"
            head = f"{self.volts:g}V{tail}"
        tail = "" if self.seed is None else f"_seed{self.seed}"
        if self.theta_refine != 1:
            tail += f"_theta{self.theta_refine}x"
        return f"{self.tag}{head}_{self.imbalance * 1e6:g}gmm{tail}"

    def describe(self) -> str:
        imbalance = f"imbalance {self.imbalance * 1e6:g} g·mm"
        if self.seed is not None:
            imbalance += f", disturbance seed {self.seed}"
        if self.theta_refine != 1:
            imbalance += f", {self.theta_refine} × the θ cells"
        if self.schedule is not None:
            return f"voltage schedule, {imbalance}"
        if self.constant:
            return f"{self.volts:g} V from the start, {imbalance}"
        control = (
            "none" if self.ramp is None else f"ramp at {self.ramp[0]:.2f}-{self.ramp[1]:.2f} s"
        )
        return f"{self.volts:g} V, control {control}, {imbalance}"


def run_one(case: Case, run: OrbitRun, out: Path, stop_time: float | None = None) -> dict[str, Any]:
    """One speed-up run; saves ``orbit_<label>.nc`` and returns its analysis."""
    from foilbearing.control import linear_ramp, voltage_ramp
    from foilbearing.io import write_with
    from foilbearing.orbit import simulate
    from foilbearing.orbit.analysis import analyse_orbit
    from foilbearing.orbit.netcdf import to_netcdf
    from foilbearing.orbit.spec import RunSpec, ScheduleText

    case = replace(case, rotor=replace(case.rotor, imbalance=run.imbalance))
    if run.seed is not None and case.disturbance is not None:
        case = replace(case, disturbance=replace(case.disturbance, seed=run.seed))
    if run.theta_refine != 1:
        n_theta = case.grid.orbit_shape[0] * run.theta_refine
        case = replace(case, grid=replace(case.grid, orbit_n_theta=n_theta))
    profile = linear_ramp(3000 * RPM, 90000 * RPM, 500.0)
    program = None if run.ramp is None else voltage_ramp(*run.ramp, run.volts)
    schedule_spec = None
    if run.schedule is not None:
        from foilbearing.control.schedule_file import schedule_toml

        program = run.schedule.program(profile)
        text = schedule_toml(run.schedule, case.title)
        schedule_spec = ScheduleText(text, str(out / "schedule.toml"))
    last = [0.0]

    def progress(t: float, w: float) -> None:
        if t - last[0] >= 2.0:
            last[0] = t
            print(f"    orbit {run.label}: t = {t:5.2f} s, {w / RPM:6.0f} rpm", flush=True)

    result = simulate(case, profile, program, progress=progress, stop_time=stop_time)
    ramp = run.ramp
    spec = RunSpec.of(  # a resumed run goes on to the end of the profile
        profile,
        program if schedule_spec is None else schedule_spec,
        case=case.source,
        imbalance=run.imbalance,
        settings=result.settings,
    )
    path = out / f"orbit_{run.label}.nc"
    write_with(path, lambda tmp: to_netcdf(result, spec, tmp))
    analysis = analyse_orbit(result)
    head = analysis.headline(result)
    head["half_order"] = _half_order(result)
    control_end = 3000 + 500.0 * (ramp[1] if ramp else 0.0) / RPM
    after = [
        iv
        for iv in (analysis.onset.intervals if analysis.onset else [])
        if ramp is not None and iv[0] > control_end
    ]
    head.update(
        label=run.label,
        series=run.series,
        description=run.describe(),
        voltage_V=run.volts,
        control_ramp_s=None if ramp is None else list(ramp),
        imbalance_g_mm=run.imbalance * 1e6,
        disturbance_seed=None if case.disturbance is None else case.disturbance.seed,
        onset_after_control_rpm=after[0][0] if after else None,
        whip_after_control_Hz=after[0][2] if after else None,
        netcdf=str(path),
    )
    return {"headline": head, "result": result, "analysis": analysis, "label": run.label}


def _half_order(result: Any) -> dict[str, float] | None:
    """Where the 0.5X component of e_X exceeds 1 µm (the paper's 0 V observation is a 0.5X
    subharmonic): speeds (rpm), its peak (µm) and the frequency there (Hz); None if never."""
    from foilbearing.signals import order_amplitude, order_interval

    if result.time.size < 100:
        return None
    amp = order_amplitude(result.time, result.e_x, result.phase, 0.5)
    found = order_interval(result.speed, amp, 1e-6)
    if found is None:
        return None
    lo, hi, peak, at = found
    return {
        "from_rpm": lo,
        "to_rpm": hi,
        "peak_um": peak * 1e6,
        "peak_speed_rpm": at,
        "peak_frequency_Hz": 0.5 * at / 60.0,
    }
