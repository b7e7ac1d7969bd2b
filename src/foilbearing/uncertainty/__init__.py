"""What the unknowns allow: uncertainty envelopes and sensitivity indices.

An uncertainty file (``docs/uncertainty.md``) puts distributions on case
fields nobody knows exactly (viscosity, rotor mass, loss factor, clearance,
imbalance, ...) and names the outputs: static readouts at chosen speeds and
voltages, linear onset speed and whirl frequency at chosen voltages. The
sample (:mod:`~foilbearing.uncertainty.design`) runs on the sweep's Dask
machinery, each finished point written as it completes; the result is the
5th, 50th and 95th percentiles of every output and its sensitivity indices
per input (:mod:`~foilbearing.uncertainty.result`).

============  ==================================================================================
module        responsibility
============  ==================================================================================
``spec``      the uncertainty file: uncertain inputs, their distributions, the outputs and the
              sample
``design``    the sample design and the sensitivity estimators
``evaluate``  one sample point: every output for one case
``result``    percentiles and sensitivity indices of every output, as a Dataset and as JSON
``grid``      the grid's error of the outputs, at the centre of the inputs
============  ==================================================================================
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from foilbearing.errors import InputError
from foilbearing.io import write_text, write_with
from foilbearing.sweep.runner import done_points, run_points
from foilbearing.uncertainty.evaluate import evaluate_sample
from foilbearing.uncertainty.result import summarise, summary_json
from foilbearing.uncertainty.spec import UncertaintySpec, default_uncertainty_path, load_uncertainty

__all__ = [
    "UncertaintySpec",
    "default_uncertainty_path",
    "load_uncertainty",
    "result_paths",
    "run_uncertainty",
    "summarise",
    "summary_json",
]


def result_paths(out: str | Path) -> dict[str, Path]:
    """The files of an uncertainty run in folder ``out``: points, dataset, JSON."""
    out = Path(out)
    return {
        "folder": out,
        "points": out / "points",
        "dataset": out / "uncertainty.nc",
        "json": out / "uncertainty.json",
    }


def run_uncertainty(
    spec: UncertaintySpec,
    out: str | Path,
    *,
    client: Any = None,
    scheduler: str | None = None,
    n_workers: int | None = None,
    dashboard: bool = False,
    resume: bool = False,
    compute: bool = True,
    progress: bool = False,
    on_point: Callable[[dict[str, Any]], None] | None = None,
    grid_check: int = 1,
) -> tuple[Any, dict[str, Any]]:
    """Evaluate the sample on Dask and summarise it.

    Parameters
    ----------
    spec
        The validated analysis (:func:`load_uncertainty`).
    out
        Results folder: ``points/`` (one JSON per point, written as each
        finishes), ``uncertainty.nc`` and ``uncertainty.json`` (written
        atomically when the sample is done, or stopped).
    client, scheduler, n_workers, dashboard, resume, compute, progress, on_point
        As :func:`foilbearing.sweep.runner.run_sweep`.
    grid_check
        With 2 or more, the static and stability outputs are solved again at the centre of
        the inputs on the case's grid and on that many times its cells
        (:func:`foilbearing.uncertainty.grid.grid_errors`), after the sample: the summary's
        ``grid_check``, each output's discretisation error. 1: not checked.

    Returns
    -------
    (Dataset, dict)
        The summary Dataset and its JSON (:func:`summary_json`) with
        ``n_computed``, ``n_skipped``, ``dataset``, ``wall_time_s`` (and ``grid_check``)
        added.
    """
    t0 = time.perf_counter()
    paths = result_paths(out)
    try:
        run = run_points(
            spec,
            paths["folder"],
            evaluate_sample,
            client=client,
            scheduler=scheduler,
            n_workers=n_workers,
            dashboard=dashboard,
            resume=resume,
            compute=compute,
            progress=progress,
            on_point=on_point,
        )
    except InputError:  # nothing computed: leave the folder as it is
        raise
    except BaseException:  # a stopped run keeps what it computed: the summary so far
        _write_summary(spec, paths, {}, t0)
        raise
    check = None
    if grid_check > 1 and compute:
        from foilbearing.uncertainty.grid import grid_errors

        check = grid_errors(spec, grid_check, progress=_say if progress else None)
    return _write_summary(spec, paths, run, t0, check)


def _say(line: str) -> None:
    import sys

    print(line, file=sys.stderr)


def _write_summary(
    spec: UncertaintySpec,
    paths: dict[str, Path],
    run: dict[str, Any],
    t0: float,
    grid_check: dict[str, Any] | None = None,
) -> tuple[Any, dict[str, Any]]:
    records = done_points(paths["folder"], spec) if paths["points"].exists() else {}
    ds = summarise(spec, records)
    write_with(paths["dataset"], lambda tmp: ds.to_netcdf(tmp))
    summary = summary_json(ds)
    summary.update(
        n_computed=run.get("n_computed"),
        n_skipped=run.get("n_skipped"),
        dataset=str(paths["dataset"]),
        wall_time_s=time.perf_counter() - t0,
    )
    if grid_check is not None:
        summary["grid_check"] = grid_check
    write_text(paths["json"], json.dumps(summary, indent=1))
    return ds, summary
