"""The static part of the paper's study: speed × voltage sweeps of C-GFB and shimmed GFB (Figs. 9-12).

Each sweep walks the speeds in order and starts every equilibrium from the one
before (continuation), so the whole map costs a few Newton iterations a point.
Each point is the static analysis of :mod:`foilbearing.analysis.equilibrium` (whose old
name is ``foilbearing.static``); the film inside it is :mod:`foilbearing.reynolds.steady`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from foilbearing.analysis.equilibrium import StaticResult, solve_equilibrium
from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.film import film_model

__all__ = [
    "MIN_FILM_FLOOR",
    "PAPER_SPEEDS_RPM",
    "PAPER_VOLTAGES",
    "SHOWN_SPEEDS_RPM",
    "grid_errors_at",
    "speed_sweep",
    "static_errors",
    "static_sweep",
]

PAPER_SPEEDS_RPM = tuple(float(s) for s in range(10_000, 90_001, 10_000))
PAPER_VOLTAGES = (0.0, 50.0, 100.0, 150.0)
#: The speeds of the sweep the report's table shows, each with its grid error.
SHOWN_SPEEDS_RPM = (10_000.0, 50_000.0, 90_000.0)

#: The readouts of a point of the sweep printed with their grid error (key, name, unit,
#: scale to the unit), and those that are one value per actuator.
_POINT_READOUTS = (
    ("eccentricity", "eccentricity", "", 1.0),
    ("attitude_deg", "attitude", "°", 1.0),
    ("min_film_um", "minimum film", "µm", 1.0),
    ("drag_torque_Nm", "drag torque", "N m", 1.0),
)
_PER_ACTUATOR = ("preload_um", "actuator_pressure_kPa")

#: The least relative error stated for the minimum film: the film's least value over the
#: cells moves with where the minimum falls among them, and from 192 × 24 to 384 × 48 it
#: moved by up to 0.32 % where the two coarser grids agreed more closely (C-GFB, 150 V,
#: 10 krpm; 0.75 % at most anywhere), rounded up. Every other readout's two coarser grids
#: differed by more than the next refinement's move (order about 2, 2026-12-06).
MIN_FILM_FLOOR = 0.004

#: The scalar readouts of a sweep: unit in the dataset and factor from SI.
_UNITS = {
    "eccentricity": ("", 1.0),
    "attitude": ("deg", 180 / math.pi),
    "eps_x": ("", 1.0),
    "eps_y": ("", 1.0),
    "min_film": ("um", 1e6),
    "min_film_angle": ("deg", 180 / math.pi),
    "force_x": ("N", 1.0),
    "force_y": ("N", 1.0),
    "drag_torque": ("N m", 1.0),
    "power_loss": ("W", 1.0),
    "iterations": ("", 1.0),
}


def static_sweep(
    case: Case,
    speeds: Sequence[float],
    voltages: Sequence[float],
    *,
    bearings: Sequence[str] = ("C-GFB", "shimmed"),
    progress: Callable[[str], None] | None = None,
) -> Any:
    """Equilibria over speeds (rad/s) × voltages (V) for the C-GFB and its shimmed twin.

    Parameters
    ----------
    case
        A case with ``[actuators]``.
    speeds
        Rotor speeds, rad/s, swept in increasing order.
    voltages
        Actuator voltages (the same on every actuator), V.
    bearings
        Which of "C-GFB" and "shimmed" to compute.
    progress
        Called with a short line after each (bearing, voltage) row.

    Returns
    -------
    xarray.Dataset with dimensions ``bearing``, ``voltage``, ``speed``,
    ``actuator`` and ``theta``: eccentricity, attitude angle, minimum film,
    actuator pressure and piezoelectric preload per actuator, film force,
    drag torque, and the mid-plane pressure and film thickness around the
    bearing; ``converged`` flags each point.
    """
    import xarray as xr

    if case.actuators is None:
        raise ValueError("the static sweep compares a C-GFB with shims: the case needs [actuators]")
    speeds = sorted(speeds)
    n_act = len(case.actuators.angles)
    model_theta = film_model(case).grid.theta
    shape = (len(bearings), len(voltages), len(speeds))
    scalars = {k: np.full(shape, np.nan) for k in _UNITS}
    converged = np.zeros(shape, dtype=bool)
    per_act = {k: np.full((*shape, n_act), np.nan) for k in ("actuator_pressure", "preload")}
    fields = {k: np.full((*shape, model_theta.size), np.nan) for k in ("pressure", "film")}
    for b, kind in enumerate(bearings):
        for v, volt in enumerate(voltages):
            base = case.with_voltages(float(volt))
            bearing = base.shimmed() if kind == "shimmed" else base
            model = film_model(bearing)
            start = None
            for s, omega in enumerate(speeds):
                res = solve_equilibrium(bearing, speed=omega, model=model, start=start)
                if not res.converged:
                    start = None
                    continue
                start = (res.eps_x, res.eps_y, res.P)
                _store(res, (b, v, s), scalars, per_act, fields)
                converged[b, v, s] = True
            if progress is not None:
                ok = int(converged[b, v].sum())
                progress(f"{kind} at {volt:g} V: {ok}/{len(speeds)} speeds converged")
    coords = {
        "bearing": list(bearings),
        "voltage": ("voltage", np.asarray(voltages, float), {"units": "V"}),
        "speed": ("speed", np.asarray(speeds) / RPM / 1e3, {"units": "krpm"}),
        "actuator": ("actuator", np.round(np.degrees(case.actuators.angles), 9), {"units": "deg"}),
        "theta": ("theta", np.degrees(model_theta), {"units": "deg"}),
    }
    dims = ("bearing", "voltage", "speed")
    data: dict[str, Any] = {
        k: (dims, scalars[k] * _UNITS[k][1], {"units": _UNITS[k][0]}) for k in scalars
    }
    data["converged"] = (dims, converged)
    data["actuator_pressure"] = (
        (*dims, "actuator"),
        per_act["actuator_pressure"] / 1e3,
        {"units": "kPa", "long_name": "axially averaged gauge pressure p_A at the actuator"},
    )
    data["preload"] = (
        (*dims, "actuator"),
        per_act["preload"] * 1e6,
        {"units": "um", "long_name": "piezoelectric preload (Eq. 3b); shim thickness for shims"},
    )
    data["midplane_pressure"] = (
        (*dims, "theta"),
        fields["pressure"] / 1e3,
        {"units": "kPa", "long_name": "absolute pressure in the cell row next to the mid-plane"},
    )
    data["midplane_film"] = ((*dims, "theta"), fields["film"] * 1e6, {"units": "um"})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(
        viscosity_Pa_s=case.gas.viscosity,
        clearance_um=case.bearing.clearance * 1e6,
        load_N=case.operation.load,
        n_theta=case.grid.n_theta,
        n_z=case.grid.n_z,
    )
    return ds


def static_errors(
    points: list[dict[str, Any]], fine: list[dict[str, Any]], grid: Sequence[int]
) -> None:
    """Set on each point of ``points`` (:func:`foilbearing.output.summary.sweep_points`)
    that ``fine`` has too (the same bearing, voltage and speed on a refined grid) its
    ``grid_refined``: the finer values, each readout's error and its text (the value with
    its error, :func:`~foilbearing.study.converged.with_error`).

    The error is the difference to the finer grid: the two-level estimate at order 1
    (:data:`foilbearing.study.converged.ASSUMED_ORDER`), which the statics' second order
    (docs/numerics.md) makes an upper bound where the differences shrink smoothly; for the
    minimum film at least :data:`MIN_FILM_FLOOR` of it.
    """
    from foilbearing.study.converged import two_grid_readouts, with_error

    def at(p: dict[str, Any]) -> tuple[str, float, float]:
        return (p["bearing"], float(p["voltage_V"]), round(float(p["speed_rpm"]), 6))

    finer = {at(p): p for p in fine if p.get("converged")}
    for p in points:
        f = finer.get(at(p))
        if f is None or not p.get("converged"):
            continue
        out, _ = two_grid_readouts(_POINT_READOUTS, p, f, _error, grid[0])
        for key in _PER_ACTUATOR:
            pairs = list(zip(p.get(key) or [], f.get(key) or [], strict=False))
            out[key] = [b for _, b in pairs]
            out["errors"][key] = [abs(a - b) for a, b in pairs]
            out["texts"][key] = " / ".join(  # a shim's thickness: the same on every grid
                with_error(a, abs(a - b)) if a != b else f"{a:.1f}" for a, b in pairs
            )
        p["grid_refined"] = out | {"grid": list(grid)}


def grid_errors_at(points: list[dict[str, Any]], at: tuple[str, float, float], key: str) -> Any:
    """The grid error of readout ``key`` at the point ``at`` (bearing, voltage in V, speed
    in rpm) of :func:`static_errors`'s ``points``; None where that point was not refined."""
    for p in points:
        if (p["bearing"], float(p["voltage_V"]), float(p["speed_rpm"])) == at:
            return ((p.get("grid_refined") or {}).get("errors") or {}).get(key)
    return None


def _error(key: str, f1: float, f2: float) -> float:
    return max(abs(f1 - f2), MIN_FILM_FLOOR * abs(f1) if key == "min_film_um" else 0.0)


def _store(
    res: StaticResult,
    idx: tuple[int, ...],
    scalars: dict[str, np.ndarray],
    per_act: dict[str, np.ndarray],
    fields: dict[str, np.ndarray],
) -> None:
    pa, c = res.case.gas.ambient_pressure, res.case.bearing.clearance
    values = {
        "eccentricity": res.eccentricity,
        "attitude": res.attitude_angle,
        "eps_x": res.eps_x,
        "eps_y": res.eps_y,
        "min_film": res.min_film,
        "min_film_angle": res.min_film_angle,
        "force_x": res.force[0],
        "force_y": res.force[1],
        "drag_torque": res.drag_torque,
        "power_loss": res.power_loss,
        "iterations": res.iterations,
    }
    for k, val in values.items():
        scalars[k][idx] = val
    per_act["actuator_pressure"][idx] = res.actuator_pressure
    per_act["preload"][idx] = res.preload
    fields["pressure"][idx] = res.P[:, 0] * pa
    fields["film"][idx] = res.H[:, 0] * c


def speed_sweep(
    case: Case, speeds: Sequence[float], *, progress: Callable[[str], None] | None = None
) -> Any:
    """Equilibria of the case as it is (any kind of bearing) over speeds, at its load.

    The speeds are walked in increasing order, each equilibrium started from the one
    before (continuation); a point that does not converge is flagged and the next one
    starts afresh.

    Parameters
    ----------
    case
        Any case: a passive, shimmed or rigid bearing, or a C-GFB at its voltages.
    speeds
        Rotor speeds, rad/s.
    progress
        Called with one line when the sweep is done.

    Returns
    -------
    xarray.Dataset with dimensions ``speed`` (krpm) and ``theta`` (deg), and ``arc``
    (deg) for the shims' or actuators' angles where the bearing has any: the readouts
    of :func:`static_sweep` (no ``voltage`` or ``bearing`` dimension), the bearing's
    kind in the attribute ``bearing``; ``converged`` flags each point.
    """
    import xarray as xr

    speeds = sorted(speeds)
    model = film_model(case)
    theta = model.grid.theta
    arcs: tuple[float, ...] = ()
    if case.actuators is not None:
        arcs = case.actuators.angles
    elif case.shims is not None:
        arcs = case.shims.angles
    n = len(speeds)
    scalars = {k: np.full(n, np.nan) for k in _UNITS}
    per_arc = {k: np.full((n, len(arcs)), np.nan) for k in ("actuator_pressure", "preload")}
    fields = {k: np.full((n, theta.size), np.nan) for k in ("pressure", "film")}
    converged = np.zeros(n, dtype=bool)
    start = None
    for s, omega in enumerate(speeds):
        res = solve_equilibrium(case, speed=omega, model=model, start=start)
        if not res.converged:
            start = None
            continue
        start = (res.eps_x, res.eps_y, res.P)
        _store(res, (s,), scalars, per_arc, fields)
        converged[s] = True
    if progress is not None:
        progress(f"{case.kind}: {int(converged.sum())}/{n} speeds converged")
    data: dict[str, Any] = {
        k: ("speed", scalars[k] * _UNITS[k][1], {"units": _UNITS[k][0]}) for k in scalars
    }
    data["converged"] = ("speed", converged)
    coords: dict[str, Any] = {
        "speed": ("speed", np.asarray(speeds) / RPM / 1e3, {"units": "krpm"}),
        "theta": ("theta", np.degrees(theta), {"units": "deg"}),
    }
    if arcs:  # NetCDF 3 has no empty dimension: a bearing without arcs has none
        coords["arc"] = ("arc", np.round(np.degrees(arcs), 9), {"units": "deg"})
        data["actuator_pressure"] = (
            ("speed", "arc"),
            per_arc["actuator_pressure"] / 1e3,
            {"units": "kPa", "long_name": "axially averaged gauge pressure p_A at the arc"},
        )
        data["preload"] = (
            ("speed", "arc"),
            per_arc["preload"] * 1e6,
            {"units": "um", "long_name": "piezoelectric preload (Eq. 3b); shim thickness"},
        )
    data["midplane_pressure"] = (
        ("speed", "theta"),
        fields["pressure"] / 1e3,
        {"units": "kPa", "long_name": "absolute pressure in the cell row next to the mid-plane"},
    )
    data["midplane_film"] = (("speed", "theta"), fields["film"] * 1e6, {"units": "um"})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(
        bearing=case.kind,
        viscosity_Pa_s=case.gas.viscosity,
        clearance_um=case.bearing.clearance * 1e6,
        load_N=case.operation.load,
        rotor_mass_kg=case.rotor.mass,
        n_theta=case.grid.n_theta,
        n_z=case.grid.n_z,
    )
    return ds
