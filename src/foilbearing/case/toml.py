"""The bearing case: frozen dataclasses loaded from a TOML file, SI inside.

A case file has the tables ``[bearing]``, ``[gas]``, ``[foil]`` (optional:
without it the bearing is a rigid-surface gas journal bearing),
``[actuators]`` (optional), ``[shims]`` (optional), ``[rotor]`` (optional when
``[operation]`` gives the load), ``[operation]``, ``[grid]`` and ``[disturbance]`` (optional); ``docs/case-format.md`` documents every field.
Dimensional values are plain SI numbers or quantity strings ("100 um"),
converted once, here. Loading validates everything and raises
:class:`~foilbearing.errors.InputError` with the file, the field, the value and
what is allowed.
"""

from __future__ import annotations

import json
import math
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.bearing_system.scales import Scales
from foilbearing.case.model import (
    ACTUATOR_DYNAMICS,
    MAX_LIFT_OFF_SMOOTHING,
    MAX_SPEED_DEFAULT,
    PRELOAD_RESPONSES,
    SUBAMBIENT_MODELS,
    Actuators,
    Bearing,
    BumpGeometry,
    Case,
    Disturbance,
    Foil,
    Gas,
    Grid,
    Operation,
    Rotor,
    Shims,
    check_actuators,
)
from foilbearing.constants import RPM, STANDARD_GRAVITY
from foilbearing.errors import InputError
from foilbearing.units import parse_quantity

__all__ = [
    "TableReader",
    "case_from_dict",
    "default_case",
    "default_case_path",
    "is_default_case_file",
    "load_case",
    "per_item_quantities",
]


def default_case_path() -> Path:
    """Path of the built-in default case: the paper's C-GFB (docs/model.md §1)."""
    return Path(str(resources.files("foilbearing") / "cases" / "cgfb.toml"))


def is_default_case_file(path: str | Path | None) -> bool:
    """Whether ``path`` is the built-in case file (the paper's C-GFB)."""
    return path is not None and Path(path).resolve() == default_case_path().resolve()


def default_case() -> Case:
    """The paper's C-GFB, the built-in default case."""
    return load_case(default_case_path())


def load_case(path: str | Path | None = None) -> Case:
    """Read and validate a TOML case file (None: the built-in default case).

    Raises
    ------
    InputError
        Missing file, TOML syntax error, missing or unknown field, wrong unit,
        or a value outside its allowed range; the message names the file, the
        field, the value and what is allowed.
    """
    path = default_case_path() if path is None else Path(path)
    source = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError("case file not found", source=source) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(
            f"cannot read case file ({exc.__class__.__name__})", source=source
        ) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", source=source) from None
    return case_from_dict(data, source=source)


def case_from_dict(data: dict[str, Any], *, source: str | None = None) -> Case:
    """Build and validate a :class:`Case` from the parsed TOML tables."""
    root = TableReader(data, "", source)
    title = root.string("title", "")
    bearing_t = root.table("bearing")
    bearing = Bearing(
        radius=bearing_t.positive("radius", "length"),
        length=bearing_t.positive("length", "length"),
        clearance=bearing_t.positive("clearance", "length"),
    )
    bearing_t.done()
    gas_t = root.table("gas")
    gas = Gas(
        viscosity=gas_t.positive("viscosity", "viscosity"),
        ambient_pressure=gas_t.positive("ambient_pressure", "pressure"),
    )
    gas_t.done()
    _check_proportions(bearing_t, gas_t, bearing, gas)
    foil = _read_foil(root.table("foil")) if "foil" in data else None
    if foil is not None:
        _check_compliance(root.table("foil"), foil, bearing, gas)
    actuators = _read_actuators(root.table("actuators"), bearing) if "actuators" in data else None
    shims = _read_shims(root.table("shims"), bearing) if "shims" in data else None
    if actuators is not None and shims is not None:
        raise InputError(
            "[actuators] and [shims] both given: a bearing has one or the other", source=source
        )
    if actuators is not None and foil is None:
        raise InputError("[actuators] needs a [foil] for the stingers to push", source=source)
    rotor_t = root.table("rotor") if "rotor" in data else TableReader({}, "rotor", source)
    op_t = root.table("operation")
    mass = rotor_t.positive("mass", "mass", default=None)
    load = op_t.nonnegative("load", "force", default=None)
    if mass is None and load is None:
        raise InputError(
            "rotor.mass and operation.load are both missing: give the static load (e.g. "
            "load = '8.8 N' in [operation]), the rotor mass, or both",
            source=source,
        )
    if mass is None and load == 0.0:
        raise op_t.error("load", op_t.data["load"], "a load > 0 or a [rotor] mass")
    # One given: the other by W = m g (a horizontal rotor whose weight is the only static
    # load on this bearing; docs/case-format.md, "Load and rotor mass").
    rotor = Rotor(
        mass=load / STANDARD_GRAVITY if mass is None else mass,
        imbalance=rotor_t.nonnegative("imbalance", "mass_length", default=0.0),
    )
    rotor_t.done()
    operation = Operation(
        load=mass * STANDARD_GRAVITY if load is None else load,
        speed=op_t.positive("speed", "speed"),
        max_speed=op_t.positive("max_speed", "speed", default=MAX_SPEED_DEFAULT),
    )
    op_t.done()
    bearing_number = Scales.from_parts(bearing, gas).bearing_number(operation.max_speed)
    if not bearing_number <= MAX_BEARING_NUMBER:
        raise gas_t.error(
            "viscosity",
            gas_t.data.get("viscosity"),
            f"a bearing number 6 mu omega R^2/(p_a c^2) up to {MAX_BEARING_NUMBER:g} at "
            f"operation.max_speed, here {bearing_number:.3g}",
        )
    if operation.speed > operation.max_speed:
        raise InputError(
            f"operation.speed = {operation.speed / RPM:.0f} rpm is above operation.max_speed = "
            f"{operation.max_speed / RPM:.0f} rpm: raise max_speed or lower the speed",
            source=source,
        )
    grid = Grid()
    if "grid" in data:
        grid_t = root.table("grid")
        grid = Grid(
            n_theta=grid_t.integer("n_theta", 24, 2048, default=Grid.n_theta),
            n_z=grid_t.integer("n_z", 2, 256, default=Grid.n_z),
            orbit_n_theta=_optional_integer(grid_t, "orbit_n_theta", 24, 2048),
            orbit_n_z=_optional_integer(grid_t, "orbit_n_z", 2, 256, Grid.orbit_n_z),
            axial_order=_axial_order(grid_t, "axial_order", Grid.axial_order),
            orbit_axial_order=(
                _axial_order(grid_t, "orbit_axial_order", 2)
                if "orbit_axial_order" in grid_t.data
                else Grid.orbit_axial_order
            ),
            lift_off_smoothing=grid_t.number(
                "lift_off_smoothing", 0.0, MAX_LIFT_OFF_SMOOTHING, default=Grid.lift_off_smoothing
            ),
        )
        orbit_key = "orbit_n_z" if grid.orbit_n_z is not None else "n_z"
        for order, key, n_z in (
            (grid.axial_order, "n_z", grid.n_z),
            (grid.orbit_order, orbit_key, grid.orbit_shape[1]),
        ):
            if order == 4 and n_z < 3:
                raise grid_t.error(key, n_z, "at least 3 at axial order 4 (the end's cubic)")
        grid_t.done()
    disturbance = _read_disturbance(root.table("disturbance")) if "disturbance" in data else None
    study = root.raw("study", default=None)
    if study is not None and not isinstance(study, dict):
        raise InputError(f"[study] must be a table, got {study!r}", source=source)
    root.done()
    return Case(
        bearing,
        gas,
        rotor,
        operation,
        grid,
        foil,
        actuators,
        shims,
        title,
        source,
        study_table=None if study is None else json.dumps(study, default=str),
        disturbance=disturbance,
    )


#: The film's proportions the model holds for (each a ratio of two fields, SI) and the
#: ambient pressures of a continuum gas film whose force double precision resolves.
CLEARANCE_RATIO = (1e-6, 0.1)  # c/R: Reynolds' thin film needs c << R
LENGTH_RATIO = (1e-2, 1e2)  # L/R: from a ring to a long bearing
AMBIENT_PRESSURE = (1e3, 1e9)  # Pa: 1 kPa (rarefied below) to 1 GPa


def _check_proportions(
    bearing_t: TableReader, gas_t: TableReader, bearing: Bearing, gas: Gas
) -> None:
    """One-line errors for a film outside the ranges the model and its numbers hold for:
    a clearance or length out of proportion with the radius (a clearance of 1e-300 m gave
    a ZeroDivisionError, a radius of 1e300 m an OverflowError), or an ambient pressure
    against which no load can be resolved (1e300 Pa "converged" with zero force)."""
    checks = (
        (bearing_t, "clearance", bearing.clearance / bearing.radius, CLEARANCE_RATIO,
         "of bearing.radius (a thin film)"),
        (bearing_t, "length", bearing.length / bearing.radius, LENGTH_RATIO,
         "times bearing.radius"),
        (gas_t, "ambient_pressure", gas.ambient_pressure, AMBIENT_PRESSURE, "Pa"),
    )  # fmt: skip
    for table, key, value, (lo, hi), what in checks:
        if not lo <= value <= hi:
            raw = table.data.get(key, value)
            raise table.error(key, raw, f"{lo:g} to {hi:g} {what}, here {value:.3g}")


#: The foil's compliance p_a/(k_b c) the film's numbers hold for: the foil deflecting by
#: up to a thousand clearances under the ambient pressure (the paper's: 0.116).
MAX_COMPLIANCE = 1e3


def _check_compliance(foil_t: TableReader, foil: Foil, bearing: Bearing, gas: Gas) -> None:
    """A one-line error for a foil so soft that the film's Newton matrix is singular (a
    bump 1e300 m high gave a LinAlgError)."""
    alpha = gas.ambient_pressure / (foil.bump_stiffness * bearing.clearance)
    if not alpha <= MAX_COMPLIANCE:
        key = "bump_stiffness" if "bump_stiffness" in foil_t.data else "bump"
        raise InputError(
            f"foil.{key}: the foil's compliance p_a/(k_b c) = {alpha:.3g} is above "
            f"{MAX_COMPLIANCE:g} (k_b = {foil.bump_stiffness:.3g} N/m**3): a stiffer foil, "
            "or check the [foil.bump] geometry",
            source=foil_t.source,
        )


#: The largest bearing number 6 mu omega R^2/(p_a c^2) at operation.max_speed the film's
#: numbers hold for (the paper's bearing: 0.69 at 150 krpm).
MAX_BEARING_NUMBER = 1e4


def _optional_integer(
    t: TableReader, key: str, lo: int, hi: int, default: int | None = None
) -> int | None:
    """An integer field from ``lo`` to ``hi`` that may be left out (``default``)."""
    return default if key not in t.data else t.integer(key, lo, hi, default=lo)


def _axial_order(t: TableReader, key: str, default: int) -> int:
    """An axial order: 2 or 4 (:class:`foilbearing.reynolds.grid.FilmGrid`)."""
    value = t.raw(key, default)
    if value not in (2, 4) or isinstance(value, bool):
        raise t.error(key, value, "2 or 4")
    return int(value)


def _read_disturbance(t: TableReader) -> Disturbance:
    f_min = t.positive("min_frequency", "frequency", default=5.0)
    f_max = t.positive("max_frequency", "frequency", default=500.0)
    if f_max <= f_min:
        raise t.error(
            "max_frequency",
            t.data.get("max_frequency", f_max),
            f"above min_frequency ({f_min:g} Hz)",
        )
    d = Disturbance(
        force_rms=t.nonnegative("force_rms", "force"),
        min_frequency=f_min,
        max_frequency=f_max,
        seed=t.integer("seed", 0, 2**31 - 1, default=1),
        tones=t.integer("tones", 1, 4096, default=256),
    )
    t.done()
    return d


def _read_foil(t: TableReader) -> Foil:
    loss = t.nonnegative("loss_factor", "dimensionless", default=0.0)
    if loss > 1.0:
        raise t.error("loss_factor", loss, "0 to 1 (0.05-0.2 is typical for bump foils)")
    bump = None
    if "bump" in t.data:
        b = t.table("bump")
        bump = BumpGeometry(
            thickness=b.positive("thickness", "length"),
            height=b.positive("height", "length"),
            pitch=b.positive("pitch", "length"),
            half_length=b.positive("half_length", "length"),
            youngs_modulus=b.positive("youngs_modulus", "pressure"),
            poisson_ratio=b.number("poisson_ratio", -1.0, 0.5, lo_open=True, hi_open=True),
            friction_coefficient=b.nonnegative(
                "friction_coefficient", "dimensionless", default=0.0
            ),
            top_foil_thickness=b.positive("top_foil_thickness", "length", default=None),
            formula=b.choice("formula", ("iordanoff", "walowit-anno"), default="iordanoff"),
        )
        if 2.0 * bump.half_length > bump.pitch:
            raise b.error(
                "half_length", bump.half_length, f"at most half the pitch ({bump.pitch / 2:g} m)"
            )
        b.done()
    if "bump_stiffness" in t.data:
        k_b = t.positive("bump_stiffness", "stiffness_per_area")
    elif bump is not None:
        try:
            k_b = bump.stiffness()
        except (ZeroDivisionError, OverflowError, ValueError):
            k_b = math.nan
        if not (math.isfinite(k_b) and k_b > 0.0):
            raise InputError(
                f"[foil.bump]: its thickness, height, half_length and pitch give no finite "
                f"bump stiffness (k_b = {k_b:g} N/m**3): check them",
                source=t.source,
            )
    else:
        raise t.error(
            "bump_stiffness",
            None,
            "a stiffness per unit area (e.g. '8.69e9 N/m**3') or a [foil.bump] geometry",
        )
    subambient = t.choice("subambient", SUBAMBIENT_MODELS, default="lift-off")
    t.done()
    return Foil(bump_stiffness=k_b, loss_factor=loss, bump=bump, subambient=subambient)


def _read_actuators(t: TableReader, bearing: Bearing) -> Actuators:
    angles = t.angles("angles")
    n = len(angles)
    volts = t.raw("voltages", default="0 V")
    voltages = per_item_quantities(volts, n, "voltage", t, "voltages")
    act = Actuators(
        angles=angles,
        stinger_arc=t.angle_arc("stinger_arc"),
        contact_area=t.positive("contact_area", "area"),
        d33_quadratic=t.quantity("d33_quadratic", "length_per_voltage2"),
        d33_linear=t.quantity("d33_linear", "length_per_voltage"),
        stack_stiffness=t.positive("stack_stiffness", "stiffness"),
        holder_spring_stiffness=t.nonnegative("holder_spring_stiffness", "stiffness_per_area"),
        holder_pre_extension=t.nonnegative("holder_pre_extension", "length", default=0.0),
        voltages=voltages,
        max_voltage=t.positive("max_voltage", "voltage"),
        smoothness=t.number("smoothness", 0.0, math.inf, lo_open=True, default=50.0),
        preload_response=t.choice("preload_response", PRELOAD_RESPONSES, default="local"),
        dynamics=t.choice("dynamics", ACTUATOR_DYNAMICS, default="compliant"),
    )
    t.done()
    _check_arcs(act.angles, act.stinger_arc, t, "stinger_arc")
    check_actuators(act, bearing, t.source)
    return act


def _read_shims(t: TableReader, bearing: Bearing) -> Shims:
    angles = t.angles("angles")
    arc = t.angle_arc("arc")
    raw = t.raw("thickness")
    thick = per_item_quantities(raw, len(angles), "length", t, "thickness")
    for i, d in enumerate(thick):
        if not 0.0 <= d < bearing.clearance:
            raise InputError(
                f"shims.thickness[{i}] = {d * 1e6:.2f} um: allowed 0 to below the clearance "
                f"{bearing.clearance * 1e6:.2f} um",
                source=t.source,
            )
    t.done()
    _check_arcs(angles, arc, t, "arc")
    return Shims(angles, arc, thick)


def _check_arcs(angles: tuple[float, ...], arc: float, t: TableReader, name: str) -> None:
    if len(angles) < 2:
        return
    s = np.sort(np.asarray(angles))
    gaps = np.diff(np.append(s, s[0] + 2.0 * np.pi))
    if np.min(gaps) <= arc:
        raise t.error(
            name,
            f"{math.degrees(arc):g} deg",
            f"less than the smallest gap between angles ({math.degrees(np.min(gaps)):g} deg): "
            "the arcs overlap",
        )


def per_item_quantities(
    raw: Any, n: int, kind: str, t: TableReader, name: str
) -> tuple[float, ...]:
    """Field ``name`` of table ``t`` as ``n`` SI values: one quantity for all, or a list of 1 or n."""
    if isinstance(raw, list):
        if len(raw) not in (1, n):
            raise t.error(name, raw, f"1 or {n} values (one per angle)")
        vals = [
            parse_quantity(v, kind, field=f"{t.prefix}{name}[{i}]", source=t.source)
            for i, v in enumerate(raw)
        ]
        return tuple(vals) * (n if len(vals) == 1 else 1)
    return (parse_quantity(raw, kind, field=f"{t.prefix}{name}", source=t.source),) * n


class TableReader:
    """One TOML table being read: tracks the fields used, so unknown ones are reported."""

    def __init__(self, data: Any, name: str, source: str | None) -> None:
        if not isinstance(data, dict):
            raise InputError(f"[{name}] must be a table, got {data!r}", source=source)
        self.data = data
        self.name = name
        self.prefix = f"{name}." if name else ""
        self.source = source
        self.used: set[str] = set()

    def error(self, key: str, value: Any, allowed: str) -> InputError:
        shown = "missing" if value is None else f"= {value!r}"
        return InputError(f"{self.prefix}{key} {shown}: expected {allowed}", source=self.source)

    def raw(self, key: str, default: Any = ...) -> Any:
        self.used.add(key)
        if key not in self.data:
            if default is ...:
                raise InputError(f"{self.prefix}{key} is missing", source=self.source)
            return default
        return self.data[key]

    def table(self, key: str) -> TableReader:
        if key not in self.data:
            raise InputError(f"table [{self.prefix}{key}] is missing", source=self.source)
        self.used.add(key)
        return TableReader(self.data[key], f"{self.prefix}{key}", self.source)

    def string(self, key: str, default: str) -> str:
        value = self.raw(key, default)
        if not isinstance(value, str):
            raise self.error(key, value, "a string")
        return value

    def choice(self, key: str, allowed: tuple[str, ...], default: str) -> str:
        value = self.raw(key, default)
        if value not in allowed:
            raise self.error(key, value, "one of " + ", ".join(repr(a) for a in allowed))
        return str(value)

    def quantity(self, key: str, kind: str, default: Any = ...) -> Any:
        value = self.raw(key, default)
        if value is default and default is not ...:
            return default
        return parse_quantity(value, kind, field=f"{self.prefix}{key}", source=self.source)

    def positive(self, key: str, kind: str, default: Any = ...) -> Any:
        value = self.quantity(key, kind, default)
        if value is not None and value is not default and value <= 0.0:
            raise self.error(key, self.data[key], "a value > 0")
        return value

    def nonnegative(self, key: str, kind: str, default: Any = ...) -> Any:
        value = self.quantity(key, kind, default)
        if value is not None and value is not default and value < 0.0:
            raise self.error(key, self.data[key], "a value >= 0")
        return value

    def number(
        self,
        key: str,
        lo: float,
        hi: float,
        *,
        lo_open: bool = False,
        hi_open: bool = False,
        default: Any = ...,
    ) -> float:
        value = self.quantity(key, "dimensionless", default)
        ok_lo = value > lo if lo_open else value >= lo
        ok_hi = value < hi if hi_open else value <= hi
        if not (ok_lo and ok_hi):
            lo_s, hi_s = ("(" if lo_open else "["), (")" if hi_open else "]")
            raise self.error(
                key, self.data.get(key, value), f"a number in {lo_s}{lo:g}, {hi:g}{hi_s}"
            )
        return float(value)

    def integer(self, key: str, lo: int, hi: int, default: int) -> int:
        value = self.raw(key, default)
        if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
            raise self.error(key, value, f"an integer from {lo} to {hi}")
        return value

    def angles(self, key: str) -> tuple[float, ...]:
        raw = self.raw(key)
        if not isinstance(raw, list) or not raw:
            raise self.error(key, raw, "a non-empty list of angles (e.g. ['60 deg', '180 deg'])")
        out = []
        for i, v in enumerate(raw):
            a = parse_quantity(v, "angle", field=f"{self.prefix}{key}[{i}]", source=self.source)
            if not 0.0 <= a < 2.0 * math.pi:
                raise InputError(
                    f"{self.prefix}{key}[{i}] = {v!r}: allowed 0 to below 360 deg",
                    source=self.source,
                )
            out.append(a)
        if len(set(out)) != len(out):
            raise self.error(key, raw, "distinct angles")
        return tuple(out)

    def angle_arc(self, key: str) -> float:
        value = self.quantity(key, "angle")
        if not 0.0 < value < 2.0 * math.pi:
            raise self.error(key, self.data[key], "an arc between 0 and 360 deg")
        return float(value)

    def done(self) -> None:
        unknown = sorted(set(self.data) - self.used - {"bump"})
        if unknown:
            where = f"[{self.name}]" if self.name else "the top level"
            raise InputError(
                f"unknown field {unknown[0]!r} in {where} (allowed: "
                f"{', '.join(sorted(self.used | ({'bump'} if self.name == 'foil' else set())))})",
                source=self.source,
            )
