"""The study's voltage schedule (beyond the paper): computed, then verified in speed-ups.

The schedule (:func:`foilbearing.schedule.voltage_schedule`) is computed on the
study's case from 10 to 90 krpm (17 speeds) with the default margin and slew
rate, and written as ``schedule.toml`` and ``schedule.png``. It is then run in
the paper's speed-up (3 → 90 krpm at 500 rad/s²) beside three other voltage
programs on the same speed-up:

- 0 V throughout;
- 150 V from the start;
- the paper's control, 0 → 150 V between 6.0 and 6.5 s;
- the schedule.

All four with the 1 g·mm imbalance of the study's sensitivity series (with the
paper's 8.5 g·mm our 0 V rotor reaches contact near 14 krpm by its imbalance
response, before any whirl could be controlled; see ``foilbearing.study.orbits``). Runs the
orbit stage already made are taken from it; the others are
separate processes, one per core. Each run is read for the onset of sustained
sub-synchronous motion, its whip frequency, the divergence speed and the power
loss averaged over the run, and over the speeds all four runs reach.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

from foilbearing.case import Case
from foilbearing.constants import RPM

__all__ = ["SCHEDULE_SPEEDS_RPM", "schedule_stage"]

#: The study's schedule grid, rpm: 10 to 90 krpm in 5 krpm steps (17 speeds).
SCHEDULE_SPEEDS_RPM = tuple(range(10_000, 90_001, 5_000))
VERIFY_IMBALANCE = 1e-6  # kg·m, 1 g·mm


def _runs(schedule: Any) -> list[Any]:
    from foilbearing.study.orbits import RAMP, OrbitRun

    series = "schedule verification"
    return [
        OrbitRun(0.0, None, VERIFY_IMBALANCE, series),
        OrbitRun(150.0, (0.0, 0.0), VERIFY_IMBALANCE, series),
        OrbitRun(150.0, RAMP, VERIFY_IMBALANCE, series),
        OrbitRun(0.0, None, VERIFY_IMBALANCE, series, schedule=schedule),
    ]


def schedule_stage(
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    *,
    previous: dict[str, Any] | None = None,
    verify: bool = True,
    workers: int | None = None,
    speeds: list[float] | None = None,
) -> dict[str, Any]:
    """Compute, write and (with ``verify``) run the schedule; returns its summary.

    ``previous`` holds the orbit stage's runs by label, as
    :func:`foilbearing.study.orbits.run_one` returns them: those with the same
    program and imbalance are reused, results and analyses alike.
    """
    from foilbearing.io import save_figure, write_text
    from foilbearing.orbit.analysis import mean_power_loss
    from foilbearing.output.plots.orbit import plot_subsync
    from foilbearing.output.plots.schedule import plot_run_power, plot_schedule
    from foilbearing.schedule import voltage_schedule
    from foilbearing.schedule_file import schedule_toml
    from foilbearing.study.orbits import run_one

    assert case.actuators is not None
    if speeds is None:
        speeds = [rpm * RPM for rpm in SCHEDULE_SPEEDS_RPM]
    schedule = voltage_schedule(case, speeds, progress=lambda line: stage("  " + line.strip()))
    write_text(out / "schedule.toml", schedule_toml(schedule, case.title))
    angles = [math.degrees(a) for a in case.actuators.angles]
    figures = [str(save_figure(plot_schedule(schedule, angles), out / "schedule.png"))]
    summary: dict[str, Any] = {
        "schedule": schedule.headline(),
        "schedule_file": str(out / "schedule.toml"),
        "figures": figures,
    }
    if not verify:
        return summary
    plan = _runs(schedule)
    runs: dict[str, Any] = {r.label: (previous or {}).get(r.label) for r in plan}
    todo = [r for r in plan if runs[r.label] is None]
    for r in plan:
        if runs[r.label] is not None:
            stage(f"  {r.describe()}: taken from the orbit stage")
    with ProcessPoolExecutor(max_workers=workers or (os.cpu_count() or 1)) as pool:
        futures = {pool.submit(run_one, case, r, out): r for r in todo}
        for fut, r in futures.items():
            runs[r.label] = fut.result()
            head = runs[r.label]["headline"]
            stage(f"  {r.describe()}: {head['message']} ({head['wall_time_s']:.0f} s)")
    common = min(float(runs[r.label]["result"].speed[-1]) for r in plan) / RPM
    rows, subs, onsets, power = [], {}, {}, {}
    for r in plan:
        res, analysis = runs[r.label]["result"], runs[r.label]["analysis"]
        head = analysis.headline(res)
        if analysis.subsync is not None:
            subs[r.describe()] = analysis.subsync
        if analysis.onset is not None:
            onsets[r.describe()] = analysis.onset
        if res.power_loss is not None:
            power[r.describe()] = (res.speed / RPM, res.power_loss)
        rows.append(
            {
                "run": r.describe(),
                "label": r.label,
                "onset_speed_rpm": head["onset_speed_rpm"],
                "whip_frequency_Hz": head["whip_frequency_Hz"],
                "divergence_speed_rpm": head["divergence_speed_rpm"],
                "end_speed_rpm": head["end_speed_rpm"],
                "status": head["status"],
                "mean_power_loss_W": head["mean_power_loss_W"],
                "mean_power_loss_common_W": mean_power_loss(res, until_rpm=common),
            }
        )
    if subs:
        figures.append(str(save_figure(plot_subsync(subs, onsets), out / "schedule_subsync.png")))
    if power:
        figures.append(str(save_figure(plot_run_power(power), out / "schedule_power.png")))
    summary["verification"] = {
        "speed_up": "3000-90000 rpm at 500 rad/s²",
        "imbalance_g_mm": VERIFY_IMBALANCE * 1e6,
        "common_range_rpm": [3000.0, common],
        "runs": rows,
    }
    return summary
