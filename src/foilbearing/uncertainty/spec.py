"""The uncertainty file: uncertain inputs, their distributions, the outputs and the sample.

:func:`load_uncertainty` reads an uncertainty file (``docs/uncertainty.md``),
converts every distribution's parameters to SI, draws the sample and validates
the case of every sample point before any work (:class:`UncertaintySpec`).
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy import stats

from foilbearing.case import case_from_dict
from foilbearing.errors import InputError
from foilbearing.io import read_toml
from foilbearing.sweep.analyses import speed_scan, value_list
from foilbearing.sweep.spec import FIELD_KINDS, base_tables, write_field
from foilbearing.uncertainty.design import ESTIMATORS, SAMPLERS, minimum_samples, unit_sample
from foilbearing.units import SI_UNITS, si_text, ureg

__all__ = [
    "DISTRIBUTIONS",
    "Distribution",
    "UncertainInput",
    "UncertaintySpec",
    "default_uncertainty_path",
    "load_uncertainty",
]

DISTRIBUTIONS = ("uniform", "normal", "log-uniform")
#: Case fields an uncertainty file may not make uncertain: the outputs set them.
_SET_BY_OUTPUTS = ("operation.speed", "actuators.voltages")
#: A normal input's case is validated at mean ± this many σ (P(outside) = 6e-7).
_NORMAL_REACH = 5.0


@dataclass(frozen=True)
class Distribution:
    """One input's distribution, parameters in SI.

    ``uniform`` and ``log-uniform`` on [low, high]; ``normal`` with mean and σ.
    """

    kind: str
    a: float  # low, or the mean
    b: float  # high, or σ

    def ppf(self, u: np.ndarray) -> np.ndarray:
        """Values at probabilities ``u`` in (0, 1) (the inverse CDF), SI."""
        if self.kind == "uniform":
            return self.a + u * (self.b - self.a)
        if self.kind == "log-uniform":
            return np.exp(math.log(self.a) + u * (math.log(self.b) - math.log(self.a)))
        return np.asarray(stats.norm.ppf(u, loc=self.a, scale=self.b))

    @property
    def reach(self) -> tuple[float, float]:
        """The values the sample can take (a normal's: mean ± 5σ), SI."""
        if self.kind == "normal":
            return self.a - _NORMAL_REACH * self.b, self.a + _NORMAL_REACH * self.b
        return self.a, self.b


@dataclass(frozen=True)
class UncertainInput:
    """One uncertain case field: its dotted path, kind, display unit and distribution."""

    name: str  # the case field, e.g. "bearing.clearance"
    kind: str  # quantity kind (units.SI_UNITS)
    unit: str  # the unit its values were written in ("um"; SI for plain numbers)
    scale: float  # SI per display unit
    distribution: Distribution
    written: dict[str, Any]  # the table as written


@dataclass(frozen=True)
class UncertaintySpec:
    """A validated uncertainty analysis: case tables, inputs, outputs and the sample.

    ``design`` is the sample, shape (n_points, n_inputs), SI. With the Sobol
    estimator its rows come in groups of n_inputs + 2 (A, AB_1 … AB_D, B:
    :mod:`foilbearing.uncertainty.design`).
    """

    source: str
    title: str
    case_file: str
    base: dict[str, Any]
    inputs: tuple[UncertainInput, ...]
    outputs: dict[str, Any]
    samples: int  # as asked
    sampler: str
    estimator: str
    seed: int
    design: np.ndarray

    @property
    def options(self) -> dict[str, Any]:
        """The outputs, passed to each point's evaluation."""
        return self.outputs

    @property
    def n_points(self) -> int:
        """Number of model evaluations (rows of the design)."""
        return int(self.design.shape[0])

    def point_values(self, index: int) -> dict[str, Any]:
        """The point's input values, in the units they were written in."""
        return {
            inp.name: float(self.design[index, k]) / inp.scale for k, inp in enumerate(self.inputs)
        }

    def point_source(self, index: int) -> str:
        """Where a point comes from, for messages: file, index and values."""
        vals = ", ".join(
            f"{inp.name} = {v:.6g} {inp.unit}".rstrip()
            for inp, v in zip(self.inputs, self.point_values(index).values(), strict=True)
        )
        return f"{self.source}, sample {index} ({vals})"

    def point_data(self, index: int) -> dict[str, Any]:
        """The case tables of sample point ``index`` (a new dict, SI values written in with
        their unit)."""
        data = copy.deepcopy(self.base)
        for k, inp in enumerate(self.inputs):
            write_field(data, inp.name, si_text(self.design[index, k], inp.kind))
        return data

    def describe(self) -> dict[str, Any]:
        """What the results folder records of the analysis."""
        return {
            "uncertainty_file": self.source,
            "case_file": self.case_file,
            "inputs": {i.name: i.written for i in self.inputs},
            "outputs": self.outputs,
            "samples": self.samples,
            "n_points": self.n_points,
            "sampler": self.sampler,
            "estimator": self.estimator,
            "seed": self.seed,
            "case": self.base,
        }

    def fingerprint(self) -> str:
        """SHA-256 of everything that determines the results."""
        key = [
            self.base,
            self.outputs,
            [
                (i.name, i.distribution.kind, i.distribution.a, i.distribution.b)
                for i in self.inputs
            ],
            self.sampler,
            self.estimator,
            self.seed,
            self.n_points,
        ]
        return hashlib.sha256(json.dumps(key, sort_keys=True, default=str).encode()).hexdigest()


def default_uncertainty_path() -> Path:
    """The built-in uncertainty file: what the paper leaves open (issue 15's example)."""
    from importlib import resources

    return Path(str(resources.files("foilbearing") / "cases" / "uncertainty_paper.toml"))


_TOP_KEYS = {
    "title",
    "case",
    "set",
    "samples",
    "sampler",
    "estimator",
    "seed",
    "inputs",
    "outputs",
}


def load_uncertainty(
    path: str | Path | None = None,
    *,
    samples: int | None = None,
    estimator: str | None = None,
    sampler: str | None = None,
) -> UncertaintySpec:
    """Read an uncertainty file, draw the sample and validate every point's case.

    Parameters
    ----------
    path
        The uncertainty file (default: :func:`default_uncertainty_path`).
    samples
        Number of model evaluations, overriding the file's ``samples``.
    estimator
        ``"sobol"`` or ``"rbd_fast"``, overriding the file's ``estimator``
        (``--estimator``; the study's quick plan takes ``rbd_fast``).
    sampler
        ``"sobol"`` or ``"lhs"``, overriding the file's ``sampler`` (``--sampler``).

    Raises
    ------
    InputError
        Bad TOML, an unknown key or field, a distribution with bad parameters
        (low ≥ high, σ ≤ 0, a reach outside the field's allowed range), a bad
        output table, or a sample too small for the estimator; the message
        names the file, the key and the value. Nothing is computed then.
    """
    path = Path(path) if path is not None else default_uncertainty_path()
    src = str(path)
    data = read_toml(path, "uncertainty file")
    for key in data:
        if key not in _TOP_KEYS:
            raise InputError(f"unknown key {key!r} (allowed: {sorted(_TOP_KEYS)})", source=src)
    case_path, base, case = base_tables(data, path)
    file_sampler = _choice(data, "sampler", "sobol", SAMPLERS, src)
    if sampler is not None and sampler not in SAMPLERS:
        raise InputError(f"--sampler {sampler!r}: expected one of {list(SAMPLERS)}")
    sampler = file_sampler if sampler is None else sampler
    file_estimator = _choice(data, "estimator", "sobol", ESTIMATORS, src)
    if estimator is not None and estimator not in ESTIMATORS:
        raise InputError(f"--estimator {estimator!r}: expected one of {list(ESTIMATORS)}")
    estimator = file_estimator if estimator is None else estimator
    seed = data.get("seed", 1)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise InputError(f"seed = {seed!r}: expected an integer ≥ 0", source=src)
    inputs = _inputs(data.get("inputs"), base, src)
    n_in = len(inputs)
    where = "--samples" if samples is not None else f"{src}: samples"
    n = samples if samples is not None else data.get("samples", 256)
    least = minimum_samples(estimator, n_in)
    if isinstance(n, bool) or not isinstance(n, int) or n < least:
        raise InputError(
            f"{where} = {n!r}: the {estimator!r} estimator with {n_in} inputs needs at least "
            f"{least} samples"
            + (f" (it uses whole groups of {n_in + 2})" if estimator == "sobol" else "")
        )
    outputs = _outputs(data.get("outputs"), case, src)
    u = unit_sample(n_in, n, sampler, estimator, seed)
    design = np.column_stack([inp.distribution.ppf(u[:, k]) for k, inp in enumerate(inputs)])
    spec = UncertaintySpec(
        src,
        str(data.get("title", "")),
        str(case_path),
        base,
        inputs,
        outputs,
        n,
        sampler,
        estimator,
        seed,
        design,
    )
    for index in range(spec.n_points):
        case_from_dict(spec.point_data(index), source=spec.point_source(index))
    return spec


def _choice(
    data: dict[str, Any], key: str, default: str, allowed: tuple[str, ...], src: str
) -> str:
    value = data.get(key, default)
    if value not in allowed:
        raise InputError(f"{key} = {value!r}: expected one of {list(allowed)}", source=src)
    return str(value)


def _inputs(table: Any, base: dict[str, Any], src: str) -> tuple[UncertainInput, ...]:
    if not isinstance(table, dict) or not table:
        raise InputError(
            "[inputs] is missing or empty: name at least one case field, e.g. "
            '"bearing.clearance" = { distribution = "uniform", low = "80 um", '
            'high = "120 um" }',
            source=src,
        )
    allowed = [
        f
        for f, k in FIELD_KINDS.items()
        if k not in ("integer", "choice") and not f.startswith("grid.") and f not in _SET_BY_OUTPUTS
    ]
    out = []
    for name, spec in _flatten_inputs(table):
        if name not in allowed:
            why = (
                "set by the outputs (their speeds and voltages)"
                if name in _SET_BY_OUTPUTS
                else "a numerical (grid) setting, not an input of the bearing"
                if name.startswith("grid.")
                else "a modelling choice, not a quantity (set it in the case)"
                if name in FIELD_KINDS
                else "unknown field"
            )
            raise InputError(f"inputs.{name}: {why} (allowed: {', '.join(allowed)})", source=src)
        kind = FIELD_KINDS[name]
        dist, unit, scale = _distribution(name, kind, spec, src)
        out.append(UncertainInput(name, kind, unit, scale, dist, dict(spec)))
        _check_reach(name, dist, base, src)
    return tuple(out)


def _flatten_inputs(table: dict[str, Any], prefix: str = "") -> list[tuple[str, dict[str, Any]]]:
    """(dotted field, distribution table) pairs: a table with ``distribution`` is a leaf."""
    out = []
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and "distribution" not in value:
            out.extend(_flatten_inputs(value, f"{name}."))
        else:
            out.append((name, value))
    return out


_PARAMETERS = {
    "uniform": ("low", "high"),
    "log-uniform": ("low", "high"),
    "normal": ("mean", "std"),
}


def _distribution(name: str, kind: str, spec: Any, src: str) -> tuple[Distribution, str, float]:
    where = f"inputs.{name}"
    if not isinstance(spec, dict):
        raise InputError(
            f"{where} = {spec!r}: expected a table such as "
            '{ distribution = "uniform", low = ..., high = ... }',
            source=src,
        )
    dist = spec.get("distribution")
    if dist not in _PARAMETERS:
        raise InputError(
            f"{where}.distribution = {dist!r}: expected one of {list(DISTRIBUTIONS)}", source=src
        )
    keys = _PARAMETERS[dist]
    extra = set(spec) - {"distribution", *keys}
    missing = [k for k in keys if k not in spec]
    if extra or missing:
        raise InputError(
            f"{where}: a {dist} distribution takes {keys[0]} and {keys[1]}"
            + (f" (unknown: {sorted(extra)})" if extra else f" (missing: {missing})"),
            source=src,
        )
    a, b = value_list([spec[k] for k in keys], kind, where, src)
    if dist == "normal" and not b > 0.0:
        raise InputError(f"{where}.std = {spec['std']!r}: expected σ > 0", source=src)
    if dist != "normal" and not a < b:
        raise InputError(
            f"{where}: low = {spec['low']!r} ≥ high = {spec['high']!r}: expected low < high",
            source=src,
        )
    if dist == "log-uniform" and not a > 0.0:
        raise InputError(f"{where}.low = {spec['low']!r}: a log-uniform needs low > 0", source=src)
    unit, scale = _display_unit(spec[keys[0]], kind)
    return Distribution(dist, a, b), unit, scale


def _display_unit(first: Any, kind: str) -> tuple[str, float]:
    """The unit a value was written in and its size in SI (SI for plain numbers)."""
    si = SI_UNITS.get(kind, "")
    if not isinstance(first, str) or not si:
        return si, 1.0
    try:
        q = ureg.Quantity(first)
        unit = f"{q.units:~}".replace(" ", "")
        return unit, float(ureg.Quantity(1.0, q.units).to(si).m)
    except Exception:  # pint reads it differently: show SI
        return si, 1.0


def _check_reach(name: str, dist: Distribution, base: dict[str, Any], src: str) -> None:
    """The case must be valid at both ends of the input's reach (others at the base case)."""
    for end, value in zip(("low", "high"), dist.reach, strict=True):
        data = copy.deepcopy(base)
        write_field(data, name, si_text(value, FIELD_KINDS[name]))
        try:
            case_from_dict(data, source=src)
        except InputError as exc:
            what = "mean ± 5σ" if dist.kind == "normal" else end
            raise InputError(
                f"inputs.{name}: the distribution reaches {value:.6g} {SI_UNITS[FIELD_KINDS[name]]}"
                f" ({what}), outside the field's allowed range: {exc.detail}",
                source=src,
            ) from None


def _outputs(table: Any, case: Any, src: str) -> dict[str, Any]:
    """The outputs table: static readouts and linear onsets, speeds in rad/s, voltages in V."""
    table = {} if table is None else table
    if not isinstance(table, dict):
        raise InputError("[outputs] must be a table", source=src)
    allowed = {"static", "stability", "orbit"}
    for key in table:
        if key not in allowed:
            raise InputError(
                f"outputs.{key}: unknown output (allowed: {sorted(allowed)})", source=src
            )
    if not table:
        table = {"static": {}, "stability": {}}
    out: dict[str, Any] = {}
    if "static" in table:
        st = _table(table["static"], "outputs.static", {"speeds", "voltages"}, src)
        speeds = value_list(
            st.get("speeds", [si_text(case.operation.speed, "speed")]),
            "speed",
            "outputs.static.speeds",
            src,
        )
        if any(s <= 0.0 for s in speeds):
            raise InputError(f"outputs.static.speeds = {st['speeds']!r}: expected > 0", source=src)
        out["static"] = {
            "speeds_rad_s": sorted(speeds),
            "voltages_V": _voltages(st, case, "outputs.static.voltages", src),
        }
    if "stability" in table:
        st = _table(table["stability"], "outputs.stability", {"voltages", "speed_range"}, src)
        raw = st.get("speed_range", ["5000 rpm", "150000 rpm", "5000 rpm"])
        out["stability"] = {
            "speeds_rad_s": speed_scan(raw, "outputs.stability.speed_range", src),
            "voltages_V": _voltages(st, case, "outputs.stability.voltages", src),
        }
    if "orbit" in table:
        out["orbit"] = _orbit_outputs(table["orbit"], case, src)
    return out


def _orbit_outputs(value: Any, case: Any, src: str) -> dict[str, Any]:
    """A speed-up per voltage: the ramp (start, stop, rad/s; rad/s²) and the voltage program."""
    where = "outputs.orbit"
    st = _table(value, where, {"speed_ramp", "voltages", "voltage_ramp"}, src)
    raw = st.get("speed_ramp", ["3000 rpm", "90000 rpm", "500 rad/s**2"])
    if not isinstance(raw, list) or len(raw) != 3:
        raise InputError(
            f"{where}.speed_ramp = {raw!r}: expected [START, STOP, ACCELERATION], "
            "e.g. ['3000 rpm', '90000 rpm', '500 rad/s**2']",
            source=src,
        )
    w0, w1 = value_list(raw[:2], "speed", f"{where}.speed_ramp", src)
    (accel,) = value_list(raw[2:], "angular_acceleration", f"{where}.speed_ramp", src)
    if not 0.0 < w0 < w1 or accel <= 0.0:
        raise InputError(
            f"{where}.speed_ramp = {raw!r}: need 0 < START < STOP and ACCELERATION > 0",
            source=src,
        )
    ramp = None
    if "voltage_ramp" in st:
        if "voltages" not in st:
            raise InputError(f"{where}.voltage_ramp: give the voltages it ramps to", source=src)
        ramp = list(value_list(st["voltage_ramp"], "time", f"{where}.voltage_ramp", src))
        if len(ramp) != 2 or not 0.0 <= ramp[0] <= ramp[1]:
            raise InputError(
                f"{where}.voltage_ramp = {st['voltage_ramp']!r}: expected [START, END] times, "
                "0 ≤ START ≤ END, e.g. ['6.0 s', '6.5 s'] (the paper's)",
                source=src,
            )
    return {
        "speed_ramp": [w0, w1, accel],
        "voltages_V": _voltages(st, case, f"{where}.voltages", src),
        "voltage_ramp_s": ramp,
    }


def _table(value: Any, where: str, keys: set[str], src: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise InputError(f"[{where}] must be a table", source=src)
    unknown = set(value) - keys
    if unknown:
        raise InputError(
            f"{where}: unknown key(s) {sorted(unknown)} (allowed: {sorted(keys)})", source=src
        )
    return value


def _voltages(table: dict[str, Any], case: Any, where: str, src: str) -> list[float | None]:
    """Common actuator voltages, V; [None] (the case's own voltages) when not given."""
    if "voltages" not in table:
        return [None]
    if case.actuators is None:
        raise InputError(f"{where}: the case has no [actuators]", source=src)
    volts = value_list(table["voltages"], "voltage", where, src)
    top = case.actuators.max_voltage
    for v in volts:
        if not 0.0 <= v <= top:
            raise InputError(
                f"{where} = {table['voltages']!r}: expected voltages in [0, {top:g}] V "
                "(actuators.max_voltage)",
                source=src,
            )
    return list(volts)
