"""foilbearing: gas foil bearings with piezoelectric preload control.

Reproduces and extends Park, Kim and Sim (2021), "Rotordynamic Analysis of
Piezoelectric Gas Foil Bearings with a Mechanical Preload Control Based on
Structural Parameter Identifications". The model, its conventions and every
modelling choice: ``docs/model.md``; the numerical methods: ``docs/numerics.md``.
SI units inside; quantities with units only at the edges (case files, CLI,
reports).

The main entry points, imported on first use (``import foilbearing`` itself
loads no numerics, so the command line starts quickly)::

    import foilbearing as fb

    case = fb.default_case().with_voltages(150.0)       # or fb.load_case("my.toml")
    st = fb.solve_equilibrium(case, speed=50_000 * fb.RPM)
    fc = fb.force_coefficients(st, [st.speed])          # K (N/m), C (N·s/m)
    onset = fb.onset_speed(case)                        # linear stability threshold
    run = fb.simulate(case, fb.linear_ramp(3e3 * fb.RPM, 90e3 * fb.RPM, 500.0))
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from foilbearing.constants import RPM
from foilbearing.errors import InputError, SolverError

if TYPE_CHECKING:
    from foilbearing.case import Case, default_case, load_case
    from foilbearing.coefficients import force_coefficients
    from foilbearing.control import constant_speed, linear_ramp, voltage_ramp
    from foilbearing.orbit import OrbitSettings, simulate
    from foilbearing.orbit.analysis import analyse_orbit
    from foilbearing.schedule import voltage_schedule
    from foilbearing.stability import onset_speed, stability_map, whirl_mode
    from foilbearing.static import solve_equilibrium
    from foilbearing.study.paper import run_study
    from foilbearing.sweep.runner import run_sweep
    from foilbearing.uncertainty import run_uncertainty

#: Public name -> module that defines it (imported on first access, PEP 562).
_LAZY = {
    "Case": "foilbearing.case",
    "default_case": "foilbearing.case",
    "load_case": "foilbearing.case",
    "solve_equilibrium": "foilbearing.static",
    "force_coefficients": "foilbearing.coefficients",
    "whirl_mode": "foilbearing.stability",
    "onset_speed": "foilbearing.stability",
    "stability_map": "foilbearing.stability",
    "simulate": "foilbearing.orbit",
    "OrbitSettings": "foilbearing.orbit",
    "analyse_orbit": "foilbearing.orbit.analysis",
    "constant_speed": "foilbearing.control",
    "linear_ramp": "foilbearing.control",
    "voltage_ramp": "foilbearing.control",
    "run_sweep": "foilbearing.sweep.runner",
    "run_study": "foilbearing.study.paper",
    "run_uncertainty": "foilbearing.uncertainty",
    "voltage_schedule": "foilbearing.schedule",
}

__all__ = [
    "RPM",
    "Case",
    "InputError",
    "OrbitSettings",
    "SolverError",
    "analyse_orbit",
    "constant_speed",
    "default_case",
    "force_coefficients",
    "linear_ramp",
    "load_case",
    "onset_speed",
    "run_study",
    "run_sweep",
    "run_uncertainty",
    "simulate",
    "solve_equilibrium",
    "stability_map",
    "voltage_ramp",
    "voltage_schedule",
    "whirl_mode",
]
__version__ = "0.1.0"


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'foilbearing' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
