"""``foilbearing study ROTOR.toml``: the study of a rotor on two foil bearings.

A rotor file (docs/rotor-format.md) in place of a bearing case runs this stage instead of
the bearing's: the weight each bearing carries, the Campbell diagram and onset with matched
whirl on ROSS, the convergence of the reduced rotor with its shaft modes, and a nonlinear
speed-up through the onset, with the mode shapes at the onset and the response to an
unbalance at the heaviest disk. It writes ``summary.json``, the figures and ``report.html``
(section "A rotor on two foil bearings").
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.constants import RPM
from foilbearing.output.result import StudyResult
from foilbearing.rotor.model import RotorCase

__all__ = ["is_rotor_file", "rotor_study", "run_rotor_study"]

#: The speeds of the linear analysis: 20-70 krpm, 2 krpm apart (the onset read to about
#: 0.5 %, docs/rotor-format.md).
SPEEDS_RPM = np.arange(20e3, 70.01e3, 2e3)
#: Shaft modes kept in the reduction's convergence table, and in the nonlinear run.
REDUCTION_MODES = (0, 4, 8, 16)
ORBIT_MODES = 8
#: The nonlinear speed-up: from 0.85 to 1.3 times the linear onset at 500 rad/s² (the
#: paper's acceleration), with this unbalance at the heaviest disk, kg·m. (To 1.15 times,
#: the flexible example's whirl, growing from 52 krpm, had not lasted the half second the
#: signal analysis asks of a sustained one.)
ORBIT_SPAN = (0.85, 1.3)
ORBIT_ACCELERATION = 500.0
ORBIT_UNBALANCE = 1e-6


def is_rotor_file(path: Path | None) -> bool:
    """Whether ``path`` is a rotor file (a TOML file with a ``[shaft]`` table)."""
    if path is None or Path(path).suffix != ".toml" or not Path(path).is_file():
        return False
    from foilbearing.io import read_toml

    return "shaft" in read_toml(Path(path), "rotor file")


def rotor_study(
    rotor: RotorCase, out: Path, stage: Callable[[str], None], *, orbits: bool = True
) -> dict[str, Any]:
    """The rotor's stage of the study (module docstring); its summary, unit-named keys,
    with the figures it wrote under ``figures``."""
    from foilbearing.io import save_figure
    from foilbearing.output.plots.rotor import (
        plot_campbell,
        plot_mode_shapes,
        plot_unbalance_response,
    )
    from foilbearing.rotor import mode_shapes, ross_rotor, rotor_modes, unbalance_response
    from foilbearing.rotor.linear import modes_at, refine_onset
    from foilbearing.rotor.reduced import reduced_onset
    from foilbearing.rotor.response import table_frequencies

    speeds = list(SPEEDS_RPM * RPM)
    summary: dict[str, Any] = {
        "title": rotor.title,
        "mass_kg": rotor.mass,
        "bearings": [
            {
                "label": b.label,
                "node": b.node,
                "load_N": load,
                "voltages_V": list(b.case.actuators.voltages) if b.case.actuators else [],
            }
            for b, load in zip(rotor.bearings, rotor.bearing_loads(), strict=True)
        ],
        "speeds_rpm": [float(v) for v in SPEEDS_RPM],
    }
    figures: list[str] = []
    stage(
        f"rotor: the bearings' coefficient tables, {len(speeds)} speeds "
        f"{SPEEDS_RPM[0] / 1e3:.0f}-{SPEEDS_RPM[-1] / 1e3:.0f} krpm; modes with matched whirl"
    )
    # Each speed is also a frequency of the tables: the unbalance response is then exact.
    model = ross_rotor(rotor, speeds, list(table_frequencies(speeds)))
    modes = rotor_modes(rotor, speeds, model=model)
    onset, whirl = refine_onset(modes, lambda w: modes_at(model, w, 4))
    summary["onset_speed_rpm"] = None if onset is None else onset / RPM
    summary["whirl_frequency_Hz"] = whirl
    summary["least_log_decrement"] = [float(v) for v in modes.least_stable()]
    figures.append(str(save_figure(plot_campbell(modes, onset, rotor.title), out / "campbell.png")))
    at = speeds[-1] if onset is None else onset
    shapes = mode_shapes(rotor, at, model=model)
    title = f"{rotor.title}: modes at {at / RPM:,.0f} rpm"
    figures.append(str(save_figure(plot_mode_shapes(shapes, title), out / "mode_shapes.png")))
    node = _heaviest_disk_node(rotor)
    response = unbalance_response(rotor, speeds, [(node, ORBIT_UNBALANCE, 0.0)], model=model)
    amplitude = response.amplitude_um()  # (speeds, nodes)
    peak = np.unravel_index(int(np.argmax(amplitude)), amplitude.shape)
    summary["unbalance_response"] = {
        "unbalance_g_mm": ORBIT_UNBALANCE * 1e6,
        "unbalance_node": node,
        "peak_amplitude_um": float(amplitude[peak]),
        "peak_speed_rpm": float(SPEEDS_RPM[peak[0]]),
        "peak_at": response.labels[peak[1]],
    }
    figures.append(
        str(
            save_figure(
                plot_unbalance_response(response, rotor.title), out / "unbalance_response.png"
            )
        )
    )
    if len(rotor.bearings) >= 2 and onset is not None:
        stage(
            f"rotor: the reduced rotor's onset with {', '.join(map(str, REDUCTION_MODES))} shaft modes"
        )
        nodes = [b.node for b in rotor.bearings]
        rows = []
        for n in REDUCTION_MODES:
            reduced, _w, _m = reduced_onset(model, nodes, speeds, n_modes=n)
            rows.append({
                "shaft_modes": n,
                "onset_speed_rpm": None if reduced is None else reduced / RPM,
                "error_percent": None if reduced is None else 100.0 * (reduced / onset - 1.0),
            })  # fmt: skip
        summary["reduction"] = rows
    if orbits and onset is not None and len(rotor.bearings) >= 2:
        summary["orbit"] = _speed_up(rotor, onset, out, stage, figures)
    summary["figures"] = figures
    return summary


def _speed_up(
    rotor: RotorCase,
    onset: float,
    out: Path,
    stage: Callable[[str], None],
    figures: list[str],
) -> dict[str, Any]:
    """The nonlinear speed-up through the linear onset (module constants)."""
    from foilbearing.control import linear_ramp
    from foilbearing.io import save_figure, write_with
    from foilbearing.output.plots.rotor_orbit import plot_rotor_orbit
    from foilbearing.rotor.nonlinear import RotorOrbitSystem, Unbalance
    from foilbearing.rotor.stepper import run_rotor

    start, stop = (onset * f for f in ORBIT_SPAN)
    node = _heaviest_disk_node(rotor)
    profile = linear_ramp(start, stop, ORBIT_ACCELERATION)
    stage(
        f"rotor: nonlinear speed-up {start / RPM / 1e3:.1f}-{stop / RPM / 1e3:.1f} krpm at "
        f"{ORBIT_ACCELERATION:g} rad/s², {ORBIT_UNBALANCE * 1e6:g} g·mm at node {node} "
        f"({profile.duration:.1f} s simulated)"
    )
    system = RotorOrbitSystem(
        rotor, None, profile, n_modes=ORBIT_MODES, unbalances=[Unbalance(node, ORBIT_UNBALANCE)]
    )
    clock = time.perf_counter()
    run = run_rotor(system, profile.duration)
    found = run.subsynchronous_onset(profile)
    write_with(out / "rotor_orbit.nc", run.to_dataset(rotor.title).to_netcdf)
    figures.append(str(save_figure(plot_rotor_orbit(run, rotor.title), out / "rotor_orbit.png")))
    return {
        "speed_up": f"{start / RPM:.0f}-{stop / RPM:.0f} rpm at {ORBIT_ACCELERATION:g} rad/s²",
        "unbalance_g_mm": ORBIT_UNBALANCE * 1e6,
        "unbalance_node": node,
        "shaft_modes": ORBIT_MODES,
        "status": run.status,
        "message": run.message,
        "steps": run.steps,
        "wall_time_s": time.perf_counter() - clock,
        "onset_speed_rpm": None if found is None else found.onset_speed_rpm,
        "whirl_frequency_Hz": None if found is None else found.whirl_frequency_hz,
        "largest_excursion_um": [float(a * 1e6) for a in run.amplitude()],
        "end_speed_rpm": float(profile.omega(float(run.time[-1])) / RPM),
    }


def _heaviest_disk_node(rotor: RotorCase) -> int:
    """Where the study puts its unbalance: the heaviest disk (the first bearing without)."""
    disk = max(rotor.disks, key=lambda d: d.mass, default=None)
    return disk.node if disk is not None else rotor.bearings[0].node


def run_rotor_study(
    rotor: RotorCase, out: Path, *, progress: bool = True, orbits: bool = True
) -> StudyResult:
    """Run the rotor's study into ``out``: summary.json, the figures and report.html."""
    from foilbearing.study.paper import _finish

    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()

    def stage(name: str) -> None:
        if progress:
            print(f"[{time.perf_counter() - t0:6.1f} s] {name}", flush=True)

    stage(f"rotor: {rotor.title}")
    case = {"title": rotor.title, "source": rotor.source, "bearing_type": "rotor on foil bearings"}
    results: dict[str, Any] = {"case": case, "rotor": rotor_study(rotor, out, stage, orbits=orbits)}
    return _finish(out, results, stage)
