"""One function per section of the report: a part of ``summary.json`` to HTML."""

from __future__ import annotations

import re
from collections.abc import Callable
from html import escape
from pathlib import Path
from typing import Any

from foilbearing.output.report.tables import (
    Column,
    _entry,
    _f,
    _key,
    _krpm,
    _nearest,
    _records,
    _table,
    _transpose,
)

__all__ = ["STAGES"]


#: Stage keys of summary.json in the paper's order, with section titles.
STAGES: tuple[tuple[str, str], ...] = (
    ("plan", "The study's plan"),
    ("reference_comparison", "Our numbers beside the case's reference values"),
    ("bearing_static", "Static performance against speed"),
    ("load_capacity", "Load capacity"),
    ("bearing_coefficients", "Dynamic force coefficients"),
    ("bearing_stability", "Linear stability"),
    ("shim_stability", "Linear stability against the shims' thickness"),
    ("voltage_stability", "Linear stability against the actuators' voltage"),
    ("actuator_static", "Static performance against the actuators' voltage"),
    ("bearing_orbit", "Speed-up orbit"),
    ("identification", "Identification of the PZT stacks (Figs. 5-6)"),
    ("structure", "Foil structure and base preloads (Figs. 7-8)"),
    ("static", "Static performance, C-GFB and shimmed GFB (Figs. 9-12)"),
    ("coefficients", "Dynamic force coefficients"),
    ("stability", "Linear stability"),
    ("actuator_design", "What the stack's stiffness buys (the paper's conclusion)"),
    ("bifurcation", "Is the whirl past the onset bounded? Limit cycles (beyond the paper)"),
    ("orbits", "Speed-up orbits (Figs. 13-15)"),
    (
        "orbits_paper_reading",
        "Speed-up orbits under the paper's reading of the actuator: lobe + held (Figs. 13-15)",
    ),
    ("uncertainty", "What the unknowns allow: uncertainty envelopes (beyond the paper)"),
    ("schedule", "A voltage schedule for the controller (beyond the paper)"),
    ("rotor", "A rotor on two foil bearings (beyond the paper)"),
)


_FIG14 = {50.0: "a", 100.0: "b", 150.0: "c"}


def _intro(summary: dict[str, Any], case: dict[str, Any]) -> str:
    ran = [t.split(" (")[0] for k, t in STAGES if isinstance(summary.get(k), dict)]
    if isinstance(summary.get("rotor"), dict):
        return (
            "<p>What <code>foilbearing study</code> computed for the rotor "
            f"<b>{escape(str(case.get('title', '?')))}</b> on its foil bearings "
            "(docs/rotor-format.md): the weight each bearing carries, the modes and the onset "
            "with each mode's coefficients at its own whirl frequency (ROSS, matched whirl), "
            "the reduced rotor's convergence, and a nonlinear speed-up through the onset.</p>"
        )
    grid = case.get("grid") or {}
    kind = f" ({case['bearing_type']})" if case.get("bearing_type") else ""
    if isinstance(summary.get("plan"), dict):
        text = (
            "<p>What <code>foilbearing study</code> computed for the case "
            f"<b>{escape(str(case.get('title', '?')))}</b>{escape(kind)}: every analysis that "
            f"applies to this kind of bearing, on the plan below. Stages: "
            f"{escape('; '.join(ran[1:]) or 'none')}. Reynolds grid "
            f"{_grid_text(grid)}. "
            "The paper's numbers belong to the paper's bearing and are not shown here; a "
            "<code>[study.reference]</code> table in the case file puts measured values beside "
            "ours.</p>"
        )
        return text + _records([case], [c for c in _CASE_COLUMNS if c[1](case) is not None])
    text = (
        "<p>What <code>foilbearing study</code> computed for the case "
        f"<b>{escape(str(case.get('title', '?')))}</b>{escape(kind)}, reproducing Park, Kim and "
        "Sim (2021), <i>Rotordynamic Analysis of Piezoelectric Gas Foil Bearings with a "
        "Mechanical Preload Control Based on Structural Parameter Identifications</i>. Stages, "
        f"in the paper's order: {escape('; '.join(ran) or 'none')}. The comparison with the "
        "paper's numbers comes first; each stage then shows its headline numbers and figures.</p>"
        "<p>Assumed, since the paper does not give them: gas viscosity μ = "
        f"{_f(case.get('viscosity_Pa_s'), '.3g')} Pa·s, rotor mass "
        f"{_f(case.get('rotor_mass_kg'), '.3g')} kg, imbalance "
        f"{_f(case.get('imbalance_g_mm'), '.3g')} g·mm. Reynolds grid "
        f"{_grid_text(grid)}.</p>"
    )
    return text + _records([case], [c for c in _CASE_COLUMNS if c[1](case) is not None])


def _grid_text(grid: dict[str, Any]) -> str:
    """'96 × 12 (θ × half length)', and the orbits' own grid where they have one."""
    text = f"{_f(grid.get('n_theta'), 'd')} × {_f(grid.get('n_z'), 'd')} (θ × half length)"
    order = grid.get("axial_order", 2)
    if order != 2:
        text += f", axial order {order}"
    orbit = (grid.get("orbit_n_theta"), grid.get("orbit_n_z"), grid.get("orbit_axial_order", order))
    if None not in orbit[:2] and orbit != (grid.get("n_theta"), grid.get("n_z"), order):
        text += f"; the orbits run on {_f(orbit[0], 'd')} × {_f(orbit[1], 'd')}"
        if orbit[2] != 2:
            text += f", axial order {orbit[2]}"
    kappa = grid.get("lift_off_smoothing", 0.0)
    if kappa:
        text += f"; lift-off edge smoothed, κ = {kappa:g} (δ = κΔθ²)"
    return text


_CASE_COLUMNS: list[Column] = [
    ("radius (mm)", lambda r: r.get("radius_mm"), ".4g"),
    ("length (mm)", lambda r: r.get("length_mm"), ".4g"),
    ("clearance (µm)", lambda r: r.get("clearance_um"), ".4g"),
    ("load (N)", lambda r: r.get("load_N"), ".4g"),
    ("speed (rpm)", lambda r: r.get("speed_rpm"), ".6g"),
    ("rotor mass (kg)", lambda r: r.get("rotor_mass_kg"), ".3g"),
    ("k_b (N/m³)", lambda r: r.get("k_b_N_per_m3"), ".4g"),
    ("loss factor", lambda r: r.get("loss_factor"), ".3g"),
    ("actuators at (°)", lambda r: r.get("actuator_angles_deg"), ".0f"),
    ("stinger arc (°)", lambda r: r.get("stinger_arc_deg"), ".3g"),
    ("k_p (N/m³)", lambda r: r.get("k_p_N_per_m3"), ".4g"),
    ("k_sp (N/m³)", lambda r: r.get("k_sp_N_per_m3"), ".4g"),
    ("shims at (°)", lambda r: r.get("shim_angles_deg"), ".0f"),
    ("shim thickness (µm)", lambda r: r.get("shim_thickness_um"), ".3g"),
]


def _comparison(rows: list[dict[str, Any]]) -> str:
    heads = ["quantity", "paper", "ours", "deviation", "why they differ"]
    cells = [[str(r.get(k, "")) for k in ("quantity", "paper", "ours", "deviation", "note")]
             for r in rows]  # fmt: skip
    flags = [_flagged(c[2], c[3]) for c in cells]
    return (
        '<p class="note">Shaded: a deviation above 5 %, or a statement of the paper that we do '
        "not reproduce (NO).</p>" + _table(heads, cells, num=(3,), flags=flags)
    )


def _flagged(ours: str, deviation: str) -> bool:
    m = re.match(r"\s*([+-]?[0-9.]+)\s*%", deviation)
    return bool(m and abs(float(m.group(1))) > 5.0) or bool(re.search(r"\bNO\b", ours))


def _identification(d: dict[str, Any], case: dict[str, Any]) -> str:
    def pm(key: str, se: str, spec: str) -> Callable[[dict[str, Any]], str]:
        return lambda r: f"{_f(r.get(key), spec)} ± {_f(r.get(se), '.2g')}"

    fit: list[Column] = [
        ("D33,1 (µm/V²)", pm("d33_1_um_per_V2", "d33_1_se_um_per_V2", ".4g"), ""),
        ("D33,2 (µm/V)", pm("d33_2_um_per_V", "d33_2_se_um_per_V", ".4g"), ""),
        ("R²", _key("r_squared"), ".4f"),
        ("linear D33 (µm/V)", _key("d33_linear_um_per_V"), ".4g"),
        ("R², linear", _key("d33_linear_r_squared"), ".3f"),
        (
            "stack stiffness (N/m)",
            pm("stack_stiffness_N_per_m", "stack_stiffness_se_N_per_m", ".4g"),
            "",
        ),
        ("k_p (N/m³)", _key("k_p_N_per_m3"), ".4g"),
    ]
    stacks = [{"stack": f"#{k}", **v} for k, v in (d.get("per_stack") or {}).items()]
    per: list[Column] = [
        ("stack", _key("stack"), ""),
        ("D33,1 (µm/V²)", _key("d33_1_um_per_V2"), ".4g"),
        ("D33,2 (µm/V)", _key("d33_2_um_per_V"), ".4g"),
        ("R²", _key("r_squared"), ".4f"),
        ("stroke at 150 V (µm)", _key("stroke_150V_um"), ".2f"),
        ("stiffness (N/m)", _key("stack_stiffness_N_per_m"), ".4g"),
    ]
    return _records([d], fit) + _records(stacks, per)


def _structure(d: dict[str, Any], case: dict[str, Any]) -> str:
    springs: list[Column] = [
        ("k_b (N/m³)", _key("k_b_N_per_m3"), ".4g"),
        ("k_p (N/m³)", _key("k_p_N_per_m3"), ".4g"),
        ("k_assy (N/m³)", _key("k_assy_N_per_m3"), ".4g"),
    ]
    keys = ("voltages_V", "stack_stroke_um", "base_preload_um")
    volts = _transpose(d, keys)
    cols: list[Column] = [
        ("driving voltage (V)", _key("voltages_V"), "g"),
        ("stack stroke (µm)", _key("stack_stroke_um"), ".2f"),
        ("base preload (µm)", _key("base_preload_um"), ".2f"),
    ]
    return _records([d], springs) + _records(volts, cols)


def _static(d: dict[str, Any], case: dict[str, Any]) -> str:
    points = [p for p in d.get("points", []) if isinstance(p, dict) and "speed_rpm" in p]
    if not points:
        return ""
    speeds = sorted({float(p["speed_rpm"]) for p in points})
    shown = sorted({_nearest(speeds, t) for t in (10e3, 50e3, 90e3)})
    at = "/".join(_f(a, ".0f") for a in case.get("actuator_angles_deg", [])) or "actuators"
    cols: list[Column] = [
        ("bearing", _key("bearing"), ""),
        ("voltage (V)", _key("voltage_V"), "g"),
        ("speed (krpm)", lambda p: p["speed_rpm"] / 1e3, ".0f"),
        ("eccentricity ε", _key("eccentricity"), ".3f"),
        ("attitude (°)", _key("attitude_deg"), ".1f"),
        ("min film (µm)", _key("min_film_um"), ".1f"),
        (f"preload at {at}° (µm)", _key("preload_um"), ".1f"),
        (f"film pressure at {at}° (kPa)", _key("actuator_pressure_kPa"), ".1f"),
        ("converged", _key("converged"), ""),
    ]
    n_ok = sum(bool(p.get("converged")) for p in points)
    note = (
        f'<p class="note">{len(points)} equilibria ({n_ok} converged), shown here at '
        f"{', '.join(_f(s / 1e3, '.0f') for s in shown)} krpm; all of them are in "
        "<code>static_sweep.nc</code> beside this page.</p>"
    )
    return note + _records([p for p in points if float(p["speed_rpm"]) in shown], cols)


def _coefficients(d: dict[str, Any], case: dict[str, Any]) -> str:
    note = (
        f'<p class="note">Equilibrium at {_f(d.get("speed_rpm"), ".6g")} rpm: ε = '
        f"{_f(d.get('eccentricity'), '.3f')}, attitude {_f(d.get('attitude_deg'), '.1f')}°.</p>"
    )
    keys = ("frequency_Hz", "frequency_ratio", "K_N_per_m", "C_Ns_per_m")
    rows = _transpose(d, keys)
    cols: list[Column] = [
        ("frequency (Hz)", _key("frequency_Hz"), ".1f"),
        ("ratio to speed", _key("frequency_ratio"), ".2f"),
    ]
    for i, ij in enumerate(("xx", "xy", "yx", "yy")):
        cols.append((f"K{ij} (MN/m)", _entry("K_N_per_m", i, 1e-6), ".4f"))
    for i, ij in enumerate(("xx", "xy", "yx", "yy")):
        cols.append((f"C{ij} (N·s/m)", _entry("C_Ns_per_m", i), ".1f"))
    return note + _records(rows, cols)


def _stability(d: dict[str, Any], case: dict[str, Any]) -> str:
    others = {
        key: {e.get("voltage_V"): e for e in d.get(kind, [])}
        for key, kind in (
            ("shim", "shimmed"),
            ("kept", "C-GFB, suction retained"),
            ("shim_kept", "shimmed, suction retained"),
            ("paper_reading", "C-GFB, lobe+held"),
            ("orbit_grid", "C-GFB, orbit grid"),
        )
    }
    rows = [
        e | {key: per.get(e.get("voltage_V"), {}) for key, per in others.items()}
        for e in d.get("C-GFB", [])
    ]

    def onset_of(key: str) -> Any:
        return lambda r: _krpm("onset_speed_rpm")(r[key])

    cols: list[Column] = [
        ("voltage (V)", _key("voltage_V"), "g"),
        ("C-GFB onset (krpm)", _krpm("onset_speed_rpm"), ".1f"),
        ("whirl frequency (Hz)", _key("whirl_frequency_Hz"), ".0f"),
        ("whirl ratio", _key("whirl_ratio"), ".2f"),
        ("shimmed onset (krpm)", onset_of("shim"), ".1f"),
        ("shimmed whirl (Hz)", lambda r: r["shim"].get("whirl_frequency_Hz"), ".0f"),
    ]
    if others["orbit_grid"]:
        cols.append(("C-GFB on the orbits' grid (krpm)", onset_of("orbit_grid"), ".1f"))
    if others["paper_reading"]:
        cols += [
            ("C-GFB, paper's reading: lobe + held (krpm)", onset_of("paper_reading"), ".1f"),
            (
                "its whirl (Hz)",
                lambda r: r["paper_reading"].get("whirl_frequency_Hz"),
                ".0f",
            ),
        ]
    if others["kept"]:
        cols += [
            ("C-GFB, suction retained (krpm)", onset_of("kept"), ".1f"),
            ("shimmed, suction retained (krpm)", onset_of("shim_kept"), ".1f"),
        ]
    note = (
        '<p class="note">Linear onset of instability (rigid rotor, voltage held from the '
        "start); the paper's Figs. 13-15 are nonlinear speed-ups, compared in the orbit "
        "section."
        + (
            " The film under the foil holds no sub-ambient pressure (top-foil lift-off, "
            "docs/model.md §3); the suction-retained columns keep it, as a rigid surface "
            "would, and go unstable 2-3.5 times earlier."
            if others["kept"]
            else ""
        )
        + (
            " The C-GFB columns read the actuator as the case does (local + compliant: the "
            "stack's compression a pocket under the stinger, its compliance acting at the "
            "whirl); the paper's reading lowers the whole lobe and holds the stinger during "
            "the motion (docs/model.md §3.8)."
            if others["paper_reading"]
            else ""
        )
        + "</p>"
    )
    return note + _records(rows, cols)


def _actuator_design(d: dict[str, Any], case: dict[str, Any]) -> str:
    cols: list[Column] = [
        ("bearing at the voltage", _key("bearing"), ""),
        ("stack stiffness K_p (MN/m)", _scaled("stack_stiffness_N_per_m", 1e-6), ".3g"),
        ("linear onset (krpm)", _krpm("onset_speed_rpm"), ".1f"),
        ("whirl (Hz)", _key("whirl_frequency_Hz"), ".0f"),
    ]
    need = d.get("required_stack_stiffness_N_per_m") or {}
    target = d.get("target_fraction_of_shimmed_onset", 0.9)
    items = "".join(
        f"<li>{escape(k)}: "
        + ("not reached in the scan" if v is None else f"K_p = {v / 1e6:.3g} MN/m")
        + "</li>"
        for k, v in need.items()
    )
    note = (
        f'<p class="note">At {d.get("voltage_V", 150):g} V: the linear onset under the '
        "case's reading of the actuator (local + compliant) and the paper's (lobe + held), "
        "beside the shimmed GFB, rigid shims at the base preloads: an ideal positioner "
        "(docs/model.md §3.8). The stack stiffness each reading needs for "
        f"{target:.0%} of the shimmed onset:</p><ul>{items}</ul>"
    )
    return note + _records(d.get("table", []), cols)


def _bifurcation(d: dict[str, Any], case: dict[str, Any]) -> str:
    cols: list[Column] = [
        ("reading of the actuator", _key("reading"), ""),
        ("voltage (V)", _key("voltage_V"), "g"),
        ("Hopf bifurcation", _key("bifurcation_type"), ""),
        ("linear onset (krpm)", _krpm("hopf_speed_rpm"), ".1f"),
        ("whirl (Hz)", _key("linear_whirl_frequency_Hz"), ".0f"),
        ("speed limit (krpm)", _krpm("speed_limit_rpm"), ".1f"),
        ("largest stable cycle (µm)", _key("largest_stable_cycle_um"), ".1f"),
        ("cycles", _key("cycles"), "d"),
        ("status", _key("status"), ""),
    ]
    grid = d.get("grid") or ["?", "?"]
    label = d.get("grid_label") or f"{grid[0]} × {grid[1]}"
    files = ", ".join(f"<code>{escape(Path(f).name)}</code>" for f in d.get("sweep_files", []))
    note = (
        '<p class="note">Past a <b>supercritical</b> Hopf bifurcation the whirl grows into a '
        "stable, bounded limit cycle as the speed passes the linear onset; past a "
        "<b>subcritical</b> one the small cycles are unstable and lie below the onset, so a "
        "large enough disturbance throws the journal into a growing whirl before it "
        "(docs/bifurcation.md). Each branch is continued from the linear onset by shooting "
        "on the orbit's own stepper, its stability from Floquet multipliers of the exact "
        "monodromy. Speed limit: the lowest fold of a subcritical branch, the first fold "
        "of a supercritical one (past it no bounded cycle is left), or contact. "
        f"Grid {escape(label)} (the speed-ups'), {d.get('steps', 0) + 2} cycles a "
        "branch for this stage's time. Under the sharp lift-off law the type near the "
        "onset is sensitive to the grid (the lift-off boundary moves cell by cell; "
        "docs/bifurcation.md measures it from 32 × 4 to 128 × 16); with the edge smoothed "
        "at κ = 0.2 they did not change between 96 × 4 and 96 × 12, and a branch that bends "
        "back by a few hundredths of a percent of the speed is flat to the grid's resolution. "
        f"Each reading is a Dask sweep: rerun or extend {files} with "
        "<code>foilbearing sweep FILE --out RESULT</code>.</p>"
    )
    return note + _records(d.get("rows", []), cols)


def _scaled(name: str, factor: float) -> Callable[[dict[str, Any]], Any]:
    return lambda r: None if r.get(name) is None else float(r[name]) * factor


def _orbits(d: dict[str, Any], case: dict[str, Any]) -> str:
    def intervals(r: dict[str, Any]) -> str:
        ivs = r.get("subsync_intervals_rpm_Hz") or []
        return "; ".join(f"{a / 1e3:.1f}-{b / 1e3:.1f} krpm at {f:.0f} Hz" for a, b, f in ivs)

    def run(r: dict[str, Any]) -> str | None:
        described = r.get("description")
        volts = r.get("voltage_V")
        return str(described) if described else None if volts is None else f"{volts:g} V"

    cols: list[Column] = [
        ("run", run, ""),
        ("sub-sync onset (krpm)", _krpm("onset_speed_rpm"), ".1f"),
        ("whip (Hz)", _key("whip_frequency_Hz"), ".0f"),
        ("sub-synchronous intervals", lambda r: intervals(r) or None, ""),
        ("divergence (krpm)", _krpm("divergence_speed_rpm"), ".1f"),
        ("max sub-sync amplitude (µm)", _key("max_subsync_amplitude_um"), ".1f"),
        ("end speed (krpm)", _krpm("end_speed_rpm"), ".1f"),
        ("wall time (s)", _key("wall_time_s"), ".0f"),
        ("solver", _key("message"), ""),
    ]
    force = case.get("disturbance_N_rms") or 0.0
    band = case.get("disturbance_band_Hz") or [0.0, 0.0]
    seed = (
        f"A divergence above the linear onset comes from a whirl that grows from the case's "
        f"random disturbance ({force * 1e3:.3g} mN RMS per direction, {band[0]:g}-{band[1]:g} "
        "Hz): its speed is a property of the bearing and that disturbance, within 0.1 % of "
        "the solver's settings (a contact forced by the imbalance response, about 1 %); "
        "without one it would depend on the numerical seed, by several per cent"
        if force > 0
        else "A divergence above the linear onset comes from a whirl that grows out of the "
        "noise floor: the case has no [disturbance], so its speed depends on the numerical "
        "seed, by up to several per cent"
    )
    reading = d.get("reading") or case.get("actuator_reading")
    named = (
        f" The actuator in the film is read as <b>{escape(str(reading))}</b> "
        "(docs/model.md §3.8)"
        + (
            ": the paper's reading, with 1 g·mm, since 8.5 g·mm drives this model to contact "
            "through its low-speed critical."
            if d.get("reading")
            else "."
        )
        if reading
        else ""
    )
    note = (
        '<p class="note">Speed-up from 3 to 90 krpm at 500 rad/s²; each run says its voltage '
        "program and imbalance (the paper's ramps go up from 0 between 6.0 and 6.5 s, about "
        f"32.6 krpm).{named} {seed} (docs/orbit-performance.md in the repository); the "
        "linear onsets do not depend on it.</p>"
    )
    return note + _records([r for r in d.get("runs", []) if isinstance(r, dict)], cols)


def _generic(d: dict[str, Any], case: dict[str, Any]) -> str:
    rows = [[k, _f(v, ".4g")] for k, v in d.items() if isinstance(v, int | float | str)]
    return _table(["quantity", "value"], rows, num=(1,)) if rows else ""


def _uncertainty(d: dict[str, Any], case: dict[str, Any]) -> str:
    inputs = d.get("inputs") or {}
    idx = d.get("indices") or {}
    described = idx.get("description") or f"{d.get('estimator')} estimator"
    intro = (
        f'<p class="note">{d.get("n_ok", "?")} of {d.get("n_points", "?")} evaluations ok, '
        f"on a {escape(str(d.get('sampler')))} sample. Inputs: "
        + escape("; ".join(f"{k} {v.get('distribution', '')}" for k, v in inputs.items()))
        + ". Static readouts hold the case's load; onset speeds and whirl frequencies are "
        "linear (rigid rotor), and orbit_* readouts, where asked for, come from speed-ups.</p>"
        f'<p class="note">Sensitivity indices: {escape(str(described))}. Every index shown '
        "lies in [0, 1]: an estimate outside it whose 95 % half-width reaches back into "
        "[0, 1] is clipped to the nearer end and marked so, one whose interval lies wholly "
        "outside is shown as not estimable at this sample size (the raw numbers are in the "
        "results' JSON). The half-widths shrink as 1/√N: rerun with "
        f"<code>{escape(str(d.get('command', 'foilbearing uncertainty')))}</code> and a larger "
        "<code>--samples</code>, or <code>foilbearing study --uncertainty full</code> "
        "(252 evaluations, first-order and total indices), for sharper ones.</p>"
    )
    rows = []
    for name, o in (d.get("outputs") or {}).items():
        kind = "total_order" if o.get("total_order") else "first_order"
        values = o.get(kind) or {}
        ranked = {k: v for k, v in values.items() if v is not None}
        top = max(ranked, key=lambda k: ranked[k]) if ranked else None
        if top is None:
            cell = "not estimable" if values else "—"
        else:
            conf = (o.get(f"{kind}_conf") or {}).get(top)
            mark = (o.get(f"{kind}_status") or {}).get(top)
            cell = f"{top}: {_f(ranked[top], '.2f')} ± {_f(conf, '.2f')}" + (
                " (clipped)" if mark == "clipped" else ""
            )
            cell += "" if kind == "first_order" else " (total)"
        rows.append(
            [name, _f(o.get("p5"), ".4g"), _f(o.get("p50"), ".4g"), _f(o.get("p95"), ".4g"), cell]
        )
    heads = ["output (unit in the name)", "p5", "p50", "p95", "largest index ± 95 %"]
    return intro + _table(heads, rows, num=(1, 2, 3))


def _schedule(d: dict[str, Any], case: dict[str, Any]) -> str:
    sched = d.get("schedule") or {}
    limit = sched.get("limit_speed_rpm")
    speeds = sched.get("speeds_rpm") or []
    top = f"{speeds[-1] / 1e3:.0f} krpm" if speeds else "the top speed"
    note = (
        f'<p class="note">At each speed the voltages of least power loss with a log decrement '
        f"of the least stable whirl mode of at least {_f(sched.get('margin'), 'g')} (linear "
        "analysis), smoothed for an amplifier slew rate of "
        f"{_f(sched.get('slew_rate_V_per_s'), 'g')} V/s during a speed-up at "
        f"{_f(sched.get('acceleration_rad_per_s2'), 'g')} rad/s². "
        + (
            f"No voltage keeps the rotor stable above {limit / 1e3:.1f} krpm."
            if limit is not None
            else f"The schedule keeps the margin up to {top}."
        )
        + f" File: <code>{escape(Path(str(d.get('schedule_file', 'schedule.toml'))).name)}</code> "
        "(<code>foilbearing orbit --voltage-schedule</code> runs it).</p>"
    )
    rows = []
    for k, w in enumerate(speeds):

        def at(key: str, k: int = k) -> Any:
            values = sched.get(key) or []
            return values[k] if k < len(values) else None

        rows.append(
            [
                _f(w / 1e3, ".0f"),
                _f(at("voltages_V"), ".1f"),
                _f(at("log_decrement"), ".3f"),
                _f(at("whirl_frequency_Hz"), ".0f"),
                _f(at("power_loss_W"), ".2f"),
                _f(at("power_loss_150V_W"), ".2f"),
            ]
        )
    heads = ["speed (krpm)", "voltages (V)", "log dec", "whirl (Hz)", "power (W)", "at 150 V (W)"]
    body = note + _table(heads, rows, num=(0, 2, 3, 4, 5))
    ver = d.get("verification")
    if isinstance(ver, dict):
        common = (ver.get("common_range_rpm") or [None, None])[1]
        body += (
            f'<p class="note">The paper\'s speed-up ({escape(str(ver.get("speed_up")))}) with '
            f"{_f(ver.get('imbalance_g_mm'), 'g')} g·mm imbalance on four voltage programs. "
            "Onset: sustained sub-synchronous motion (nonlinear, read from the run; not the "
            "linear onset). Mean power: over each run, and over the speeds all four reach "
            f"(3 to {_f(None if common is None else common / 1e3, '.1f')} krpm).</p>"
        )
        cols: list[Column] = [
            ("run", _key("run"), ""),
            ("sub-sync onset (krpm)", _krpm("onset_speed_rpm"), ".1f"),
            ("whip (Hz)", _key("whip_frequency_Hz"), ".0f"),
            ("divergence (krpm)", _krpm("divergence_speed_rpm"), ".1f"),
            ("end speed (krpm)", _krpm("end_speed_rpm"), ".1f"),
            ("mean power, run (W)", _key("mean_power_loss_W"), ".2f"),
            ("mean power, common speeds (W)", _key("mean_power_loss_common_W"), ".2f"),
        ]
        body += _records([r for r in ver.get("runs", []) if isinstance(r, dict)], cols)
    return body


def _rotor(d: dict[str, Any], case: dict[str, Any]) -> str:
    bearings = [b for b in d.get("bearings", []) if isinstance(b, dict)]
    cols: list[Column] = [
        ("bearing", _key("label"), ""),
        ("node", _key("node"), "d"),
        ("load (N)", _key("load_N"), ".2f"),
        ("voltages (V)", lambda r: ", ".join(f"{v:g}" for v in r.get("voltages_V", [])), ""),
    ]
    body = _records(bearings, cols)
    onset = d.get("onset_speed_rpm")
    speeds = d.get("speeds_rpm") or []
    span = f"{speeds[0] / 1e3:.0f}-{speeds[-1] / 1e3:.0f} krpm" if speeds else "its speeds"
    body += (
        f'<p class="note">Rotor {_f(d.get("mass_kg"), ".3f")} kg. Linear analysis over {span} '
        "(ROSS, each mode's coefficients at its own whirl frequency): "
        + (
            f"onset {_f(onset, ',.0f')} rpm, whirl {_f(d.get('whirl_frequency_Hz'), '.1f')} Hz."
            if onset is not None
            else "stable over them."
        )
        + "</p>"
    )
    resp = d.get("unbalance_response")
    if isinstance(resp, dict):
        body += (
            f'<p class="note">Synchronous response to {_f(resp.get("unbalance_g_mm"), "g")} g·mm '
            f"at node {resp.get('unbalance_node')} (linear, each bearing's coefficients at "
            f"frequency = speed): largest {_f(resp.get('peak_amplitude_um'), '.2f')} µm at "
            f"{escape(str(resp.get('peak_at')))}, {_f(resp.get('peak_speed_rpm'), ',.0f')} rpm."
            "</p>"
        )
    red = [r for r in d.get("reduction", []) if isinstance(r, dict)]
    if red:
        body += (
            '<p class="note">The rotor reduced to its journals and N shaft modes (the '
            "nonlinear run's rotor), its onset against the full beam model's:</p>"
        )
        body += _records(red, [
            ("shaft modes N", _key("shaft_modes"), "d"),
            ("onset (rpm)", _key("onset_speed_rpm"), ",.0f"),
            ("error (%)", _key("error_percent"), "+.3f"),
        ])  # fmt: skip
    orb = d.get("orbit")
    if isinstance(orb, dict):
        body += (
            f'<p class="note">Nonlinear speed-up {escape(str(orb.get("speed_up")))}, '
            f"{_f(orb.get('unbalance_g_mm'), 'g')} g·mm at node {orb.get('unbalance_node')}, "
            f"{orb.get('shaft_modes')} shaft modes: {escape(str(orb.get('message')))}. "
            f"The run ends at {_f(orb.get('end_speed_rpm'), ',.0f')} rpm. Sustained "
            "sub-synchronous motion read from bearing A's X (a ramped run, not the linear "
            f"onset; none when the whirl lasts under half a second before contact or the end of "
            "the run): "
            f"{_f(orb.get('onset_speed_rpm'), ',.0f')} rpm, whirl "
            f"{_f(orb.get('whirl_frequency_Hz'), '.0f')} Hz.</p>"
        )
    return body


def _plan(d: dict[str, Any], case: dict[str, Any]) -> str:
    rows = [[k, _f(v, ".6g") if not isinstance(v, dict) else escape(str(v) or "none")]
            for k, v in d.items()]  # fmt: skip
    note = (
        '<p class="note">Derived from the case; a <code>[study]</code> table in the case file '
        "sets any of it (docs/case-format.md).</p>"
    )
    return note + _table(["plan", "value"], rows)


def _point_columns() -> list[Column]:
    return [
        ("eccentricity", _key("eccentricity"), ".4f"),
        ("attitude (°)", _key("attitude_deg"), ".1f"),
        ("min film (µm)", _key("min_film_um"), ".2f"),
        (
            "drag (mN·m)",
            lambda r: None if r.get("drag_torque_Nm") is None else r["drag_torque_Nm"] * 1e3,
            ".4f",
        ),
        ("power loss (W)", _key("power_loss_W"), ".3f"),
        ("converged", _key("converged"), ""),
        ("what to try", _key("message"), ""),
    ]


def _bearing_static(d: dict[str, Any], case: dict[str, Any]) -> str:
    cols: list[Column] = [("speed (krpm)", _krpm("speed_rpm"), ".1f"), *_point_columns()]
    return _records([p for p in d.get("points", []) if isinstance(p, dict)], cols)


def _load_capacity(d: dict[str, Any], case: dict[str, Any]) -> str:
    note = (
        f'<p class="note">At {_f(d.get("speed_rpm"), ".6g")} rpm: largest load carried '
        f"{_f(d.get('largest_load_carried_N'), '.4g')} N ({escape(str(d.get('note', '')))}).</p>"
    )
    cols: list[Column] = [("load (N)", _key("load_N"), ".4g"), *_point_columns()]
    return note + _records([p for p in d.get("points", []) if isinstance(p, dict)], cols)


def _bearing_coefficients(d: dict[str, Any], case: dict[str, Any]) -> str:
    cols: list[Column] = [("speed (krpm)", _krpm("speed_rpm"), ".1f")]
    for i, a in enumerate("XY"):
        for j, b in enumerate("XY"):
            cols.append((f"K{a}{b} (N/m)", _entry("K_N_per_m", 2 * i + j), ".4g"))
    for i, a in enumerate("XY"):
        for j, b in enumerate("XY"):
            cols.append((f"C{a}{b} (N·s/m)", _entry("C_N_s_per_m", 2 * i + j), ".4g"))
    note = '<p class="note">Synchronous: the excitation at the running speed.</p>'
    return note + _records([r for r in d.get("synchronous", []) if isinstance(r, dict)], cols)


def _bearing_stability(d: dict[str, Any], case: dict[str, Any]) -> str:
    onset = d.get("onset") or {}
    note = (
        f'<p class="note">Linear onset speed {_f(onset.get("onset_speed_rpm"), ".6g")} rpm, '
        f"whirl frequency {_f(onset.get('whirl_frequency_Hz'), '.4g')} Hz "
        f"({escape(str(onset.get('message', '')))}).</p>"
    )
    cols: list[Column] = [
        ("speed (krpm)", _krpm("speed_rpm"), ".1f"),
        ("log decrement", _key("log_decrement"), ".4f"),
        ("whirl ratio", _key("whirl_ratio"), ".3f"),
        ("whirl (Hz)", _key("whirl_frequency_Hz"), ".1f"),
        ("message", _key("message"), ""),
    ]
    return note + _records([m for m in d.get("modes", []) if isinstance(m, dict)], cols)


def _actuator_static(d: dict[str, Any], case: dict[str, Any]) -> str:
    def listed(key: str) -> Callable[[dict[str, Any]], Any]:
        return lambda r: ", ".join(f"{x:.3g}" for x in r.get(key) or []) or None

    note = f'<p class="note">At {_f(d.get("speed_rpm"), ".6g")} rpm and the case load.</p>'
    cols: list[Column] = [
        ("voltage (V)", _key("voltage_V"), "g"),
        ("preloads (µm)", listed("preload_um"), ""),
        ("actuator pressures (kPa)", listed("actuator_pressure_kPa"), ""),
        *_point_columns(),
    ]
    return note + _records([p for p in d.get("points", []) if isinstance(p, dict)], cols)


def _onsets_against(*lead: tuple[str, str, str]) -> Callable[[dict[str, Any], dict[str, Any]], str]:
    """A table of linear onsets against a knob: ``lead`` columns (header, key, format) first."""

    def render(d: dict[str, Any], case: dict[str, Any]) -> str:
        cols: list[Column] = [(h, _key(k), f) for h, k, f in lead]
        cols += [
            ("onset (krpm)", _krpm("onset_speed_rpm"), ".1f"),
            ("whirl (Hz)", _key("whirl_frequency_Hz"), ".1f"),
            ("how it was read", _key("message"), ""),
        ]
        return _records([r for r in d.get("rows", []) if isinstance(r, dict)], cols)

    return render


def _bearing_orbit(d: dict[str, Any], case: dict[str, Any]) -> str:
    rows = [
        ["sub-synchronous onset (krpm)", _f(_krpm("onset_speed_rpm")(d), ".1f")],
        ["whip frequency (Hz)", _f(d.get("whip_frequency_Hz"), ".0f")],
        ["divergence (krpm)", _f(_krpm("divergence_speed_rpm")(d), ".1f")],
        ["largest sub-synchronous amplitude (µm)", _f(d.get("max_subsync_amplitude_um"), ".2f")],
        ["end speed (krpm)", _f(_krpm("end_speed_rpm")(d), ".1f")],
        ["mean power loss (W)", _f(d.get("mean_power_loss_W"), ".2f")],
        ["how it ended", str(d.get("message", ""))],
    ]
    return _table(["readout", "value"], rows, num=(1,))


def _reference(d: dict[str, Any], case: dict[str, Any]) -> str:
    cols: list[Column] = [
        ("quantity", _key("quantity"), ""),
        ("reference", _key("reference"), ".5g"),
        ("ours", _key("ours"), ".5g"),
        ("deviation (%)", _key("deviation_percent"), "+.1f"),
        ("how ours was read", _key("note"), ""),
    ]
    return _records([r for r in d.get("rows", []) if isinstance(r, dict)], cols)


_TABLES: dict[str, Callable[[dict[str, Any], dict[str, Any]], str]] = {
    "identification": _identification,
    "structure": _structure,
    "static": _static,
    "coefficients": _coefficients,
    "stability": _stability,
    "actuator_design": _actuator_design,
    "bifurcation": _bifurcation,
    "orbits": _orbits,
    "orbits_paper_reading": _orbits,
    "uncertainty": _uncertainty,
    "schedule": _schedule,
    "rotor": _rotor,
    "plan": _plan,
    "bearing_static": _bearing_static,
    "load_capacity": _load_capacity,
    "bearing_coefficients": _bearing_coefficients,
    "bearing_stability": _bearing_stability,
    "bearing_orbit": _bearing_orbit,
    "shim_stability": _onsets_against(
        ("× case thickness", "scale", "g"), ("shim thickness (µm)", "thickness_um", ".3g")
    ),
    "voltage_stability": _onsets_against(("voltage (V)", "voltage_V", "g")),
    "actuator_static": _actuator_static,
    "reference_comparison": _reference,
}
