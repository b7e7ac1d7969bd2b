"""The study's uncertainty stage (beyond the paper): envelopes of what the paper leaves open.

The built-in uncertainty file (``foilbearing/cases/uncertainty_paper.toml``: viscosity,
rotor mass, loss factor, clearance and imbalance as distributions) is sampled under one of
:data:`UNCERTAINTY_PLANS` on a local Dask cluster; the envelopes (5th, 50th and 95th
percentiles) and sensitivity indices of its static readouts and linear onsets are written
beside the study's results, and with ``grid_check`` each output's grid error at the centre
of the inputs (:mod:`foilbearing.uncertainty.grid`).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

__all__ = ["UNCERTAINTY_PLANS", "uncertainty_plan", "uncertainty_stage"]

#: The study's uncertainty stage: (evaluations, estimator, sampler), None for the file's
#: own. "quick" is RBD-FAST on a 64-point Latin hypercube: the Sobol' estimator on the
#: 8 base rows such a budget allows gave first-order indices up to 2.07 (issue 33;
#: docs/uncertainty.md measures both against the full plan). "full" is the file's own,
#: 252 points with the Sobol' estimator (first-order and total indices).
UNCERTAINTY_PLANS: dict[str, tuple[int | None, str | None, str | None]] = {
    "quick": (64, "rbd_fast", "lhs"),
    "full": (None, None, None),
}


def uncertainty_plan(plan: str) -> Any:
    """The built-in uncertainty file's sample under the study's ``plan`` ("quick" or "full")."""
    from foilbearing.uncertainty import load_uncertainty

    samples, estimator, sampler = UNCERTAINTY_PLANS[plan]
    return load_uncertainty(samples=samples, estimator=estimator, sampler=sampler)


def uncertainty_stage(
    out: Path, plan: str, stage: Callable[[str], None], *, grid_check: int = 1
) -> dict[str, Any]:
    """Envelopes and sensitivity indices of what the paper leaves open (issue 15).

    ``grid_check`` (2 or more): the static and stability outputs solved again at the centre
    of the inputs on that many times the cells, each one's grid error in the summary's
    ``grid_check`` (:func:`foilbearing.uncertainty.grid.grid_errors`); 1: not checked.
    """
    from foilbearing.output.figures import write_uncertainty_figures
    from foilbearing.uncertainty import run_uncertainty

    samples, estimator, sampler = UNCERTAINTY_PLANS[plan]
    spec = uncertainty_plan(plan)
    stage(
        f"uncertainty: {spec.n_points} evaluations of {len(spec.inputs)} uncertain inputs "
        f"({spec.estimator} estimator) on a local Dask cluster"
    )
    tail = "" if estimator is None else f"_{estimator}_{sampler}"
    folder = out / f"uncertainty_{spec.n_points}pts{tail}"  # a rerun of the same sample resumes it
    ds, summary = run_uncertainty(
        spec, folder, resume=folder.exists(), grid_check=grid_check, progress=False
    )
    if "grid_check" in summary:
        check = summary["grid_check"]
        stage(
            f"  grid check at the inputs' centre ({check['grid'][0]} x {check['grid'][1]} "
            f"against {check['refined_grid'][0]} x {check['refined_grid'][1]}): "
            f"{check['wall_time_s']:.0f} s"
        )
    summary["figures"] = [str(p) for p in write_uncertainty_figures(ds, out)]
    summary["command"] = " ".join(
        ["foilbearing uncertainty"]
        + ([f"--estimator {estimator}"] if estimator is not None else [])
        + ([f"--sampler {sampler}"] if sampler is not None else [])
        + ([f"--samples {spec.samples}"] if samples is not None else [])
        + (["--grid-check"] if grid_check > 1 else [])
        + [f"--out {folder}"]
    )
    return summary
