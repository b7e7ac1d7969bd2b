"""The paper's analysis end to end on one case: the README's main job.

Stages run in the paper's order and each writes its figures and results into
the output folder as it finishes, so an interrupted study keeps what it did.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

from foilbearing.case import Case, is_default_case_file
from foilbearing.io import write_text

if TYPE_CHECKING:
    from foilbearing.output.result import StudyResult

__all__ = ["run_study", "run_study_result"]


def run_study(
    case: Case,
    out: Path,
    *,
    progress: bool = True,
    orbits: bool = True,
    uncertainty: str = "quick",
    schedule: bool = True,
    paper_reading: bool = True,
    bifurcation: bool = True,
    seeds: int = 1,
    theta_refine: int = 1,
) -> dict[str, Any]:
    """Run every stage available on ``case`` and write ``out/summary.json``.

    The summary of :func:`run_study_result`, which takes the same arguments.

    Returns
    -------
    The headline numbers of every stage, unit-named keys.
    """
    return run_study_result(
        case,
        out,
        progress=progress,
        orbits=orbits,
        uncertainty=uncertainty,
        schedule=schedule,
        paper_reading=paper_reading,
        bifurcation=bifurcation,
        seeds=seeds,
        theta_refine=theta_refine,
    ).summary


def run_study_result(
    case: Case,
    out: Path,
    *,
    progress: bool = True,
    orbits: bool = True,
    uncertainty: str = "quick",
    schedule: bool = True,
    paper_reading: bool = True,
    bifurcation: bool = True,
    seeds: int = 1,
    theta_refine: int = 1,
) -> StudyResult:
    """Run every stage available on ``case``; write ``out/summary.json`` and the report.

    Parameters
    ----------
    case
        The bearing case (the paper's C-GFB by default on the command line).
    out
        Output folder, created if needed.
    progress
        Print a line per stage to stderr.
    orbits
        Run the paper's four speed-up orbits (Figs. 13-15; the longest stage).
    uncertainty
        The envelopes of what the paper leaves open (the built-in uncertainty
        file, on the paper's case only): ``"quick"`` (64 evaluations of a Latin
        hypercube, RBD-FAST first-order indices, about a minute on 2 cores), ``"full"`` (the file's
        256, 252 with the Sobol' estimator's first-order and total indices) or
        ``"none"``.
    schedule
        The voltage schedule a controller should apply (C-GFB only; beyond the
        paper), verified in speed-ups when ``orbits`` is set.
    paper_reading
        With ``orbits``, also run the protocol under the paper's reading of the actuator
        (lobe + held, 1 g·mm; :func:`paper_reading_orbits`), about a minute more on 2
        cores on the built-in case's orbit grid (2.7 minutes on 96 × 12, 2026-12-02).
    bifurcation
        Is the whirl past the onset bounded? The Hopf type and the branch of limit
        cycles at each voltage under the case's reading and the paper's, on Dask
        (the paper's case; :func:`~foilbearing.study.bifurcation.bifurcation_stage`).
    seeds
        With ``orbits``, each 0 V speed-up over that many seeds of the case's disturbance
        (1: the case's alone), its sub-synchronous onset given as a range over them
        (:mod:`foilbearing.study.orbits`); each seed adds a speed-up per 0 V run.
    theta_refine
        With ``orbits``, each 0 V speed-up (the case's seed) again on its orbit grid with
        that many times the θ cells, for its readouts' discretisation error (1: none;
        :mod:`foilbearing.study.orbits`); with ``bifurcation``, every limit-cycle branch
        as well (:func:`~foilbearing.study.bifurcation.cycle_errors`); > 1 also solves the
        static table's shown speeds and the coefficients on twice the cells in θ and Z,
        for theirs (:func:`~foilbearing.study.static.static_errors`,
        :func:`~foilbearing.study.converged.refined_coefficients`), and on a bearing of
        its own the grid check of its case point and onset.

    Returns
    -------
    StudyResult
        The headline numbers of every stage (unit-named keys), the folder, and the
        figures each stage wrote; ``report.html`` is rendered from it.
    """
    from foilbearing.output.figures import write_identification_figures, write_structure_figures
    from foilbearing.output.summary import case_summary, format_summary, structure_summary
    from foilbearing.study.plan import check_load_is_carried, study_plan

    plan = study_plan(case)  # the [study] table is checked before any work
    paper = case.actuators is not None and is_default_case_file(case.source)
    if not paper:
        check_load_is_carried(case, plan)
    out.mkdir(parents=True, exist_ok=True)
    results: dict[str, Any] = {}
    t0 = time.perf_counter()

    def stage(name: str) -> None:
        if progress:
            print(f"[{time.perf_counter() - t0:6.1f} s] {name}", flush=True)

    stage("case")
    results["case"] = case_summary(case)
    if progress:
        print(format_summary(results["case"]))

    if paper and case.actuators is not None:
        stage("identification of the PZT stacks from the shipped synthetic measurements")
        from foilbearing.identification import example_measurements, identify

        no_load, stiffness = example_measurements()

        ident = identify(no_load, stiffness, case.actuators.contact_area)
        results["identification"] = ident.headline()
        results["identification"]["figures"] = [
            str(p) for p in write_identification_figures(ident, out)
        ]

    stage(
        "structure: k_b, k_assy, base preloads; Figs. 7-8"
        if case.actuators is not None
        else "structure: bump stiffness"
    )
    structure = structure_summary(case, list(plan.voltages) or [0.0])
    if structure:  # a rigid gas bearing has no foil: no structure, and no section of it
        structure["figures"] = [str(p) for p in write_structure_figures(case, out)]
        results["structure"] = structure

    if not paper:  # any other case: its own plan (foilbearing.study.plan); the paper's
        # numbers, its synthetic stack data and the uncertainty file fit its bearing only
        from foilbearing.study.bearing import bearing_study

        if plan.identification is not None and case.actuators is not None:
            stage("identification of the PZT stacks from the case's test files")
            from foilbearing.identification import case_values, identify

            ident = identify(*plan.identification, case.actuators.contact_area)
            names = ("stack_displacement.png", "stack_stiffness.png")
            results["identification"] = ident.headline() | {
                "files": list(plan.identification),
                "for_the_case_file": case_values(ident),
                "figures": [str(p) for p in write_identification_figures(ident, out, names)],
            }

        results |= bearing_study(case, plan, out, stage, orbits=orbits, theta_refine=theta_refine)
        if bifurcation and case.actuators is None:
            from foilbearing.study.bifurcation import passive_bifurcation_stage

            onset = (results.get("bearing_stability") or {}).get("onset") or {}
            results["bifurcation"] = passive_bifurcation_stage(
                case, out, stage, onset.get("onset_speed_rpm"), theta_refine
            )
        if schedule and case.actuators is not None:
            from foilbearing.study.schedule import schedule_stage

            stage("voltage schedule over the plan's speeds")
            results["schedule"] = schedule_stage(
                case, out, stage, verify=False, speeds=list(plan.speeds)
            )
        return _finish(out, results, stage)

    sweep = _static_stage(case, out, results, stage, theta_refine > 1)
    onsets, onset_errors = _stability_stage(case, out, results, stage, theta_refine > 1)
    if case.actuators is not None:
        from foilbearing.study.design import design_stage

        results["actuator_design"] = design_stage(case, out, stage, onset_errors)
        if bifurcation:
            from foilbearing.study.bifurcation import bifurcation_stage

            results["bifurcation"] = bifurcation_stage(case, out, stage, theta_refine=theta_refine)
            write_text(out / "summary.json", json.dumps(results, indent=2, default=_plain))

    if uncertainty != "none":
        from foilbearing.study.envelopes import uncertainty_stage

        results["uncertainty"] = uncertainty_stage(
            out, uncertainty, stage, grid_check=2 if theta_refine > 1 else 1
        )
        write_text(out / "summary.json", json.dumps(results, indent=2, default=_plain))

    orbit_runs: dict[str, Any] = {}  # the runs by label, for the report's figures
    _speed_ups(
        case, out, results, stage, orbits, paper_reading, schedule, orbit_runs, seeds,
        theta_refine,
    )  # fmt: skip

    _paper_comparison(case, out, results, sweep, onsets, progress, onset_errors)
    return _finish(out, results, stage, orbit_runs)


def _speed_ups(
    case: Case,
    out: Path,
    results: dict[str, Any],
    stage: Any,
    orbits: bool,
    paper_reading: bool,
    schedule: bool,
    orbit_runs: dict[str, Any],
    seeds: int = 1,
    theta_refine: int = 1,
) -> None:
    """The stages of speed-ups (the protocol, under the paper's reading, the schedule's) on
    one queue of worker processes: each run starts as soon as a core is free, the 0 V runs
    first, and a run two stages ask for runs once (:class:`~foilbearing.study.queue.OrbitQueue`).
    The schedule is computed here while the workers run the first speed-ups."""
    from foilbearing.study.queue import OrbitQueue

    queue = OrbitQueue() if orbits else None
    summaries: dict[str, Any] = {}
    if queue is not None:
        from foilbearing.study.orbits import queue_paper_orbits

        stage("orbits: speed-up 3-90 krpm at 500 rad/s², 0 V and ramps to 50/100/150 V at 6-6.5 s")
        summaries["orbits"] = queue_paper_orbits(
            queue, case, out, stage, results=orbit_runs, seeds=seeds, theta_refine=theta_refine
        )
        if paper_reading and case.actuators is not None:
            summaries[PAPER_READING_KEY] = queue_paper_reading(
                queue, case, out, stage, seeds=seeds, theta_refine=theta_refine
            )
    if schedule:
        from foilbearing.study.schedule import queue_schedule

        stage(
            "voltage schedule: least-drag voltages with log decrement >= 0.1, 10-90 krpm"
            + ("; verified in speed-ups" if orbits else "")
        )
        summaries["schedule"] = queue_schedule(
            queue, case, out, stage, grid_check=2 if theta_refine > 1 else 1
        )
    if queue is not None:
        queue.drain()
    for key, summary in summaries.items():  # the stages' order
        results[key] = summary()
        _share_refined(results)  # once the schedule's verification is in
        write_text(out / "summary.json", json.dumps(results, indent=2, default=_plain))


def _share_refined(results: dict[str, Any]) -> bool:
    """A speed-up the schedule's verification shares with an orbit stage (its 0 V, 1 g·mm
    run is the protocol's) carries there too the two-grid error of the refined run the
    orbit stage ran, instead of the floor; returns whether any row changed."""
    refined = {
        r["label"]: r["theta_refined"]
        for key in ("orbits", PAPER_READING_KEY)
        for r in (results.get(key) or {}).get("runs", [])
        if r.get("theta_refined")
    }
    changed = False
    for row in ((results.get("schedule") or {}).get("verification") or {}).get("runs", []):
        if row.get("label") in refined:
            row.pop("grid_floor", None)
            row["theta_refined"] = refined[row["label"]]
            changed = True
    return changed


def _paper_comparison(
    case: Case,
    out: Path,
    results: dict[str, Any],
    sweep: Any,
    onsets: dict[str, dict[float, Any]] | None,
    progress: bool,
    onset_errors: dict[str, dict[float, dict[str, Any]]] | None = None,
) -> None:
    """Our numbers beside the paper's (paper_comparison.md and the summary).

    ``onset_errors``: the published onsets' refinements and errors by kind and voltage
    (:func:`~foilbearing.study.converged.published_onsets`); the paper's reading is set
    beside the paper at its value at the published resolution."""
    from foilbearing.paper import markdown_table, static_comparison
    from foilbearing.paper_dynamics import orbit_comparison, stability_comparison
    from foilbearing.study.static import grid_errors_at

    at = ("C-GFB", 150.0, 90e3)  # the preloads the paper gives, with their grid error
    errors = grid_errors_at(results["static"]["points"], at, "preload_um")
    rows = static_comparison(case, results["structure"], sweep, errors)
    if onsets is not None:
        rows += stability_comparison(onsets, onset_errors)
    if "orbits" in results:
        # The linear partner of the orbits is the analysis on their grid.
        partner = "C-GFB, orbit grid" if case.grid.orbit_is_own else "C-GFB"
        linear = (
            {
                v: r.onset_speed and r.onset_speed * 30.0 / math.pi
                for v, r in onsets[partner].items()
            }
            if onsets is not None
            else None
        )
        force = 0.0 if case.disturbance is None else case.disturbance.force_rms
        act = case.actuators
        own = None if act is None else f"{act.preload_response} + {act.dynamics}"
        # The partner on the orbits' grid, with its error (foilbearing.study.converged).
        partner_texts = {
            v: e["onset_text_krpm"]
            for v, e in (onset_errors or {}).get(partner, {}).items()
            if e.get("refined_grid")
        }
        rows += orbit_comparison(results["orbits"]["runs"], linear, force, own, partner_texts)
        if PAPER_READING_KEY in results and onsets is not None:
            held = onsets.get("C-GFB, lobe+held", {})
            lin = {v: r.onset_speed and r.onset_speed * 30.0 / math.pi for v, r in held.items()}
            conv = (onset_errors or {}).get("C-GFB, lobe+held", {})
            lin |= {v: e["onset_refined_rpm"] for v, e in conv.items() if "onset_refined_rpm" in e}
            texts = {
                v: e["onset_refined_text_krpm"] for v, e in conv.items() if e.get("refined_grid")
            }
            runs = results[PAPER_READING_KEY]["runs"]
            rows += orbit_comparison(runs, lin, force, "the paper's: lobe + held", texts)
    table = markdown_table(rows)
    results["paper_comparison"] = [r.__dict__ for r in rows]
    write_text(
        out / "paper_comparison.md",
        "# Our numbers beside the paper's\n\n"
        f"Case: {case.title}. Viscosity {case.gas.viscosity:g} Pa·s (assumed: the paper does "
        f"not give it); grid {case.grid.n_theta} × {case.grid.n_z} (θ × half length)"
        + (f"; the orbits on {case.grid.orbit_label}" if case.grid.orbit_is_own else "")
        + ".\n\n"
        + table
        + "\n",
    )
    if progress:
        print(table)


#: The summary's key of the speed-ups under the paper's reading of the actuator.
PAPER_READING_KEY = "orbits_paper_reading"


def paper_reading_orbits(
    case: Case, out: Path, stage: Any, stop_time: float | None = None
) -> dict[str, Any]:
    """The protocol of Figs. 13-15 under the paper's reading (lobe + held), at 1 g·mm.

    The reading that gives the paper's 100 and 150 V behaviour (docs/model.md §3.8); 1 g·mm
    because 8.5 g·mm drives this model to contact through its low-speed critical (the
    measurement: ``scripts/paper_reading_protocol.py --imbalance-check``). Files carry the
    prefix ``lobe-held_``; the stage's figures are those of its runs and its Fig. 15.
    ``stop_time`` (s) ends each run early (tests).
    """
    from foilbearing.study.queue import OrbitQueue

    queue = OrbitQueue()
    summary = queue_paper_reading(queue, case, out, stage, stop_time)
    queue.drain()
    return summary()


def queue_paper_reading(
    queue: Any,
    case: Case,
    out: Path,
    stage: Any,
    stop_time: float | None = None,
    seeds: int = 1,
    theta_refine: int = 1,
) -> Any:
    """:func:`paper_reading_orbits` on a shared queue; returns its summary, to call once the
    queue has drained."""
    from dataclasses import replace

    from foilbearing.output.report.captions import READING_TAG
    from foilbearing.study.orbits import SENSITIVITY_IMBALANCE, queue_paper_orbits

    stage(
        "orbits under the paper's reading of the actuator (lobe + held), 1 g·mm: 0 V, then "
        "ramps to 50/100/150 V at 6-6.5 s"
    )
    reading = case.with_actuator_reading("lobe", "held")
    reading = replace(reading, rotor=replace(reading.rotor, imbalance=SENSITIVITY_IMBALANCE))
    runs: dict[str, Any] = {}
    protocol = queue_paper_orbits(
        queue, reading, out, stage, stop_time=stop_time, results=runs, tag=READING_TAG,
        seeds=seeds, theta_refine=theta_refine,
    )  # fmt: skip

    def summary() -> dict[str, Any]:
        stage_result = protocol()
        own = [p for run in runs.values() for p in run.get("figures", ())]
        stage_result["figures"] = [str(p) for p in own] + list(stage_result["figures"])
        stage_result["reading"] = "lobe + held"
        return stage_result

    return summary


def _finish(
    out: Path, results: dict[str, Any], stage: Any, orbit_runs: dict[str, Any] | None = None
) -> StudyResult:
    """The study's result: summary.json with its figure record, and report.html from it.

    ``orbit_runs``: the paper's speed-ups by label, each with the ``"figures"`` it
    wrote; they follow the orbit stage's own figures in the protocol's order of
    the runs (:func:`foilbearing.output.result.orbit_figure_order`).
    """
    from foilbearing.output.report import write_report
    from foilbearing.output.result import FIGURE_RECORD_KEY, StudyResult, orbit_figure_order

    runs = [p for run in (orbit_runs or {}).values() for p in run.get("figures", ())]
    protocol = results["orbits"]["runs"] if "orbits" in results else []
    order = orbit_figure_order(protocol)
    extra = {"orbits": sorted(runs, key=order)} if "orbits" in results else None
    result = StudyResult.from_stages(results, out, extra)
    results[FIGURE_RECORD_KEY] = result.figure_record()
    write_text(out / "summary.json", json.dumps(results, indent=2, default=_plain))
    report = write_report(result)
    results["report"] = str(report)
    write_text(out / "summary.json", json.dumps(results, indent=2, default=_plain))
    stage(f"done: results in {out}/, report {report}")
    return result


def _static_stage(case: Case, out: Path, results: dict[str, Any], stage: Any, refine: bool) -> Any:
    """Figs. 9-12: C-GFB and shimmed GFB, 10-90 krpm, 0/50/100/150 V; ``refine``: the
    speeds the report shows again on twice the cells, for their grid error."""
    import math

    from foilbearing.check import refined
    from foilbearing.io import write_with
    from foilbearing.output.figures import write_static_figures
    from foilbearing.output.summary import sweep_points
    from foilbearing.study.static import (
        PAPER_SPEEDS_RPM,
        PAPER_VOLTAGES,
        SHOWN_SPEEDS_RPM,
        static_errors,
        static_sweep,
    )

    stage("static analysis: C-GFB and shimmed GFB, 10-90 krpm x 0/50/100/150 V (Figs. 9-12)")
    rpm = math.pi / 30.0
    speeds = [s * rpm for s in PAPER_SPEEDS_RPM]
    ds = static_sweep(case, speeds, PAPER_VOLTAGES, progress=lambda line: stage("  " + line))
    write_with(out / "static_sweep.nc", lambda tmp: ds.to_netcdf(tmp))
    points = sweep_points(ds)
    if refine:
        fine = refined(case, 2)
        stage(f"  {len(SHOWN_SPEEDS_RPM)} speeds on {fine.grid.n_theta} × {fine.grid.n_z}")
        finer = static_sweep(fine, [s * rpm for s in SHOWN_SPEEDS_RPM], PAPER_VOLTAGES)
        static_errors(points, sweep_points(finer), [fine.grid.n_theta, fine.grid.n_z])
    results["static"] = {
        "points": points,
        "figures": [str(p) for p in write_static_figures(ds, out)],
        "netcdf": str(out / "static_sweep.nc"),
    }
    return ds


def _stability_stage(
    case: Case, out: Path, results: dict[str, Any], stage: Any, refine: bool
) -> tuple[dict[str, dict[float, Any]], dict[str, dict[float, dict[str, Any]]]]:
    """Coefficients at 50 krpm and 150 V (``refine``: with their grid error); onset speeds
    per voltage; the stability map.

    Returns the onsets by kind and voltage, and the published ones' refinements and errors
    (:func:`~foilbearing.study.converged.published_onsets`)."""
    import math
    import os

    from foilbearing.analysis.coefficients import force_coefficients
    from foilbearing.analysis.equilibrium import solve_equilibrium
    from foilbearing.analysis.stability import stability_map
    from foilbearing.errors import InputError
    from foilbearing.io import save_figure
    from foilbearing.output.plots.dynamics import plot_coefficients, plot_stability_map
    from foilbearing.study.converged import STUDY_SCAN_RPM, onset_table, refined_coefficients
    from foilbearing.study.queue import worker_pool
    from foilbearing.study.static import PAPER_VOLTAGES

    rpm = math.pi / 30.0
    stage("dynamic coefficients at 50 krpm, 150 V")
    st = solve_equilibrium(case.with_voltages(150.0), speed=50e3 * rpm)
    fc = force_coefficients(st, [f * st.speed for f in (0.1, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0)])
    fig = save_figure(plot_coefficients(fc), out / "coefficients_50krpm_150V.png")
    results["coefficients"] = fc.headline() | {"figures": [str(fig)]}
    if refine:  # each coefficient with its grid error (the report's table)
        results["coefficients"]["grid_refined"] = refined_coefficients(fc)
    stage("linear stability: onset speed per voltage, C-GFB and shimmed GFB")
    scan = [s * rpm for s in STUDY_SCAN_RPM]
    if case.actuators is None:
        raise InputError("the onset over voltages needs a case with [actuators]")
    # Every onset the study prints, each with its error (foilbearing.study.converged): the
    # case's reading and its shimmed twin (the paper's comparison); where the case has
    # lift-off, both with the suction retained, to show what relieving the sub-ambient film
    # does (docs/model.md §3); the orbits' linear partner on their own grid, beside which
    # their readouts are set; and the paper's reading of the actuator (lobes lowered,
    # stingers held; docs/model.md §3.8). Kind → (case, shimmed).
    kinds: dict[str, tuple[Case, bool]] = {"C-GFB": (case, False), "shimmed": (case, True)}
    if case.foil is not None and case.foil.lift_off:
        kept = case.with_subambient("retained")
        kinds["C-GFB, suction retained"] = (kept, False)
        kinds["shimmed, suction retained"] = (kept, True)
    if case.grid.orbit_is_own:
        kinds["C-GFB, orbit grid"] = (case.orbit_case(), False)
    kinds["C-GFB, lobe+held"] = (case.with_actuator_reading("lobe", "held"), False)
    with worker_pool(min(os.cpu_count() or 1, len(PAPER_VOLTAGES))) as pool:
        onsets, errors = onset_table(kinds, PAPER_VOLTAGES, scan, pool, stage)
    ds = stability_map(case, scan[: len(scan) // 2], PAPER_VOLTAGES)
    points = [onsets["C-GFB"][v].onset_speed for v in PAPER_VOLTAGES]
    fig = save_figure(
        plot_stability_map(ds, [None if o is None else o / rpm for o in points]),
        out / "stability_map.png",
    )
    results["stability"] = {
        kind: [
            {"voltage_V": v} | r.headline() | errors.get(kind, {}).get(v, {})
            for v, r in per_volt.items()
        ]
        for kind, per_volt in onsets.items()
    } | {"figures": [str(fig)]}
    return onsets, errors


def _plain(x: Any) -> Any:
    if hasattr(x, "tolist"):
        return x.tolist()
    return str(x)
