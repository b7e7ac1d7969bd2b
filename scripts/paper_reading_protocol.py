"""The paper's speed-up protocol (Figs. 13-15) under one reading of the actuator in the film.

Run: .venv/bin/python scripts/paper_reading_protocol.py OUT_DIR [--reading lobe+held]
     [--imbalance 1g*mm] [--workers 2] [--stop-time S]

0 V from 3 krpm at 500 rad/s², then ramps of all actuators from 0 to 50 / 100 / 150 V
between 6.0 and 6.5 s, on the default case with the imbalance given (default 1 g·mm:
``--imbalance-check`` prints the linear 1X orbit against the minimum film from 3 to
33 krpm, the measurement that chooses it). Each run's NetCDF, its figures and a
``protocol.json`` of the readouts (onset, whip frequency, divergence or the speed
reached) go to OUT_DIR. Runs go two at a time, one per core; each 3-90 krpm speed-up
takes 3-10 minutes.
"""

from __future__ import annotations

import argparse
import json
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.case import default_case
from foilbearing.constants import RPM
from foilbearing.units import parse_quantity


def case_for(reading: str) -> Any:
    response, dynamics = reading.split("+")
    return default_case().with_actuator_reading(response, dynamics)


def imbalance_check(reading: str, imbalances: tuple[float, ...]) -> None:
    """The linear 1X orbit radius against the equilibrium's minimum film, 0 V, 3-33 krpm."""
    from foilbearing.coefficients import force_coefficients
    from foilbearing.static import solve_equilibrium

    case = case_for(reading)
    m = case.rotor.mass
    print(
        "speed (krpm)  min film (um)  "
        + "  ".join(f"1X at {u * 1e6:g} g·mm (um)" for u in imbalances)
    )
    worst = dict.fromkeys(imbalances, 0.0)
    for rpm in range(3000, 33001, 1500):
        w = rpm * RPM
        st = solve_equilibrium(case, speed=w)
        fc = force_coefficients(st, w)
        z = fc.K[0] + 1j * w * fc.C[0] - m * w * w * np.eye(2)
        cells = []
        for u in imbalances:
            x = np.linalg.solve(z, m * u * w * w * np.array([1.0, -1j]))
            r = float(np.max(np.abs(x)))
            worst[u] = max(worst[u], r / st.min_film)
            cells.append(f"{r * 1e6:10.2f}")
        print(f"{rpm / 1e3:8.1f}      {st.min_film * 1e6:8.2f}      " + "     ".join(cells))
    for u, ratio in worst.items():
        print(f"{u * 1e6:g} g·mm: largest 1X radius / minimum film = {ratio:.2f}")


def one(args: tuple[str, float, float, str, float | None]) -> dict[str, Any]:
    from foilbearing.study.orbits import RAMP
    from foilbearing.study.runs import OrbitRun, run_one

    reading, volts, imbalance, out, stop = args
    case = case_for(reading)
    run = OrbitRun(volts, None if volts == 0.0 else RAMP, imbalance, reading)
    done = run_one(case, run, Path(out), stop_time=stop)
    from foilbearing.orbit.analysis import write_orbit_figures

    write_orbit_figures(done["result"], done["analysis"], Path(out), f"{reading}_{run.label}")
    head = dict(done["headline"])
    head["reading"] = reading
    return {
        k: v for k, v in head.items() if isinstance(v, (int, float, str, list, dict, type(None)))
    }


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out", type=Path)
    p.add_argument("--reading", default="lobe+held")
    p.add_argument("--imbalance", default="1 g*mm")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--stop-time", type=float, default=None)
    p.add_argument("--imbalance-check", action="store_true")
    a = p.parse_args()
    imbalance = parse_quantity(a.imbalance, "mass_length", field="--imbalance")
    if a.imbalance_check:
        imbalance_check(a.reading, (imbalance, 2e-6, 8.5e-6))
        return
    a.out.mkdir(parents=True, exist_ok=True)
    jobs = [(a.reading, v, imbalance, str(a.out), a.stop_time) for v in (0.0, 50.0, 100.0, 150.0)]
    with ProcessPoolExecutor(a.workers) as pool:
        heads = list(pool.map(one, jobs))
    (a.out / "protocol.json").write_text(json.dumps(heads, indent=2, default=str))
    for h in heads:
        print(
            json.dumps(
                {
                    k: h.get(k)
                    for k in (
                        "label",
                        "message",
                        "onset_speed_rpm",
                        "whip_frequency_Hz",
                        "divergence_speed_rpm",
                        "end_speed_rpm",
                        "onset_after_control_rpm",
                        "whip_after_control_Hz",
                        "wall_time_s",
                    )
                },
                default=str,
            )
        )


if __name__ == "__main__":
    main()
