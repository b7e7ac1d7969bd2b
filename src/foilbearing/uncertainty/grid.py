"""How far the grid moves an uncertainty analysis's outputs (issue 49: every printed number
with its error).

Every sample point is solved on the case's grid, so the percentiles carry the grid's
discretisation error as well as the inputs' spread. That error is nearly the same at every
point (a bias of the whole envelope, not a spread), so it is measured once, where the
inputs are at the centre of their distributions (each one's median): the outputs there on
the case's grid and on :func:`foilbearing.check.refined` grid (``factor`` times the cells
in θ and in Z, the axial order and the lift-off smoothing κ held), the error being their
difference (:func:`foilbearing.check.error_estimate` with two levels, as ``foilbearing
check`` states it). Onsets are found to a Brent tolerance of 1e-6 on both grids here, not
the sample's 1e-3, so that the difference is the grid's.

The readouts of speed-ups (``[outputs.orbit]``) are not checked: a refined speed-up costs
minutes; the study states their error from refined runs (docs/guide/accuracy.md).
"""

from __future__ import annotations

import copy
import time
from collections.abc import Callable
from typing import Any

from foilbearing.case import Case, case_from_dict
from foilbearing.sweep.spec import write_field
from foilbearing.uncertainty.evaluate import stability_outputs, static_outputs
from foilbearing.uncertainty.spec import UncertaintySpec
from foilbearing.units import si_text

__all__ = ["centre_case", "grid_errors"]

#: Brent's tolerance on the centre's onsets, relative to the speed: far below the grid's
#: error (0.5-2 % on 96 × 12), so the two grids' difference is not Brent's.
CENTRE_ONSET_TOL = 1e-6


def centre_values(spec: UncertaintySpec) -> dict[str, float]:
    """Each uncertain input's median, SI (the centre of a log-uniform one is its geometric
    mean)."""
    import numpy as np

    return {i.name: float(i.distribution.ppf(np.array([0.5]))[0]) for i in spec.inputs}


def centre_case(spec: UncertaintySpec) -> Case:
    """The case of the analysis with every uncertain input at its median."""
    data = copy.deepcopy(spec.base)
    kinds = {i.name: i.kind for i in spec.inputs}
    for name, value in centre_values(spec).items():
        write_field(data, name, si_text(value, kinds[name]))
    return case_from_dict(data, source=f"{spec.source}, the inputs at their medians")


def _outputs(
    case: Case, options: dict[str, Any], near: dict[str, float | None]
) -> tuple[dict[str, float | None], list[str]]:
    """The static and stability outputs of ``case`` (names as the sample's), and why some
    are None. ``near``: each onset's value on a coarser grid, krpm (its bracket)."""
    values: dict[str, float | None] = {}
    why: list[str] = []
    if options.get("static"):
        static_outputs(case, options["static"], values, why)
    if options.get("stability"):
        stability_outputs(
            case, options["stability"], values, why, rel_tol=CENTRE_ONSET_TOL, near=near
        )
    return values, why


def grid_errors(
    spec: UncertaintySpec, factor: int = 2, progress: Callable[[str], None] | None = None
) -> dict[str, Any]:
    """The static and stability outputs at the centre of the inputs on the case's grid and
    on ``factor`` times its cells, and each one's error on the case's grid.

    Returns
    -------
    dict
        ``grid`` and ``refined_grid`` ([n_θ, n_z]), ``centre`` (input → median, in the unit
        it was written in: ``centre_unit``), ``outputs`` (name → ``value`` on the case's
        grid, ``refined``, ``error`` (value − refined, None where either is None) and
        ``relative_error``),
        ``not_checked`` (the speed-up outputs), ``message`` (why some are None) and
        ``wall_time_s``.
    """
    from foilbearing.check import error_estimate, refined

    t0 = time.perf_counter()
    say = progress or (lambda _line: None)
    case = centre_case(spec)
    g = case.grid
    say(f"grid check at the inputs' centre: {g.n_theta} × {g.n_z}")
    coarse, why = _outputs(case, spec.options, {})
    fine_case = refined(case, factor)
    say(f"grid check at the inputs' centre: {fine_case.grid.n_theta} × {fine_case.grid.n_z}")
    fine, why_fine = _outputs(fine_case, spec.options, coarse)
    outputs: dict[str, Any] = {}
    for name, value in coarse.items():
        est = error_estimate([value, fine.get(name)])
        outputs[name] = {
            "value": value,
            "refined": fine.get(name),
            "error": est["error"],
            "relative_error": est["relative_error"],
        }
    orbit = spec.options.get("orbit")
    centre = centre_values(spec)
    return {
        "grid": [g.n_theta, g.n_z],
        "refined_grid": [fine_case.grid.n_theta, fine_case.grid.n_z],
        "centre": {i.name: centre[i.name] / i.scale for i in spec.inputs},
        "centre_unit": {i.name: i.unit for i in spec.inputs},
        "outputs": outputs,
        "not_checked": ["speed-up readouts"] if orbit else [],
        "message": "; ".join(why + [f"refined: {w}" for w in why_fine]),
        "wall_time_s": time.perf_counter() - t0,
    }
