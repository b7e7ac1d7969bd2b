"""Sections of the paper's stages (Figs. 5-15 and the analyses beside them)."""

from __future__ import annotations

from collections.abc import Callable
from html import escape
from pathlib import Path
from typing import Any

from foilbearing.output.report.tables import (
    Column,
    _f,
    _key,
    _krpm,
    _nearest,
    _records,
    _refined_readouts,
    _transpose,
    _with_grid_error,
)

__all__: list[str] = []


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
    """The foil's springs and, on a bearing with actuators, their strokes and base preloads
    (a column only where the summary has it: a passive foil has k_b alone)."""
    springs: list[Column] = [
        c
        for c in (
            ("k_b (N/m³)", _key("k_b_N_per_m3"), ".4g"),
            ("k_p (N/m³)", _key("k_p_N_per_m3"), ".4g"),
            ("k_assy (N/m³)", _key("k_assy_N_per_m3"), ".4g"),
        )
        if c[1](d) is not None
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

    def checked(key: str, spec: str) -> Callable[[dict[str, Any]], Any]:
        return _with_grid_error(key, 1.0, spec, "grid_refined")

    cols: list[Column] = [
        ("bearing", _key("bearing"), ""),
        ("voltage (V)", _key("voltage_V"), "g"),
        ("speed (krpm)", lambda p: p["speed_rpm"] / 1e3, ".0f"),
        ("eccentricity ε", checked("eccentricity", ".3f"), ".3f"),
        ("attitude (°)", checked("attitude_deg", ".1f"), ".1f"),
        ("min film (µm)", checked("min_film_um", ".1f"), ".1f"),
        (f"preload at {at}° (µm)", checked("preload_um", ".1f"), ".1f"),
        (f"film pressure at {at}° (kPa)", checked("actuator_pressure_kPa", ".1f"), ".1f"),
        ("converged", _key("converged"), ""),
    ]
    n_ok = sum(bool(p.get("converged")) for p in points)
    fine = next((p["grid_refined"]["grid"] for p in points if p.get("grid_refined")), None)
    note = (
        f'<p class="note">{len(points)} equilibria ({n_ok} converged), shown here at '
        f"{', '.join(_f(s / 1e3, '.0f') for s in shown)} krpm; all of them are in "
        "<code>static_sweep.nc</code> beside this page."
        + (
            f" A value printed ± carries its grid error: the difference to the same "
            f"equilibrium on {fine[0]} × {fine[1]} cells (the axial order and κ held)."
            if fine
            else ""
        )
        + "</p>"
    )
    return note + _records([p for p in points if float(p["speed_rpm"]) in shown], cols)


def _coefficients(d: dict[str, Any], case: dict[str, Any]) -> str:
    note = (
        f'<p class="note">Equilibrium at {_f(d.get("speed_rpm"), ".6g")} rpm: ε = '
        f"{_f(d.get('eccentricity'), '.3f')}, attitude {_f(d.get('attitude_deg'), '.1f')}°.</p>"
    )
    keys = ("frequency_Hz", "frequency_ratio", "K_N_per_m", "C_Ns_per_m")
    fine = d.get("grid_refined") or {}
    k_texts, c_texts = fine.get("K_texts_MN_per_m") or [], fine.get("C_texts_Ns_per_m") or []
    rows = _transpose(d, keys)
    checked = bool(k_texts and c_texts)
    if checked:  # each coefficient's text with its grid error, per frequency
        for row, k_text, c_text in zip(rows, k_texts, c_texts, strict=False):
            row |= {"tK_N_per_m": k_text, "tC_Ns_per_m": c_text}

    def entry(name: str, i: int, scale: float, spec: str) -> Callable[[dict[str, Any]], Any]:
        def get(r: dict[str, Any]) -> str:
            if "t" + name in r:
                return str(r["t" + name][i // 2][i % 2])
            return _f(r[name][i // 2][i % 2] * scale, spec)

        return get

    cols: list[Column] = [
        ("frequency (Hz)", _key("frequency_Hz"), ".1f"),
        ("ratio to speed", _key("frequency_ratio"), ".2f"),
    ]
    for i, ij in enumerate(("xx", "xy", "yx", "yy")):
        cols.append((f"K{ij} (MN/m)", entry("K_N_per_m", i, 1e-6, ".4f"), "r"))
    for i, ij in enumerate(("xx", "xy", "yx", "yy")):
        cols.append((f"C{ij} (N·s/m)", entry("C_Ns_per_m", i, 1.0, ".1f"), "r"))
    if checked:
        grid = fine.get("grid") or ["?", "?"]
        note += (
            f'<p class="note">Each coefficient ± its grid error: the difference to the same '
            f"equilibrium and frequency on {grid[0]} × {grid[1]} cells (the axial order and "
            "κ held).</p>"
        )
    elif fine.get("message"):
        note += f'<p class="note">{escape(str(fine["message"]))}</p>'
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

    # The published onsets with their error (foilbearing.study.converged): the case's
    # reading on its grid and at the published resolution, the paper's at the latter.
    errors = any(e.get("onset_text_krpm") for e in d.get("C-GFB", []))
    first = next((e for e in d.get("C-GFB", []) if e.get("refined_grid")), None)
    on_refined = (
        ""
        if first is None
        else f" on {first['refined_grid'][0]} × {first['refined_grid'][1]}, "
        f"κ {first.get('refined_kappa', 0.0):g}"
    )

    def published(r: dict[str, Any], text: str) -> Any:
        if r.get(text):
            return r[text]
        krpm = _krpm("onset_speed_rpm")(r)
        return None if krpm is None else f"{krpm:.1f}"

    cols: list[Column] = [
        ("voltage (V)", _key("voltage_V"), "g"),
        (
            "C-GFB onset (krpm)",
            lambda r: published(r, "onset_text_krpm") if errors else _krpm("onset_speed_rpm")(r),
            "" if errors else ".1f",
        ),
    ]
    if errors:
        cols.append(
            (
                f"C-GFB onset (krpm{on_refined})",
                lambda r: r.get("onset_refined_text_krpm"),
                "",
            )
        )
    cols += [
        ("whirl frequency (Hz)", _key("whirl_frequency_Hz"), ".0f"),
        ("whirl ratio", _key("whirl_ratio"), ".2f"),
        (
            f"shimmed onset (krpm{on_refined})",
            (lambda r: published(r["shim"], "onset_refined_text_krpm"))
            if errors
            else onset_of("shim"),
            "" if errors else ".1f",
        ),
        (
            "shimmed whirl (Hz)",
            lambda r: r["shim"].get(
                "whirl_frequency_refined_Hz", r["shim"].get("whirl_frequency_Hz")
            ),
            ".0f",
        ),
    ]
    if others["orbit_grid"]:
        cols.append(
            (
                "C-GFB on the orbits' grid (krpm)",
                (lambda r: published(r["orbit_grid"], "onset_text_krpm"))
                if errors
                else onset_of("orbit_grid"),
                "" if errors else ".1f",
            )
        )
    if others["paper_reading"]:
        cols += [
            (
                f"C-GFB, paper's reading: lobe + held (krpm{on_refined})",
                (
                    (lambda r: published(r["paper_reading"], "onset_refined_text_krpm"))
                    if errors
                    else onset_of("paper_reading")
                ),
                "" if errors else ".1f",
            ),
            (
                "its whirl (Hz)",
                lambda r: r["paper_reading"].get(
                    "whirl_frequency_refined_Hz", r["paper_reading"].get("whirl_frequency_Hz")
                ),
                ".0f",
            ),
        ]
    if others["kept"]:
        cols += [
            (
                f"C-GFB, suction retained (krpm{on_refined})",
                (lambda r: published(r["kept"], "onset_refined_text_krpm"))
                if errors
                else onset_of("kept"),
                "" if errors else ".1f",
            ),
            (
                f"shimmed, suction retained (krpm{on_refined})",
                (lambda r: published(r["shim_kept"], "onset_refined_text_krpm"))
                if errors
                else onset_of("shim_kept"),
                "" if errors else ".1f",
            ),
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
        + (
            " The C-GFB onsets are given with their estimated discretisation error, on the "
            "case's grid and at the published resolution"
            f"{on_refined} (the grid refined by 2, the lift-off smoothing κ ≤ 0.02, where it "
            "moves no onset by more than 0.23 %; docs/lift-off.md), the shimmed GFB, the "
            "suction-retained columns and the paper's reading at the latter, the orbits' "
            "partner on their own grid."
            if errors
            else ""
        )
        + "</p>"
    )
    return note + _records(rows, cols)


def _actuator_design(d: dict[str, Any], case: dict[str, Any]) -> str:
    cols: list[Column] = [
        ("bearing at the voltage", _key("bearing"), ""),
        ("stack stiffness K_p (MN/m)", _scaled("stack_stiffness_N_per_m", 1e-6), ".3g"),
        ("linear onset (krpm)", _text_or("onset_text_krpm", _krpm("onset_speed_rpm")), ".1f"),
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
        "(docs/model.md §3.8); each onset on the case's grid ± its error, as the linear "
        "stability section states it. The stack stiffness each reading needs for "
        f"{target:.0%} of the shimmed onset:</p><ul>{items}</ul>"
    )
    return note + _records(d.get("table", []), cols)


def _bifurcation(d: dict[str, Any], case: dict[str, Any]) -> str:
    cols: list[Column] = [
        ("reading of the actuator", _key("reading"), ""),
        ("voltage (V)", _key("voltage_V"), "g"),
        ("Hopf bifurcation", _key("bifurcation_type"), ""),
        ("linear onset (krpm)", _with_grid_error("hopf_speed_rpm", 1e-3, ".1f"), ""),
        ("whirl (Hz)", _with_grid_error("linear_whirl_frequency_Hz", 1.0, ".0f"), ""),
        ("speed limit (krpm)", _with_grid_error("speed_limit_rpm", 1e-3, ".1f"), ""),
        ("largest stable cycle (µm)", _with_grid_error("largest_stable_cycle_um", 1.0, ".1f"), ""),
        ("its speed past the onset (%)", _scaled("largest_stable_cycle_past_onset", 100.0), ".2f"),
        ("on the refined grid", _refined_type, ""),
        ("cycles", _key("cycles"), "d"),
        ("status", _key("status"), ""),
    ]
    grid = d.get("grid") or ["?", "?"]
    if "scan_rpm" in d:  # a bearing of its own: one branch, no readings of an actuator
        fine = (d.get("theta_refined") or {}).get("grid")
        note = (
            f'<p class="note">{escape(str(d.get("message", "")))} The branch from the '
            f"linear onset on the orbit grid {grid[0]} × {grid[1]}, as "
            "<code>foilbearing bifurcation CASE</code> gives it (docs/bifurcation.md)"
            + (
                f"; a value printed ± carries the difference to the same branch on "
                f"{fine[0]} × {fine[1]} cells (the cycle's at the same distance past "
                "each grid's onset)."
                if fine
                else "."
            )
            + "</p>"
        )
        return note + _records(d.get("rows", []), cols[2:-1])
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
    fine = d.get("refined_grid")
    if fine:
        note += (
            f'<p class="note">Each branch was run again on {fine[0]} × {fine[1]} cells '
            "(<code>--theta-refine</code>); a value printed ± carries the two grids' "
            "difference: for the onset, its whirl and the speed limit at least the "
            "published onsets' 0.7 %; for the largest stable cycle, the finer branch's "
            "amplitude at the same distance past its own onset, relative to the onset "
            "speed (the onset's move is the onset's error; near it a cycle grows as the "
            "square root of that distance). A branch whose type differs between the two "
            "grids bends by less than the grid resolves: its cycle's error is the cycle "
            "itself.</p>"
        )
    return note + _records(d.get("rows", []), cols)


def _text_or(key: str, get: Callable[[dict[str, Any]], Any]) -> Callable[[dict[str, Any]], Any]:
    """The record's printed ``key`` (a value with its error) where it has one, else ``get``."""
    return lambda r: r.get(key) or get(r)


def _refined_type(r: dict[str, Any]) -> str | None:
    """The Hopf type on a refined branch's grid: "192 × 4: supercritical"."""
    f = r.get("theta_refined")
    if not f:
        return None
    grid = f.get("grid") or ["?", "?"]
    return f"{grid[0]} × {grid[1]}: {f.get('bifurcation_type') or 'no branch'}"


def _scaled(name: str, factor: float) -> Callable[[dict[str, Any]], Any]:
    return lambda r: None if r.get(name) is None else float(r[name]) * factor


def _orbits(d: dict[str, Any], case: dict[str, Any]) -> str:
    def intervals(r: dict[str, Any]) -> str:
        ivs = r.get("subsync_intervals_rpm_Hz") or []
        return "; ".join(f"{a / 1e3:.1f}-{b / 1e3:.1f} krpm at {f:.0f} Hz" for a, b, f in ivs)

    def over_seeds(key: str) -> Callable[[dict[str, Any]], str | None]:
        """A 0 V run's readout over the disturbance's seeds: "lo-hi (n seeds)"; a controlled
        run's, under one seed: "one seed (up to 2 % over seeds)"."""

        def get(r: dict[str, Any]) -> str | None:
            seeds = r.get("subsync_onset_seeds") or {}
            found = [x for x in seeds.get(key) or [] if x is not None]
            if len(seeds.get("seeds") or []) < 2 or not found:
                spread = ((r.get("seed_floor") or {}).get("texts") or {}).get(key)
                return f"one seed ({spread} over seeds)" if spread else None
            return (
                f"{min(found) / 1e3:.1f}-{max(found) / 1e3:.1f} "
                f"({len(found)} of {len(seeds['seeds'])} seeds)"
            )

        return get

    def run(r: dict[str, Any]) -> str | None:
        described = r.get("description")
        volts = r.get("voltage_V")
        return str(described) if described else None if volts is None else f"{volts:g} V"

    cols: list[Column] = [
        ("run", run, ""),
        ("sub-sync onset (krpm)", _with_grid_error("onset_speed_rpm", 1e-3, ".1f"), ""),
        ("onset over the seeds (krpm)", over_seeds("onset_speed_rpm"), ""),
        ("whip (Hz)", _with_grid_error("whip_frequency_Hz", 1.0, ".0f"), ""),
        ("sub-synchronous intervals", lambda r: intervals(r) or None, ""),
        ("divergence (krpm)", _with_grid_error("divergence_speed_rpm", 1e-3, ".1f"), ""),
        ("divergence over the seeds (krpm)", over_seeds("divergence_speed_rpm"), ""),
        ("on the refined θ grid", _refined_readouts, ""),
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
        f"32.6 krpm).{named} {seed} (docs/development/orbit-performance.md in the repository); the "
        "linear onsets do not depend on it. Where a 0 V run was run again on refined θ cells "
        "(<code>foilbearing study --theta-refine</code>), its onset, whip and divergence carry "
        "their grid error: the difference between the two grids, or at least the moves "
        "measured on the paper's case from 192 to 384 θ cells (onset 8 %, whip and "
        "divergence 2 %), which two grids alone would miss; the runs that were not (the "
        "controlled ones) carry that floor. A 0 V run run again under other seeds of the "
        "disturbance (<code>--seeds</code>) shows its readouts' range over them; a controlled "
        "run, run under the case's seed alone, the largest range measured over three seeds on "
        "the paper's case's controlled runs (onset 6 %, whip 1 %, divergence 2 %).</p>"
    )
    return note + _records([r for r in d.get("runs", []) if isinstance(r, dict)], cols)
