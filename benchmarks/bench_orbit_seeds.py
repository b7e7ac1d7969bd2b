"""Benchmark of the controlled speed-ups' spread over the disturbance's seed: the paper's
protocol (1 g·mm, voltage ramps to 50, 100 and 150 V at 6.0-6.5 s) under the case's own
reading of the actuator and the paper's (lobe + held), each run under several seeds of
the case's random disturbance force. Prints each run's readouts per seed, their range,
and the largest spread of each readout relative to its mean. Prints its figures; not a
test.

The study runs each 0 V speed-up over three seeds (``--seeds 3``) and states the range of
its readouts; the controlled runs it runs under the case's seed alone. This measures what
the other seeds would give them.

Run: .venv/bin/python benchmarks/bench_orbit_seeds.py [--seeds 1,2,3] [--reading own|paper|both]
     [--volts 50,100,150] [--ramp 6.0,6.5] [--imbalance 1]

(``--ramp 0.08,0.58 --imbalance 8.5 --reading own``: the control the study applies before
the 8.5 g·mm 0 V run's divergence, 1 s a run.)

Two runs at a time (the study's worker pool); about 30 s (own reading) to 70 s (the paper's)
a run on an idle core.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path
from typing import Any

READOUTS = (
    ("onset_speed_rpm", "onset, krpm", 1e-3),
    ("whip_frequency_Hz", "whip, Hz", 1.0),
    ("divergence_speed_rpm", "divergence, krpm", 1e-3),
)


def _case(reading: str) -> Any:
    from foilbearing.case import default_case

    case = default_case()
    return case.with_actuator_reading("lobe", "held") if reading == "paper" else case


Job = tuple[str, float, int, tuple[float, float], float, str]


def _run(job: Job) -> tuple[tuple[str, float, int], dict[str, Any]]:
    from foilbearing.study.runs import OrbitRun, run_one

    reading, volts, seed, ramp, imbalance, out = job
    run = OrbitRun(volts, ramp, imbalance, "seeds", seed=seed, tag=reading + "_")
    head = run_one(_case(reading), run, Path(out))["headline"]
    return (reading, volts, seed), head


def main() -> None:
    from foilbearing.study.queue import worker_pool

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", default="1,2,3")
    parser.add_argument("--reading", choices=("own", "paper", "both"), default="both")
    parser.add_argument("--volts", default="50,100,150")
    parser.add_argument("--ramp", default="6.0,6.5", help="the voltage ramp's start, end, s")
    parser.add_argument("--imbalance", type=float, default=1.0, help="g·mm")
    args = parser.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    volts = [float(v) for v in args.volts.split(",")]
    start, end = (float(t) for t in args.ramp.split(","))
    readings = ["own", "paper"] if args.reading == "both" else [args.reading]
    print(
        f"the protocol's controlled speed-ups (3-90 krpm at 500 rad/s², {args.imbalance:g} g·mm, "
        f"ramp at {start:g}-{end:g} s) under the disturbance seeds {args.seeds}; two runs at a "
        "time"
    )
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as out, worker_pool(2) as pool:
        # the longest runs (the paper's reading, the highest voltages) first
        jobs: list[Job] = [
            (r, v, s, (start, end), args.imbalance * 1e-6, out)
            for r in reversed(readings)
            for v in reversed(volts)
            for s in seeds
        ]
        got = dict(pool.map(_run, jobs))
    print(f"{len(jobs)} runs in {time.perf_counter() - t0:.0f} s wall")
    worst = {key: 0.0 for key, _, _ in READOUTS}
    for reading in readings:
        for v in volts:
            heads = [got[reading, v, s] for s in seeds]
            walls = ", ".join(f"{h['wall_time_s']:.0f}" for h in heads)
            print(f"\n{reading} reading, {v:g} V ramp (run times {walls} s)")
            for key, name, scale in READOUTS:
                values = [h.get(key) for h in heads]
                shown = " / ".join("-" if x is None else f"{x * scale:.2f}" for x in values)
                found = [x for x in values if x is not None]
                spread = ""
                if len(found) == len(values) and len(found) > 1:
                    rel = (max(found) - min(found)) / (sum(found) / len(found))
                    worst[key] = max(worst[key], rel)
                    spread = f"   range {100 * rel:.2f} % of the mean"
                print(f"  {name:18s} {shown}{spread}")
    print("\nlargest range over the seeds, of the mean, where every seed gave the readout:")
    for key, name, _ in READOUTS:
        print(f"  {name:18s} {100 * worst[key]:.2f} %")


if __name__ == "__main__":
    main()
