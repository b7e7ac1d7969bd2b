"""Orbit runs on disk: NetCDF with the time series, the run specification and the checkpoint."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.orbit.spec import RunSpec

__all__ = ["load_orbit", "to_netcdf"]


def to_netcdf(result: Any, spec: RunSpec, path: Path) -> None:
    """Write a run (``OrbitResult``) and its specification to ``path`` (NetCDF).

    The specification is the ``run_spec`` attribute, as :meth:`RunSpec.to_json`.
    """
    ds = result.to_dataset()
    ds.attrs["run_spec"] = spec.to_json()
    ds.to_netcdf(path)


#: SI factor of each unit an orbit file may hold (files before SI datasets held um and rpm).
_TO_SI = {"m": 1.0, "um": 1e-6, "rad/s": 1.0, "rpm": RPM}


def _si(ds: Any, name: str) -> np.ndarray:
    """Variable ``name`` of the dataset in SI, by its ``units`` attribute."""
    return np.asarray(ds[name].values) * _TO_SI[ds[name].attrs.get("units", "m")]


def load_orbit(path: Path) -> tuple[Any, RunSpec]:
    """Read a saved run: the ``OrbitResult`` (with its checkpoint) and its :class:`RunSpec`.

    The file is SI (:meth:`OrbitResult.to_dataset`); files written before the
    datasets were SI (e_x, e_y, min_film in µm, speed in rpm) are read by their
    ``units`` attributes, and the command-line strings that earlier versions
    stored as the specification by :meth:`RunSpec.from_cli_strings`.

    Raises
    ------
    InputError
        Not an orbit file with a checkpoint, or a run that already ended
        (completed or contact): nothing to resume.
    """
    import xarray as xr

    from foilbearing.orbit.result import OrbitResult, RunStatus
    from foilbearing.orbit.settings import OrbitSettings

    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError) as exc:
        raise InputError(
            f"cannot read the run ({exc.__class__.__name__})", source=str(path)
        ) from None
    if "run_spec" not in ds.attrs or "checkpoint_y" not in ds:
        raise InputError("not a foilbearing orbit file with a checkpoint", source=str(path))
    spec = RunSpec.from_json(ds.attrs["run_spec"])
    case = spec.load_case()
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
        _si(ds, "e_x"),
        _si(ds, "e_y"),
        _si(ds, "speed"),
        ds.phase.values,
        _si(ds, "min_film"),
        ds.voltage.values if "voltage" in ds else np.zeros((ds.time.size, 0)),
        RunStatus(str(a["status"])),
        str(a["message"]),
        float(a["wall_time_s"]),
        int(a["steps"]),
        int(a["factorizations"]),
        int(a["newton_iterations"]),
        checkpoint=checkpoint,
        power_loss=ds.power_loss.values if "power_loss" in ds else None,
    )
    if not result.status.resumable:
        raise InputError(
            f"the run already ended ({result.message}): nothing to resume", source=str(path)
        )
    return result, spec


def read_subsync_envelope(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The sub-synchronous amplitude of a saved run against its speed: (rpm, m).

    Any orbit file, finished or not (:func:`foilbearing.signals.subsynchronous_amplitude`
    on its e_X, with the 1X removed by order tracking), for laying a speed-up's whirl
    over a branch of limit cycles.

    Raises
    ------
    InputError
        Not an orbit file, or a run too short for the analysis' 0.25 s windows.
    """
    import xarray as xr

    from foilbearing.signals import subsynchronous_amplitude

    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError) as exc:
        raise InputError(
            f"cannot read it as a run ({exc.__class__.__name__}): give an `orbit --out` "
            "NetCDF file",
            source=str(path),
        ) from None
    if not {"e_x", "speed", "phase"} <= set(map(str, ds.data_vars)):
        raise InputError("not a foilbearing orbit file (no e_x, speed, phase)", source=str(path))
    t = ds.time.values
    if t.size < 8 or t[-1] - t[0] < 1.0:
        raise InputError(
            f"the run lasts {t[-1] - t[0] if t.size else 0.0:.3g} s: too short for the "
            "sub-synchronous envelope (0.25 s windows); run a speed-up of 1 s or more",
            source=str(path),
        )
    sub = subsynchronous_amplitude(t, _si(ds, "e_x"), _si(ds, "speed"), ds.phase.values)
    return np.asarray(sub.speeds_rpm, float), np.asarray(sub.amplitude, float)
