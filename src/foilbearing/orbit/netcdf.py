"""Orbit runs on disk: NetCDF with the time series, the run specification and the checkpoint."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.orbit.spec import RunSpec

__all__ = ["load_orbit", "to_netcdf"]


def to_netcdf(result: Any, spec: RunSpec, path: Path) -> None:
    """Write a run (``OrbitResult``) and its specification to ``path`` (NetCDF).

    The specification is the ``run_spec`` attribute, as :meth:`RunSpec.to_json`, with
    the case recorded as data: a specification made without one records the case the
    run ran on (``result.case``), so the file resumes on that case by construction.
    """
    if spec.recorded_case is None:
        spec = spec.with_case(result.case)
    ds = result.to_dataset()
    ds.attrs["run_spec"] = spec.to_json()
    ds.to_netcdf(path)


#: SI factor of each unit an orbit file may hold (files before SI datasets held um and rpm).
_TO_SI = {"m": 1.0, "um": 1e-6, "rad": 1.0, "rad/s": 1.0, "rpm": RPM}

#: The time series of an orbit file, each of which must be finite.
_SERIES = ("e_x", "e_y", "speed", "phase", "min_film")


def _si(ds: Any, name: str) -> np.ndarray:
    """Variable ``name`` of the dataset in SI, by its ``units`` attribute."""
    unit = ds[name].attrs.get("units", "m")
    if unit not in _TO_SI:
        raise ValueError(f"{name} has units {unit!r}: expected one of {', '.join(_TO_SI)}")
    return np.asarray(ds[name].values, float) * _TO_SI[unit]


def _notice(line: str) -> None:
    print(f"foilbearing: note: {line}", file=sys.stderr)


def load_orbit(path: Path, notice: Callable[[str], None] = _notice) -> tuple[Any, RunSpec]:
    """Read a saved run: the ``OrbitResult`` (with its checkpoint) and its :class:`RunSpec`.

    The file is SI (:meth:`OrbitResult.to_dataset`); files written before the
    datasets were SI (e_x, e_y, min_film in µm, speed in rpm) are read by their
    ``units`` attributes, and the command-line strings that earlier versions
    stored as the specification by :meth:`RunSpec.from_cli_strings`.

    The run's case is the one its specification recorded, whatever its case file
    holds now; a case file that has changed since the run started is reported by one
    line to ``notice`` (default: stderr). A file of an earlier version, which recorded
    only the case file's path, rebuilds the case from that file.

    Raises
    ------
    InputError
        Naming the file: not an orbit file with a checkpoint; a run that already ended
        (completed or contact), nothing to resume; or a damaged file: a run specification
        that is cut, altered (its case does not match its sha256) or not one; an unknown
        status; a checkpoint time outside the run's profile or before its last sample; a
        state or time series that is not finite or not of the run's shape.
    """
    import xarray as xr

    source = str(path)
    try:
        ds = xr.load_dataset(path)
    except (OSError, ValueError) as exc:
        raise InputError(f"cannot read the run ({exc.__class__.__name__})", source=source) from None
    if "run_spec" not in ds.attrs or "checkpoint_y" not in ds:
        raise InputError("not a foilbearing orbit file with a checkpoint", source=source)
    try:
        spec = RunSpec.from_json(ds.attrs["run_spec"])
    except InputError as exc:
        raise InputError(exc.detail, source=source) from None
    if spec.recorded_case is None:  # an earlier version's file: the case from its file
        try:
            case = spec.load_case()
        except InputError as exc:
            raise InputError(
                f"this file (from an earlier version) records only its case file's path, "
                f"and that does not give the case: {exc}",
                source=source,
            ) from None
    else:
        try:
            case = spec.load_case()
        except InputError as exc:
            raise InputError(
                f"run specification's recorded case: {exc.detail}", source=source
            ) from None
        line = spec.recorded_case.changes(spec.case)
        if line is not None:
            notice(line)
    try:
        result = _result(ds, case, spec)
    except (KeyError, TypeError, ValueError) as exc:
        what = f"{exc} is missing" if isinstance(exc, KeyError) else str(exc)
        raise InputError(f"damaged orbit file: {what}", source=source) from None
    if not result.status.resumable:
        raise InputError(
            f"the run already ended ({result.message}): nothing to resume (a run stopped by "
            "--stop-time or interrupted resumes); to run on, start it again with a longer "
            "--duration or --speed-ramp",
            source=source,
        )
    return result, spec


#: The largest film pressure p/p_a, and journal or foil displacement in units of C, a
#: checkpoint's state may hold: 10⁴ atmospheres and 10³ clearances are no state of a gas
#: bearing, and a state of that size (1e300 from a damaged file) would overflow the film's
#: Jacobian into a traceback instead of a one-line error.
STATE_BOUNDS = (1e4, 1e3)


def _check_state(name: str, y: Any, n: int, omega_max: float) -> None:
    """A finite state (P, U, ε, v) of ``n`` pressures that a bearing can be in: 0 < P ≤ 10⁴,
    |U|, |ε| ≤ 10³ C and |v| ≤ 10³ C times the run's top speed (rad/s).

    Raises
    ------
    ValueError
        Naming the part of the state out of range and its worst value.
    """
    p_max, x_max = STATE_BOUNDS
    pressure, v = y[:n], y[-2:]
    if not (pressure.min() > 0.0 and pressure.max() <= p_max):
        worst = pressure.min() if pressure.min() <= 0.0 else pressure.max()
        raise ValueError(
            f"{name} holds a film pressure p/p_a = {worst:.3g}: expected 0 < p/p_a <= {p_max:g}"
        )
    displacement = np.abs(y[n:-2]).max()
    if displacement > x_max:
        raise ValueError(
            f"{name} holds a journal or foil displacement of {displacement:.3g} C: expected "
            f"at most {x_max:g} C"
        )
    v_max = x_max * max(omega_max, 1.0)
    if np.abs(v).max() > v_max:
        raise ValueError(
            f"{name} holds a journal velocity of {np.abs(v).max():.3g} C/s: expected at most "
            f"{x_max:g} C times the run's top speed, {v_max:.3g} C/s"
        )


def _result(ds: Any, case: Any, spec: RunSpec) -> Any:
    """The run of the dataset on ``case``, its checkpoint checked against the run.

    Raises
    ------
    KeyError, TypeError, ValueError
        What of the file is missing, mistyped, not finite, out of range or mis-shaped.
    """
    from foilbearing.orbit.result import OrbitResult, RunStatus
    from foilbearing.orbit.system import OrbitSimulation

    a = ds.attrs
    status = str(a["status"])
    if status not in {s.value for s in RunStatus}:
        raise ValueError(
            f"status = {status!r}: expected one of " + ", ".join(s.value for s in RunStatus)
        )
    names = [str(k) for k in ds.data_vars]
    checkpoint = {
        k.removeprefix("checkpoint_"): np.asarray(ds[k].values, float)
        for k in names
        if k.startswith("checkpoint_")
    }
    t0, t_end = spec.speed_times[0], spec.speed_times[-1]
    if "t" not in checkpoint:
        raise ValueError("checkpoint_t is missing")
    if checkpoint["t"].size != 1 or not t0 <= float(checkpoint["t"][0]) <= t_end:
        raise ValueError(
            f"checkpoint_t = {checkpoint['t'].tolist()}: expected one time within the run's "
            f"profile, {t0:g} to {t_end:g} s"
        )
    t_check = float(checkpoint["t"][0])
    built = spec.build(case)
    system = OrbitSimulation(built.case, built.profile, None, built.settings).system
    size = system.size
    for key, value in checkpoint.items():
        is_state = key == "y" or key.startswith("y_prev")
        if is_state and value.shape != (size,):
            raise ValueError(
                f"checkpoint_{key} holds {value.size} values: the run's case has {size} states"
            )
        if key.startswith("h_prev") and not (value.size == 1 and value[0] > 0.0):
            raise ValueError(f"checkpoint_{key} = {value.tolist()}: expected one step > 0 s")
        if key != "triggered_at" and not np.all(np.isfinite(value)):  # NaN: not triggered
            raise ValueError(f"checkpoint_{key} holds values that are not finite")
        if is_state:
            _check_state(f"checkpoint_{key}", value, system.n, float(np.max(spec.speeds)))
    time = np.asarray(ds.time.values, float)
    series = {name: _si(ds, name) for name in _SERIES}
    # a bearing without actuators writes no voltage (a zero-length dimension does not
    # round-trip through NetCDF)
    voltages = np.asarray(ds.voltage.values, float) if "voltage" in ds else np.zeros((time.size, 0))
    for name, values in (("time", time), *series.items(), ("voltage", voltages)):
        if not np.all(np.isfinite(values)):
            raise ValueError(f"{name} holds values that are not finite")
    if np.any(np.diff(time) <= 0.0) or (time.size and time[-1] > t_check * (1 + 1e-12)):
        raise ValueError(f"time is not increasing up to the checkpoint at t = {t_check:g} s")
    return OrbitResult(
        case,
        spec.settings,
        time,
        series["e_x"],
        series["e_y"],
        series["speed"],
        series["phase"],
        series["min_film"],
        voltages,
        RunStatus(status),
        str(a["message"]),
        float(a["wall_time_s"]),
        int(a["steps"]),
        int(a["factorizations"]),
        int(a["newton_iterations"]),
        checkpoint=checkpoint,
        power_loss=ds.power_loss.values if "power_loss" in ds else None,
    )


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
