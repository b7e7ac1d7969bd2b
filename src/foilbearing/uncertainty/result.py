"""Percentiles and sensitivity indices of every output, as a Dataset and as JSON.

:func:`summarise` gathers the sample's point records into an xarray Dataset:
the design ``x(sample, input)``, the outputs ``y(sample, output)``, the 5th, 50th
and 95th percentiles of each output over the points where it was computed, and
the sensitivity indices ``first_order`` / ``total_order (output, input)`` with
their 95 % bootstrap half-widths (:func:`foilbearing.uncertainty.design.indices`).
Every reported index lies in [0, 1] or is NaN with the status ``not estimable``
(:func:`foilbearing.uncertainty.design.screen`); ``*_raw`` keeps the estimator's
own numbers, and the attributes name the estimator and the sample size.
"""

from __future__ import annotations

import json
import math
import warnings
from typing import Any

import numpy as np

from foilbearing.uncertainty.design import RBD_HARMONICS, describe_estimator, indices, screen
from foilbearing.uncertainty.evaluate import output_names
from foilbearing.uncertainty.spec import UncertaintySpec

__all__ = ["PERCENTILES", "summarise", "summary_json"]

PERCENTILES = (5.0, 50.0, 95.0)
#: What the index statuses mean, in the JSON and the report.
INDEX_NOTE = (
    "A first-order or total index lies in [0, 1]. An estimate outside it whose 95 % "
    "half-width reaches back into [0, 1] is clipped to the nearer end ('clipped'); one "
    "whose interval lies wholly outside, or that could not be computed, is null "
    "('not estimable' at this sample size). '*_raw' is the estimator's own number."
)


def summarise(spec: UncertaintySpec, records: dict[int, dict[str, Any]]) -> Any:
    """The analysis as an xarray Dataset (see the module docstring).

    ``records`` are the point records by index (``run_points``' files); points
    not there are ``missing``, points that failed ``failed``; both count as
    NaN in every output.
    """
    import xarray as xr

    n_act = len(spec.base.get("actuators", {}).get("angles", []))
    outs = output_names(spec.outputs, n_act)
    names = [o["name"] for o in outs]
    n, m = spec.n_points, len(outs)
    y = np.full((n, m), np.nan)
    status = np.full(n, "missing", dtype=object)
    error = np.full(n, "", dtype=object)
    for i, rec in records.items():
        status[i] = rec["status"]
        res = rec.get("result") or {}
        error[i] = rec.get("error") or res.get("message", "")
        values = res.get("outputs", {}) if rec["status"] == "ok" else {}
        for j, name in enumerate(names):
            v = values.get(name)
            if v is not None:
                y[i, j] = float(v)
    inputs = [inp.name for inp in spec.inputs]
    d = len(inputs)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # an output never computed: NaN
        pct = np.nanpercentile(y, PERCENTILES, axis=0) if n else np.full((3, m), np.nan)
    s1, s1c, st, stc = (np.full((m, d), np.nan) for _ in range(4))
    n_used = np.zeros(m, dtype=int)
    for j in range(m):
        idx = indices(spec.estimator, inputs, spec.design, y[:, j], spec.seed)
        s1[j], s1c[j], n_used[j] = idx["first_order"], idx["first_order_conf"], idx["n_used"]
        if "total_order" in idx:
            st[j], stc[j] = idx["total_order"], idx["total_order_conf"]
    first, first_conf, first_status = screen(s1, s1c)
    total, total_conf, total_status = screen(st, stc)
    if spec.estimator != "sobol":  # no total index: NaN, not "not estimable"
        total_status[:] = ""
    scale = np.array([inp.scale for inp in spec.inputs])
    ds = xr.Dataset(
        {
            "x": (("sample", "input"), spec.design / scale, {"long_name": "input value"}),
            "y": (("sample", "output"), y, {"long_name": "output value (unit in its name)"}),
            "status": ("sample", status.astype(str)),
            "error": ("sample", error.astype(str)),
            "percentile": (("quantile", "output"), pct),
            "n_valid": ("output", np.isfinite(y).sum(axis=0)),
            "n_used": ("output", n_used, {"long_name": "evaluations the indices used"}),
            "first_order": (("output", "input"), first, {"long_name": "in [0, 1], or NaN"}),
            "first_order_conf": (("output", "input"), first_conf, {"long_name": "95 % half-width"}),
            "first_order_status": (("output", "input"), first_status.astype(str)),
            "first_order_raw": (("output", "input"), s1, {"long_name": "the estimator's own"}),
            "total_order": (("output", "input"), total, {"long_name": "in [0, 1], or NaN"}),
            "total_order_conf": (("output", "input"), total_conf, {"long_name": "95 % half-width"}),
            "total_order_status": (("output", "input"), total_status.astype(str)),
            "total_order_raw": (("output", "input"), st, {"long_name": "the estimator's own"}),
        },
        coords={
            "sample": np.arange(n),
            "input": inputs,
            "input_unit": ("input", [inp.unit or "1" for inp in spec.inputs]),
            "input_distribution": ("input", [_describe(inp) for inp in spec.inputs]),
            "output": names,
            "quantity": ("output", [o["quantity"] for o in outs]),
            "speed_krpm": ("output", [o["speed_krpm"] for o in outs], {"units": "krpm"}),
            "voltage_V": ("output", [o["voltage_V"] for o in outs], {"units": "V"}),
            "actuator": ("output", [o["actuator"] for o in outs]),
            "quantile": ("quantile", list(PERCENTILES), {"units": "%"}),
        },
        attrs={
            "title": spec.title,
            "uncertainty_file": spec.source,
            "case_file": spec.case_file,
            "estimator": spec.estimator,
            "indices_from": describe_estimator(spec.estimator, n, d),
            "rbd_harmonics": RBD_HARMONICS if spec.estimator == "rbd_fast" else 0,
            "sampler": spec.sampler,
            "seed": spec.seed,
            "samples": spec.samples,
            "n_points": n,
            "outputs": json.dumps(spec.outputs),
            "fingerprint": spec.fingerprint(),
        },
    )
    return ds


def _describe(inp: Any) -> str:
    d, s, u = inp.distribution, inp.scale, inp.unit
    if d.kind == "normal":
        return f"normal(mean {d.a / s:.6g}, σ {d.b / s:.6g}) {u}".rstrip()
    return f"{d.kind}({d.a / s:.6g}, {d.b / s:.6g}) {u}".rstrip()


def _num(x: Any) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def summary_json(ds: Any) -> dict[str, Any]:
    """The JSON of ``foilbearing uncertainty --json``.

    ``{"outputs": {NAME: {"p5", "p50", "p95", "n_valid", "n_used", "first_order":
    {INPUT: …}, "first_order_conf", "first_order_status", "first_order_raw",
    "total_order", … (Sobol only)}}, "indices": {"estimator", "n_points",
    "description", "note"}, "inputs", "estimator", "sampler", "n_points", "n_ok",
    "n_failed", "n_missing"}``; NaN is null. Every index is in [0, 1] or null;
    its status says ``ok``, ``clipped`` or ``not estimable``.
    """
    inputs = [str(i) for i in ds["input"].values]
    estimator = ds.attrs["estimator"]
    kinds = ("first_order", "total_order") if estimator == "sobol" else ("first_order",)
    outputs: dict[str, Any] = {}
    for j, name in enumerate(ds["output"].values):
        entry: dict[str, Any] = {
            f"p{q:g}": _num(ds["percentile"].values[k, j]) for k, q in enumerate(PERCENTILES)
        }
        entry["n_valid"] = int(ds["n_valid"].values[j])
        entry["n_used"] = int(ds["n_used"].values[j])
        for kind in kinds:
            for key in (kind, f"{kind}_conf", f"{kind}_raw"):
                row = ds[key].values[j]
                entry[key] = {i: _num(v) for i, v in zip(inputs, row, strict=True)}
            row = ds[f"{kind}_status"].values[j]
            entry[f"{kind}_status"] = {i: str(v) for i, v in zip(inputs, row, strict=True)}
        outputs[str(name)] = entry
    status = ds["status"].values
    return {
        "outputs": outputs,
        "indices": {
            "estimator": estimator,
            "n_points": int(ds.attrs["n_points"]),
            "description": str(ds.attrs.get("indices_from", estimator)),
            "note": INDEX_NOTE,
        },
        "inputs": {
            i: {"unit": str(u), "distribution": str(dist)}
            for i, u, dist in zip(
                inputs, ds["input_unit"].values, ds["input_distribution"].values, strict=True
            )
        },
        "estimator": estimator,
        "sampler": ds.attrs["sampler"],
        "n_points": int(ds.attrs["n_points"]),
        "n_ok": int((status == "ok").sum()),
        "n_failed": int((status == "failed").sum()),
        "n_missing": int((status == "missing").sum()),
    }
