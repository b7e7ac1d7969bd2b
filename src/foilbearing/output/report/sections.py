"""One function per section of the report: a part of ``summary.json`` to HTML."""

from __future__ import annotations

from collections.abc import Callable
from html import escape
from typing import Any

from foilbearing.output.report.bearing_stages import (
    _actuator_static,
    _bearing_coefficients,
    _bearing_orbit,
    _bearing_stability,
    _bearing_static,
    _grid_check,
    _load_capacity,
    _onsets_against,
    _plan,
    _reference,
)
from foilbearing.output.report.beyond import _rotor, _schedule, _uncertainty
from foilbearing.output.report.comparison import _comparison
from foilbearing.output.report.paper_stages import (
    _actuator_design,
    _bifurcation,
    _coefficients,
    _identification,
    _orbits,
    _stability,
    _static,
    _structure,
)
from foilbearing.output.report.tables import (
    Column,
    _f,
    _records,
    _table,
)

__all__ = [
    "STAGES",
    "_FIG14",
    "_TABLES",
    "_comparison",
    "_grid_text",
    "_intro",
    "_orbits",
    "stage_title",
]


#: Stage keys of summary.json in the paper's order, with section titles.
STAGES: tuple[tuple[str, str], ...] = (
    ("plan", "The study's plan"),
    ("reference_comparison", "Our numbers beside the case's reference values"),
    ("bearing_static", "Static performance against speed"),
    ("load_capacity", "Load capacity"),
    ("bearing_coefficients", "Dynamic force coefficients"),
    ("bearing_stability", "Linear stability"),
    ("grid_check", "How far to trust the grid: the case point and the onset on twice the cells"),
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


def stage_title(key: str, data: Any) -> str:
    """A stage's section title: a foil without actuators is "Foil structure" alone."""
    title = dict(STAGES).get(key, key.replace("_", " ").capitalize())
    if key == "structure" and isinstance(data, dict) and not data.get("voltages_V"):
        return "Foil structure"
    return title


def _intro(summary: dict[str, Any], case: dict[str, Any]) -> str:
    ran = [
        stage_title(k, summary[k]).split(" (")[0]
        for k, _ in STAGES
        if isinstance(summary.get(k), dict) and summary[k]
    ]
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


def _generic(d: dict[str, Any], case: dict[str, Any]) -> str:
    rows = [[k, _f(v, ".4g")] for k, v in d.items() if isinstance(v, int | float | str)]
    return _table(["quantity", "value"], rows, num=(1,)) if rows else ""


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
    "grid_check": _grid_check,
    "bearing_orbit": _bearing_orbit,
    "shim_stability": _onsets_against(
        ("× case thickness", "scale", "g"), ("shim thickness (µm)", "thickness_um", ".3g")
    ),
    "voltage_stability": _onsets_against(("voltage (V)", "voltage_V", "g")),
    "actuator_static": _actuator_static,
    "reference_comparison": _reference,
}
