"""Headline numbers of a case: what ``foilbearing case show`` prints.

Keys carry their units (``k_assy_N_per_m3``), so scripts can use the JSON. A field of
the case is shown by its key and display unit in the case schema
(:func:`foilbearing.case.schema.summary_entry`); the derived quantities (Λ, k_assy,
strokes, the grid an orbit runs on) are computed here.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from foilbearing.case import Case
from foilbearing.case.schema import summary_entry
from foilbearing.structure import walowit_anno_bump_stiffness

__all__ = [
    "BEARING_TYPES",
    "case_summary",
    "format_summary",
    "grid_line",
    "grid_used",
    "speed_sweep_points",
    "structure_summary",
    "sweep_points",
]


def case_summary(case: Case) -> dict[str, Any]:
    """Inputs and derived quantities of a case, in engineering units with unit-named keys."""
    d = case.disturbance

    def shown(*paths: str) -> dict[str, Any]:
        # each field's summary key and value in its display unit, from the case schema
        return {k: v for p in paths for k, v in summary_entry(case, p).items()}

    out: dict[str, Any] = {
        "title": case.title,
        "source": case.source,
        **shown("bearing.radius", "bearing.length", "bearing.clearance"),
        **shown("gas.viscosity", "gas.ambient_pressure", "operation.load", "operation.speed"),
        "bearing_number": case.bearing_number(),
        **shown("rotor.mass", "rotor.imbalance"),
        "imbalance_radius_um": case.rotor.imbalance_radius * 1e6,
        "disturbance_N_rms": 0.0 if d is None else d.force_rms,
        **(
            {}
            if d is None
            else {
                "disturbance_band_Hz": [d.min_frequency, d.max_frequency],
                **shown("disturbance.seed"),
            }
        ),
        "grid": {
            "n_theta": case.grid.n_theta,
            "n_z": case.grid.n_z,
            "orbit_n_theta": case.grid.orbit_shape[0],
            "orbit_n_z": case.grid.orbit_shape[1],
            "axial_order": case.grid.axial_order,
            "orbit_axial_order": case.grid.orbit_order,
            "lift_off_smoothing": case.grid.lift_off_smoothing,
        },
        "bearing_type": BEARING_TYPES[case.kind],
        **(
            {}
            if case.actuators is None
            else {
                "actuator_reading": (
                    f"{case.actuators.preload_response} + {case.actuators.dynamics}"
                )
            }
        ),
    }
    if case.foil is not None:
        out |= shown("foil.bump_stiffness", "foil.loss_factor")
        bump = case.foil.bump
        if bump is not None:
            out["k_b_formula"] = bump.formula
            out["k_b_walowit_anno_N_per_m3"] = walowit_anno_bump_stiffness(
                bump.thickness,
                bump.pitch,
                bump.half_length,
                bump.youngs_modulus,
                bump.poisson_ratio,
            )
    act = case.actuators
    if act is not None:
        out |= shown("actuators.angles", "actuators.stinger_arc", "actuators.voltages")
        out["k_p_N_per_m3"] = act.k_p
        out |= shown("actuators.holder_spring_stiffness")
        out["k_assy_N_per_m3"] = case.assembly_stiffness()
        out["stack_stroke_um"] = [x * 1e6 for x in act.stack_strokes()]
        out["base_preload_um"] = [x * 1e6 for x in act.base_preloads()]
        out |= shown("actuators.smoothness")
    if case.shims is not None:
        out |= shown("shims.angles", "shims.arc", "shims.thickness")
    return out


def grid_used(case: Case) -> dict[str, Any]:
    """The grid and lift-off law an analysis of ``case`` ran on, unit-named keys.

    ``grid`` is [n_theta, n_z] (the half length), ``grid_axial_order`` the axial order,
    ``grid_lift_off_smoothing`` κ, and ``lift_off_law`` the law in words: "smoothed edge"
    (κ > 0), "sharp edge" (κ = 0) or "none" where the film holds sub-ambient pressure
    (a rigid bearing, or ``subambient = "retained"``) and κ plays no part. An orbit's
    case is already on the orbit's grid (:meth:`Case.orbit_case`).
    """
    g = case.grid
    lifts = case.foil is not None and case.foil.lift_off
    law = "none" if not lifts else ("smoothed edge" if g.lift_off_smoothing else "sharp edge")
    return {
        "grid": [g.n_theta, g.n_z],
        "grid_axial_order": g.axial_order,
        "grid_lift_off_smoothing": g.lift_off_smoothing,
        "lift_off_law": law,
    }


def grid_line(case: Case) -> str:
    """:func:`grid_used` in words, e.g. "grid 96 × 12, axial order 2, lift-off edge
    smoothed (κ = 0.1)", for the commands' text output."""
    used = grid_used(case)
    n_theta, n_z = used["grid"]
    law = {
        "none": "no lift-off (sub-ambient film held)",
        "sharp edge": "sharp lift-off edge (κ = 0)",
        "smoothed edge": f"lift-off edge smoothed (κ = {used['grid_lift_off_smoothing']:g})",
    }[used["lift_off_law"]]
    return f"grid {n_theta} × {n_z}, axial order {used['grid_axial_order']}, {law}"


#: What each kind of bearing (``Case.kind``) is called in summaries and reports.
BEARING_TYPES = {
    "rigid": "rigid gas journal bearing",
    "C-GFB": "C-GFB (PZT-controlled gas foil bearing)",
    "shimmed GFB": "shimmed gas foil bearing",
    "GFB": "gas foil bearing",
}


def format_summary(summary: dict[str, Any]) -> str:
    """A readable multi-line rendering of :func:`case_summary`."""
    lines = []
    for key, value in summary.items():
        if isinstance(value, float):
            text = f"{value:.6g}"
        elif isinstance(value, list):
            text = ", ".join(f"{v:.4g}" if isinstance(v, float) else str(v) for v in value)
        else:
            text = str(value)
        lines.append(f"  {key:<28} {text}")
    return "\n".join(lines)


def structure_summary(case: Case, voltages: Sequence[float]) -> dict[str, Any]:
    """k_b, k_assy and, per voltage, stack stroke and base preload (unit-named keys)."""
    from foilbearing.structure import base_preload, stack_displacement

    out: dict[str, Any] = {}
    if case.foil is not None:
        out["k_b_N_per_m3"] = case.foil.bump_stiffness
    act = case.actuators
    if act is not None:
        out["k_p_N_per_m3"] = act.k_p
        out["k_assy_N_per_m3"] = case.assembly_stiffness()
        out["voltages_V"] = list(voltages)
        out["stack_stroke_um"] = [
            float(stack_displacement(v, act.d33_quadratic, act.d33_linear)) * 1e6 for v in voltages
        ]
        out["base_preload_um"] = [
            float(
                base_preload(
                    v,
                    act.d33_quadratic,
                    act.d33_linear,
                    act.k_p,
                    act.holder_spring_stiffness,
                    act.holder_pre_extension,
                )
            )
            * 1e6
            for v in voltages
        ]
    return out


def sweep_points(ds: Any) -> list[dict[str, Any]]:
    """One dict per (bearing, voltage, speed) point of a static sweep, unit-named keys."""
    points = []
    for b in ds.bearing.values:
        for v in ds.voltage.values:
            for s in ds.speed.values:
                row = ds.sel(bearing=b, voltage=v, speed=s)
                ok = bool(row.converged)
                points.append(
                    {
                        "bearing": str(b),
                        "voltage_V": float(v),
                        "speed_rpm": float(s) * 1e3,
                        "converged": ok,
                        "eccentricity": float(row.eccentricity) if ok else None,
                        "attitude_deg": float(row.attitude) if ok else None,
                        "min_film_um": float(row.min_film) if ok else None,
                        "force_N": [float(row.force_x), float(row.force_y)] if ok else None,
                        "preload_um": [float(x) for x in row.preload.values] if ok else [],
                        "actuator_pressure_kPa": (
                            [float(x) for x in row.actuator_pressure.values] if ok else []
                        ),
                        "drag_torque_Nm": float(row.drag_torque) if ok else None,
                        "iterations": int(row.iterations) if ok else None,
                    }
                )
    return points


def speed_sweep_points(ds: Any) -> list[dict[str, Any]]:
    """One dict per speed of :func:`foilbearing.study.static.speed_sweep`, unit-named keys
    (those of the study's static stage, and the arcs' preloads and pressures if any)."""
    points = []
    for s in ds.speed.values:
        row = ds.sel(speed=s)
        ok = bool(row.converged)
        point: dict[str, Any] = {"speed_rpm": float(s) * 1e3, "converged": ok}
        if ok:
            point |= {
                "load_N": float(ds.attrs["load_N"]),
                "eccentricity": float(row.eccentricity),
                "attitude_deg": float(row.attitude),
                "min_film_um": float(row.min_film),
                "force_N": [float(row.force_x), float(row.force_y)],
                "drag_torque_Nm": float(row.drag_torque),
                "power_loss_W": float(row.power_loss),
                "iterations": int(row.iterations),
            }
            if "preload" in ds:
                point["preload_um"] = [float(x) for x in row.preload.values]
                point["actuator_pressure_kPa"] = [float(x) for x in row.actuator_pressure.values]
        points.append(point)
    return points
