"""Analysis kinds of a parameter sweep: what each grid point computes.

:data:`ANALYSES` maps a kind's name (the sweep file's ``analysis``) to an
:class:`Analysis`: the pure function evaluated at each point, the parser of its
options table and the layout of its list-valued results. A new kind is one
more entry (``docs/sweep-format.md``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from foilbearing.case import Case
from foilbearing.errors import InputError
from foilbearing.units import parse_quantity

__all__ = ["ANALYSES", "FLAG_KEYS", "TEXT_KEYS", "Analysis"]

#: Result keys whose values are words (a point's record is checked against these when
#: read back, :mod:`foilbearing.sweep.records`); every other key holds numbers.
TEXT_KEYS = frozenset({"bearing", "message", "bifurcation_type"})
#: Result keys whose values are true or false (a scalar or one per cycle).
FLAG_KEYS = frozenset({"converged", "stable"})


def value_list(raw: Any, kind: str, where: str, src: str) -> tuple[Any, ...]:
    """A list of values in a sweep file, in SI.

    ``kind`` is a quantity kind of :data:`~foilbearing.units.SI_UNITS` or
    ``"integer"`` or ``"choice"`` (a word such as ``"lobe"``, checked where the case is
    built); ``where`` names the key for messages.
    """
    if not isinstance(raw, list):
        raise InputError(f"{where} = {raw!r}: expected a list", source=src)
    out: list[Any] = []
    for k, v in enumerate(raw):
        if kind == "choice":
            if not isinstance(v, str):
                raise InputError(f"{where}[{k}] = {v!r}: expected a word, e.g. 'lobe'", source=src)
            out.append(v)
        elif kind == "integer":
            if isinstance(v, bool) or not isinstance(v, int):
                raise InputError(f"{where}[{k}] = {v!r}: expected an integer", source=src)
            out.append(v)
        else:
            out.append(parse_quantity(v, kind, field=f"{where}[{k}]", source=src))
    return tuple(out)


@dataclass(frozen=True)
class Analysis:
    """One analysis kind a sweep can run at each point.

    Attributes
    ----------
    evaluate
        ``evaluate(case, options) -> dict``: the headline numbers of one point,
        unit-named keys; values are scalars (float, int, bool, str, None) or
        1-D lists: words only under :data:`TEXT_KEYS`, true/false only under
        :data:`FLAG_KEYS`, finite numbers (or None) under every other key. A
        ``converged`` key that is False marks the point failed,
        with its ``message``. Must be a module-level function (Dask pickles it
        by reference) and pure.
    parse_options
        ``parse_options(table, source) -> dict``: checks the sweep file's table
        named after the kind; the JSON-able result is passed to ``evaluate``.
        None: the kind takes no options.
    layout
        ``layout(options) -> (dims, coords)``: the dimension of each list-valued
        key and ``{dim: (values, units)}`` for those dimensions (None: none).
    fixed
        Case fields the analysis sets itself, which a sweep may not vary.
    """

    evaluate: Callable[[Case, Mapping[str, Any]], dict[str, Any]]
    parse_options: Callable[[Mapping[str, Any], str], dict[str, Any]] | None = None
    layout: Callable[[Mapping[str, Any]], tuple[dict[str, str], dict[str, Any]]] | None = None
    fixed: tuple[str, ...] = ()


def _static(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    from foilbearing.analysis.equilibrium import solve_equilibrium

    return solve_equilibrium(case).headline()


_ACTUATOR_KEYS = ("voltages_V", "preload_um", "actuator_pressure_kPa")
_STATIC_DIMS = {**dict.fromkeys(_ACTUATOR_KEYS, "actuator"), "force_N": "axis"}


def _static_layout(options: Mapping[str, Any]) -> tuple[dict[str, str], dict[str, Any]]:
    return dict(_STATIC_DIMS), {"axis": (["X", "Y"], "")}


def _coefficients(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    from foilbearing.analysis.coefficients import force_coefficients
    from foilbearing.analysis.equilibrium import solve_equilibrium

    static = solve_equilibrium(case)
    out = static.headline()
    if not static.converged:
        return out
    if "frequencies_Hz" in options:
        freqs = 2.0 * math.pi * np.asarray(options["frequencies_Hz"])
    else:
        freqs = np.asarray(options["frequency_ratios"]) * static.speed
    fc = force_coefficients(static, freqs)
    for i, a in enumerate("XY"):
        for j, b in enumerate("XY"):
            out[f"K_{a}{b}_N_per_m"] = fc.K[:, i, j].tolist()
            out[f"C_{a}{b}_Ns_per_m"] = fc.C[:, i, j].tolist()
    return out


def _coefficient_options(table: Mapping[str, Any], source: str) -> dict[str, Any]:
    unknown = set(table) - {"frequencies", "frequency_ratios"}
    if unknown or len(table) > 1:
        raise InputError(
            f"[coefficients] {sorted(table)}: give one of 'frequencies' (e.g. ['100 Hz']) "
            "or 'frequency_ratios' (e.g. [0.5, 1.0], of the rotor speed)",
            source=source,
        )
    key = next(iter(table), "frequency_ratios")
    raw = table.get(key, [1.0])
    kind = "frequency" if key == "frequencies" else "dimensionless"
    values = value_list(raw, kind, f"coefficients.{key}", source)
    if any(v <= 0.0 for v in values):
        raise InputError(f"coefficients.{key} = {raw!r}: expected values > 0", source=source)
    return {"frequencies_Hz" if key == "frequencies" else "frequency_ratios": values}


def _coefficient_layout(options: Mapping[str, Any]) -> tuple[dict[str, str], dict[str, Any]]:
    dims, coords = _static_layout(options)
    if "frequencies_Hz" in options:
        dim, coord = "frequency", (options["frequencies_Hz"], "Hz")
    else:
        dim, coord = "frequency_ratio", (options["frequency_ratios"], "1")
    for ij in ("XX", "XY", "YX", "YY"):
        dims[f"K_{ij}_N_per_m"] = dims[f"C_{ij}_Ns_per_m"] = dim
    return dims, {**coords, dim: coord}


def _stability(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    from foilbearing.analysis.stability import onset_speed

    return onset_speed(case, options["speeds_rad_s"]).headline()


def _stability_options(table: Mapping[str, Any], source: str) -> dict[str, Any]:
    if set(table) - {"speed_range"}:
        raise InputError(
            f"[stability] {sorted(table)}: the only option is speed_range", source=source
        )
    raw = table.get("speed_range", ["5000 rpm", "150000 rpm", "5000 rpm"])
    return {"speeds_rad_s": speed_scan(raw, "stability.speed_range", source)}


def speed_scan(raw: Any, where: str, source: str) -> list[float]:
    """The scan speeds (rad/s) of ``[START, STOP, STEP]`` in a sweep or uncertainty file."""
    if not isinstance(raw, list) or len(raw) != 3:
        raise InputError(
            f"{where} = {raw!r}: expected [START, STOP, STEP], "
            "e.g. ['5000 rpm', '150000 rpm', '5000 rpm']",
            source=source,
        )
    start, stop, step = value_list(raw, "speed", where, source)
    if not 0.0 < start < stop or step <= 0.0 or (stop - start) / step > 1000:
        raise InputError(
            f"{where} = {raw!r}: need 0 < START < STOP, STEP > 0, at most 1000 steps",
            source=source,
        )
    n = round((stop - start) / step) + 1
    return [start + k * step for k in range(n)]


def _bifurcation(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    from foilbearing.bifurcation import ShootingError
    from foilbearing.bifurcation.bearing import whirl_branch_headline

    try:
        out, _branch = whirl_branch_headline(case, options["speeds_rad_s"], options["steps"])
    except ShootingError as exc:
        return {"converged": False, "message": f"shooting did not converge ({exc})"}
    return out


def _bifurcation_options(table: Mapping[str, Any], source: str) -> dict[str, Any]:
    if set(table) - {"speed_range", "steps"}:
        raise InputError(
            f"[bifurcation] {sorted(table)}: the options are speed_range and steps", source=source
        )
    raw = table.get("speed_range", ["5000 rpm", "150000 rpm", "2500 rpm"])
    steps = table.get("steps", 4)
    if isinstance(steps, bool) or not isinstance(steps, int) or not 0 <= steps <= 100:
        raise InputError(
            f"bifurcation.steps = {steps!r}: cycles after the two first, 0 to 100", source=source
        )
    return {"speeds_rad_s": speed_scan(raw, "bifurcation.speed_range", source), "steps": steps}


#: List-valued results of a branch, one value a cycle.
_CYCLE_KEYS = (
    "speeds_rpm",
    "amplitude_um",
    "min_film_um",
    "whirl_frequency_Hz",
    "stable",
    "largest_multiplier",
)


def _bifurcation_layout(options: Mapping[str, Any]) -> tuple[dict[str, str], dict[str, Any]]:
    dims = dict.fromkeys(_CYCLE_KEYS, "cycle") | {"grid": "grid_axis"}
    cycles = list(range(options["steps"] + 2))
    return dims, {"cycle": (cycles, ""), "grid_axis": (["n_theta", "n_z"], "")}


#: Analysis kinds by name. Add a kind (e.g. ``"orbit"``) with one more entry.
ANALYSES: dict[str, Analysis] = {
    "static": Analysis(_static, layout=_static_layout),
    "coefficients": Analysis(_coefficients, _coefficient_options, _coefficient_layout),
    "stability": Analysis(_stability, _stability_options, fixed=("operation.speed",)),
    "bifurcation": Analysis(
        _bifurcation, _bifurcation_options, _bifurcation_layout, fixed=("operation.speed",)
    ),
}
