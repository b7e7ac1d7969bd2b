"""The orbit part of the paper's study (Figs. 13-15): speed-up runs from 3 to 90 krpm.

The paper's protocol: 0 V throughout, and ramps of all actuators from 0 to
50/100/150 V between 6.0 and 6.5 s (32.6 krpm), "at the initiation of unstable
motions", just before its 0 V run diverges (~33 krpm), during the speed-up from
3 to 90 krpm at 500 rad/s². The 0 V run goes first. A controlled run is
identical to it until its ramp starts, so if our 0 V run diverges before the
paper's control time (our viscosity, rotor mass and imbalance are assumptions,
MODEL.md section 1) the controlled runs of the protocol would diverge with it
and are not run; that is reported. Beyond the protocol, the study also runs the
speed-up with each voltage held from the start, which reads the nonlinear onset
speed, whip frequency and divergence for each preload. Runs after the first are
separate processes (one per core); each writes its NetCDF as it finishes.
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


def run_one(
    case: Case,
    volts: float,
    out: Path,
    stop_time: float | None = None,
    ramp: tuple[float, float] = RAMP,
    kind: str = "ramp",
) -> dict[str, Any]:
    """One speed-up run; saves ``orbit_<label>.nc`` and returns its analysis.

    ``kind`` "ramp": 0 V until the ramp to ``volts`` (the paper's protocol);
    "held": ``volts`` on every actuator from the start (equilibrium included).
    """
    from foilbearing.control import linear_ramp, voltage_ramp
    from foilbearing.io import write_with
    from foilbearing.orbit import simulate
    from foilbearing.orbit_analysis import analyse_orbit
    from foilbearing.orbit_io import to_netcdf

    held = kind == "held" and volts > 0
    label = f"{volts:g}V" + ("_held" if held else "")
    program = voltage_ramp(*ramp, volts) if volts > 0 and not held else None
    if held:
        case = case.with_voltages(volts)
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
        "voltage_ramp": f"{ramp[0]}s:{ramp[1]}s:{volts}V" if program is not None else None,
        "controller": None,
        "stop_time": None,
        "steps_per_rev": result.settings.steps_per_rev,
        "sample_rate": f"{result.settings.sample_rate}Hz",
    }
    path = out / f"orbit_{label}.nc"
    write_with(path, lambda tmp: to_netcdf(result, spec, tmp))
    analysis = analyse_orbit(result)
    head = analysis.headline(result)
    control_end = 3000 + 500.0 * ramp[1] / RPM
    after = [
        iv for iv in (analysis.onset.intervals if analysis.onset else []) if iv[0] > control_end
    ]
    head["voltage_V"] = volts
    head["control"] = (
        "held from the start"
        if held
        else (f"ramp at {ramp[0]}-{ramp[1]} s" if program is not None else "none")
    )
    head["onset_after_control_rpm"] = after[0][0] if after and program is not None else None
    head["whip_after_control_Hz"] = after[0][2] if after and program is not None else None
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

    n = workers or (os.cpu_count() or 1)
    done: dict[str, dict[str, Any]] = {}
    zero = run_one(case, 0.0, out, stop_time)
    done["0 V"] = zero
    stage(f"  orbit 0 V: {zero['headline']['message']} ({zero['headline']['wall_time_s']:.0f} s)")
    write_orbit_figures(zero["result"], zero["analysis"], out, "orbit_0V")
    contact = zero["result"].contact
    protocol_possible = not (contact is not None and contact["time_s"] < RAMP[0])
    jobs: dict[str, tuple[float, str]] = {}
    if protocol_possible:
        jobs.update({f"{v:g} V ramp": (v, "ramp") for v in PAPER_ORBITS if v > 0})
    else:
        stage(
            f"  our 0 V run diverges at {contact['time_s']:.2f} s ({contact['speed_rpm']:.0f} "
            f"rpm), before the paper's control at {RAMP[0]}-{RAMP[1]} s: the controlled runs "
            "of the protocol are identical to it until then and are not run"
        )
    jobs.update({f"{v:g} V held": (v, "held") for v in PAPER_ORBITS if v > 0})
    with ProcessPoolExecutor(max_workers=n) as pool:
        futures = {
            pool.submit(run_one, case, v, out, stop_time, RAMP, kind): label
            for label, (v, kind) in jobs.items()
        }
        for fut in as_completed(futures):
            label = futures[fut]
            run = fut.result()
            done[label] = run
            h = run["headline"]
            stage(f"  orbit {label}: {h['message']} ({h['wall_time_s']:.0f} s)")
            write_orbit_figures(run["result"], run["analysis"], out, f"orbit_{run['label']}")
    order = ["0 V", *jobs]
    subs = {
        k: done[k]["analysis"].subsync for k in order if done[k]["analysis"].subsync is not None
    }
    onsets = {k: done[k]["analysis"].onset for k in order if done[k]["analysis"].onset is not None}
    figures = []
    if subs:
        figures.append(str(save_figure(plot_subsync(subs, onsets), out / "fig15_subsync.png")))
    return {
        "runs": [done[k]["headline"] | {"label": k} for k in order],
        "protocol_run": protocol_possible,
        "control_ramp_s": list(RAMP),
        "figures": figures,
    }
