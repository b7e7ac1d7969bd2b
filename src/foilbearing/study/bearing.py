"""The study of any bearing other than the paper's C-GFB: every analysis that applies.

Runs the plan of :func:`foilbearing.study.plan.study_plan` on a passive gas foil
bearing, a shimmed one or a rigid gas journal bearing, each stage writing its
figures into the output folder as it finishes:

1. **static** against speed at the case load (continuation in speed): eccentricity,
   attitude angle, minimum film, drag torque and power loss; film and pressure
   maps at the plan's map speeds;
2. **load capacity** at the case speed: the same readouts against load, the case
   load halved then doubled until the film closes (or the plan's loads);
3. **dynamic coefficients**: the eight synchronous K and C against speed, and
   against excitation frequency at the plan's frequency speeds;
4. **linear stability**: the onset speed and whirl frequency (scan continued up
   to ``onset_top``), and the log decrement of the least stable whirl mode at
   every plan speed (the stability map of a bearing without voltages); for a
   shimmed bearing also the onset against the shims' thickness;
   **grid check**: the readouts at the case speed and load (static, synchronous
   K and C) and the onset and whirl frequency on the case's grid and on twice its
   cells (:func:`foilbearing.check.grid_check`), each printed with its error;
5. **actuators** (C-GFB): the static readouts, the preloads and the actuator
   pressures against the actuators' voltage at the case speed and load;
6. **orbit**: a speed-up over the plan's speeds with the case's imbalance
   (and, for a C-GFB, the plan's voltage ramp): waterfall, sub-synchronous
   amplitude, onset and divergence.

The case's declared reference values are set beside the readouts they name;
those at the case speed and load (static readouts, synchronous coefficients)
come from one equilibrium there.

A point that does not converge is recorded with its message and what to try;
it does not stop the study.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError, SolverError
from foilbearing.study.plan import CASE_POINT_KEYS, REFERENCE_KEYS, StudyPlan, shown_reference

__all__ = ["bearing_study", "reference_rows"]

#: The film "closes" for the load-capacity curve below this fraction of C.
CLOSED_FILM = 0.02
FREQUENCY_RATIOS = (0.1, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0)  # of the speed, for K(ω), C(ω)
_TRY = "try a finer speed step in [study] speed_range, or a lower load"


def _readouts(st: Any) -> dict[str, Any]:
    return {
        "speed_rpm": st.speed / RPM,
        "load_N": st.case.operation.load,
        "eccentricity": st.eccentricity,
        "attitude_deg": math.degrees(st.attitude_angle),
        "min_film_um": st.min_film * 1e6,
        "drag_torque_Nm": st.drag_torque,
        "power_loss_W": st.power_loss,
        "converged": True,
    }


def _equilibrium(
    case: Case, speed: float, *, model: Any = None, start: Any = None
) -> tuple[Any, str]:
    """The converged equilibrium and its message, or None and why not: a failed solve is
    recorded by the stage, never raised through the study."""
    from foilbearing.analysis.equilibrium import solve_equilibrium

    try:
        st = solve_equilibrium(case, speed=speed, model=model, start=start)
    except SolverError as exc:
        return None, str(exc)
    return (st if st.converged else None), st.message


def _failed(speed: float, load: float, message: str) -> dict[str, Any]:
    return {
        "speed_rpm": speed / RPM,
        "load_N": load,
        "converged": False,
        "message": f"{message}; {_TRY}",
    }


def _static(
    case: Case, plan: StudyPlan, out: Path, stage: Callable[[str], None]
) -> tuple[dict[str, Any], dict[float, Any]]:
    from foilbearing.film import film_model
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bearing import plot_against
    from foilbearing.output.plots.static import plot_point

    model = film_model(case)
    points, found = [], {}
    start = None
    for w in plan.speeds:
        st, message = _equilibrium(case, w, model=model, start=start)
        if st is None:
            points.append(_failed(w, case.operation.load, message))
            start = None
            continue
        start = (st.eps_x, st.eps_y, st.P)
        found[w] = st
        points.append(_readouts(st))
    ok = sum(p["converged"] for p in points)
    stage(f"  static: {ok}/{len(points)} speeds converged")
    figures = [str(save_figure(plot_against(points, "speed_rpm"), out / "static_vs_speed.png"))]
    for w in plan.map_speeds:
        st = found.get(w) or _equilibrium(case, w, model=model)[0]
        if st is not None:
            name = f"film_map_{w / RPM:.0f}rpm.png"
            figures.append(str(save_figure(plot_point(st), out / name)))
    return {"points": points, "figures": figures}, found


def _load_capacity(
    case: Case, plan: StudyPlan, out: Path, stage: Callable[[str], None]
) -> dict[str, Any]:
    from dataclasses import replace

    from foilbearing.film import film_model
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bearing import plot_against

    w = case.operation.speed
    model = film_model(case)
    c = case.bearing.clearance
    auto = not plan.loads
    loads = list(plan.loads) or [case.operation.load * 2.0**k for k in range(-1, 12)]
    points: list[dict[str, Any]] = []
    note = "the plan's loads"
    for load in loads:
        at = replace(case, operation=replace(case.operation, load=load))
        st, message = _equilibrium(at, w, model=model)
        if st is None:
            points.append(_failed(w, load, message))
            if auto:
                note = f"stopped at {load:g} N: no equilibrium (the film closes)"
                break
            continue
        points.append(_readouts(st))
        if auto and st.min_film < CLOSED_FILM * c:
            note = f"stopped at {load:g} N: minimum film below {CLOSED_FILM:g} C"
            break
    else:
        if auto:
            note = f"stopped after {len(loads)} doublings (the film did not close)"
    carried = [p["load_N"] for p in points if p["converged"]]
    stage(f"  load capacity at {w / RPM:.0f} rpm: up to {max(carried, default=0.0):g} N; {note}")
    fig = save_figure(plot_against(points, "load_N"), out / "load_capacity.png")
    return {
        "speed_rpm": w / RPM,
        "points": points,
        "largest_load_carried_N": max(carried, default=None),
        "note": note,
        "figures": [str(fig)],
    }


def _coefficients(
    case: Case, plan: StudyPlan, found: dict[float, Any], out: Path, stage: Callable[[str], None]
) -> dict[str, Any]:
    from foilbearing.analysis.coefficients import force_coefficients
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bearing import plot_synchronous
    from foilbearing.output.plots.dynamics import plot_coefficients

    rows = []
    for w, st in found.items():
        fc = force_coefficients(st, w)
        rows.append(
            {
                "speed_rpm": w / RPM,
                "K_N_per_m": np.asarray(fc.K[0]).tolist(),
                "C_N_s_per_m": np.asarray(fc.C[0]).tolist(),
            }
        )
    figures = [str(save_figure(plot_synchronous(rows), out / "coefficients_vs_speed.png"))]
    per_frequency = []
    for w in plan.frequency_speeds:
        st = found.get(w) or _equilibrium(case, w)[0]
        if st is None:
            continue
        fc = force_coefficients(st, [r * w for r in FREQUENCY_RATIOS])
        name = f"coefficients_{w / RPM:.0f}rpm.png"
        figures.append(str(save_figure(plot_coefficients(fc), out / name)))
        per_frequency.append({"speed_rpm": w / RPM} | fc.headline())
    stage(f"  coefficients at {len(rows)} speeds, and against frequency at {len(per_frequency)}")
    return {"synchronous": rows, "against_frequency": per_frequency, "figures": figures}


def _stability(
    case: Case, plan: StudyPlan, found: dict[float, Any], out: Path, stage: Callable[[str], None]
) -> dict[str, Any]:
    from foilbearing.analysis.stability import whirl_mode
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bearing import plot_log_decrement

    modes = []
    for w, st in found.items():
        try:
            m = whirl_mode(st, case.rotor.mass)
        except SolverError as exc:
            modes.append({"speed_rpm": w / RPM, "message": str(exc)})
            continue
        modes.append(
            {
                "speed_rpm": w / RPM,
                "log_decrement": m.log_decrement,
                "whirl_ratio": m.whirl_ratio,
                "whirl_frequency_Hz": m.whirl_frequency / (2 * math.pi),
            }
        )
    onset = _onset(case, plan)
    stage(f"  stability: {onset['message']}")
    fig = save_figure(
        plot_log_decrement(modes, onset.get("onset_speed_rpm")), out / "log_decrement.png"
    )
    return {"onset": onset, "modes": modes, "figures": [str(fig)]}


def _grid_check(case: Case, plan: StudyPlan, stage: Callable[[str], None]) -> dict[str, Any]:
    """The case point's readouts and the linear onset on the case's grid and on twice its
    cells in θ and Z (:func:`foilbearing.check.grid_check`, as ``foilbearing check CASE``
    gives them); ``rows`` (readout, its value per grid, the text printed) and ``texts``: each
    readout on the case's grid with its error (the difference to the finer grid,
    :func:`~foilbearing.study.converged.with_error`; the onset in krpm)."""
    from foilbearing.check import READOUTS, grid_check
    from foilbearing.study.converged import with_error

    try:
        check = grid_check(case, 2, onset_speeds=plan.onset_scan())
    except (InputError, SolverError) as exc:
        return {"message": f"no grid check: {exc}"}
    head = check.headline()
    rows, texts = [], {}
    for key, label, _ in READOUTS:
        r = head["readouts"].get(key)
        if r is None or r["values"][0] is None or r["error"] is None:
            continue
        scale = 1e-3 if key == "onset_speed_rpm" else 1.0  # printed in krpm
        values = [None if v is None else v * scale for v in r["values"]]
        texts[key] = with_error(r["values"][0] * scale, abs(r["error"]) * scale)
        label = label.replace(", rpm", ", krpm")
        rows.append({"readout": label, "values": values, "text": texts[key]})
    head["rows"], head["texts"] = rows, texts
    onset = texts.get("onset_speed_rpm")
    fine = " × ".join(str(n) for n in head["grids"][1])
    stage(f"  on {fine}: onset {onset or 'none'} krpm ({sum(check.wall_times):.1f} s)")
    return head


def _onset(case: Case, plan: StudyPlan) -> dict[str, Any]:
    from foilbearing.analysis.stability import onset_speed

    try:
        return onset_speed(case, plan.onset_scan()).headline()
    except (InputError, SolverError) as exc:
        return {"onset_speed_rpm": None, "message": f"{exc}; {_TRY}"}


def _shims(case: Case, plan: StudyPlan, out: Path, stage: Callable[[str], None]) -> dict[str, Any]:
    """Linear onset against the shims' thickness (the shimmed bearing's control knob)."""
    from dataclasses import replace

    from foilbearing.io import save_figure
    from foilbearing.output.plots.bearing import plot_onsets

    assert case.shims is not None
    rows = []
    for k in plan.shim_scales:
        thick = tuple(k * t for t in case.shims.thicknesses)
        head = _onset(replace(case, shims=replace(case.shims, thicknesses=thick)), plan)
        rows.append(
            {"scale": k, "x": max(thick) * 1e6, "thickness_um": [t * 1e6 for t in thick]} | head
        )
        stage(f"  shims x{k:g} ({max(thick) * 1e6:.0f} um): {head['message']}")
    fig = save_figure(plot_onsets(rows, "shim thickness (µm)"), out / "onset_vs_shims.png")
    return {"rows": rows, "figures": [str(fig)]}


def _voltages(
    case: Case, plan: StudyPlan, out: Path, stage: Callable[[str], None]
) -> dict[str, Any]:
    """Linear onset against the actuators' voltage (all the same)."""
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bearing import plot_onsets

    rows = []
    for v in plan.voltages:
        head = _onset(case.with_voltages(v), plan)
        rows.append({"voltage_V": v, "x": v} | head)
        stage(f"  {v:g} V: {head['message']}")
    fig = save_figure(plot_onsets(rows, "actuator voltage (V)"), out / "onset_vs_voltage.png")
    return {"rows": rows, "figures": [str(fig)]}


def _actuators(
    case: Case, plan: StudyPlan, out: Path, stage: Callable[[str], None]
) -> dict[str, Any]:
    """Static readouts, preloads and actuator pressures against voltage (all actuators the
    same) at the case speed and load, continued from one voltage to the next."""
    from foilbearing.io import save_figure
    from foilbearing.output.plots.bearing import plot_against, plot_preloads

    w = case.operation.speed
    points: list[dict[str, Any]] = []
    start = None
    for v in plan.voltages:
        st, message = _equilibrium(case.with_voltages(v), w, start=start)
        if st is None:
            points.append(_failed(w, case.operation.load, message) | {"voltage_V": v})
            start = None
            continue
        start = (st.eps_x, st.eps_y, st.P)
        points.append(
            _readouts(st)
            | {
                "voltage_V": v,
                "preload_um": [x * 1e6 for x in st.preload],
                "actuator_pressure_kPa": [x / 1e3 for x in st.actuator_pressure],
            }
        )
    ok = sum(p["converged"] for p in points)
    stage(f"  actuators: {ok}/{len(points)} voltages converged at {w / RPM:.0f} rpm")
    figures = [
        str(save_figure(plot_against(points, "voltage_V"), out / "static_vs_voltage.png")),
        str(save_figure(plot_preloads(points, case), out / "preloads_vs_voltage.png")),
    ]
    return {"speed_rpm": w / RPM, "points": points, "figures": figures}


def _case_point(case: Case, found: dict[float, Any]) -> dict[str, Any]:
    """Static readouts and synchronous K, C at the case speed and load (reference values)."""
    from foilbearing.analysis.coefficients import force_coefficients

    w = case.operation.speed
    st = next((s for speed, s in found.items() if math.isclose(speed, w, rel_tol=1e-9)), None)
    message = ""
    if st is None:
        st, message = _equilibrium(case, w)
    if st is None:
        return {"message": f"no equilibrium at the case speed: {message}; {_TRY}"}
    fc = force_coefficients(st, w)
    K, C = np.asarray(fc.K[0]), np.asarray(fc.C[0])
    point = {
        "eccentricity": st.eccentricity,
        "attitude_angle": st.attitude_angle,
        "min_film": st.min_film,
        "power_loss": st.power_loss,
        "message": f"equilibrium at {w / RPM:.0f} rpm and {case.operation.load:g} N",
    }
    for i, a in enumerate("xy"):
        for j, b in enumerate("xy"):
            point[f"K_{a}{b}"], point[f"C_{a}{b}"] = float(K[i, j]), float(C[i, j])
    return point


def _orbit(
    case: Case,
    plan: StudyPlan,
    out: Path,
    stage: Callable[[str], None],
    onset_whirl_hz: float | None = None,
    theta_refine: int = 1,
) -> dict[str, Any]:
    from foilbearing.control import linear_ramp, voltage_ramp
    from foilbearing.io import write_with
    from foilbearing.orbit import simulate
    from foilbearing.orbit.analysis import analyse_orbit, write_orbit_figures
    from foilbearing.orbit.netcdf import to_netcdf
    from foilbearing.orbit.spec import RunSpec

    lo, hi = plan.speeds[0], plan.speeds[-1]
    profile = linear_ramp(lo, hi, plan.orbit_acceleration)
    last = [0.0]

    def progress(t: float, w: float) -> None:
        if t - last[0] >= 2.0:
            last[0] = t
            stage(f"    orbit: t = {t:5.2f} s, {w / RPM:6.0f} rpm")

    program = None
    if plan.orbit_voltage_ramp is not None and case.actuators is not None:
        t0, t1, volts = plan.orbit_voltage_ramp
        program = voltage_ramp(t0, t1, volts, initial=np.asarray(case.actuators.voltages))
    try:
        result = simulate(case, profile, program, progress=progress)
    except (InputError, SolverError) as exc:  # no equilibrium to start from at the first speed
        message = (
            f"the speed-up could not start at {lo / RPM:.0f} rpm: {exc}; try a higher first "
            "speed in [study] speed_range, or a lower load"
        )
        stage(f"  orbit: {message}")
        return {"status": "failed", "message": message}
    spec = RunSpec.of(
        profile,
        program,
        case=case.source,
        settings=result.settings,
    )
    path = out / "orbit_speedup.nc"
    write_with(path, lambda tmp: to_netcdf(result, spec, tmp))
    analysis = analyse_orbit(result)
    head = analysis.headline(result) | {"netcdf": str(path)}
    figures = write_orbit_figures(result, analysis, out, "speedup", onset_whirl_hz=onset_whirl_hz)
    stage(f"  orbit: {result.message} ({result.wall_time:.0f} s)")
    if theta_refine > 1:
        from dataclasses import replace

        from foilbearing.study.orbits import readout_errors, refined_stop

        n_theta = case.grid.orbit_shape[0] * theta_refine
        finer = replace(case, grid=replace(case.grid, orbit_n_theta=n_theta))
        stop = refined_stop(analysis.divergence, None)
        try:
            fine = simulate(finer, profile, program, stop_time=stop)
        except (InputError, SolverError) as exc:  # the readouts stay, without their error
            stage(f"  orbit on {n_theta} θ cells: could not run ({exc}); no grid error")
            return head | {"figures": [str(p) for p in figures]}
        fine_path = out / f"orbit_speedup_theta{theta_refine}x.nc"
        fine_spec = RunSpec.of(profile, program, case=finer.source, settings=fine.settings)
        write_with(fine_path, lambda tmp: to_netcdf(fine, fine_spec, tmp))
        head["theta_refined"] = readout_errors(
            head, analyse_orbit(fine).headline(fine), theta_refine
        )
        stage(f"  orbit on {n_theta} θ cells: {head['theta_refined']['text'] or fine.message}")
    return head | {"figures": [str(p) for p in figures]}


def reference_rows(plan: StudyPlan, results: dict[str, Any]) -> list[dict[str, Any]]:
    """The case's declared reference values beside ours, with how ours was read."""
    onset = (results.get("bearing_stability") or {}).get("onset") or {}
    orbit = results.get("bearing_orbit") or {}
    point = results.get("case_point") or {}
    unstable_at_once = "already" in str(onset.get("message", ""))
    ours: dict[str, tuple[Any, dict[str, Any]]] = {
        "onset_speed": (None if unstable_at_once else onset.get("onset_speed_rpm"), onset),
        "whirl_frequency": (onset.get("whirl_frequency_Hz"), onset),
        "divergence_speed": (orbit.get("divergence_speed_rpm"), orbit),
    }
    for key in CASE_POINT_KEYS:
        value = point.get(key)
        ours[key] = (None if value is None else shown_reference(key, value)[0], point)
    rows = []
    for key, value in plan.reference.items():
        what = REFERENCE_KEYS[key][1]
        ref, unit = shown_reference(key, value)
        mine, source = ours[key]
        rows.append(
            {
                "quantity": f"{what} ({unit})",
                "reference": ref,
                "ours": mine,
                "deviation_percent": (
                    None if mine is None or ref == 0.0 else 100.0 * (mine - ref) / abs(ref)
                ),
                "note": str(source.get("message", "not computed (orbit off?)")),
            }
        )
    return rows


def bearing_study(
    case: Case,
    plan: StudyPlan,
    out: Path,
    stage: Callable[[str], None],
    *,
    orbits: bool = True,
    theta_refine: int = 1,
) -> dict[str, Any]:
    """Run the plan's stages on ``case`` (see the module docstring); returns their summaries.

    ``theta_refine`` > 1: the speed-up again with that many times the θ cells, its onset,
    whip and divergence with their grid error (:func:`foilbearing.study.orbits.readout_errors`),
    and the grid check of the case point and the onset (:func:`_grid_check`); 1: neither.
    """
    # The plan as it ran: the speed-up only where --orbits let it
    ran = plan.describe() | {"orbit": bool(orbits and plan.orbit)}
    if not ran["orbit"]:
        del ran["orbit_acceleration_rad_per_s2"]
    results: dict[str, Any] = {"plan": ran}
    stage(f"static: {len(plan.speeds)} speeds at {case.operation.load:g} N, and film maps")
    results["bearing_static"], found = _static(case, plan, out, stage)
    stage(f"load capacity at {case.operation.speed / RPM:.0f} rpm")
    results["load_capacity"] = _load_capacity(case, plan, out, stage)
    if found:
        stage("dynamic coefficients: synchronous against speed, and against frequency")
        results["bearing_coefficients"] = _coefficients(case, plan, found, out, stage)
        stage("linear stability: onset speed, log decrement against speed")
        results["bearing_stability"] = _stability(case, plan, found, out, stage)
        if theta_refine > 1:
            stage("grid check: the case point and the onset on twice the cells")
            results["grid_check"] = check = _grid_check(case, plan, stage)
            onset = results["bearing_stability"]["onset"]
            for key in ("onset_speed_rpm", "whirl_frequency_Hz"):  # the report's onset line
                if key in check.get("texts", {}):
                    onset.setdefault("with_grid_error", {})[key] = check["texts"][key]
    if plan.shim_scales:
        stage("linear stability against the shims' thickness")
        results["shim_stability"] = _shims(case, plan, out, stage)
    if plan.voltages:
        stage("linear stability against the actuators' voltage")
        results["voltage_stability"] = _voltages(case, plan, out, stage)
    if plan.voltages:
        stage(f"actuators: static readouts against voltage at {case.operation.speed / RPM:.0f} rpm")
        results["actuator_static"] = _actuators(case, plan, out, stage)
    if orbits and plan.orbit:
        ramp = plan.orbit_voltage_ramp
        stage(
            f"orbit: speed-up {plan.speeds[0] / RPM:.0f}-{plan.speeds[-1] / RPM:.0f} rpm at "
            f"{plan.orbit_acceleration:g} rad/s², imbalance {case.rotor.imbalance * 1e6:g} g·mm"
            + ("" if ramp is None else f", voltages to {ramp[2]:g} V at {ramp[0]:g}-{ramp[1]:g} s")
        )
        onset = (results.get("bearing_stability") or {}).get("onset") or {}
        results["bearing_orbit"] = _orbit(
            case, plan, out, stage, onset.get("whirl_frequency_Hz"), theta_refine
        )
    if any(k in CASE_POINT_KEYS for k in plan.reference):
        results["case_point"] = _case_point(case, found)
    if plan.reference:
        results["reference_comparison"] = {"rows": reference_rows(plan, results)}
    return results
