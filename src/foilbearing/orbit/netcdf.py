"""Orbit runs on disk: NetCDF with the time series, the run specification and the checkpoint."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.errors import InputError

__all__ = ["load_orbit", "to_netcdf"]


def to_netcdf(result: Any, spec: dict[str, Any], path: Path) -> None:
    """Write a run (``OrbitResult``) and its specification to ``path`` (NetCDF)."""
    ds = result.to_dataset()
    ds.attrs["run_spec"] = json.dumps(spec)
    ds.to_netcdf(path)


def load_orbit(path: Path) -> tuple[Any, dict[str, Any]]:
    """Read a saved run: the ``OrbitResult`` (with its checkpoint) and the run specification."""
    import xarray as xr

    from foilbearing.case import load_case
    from foilbearing.orbit import OrbitResult, OrbitSettings

    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError) as exc:
        raise InputError(
            f"cannot read the run ({exc.__class__.__name__})", source=str(path)
        ) from None
    if "run_spec" not in ds.attrs or "checkpoint_y" not in ds:
        raise InputError("not a foilbearing orbit file with a checkpoint", source=str(path))
    spec = json.loads(ds.attrs["run_spec"])
    case = load_case(spec["case"])
    if spec.get("subambient") is not None:
        case = case.with_subambient(spec["subambient"])
    a = ds.attrs
    settings = OrbitSettings(
        steps_per_rev=int(a["steps_per_rev"]),
        order=int(a.get("bdf_order", 2)),  # files written before the order was stored: BDF2
        max_step=float(a["max_step_s"]),
        sample_rate=float(a["sample_rate_Hz"]),
        contact_film=float(a["contact_film"]),
    )
    names = [str(k) for k in ds.data_vars]
    checkpoint = {
        k.removeprefix("checkpoint_"): np.asarray(ds[k].values)
        for k in names
        if k.startswith("checkpoint_")
    }
    result = OrbitResult(
        case,
        settings,
        ds.time.values,
        ds.e_x.values * 1e-6,
        ds.e_y.values * 1e-6,
        ds.speed.values * math.pi / 30.0,
        ds.phase.values,
        ds.min_film.values * 1e-6,
        ds.voltage.values,
        str(a["status"]),
        str(a["message"]),
        float(a["wall_time_s"]),
        int(a["steps"]),
        int(a["factorizations"]),
        int(a["newton_iterations"]),
        checkpoint=checkpoint,
        power_loss=ds.power_loss.values if "power_loss" in ds else None,
    )
    if result.status in ("completed", "contact"):
        raise InputError(
            f"the run already ended ({result.message}): nothing to resume", source=str(path)
        )
    return result, spec
