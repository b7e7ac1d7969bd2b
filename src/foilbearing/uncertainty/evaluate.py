"""One sample point: every output of an uncertainty analysis for one case.

:func:`evaluate_sample` is the pure Dask task (module level, pickled by
reference). It returns the outputs by name; each name carries its unit and
where it is read, e.g. ``min_film_um[90 krpm, 150 V]`` or
``onset_speed_krpm[0 V]``. An output that cannot be computed at a point (no
equilibrium, an onset beyond the scan) is None there with the reason in
``message``; the point fails only if no output could be computed.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from foilbearing.case import Case
from foilbearing.constants import RPM
from foilbearing.errors import InputError, SolverError

__all__ = [
    "at_voltages",
    "evaluate_sample",
    "output_names",
    "stability_outputs",
    "static_outputs",
    "where_read",
]

#: Static readouts: (name with unit, function of the StaticResult's headline).
STATIC_QUANTITIES = (
    "eccentricity_ratio",
    "attitude_deg",
    "min_film_um",
    "power_loss_W",
)
STABILITY_QUANTITIES = ("onset_speed_krpm", "whirl_frequency_Hz")
#: Brent's tolerance on each sample's onset, relative to the speed (0.1 %). The
#: spread over the samples is tens of per cent and the grid's own error about 1.7 %
#: (docs/development/orbit-performance.md), so a finer root buys nothing; it saves 3 of the 43
#: equilibria of the default case's four onsets.
ONSET_REL_TOL = 1e-3
#: Readouts of a speed-up (the orbit's signal analysis, :mod:`foilbearing.orbit.analysis`).
ORBIT_QUANTITIES = (
    "orbit_onset_krpm",
    "orbit_whip_frequency_Hz",
    "orbit_divergence_krpm",
    "orbit_max_subsync_um",
)


def _orbit_where(volt: float | None, ramp: list[float] | None) -> str:
    if volt is None:
        return "case voltages"
    if ramp is None:
        return f"{volt:g} V"
    return f"{volt:g} V ramp {ramp[0]:g}-{ramp[1]:g} s"


def where_read(speed: float | None, volt: float | None, actuator: int | None = None) -> str:
    """Where an output is read, as its name says it: "90 krpm, 150 V, actuator 2" (speed in
    rad/s, voltage in V or None for the case's own, actuator 0-based or None)."""
    parts = []
    if speed is not None:
        parts.append(f"{speed / RPM / 1e3:g} krpm")
    parts.append("case voltages" if volt is None else f"{volt:g} V")
    if actuator is not None:
        parts.append(f"actuator {actuator + 1}")
    return ", ".join(parts)


def output_names(outputs: Mapping[str, Any], n_actuators: int) -> list[dict[str, Any]]:
    """Every output of ``outputs`` with its labels, in a fixed order.

    Returns
    -------
    list of dict
        ``name`` (unit in it), ``quantity``, ``speed_krpm`` (NaN for an onset),
        ``voltage_V`` (NaN for the case's own voltages), ``actuator`` (1-based,
        0 when not per actuator).
    """
    nan = float("nan")
    out = []
    st = outputs.get("static")
    if st:
        for v in st["voltages_V"]:
            for w in st["speeds_rad_s"]:
                labels = {"speed_krpm": w / RPM / 1e3, "voltage_V": nan if v is None else v}
                for q in STATIC_QUANTITIES:
                    out.append(
                        {"name": f"{q}[{where_read(w, v)}]", "quantity": q, **labels, "actuator": 0}
                    )
                for a in range(n_actuators):
                    out.append(
                        {
                            "name": f"preload_um[{where_read(w, v, a)}]",
                            "quantity": "preload_um",
                            **labels,
                            "actuator": a + 1,
                        }
                    )
    stab = outputs.get("stability")
    if stab:
        for v in stab["voltages_V"]:
            for q in STABILITY_QUANTITIES:
                out.append(
                    {
                        "name": f"{q}[{where_read(None, v)}]",
                        "quantity": q,
                        "speed_krpm": nan,
                        "voltage_V": nan if v is None else v,
                        "actuator": 0,
                    }
                )
    orb = outputs.get("orbit")
    if orb:
        for v in orb["voltages_V"]:
            where = _orbit_where(v, orb["voltage_ramp_s"])
            for q in ORBIT_QUANTITIES:
                out.append(
                    {
                        "name": f"{q}[{where}]",
                        "quantity": q,
                        "speed_krpm": nan,
                        "voltage_V": nan if v is None else v,
                        "actuator": 0,
                    }
                )
    return out


def evaluate_sample(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    """Static readouts and linear onsets of one sampled case.

    Parameters
    ----------
    case
        The sampled case.
    options
        The uncertainty file's outputs (:func:`~foilbearing.uncertainty.spec.load_uncertainty`):
        ``static`` (speeds, rad/s; voltages, V or None) and ``stability``
        (scan speeds, rad/s; voltages).

    Returns
    -------
    dict
        ``outputs`` (name → value or None), ``message`` (why some are None),
        ``converged`` (False when none could be computed).
    """
    values: dict[str, float | None] = {}
    why: list[str] = []
    if options.get("static"):
        static_outputs(case, options["static"], values, why)
    if options.get("stability"):
        stability_outputs(case, options["stability"], values, why)
    if options.get("orbit"):
        _orbit(case, options["orbit"], values, why)
    ok = any(v is not None for v in values.values())
    return {"outputs": values, "message": "; ".join(why), "converged": ok}


def at_voltages(case: Case, volt: float | None) -> Case:
    """``case`` with every actuator at ``volt`` (V); None: the case's own voltages."""
    return case if volt is None else case.with_voltages(volt)


def static_outputs(
    case: Case, opts: Mapping[str, Any], values: dict[str, Any], why: list[str]
) -> None:
    from foilbearing.analysis.equilibrium import solve_equilibrium
    from foilbearing.film import film_model

    n_act = len(case.actuators.angles) if case.actuators is not None else 0
    for volt in opts["voltages_V"]:
        c = at_voltages(case, volt)
        model, start = film_model(c), None
        for w in opts["speeds_rad_s"]:  # increasing: each equilibrium starts from the last
            st = solve_equilibrium(c, speed=w, model=model, start=start)
            if not st.converged and start is not None:
                st = solve_equilibrium(c, speed=w, model=model)
            where = where_read(w, volt)
            if not st.converged:
                why.append(f"no equilibrium at {where}: {st.message}")
                for q in STATIC_QUANTITIES:
                    values[f"{q}[{where}]"] = None
                for a in range(n_act):
                    values[f"preload_um[{where_read(w, volt, a)}]"] = None
                continue
            start = (st.eps_x, st.eps_y, st.P)
            values[f"eccentricity_ratio[{where}]"] = st.eccentricity
            values[f"attitude_deg[{where}]"] = math.degrees(st.attitude_angle)
            values[f"min_film_um[{where}]"] = st.min_film * 1e6
            values[f"power_loss_W[{where}]"] = st.power_loss
            for a in range(n_act):
                values[f"preload_um[{where_read(w, volt, a)}]"] = float(st.preload[a]) * 1e6


def stability_outputs(
    case: Case,
    opts: Mapping[str, Any],
    values: dict[str, Any],
    why: list[str],
    *,
    rel_tol: float = ONSET_REL_TOL,
    near: Mapping[str, float | None] | None = None,
) -> None:
    """The linear onset (krpm) and whirl frequency (Hz) of ``case`` at each of ``opts``'
    voltages over its scan (rad/s), found to Brent's ``rel_tol``, into ``values`` by name;
    why any is None, into ``why``. ``near``: each onset's value on a coarser grid, krpm, by
    name (:func:`foilbearing.check.onset_near` scans a bracket around it first)."""
    from foilbearing.check import onset_near

    speeds = opts["speeds_rad_s"]
    for volt in opts["voltages_V"]:
        where = where_read(None, volt)
        onset = whirl = None
        coarse = (near or {}).get(f"onset_speed_krpm[{where}]")
        try:
            res = onset_near(
                at_voltages(case, volt), speeds, None if coarse is None else coarse * 1e3 * RPM,
                rel_tol=rel_tol,
            )  # fmt: skip
        except (InputError, SolverError) as exc:
            why.append(f"no onset at {where}: {exc}")
        else:
            if res.onset_speed is None:
                why.append(f"stable over the scan at {where} (up to {speeds[-1] / RPM:.0f} rpm)")
            elif res.onset_speed <= speeds[0]:
                why.append(f"unstable already at {speeds[0] / RPM:.0f} rpm at {where}")
            else:
                onset = res.onset_speed / RPM / 1e3
                whirl = (res.whirl_frequency or float("nan")) / (2.0 * math.pi)
        values[f"onset_speed_krpm[{where}]"] = onset
        values[f"whirl_frequency_Hz[{where}]"] = whirl


def _orbit(case: Case, opts: Mapping[str, Any], values: dict[str, Any], why: list[str]) -> None:
    """One speed-up per voltage, read as ``foilbearing orbit`` reads it (default settings)."""
    from foilbearing.control import linear_ramp, voltage_ramp
    from foilbearing.orbit import simulate
    from foilbearing.orbit.analysis import analyse_orbit

    profile = linear_ramp(*opts["speed_ramp"])
    ramp = opts["voltage_ramp_s"]
    for volt in opts["voltages_V"]:
        where = _orbit_where(volt, ramp)
        c, program = case, None
        if volt is not None and ramp is None:
            c = case.with_voltages(volt)
        elif volt is not None:
            program = voltage_ramp(ramp[0], ramp[1], volt)
        result = simulate(c, profile, program)
        head = analyse_orbit(result).headline(result)
        onset, div = head["onset_speed_rpm"], head["divergence_speed_rpm"]
        values[f"orbit_onset_krpm[{where}]"] = None if onset is None else onset / 1e3
        values[f"orbit_whip_frequency_Hz[{where}]"] = head["whip_frequency_Hz"]
        values[f"orbit_divergence_krpm[{where}]"] = None if div is None else div / 1e3
        values[f"orbit_max_subsync_um[{where}]"] = head["max_subsync_amplitude_um"]
        if result.status not in ("completed", "contact"):
            why.append(f"speed-up at {where} {result.status}: {result.message}")
        elif div is None:
            end = head["end_speed_rpm"] or 0.0
            why.append(f"speed-up at {where}: no divergence up to {end:.0f} rpm")
        if onset is None:
            why.append(f"speed-up at {where}: no sustained sub-synchronous motion")
