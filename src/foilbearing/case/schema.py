"""The case schema: every field of a case file declared once.

Each :class:`CaseField` of :data:`CASE_FIELDS` says where a field lives in a case
file (its dotted TOML path, ``"bearing.clearance"``), which dataclass attribute
of :mod:`foilbearing.case.model` holds it, the kind of quantity the reader takes
(a key of :data:`foilbearing.units.SI_UNITS`, or one of the non-quantity kinds
of :data:`NON_QUANTITY_KINDS`), the unit it is shown in (µm for a clearance,
rpm for a speed), the range the reader checks, the key it has in a case
summary, and whether a sweep may set it.

The tables that other modules need are derived from it, not written again:

- :data:`FIELD_UNITS` (each dataclass field's SI unit), by which
  :mod:`foilbearing.case.record` writes a run's record;
- :data:`FILE_NAMES`, the file's name of a field where it differs from the attribute's;
- :data:`SWEEP_KINDS`, the fields a sweep file may set and the kind of each
  (:data:`foilbearing.sweep.spec.FIELD_KINDS`);
- :func:`summary_entry`, a field's summary key and value in its display unit
  (:func:`foilbearing.output.summary.case_summary`).

The reader, :mod:`foilbearing.case.toml`, still states each field's kind and range
in its own calls; the tests read every field with a value of the wrong dimension
and one outside its :attr:`CaseField.bounds` and check that the reader refuses
it by the field's name, so the two cannot drift apart unnoticed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from foilbearing.case.model import (
    MAX_LIFT_OFF_SMOOTHING,
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
)
from foilbearing.constants import RPM
from foilbearing.units import SI_UNITS

__all__ = [
    "CASE_FIELDS",
    "FIELD_UNITS",
    "FILE_NAMES",
    "NON_QUANTITY_KINDS",
    "SWEEP_KINDS",
    "Bounds",
    "CaseField",
    "case_field",
    "summary_entry",
    "to_display",
]

#: Kinds of field that are not a quantity of :data:`~foilbearing.units.SI_UNITS`: an
#: integer, one word of a fixed set, a nested table, and a law object given in Python
#: (no case file holds it).
NON_QUANTITY_KINDS = ("integer", "choice", "table", "law")


@dataclass(frozen=True)
class Bounds:
    """The range the reader allows a field, in SI: ``lo`` to ``hi``, each end open or closed.

    ``allowed`` lists the only values allowed (the axial orders 2 and 4), in place of a range.
    """

    lo: float = -math.inf
    hi: float = math.inf
    lo_open: bool = False
    hi_open: bool = False
    allowed: tuple[int, ...] = ()

    def contains(self, value: float) -> bool:
        """Whether the reader accepts ``value`` (SI) by this range."""
        if self.allowed:
            return value in self.allowed
        above = value > self.lo if self.lo_open else value >= self.lo
        below = value < self.hi if self.hi_open else value <= self.hi
        return above and below


_POSITIVE = Bounds(lo=0.0, lo_open=True)
_NONNEGATIVE = Bounds(lo=0.0)
_ANGLE = Bounds(lo=0.0, hi=2.0 * math.pi, hi_open=True)  # each angle of a list
_ARC = Bounds(lo=0.0, hi=2.0 * math.pi, lo_open=True, hi_open=True)
_AXIAL_ORDER = Bounds(allowed=(2, 4))


@dataclass(frozen=True)
class CaseField:
    """One field of a case file.

    Attributes
    ----------
    path
        Dotted TOML path in a case file, ``"bearing.clearance"``.
    owner
        The dataclass of :mod:`foilbearing.case.model` that holds it.
    attr
        Its attribute there (``Shims.thicknesses`` is the file's ``shims.thickness``).
    kind
        What the reader takes: a key of :data:`~foilbearing.units.SI_UNITS` (a quantity
        of that dimension, ``"dimensionless"`` for a plain number), or one of
        :data:`NON_QUANTITY_KINDS`.
    display
        The unit it is shown in (summaries, reports); ``""``: its SI unit.
    bounds
        The range the reader checks on the value (SI); None where it checks none, or
        only against other fields (a shim's thickness below the clearance).
    summary
        Its key in :func:`~foilbearing.output.summary.case_summary`, or None if not shown there.
    not_swept
        Why a sweep file may not set it; ``""``: it may.
    """

    path: str
    owner: type
    attr: str
    kind: str
    display: str = ""
    bounds: Bounds | None = None
    summary: str | None = None
    not_swept: str = ""

    @property
    def unit(self) -> str:
        """The SI unit (``""`` for a plain number, an integer or a word; ``"table"`` for a
        nested table; ``"law"`` for a law object)."""
        if self.kind in ("table", "law"):
            return self.kind
        return SI_UNITS.get(self.kind, "")

    @property
    def display_unit(self) -> str:
        """The unit it is shown in: :attr:`display`, or the SI unit."""
        return self.display or self.unit

    @property
    def sweepable(self) -> bool:
        """Whether a sweep file may set it."""
        return not self.not_swept

    def value(self, case: Case) -> Any:
        """The field's value (SI) in ``case``; None where its table is absent."""
        node: Any = case
        for name in self.path.split(".")[:-1]:
            node = getattr(node, name, None)
            if node is None:
                return None
        return getattr(node, self.attr)


_LAYOUT = "the layout: the list's length sets how many there are"
_NOT_SWEEP = "not offered by sweep files"

#: Every field of a case file (and the law objects given in Python), table by table.
CASE_FIELDS: tuple[CaseField, ...] = (
    CaseField("bearing.radius", Bearing, "radius", "length", "mm", _POSITIVE, "radius_mm"),
    CaseField("bearing.length", Bearing, "length", "length", "mm", _POSITIVE, "length_mm"),
    CaseField("bearing.clearance", Bearing, "clearance", "length", "um", _POSITIVE, "clearance_um"),
    CaseField("gas.viscosity", Gas, "viscosity", "viscosity", "", _POSITIVE, "viscosity_Pa_s"),
    CaseField(
        "gas.ambient_pressure",
        Gas,
        "ambient_pressure",
        "pressure",
        "",
        _POSITIVE,
        "ambient_pressure_Pa",
    ),
    CaseField(
        "foil.bump_stiffness",
        Foil,
        "bump_stiffness",
        "stiffness_per_area",
        "",
        _POSITIVE,
        "k_b_N_per_m3",
    ),
    CaseField(
        "foil.loss_factor",
        Foil,
        "loss_factor",
        "dimensionless",
        "",
        Bounds(0.0, 1.0),
        "loss_factor",
    ),
    CaseField("foil.bump", Foil, "bump", "table", not_swept="a table: sweep its fields"),
    CaseField("foil.subambient", Foil, "subambient", "choice"),
    CaseField(
        "foil.damping",
        Foil,
        "damping",
        "law",
        not_swept="a law object given in Python, not a field of a case file",
    ),
    CaseField("foil.bump.thickness", BumpGeometry, "thickness", "length", "um", _POSITIVE),
    CaseField("foil.bump.height", BumpGeometry, "height", "length", "um", _POSITIVE),
    CaseField("foil.bump.pitch", BumpGeometry, "pitch", "length", "mm", _POSITIVE),
    CaseField("foil.bump.half_length", BumpGeometry, "half_length", "length", "mm", _POSITIVE),
    CaseField(
        "foil.bump.youngs_modulus", BumpGeometry, "youngs_modulus", "pressure", "GPa", _POSITIVE
    ),
    CaseField(
        "foil.bump.poisson_ratio",
        BumpGeometry,
        "poisson_ratio",
        "dimensionless",
        bounds=Bounds(-1.0, 0.5, lo_open=True, hi_open=True),
    ),
    CaseField(
        "foil.bump.friction_coefficient",
        BumpGeometry,
        "friction_coefficient",
        "dimensionless",
        bounds=_NONNEGATIVE,
    ),
    CaseField(
        "foil.bump.top_foil_thickness",
        BumpGeometry,
        "top_foil_thickness",
        "length",
        "um",
        _POSITIVE,
        not_swept="informational: no analysis reads it",
    ),
    CaseField(
        "foil.bump.formula",
        BumpGeometry,
        "formula",
        "choice",
        not_swept="how k_b is computed from the bump; sweep foil.bump_stiffness or the bump's sizes",
    ),
    CaseField(
        "actuators.angles",
        Actuators,
        "angles",
        "angle",
        "deg",
        _ANGLE,
        "actuator_angles_deg",
        not_swept=_LAYOUT,
    ),
    CaseField(
        "actuators.stinger_arc", Actuators, "stinger_arc", "angle", "deg", _ARC, "stinger_arc_deg"
    ),
    CaseField("actuators.contact_area", Actuators, "contact_area", "area", "mm**2", _POSITIVE),
    CaseField(
        "actuators.d33_quadratic", Actuators, "d33_quadratic", "length_per_voltage2", "um/V**2"
    ),
    CaseField("actuators.d33_linear", Actuators, "d33_linear", "length_per_voltage", "um/V"),
    CaseField(
        "actuators.stack_stiffness", Actuators, "stack_stiffness", "stiffness", "", _POSITIVE
    ),
    CaseField(
        "actuators.holder_spring_stiffness",
        Actuators,
        "holder_spring_stiffness",
        "stiffness_per_area",
        "",
        _NONNEGATIVE,
        "k_sp_N_per_m3",
    ),
    CaseField(
        "actuators.holder_pre_extension",
        Actuators,
        "holder_pre_extension",
        "length",
        "um",
        _NONNEGATIVE,
    ),
    CaseField("actuators.voltages", Actuators, "voltages", "voltage", "", None, "voltages_V"),
    CaseField("actuators.max_voltage", Actuators, "max_voltage", "voltage", "", _POSITIVE),
    CaseField(
        "actuators.smoothness",
        Actuators,
        "smoothness",
        "dimensionless",
        "",
        Bounds(lo=0.0, lo_open=True),
        "smoothness_per_rad",
    ),
    CaseField("actuators.preload_response", Actuators, "preload_response", "choice"),
    CaseField("actuators.dynamics", Actuators, "dynamics", "choice"),
    CaseField("shims.angles", Shims, "angles", "angle", "deg", _ANGLE, "shim_angles_deg", _LAYOUT),
    CaseField("shims.arc", Shims, "arc", "angle", "deg", _ARC, "shim_arc_deg"),
    # 0 to below the clearance: checked against bearing.clearance, so no bounds of its own.
    CaseField("shims.thickness", Shims, "thicknesses", "length", "um", None, "shim_thickness_um"),
    CaseField("rotor.mass", Rotor, "mass", "mass", "", _POSITIVE, "rotor_mass_kg"),
    CaseField(
        "rotor.imbalance", Rotor, "imbalance", "mass_length", "g*mm", _NONNEGATIVE, "imbalance_g_mm"
    ),
    CaseField(
        "disturbance.force_rms",
        Disturbance,
        "force_rms",
        "force",
        "",
        _NONNEGATIVE,
        "disturbance_N_rms",
        _NOT_SWEEP,
    ),
    CaseField(
        "disturbance.min_frequency",
        Disturbance,
        "min_frequency",
        "frequency",
        "",
        _POSITIVE,
        not_swept=_NOT_SWEEP,
    ),
    CaseField(
        "disturbance.max_frequency",
        Disturbance,
        "max_frequency",
        "frequency",
        "",
        _POSITIVE,
        not_swept=_NOT_SWEEP,
    ),
    CaseField(
        "disturbance.seed",
        Disturbance,
        "seed",
        "integer",
        bounds=Bounds(0, 2**31 - 1),
        summary="disturbance_seed",
        not_swept=_NOT_SWEEP,
    ),
    CaseField(
        "disturbance.tones",
        Disturbance,
        "tones",
        "integer",
        bounds=Bounds(1, 4096),
        not_swept=_NOT_SWEEP,
    ),
    CaseField("operation.load", Operation, "load", "force", "", _NONNEGATIVE, "load_N"),
    CaseField("operation.speed", Operation, "speed", "speed", "rpm", _POSITIVE, "speed_rpm"),
    CaseField(
        "operation.max_speed",
        Operation,
        "max_speed",
        "speed",
        "rpm",
        _POSITIVE,
        not_swept="the top of the speed ranges asked for, not a state of the bearing",
    ),
    CaseField("grid.n_theta", Grid, "n_theta", "integer", bounds=Bounds(24, 2048)),
    CaseField("grid.n_z", Grid, "n_z", "integer", bounds=Bounds(2, 256)),
    CaseField("grid.orbit_n_theta", Grid, "orbit_n_theta", "integer", bounds=Bounds(24, 2048)),
    CaseField("grid.orbit_n_z", Grid, "orbit_n_z", "integer", bounds=Bounds(2, 256)),
    CaseField("grid.axial_order", Grid, "axial_order", "integer", bounds=_AXIAL_ORDER),
    CaseField("grid.orbit_axial_order", Grid, "orbit_axial_order", "integer", bounds=_AXIAL_ORDER),
    CaseField(
        "grid.lift_off_smoothing",
        Grid,
        "lift_off_smoothing",
        "dimensionless",
        bounds=Bounds(0.0, MAX_LIFT_OFF_SMOOTHING),
    ),
)

_BY_PATH = {f.path: f for f in CASE_FIELDS}


def case_field(path: str) -> CaseField:
    """The field at the dotted TOML ``path`` (``"bearing.clearance"``).

    Raises
    ------
    KeyError
        No field of a case file has that path.
    """
    return _BY_PATH[path]


#: Per class of the case, each field's SI unit as the case files write it: a unit string,
#: ``""`` for a plain number (dimensionless, an integer, a word), ``"table"`` for a nested
#: table (``[foil.bump]``), ``"law"`` for a law object (no case file holds it).
FIELD_UNITS: dict[type, dict[str, str]] = {}
for _f in CASE_FIELDS:
    FIELD_UNITS.setdefault(_f.owner, {})[_f.attr] = _f.unit

#: The case file's name of a field where it differs from the dataclass attribute's.
FILE_NAMES: dict[tuple[type, str], str] = {
    (f.owner, f.attr): f.path.rsplit(".", 1)[1]
    for f in CASE_FIELDS
    if f.path.rsplit(".", 1)[1] != f.attr
}

#: The fields a sweep file may set (dotted path) and the kind of value each takes.
SWEEP_KINDS: dict[str, str] = {f.path: f.kind for f in CASE_FIELDS if f.sweepable}

#: Display units other than SI: per SI unit, the factor the SI value is multiplied by
#: (divided by, for rpm: ``speed / RPM`` as everywhere else).
_TIMES = {"mm": 1e3, "um": 1e6, "g*mm": 1e6, "deg": 180.0 / math.pi, "GPa": 1e-9, "mm**2": 1e6}
_TIMES |= {"um/V": 1e6, "um/V**2": 1e6}
_DIVIDED_BY = {"rpm": RPM}


def to_display(field: CaseField, value: Any) -> Any:
    """``value`` (SI, or a tuple of SI values) in the field's display unit (a list for a tuple)."""
    if isinstance(value, tuple):
        return [to_display(field, v) for v in value]
    unit = field.display_unit
    if unit in _DIVIDED_BY:
        return value / _DIVIDED_BY[unit]
    if unit in _TIMES:
        return value * _TIMES[unit]
    return value


def summary_entry(case: Case, path: str) -> dict[str, Any]:
    """``{summary key: value in the display unit}`` of the field at ``path`` in ``case``."""
    f = _BY_PATH[path]
    if f.summary is None:
        raise KeyError(f"{path} has no summary key in foilbearing.case.schema")
    return {f.summary: to_display(f, f.value(case))}
