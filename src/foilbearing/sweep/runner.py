"""Parameter sweeps on Dask: a grid of bearing cases, one task per point.

A sweep file (``docs/sweep-format.md``) names a case, an analysis kind and the
swept parameters: any case field by dotted path, or ``speed``, ``voltage``,
``voltage[i]``. Each point's case is the case file's tables with the point's
values written in, validated by :func:`~foilbearing.case.case_from_dict` like a
case file; all points are validated before any work. Each point is one pure
task (:func:`run_point`); the client writes each finished point atomically to
``RESULT.d/points/`` as it completes, and :func:`assemble` gathers them into
one xarray Dataset (NetCDF, ``RESULT.nc``) with the parameters as dimensions.

This module runs and assembles; the sweep file is read and validated in
:mod:`foilbearing.sweep.spec`, and the analysis kinds are the entries of
:data:`foilbearing.sweep.analyses.ANALYSES` (a new kind is one more entry);
both are re-exported here. The results folder is read back, and checked, in
:mod:`foilbearing.sweep.records`; the Dask client is made in
:mod:`foilbearing.sweep.cluster`.
"""

from __future__ import annotations

import json
import math
import time
import uuid
from collections.abc import Callable, Mapping
from contextlib import nullcontext
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from foilbearing.case import Case, case_from_dict
from foilbearing.errors import InputError
from foilbearing.io import write_text, write_with
from foilbearing.sweep.analyses import ANALYSES, Analysis
from foilbearing.sweep.cluster import client as _client
from foilbearing.sweep.records import (
    MANIFEST,
    base_record,
    case_change,
    done_points,
    notice,
    point_file,
    read_manifest,
    same_sweep,
    stored_fingerprint,
)
from foilbearing.sweep.spec import FIELD_KINDS, Parameter, SweepSpec, load_sweep

__all__ = [
    "ANALYSES",
    "FIELD_KINDS",
    "Analysis",
    "Parameter",
    "PointSet",
    "SweepSpec",
    "assemble",
    "done_points",
    "load_sweep",
    "output_paths",
    "run_point",
    "run_points",
    "run_sweep",
    "stored_fingerprint",
]

# --------------------------------------------------------------------------- running


def run_point(
    index: int,
    case_data: dict[str, Any],
    source: str,
    evaluate: Callable[[Case, Mapping[str, Any]], dict[str, Any]],
    options: Mapping[str, Any],
) -> dict[str, Any]:
    """Evaluate one point: the Dask task. Pure: the same inputs give the same record.

    A failure of the point's physics (no equilibrium, contact, a solver that did not
    converge) is its result, stored as "failed"; a failure of the machine (out of
    memory, a file system error) is raised: it is no result, and the point stays to be
    computed (as are points lost to the cluster, :func:`run_points`).

    Returns
    -------
    dict
        ``index``, ``status`` ("ok" or "failed"), ``error`` (message, "" if ok),
        ``result`` (the analysis headline, JSON-able) and ``elapsed_s``.
    """
    t0 = time.perf_counter()
    result: dict[str, Any] = {}
    try:
        result = evaluate(case_from_dict(case_data, source=source), options)
        ok = result.get("converged", True) is not False
        status, error = ("ok", "") if ok else ("failed", str(result.get("message", "")))
    except (MemoryError, OSError):
        raise
    except Exception as exc:
        status, error = "failed", f"{type(exc).__name__}: {exc}"
    return {
        "index": index,
        "status": status,
        "error": error,
        "result": _jsonable(result),
        "elapsed_s": time.perf_counter() - t0,
    }


def _jsonable(x: Any) -> Any:
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple | np.ndarray):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.generic):
        x = x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def output_paths(out: str | Path) -> tuple[Path, Path]:
    """The results folder ``RESULT.d`` and the dataset ``RESULT.nc`` of ``--out RESULT``."""
    out = Path(out)
    stem = out.with_suffix("") if out.suffix in (".nc", ".d") else out
    return stem.with_name(stem.name + ".d"), stem.with_name(stem.name + ".nc")


def _prepare(
    spec: PointSet, folder: Path, resume: bool, compute: bool
) -> dict[int, dict[str, Any]]:
    """The valid records already in ``folder`` (a new folder: its manifest written).

    The manifest must be there and this sweep's, its recorded case (if it has one, an
    earlier version's has none) the one the points start from now
    (:func:`~.records.case_change`); damaged records are set aside to be computed again
    when ``compute``, else an error (:func:`~.records.done_points`). A new manifest
    records the case as data (``base_case``, :func:`~.records.base_record`).
    """
    meta = folder / MANIFEST
    points = folder / "points"
    if meta.exists() or points.exists():
        if not resume:
            raise InputError(
                f"results folder {folder} exists: pass --resume to continue it, "
                "or choose another --out"
            )
        if meta.exists() or any(points.glob("*.json")):
            manifest = read_manifest(folder)
            changed = case_change(manifest, spec, folder)
            if changed is not None:
                raise InputError(changed)
            if not same_sweep(manifest, spec):
                raise InputError(
                    f"results folder {folder} holds another sweep or sample (different case, "
                    "analysis, parameters or inputs): choose another --out"
                )
            return done_points(folder, spec, set_aside=compute)
    write_text(
        meta,
        json.dumps(
            {
                "fingerprint": spec.fingerprint(),
                **spec.describe(),
                "base_case": base_record(spec).to_dict(),
            },
            indent=1,
            default=str,
        ),
    )
    return {}


class PointSet(Protocol):
    """What the runner needs of a set of points: a sweep's grid, an uncertainty sample.

    Each point is a case (its tables, validated by
    :func:`~foilbearing.case.case_from_dict`) evaluated by one pure function.
    """

    @property
    def options(self) -> dict[str, Any]: ...

    @property
    def n_points(self) -> int: ...

    @property
    def base(self) -> dict[str, Any]: ...

    @property
    def case_file(self) -> str: ...

    @property
    def source(self) -> str: ...

    def point_data(self, index: int) -> dict[str, Any]: ...

    def point_source(self, index: int) -> str: ...

    def point_values(self, index: int) -> dict[str, Any]: ...

    def fingerprint(self) -> str: ...

    def describe(self) -> dict[str, Any]: ...


def run_points(
    points: PointSet,
    folder: Path,
    evaluate: Callable[[Case, Mapping[str, Any]], dict[str, Any]],
    *,
    client: Any = None,
    scheduler: str | None = None,
    n_workers: int | None = None,
    dashboard: bool = False,
    resume: bool = False,
    compute: bool = True,
    progress: bool = False,
    on_point: Callable[[dict[str, Any]], None] | None = None,
) -> dict[str, Any]:
    """Evaluate every point of ``points`` on Dask, writing each to ``folder/points/``.

    The engine of :func:`run_sweep` and of the uncertainty analysis. Points
    already in ``folder`` are skipped with ``resume`` (the folder's fingerprint
    must match); with ``compute`` False nothing is evaluated. Parameters as
    :func:`run_sweep`.

    A point lost to the cluster (a worker that died for good, ``KilledWorker``; a
    timeout; a cancelled task; a worker's ``MemoryError`` or ``OSError``) is not a
    result: it is not written, one line says so, and ``resume`` computes it.

    Returns
    -------
    dict
        n_computed (points evaluated, lost ones included), n_skipped, n_failed (of all
        points in the folder), n_lost.
    """
    from tqdm import tqdm

    done = _prepare(points, folder, resume, compute)
    todo = [i for i in range(points.n_points) if i not in done] if compute else []
    n_failed = sum(r["status"] != "ok" for r in done.values())
    bar = tqdm(
        total=points.n_points,
        initial=len(done),
        unit="pt",
        disable=not progress,
        dynamic_ncols=True,
    )
    bar.set_postfix(failed=n_failed)
    n_lost = 0
    try:
        if todo:
            prefix = uuid.uuid4().hex[:12]
            pool = (
                _client(scheduler, n_workers, dashboard=dashboard)
                if client is None
                else nullcontext(client)
            )
            with pool as cl:
                failed, n_lost = _run_points(
                    points, todo, folder, cl, evaluate, prefix, bar, on_point
                )
                n_failed += failed
    finally:
        bar.close()
    return {
        "n_computed": len(todo),
        "n_skipped": len(done),
        "n_failed": n_failed,
        "n_lost": n_lost,
    }


def run_sweep(
    spec: SweepSpec,
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
) -> dict[str, Any]:
    """Run every point of ``spec`` on Dask, persisting each as it completes.

    Parameters
    ----------
    spec
        The validated sweep (:func:`load_sweep`).
    out
        ``RESULT``: points go to ``RESULT.d/points/``, the Dataset to ``RESULT.nc``.
    client
        A ``distributed.Client`` to use; else one on ``scheduler`` (an address),
        else a new ``LocalCluster`` of ``n_workers`` single-thread processes
        (default: one per core), listening on 127.0.0.1 only.
    dashboard
        Start the new local cluster's dashboard, on 127.0.0.1 at a free port,
        and print its address on stderr (default: no dashboard).
    resume
        Continue the sweep in ``RESULT.d``, skipping the points already there.
    compute
        False: only assemble the points already there (with ``resume``).
    progress
        A tqdm bar on stderr: points done, failed, ETA.
    on_point
        Called with each record after it is written (e.g. to watch a run).

    A point lost to the cluster (a worker that died for good, ``KilledWorker``; a
    timeout; a cancelled task; a worker's ``MemoryError`` or ``OSError``) is not a
    result: it is not written, one line says so, and ``resume`` computes it.

    Returns
    -------
    dict
        n_points, n_ok, n_failed, n_missing, n_computed, n_skipped,
        results_folder, dataset, wall_time_s.
    """
    t0 = time.perf_counter()
    folder, nc_path = output_paths(out)
    run = run_points(
        spec,
        folder,
        ANALYSES[spec.analysis].evaluate,
        client=client,
        scheduler=scheduler,
        n_workers=n_workers,
        dashboard=dashboard,
        resume=resume,
        compute=compute,
        progress=progress,
        on_point=on_point,
    )
    ds = assemble(spec, out)
    status = ds["status"].values
    return {
        "n_points": spec.n_points,
        "n_ok": int((status == "ok").sum()),
        "n_failed": int((status == "failed").sum()),
        "n_missing": int((status == "missing").sum()),
        "n_computed": run["n_computed"],
        "n_skipped": run["n_skipped"],
        "results_folder": str(folder),
        "dataset": str(nc_path),
        "wall_time_s": time.perf_counter() - t0,
    }


def _run_points(
    spec: PointSet,
    todo: list[int],
    folder: Path,
    client: Any,
    evaluate: Callable[..., dict[str, Any]],
    prefix: str,
    bar: Any,
    on_point: Callable[[dict[str, Any]], None] | None,
) -> tuple[int, int]:
    """Submit ``todo``, write each record as it completes; returns (n_failed, n_lost)."""
    from asyncio import CancelledError

    from distributed import as_completed

    futures = {
        client.submit(
            run_point,
            i,
            spec.point_data(i),
            spec.point_source(i),
            evaluate,
            spec.options,
            key=f"sweep-point-{i}-{prefix}",  # new per run: a cancelled key may linger
        ): i
        for i in todo
    }
    n_failed = n_lost = 0
    try:
        for fut in as_completed(futures):
            i = futures[fut]
            if fut.cancelled():  # cancelled from outside: stays missing, --resume runs it
                continue
            try:
                rec = _gather(fut)
            except (Exception, CancelledError) as exc:  # run_point keeps the point's own
                n_lost += 1
                bar.clear()
                why = str(exc).split(". ")[0]  # KilledWorker's first sentence of five
                notice(
                    f"point {i} lost to the cluster ({type(exc).__name__}: {why}): not stored, "
                    "--resume computes it"
                )
                bar.refresh()
                fut.release()
                continue
            fut.release()
            rec["parameters"] = spec.point_values(i)
            write_text(point_file(folder, i), json.dumps(rec, indent=1))
            n_failed += rec["status"] != "ok"
            bar.update(1)
            bar.set_postfix(failed=n_failed)
            if on_point is not None:
                on_point(rec)
    finally:
        client.cancel([f for f in futures if not f.done()])
    return n_failed, n_lost


def _gather(future: Any) -> dict[str, Any]:
    """The record of a finished point's task (raises what lost it: ``KilledWorker``, ...)."""
    return dict(future.result())


# --------------------------------------------------------------------------- assembling


def assemble(spec: SweepSpec, out: str | Path, *, write: bool = True) -> Any:
    """Gather the point files into one xarray Dataset (and write ``RESULT.nc``).

    Dimensions are the swept parameters (coordinates in the units written in
    the sweep file, attribute ``units``), plus any dimension of list-valued
    results (``actuator``, ``axis``, ``frequency``). Every headline value is a
    variable, NaN / "" / False where a point is not ok (a list empty at every point, such
    as the voltages of a bearing without actuators, is left out); ``status`` is "ok",
    "failed" or "missing" and ``error`` the failure message.

    Notes
    -----
    The arrays are filled by point index: a one-point Dataset per point joined
    with ``xarray.combine_by_coords`` (or ``concat`` and ``unstack``) gives the same
    grid 15 to 45 times slower (about 2-3 s against 60 ms for 400 points of a
    static sweep, xarray 2026.9), before restoring each variable's type.
    """
    import xarray as xr

    folder, nc_path = output_paths(out)
    records = done_points(folder, spec) if (folder / "points").exists() else {}
    shape, n = spec.shape, spec.n_points
    dims = tuple(p.dim for p in spec.parameters)
    status = np.full(n, "missing", dtype=object)
    error = np.full(n, "", dtype=object)
    elapsed = np.full(n, np.nan)
    for i, rec in records.items():
        status[i], error[i] = rec["status"], rec.get("error", "")
        elapsed[i] = np.nan if rec.get("elapsed_s") is None else rec["elapsed_s"]
    ok = {i: rec["result"] for i, rec in records.items() if rec["status"] == "ok"}
    layout = ANALYSES[spec.analysis].layout
    list_dims, extra = layout(spec.options) if layout is not None else ({}, {})
    data_vars: dict[str, Any] = {
        "status": (dims, status.astype(str).reshape(shape)),
        "error": (dims, error.astype(str).reshape(shape)),
        "point_time_s": (dims, elapsed.reshape(shape), {"units": "s"}),
    }
    keys = list(dict.fromkeys(k for r in ok.values() for k in r))
    for key in keys:
        vals = [ok[i].get(key) if i in ok else None for i in range(n)]
        if any(v == [] for v in vals) and not any(v for v in vals if isinstance(v, list)):
            continue  # an empty list at every point (no actuators): NetCDF 3 has no empty dim
        data_vars[key] = _variable(key, vals, dims, shape, list_dims)
    coords: dict[str, Any] = {
        p.dim: (p.dim, list(p.coords), {"units": p.unit, "parameter": p.name})
        for p in spec.parameters
    }
    used = {d for var in data_vars.values() for d in var[0]}
    for dim, (values, units) in extra.items():
        if dim in used:
            coords[dim] = (dim, list(values), {"units": units} if units else {})
    ds = xr.Dataset(data_vars, coords=coords)
    ds.attrs.update(
        title=spec.title,
        analysis=spec.analysis,
        sweep_file=spec.source,
        case_file=spec.case_file,
        options=json.dumps(spec.options),
        fingerprint=spec.fingerprint(),
    )
    if write:
        write_with(nc_path, lambda tmp: ds.to_netcdf(tmp))
    return ds


def _variable(
    key: str, vals: list[Any], dims: tuple[str, ...], shape: tuple[int, ...], list_dims: Any
) -> tuple[Any, ...]:
    present = [v for v in vals if v is not None]
    if any(isinstance(v, list) for v in present):
        width = max(len(v) for v in present)
        arr = np.full((len(vals), width), np.nan)
        for i, v in enumerate(vals):
            if v:
                arr[i, : len(v)] = [np.nan if x is None else x for x in v]
        return (*dims, list_dims.get(key, f"{key}_index")), arr.reshape(*shape, width)
    if present and all(isinstance(v, bool) for v in present):
        return dims, np.array([bool(v) for v in vals]).reshape(shape)
    if any(isinstance(v, str) for v in present):
        return dims, np.array(["" if v is None else str(v) for v in vals]).reshape(shape)
    return dims, np.array([np.nan if v is None else float(v) for v in vals]).reshape(shape)
