"""The bearing case: frozen dataclasses loaded from a TOML file, SI inside.

A case file has the tables ``[bearing]``, ``[gas]``, ``[foil]`` (optional:
without it the bearing is a rigid-surface gas journal bearing),
``[actuators]`` (optional), ``[shims]`` (optional), ``[rotor]``,
``[operation]`` and ``[grid]``; ``docs/case-format.md`` documents every field.
Dimensional values are plain SI numbers or quantity strings ("100 um"),
converted once, here. Loading validates everything and raises
:class:`~foilbearing.errors.InputError` with the file, the field, the value and
what is allowed.
"""

from __future__ import annotations

import json
import math
import tomllib
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from foilbearing.constants import RPM
from foilbearing.errors import InputError
from foilbearing.structure import (
    actuator_stiffness,
    assembly_stiffness,
    base_preload,
    iordanoff_bump_stiffness,
    stack_displacement,
    walowit_anno_bump_stiffness,
)
from foilbearing.units import parse_quantity

__all__ = [
    "Actuators",
    "Bearing",
    "BumpGeometry",
    "Case",
    "Foil",
    "Gas",
    "Grid",
    "Operation",
    "Rotor",
    "Shims",
    "TableReader",
    "default_case",
    "default_case_path",
    "is_default_case_file",
    "load_case",
    "per_item_quantities",
]

#: Default top of the speeds an analysis may be asked for, rad/s (150 000 rpm, the top
#: of the default onset scan); a case sets its own with ``[operation] max_speed``.
MAX_SPEED_DEFAULT = 150_000 * RPM


@dataclass(frozen=True)
class Bearing:
    """Journal and bearing geometry, m."""

    radius: float
    length: float
    clearance: float


@dataclass(frozen=True)
class Gas:
    """Isothermal, isoviscous ideal gas."""

    viscosity: float  # Pa·s
    ambient_pressure: float  # Pa


@dataclass(frozen=True)
class BumpGeometry:
    """Bump-foil geometry and material, SI."""

    thickness: float  # t_b, m
    height: float  # h_b, m
    pitch: float  # s, m
    half_length: float  # l_0, m
    youngs_modulus: float  # E, Pa
    poisson_ratio: float  # ν
    friction_coefficient: float = 0.0  # μ_f at the bump feet (Iordanoff)
    top_foil_thickness: float | None = None  # m, informational
    formula: str = "iordanoff"  # or "walowit-anno"

    def stiffness(self) -> float:
        """Bump stiffness per unit area from the geometry, N/m³."""
        if self.formula == "walowit-anno":
            return walowit_anno_bump_stiffness(
                self.thickness,
                self.pitch,
                self.half_length,
                self.youngs_modulus,
                self.poisson_ratio,
            )
        return iordanoff_bump_stiffness(
            self.thickness,
            self.height,
            self.pitch,
            self.half_length,
            self.youngs_modulus,
            self.poisson_ratio,
            self.friction_coefficient,
        )


#: How a foil bearing treats sub-ambient film pressure (docs/model.md §3).
SUBAMBIENT_MODELS = ("lift-off", "retained")


@dataclass(frozen=True)
class Foil:
    """Compliant foil: an elastic foundation of stiffness k_b per unit area with loss factor γ.

    ``subambient`` says what the film does where its pressure falls below
    ambient (docs/model.md §3): ``"lift-off"`` (default) — the top foil,
    which only rests on the bumps, is pulled off them towards the journal
    until the suction is relieved, so the film holds no sub-ambient pressure
    (``P ≥ 1`` as a complementarity condition); ``"retained"`` — the foil
    stays on the bumps and the film keeps its sub-ambient pressure, as a rigid
    surface would (the model before lift-off, kept for comparison).
    """

    bump_stiffness: float  # k_b, N/m³
    loss_factor: float  # γ
    bump: BumpGeometry | None = None
    subambient: str = "lift-off"

    @property
    def lift_off(self) -> bool:
        """Whether sub-ambient film pressure lifts the top foil (no suction held)."""
        return self.subambient == "lift-off"


@dataclass(frozen=True)
class Actuators:
    """PZT actuators pushing the foil through stingers (paper section 2-3)."""

    angles: tuple[float, ...]  # θ_n, rad
    stinger_arc: float  # θ_s, rad
    contact_area: float  # A_c, m²
    d33_quadratic: float  # D33,1, m/V²
    d33_linear: float  # D33,2, m/V
    stack_stiffness: float  # K_p, N/m
    holder_spring_stiffness: float  # k_sp per unit area, each of four, N/m³
    holder_pre_extension: float  # δ_pre, m
    voltages: tuple[float, ...]  # V per actuator
    max_voltage: float  # V
    smoothness: float = 50.0  # α of k(θ), 1/rad

    @property
    def k_p(self) -> float:
        """Stack stiffness per unit contact area, N/m³."""
        return self.stack_stiffness / self.contact_area

    @property
    def stiffness(self) -> float:
        """Actuator stiffness per unit area k_p + 4k_sp, N/m³."""
        return actuator_stiffness(self.k_p, self.holder_spring_stiffness)

    def stack_strokes(self) -> np.ndarray:
        """Free stroke of each stack at its voltage, m (Eq. 2)."""
        return stack_displacement(np.array(self.voltages), self.d33_quadratic, self.d33_linear)

    def base_preloads(self) -> np.ndarray:
        """Base piezoelectric preload of each actuator at its voltage, m (Eq. 3b, p_A = 0)."""
        return base_preload(
            np.array(self.voltages),
            self.d33_quadratic,
            self.d33_linear,
            self.k_p,
            self.holder_spring_stiffness,
            self.holder_pre_extension,
        )


@dataclass(frozen=True)
class Shims:
    """Rigid shims under the foil: the shimmed GFB."""

    angles: tuple[float, ...]  # rad
    arc: float  # rad
    thicknesses: tuple[float, ...]  # m, one per shim


@dataclass(frozen=True)
class Rotor:
    """Rigid rotor mass carried by this bearing and its imbalance."""

    mass: float  # kg
    imbalance: float  # kg·m (mass times radius)

    @property
    def imbalance_radius(self) -> float:
        """u_im = imbalance / mass, m."""
        return self.imbalance / self.mass


@dataclass(frozen=True)
class Operation:
    """Operating point: static load along +X and rotor speed, and the speeds analyses may use."""

    load: float  # N
    speed: float  # rad/s
    max_speed: float = MAX_SPEED_DEFAULT  # rad/s, the top of any speed range asked for


@dataclass(frozen=True)
class Grid:
    """Finite-volume grid of the film: cells around the bearing and axially over half its length."""

    n_theta: int = 96
    n_z: int = 12


@dataclass(frozen=True)
class Case:
    """A bearing case. All fields SI; see the module docstring for the file format."""

    bearing: Bearing
    gas: Gas
    rotor: Rotor
    operation: Operation
    grid: Grid = field(default_factory=Grid)
    foil: Foil | None = None
    actuators: Actuators | None = None
    shims: Shims | None = None
    title: str = ""
    source: str | None = None
    #: The optional ``[study]`` table as JSON text, read and checked by
    #: :func:`foilbearing.study.plan.study_plan` (it belongs to the study, not the bearing).
    study_table: str | None = None

    @property
    def kind(self) -> str:
        """``"C-GFB"`` (actuators), ``"shimmed GFB"``, ``"GFB"`` (passive foil) or ``"rigid"``."""
        if self.foil is None:
            return "rigid"
        if self.actuators is not None:
            return "C-GFB"
        return "shimmed GFB" if self.shims is not None else "GFB"

    def bearing_number(self, speed: float | None = None) -> float:
        """Λ = 6 μ ω R² / (p_a C²) at ``speed`` (rad/s; default: the operating speed)."""
        omega = self.operation.speed if speed is None else speed
        b, g = self.bearing, self.gas
        return 6.0 * g.viscosity * omega * b.radius**2 / (g.ambient_pressure * b.clearance**2)

    def assembly_stiffness(self) -> float | None:
        """k_assy under a stinger, N/m³ (Eq. 7); None without foil or actuators."""
        if self.foil is None or self.actuators is None:
            return None
        return assembly_stiffness(
            self.foil.bump_stiffness, self.actuators.k_p, self.actuators.holder_spring_stiffness
        )

    def with_voltages(self, voltages: float | tuple[float, ...]) -> Case:
        """The same case with new actuator voltages (one for all, or one per actuator), validated."""
        if self.actuators is None:
            raise InputError(
                "this case has no [actuators]: a voltage cannot be set", source=self.source
            )
        volts = _per_item(voltages, len(self.actuators.angles), "actuators.voltages", self.source)
        act = replace(self.actuators, voltages=volts)
        _check_actuators(act, self.bearing, self.source)
        return replace(self, actuators=act)

    def with_subambient(self, model: str) -> Case:
        """The same case with another sub-ambient film model: ``"lift-off"`` or ``"retained"``.

        Only a bearing with a ``[foil]`` has the choice: rigid surfaces hold suction.
        """
        if model not in SUBAMBIENT_MODELS:
            raise InputError(
                f"subambient = {model!r}: expected one of "
                + ", ".join(repr(m) for m in SUBAMBIENT_MODELS),
                source=self.source,
            )
        if self.foil is None:
            raise InputError(
                f"subambient = {model!r}: this bearing has no [foil]; a rigid surface holds "
                "sub-ambient pressure (add a [foil] table, or drop the option)",
                source=self.source,
            )
        return replace(self, foil=replace(self.foil, subambient=model))

    def with_speed(self, speed: float) -> Case:
        """The same case at another rotor speed (rad/s, > 0)."""
        _require(speed > 0.0, "operation.speed", speed, "> 0 rad/s", self.source)
        return replace(self, operation=replace(self.operation, speed=speed))

    def shimmed(self) -> Case:
        """The shimmed GFB equivalent to this C-GFB (paper Fig. 8).

        Rigid shims at the actuator angles, of the stinger arc, as thick as the
        base piezoelectric preloads at the present voltages; no actuators.
        """
        if self.actuators is None:
            raise InputError("this case has no [actuators] to replace by shims", source=self.source)
        act = self.actuators
        shims = Shims(act.angles, act.stinger_arc, tuple(float(x) for x in act.base_preloads()))
        return replace(self, actuators=None, shims=shims, title=f"{self.title} (shimmed)")


# --------------------------------------------------------------------------- loading


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
    foil = _read_foil(root.table("foil")) if "foil" in data else None
    actuators = _read_actuators(root.table("actuators"), bearing) if "actuators" in data else None
    shims = _read_shims(root.table("shims"), bearing) if "shims" in data else None
    if actuators is not None and shims is not None:
        raise InputError(
            "[actuators] and [shims] both given: a bearing has one or the other", source=source
        )
    if actuators is not None and foil is None:
        raise InputError("[actuators] needs a [foil] for the stingers to push", source=source)
    rotor_t = root.table("rotor")
    rotor = Rotor(
        mass=rotor_t.positive("mass", "mass"),
        imbalance=rotor_t.nonnegative("imbalance", "mass_length", default=0.0),
    )
    rotor_t.done()
    op_t = root.table("operation")
    operation = Operation(
        load=op_t.nonnegative("load", "force"),
        speed=op_t.positive("speed", "speed"),
        max_speed=op_t.positive("max_speed", "speed", default=MAX_SPEED_DEFAULT),
    )
    op_t.done()
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
        )
        grid_t.done()
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
    )


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
        k_b = bump.stiffness()
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
    volts = t.raw("voltages", default=0.0)
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
    )
    t.done()
    _check_arcs(act.angles, act.stinger_arc, t, "stinger_arc")
    _check_actuators(act, bearing, t.source)
    return act


def _check_actuators(act: Actuators, bearing: Bearing, source: str | None) -> None:
    for i, v in enumerate(act.voltages):
        if not 0.0 <= v <= act.max_voltage:
            raise InputError(
                f"actuators.voltages[{i}] = {v:g} V: allowed 0 to max_voltage = {act.max_voltage:g} V",
                source=source,
            )
    base = act.base_preloads()
    for i, d in enumerate(base):
        if d < 0.0:
            raise InputError(
                f"actuators.holder_pre_extension = {act.holder_pre_extension * 1e6:g} um at "
                f"voltages[{i}] = {act.voltages[i]:g} V gives a negative base preload "
                f"({d * 1e6:.2f} um): the stinger would leave the foil; lower the pre-extension",
                source=source,
            )
        if d >= bearing.clearance:
            raise InputError(
                f"actuators.voltages[{i}] = {act.voltages[i]:g} V gives a base preload of "
                f"{d * 1e6:.2f} um, at or beyond the clearance {bearing.clearance * 1e6:.2f} um: "
                "lower the voltage or enlarge the clearance",
                source=source,
            )


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


def _per_item(value: Any, n: int, field: str, source: str | None) -> tuple[float, ...]:
    if isinstance(value, int | float):
        return (float(value),) * n
    items = tuple(float(v) for v in value)
    if len(items) != n:
        raise InputError(
            f"{field}: {len(items)} values given, expected 1 or {n} (one per actuator)",
            source=source,
        )
    return items


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


def _require(ok: bool, field: str, value: float, allowed: str, source: str | None) -> None:
    if not ok:
        raise InputError(f"{field} = {value!r}: expected {allowed}", source=source)
