"""Sections beyond the paper: uncertainty envelopes, the voltage schedule, a rotor."""

from __future__ import annotations

from html import escape
from pathlib import Path
from typing import Any

from foilbearing.output.report.tables import (
    Column,
    _f,
    _key,
    _krpm,
    _records,
    _table,
    _with_grid_error,
)

__all__: list[str] = []


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
    check = d.get("grid_check") or {}
    errors = check.get("outputs") or {}
    if check:
        g, f = check.get("grid") or ["?", "?"], check.get("refined_grid") or ["?", "?"]
        units = check.get("centre_unit") or {}
        centre = "; ".join(
            f"{k} {v:.4g} {units.get(k, '')}".rstrip()
            for k, v in (check.get("centre") or {}).items()
        )
        intro += (
            f'<p class="note">Every sample point is solved on the case\'s {g[0]} × {g[1]} '
            "grid. The grid's error is nearly the same at every point, a shift of the whole "
            'envelope rather than a spread: the column "grid error" is each output at the '
            f"centre of the inputs ({escape(centre)}) on {g[0]} × {g[1]} less the same on "
            f"{f[0]} × {f[1]} (as <code>foilbearing check</code> states it; "
            f"{_f(check.get('wall_time_s'), '.0f')} s)."
            + (" Speed-up readouts are not checked here." if check.get("not_checked") else "")
            + "</p>"
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
        row = [name, _f(o.get("p5"), ".4g"), _f(o.get("p50"), ".4g"), _f(o.get("p95"), ".4g")]
        if check:
            err = (errors.get(name) or {}).get("error")
            row.append("—" if err is None else f"{err:+.2g}")
        rows.append([*row, cell])
    heads = ["output (unit in the name)", "p5", "p50", "p95"]
    heads += ["grid error"] if check else []
    num = (1, 2, 3, 4) if check else (1, 2, 3)
    return intro + _table([*heads, "largest index ± 95 %"], rows, num=num)


def _schedule(d: dict[str, Any], case: dict[str, Any]) -> str:
    sched = d.get("schedule") or {}
    limit = sched.get("limit_speed_rpm")
    check = sched.get("grid_refined") or {}
    texts = check.get("texts") or {}
    limit_text = texts.get("limit_speed_krpm") or (None if limit is None else f"{limit / 1e3:.1f}")
    speeds = sched.get("speeds_rpm") or []
    top = f"{speeds[-1] / 1e3:.0f} krpm" if speeds else "the top speed"
    note = (
        f'<p class="note">At each speed the voltages of least power loss with a log decrement '
        f"of the least stable whirl mode of at least {_f(sched.get('margin'), 'g')} (linear "
        "analysis), smoothed for an amplifier slew rate of "
        f"{_f(sched.get('slew_rate_V_per_s'), 'g')} V/s during a speed-up at "
        f"{_f(sched.get('acceleration_rad_per_s2'), 'g')} rad/s². "
        + (
            f"No voltage keeps the rotor stable above {limit_text} krpm."
            if limit is not None
            else f"The schedule keeps the margin up to {top}."
        )
        + f" File: <code>{escape(Path(str(d.get('schedule_file', 'schedule.toml'))).name)}</code> "
        "(<code>foilbearing orbit --voltage-schedule</code> runs it).</p>"
    )
    if check:
        g, f = check.get("grid") or ["?", "?"], check.get("refined_grid") or ["?", "?"]
        below = check.get("below_margin_rpm") or []
        note += (
            f'<p class="note">The schedule is searched on {g[0]} × {g[1]}; its points (the '
            f"scheduled voltages at every speed and midpoint) solved again on {f[0]} × {f[1]} "
            "give each log decrement, whirl frequency and power loss its grid error (the "
            "difference), and "
            + (
                "on the finer grid the margin is missed at "
                + ", ".join(f"{w / 1e3:.0f}" for w in below)
                + " krpm."
                if below
                else "on the finer grid every speed that met the margin still meets it."
            )
            + "</p>"
        )
    rows = []
    for k, w in enumerate(speeds):

        def at(key: str, k: int = k) -> Any:
            values = sched.get(key) or []
            return values[k] if k < len(values) else None

        def shown(key: str, spec: str, k: int = k) -> str:
            text = (texts.get(key) or [])[k] if k < len(texts.get(key) or []) else None
            return str(text) if text else _f(at(key), spec)

        rows.append(
            [
                _f(w / 1e3, ".0f"),
                _f(at("voltages_V"), ".1f"),
                shown("log_decrement", ".3f"),
                shown("whirl_frequency_Hz", ".0f"),
                shown("power_loss_W", ".2f"),
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
            f"(3 to {_f(None if common is None else common / 1e3, '.1f')} krpm). Onset, "
            "whip and divergence carry their grid error as in the speed-ups' table: a run "
            "the orbit stage ran again on refined θ cells its own, the others the floor "
            "measured on those (onset 8 %, whip and divergence 2 %). Each ran under the case's "
            "seed of the disturbance alone; over three seeds the paper's case's controlled "
            "runs ranged by up to 6 % (onset), 1 % (whip) and 2 % (divergence).</p>"
        )
        cols: list[Column] = [
            ("run", _key("run"), ""),
            ("sub-sync onset (krpm)", _with_grid_error("onset_speed_rpm", 1e-3, ".1f"), ""),
            ("whip (Hz)", _with_grid_error("whip_frequency_Hz", 1.0, ".0f"), ""),
            ("divergence (krpm)", _with_grid_error("divergence_speed_rpm", 1e-3, ".1f"), ""),
            ("over the seeds", lambda r: (r.get("seed_floor") or {}).get("text"), ""),
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
