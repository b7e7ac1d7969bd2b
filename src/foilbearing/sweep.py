"""Parameter sweeps on Dask: a grid of bearing cases, one task per point.

A sweep file (``docs/sweep-format.md``) names a case, an analysis kind and the
swept parameters: any case field by dotted path, or ``speed``, ``voltage``,
``voltage[i]``. Each point's case is the case file's tables with the point's
values written in, validated by :func:`~foilbearing.case.case_from_dict` like a
case file; all points are validated before any work. Each point is one pure
task (:func:`run_point`); the client writes each finished point atomically to
``RESULT.d/points/`` as it completes, and :func:`assemble` gathers them into
one xarray Dataset (NetCDF, ``RESULT.nc``) with the parameters as dimensions.
Analysis kinds are entries of :data:`ANALYSES`; a new kind is one more entry.
"""

from __future__ import annotations

import copy
import hashlib
import json
import logging
import math
import os
import re
import time
import tomllib
import uuid
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager, nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.case import Case, case_from_dict, default_case_path, load_case
from foilbearing.errors import InputError
from foilbearing.io import write_text, write_with
from foilbearing.units import SI_UNITS, parse_quantity, ureg

__all__ = [
    "ANALYSES",
    "FIELD_KINDS",
    "Analysis",
    "Parameter",
    "SweepSpec",
    "assemble",
    "load_sweep",
    "output_paths",
    "run_point",
    "run_sweep",
]

RPM = math.pi / 30.0  # rad/s per rpm

_KINDS_FIELDS = {
    "length": "bearing.radius bearing.length bearing.clearance foil.bump.thickness "
    "foil.bump.height foil.bump.pitch foil.bump.half_length actuators.holder_pre_extension "
    "shims.thickness",
    "dimensionless": "foil.loss_factor foil.bump.poisson_ratio foil.bump.friction_coefficient "
    "actuators.smoothness",
    "pressure": "gas.ambient_pressure foil.bump.youngs_modulus",
    "stiffness_per_area": "foil.bump_stiffness actuators.holder_spring_stiffness",
    "angle": "actuators.stinger_arc shims.arc",
    "voltage": "actuators.voltages actuators.max_voltage",
    "integer": "grid.n_theta grid.n_z",
    "viscosity": "gas.viscosity",
    "area": "actuators.contact_area",
    "length_per_voltage2": "actuators.d33_quadratic",
    "length_per_voltage": "actuators.d33_linear",
    "stiffness": "actuators.stack_stiffness",
    "mass": "rotor.mass",
    "mass_length": "rotor.imbalance",
    "force": "operation.load",
    "speed": "operation.speed",
}
#: Sweepable case fields (dotted TOML path) and the kind of quantity each takes.
FIELD_KINDS: dict[str, str] = {f: k for k, fs in _KINDS_FIELDS.items() for f in fs.split()}
ALIASES = {"speed": "operation.speed", "voltage": "actuators.voltages"}
_VOLTAGE_I = re.compile(r"^voltage\[(\d+)\]$")
_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*")


# --------------------------------------------------------------------------- analyses


@dataclass(frozen=True)
class Analysis:
    """One analysis kind a sweep can run at each point.

    Attributes
    ----------
    evaluate
        ``evaluate(case, options) -> dict``: the headline numbers of one point,
        unit-named keys; values are scalars (float, int, bool, str, None) or
        1-D lists. A ``converged`` key that is False marks the point failed,
        with its ``message``. Must be a module-level function (Dask pickles it
        by reference) and pure.
    parse_options
        ``parse_options(table, source) -> dict``: checks the sweep file's table
        named after the kind; the JSON-able result is passed to ``evaluate``.
        None: the kind takes no options.
    layout
        ``layout(options) -> (dims, coords)``: the dimension of each list-valued
        key and ``{dim: (values, units)}`` for those dimensions (None: none).
    fixed
        Case fields the analysis sets itself, which a sweep may not vary.
    """

    evaluate: Callable[[Case, Mapping[str, Any]], dict[str, Any]]
    parse_options: Callable[[Mapping[str, Any], str], dict[str, Any]] | None = None
    layout: Callable[[Mapping[str, Any]], tuple[dict[str, str], dict[str, Any]]] | None = None
    fixed: tuple[str, ...] = ()


def _static(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    from foilbearing.static import solve_equilibrium

    return solve_equilibrium(case).headline()


_ACTUATOR_KEYS = ("voltages_V", "preload_um", "actuator_pressure_kPa")
_STATIC_DIMS = {**dict.fromkeys(_ACTUATOR_KEYS, "actuator"), "force_N": "axis"}


def _static_layout(options: Mapping[str, Any]) -> tuple[dict[str, str], dict[str, Any]]:
    return dict(_STATIC_DIMS), {"axis": (["X", "Y"], "")}


def _coefficients(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    from foilbearing.coefficients import force_coefficients
    from foilbearing.static import solve_equilibrium

    static = solve_equilibrium(case)
    out = static.headline()
    if not static.converged:
        return out
    if "frequencies_Hz" in options:
        freqs = 2.0 * math.pi * np.asarray(options["frequencies_Hz"])
    else:
        freqs = np.asarray(options["frequency_ratios"]) * static.speed
    fc = force_coefficients(static, freqs)
    for i, a in enumerate("XY"):
        for j, b in enumerate("XY"):
            out[f"K_{a}{b}_N_per_m"] = fc.K[:, i, j].tolist()
            out[f"C_{a}{b}_Ns_per_m"] = fc.C[:, i, j].tolist()
    return out


def _coefficient_options(table: Mapping[str, Any], source: str) -> dict[str, Any]:
    unknown = set(table) - {"frequencies", "frequency_ratios"}
    if unknown or len(table) > 1:
        raise InputError(
            f"[coefficients] {sorted(table)}: give one of 'frequencies' (e.g. ['100 Hz']) "
            "or 'frequency_ratios' (e.g. [0.5, 1.0], of the rotor speed)",
            source=source,
        )
    key = next(iter(table), "frequency_ratios")
    raw = table.get(key, [1.0])
    kind = "frequency" if key == "frequencies" else "dimensionless"
    values = _value_list(raw, kind, f"coefficients.{key}", source)
    if any(v <= 0.0 for v in values):
        raise InputError(f"coefficients.{key} = {raw!r}: expected values > 0", source=source)
    return {"frequencies_Hz" if key == "frequencies" else "frequency_ratios": values}


def _coefficient_layout(options: Mapping[str, Any]) -> tuple[dict[str, str], dict[str, Any]]:
    dims, coords = _static_layout(options)
    if "frequencies_Hz" in options:
        dim, coord = "frequency", (options["frequencies_Hz"], "Hz")
    else:
        dim, coord = "frequency_ratio", (options["frequency_ratios"], "1")
    for ij in ("XX", "XY", "YX", "YY"):
        dims[f"K_{ij}_N_per_m"] = dims[f"C_{ij}_Ns_per_m"] = dim
    return dims, {**coords, dim: coord}


def _stability(case: Case, options: Mapping[str, Any]) -> dict[str, Any]:
    from foilbearing.stability import onset_speed

    return onset_speed(case, options["speeds_rad_s"]).headline()


def _stability_options(table: Mapping[str, Any], source: str) -> dict[str, Any]:
    if set(table) - {"speed_range"}:
        raise InputError(
            f"[stability] {sorted(table)}: the only option is speed_range", source=source
        )
    raw = table.get("speed_range", ["5000 rpm", "150000 rpm", "5000 rpm"])
    if not isinstance(raw, list) or len(raw) != 3:
        raise InputError(
            f"stability.speed_range = {raw!r}: expected [START, STOP, STEP], "
            "e.g. ['5000 rpm', '150000 rpm', '5000 rpm']",
            source=source,
        )
    start, stop, step = _value_list(raw, "speed", "stability.speed_range", source)
    if not 0.0 < start < stop or step <= 0.0 or (stop - start) / step > 1000:
        raise InputError(
            f"stability.speed_range = {raw!r}: need 0 < START < STOP, STEP > 0, at most 1000 steps",
            source=source,
        )
    n = round((stop - start) / step) + 1
    return {"speeds_rad_s": [start + k * step for k in range(n)]}


#: Analysis kinds by name. Add a kind (e.g. ``"orbit"``) with one more entry.
ANALYSES: dict[str, Analysis] = {
    "static": Analysis(_static, layout=_static_layout),
    "coefficients": Analysis(_coefficients, _coefficient_options, _coefficient_layout),
    "stability": Analysis(_stability, _stability_options, fixed=("operation.speed",)),
}


# --------------------------------------------------------------------------- the sweep file


@dataclass(frozen=True)
class Parameter:
    """One swept parameter: its values as written, in SI, and as coordinates.

    ``coords`` are the values in ``unit``, the unit of the first value as
    written (SI for plain numbers); ``dim`` is the Dataset dimension name.
    """

    name: str  # as written: "speed", "bearing.clearance", "voltage[1]"
    path: str  # the case field: "operation.speed"
    index: int | None  # actuator index of voltage[i]
    kind: str
    raw: tuple[Any, ...]
    values: tuple[Any, ...]  # SI
    unit: str
    coords: tuple[Any, ...]

    @property
    def dim(self) -> str:
        """Dimension name: the name with ``.`` and ``[i]`` as ``_`` (``voltage_1``)."""
        return re.sub(r"[.\[]", "_", self.name).rstrip("]")


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: base case tables, analysis, parameters (grid in C order)."""

    source: str
    title: str
    case_file: str
    base: dict[str, Any]
    analysis: str
    options: dict[str, Any]
    parameters: tuple[Parameter, ...]

    @property
    def shape(self) -> tuple[int, ...]:
        """Number of values of each parameter."""
        return tuple(len(p.values) for p in self.parameters)

    @property
    def n_points(self) -> int:
        """Number of grid points."""
        return math.prod(self.shape)

    def point_values(self, index: int) -> dict[str, Any]:
        """The point's parameter values as written, by parameter name."""
        ijk = np.unravel_index(index, self.shape)
        return {p.name: p.raw[int(i)] for p, i in zip(self.parameters, ijk, strict=True)}

    def point_source(self, index: int) -> str:
        """Where a point comes from, for messages: file, index and values."""
        vals = ", ".join(f"{k} = {v!r}" for k, v in self.point_values(index).items())
        return f"{self.source}, point {index} ({vals})"

    def point_data(self, index: int) -> dict[str, Any]:
        """The case tables of point ``index`` (a new dict)."""
        data = copy.deepcopy(self.base)
        ijk = np.unravel_index(index, self.shape)
        for p, i in zip(self.parameters, ijk, strict=True):
            _write_field(data, p.path, p.raw[int(i)], p.index)
        return data

    def point_case(self, index: int) -> Case:
        """The validated case of point ``index``."""
        return case_from_dict(self.point_data(index), source=self.point_source(index))

    def fingerprint(self) -> str:
        """SHA-256 of everything that determines the results."""
        key = [self.base, self.analysis, self.options, [(p.name, p.raw) for p in self.parameters]]
        return hashlib.sha256(json.dumps(key, sort_keys=True, default=str).encode()).hexdigest()


def load_sweep(path: str | Path) -> SweepSpec:
    """Read a sweep file and validate every point of its grid.

    Raises
    ------
    InputError
        Bad TOML, unknown table or key, unknown field path, wrong unit, or a
        point whose case is invalid; the message names the sweep file, the
        parameter and the value.
    """
    path = Path(path)
    src = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError("sweep file not found", source=src) from None
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise InputError(f"cannot read the sweep file: {exc}", source=src) from None
    analysis = data.get("analysis", "static")
    if analysis not in ANALYSES:
        raise InputError(f"analysis = {analysis!r}: expected one of {sorted(ANALYSES)}", source=src)
    allowed = {"title", "case", "analysis", "set", "parameters", *ANALYSES}
    for key in data:
        if key not in allowed or (key in ANALYSES and key != analysis):
            raise InputError(f"unknown key {key!r} (allowed: {sorted(allowed)})", source=src)
    case_ref = data.get("case", "default")
    if not isinstance(case_ref, str):
        raise InputError(f"case = {case_ref!r}: expected a path or 'default'", source=src)
    case_path = default_case_path() if case_ref == "default" else path.parent / case_ref
    base_case = load_case(case_path)  # errors name the case file
    base = tomllib.loads(case_path.read_text(encoding="utf-8"))
    n_act = len(base_case.actuators.angles) if base_case.actuators is not None else 0
    fixed = _flatten(data.get("set", {}), "set", src)
    for name, value in fixed.items():
        fpath, idx, _ = _resolve(name, n_act, "set", src)
        _write_field(base, fpath, value, idx)
    case_from_dict(copy.deepcopy(base), source=f"{src} [set]")
    table = data.get(analysis, {})
    if not isinstance(table, dict):
        raise InputError(f"[{analysis}] must be a table", source=src)
    parse = ANALYSES[analysis].parse_options
    if parse is None and table:
        raise InputError(f"[{analysis}]: this analysis takes no options", source=src)
    options = parse(table, src) if parse is not None else {}
    params = _parameters(data.get("parameters"), n_act, ANALYSES[analysis].fixed, src)
    spec = SweepSpec(
        src, str(data.get("title", "")), str(case_path), base, analysis, options, params
    )
    for index in range(spec.n_points):
        spec.point_case(index)
    return spec


def _flatten(table: Any, where: str, src: str) -> dict[str, Any]:
    if not isinstance(table, dict):
        raise InputError(f"[{where}] must be a table of 'field = value' entries", source=src)
    out: dict[str, Any] = {}
    for key, value in table.items():
        if isinstance(value, dict):
            out.update({f"{key}.{k}": v for k, v in _flatten(value, where, src).items()})
        else:
            out[key] = value
    return out


def _resolve(name: str, n_act: int, where: str, src: str) -> tuple[str, int | None, str]:
    """Case field path, actuator index and kind of a parameter name."""
    m = _VOLTAGE_I.match(name)
    if (m or ALIASES.get(name, name) == "actuators.voltages") and n_act == 0:
        raise InputError(f"{where}.{name}: the case has no [actuators]", source=src)
    if m:
        i = int(m.group(1))
        if not 0 <= i < n_act:
            raise InputError(
                f"{where}.{name}: the case has {n_act} actuators (voltage[0] to "
                f"voltage[{n_act - 1}])",
                source=src,
            )
        return "actuators.voltages", i, "voltage"
    path = ALIASES.get(name, name)
    if path not in FIELD_KINDS:
        raise InputError(
            f"{where}.{name}: unknown parameter (allowed: speed, voltage, voltage[i], or a case "
            f"field: {', '.join(FIELD_KINDS)})",
            source=src,
        )
    return path, None, FIELD_KINDS[path]


def _parameters(table: Any, n_act: int, fixed: tuple[str, ...], src: str) -> tuple[Parameter, ...]:
    flat = _flatten(table if table is not None else {}, "parameters", src)
    if not flat:
        raise InputError("[parameters] is missing or empty: nothing to sweep", source=src)
    params: list[Parameter] = []
    seen: dict[tuple[str, int | None], str] = {}
    for name, raw in flat.items():
        fpath, idx, kind = _resolve(name, n_act, "parameters", src)
        if fpath in fixed:
            raise InputError(
                f"parameters.{name}: set by this analysis, cannot be swept", source=src
            )
        clash = next((n for (f, j), n in seen.items() if f == fpath and j in (idx, None)), None)
        clash = clash or next((n for (f, _), n in seen.items() if f == fpath and idx is None), None)
        if clash is not None:
            raise InputError(f"parameters.{name}: the same field as {clash}", source=src)
        seen[(fpath, idx)] = name
        if not isinstance(raw, list) or not raw:
            raise InputError(
                f"parameters.{name} = {raw!r}: expected a non-empty list of values", source=src
            )
        values = _value_list(raw, kind, f"parameters.{name}", src)
        unit, coords = _coordinates(raw, values, kind)
        params.append(Parameter(name, fpath, idx, kind, tuple(raw), values, unit, coords))
    return tuple(params)


def _value_list(raw: Any, kind: str, where: str, src: str) -> tuple[Any, ...]:
    if not isinstance(raw, list):
        raise InputError(f"{where} = {raw!r}: expected a list", source=src)
    out: list[Any] = []
    for k, v in enumerate(raw):
        if kind == "integer":
            if isinstance(v, bool) or not isinstance(v, int):
                raise InputError(f"{where}[{k}] = {v!r}: expected an integer", source=src)
            out.append(v)
        else:
            out.append(parse_quantity(v, kind, field=f"{where}[{k}]", source=src))
    return tuple(out)


def _coordinates(raw: list[Any], values: tuple[Any, ...], kind: str) -> tuple[str, tuple[Any, ...]]:
    """Coordinate values in the unit of the first value as written (SI for plain numbers)."""
    if kind in ("integer", "dimensionless"):
        return "1", values
    si = SI_UNITS[kind]
    first = raw[0]
    unit = _NUMBER.sub("", first, count=1).strip() if isinstance(first, str) else ""
    try:
        coords = tuple(
            float((ureg.Quantity(r) if isinstance(r, str) else ureg.Quantity(r, si)).to(unit).m)
            for r in raw
        )
    except Exception:  # no unit written, or one pint reads differently: SI
        return si, values
    return unit or si, coords


def _write_field(data: dict[str, Any], path: str, value: Any, index: int | None) -> None:
    *tables, key = path.split(".")
    node = data
    for t in tables:
        node = node.setdefault(t, {})
        if not isinstance(node, dict):
            return  # case_from_dict reports the malformed table
    if index is None:
        node[key] = value
        return
    current = node.get(key, 0.0)
    n = len(data.get("actuators", {}).get("angles", [])) or index + 1
    items = list(current) if isinstance(current, list) else [current]
    items = items * n if len(items) == 1 else items
    items[index] = value
    node[key] = items


# --------------------------------------------------------------------------- running


def run_point(
    index: int,
    case_data: dict[str, Any],
    source: str,
    evaluate: Callable[[Case, Mapping[str, Any]], dict[str, Any]],
    options: Mapping[str, Any],
) -> dict[str, Any]:
    """Evaluate one point: the Dask task. Pure: the same inputs give the same record.

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


def _point_file(folder: Path, index: int) -> Path:
    return folder / "points" / f"{index:06d}.json"


def _done_points(folder: Path) -> dict[int, dict[str, Any]]:
    done: dict[int, dict[str, Any]] = {}
    for f in sorted((folder / "points").glob("*.json")):
        rec = json.loads(f.read_text(encoding="utf-8"))
        done[int(rec["index"])] = rec
    return done


def _prepare(spec: SweepSpec, folder: Path, resume: bool) -> dict[int, dict[str, Any]]:
    meta = folder / "sweep.json"
    if meta.exists() or (folder / "points").exists():
        if not resume:
            raise InputError(
                f"results folder {folder} exists: pass --resume to continue it, "
                "or choose another --out"
            )
        try:
            stored = json.loads(meta.read_text(encoding="utf-8"))["fingerprint"]
        except (OSError, ValueError, KeyError):
            stored = None
        if stored != spec.fingerprint():
            raise InputError(
                f"results folder {folder} holds another sweep (different case, analysis or "
                "parameters): choose another --out"
            )
        return _done_points(folder)
    info = {
        "fingerprint": spec.fingerprint(),
        "sweep_file": spec.source,
        "case_file": spec.case_file,
        "analysis": spec.analysis,
        "options": spec.options,
        "parameters": [
            {"name": p.name, "dim": p.dim, "values": list(p.raw), "si": list(p.values)}
            for p in spec.parameters
        ],
        "case": spec.base,
    }
    write_text(meta, json.dumps(info, indent=1, default=str))
    return {}


@contextmanager
def _client(scheduler: str | None, n_workers: int | None) -> Iterator[Any]:
    from distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            client = Client(scheduler, timeout="20s")
        except OSError as exc:
            raise InputError(f"--scheduler {scheduler!r}: cannot connect ({exc})") from None
        with client:
            yield client
        return
    with (
        LocalCluster(
            n_workers=n_workers or os.cpu_count() or 1,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client


def run_sweep(
    spec: SweepSpec,
    out: str | Path,
    *,
    client: Any = None,
    scheduler: str | None = None,
    n_workers: int | None = None,
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
        (default: one per core).
    resume
        Continue the sweep in ``RESULT.d``, skipping the points already there.
    compute
        False: only assemble the points already there (with ``resume``).
    progress
        A tqdm bar on stderr: points done, failed, ETA.
    on_point
        Called with each record after it is written (e.g. to watch a run).

    Returns
    -------
    dict
        n_points, n_ok, n_failed, n_missing, n_computed, n_skipped,
        results_folder, dataset, wall_time_s.
    """
    from tqdm import tqdm

    t0 = time.perf_counter()
    folder, nc_path = output_paths(out)
    done = _prepare(spec, folder, resume)
    todo = [i for i in range(spec.n_points) if i not in done] if compute else []
    n_failed = sum(r["status"] != "ok" for r in done.values())
    bar = tqdm(
        total=spec.n_points, initial=len(done), unit="pt", disable=not progress, dynamic_ncols=True
    )
    bar.set_postfix(failed=n_failed)
    try:
        if todo:
            evaluate, prefix = ANALYSES[spec.analysis].evaluate, uuid.uuid4().hex[:12]
            with _client(scheduler, n_workers) if client is None else nullcontext(client) as cl:
                n_failed += _run_points(spec, todo, folder, cl, evaluate, prefix, bar, on_point)
    finally:
        bar.close()
    ds = assemble(spec, out)
    status = ds["status"].values
    return {
        "n_points": spec.n_points,
        "n_ok": int((status == "ok").sum()),
        "n_failed": int((status == "failed").sum()),
        "n_missing": int((status == "missing").sum()),
        "n_computed": len(todo),
        "n_skipped": len(done),
        "results_folder": str(folder),
        "dataset": str(nc_path),
        "wall_time_s": time.perf_counter() - t0,
    }


def _run_points(
    spec: SweepSpec,
    todo: list[int],
    folder: Path,
    client: Any,
    evaluate: Callable[..., dict[str, Any]],
    prefix: str,
    bar: Any,
    on_point: Callable[[dict[str, Any]], None] | None,
) -> int:
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
    n_failed = 0
    try:
        for fut in as_completed(futures):
            i = futures[fut]
            if fut.cancelled():  # cancelled from outside: stays missing, --resume runs it
                continue
            try:
                rec = fut.result()
            except Exception as exc:  # run_point catches everything: e.g. KilledWorker
                err = f"{type(exc).__name__}: {exc}"
                rec = {"index": i, "status": "failed", "error": err, "result": {}}
            fut.release()
            rec["parameters"] = spec.point_values(i)
            write_text(_point_file(folder, i), json.dumps(rec, indent=1))
            n_failed += rec["status"] != "ok"
            bar.update(1)
            bar.set_postfix(failed=n_failed)
            if on_point is not None:
                on_point(rec)
    finally:
        client.cancel([f for f in futures if not f.done()])
    return n_failed


# --------------------------------------------------------------------------- assembling


def assemble(spec: SweepSpec, out: str | Path, *, write: bool = True) -> Any:
    """Gather the point files into one xarray Dataset (and write ``RESULT.nc``).

    Dimensions are the swept parameters (coordinates in the units written in
    the sweep file, attribute ``units``), plus any dimension of list-valued
    results (``actuator``, ``axis``, ``frequency``). Every headline value is a
    variable, NaN / "" / False where a point is not ok; ``status`` is "ok",
    "failed" or "missing" and ``error`` the failure message.
    """
    import xarray as xr

    folder, nc_path = output_paths(out)
    records = _done_points(folder) if (folder / "points").exists() else {}
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
