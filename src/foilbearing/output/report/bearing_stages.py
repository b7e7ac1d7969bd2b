"""Sections of the study of any bearing (its plan, static, coefficients, stability, orbit)."""

from __future__ import annotations

from collections.abc import Callable
from html import escape
from typing import Any

from foilbearing.output.report.tables import (
    Column,
    _entry,
    _f,
    _key,
    _krpm,
    _records,
    _refined_readouts,
    _table,
    _with_grid_error,
)

__all__: list[str] = []


def _plan(d: dict[str, Any], case: dict[str, Any]) -> str:
    def shown(v: Any) -> str:
        if isinstance(v, bool):
            return "yes" if v else "no"
        return _f(v, ".6g") if not isinstance(v, dict) else escape(str(v) or "none")

    # what does not apply to this bearing (no actuators, no shims) is left out, not shown empty
    rows = [[k, shown(v)] for k, v in d.items() if v is not None and v != [] and v != {}]
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
    checked = onset.get("with_grid_error") or {}
    if "onset_speed_rpm" in checked:  # with its grid error (section "How far to trust ...")
        speed = f"{checked['onset_speed_rpm']} krpm"
    else:
        speed = f"{_f(_krpm('onset_speed_rpm')(onset), '.1f')} krpm"
    whirl = checked.get("whirl_frequency_Hz") or _f(onset.get("whirl_frequency_Hz"), ".1f")
    note = (
        f'<p class="note">Linear onset speed {speed}, whirl frequency {whirl} Hz '
        f"({escape(str(onset.get('message', '')))})"
        + ("; ± its grid error, from twice the cells (below)" if checked else "")
        + ".</p>"
    )
    cols: list[Column] = [
        ("speed (krpm)", _krpm("speed_rpm"), ".1f"),
        ("log decrement", _key("log_decrement"), ".4f"),
        ("whirl ratio", _key("whirl_ratio"), ".3f"),
        ("whirl (Hz)", _key("whirl_frequency_Hz"), ".1f"),
        ("message", _key("message"), ""),
    ]
    return note + _records([m for m in d.get("modes", []) if isinstance(m, dict)], cols)


def _grid_check(d: dict[str, Any], case: dict[str, Any]) -> str:
    grids = [" × ".join(str(n) for n in g) for g in d.get("grids") or []]
    if len(grids) < 2 or not d.get("rows"):
        return f'<p class="note">{escape(str(d.get("message", "no grid check")))}</p>'
    note = (
        f'<p class="note">The readouts at the case speed and load, and the linear onset, on '
        f"the case's grid {grids[0]} and on {grids[1]} (the axial order "
        f"{_f(d.get('axial_order'), 'd')} and κ = {_f(d.get('lift_off_smoothing'), 'g')} "
        "held), as <code>foilbearing check CASE</code> gives them. Each is printed with its "
        "error: the difference to the finer grid, which is not converged either "
        "(<code>foilbearing check CASE --levels 3</code> extrapolates).</p>"
    )
    cols: list[Column] = [
        ("readout", _key("readout"), ""),
        (grids[0], lambda r: r["values"][0], ".6g"),
        (grids[1], lambda r: r["values"][1], ".6g"),
        ("with its error", _key("text"), ""),
    ]
    return note + _records([r for r in d["rows"] if isinstance(r, dict)], cols)


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
        [
            "sub-synchronous onset (krpm)",
            _f(_with_grid_error("onset_speed_rpm", 1e-3, ".1f")(d), ""),
        ],
        ["whip frequency (Hz)", _f(_with_grid_error("whip_frequency_Hz", 1.0, ".0f")(d), "")],
        ["divergence (krpm)", _f(_with_grid_error("divergence_speed_rpm", 1e-3, ".1f")(d), "")],
        ["on the refined θ grid", _f(_refined_readouts(d), "")],
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
