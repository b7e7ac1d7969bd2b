"""Benchmark of the voltage schedule: 17 speeds (10-90 krpm) on the default case.

Target (issue 16): at most 2 minutes on 2 cores. The schedule is serial (each
speed starts from the previous speed's optimum), so it uses one core. The timed
part is ``voltage_schedule`` after a warm-up (imports, numba cache): 17 searches
of at most 40 equilibria with whirl modes, the slew-rate envelope and the 16
midpoint checks. Prints its figures; not a test.

``--budget N [N ...]`` runs the schedule again with larger per-speed budgets
and prints how much power loss the default budget leaves on the table.

Run: .venv/bin/python benchmarks/bench_schedule.py [--budget 100]
"""

from __future__ import annotations

import argparse
import math
import time

RPM = math.pi / 30.0


def main() -> None:
    from foilbearing.case import default_case
    from foilbearing.design.schedule_search import evaluate_voltages, voltage_schedule

    ap = argparse.ArgumentParser()
    ap.add_argument("--budget", type=int, nargs="*", default=[])
    args = ap.parse_args()
    case = default_case()
    evaluate_voltages(case, 50_000 * RPM, (150.0, 150.0, 150.0))  # warm-up
    speeds = [rpm * RPM for rpm in range(10_000, 90_001, 5_000)]
    t0 = time.perf_counter()
    sched = voltage_schedule(case, speeds)
    wall = time.perf_counter() - t0
    print(f"17-speed schedule, default case: {wall:.1f} s (target 120 s), "
          f"{sched.evaluations} equilibria with whirl modes, {wall / sched.evaluations * 1e3:.0f} ms each")  # fmt: skip
    assert sched.power_loss is not None and sched.power_loss_reference is not None
    assert sched.log_decrement is not None and sched.midpoint_log_decrement is not None
    print(" speed (krpm)  voltages (V)           log dec  power (W)  at 150 V (W)  saved")
    for k, w in enumerate(sched.speeds):
        volts = "/".join(f"{v:5.1f}" for v in sched.voltages[k])
        ref = sched.power_loss_reference[k]
        print(f" {w / RPM / 1e3:11.0f}  {volts:<21}  {sched.log_decrement[k]:+.3f}  "
              f"{sched.power_loss[k]:9.2f}  {ref:12.2f}  {100 * (1 - sched.power_loss[k] / ref):4.0f} %")  # fmt: skip
    mid = sched.midpoint_log_decrement
    print(f"midpoint log decrement: min {min(mid):+.3f}; limit speed: "
          + ("none (stable to 90 krpm)" if sched.limit_speed is None else f"{sched.limit_speed / RPM:.0f} rpm"))  # fmt: skip
    for budget in args.budget:
        t0 = time.perf_counter()
        more = voltage_schedule(case, speeds, max_evaluations=budget)
        assert more.power_loss is not None
        gap = 100 * (sched.power_loss / more.power_loss - 1)
        print(f"budget {budget} per speed: {time.perf_counter() - t0:.1f} s, "
              f"{more.evaluations} equilibria; the default budget's power loss is "
              f"{gap.min():+.1f} to {gap.max():+.1f} % of it (mean {gap.mean():+.1f} %)")  # fmt: skip


if __name__ == "__main__":
    main()
