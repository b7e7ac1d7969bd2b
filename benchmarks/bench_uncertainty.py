"""Benchmark of the uncertainty analysis: 256 samples of linear onsets at four voltages.

Target (issue 15): at most 10 minutes on a LocalCluster of 2 single-thread
workers. The inputs are the example's (examples/uncertainty_paper.toml: viscosity,
rotor mass, loss factor, clearance, imbalance), the outputs the linear onset
speed and whirl frequency at 0/50/100/150 V on the default 96 x 12 grid (scan
10-150 krpm in 10 krpm steps, then Brent). The Sobol estimator uses
256 // 7 = 36 base rows: 252 evaluations. The cluster is started and warmed up
(imports, numba cache) before the clock starts; the timed part is
``run_uncertainty``: submit, compute, write each point, summarise (SALib), write
the dataset. Prints its figures; not a test.

Run: .venv/bin/python benchmarks/bench_uncertainty.py [--samples N]
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "uncertainty_paper.toml"


def _onsets_only(text: str) -> str:
    """The example with its static outputs removed."""
    head, _, tail = text.partition("[outputs.static]")
    return head + "[outputs.stability]" + tail.partition("[outputs.stability]")[2]


def _warm() -> None:
    from foilbearing.case import default_case
    from foilbearing.stability import onset_speed

    rpm = math.pi / 30.0
    onset_speed(default_case().with_voltages(150.0), [50000 * rpm, 60000 * rpm])


def main() -> None:
    from distributed import Client, LocalCluster

    from foilbearing.uncertainty import load_uncertainty, run_uncertainty

    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=int, default=256)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "uq.toml"
        path.write_text(_onsets_only(EXAMPLE.read_text(encoding="utf-8")), encoding="utf-8")
        spec = load_uncertainty(path, samples=args.samples)
        print(
            f"{spec.n_points} evaluations, {len(spec.inputs)} inputs, outputs {list(spec.outputs)}"
        )
        with (
            LocalCluster(
                n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
            ) as cluster,
            Client(cluster) as client,
        ):
            client.run(_warm)
            t0 = time.perf_counter()
            ds, summary = run_uncertainty(spec, Path(tmp) / "run", client=client, progress=True)
            wall = time.perf_counter() - t0
        per_point = float(ds["status"].size and wall * 2 / spec.n_points)
        print(f"wall time: {wall:.1f} s ({wall / 60:.2f} min; target 10 min) on 2 workers")
        print(
            f"per point: {per_point:.2f} s of one core; ok {summary['n_ok']}, "
            f"failed {summary['n_failed']}"
        )
        print(f"{'output':<30} {'p5':>8} {'p50':>8} {'p95':>8}   ST (95 % half-width) per input")
        for name, o in summary["outputs"].items():
            st = "  ".join(
                f"{k.split('.')[-1]} {v:.2f}±{o['total_order_conf'][k]:.2f}"
                for k, v in o["total_order"].items()
                if v is not None
            )
            print(f"{name:<30} {o['p5']:8.2f} {o['p50']:8.2f} {o['p95']:8.2f}   {st}")


if __name__ == "__main__":
    main()
