"""The study's voltage schedule (beyond the paper): computed, then verified in speed-ups.

The schedule (:func:`foilbearing.design.schedule_search.voltage_schedule`) is computed on the
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
response, before any whirl could be controlled; see ``foilbearing.study.orbits``). The runs go
on the study's queue of speed-ups (:class:`foilbearing.study.queue.OrbitQueue`), where the
runs the orbit stage also asks for are run once. Each run is read for the onset of sustained
sub-synchronous motion, its whip frequency, the divergence speed and the power
loss averaged over the run, and over the speeds all four runs reach.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

from foilbearing.case import Case
from foilbearing.constants import RPM

__all__ = ["SCHEDULE_SPEEDS_RPM", "schedule_errors", "schedule_stage"]

#: The study's schedule grid, rpm: 10 to 90 krpm in 5 krpm steps (17 speeds).
SCHEDULE_SPEEDS_RPM = tuple(range(10_000, 90_001, 5_000))
VERIFY_IMBALANCE = 1e-6  # kg·m, 1 g·mm


def _runs(schedule: Any) -> list[Any]:
    from foilbearing.study.orbits import RAMP
    from foilbearing.study.runs import OrbitRun

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
    verify: bool = True,
    workers: int | None = None,
    speeds: list[float] | None = None,
    grid_check: int = 1,
) -> dict[str, Any]:
    """Compute, write and (with ``verify``) run the schedule; returns its summary."""
    from foilbearing.study.queue import OrbitQueue

    queue = OrbitQueue(workers) if verify else None
    summary = queue_schedule(queue, case, out, stage, speeds=speeds, grid_check=grid_check)
    if queue is not None:
        queue.drain()
    return summary()


def queue_schedule(
    queue: Any,
    case: Case,
    out: Path,
    stage: Callable[[str], None],
    *,
    speeds: list[float] | None = None,
    grid_check: int = 1,
) -> Callable[[], dict[str, Any]]:
    """Compute and write the schedule, and put its speed-ups on ``queue`` (None: none).

    Returns the stage's summary, to call once the queue has drained. A run another stage
    asked for on the same queue (the protocol's 1 g·mm runs) is run once and shared. With
    ``grid_check`` ≥ 2 the schedule's points are evaluated again on that many times the
    cells (:func:`schedule_errors`), the schedule's ``grid_refined``: in a process of its
    own while the speed-ups run, since the queue hands its workers new runs only when the
    study waits on it.
    """
    from foilbearing.control.schedule_file import schedule_toml
    from foilbearing.design.schedule_search import voltage_schedule
    from foilbearing.io import save_figure, write_text
    from foilbearing.output.plots.schedule import plot_schedule

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
    if queue is None:
        if grid_check > 1:
            summary["schedule"]["grid_refined"] = schedule_errors(case, schedule, grid_check, stage)
        return lambda: summary
    plan = _runs(schedule)
    runs: dict[str, Any] = {}

    def ran(result: dict[str, Any]) -> None:
        runs[result["label"]] = result
        head = result["headline"]
        stage(f"  {head['description']}: {head['message']} ({head['wall_time_s']:.0f} s)")

    for r in plan:
        # 0 V and the schedule itself first: the longest runs, and the protocol's 0 V
        # run decides the runs that follow it.
        if not queue.submit(case, r, out, ran, priority=0 if r.ramp is None else 1):
            stage(f"  {r.describe()}: shared with the orbit stage")
    checking = None
    if grid_check > 1:  # in a process of its own, beside the queue's speed-ups
        from foilbearing.design.schedule_search import schedule_grid_check
        from foilbearing.study.queue import worker_pool

        pool = worker_pool(1)
        checking = pool.submit(schedule_grid_check, case, schedule, grid_check)

    def verification() -> dict[str, Any]:
        if checking is not None:
            check = checking.result()
            pool.shutdown()
            summary["schedule"]["grid_refined"] = schedule_errors(
                case, schedule, grid_check, stage, check=check
            )
        summary["verification"] = _verification(runs, plan, out, figures)
        return summary

    return verification


def schedule_errors(
    case: Case,
    schedule: Any,
    factor: int,
    stage: Callable[[str], None],
    *,
    check: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """The schedule's points on ``factor`` times the cells
    (:func:`foilbearing.design.schedule_search.schedule_grid_check`, or its result
    ``check`` where it ran elsewhere), with the texts the report prints: each speed's log
    decrement, whirl frequency and power loss with its error (the difference to the finer
    grid), and the limit speed's."""
    from foilbearing.design.schedule_search import schedule_grid_check
    from foilbearing.study.converged import with_error

    if check is None:
        check = schedule_grid_check(case, schedule, factor)
    head = schedule.headline()
    texts: dict[str, list[str | None]] = {}
    for key in ("log_decrement", "whirl_frequency_Hz", "power_loss_W"):
        texts[key] = [
            None if v is None or e is None else with_error(v, e)
            for v, e in zip(head[key], check["errors"][key], strict=True)
        ]
    limit, error = head["limit_speed_rpm"], check["limit_speed_error_rpm"]
    check["texts"] = texts | {
        "limit_speed_krpm": None if limit is None or error is None
        else with_error(limit / 1e3, error / 1e3)
    }  # fmt: skip
    fine = check["refined_grid"]
    worst = max((abs(e) for e in check["errors"]["log_decrement"] if e is not None), default=0.0)
    stage(
        f"  the schedule's points on {fine[0]} x {fine[1]}: log decrements within {worst:.3f}"
        + (
            f"; below the margin at {', '.join(f'{w / 1e3:.0f}' for w in check['below_margin_rpm'])} krpm"
            if check["below_margin_rpm"]
            else ""
        )
        + f" ({check['wall_time_s']:.0f} s)"
    )
    return check


def _seeded(run: Any, result: Any) -> bool:
    """A controlled run of a case with a random disturbance: its seed matters."""
    controlled = run.ramp is not None or run.schedule is not None
    return controlled and result.case.disturbance is not None


def _verification(
    runs: dict[str, Any], plan: list[Any], out: Path, figures: list[str]
) -> dict[str, Any]:
    """Each run's readouts, the power loss over the speeds all runs reach, and the figures."""
    from foilbearing.io import save_figure
    from foilbearing.orbit.analysis import mean_power_loss
    from foilbearing.output.plots.orbit import plot_subsync
    from foilbearing.output.plots.schedule import plot_run_power

    common = min(float(runs[r.label]["result"].speed[-1]) for r in plan) / RPM
    rows, subs, onsets, power = [], {}, {}, {}
    from foilbearing.study.orbits import floor_errors, seed_floor

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
            # the floor; a run an orbit stage refined gets its two-grid error from the
            # study (study.paper._share_refined)
            | {"grid_floor": floor_errors(head)}
            # a controlled run under the case's seed alone (the shared 0 V run's seeds are
            # the orbit stage's)
            | ({"seed_floor": seed_floor(head)} if _seeded(r, res) else {})
        )
    if subs:
        figures.append(str(save_figure(plot_subsync(subs, onsets), out / "schedule_subsync.png")))
    if power:
        figures.append(str(save_figure(plot_run_power(power), out / "schedule_power.png")))
    return {
        "speed_up": "3000-90000 rpm at 500 rad/s²",
        "imbalance_g_mm": VERIFY_IMBALANCE * 1e6,
        "common_range_rpm": [3000.0, common],
        "runs": rows,
    }
