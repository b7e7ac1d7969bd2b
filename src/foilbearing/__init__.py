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
    print(fb.grid_check(case, onset_speeds=onset.speeds))  # the same on twice the cells
    run = fb.simulate(case, fb.linear_ramp(3e3 * fb.RPM, 90e3 * fb.RPM, 500.0))

===================  ===========================================================================
module               responsibility
===================  ===========================================================================
``case/``            the bearing case: frozen dataclasses (SI), the case file's schema, reader
                     and record
``structure/``       structure models: PZT stack and actuator springs, bump foil, stiffness
                     k(θ), preload shape r_p(θ)
``identification/``  the PZT stack's parameters identified from measured stack data
``laws/``            the modelling laws, one a module, each in every form the analyses use
``film``             the film model of a case: journal position, preload shape and foil
                     compliance on the grid
``bearing_system/``  one bearing built once from a case: its scales, its film model and the
                     three verbs equilibrium, coefficients and transient
``reynolds/``        finite-volume solvers of the Reynolds equation: steady, perturbed,
                     transient
``analysis/``        the analyses of the bearing at a speed: equilibrium, force coefficients,
                     linear stability
``static``           moved: the same module as ``analysis/equilibrium``, under its old name
``coefficients``     moved: the same module as ``analysis/coefficients``, under its old name
``stability``        moved: the same module as ``analysis/stability``, under its old name
``integrate/``       BDF time integration over callables: step loop, stop events, record
                     callback, the one Newton policy; no bearing words
``orbit/``           the nonlinear orbit of the journal during a speed-up (BDF in physical time)
``signals``          signal analysis of a speed-up orbit: waterfall, sub-synchronous amplitude,
                     onset, divergence
``bifurcation/``     periodic orbits past a Hopf point: shooting, Floquet multipliers,
                     continuation
``rotor/``           rotors on foil bearings: a shaft of beam elements with disks, linear and
                     nonlinear
``control/``         speed and voltage programs in time: speed profiles, actuator voltage
                     programs, the closed-loop preload controller, the schedule file
``design/``          design beyond the paper: the stack's stiffness, the actuator voltages by
                     optimisation, the voltage schedule in speed
``optimize``         moved: the same module as ``design/voltages``, under its old name
``schedule``         moved: the same module as ``design/schedule_search``, under its old name
``schedule_file``    moved: the same module as ``control/schedule_file``, under its old name
``check``            how far to trust a case's numbers: its headline readouts on its grid and on
                     refined grids
``study/``           studies: the paper's full analysis and the same analysis of any bearing
``sweep/``           parameter sweeps on Dask, from a laptop to a cluster
``uncertainty/``     uncertainty envelopes and sensitivity indices of a case's readouts
``paper``            the paper's reported numbers and ours beside them
``paper_dynamics``   the paper's onset and orbit rows, ours beside them, with the reasons
``headline``         headlines: the unit-named numbers of a result, read off its Dataset
``output/``          what the user reads: summaries, figures and the HTML report
``export/``          export to other rotordynamics tools (ROSS)
``cli/``             the ``foilbearing`` command, one module per subcommand family
``units``            quantities at the edges: ``"100 um"``, ``"90000 rpm"`` parsed once, to SI
``constants``        conversion constants (everything inside the package is SI)
``errors``           errors a user can act on: bad input (``InputError``, exit 2), a solve that
                     did not converge (``SolverError``, exit 3)
``io``               atomic writes: a result is either there whole or not at all
``warmup``           compiles the film kernels once, ahead of the first run
``__main__``         ``python -m foilbearing`` is the ``foilbearing`` command
``testing/``         test oracles (NumPy twins, ``solve_ivp`` references): tests import them,
                     production never
===================  ===========================================================================
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from foilbearing.constants import RPM
from foilbearing.errors import InputError, SolverError

if TYPE_CHECKING:
    from foilbearing.analysis.coefficients import force_coefficients
    from foilbearing.analysis.equilibrium import solve_equilibrium
    from foilbearing.analysis.stability import onset_speed, stability_map, whirl_mode
    from foilbearing.bearing_system.scales import Scales
    from foilbearing.bearing_system.verbs import BearingSystem
    from foilbearing.case import Case, default_case, load_case
    from foilbearing.check import grid_check
    from foilbearing.control import constant_speed, linear_ramp, voltage_ramp
    from foilbearing.design.schedule_search import voltage_schedule
    from foilbearing.orbit import OrbitSettings, simulate
    from foilbearing.orbit.analysis import analyse_orbit
    from foilbearing.study.paper import run_study
    from foilbearing.sweep.runner import run_sweep
    from foilbearing.uncertainty import run_uncertainty

#: Public name -> module that defines it (imported on first access, PEP 562).
_LAZY = {
    "Case": "foilbearing.case",
    "default_case": "foilbearing.case",
    "load_case": "foilbearing.case",
    "BearingSystem": "foilbearing.bearing_system.verbs",
    "Scales": "foilbearing.bearing_system.scales",
    "solve_equilibrium": "foilbearing.analysis.equilibrium",
    "force_coefficients": "foilbearing.analysis.coefficients",
    "whirl_mode": "foilbearing.analysis.stability",
    "onset_speed": "foilbearing.analysis.stability",
    "stability_map": "foilbearing.analysis.stability",
    "grid_check": "foilbearing.check",
    "simulate": "foilbearing.orbit",
    "OrbitSettings": "foilbearing.orbit",
    "analyse_orbit": "foilbearing.orbit.analysis",
    "constant_speed": "foilbearing.control",
    "linear_ramp": "foilbearing.control",
    "voltage_ramp": "foilbearing.control",
    "run_sweep": "foilbearing.sweep.runner",
    "run_study": "foilbearing.study.paper",
    "run_uncertainty": "foilbearing.uncertainty",
    "voltage_schedule": "foilbearing.design.schedule_search",
}

__all__ = [
    "RPM",
    "BearingSystem",
    "Case",
    "InputError",
    "OrbitSettings",
    "Scales",
    "SolverError",
    "analyse_orbit",
    "constant_speed",
    "default_case",
    "force_coefficients",
    "grid_check",
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
