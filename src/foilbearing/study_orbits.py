"""The orbit part of the paper's study (Figs. 13-15): four speed-up runs, in parallel.

0 V throughout, and ramps of all actuators from 0 to 50/100/150 V between 6.0 and
6.5 s (about 32.6 krpm), during the paper's speed-up from 3 to 90 krpm at
500 rad/s². Each run is a separate process (one per core); each writes its NetCDF
as it finishes, so an interrupted study keeps the finished runs.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any

from foilbearing.case import Case

__all__ = ["PAPER_ORBITS", "paper_orbit_runs", "run_one"]

RPM = math.pi / 30.0
#: Final voltage of the ramp of each of the paper's runs (0: no control).
PAPER_ORBITS = (0.0, 50.0, 100.0, 150.0)
RAMP = (6.0, 6.5)  # s


def run_one(case: Case, volts: float, out: Path, stop_time: float | None = None) -> dict[str, Any]:
    """One of the paper's speed-up runs; saves ``orbit_<V>V.nc`` and returns its analysis."""
    from foilbearing.control import linear_ramp, voltage_ramp
    from foilbearing.io import write_with
    from foilbearing.orbit import simulate
    from foilbearing.orbit_analysis import analyse_orbit
    from foilbearing.orbit_io import to_netcdf

    label = f"{volts:g}V"
    program = voltage_ramp(*RAMP, volts) if volts > 0 else None
    profile = linear_ramp(3000 * RPM, 90000 * RPM, 500.0)
    last = [0.0]

    def progress(t: float, w: float) -> None:
        if t - last[0] >= 1.0:
            last[0] = t
            print(f"    orbit {label}: t = {t:5.2f} s, {w / RPM:6.0f} rpm", flush=True)

    result = simulate(case, profile, program, progress=progress, stop_time=stop_time)
    spec = {
        "case": case.source,
        "speed_ramp": "3000rpm:90000rpm:500rad/s**2",
        "speed": None,
        "duration": None,
        "voltage_ramp": f"{RAMP[0]}s:{RAMP[1]}s:{volts}V" if volts else None,
        "controller": None,
        "stop_time": None,
        "steps_per_rev": result.settings.steps_per_rev,
        "sample_rate": f"{result.settings.sample_rate}Hz",
    }
    path = out / f"orbit_{label}.nc"
    write_with(path, lambda tmp: to_netcdf(result, spec, tmp))
    analysis = analyse_orbit(result)
    head = analysis.headline(result)
    control_end = 3000 + 500.0 * RAMP[1] / RPM
    after = [
        iv for iv in (analysis.onset.intervals if analysis.onset else []) if iv[0] > control_end
    ]
    head["voltage_V"] = volts
    head["onset_after_control_rpm"] = after[0][0] if after and volts > 0 else None
    head["whip_after_control_Hz"] = after[0][2] if after and volts > 0 else None
    head["netcdf"] = str(path)
    return {"headline": head, "result": result, "analysis": analysis, "label": label}


def paper_orbit_runs(
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    *,
    workers: int | None = None,
    stop_time: float | None = None,
) -> dict[str, Any]:
    """Run the paper's four speed-ups, write their figures and Fig. 15; return headlines."""
    from foilbearing.io import save_figure
    from foilbearing.orbit_analysis import write_orbit_figures
    from foilbearing.plots.orbit import plot_subsync

    n = workers or min(len(PAPER_ORBITS), os.cpu_count() or 1)
    done: dict[float, dict[str, Any]] = {}
    with ProcessPoolExecutor(max_workers=n) as pool:
        futures = {pool.submit(run_one, case, v, out, stop_time): v for v in PAPER_ORBITS}
        for fut in as_completed(futures):
            v = futures[fut]
            run = fut.result()
            done[v] = run
            h = run["headline"]
            stage(f"  orbit {v:g} V: {h['message']} ({h['wall_time_s']:.0f} s)")
            write_orbit_figures(run["result"], run["analysis"], out, f"orbit_{run['label']}")
    subs = {
        f"{v:g} V": done[v]["analysis"].subsync
        for v in PAPER_ORBITS
        if done[v]["analysis"].subsync is not None
    }
    onsets = {
        f"{v:g} V": done[v]["analysis"].onset
        for v in PAPER_ORBITS
        if done[v]["analysis"].onset is not None
    }
    figures = []
    if subs:
        figures.append(str(save_figure(plot_subsync(subs, onsets), out / "fig15_subsync.png")))
    return {"runs": [done[v]["headline"] for v in PAPER_ORBITS], "figures": figures}
