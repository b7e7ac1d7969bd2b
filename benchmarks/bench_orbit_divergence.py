"""Benchmark of the orbit's divergence speed: whether it converges with the steps per
revolution and the Newton tolerances, without and with the case's disturbance. Prints its
figures; each study takes 8-11 minutes, so it runs only when asked.

Run: .venv/bin/python benchmarks/bench_orbit_divergence.py --divergence | --disturbance


- ``--divergence``: the divergence speed of the 0 V, 1 g·mm paper speed-up against the steps
  per revolution and the Newton tolerances, without a disturbance: no converged value at any
  affordable setting (ten runs, two at a time; about 11 minutes).
- ``--disturbance``: the same with a disturbance of 0.001, 0.01 (the case's) and 0.1 N RMS:
  converged to 0.2 % (eight runs, two at a time; about 8 minutes).

The cost model behind these figures and every route tried towards the 60 s target:
docs/development/orbit-performance.md.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

from foilbearing.case import default_case
from foilbearing.control import linear_ramp
from foilbearing.orbit import OrbitSettings, simulate

sys.path.insert(0, str(Path(__file__).parent))
from bench_orbit import (
    RPM,
)

#: Settings of the divergence study: (steps per revolution, newton_tol, newton_fraction).
DIVERGENCE_SETTINGS = (
    (24, 0.3, 1e-3),
    (48, 0.3, 1e-3),
    (96, 0.3, 1e-3),
    (24, 0.03, 1e-4),
    (24, 0.01, 1e-5),
    (32, 0.01, 1e-5),
    (48, 0.01, 1e-5),
    (64, 0.01, 1e-5),
    (96, 0.01, 1e-5),
    (48, 0.001, 1e-6),
)


def _divergence_run(
    setting: tuple[int, float, float, float | None],
) -> tuple[tuple[int, float, float, float | None], float]:
    from foilbearing.orbit.analysis import analyse_orbit

    n, tol, fraction, force = setting
    base = default_case()
    case = replace(base, rotor=replace(base.rotor, imbalance=1e-6))
    assert case.disturbance is not None
    disturbance = None if force is None else replace(case.disturbance, force_rms=force)
    case = replace(case, disturbance=disturbance)
    settings = OrbitSettings(steps_per_rev=n, newton_tol=tol, newton_fraction=fraction)
    res = simulate(case, linear_ramp(3e3 * RPM, 90e3 * RPM, 500.0), settings=settings)
    speed = analyse_orbit(res).headline(res)["divergence_speed_rpm"]
    return setting, float("nan") if speed is None else speed


#: Settings of the disturbance study: (steps per revolution, newton_tol, newton_fraction,
#: disturbance N RMS), the case's band and seed.
DISTURBANCE_SETTINGS = (
    (24, 0.3, 1e-3, 0.01),
    (24, 0.01, 1e-5, 0.01),
    (48, 0.3, 1e-3, 0.01),
    (24, 0.3, 1e-3, 0.1),
    (24, 0.01, 1e-5, 0.1),
    (48, 0.3, 1e-3, 0.1),
    (24, 0.3, 1e-3, 0.001),
    (24, 0.01, 1e-5, 0.001),
)


def divergence_study(disturbed: bool) -> None:
    """The 0 V, 1 g·mm speed-up's divergence speed against the step and the Newton tolerance,
    without a disturbance (``--divergence``) or with one of three sizes (``--disturbance``)."""
    from concurrent.futures import ProcessPoolExecutor

    print(
        "divergence of the 0 V, 1 g·mm paper speed-up (default case, BDF3) against steps per "
        "revolution and the Newton tolerances (newton_tol, newton_fraction), "
        + ("with a disturbance of the case's band" if disturbed else "without a disturbance")
        + "; two runs at a time"
    )
    settings = DISTURBANCE_SETTINGS if disturbed else tuple((*s, None) for s in DIVERGENCE_SETTINGS)
    with ProcessPoolExecutor(max_workers=2) as pool:
        for (n, tol, fraction, force), speed in pool.map(_divergence_run, settings):
            what = "" if force is None else f"disturbance {force:g} N RMS, "
            print(
                f"  {what}{n:3d} steps/rev, newton_tol {tol:g}, newton_fraction {fraction:g}: "
                f"divergence {speed / 1e3:.2f} krpm",
                flush=True,
            )


if __name__ == "__main__":
    if "--divergence" in sys.argv or "--disturbance" in sys.argv:
        divergence_study(disturbed="--disturbance" in sys.argv)
    else:
        print(
            "bench_orbit_divergence.py: give --divergence (about 11 minutes) or --disturbance "
            "(about 8 minutes)"
        )
